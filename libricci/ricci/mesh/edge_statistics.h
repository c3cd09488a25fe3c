#pragma once
// Edge-length statistics of a mesh, the scale that mesh clean-up thresholds are relative to.
#include "ricci/mesh/mesh.h"

namespace ricci {

/// Median 3D edge length (the upper median for an even count); 0 for a mesh without edges.
[[nodiscard]] double median_edge_length(const Mesh& mesh);

}  // namespace ricci
