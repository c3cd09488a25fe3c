#pragma once
// The Hessian of the Ricci energy, H = ∂K/∂u (Ricci-flow paper §V, appendix D).
//   E2: the power-centre form of shape-analysis lemma 3.6, ∂θ_i/∂u_j = h_k / l_ij with h_k the
//       signed distance of the face's power centre to edge ij; H is a weighted graph Laplacian.
//   H2, S2: the chain rule ∂θ/∂u = (∂θ/∂l from the cosine law) (∂l/∂u from the circle-packing
//       length), see triangle_angle_length_jacobian and circle_edge_length_du.
// The assembler builds the sparsity pattern once and refills the values in place.
#include <vector>

#include <Eigen/SparseCore>

#include "ricci/flow/flow_state.h"
#include "ricci/metric/circle_packing.h"
#include "ricci/metric/mesh_tables.h"

namespace ricci {

/// Fills the lower triangle of H = ∂K/∂u, in compressed column storage, over the unknowns that
/// remain after pinning at most one vertex (the E2 gauge: H·1 = 0 there).
class HessianAssembler {
 public:
  /// `pinned_vertex` = -1 keeps every vertex; otherwise its row and column are dropped and the
  /// other vertices are renumbered in order (unknown(v)).
  HessianAssembler(const MeshTables& tables, int pinned_vertex);

  /// The lower-triangular pattern (values zero): analyse a factorisation on it once.
  const Eigen::SparseMatrix<double>& matrix() const { return matrix_; }

  /// Refills the values at `state` (which must be a valid evaluation) and returns the matrix.
  const Eigen::SparseMatrix<double>& assemble(Geometry geometry, const Eigen::VectorXd& eta,
                                              const FlowState& state);

  /// Index of vertex v among the unknowns, or -1 for the pinned vertex.
  int unknown(int v) const { return unknown_[v]; }
  int num_unknowns() const { return static_cast<int>(matrix_.rows()); }

 private:
  const MeshTables& tables_;
  Eigen::SparseMatrix<double> matrix_;
  std::vector<int> unknown_;
  std::vector<int> edge_slot_;    // value index of the edge's off-diagonal entry, -1 if pinned
  std::vector<int> vertex_slot_;  // value index of the diagonal entry, -1 if pinned
  Eigen::VectorXd dl_du_[2];      // ∂l_e/∂u at each endpoint of edge e
};

/// Index of vertex v among the unknowns of a system without vertex `pinned` (pinned < 0: all
/// vertices; v == pinned has none).
[[nodiscard]] inline int reduced_index(int v, int pinned) {
  return pinned >= 0 && v > pinned ? v - 1 : v;
}

/// Lower triangle of the weighted graph Laplacian of `n` vertices, sum over edges e of
/// weights[e] (x_i - x_j)^2 with e joining ends(e, 0) and ends(e, 1) (loops add nothing,
/// parallel edges add up), without row and column `pinned` (pinned < 0: with `gauge` added at
/// (0, 0) instead). One entry per edge and vertex: a 1.6M-face Laplacian assembled by face
/// corners takes 0.5 GB of triplets, this one a fifth of that.
/// \throw InvalidInputError when sizes differ or an end or `pinned` is not a vertex.
[[nodiscard]] Eigen::SparseMatrix<double> reduced_graph_laplacian(const Eigen::MatrixX2i& ends,
                                                                  const Eigen::VectorXd& weights,
                                                                  int n, int pinned,
                                                                  double gauge = 0.0);

/// ∂θ_a/∂u_m for the corners a and vertices m of face f: out[a][m].
void face_angle_derivatives(const MeshTables& tables, Geometry geometry, const FlowState& state,
                            const Eigen::VectorXd& dl_du0, const Eigen::VectorXd& dl_du1, int f,
                            double out[3][3]);

/// Full symmetric ∂K/∂u (both triangles, no pinning) at the metric's radii: for tests and
/// analysis. \throw InvalidInputError if the metric's lengths are not valid triangles.
[[nodiscard]] Eigen::SparseMatrix<double> curvature_jacobian(const MeshTables& tables,
                                                             const CirclePackingMetric& metric);

}  // namespace ricci
