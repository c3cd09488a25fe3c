#pragma once
// Midpoint (1-to-4) subdivision: the benchmark's way to make large meshes from real ones.
#include "ricci/mesh/mesh.h"

namespace ricci {

/// Splits every triangle into four by its edge midpoints. Vertex i of the input keeps index i;
/// the midpoint of edge e gets index #V + e. Topology (genus, boundaries) is unchanged.
/// \throw InvalidInputError if a face is not a triangle.
[[nodiscard]] Mesh subdivide_midpoint(const Mesh& mesh);

}  // namespace ricci
