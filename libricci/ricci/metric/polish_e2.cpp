#include "ricci/metric/polish_e2.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/SparseCore>

#include "ricci/flow/hessian.h"
#include "ricci/flow/linear_solver.h"
#include "ricci/mesh/errors.h"
#include "ricci/metric/mesh_tables.h"
#include "ricci/util/parallel.h"

namespace ricci {
namespace {

constexpr long double kPi = 3.141592653589793238462643383279502884L;
using VectorL = Eigen::Matrix<long double, Eigen::Dynamic, 1>;

// Angles of a Euclidean triangle with sides l (l[k] opposite corner k) by the half-angle
// formula tan^2(theta_k / 2) = (s - l_{k+1})(s - l_{k+2}) / (s (s - l_k)). False if degenerate.
bool angles_l(const long double l[3], long double theta[3]) {
  const long double s = 0.5L * (l[0] + l[1] + l[2]);
  const long double d[3] = {s - l[0], s - l[1], s - l[2]};
  if (!(d[0] > 0 && d[1] > 0 && d[2] > 0)) return false;
  for (int k = 0; k < 3; ++k) {
    theta[k] = 2.0L * std::atan2(std::sqrt(d[(k + 1) % 3] * d[(k + 2) % 3]), std::sqrt(s * d[k]));
  }
  return true;
}

// Faces whose corner angles are computed together: their long-double angles and cotangents (72
// bytes a face) are held for one chunk only, not for the mesh (115 MB at 1.6M faces, beside the
// flow's factorisation). A chunk is one parallel_for: 49 at 1.6M faces.
constexpr size_t kAngleChunk = 1 << 15;

// Residual K - target in long double (and, when `edge_weights`, the cotangent Laplacian's
// weight of each edge: the sum of 0.5 cot of the corners facing it). The corner angles (long
// double atan2, most of a polish step) and their cotangents are computed face-parallel a chunk
// at a time, then summed per vertex and edge in face order: the same sums on any number of
// threads.
VectorL residual_of(const MeshTables& t, const VectorL& lengths, const Eigen::VectorXd& target,
                    Eigen::VectorXd* edge_weights) {
  VectorL r(t.num_vertices());
  for (int v = 0; v < t.num_vertices(); ++v) {
    r[v] = (t.is_boundary_vertex[v] ? kPi : 2.0L * kPi) - static_cast<long double>(target[v]);
  }
  if (edge_weights) *edge_weights = Eigen::VectorXd::Zero(t.num_edges());
  const auto faces = static_cast<size_t>(t.num_faces());
  std::vector<std::array<long double, 3>> theta(std::min(faces, kAngleChunk));
  std::vector<std::array<double, 3>> half_cot(edge_weights ? theta.size() : 0);
  std::vector<char> broken(theta.size());
  for (size_t first = 0; first < faces; first += kAngleChunk) {
    const size_t count = std::min(kAngleChunk, faces - first);
    parallel_for(count, 0, [&](size_t i) {
      const int face = static_cast<int>(first + i);
      const long double l[3] = {lengths[t.face_edges(face, 0)], lengths[t.face_edges(face, 1)],
                                lengths[t.face_edges(face, 2)]};
      broken[i] = angles_l(l, theta[i].data()) ? 0 : 1;
      if (!edge_weights || broken[i]) return;
      for (size_t k = 0; k < 3; ++k) {
        half_cot[i][k] = 0.5 / std::tan(static_cast<double>(theta[i][k]));
      }
    });
    const auto end = broken.begin() + static_cast<std::ptrdiff_t>(count);
    const auto first_broken = std::find(broken.begin(), end, 1);
    if (first_broken != end) {
      const auto face = first + static_cast<size_t>(first_broken - broken.begin());
      throw InvalidInputError("polish_e2_lengths: face " + std::to_string(face) +
                              " violates the triangle inequality");
    }
    for (size_t i = 0; i < count; ++i) {
      const int f = static_cast<int>(first + i);
      const std::array<long double, 3>& angles = theta[i];
      for (int k = 0; k < 3; ++k) r[t.face_vertices(f, k)] -= angles[static_cast<size_t>(k)];
      if (!edge_weights) continue;
      for (int k = 0; k < 3; ++k) {
        (*edge_weights)[t.face_edges(f, k)] += half_cot[i][static_cast<size_t>(k)];
      }
    }
  }
  return r;
}

}  // namespace

PolishE2Result polish_e2_lengths(const Mesh& mesh, const Eigen::VectorXd& lengths,
                                 const Eigen::VectorXd& target, int max_iterations,
                                 NearbyLaplacian nearby, double good_enough) {
  return polish_e2_lengths(build_mesh_tables(mesh), lengths, target, max_iterations, nearby,
                           good_enough);
}

PolishE2Result polish_e2_lengths(const MeshTables& t, const Eigen::VectorXd& lengths,
                                 const Eigen::VectorXd& target, int max_iterations,
                                 NearbyLaplacian nearby, double good_enough) {
  const int n = t.num_vertices();
  if (lengths.size() != t.num_edges() || target.size() != n || n < 2) {
    throw InvalidInputError("polish_e2_lengths: lengths or target do not match the mesh");
  }
  if (nearby.factorization && (nearby.pinned < 0 || nearby.pinned >= n)) {
    throw InvalidInputError("polish_e2_lengths: the pinned vertex is not the mesh's");
  }
  // A uniform du only rescales (E2): du is held at 0 on the nearby factorisation's pinned
  // vertex, or by a gauge of 1 at (0, 0) in a factorisation of its own.
  const int pinned = nearby.factorization ? nearby.pinned : -1;
  VectorL current = lengths.cast<long double>(), u = VectorL::Zero(n);
  Eigen::VectorXd edge_weights;
  VectorL r = residual_of(t, current, target, &edge_weights);
  const Eigen::SparseMatrix<double> lower =
      reduced_graph_laplacian(t.edge_vertices, edge_weights, n, pinned, 1.0);
  edge_weights = Eigen::VectorXd();  // (memory: the polish runs beside the flow's factorisation)
  // Without a nearby factorisation, or where it does not converge, the matrix's own (the
  // flow's kind: CHOLMOD supernodal on large meshes, Eigen below 20k unknowns).
  std::unique_ptr<SymmetricFactorization> own;
  bool own_failed = false;
  PolishE2Result result;
  const auto solve = [&](const Eigen::VectorXd& rhs, Eigen::VectorXd& x) {
    // A step solved to 1e-6 leaves a defect 1e-6 of the flow's (~1e-10): below the floor.
    if (nearby.factorization) {
      const LinearWorkMeter meter(*nearby.factorization, result.linear_work);
      if (solve_by_preconditioned_cg(*nearby.factorization, lower, rhs, x, 1e-6, 12)) return true;
    }
    if (!own && !own_failed) {
      own = std::make_unique<SymmetricFactorization>(
          resolve_linear_solver(LinearSolver::automatic, lower.rows()));
      own->analyze(lower);
      own_failed = !own->factorize(lower);
      result.linear_work += own->work();  // its factorisation
    }
    if (own_failed) return false;
    const LinearWorkMeter meter(*own, result.linear_work);
    x = own->solve(rhs);
    return true;
  };
  result.lengths = lengths;
  result.error_before = result.error_after = static_cast<double>(r.cwiseAbs().maxCoeff());
  for (int it = 1; it <= max_iterations && result.error_after > std::max(good_enough, 0.0); ++it) {
    const long double scale = r.cwiseAbs().maxCoeff();  // keeps the residual's digits in double
    Eigen::VectorXd rhs(lower.rows()), du;
    for (int v = 0; v < n; ++v) {
      if (v != pinned) rhs[reduced_index(v, pinned)] = static_cast<double>(r[v] / scale);
    }
    if (!solve(rhs, du)) break;
    for (int v = 0; v < n; ++v) {
      if (v != pinned) u[v] -= static_cast<long double>(du[reduced_index(v, pinned)]) * scale;
    }
    parallel_for(static_cast<size_t>(t.num_edges()), 0, [&](size_t i) {
      const int e = static_cast<int>(i);
      current[e] = std::exp(0.5L * (u[t.edge_vertices(e, 0)] + u[t.edge_vertices(e, 1)])) *
                   static_cast<long double>(lengths[e]);
    });
    r = residual_of(t, current, target, nullptr);
    const double error = static_cast<double>(r.cwiseAbs().maxCoeff());
    if (!(error < result.error_after)) break;
    // A step that did not halve the defect met the long-double evaluation's floor: it is kept,
    // and the next one would only measure that floor.
    const bool at_floor = error > 0.5 * result.error_after;
    result.error_after = error;
    result.iterations = it;
    result.lengths = current.cast<double>();
    result.lengths_low = (current - result.lengths.cast<long double>()).cast<double>();
    if (at_floor) break;
  }
  return result;
}

}  // namespace ricci
