#pragma once
// From an intrinsic Delaunay triangulation back to a surface mesh: the edges of the mesh the
// flips removed, and their midpoint splits. A mesh whose edges the flow's final triangulation
// all keeps is its own Delaunay triangulation for the flat metric, so its faces (triangles in
// 3D on the surface) carry the metric exactly; a spline domain needs such a mesh, not the
// flipped triangulation's chords between distant vertices.
#include <cstdint>
#include <vector>

#include "ricci/intrinsic/intrinsic_triangulation.h"
#include "ricci/mesh/mesh.h"

namespace ricci {

/// The triangulation's edges as undirected_edge_key's of their end vertices, sorted.
[[nodiscard]] std::vector<std::uint64_t> sorted_edge_keys(const IntrinsicTriangulation& tri);

/// Edges of `mesh` (by index) whose two vertices no edge of `tri` joins. Empty when the
/// triangulation is the mesh's own connectivity.
/// \pre tri's vertices are the mesh's (same count and indices).
/// \throw InvalidInputError when the vertex counts differ.
[[nodiscard]] std::vector<int> removed_edges(const Mesh& mesh, const IntrinsicTriangulation& tri);

/// Splits each listed edge (by index) at its 3D midpoint, joining the new vertex to the two
/// opposite corners: the surface does not move, vertex indices are kept and the new vertices
/// appended. Returns the number of splits.
/// \throw InvalidInputError for an edge index out of range.
int split_edges_at_midpoints(Mesh& mesh, const std::vector<int>& edges);

}  // namespace ricci
