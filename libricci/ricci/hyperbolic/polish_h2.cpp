#include "ricci/hyperbolic/polish_h2.h"

#include <cmath>
#include <string>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "ricci/mesh/errors.h"

namespace ricci {
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

bool hyperbolic_angles_q(const RealQ l[3], RealQ theta[3]) {
  const RealQ s = RealQ(0.5) * (l[0] + l[1] + l[2]);
  const RealQ d[3] = {s - l[0], s - l[1], s - l[2]};
  if (!(d[0] > 0 && d[1] > 0 && d[2] > 0)) return false;
  const RealQ sh[3] = {sinh_q(d[0]), sinh_q(d[1]), sinh_q(d[2])};
  const RealQ ss = sinh_q(s);
  for (int k = 0; k < 3; ++k) {
    theta[k] = 2 * atan2_q(sqrt_q(sh[(k + 1) % 3] * sh[(k + 2) % 3]), sqrt_q(ss * sh[k]));
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

/// Scaled half-length sines sigma' = sinh(l'/2) = e^{(u_i+u_j)/2} sinh(l/2).
LengthsQ scaled(const Mesh& mesh, const LengthsQ& base_sigma, const LengthsQ& u) {
  LengthsQ sigma(base_sigma.size());
  for (auto e : mesh.edges()) {
    const auto h = mesh.halfedge_handle(e, 0);
    const auto i = static_cast<size_t>(mesh.from_vertex_handle(h).idx());
    const auto j = static_cast<size_t>(mesh.to_vertex_handle(h).idx());
    const auto k = static_cast<size_t>(e.idx());
    sigma[k] = exp_q(RealQ(0.5) * (u[i] + u[j])) * base_sigma[k];
  }
  return sigma;
}

/// A triangle's corner angles (corner k opposite edge k) from its sides' sigma = sinh(l/2) by
/// the law of cosines written without cancellation of the leading 1s: with x = cosh l - 1 =
/// 2 sigma^2, cos θ_a = (x_b + x_c - x_a + x_b x_c) / (sinh l_b sinh l_c). One atan2 per corner
/// and no sinh: a quarter of the half-angle formula's cost in quad precision. False when the
/// triangle inequality fails.
struct CornerAngles {
  RealQ theta[3];
  RealQ sin_theta[3], cos_theta[3], sinh_l[3];
};

bool corner_angles(const RealQ sigma[3], CornerAngles& c) {
  RealQ x[3];
  for (int k = 0; k < 3; ++k) {
    x[k] = 2 * sigma[k] * sigma[k];
    c.sinh_l[k] = 2 * sigma[k] * sqrt_q(1 + sigma[k] * sigma[k]);
  }
  for (int a = 0; a < 3; ++a) {
    const int b = (a + 1) % 3, d = (a + 2) % 3;
    const RealQ denominator = c.sinh_l[b] * c.sinh_l[d];
    const RealQ cosine = (x[b] + x[d] - x[a] + x[b] * x[d]) / denominator;
    const RealQ sine_squared = (1 - cosine) * (1 + cosine);
    if (!(sine_squared > 0)) return false;
    c.cos_theta[a] = cosine;
    c.sin_theta[a] = sqrt_q(sine_squared);
    c.theta[a] = atan2_q(c.sin_theta[a], cosine);
  }
  return true;
}

/// Adds the face's block of H = -dΘ/du (Θ the angle sums; exact, in double) to `triplets`:
/// dθ_a/dl_a = sinh l_a / (sinh l_b sinh l_c sin θ_a) = D_a, dθ_a/dl_b = -D_a cos θ_c, and
/// dl/du_i = tanh(l/2) for both ends of the edge.
void add_jacobian(const FaceCorners& f, const RealQ sigma[3], const CornerAngles& c,
                  std::vector<Eigen::Triplet<double>>& triplets) {
  double dl_du[3];  // tanh(l_k / 2) = sigma / sqrt(1 + sigma^2)
  for (int k = 0; k < 3; ++k) {
    const double s = static_cast<double>(sigma[k]);
    dl_du[k] = s / std::sqrt(1.0 + s * s);
  }
  for (int a = 0; a < 3; ++a) {
    const int b = (a + 1) % 3, d = (a + 2) % 3;
    const double da =
        static_cast<double>(c.sinh_l[a] / (c.sinh_l[b] * c.sinh_l[d] * c.sin_theta[a]));
    // dθ_a/dl for the edges opposite a, b, d.
    double dtheta_dl[3];
    dtheta_dl[a] = da;
    dtheta_dl[b] = -da * static_cast<double>(c.cos_theta[d]);
    dtheta_dl[d] = -da * static_cast<double>(c.cos_theta[b]);
    // Edge k joins the two corners other than k.
    for (int k = 0; k < 3; ++k) {
      const double g = -dtheta_dl[k] * dl_du[k];
      triplets.emplace_back(f.v[a], f.v[(k + 1) % 3], g);
      triplets.emplace_back(f.v[a], f.v[(k + 2) % 3], g);
    }
  }
}

}  // namespace

PolishH2Result polish_h2_lengths(const Mesh& mesh, const Eigen::VectorXd& lengths,
                                 const Eigen::VectorXd& target, const PolishH2Options& options) {
  const int nv = static_cast<int>(mesh.n_vertices());
  if (lengths.size() != static_cast<Eigen::Index>(mesh.n_edges()) || target.size() != nv) {
    throw InvalidInputError("polish_h2_lengths: lengths or target do not match the mesh");
  }
  const std::vector<FaceCorners> faces = face_corners(mesh);
  LengthsQ base_sigma(static_cast<size_t>(lengths.size()));
  for (size_t e = 0; e < base_sigma.size(); ++e) {
    base_sigma[e] = sinh_q(RealQ(lengths[static_cast<Eigen::Index>(e)]) / 2);
  }
  LengthsQ u(static_cast<size_t>(nv), 0);
  LengthsQ sigma = base_sigma;
  PolishH2Result result;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver;
  bool factored = false;
  LengthsQ best = sigma;
  RealQ best_error = 0;
  const RealQ two_pi = 2 * pi_q();
  for (int it = 0;; ++it) {
    // Curvature residual in quad precision, and (first time) the Jacobian.
    std::vector<RealQ> residual(static_cast<size_t>(nv));
    for (int i = 0; i < nv; ++i) residual[static_cast<size_t>(i)] = two_pi - RealQ(target[i]);
    std::vector<Eigen::Triplet<double>> triplets;
    for (size_t f = 0; f < faces.size(); ++f) {
      const FaceCorners& c = faces[f];
      const RealQ s[3] = {sigma[static_cast<size_t>(c.e[0])], sigma[static_cast<size_t>(c.e[1])],
                          sigma[static_cast<size_t>(c.e[2])]};
      CornerAngles angles;
      if (!corner_angles(s, angles)) {
        throw InvalidInputError("polish_h2_lengths: face " + std::to_string(f) +
                                " violates the hyperbolic triangle inequality");
      }
      for (int k = 0; k < 3; ++k) residual[static_cast<size_t>(c.v[k])] -= angles.theta[k];
      if (!factored) add_jacobian(c, s, angles, triplets);
    }
    RealQ error = 0;
    for (const RealQ& r : residual) error = std::max(error, r < 0 ? -r : r);
    if (it == 0) {
      result.error_before = static_cast<double>(error);
      best_error = error;
    }
    if (error > best_error) break;  // no longer improving
    best_error = error;
    best = sigma;
    result.error_after = static_cast<double>(error);
    result.iterations = it;
    if (error < RealQ(options.tolerance) || it >= options.max_iterations || error == 0) break;
    if (!factored) {
      Eigen::SparseMatrix<double> hessian(nv, nv);
      hessian.setFromTriplets(triplets.begin(), triplets.end());
      solver.compute(hessian);
      if (solver.info() != Eigen::Success) break;  // keep the flow's lengths
      factored = true;
    }
    // Scale the residual so that double carries its digits through the solve.
    Eigen::VectorXd rhs(nv);
    for (int i = 0; i < nv; ++i) {
      rhs[i] = static_cast<double>(residual[static_cast<size_t>(i)] / error);
    }
    const Eigen::VectorXd du = solver.solve(rhs);
    for (int i = 0; i < nv; ++i) u[static_cast<size_t>(i)] -= RealQ(du[i]) * error;
    sigma = scaled(mesh, base_sigma, u);
  }
  for (RealQ& s : best) s = 2 * asinh_q(s);
  result.quad_lengths = best;
  result.lengths.resize(static_cast<Eigen::Index>(best.size()));
  for (size_t e = 0; e < best.size(); ++e) {
    result.lengths[static_cast<Eigen::Index>(e)] = static_cast<long double>(best[e]);
  }
  return result;
}

}  // namespace ricci
