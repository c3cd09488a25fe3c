#include "ricci/flow/hessian.h"

#include <algorithm>
#include <vector>

#include "ricci/mesh/errors.h"

namespace ricci {

namespace {

// ∂l_e/∂u at both endpoints of every edge.
void edge_length_derivatives(const MeshTables& t, Geometry g, const Eigen::VectorXd& eta,
                             const FlowState& s, Eigen::VectorXd& d0, Eigen::VectorXd& d1) {
  d0.resize(t.num_edges());
  d1.resize(t.num_edges());
  for (int e = 0; e < t.num_edges(); ++e) {
    const double a = s.gamma[t.edge_vertices(e, 0)], b = s.gamma[t.edge_vertices(e, 1)];
    d0[e] = circle_edge_length_du(g, a, b, eta[e], s.lengths[e]);
    d1[e] = circle_edge_length_du(g, b, a, eta[e], s.lengths[e]);
  }
}

// ∂l/∂u of the edge opposite corner k of face f, at vertex v (an endpoint of that edge).
double dl_du_at(const MeshTables& t, const Eigen::VectorXd& d0, const Eigen::VectorXd& d1, int f,
                int k, int v) {
  const int e = t.face_edges(f, k);
  return t.edge_vertices(e, 0) == v ? d0[e] : d1[e];
}

}  // namespace

Eigen::SparseMatrix<double> reduced_graph_laplacian(const Eigen::MatrixX2i& ends,
                                                    const Eigen::VectorXd& weights, int n,
                                                    int pinned, double gauge) {
  if (ends.rows() != weights.size() || n < 1 || pinned >= n ||
      (ends.size() > 0 && (ends.minCoeff() < 0 || ends.maxCoeff() >= n))) {
    throw InvalidInputError("reduced_graph_laplacian: edges, weights or pinned vertex out of range");
  }
  Eigen::VectorXd diagonal = Eigen::VectorXd::Zero(n);
  if (pinned < 0) diagonal[0] = gauge;
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<size_t>(ends.rows() + n));
  for (Eigen::Index e = 0; e < ends.rows(); ++e) {
    const int i = ends(e, 0), j = ends(e, 1);
    if (i == j) continue;
    const double w = weights[e];
    diagonal[i] += w;
    diagonal[j] += w;
    if (i == pinned || j == pinned) continue;
    const int a = reduced_index(i, pinned), b = reduced_index(j, pinned);
    entries.emplace_back(std::max(a, b), std::min(a, b), -w);
  }
  for (int v = 0; v < n; ++v) {
    if (v != pinned) entries.emplace_back(reduced_index(v, pinned), reduced_index(v, pinned), diagonal[v]);
  }
  const int size = pinned < 0 ? n : n - 1;
  Eigen::SparseMatrix<double> lower(size, size);
  lower.setFromTriplets(entries.begin(), entries.end());
  return lower;
}

void face_angle_derivatives(const MeshTables& t, Geometry g, const FlowState& s,
                            const Eigen::VectorXd& d0, const Eigen::VectorXd& d1, int f,
                            double out[3][3]) {
  const int v[3] = {t.face_vertices(f, 0), t.face_vertices(f, 1), t.face_vertices(f, 2)};
  const double c[3] = {s.cosines(f, 0), s.cosines(f, 1), s.cosines(f, 2)};
  const double sn[3] = {s.sines(f, 0), s.sines(f, 1), s.sines(f, 2)};
  const double l[3] = {s.lengths[t.face_edges(f, 0)], s.lengths[t.face_edges(f, 1)],
                       s.lengths[t.face_edges(f, 2)]};
  if (g == Geometry::euclidean) {
    // Power centre: for edge k (between i and j) h_k = (d_ik - d_ij cos θ_i)/sin θ_i, where
    // d_ij = ∂l_ij/∂u_i is the distance from v_i to the foot of the power centre on edge ij.
    double w[3];
    for (int k = 0; k < 3; ++k) {
      const int i = (k + 1) % 3, j = (k + 2) % 3;
      const double d_ij = dl_du_at(t, d0, d1, f, k, v[i]);  // edge ij is opposite k
      const double d_ik = dl_du_at(t, d0, d1, f, j, v[i]);  // edge ik is opposite j
      w[k] = (d_ik - d_ij * c[i]) / (sn[i] * l[k]);
    }
    for (int k = 0; k < 3; ++k) {
      const int i = (k + 1) % 3, j = (k + 2) % 3;
      out[i][j] = out[j][i] = w[k];
    }
    for (int k = 0; k < 3; ++k) out[k][k] = -(w[(k + 1) % 3] + w[(k + 2) % 3]);
    return;
  }
  double J[3][3];
  triangle_angle_length_jacobian(g, l, c, sn, J);
  // D[e][m] = ∂l_e/∂u_m: edge e (opposite corner e) depends on its two endpoints m ≠ e.
  double D[3][3];
  for (int e = 0; e < 3; ++e) {
    for (int m = 0; m < 3; ++m) D[e][m] = m == e ? 0.0 : dl_du_at(t, d0, d1, f, e, v[m]);
  }
  for (int a = 0; a < 3; ++a) {
    for (int m = 0; m < 3; ++m) {
      out[a][m] = J[a][0] * D[0][m] + J[a][1] * D[1][m] + J[a][2] * D[2][m];
    }
  }
  // Symmetric in exact arithmetic (shape-analysis lemma 3.7); symmetrise the rounding.
  for (int a = 0; a < 3; ++a) {
    for (int m = a + 1; m < 3; ++m) out[a][m] = out[m][a] = 0.5 * (out[a][m] + out[m][a]);
  }
}

HessianAssembler::HessianAssembler(const MeshTables& t, int pinned_vertex) : tables_(t) {
  const int nv = t.num_vertices();
  unknown_.assign(nv, -1);
  int n = 0;
  for (int v = 0; v < nv; ++v) {
    if (v != pinned_vertex) unknown_[v] = n++;
  }
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(n + t.num_edges());
  for (int v = 0; v < nv; ++v) {
    if (unknown_[v] >= 0) triplets.emplace_back(unknown_[v], unknown_[v], 0.0);
  }
  for (int e = 0; e < t.num_edges(); ++e) {
    const int a = unknown_[t.edge_vertices(e, 0)], b = unknown_[t.edge_vertices(e, 1)];
    if (a >= 0 && b >= 0) triplets.emplace_back(std::max(a, b), std::min(a, b), 0.0);
  }
  matrix_.resize(n, n);
  matrix_.setFromTriplets(triplets.begin(), triplets.end());
  matrix_.makeCompressed();
  auto slot = [&](int row, int col) {
    const int* begin = matrix_.innerIndexPtr() + matrix_.outerIndexPtr()[col];
    const int* end = matrix_.innerIndexPtr() + matrix_.outerIndexPtr()[col + 1];
    return static_cast<int>(std::lower_bound(begin, end, row) - matrix_.innerIndexPtr());
  };
  vertex_slot_.assign(nv, -1);
  for (int v = 0; v < nv; ++v) {
    if (unknown_[v] >= 0) vertex_slot_[v] = slot(unknown_[v], unknown_[v]);
  }
  edge_slot_.assign(t.num_edges(), -1);
  for (int e = 0; e < t.num_edges(); ++e) {
    const int a = unknown_[t.edge_vertices(e, 0)], b = unknown_[t.edge_vertices(e, 1)];
    if (a >= 0 && b >= 0) edge_slot_[e] = slot(std::max(a, b), std::min(a, b));
  }
}

const Eigen::SparseMatrix<double>& HessianAssembler::assemble(Geometry g,
                                                              const Eigen::VectorXd& eta,
                                                              const FlowState& s) {
  const MeshTables& t = tables_;
  edge_length_derivatives(t, g, eta, s, dl_du_[0], dl_du_[1]);
  double* values = matrix_.valuePtr();
  std::fill(values, values + matrix_.nonZeros(), 0.0);
  for (int f = 0; f < t.num_faces(); ++f) {
    double dtheta[3][3];
    face_angle_derivatives(t, g, s, dl_du_[0], dl_du_[1], f, dtheta);
    // H = ∂K/∂u = -Σ_faces ∂θ/∂u.
    for (int k = 0; k < 3; ++k) {
      const int slot = vertex_slot_[t.face_vertices(f, k)];
      if (slot >= 0) values[slot] -= dtheta[k][k];
      const int i = (k + 1) % 3, j = (k + 2) % 3;
      const int edge_slot = edge_slot_[t.face_edges(f, k)];  // edge between corners i and j
      if (edge_slot >= 0) values[edge_slot] -= dtheta[i][j];
    }
  }
  return matrix_;
}

Eigen::SparseMatrix<double> curvature_jacobian(const MeshTables& t,
                                               const CirclePackingMetric& metric) {
  FlowState s;
  const Eigen::VectorXd u = u_from_radii(metric.geometry, metric.gamma);
  if (!evaluate_flow_state(t, metric.geometry, metric.eta, u, s)) {
    throw InvalidInputError("curvature_jacobian: the metric has no valid triangles");
  }
  HessianAssembler assembler(t, -1);
  const Eigen::SparseMatrix<double> lower = assembler.assemble(metric.geometry, metric.eta, s);
  Eigen::SparseMatrix<double> full = lower.selfadjointView<Eigen::Lower>();
  return full;
}

}  // namespace ricci
