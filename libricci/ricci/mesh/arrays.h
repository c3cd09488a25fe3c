#pragma once
// Adapters between ricci::Mesh and the libigl-style (V, F) arrays.
#include "ricci/mesh/mesh.h"

namespace ricci {

/// #V by 3 positions, in the mesh's own vertex order.
[[nodiscard]] Eigen::MatrixX3d vertex_positions(const Mesh& mesh);

/// #V by 3 positions and #F by 3 vertex indices, both in the mesh's own index order.
[[nodiscard]] VertexFaceArrays to_arrays(const Mesh& mesh);

/// The inverse of to_arrays: vertex i is V's row i and face f is F's row f (edges in the order
/// the faces meet them), without from_arrays' re-orientation and clean-up.
/// \pre the arrays are an oriented manifold mesh's (to_arrays of one).
/// \throw TopologyError when a face would make the mesh non-manifold.
[[nodiscard]] Mesh same_order_mesh(const VertexFaceArrays& arrays);

/// A mesh from (V, F) arrays, validated like a file (build_mesh()): faces may be re-oriented
/// consistently and unreferenced vertices are dropped (vertex indices then shift).
/// \throw InvalidInputError (index out of range, NaN, degenerate) or TopologyError.
[[nodiscard]] Mesh from_arrays(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F);

}  // namespace ricci
