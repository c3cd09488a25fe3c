#pragma once
// Boundary loops of a mesh: the one walk along face-less halfedges that every caller shares.
#include <vector>

#include "ricci/mesh/mesh.h"

namespace ricci {

/// Boundary loops of the mesh as cycles of face-less halfedges: loop k starts at the
/// lowest-numbered boundary halfedge not in loops 0..k-1 and follows next_halfedge_handle, so
/// loops[k][i] ends where loops[k][i + 1] starts.
/// \pre mesh is a manifold OpenMesh surface (every boundary vertex on one boundary loop).
[[nodiscard]] std::vector<std::vector<HalfedgeHandle>> find_boundary_loops(const Mesh& mesh);

}  // namespace ricci
