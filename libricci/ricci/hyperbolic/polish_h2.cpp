#include "ricci/hyperbolic/polish_h2.h"

#include <cmath>
#include <string>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "ricci/mesh/errors.h"

namespace ricci {
namespace {
constexpr long double kPi = 3.141592653589793238462643383279502884L;
}  // namespace

bool hyperbolic_angles_l(const long double l[3], long double theta[3]) {
  const long double s = 0.5L * (l[0] + l[1] + l[2]);
  const long double d[3] = {s - l[0], s - l[1], s - l[2]};
  if (!(d[0] > 0 && d[1] > 0 && d[2] > 0)) return false;
  const long double sh[3] = {std::sinh(d[0]), std::sinh(d[1]), std::sinh(d[2])};
  const long double ss = std::sinh(s);
  for (int k = 0; k < 3; ++k) {
    // tan²(θk/2) = sinh(s - l_{k+1}) sinh(s - l_{k+2}) / (sinh s sinh(s - l_k)).
    theta[k] =
        2.0L * std::atan2(std::sqrt(sh[(k + 1) % 3] * sh[(k + 2) % 3]), std::sqrt(ss * sh[k]));
  }
  return true;
}

namespace {

struct FaceCorners {
  int v[3];  // corner vertices
  int e[3];  // e[k] = edge opposite corner k
};

std::vector<FaceCorners> face_corners(const Mesh& mesh) {
  std::vector<FaceCorners> faces;
  faces.reserve(mesh.n_faces());
  for (auto f : mesh.faces()) {
    FaceCorners c;
    HalfedgeHandle h = mesh.halfedge_handle(f);
    for (int k = 0; k < 3; ++k) {
      // Corner k at from(h); the opposite edge is next(h)'s.
      c.v[k] = mesh.from_vertex_handle(h).idx();
      c.e[k] = mesh.edge_handle(mesh.next_halfedge_handle(h)).idx();
      h = mesh.next_halfedge_handle(h);
    }
    faces.push_back(c);
  }
  return faces;
}

/// Scaled lengths sinh(l'/2) = e^{(u_i+u_j)/2} sinh(l/2).
LengthsL scaled(const Mesh& mesh, const LengthsL& base_sinh, const LengthsL& u) {
  LengthsL l(base_sinh.size());
  for (auto e : mesh.edges()) {
    const auto h = mesh.halfedge_handle(e, 0);
    const long double s =
        std::exp(0.5L * (u[mesh.from_vertex_handle(h).idx()] + u[mesh.to_vertex_handle(h).idx()])) *
        base_sinh[e.idx()];
    l[e.idx()] = 2.0L * std::asinh(s);
  }
  return l;
}

}  // namespace

PolishH2Result polish_h2_lengths(const Mesh& mesh, const Eigen::VectorXd& lengths,
                                 const Eigen::VectorXd& target, const PolishH2Options& options) {
  const int nv = static_cast<int>(mesh.n_vertices());
  if (lengths.size() != static_cast<Eigen::Index>(mesh.n_edges()) || target.size() != nv) {
    throw InvalidInputError("polish_h2_lengths: lengths or target do not match the mesh");
  }
  const std::vector<FaceCorners> faces = face_corners(mesh);
  LengthsL base_sinh(lengths.size());
  for (Eigen::Index e = 0; e < lengths.size(); ++e) {
    base_sinh[e] = std::sinh(0.5L * static_cast<long double>(lengths[e]));
  }
  LengthsL u = LengthsL::Zero(nv);
  PolishH2Result result;
  result.lengths = lengths.cast<long double>();
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver;
  bool factored = false;
  LengthsL best = result.lengths;
  for (int it = 0;; ++it) {
    // Curvature residual in long double, and (first time) the approximate Hessian.
    LengthsL residual(nv);
    for (int i = 0; i < nv; ++i) residual[i] = 2.0L * kPi - static_cast<long double>(target[i]);
    std::vector<Eigen::Triplet<double>> triplets;
    for (size_t f = 0; f < faces.size(); ++f) {
      const FaceCorners& c = faces[f];
      const long double l[3] = {result.lengths[c.e[0]], result.lengths[c.e[1]],
                                result.lengths[c.e[2]]};
      long double theta[3];
      if (!hyperbolic_angles_l(l, theta)) {
        throw InvalidInputError("polish_h2_lengths: face " + std::to_string(f) +
                                " violates the hyperbolic triangle inequality");
      }
      for (int k = 0; k < 3; ++k) residual[c.v[k]] -= theta[k];
      if (factored) continue;
      const double area = static_cast<double>(kPi - theta[0] - theta[1] - theta[2]);
      for (int k = 0; k < 3; ++k) {
        const int i = c.v[(k + 1) % 3], j = c.v[(k + 2) % 3];
        const double w = 0.5 / std::tan(static_cast<double>(theta[k]));
        triplets.emplace_back(i, i, w);
        triplets.emplace_back(j, j, w);
        triplets.emplace_back(i, j, -w);
        triplets.emplace_back(j, i, -w);
        triplets.emplace_back(c.v[k], c.v[k], 2.0 * area / 3.0);
      }
    }
    const long double error = residual.cwiseAbs().maxCoeff();
    if (it == 0) result.error_before = result.error_after = static_cast<double>(error);
    if (error > static_cast<long double>(result.error_after)) break;  // no longer improving
    best = result.lengths;
    result.error_after = static_cast<double>(error);
    result.iterations = it;
    if (error < options.tolerance || it >= options.max_iterations) break;
    if (!factored) {
      Eigen::SparseMatrix<double> hessian(nv, nv);
      hessian.setFromTriplets(triplets.begin(), triplets.end());
      solver.compute(hessian);
      if (solver.info() != Eigen::Success) break;  // keep the flow's lengths
      factored = true;
    }
    // Scale the residual so that double carries its digits through the solve.
    const long double scale = error;
    const Eigen::VectorXd rhs = (residual / scale).cast<double>();
    const Eigen::VectorXd du = solver.solve(rhs);
    u -= du.cast<long double>() * scale;
    result.lengths = scaled(mesh, base_sinh, u);
  }
  result.lengths = best;
  return result;
}

}  // namespace ricci
