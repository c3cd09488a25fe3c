#include "ricci/singularity/open_target.h"

#include <cmath>
#include <vector>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "ricci/mesh/errors.h"
#include "ricci/metric/curvature.h"
#include "ricci/metric/mesh_tables.h"

namespace ricci {
namespace {

// Symmetric cotangent Laplacian (positive semidefinite): L_ij = -(cot a + cot b) / 2.
Eigen::SparseMatrix<double> cotangent_laplacian(const MeshTables& t, const Eigen::MatrixX3d& angles) {
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<std::size_t>(t.num_faces()) * 12);
  for (int f = 0; f < t.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int i = t.face_vertices(f, (k + 1) % 3), j = t.face_vertices(f, (k + 2) % 3);
      const double w = 0.5 / std::tan(angles(f, k));
      entries.emplace_back(i, j, -w);
      entries.emplace_back(j, i, -w);
      entries.emplace_back(i, i, w);
      entries.emplace_back(j, j, w);
    }
  }
  Eigen::SparseMatrix<double> L(t.num_vertices(), t.num_vertices());
  L.setFromTriplets(entries.begin(), entries.end());
  return L;
}

}  // namespace

Targets harmonic_boundary_target(const Mesh& mesh) {
  const MeshTables t = build_mesh_tables(mesh);
  if (t.boundary_loops.empty()) throw InvalidInputError("harmonic boundary target on a closed mesh");
  const Eigen::MatrixX3d angles = corner_angles(t, mesh_edge_lengths(mesh), Geometry::euclidean);
  const Eigen::VectorXd K = vertex_curvature(t, angles);
  const int n = t.num_vertices();
  std::vector<int> interior_index(n, -1);
  int interior = 0;
  for (int v = 0; v < n; ++v) {
    if (!t.is_boundary_vertex[v]) interior_index[v] = interior++;
  }
  Targets targets{Eigen::VectorXd::Zero(n)};
  for (int v = 0; v < n; ++v) {
    if (t.is_boundary_vertex[v]) targets.curvature[v] = K[v];
  }
  if (interior == 0) return targets;

  const Eigen::SparseMatrix<double> L = cotangent_laplacian(t, angles);
  std::vector<Eigen::Triplet<double>> inner;
  Eigen::VectorXd rhs(interior);
  for (int c = 0; c < L.outerSize(); ++c) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(L, c); it; ++it) {
      const int r = static_cast<int>(it.row()), col = static_cast<int>(it.col());
      if (interior_index[r] >= 0 && interior_index[col] >= 0) {
        inner.emplace_back(interior_index[r], interior_index[col], it.value());
      }
    }
  }
  for (int v = 0; v < n; ++v) {
    if (interior_index[v] >= 0) rhs[interior_index[v]] = -K[v];
  }
  Eigen::SparseMatrix<double> L_ii(interior, interior);
  L_ii.setFromTriplets(inner.begin(), inner.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(L_ii);
  if (solver.info() != Eigen::Success) {
    throw SolverError("harmonic boundary target: the interior cotangent Laplacian did not factorise");
  }
  const Eigen::VectorXd du_inner = solver.solve(rhs);
  Eigen::VectorXd du = Eigen::VectorXd::Zero(n);
  for (int v = 0; v < n; ++v) {
    if (interior_index[v] >= 0) du[v] = du_inner[interior_index[v]];
  }
  const Eigen::VectorXd change = L * du;
  for (int v = 0; v < n; ++v) {
    if (t.is_boundary_vertex[v]) targets.curvature[v] += change[v];
  }
  return targets;
}

}  // namespace ricci
