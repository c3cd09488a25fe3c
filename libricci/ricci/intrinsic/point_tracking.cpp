#include "ricci/intrinsic/point_tracking.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "ricci/mesh/errors.h"

namespace ricci {
namespace {

using Flip = IntrinsicCorrespondence::Flip;

void check_face(const IntrinsicTriangulation& tri, int face) {
  if (face < 0 || face >= tri.face_count()) {
    throw InvalidInputError("intrinsic point: face " + std::to_string(face) + " of " +
                            std::to_string(tri.face_count()));
  }
}

void check_scale_factors(const IntrinsicTriangulation& tri, const Eigen::VectorXd& u) {
  if (u.size() != tri.vertex_count) {
    throw InvalidInputError("intrinsic point: " + std::to_string(u.size()) + " scale factors for " +
                            std::to_string(tri.vertex_count) + " vertices");
  }
}

// Weights clamped at 0 (rounding below it) and scaled to sum 1.
Eigen::Vector3d normalised(const Eigen::Vector3d& w) {
  const Eigen::Vector3d clamped = w.cwiseMax(0.0);
  const double sum = clamped.sum();
  if (!(sum > 0) || !std::isfinite(sum)) {
    throw InvalidInputError("intrinsic point: weights must be >= 0 and not all 0");
  }
  return clamped / sum;
}

int corner_vertex(const IntrinsicTriangulation& tri, int face, int k) {
  return tri.tail[static_cast<size_t>(3 * face + k)];
}

// Carries the points of the flip's two faces (listed in in_face) to where the flip (forward) or
// its inverse (backward) puts them. Quad coefficients (i, j, k, l) may change by multiples of
// (alpha, beta, gamma, -1), the relation between the four light-like vectors; each point takes
// the face where all its coefficients are >= 0 (the zero one is the corner the face lacks).
void carry(const Flip& flip, bool forward, std::vector<TriangulationPoint>& points,
           std::vector<std::vector<int>>& in_face) {
  const int fa = flip.h / 3, fb = flip.t / 3, r = flip.h % 3, s = flip.t % 3;
  std::vector<int> moving;
  std::swap(moving, in_face[static_cast<size_t>(fa)]);
  const std::vector<int>& from_b = in_face[static_cast<size_t>(fb)];
  moving.insert(moving.end(), from_b.begin(), from_b.end());
  in_face[static_cast<size_t>(fb)].clear();
  const double alpha = flip.alpha, beta = flip.beta, gamma = flip.gamma;
  for (int id : moving) {
    TriangulationPoint& p = points[static_cast<size_t>(id)];
    const Eigen::Vector3d& w = p.weights;
    double ci = 0, cj = 0, ck = 0, cl = 0;
    const bool in_a = p.face == fa;
    // Slots of A from h: before the flip (i, j, k), after it (l, k, i); of B from t: before
    // (j, i, l), after (k, l, j).
    if (forward && in_a) {
      ci = w[r], cj = w[(r + 1) % 3], ck = w[(r + 2) % 3];
    } else if (forward) {
      cj = w[s], ci = w[(s + 1) % 3], cl = w[(s + 2) % 3];
    } else if (in_a) {
      cl = w[r], ck = w[(r + 1) % 3], ci = w[(r + 2) % 3];
    } else {
      ck = w[s], cl = w[(s + 1) % 3], cj = w[(s + 2) % 3];
    }
    Eigen::Vector3d out;
    bool to_a = true;
    if (forward && ci * beta >= cj * alpha) {  // A = (l, k, i): cancel j
      out = {cl + cj / beta, ck - cj * gamma / beta, ci - cj * alpha / beta};
    } else if (forward) {  // B = (k, l, j): cancel i
      out = {ck - ci * gamma / alpha, cl + ci / alpha, cj - ci * beta / alpha};
      to_a = false;
    } else if (ck >= -cl * gamma) {  // A = (i, j, k): cancel l
      out = {ci + cl * alpha, cj + cl * beta, ck + cl * gamma};
    } else {  // B = (j, i, l): cancel k
      const double m = -ck / gamma;
      out = {cj + m * beta, ci + m * alpha, cl - m};
      to_a = false;
    }
    const int face = to_a ? fa : fb, slot = to_a ? r : s;
    Eigen::Vector3d weights;
    for (int n = 0; n < 3; ++n) weights[(slot + n) % 3] = out[n];
    p.face = face;
    p.weights = normalised(weights);
    in_face[static_cast<size_t>(face)].push_back(id);
  }
}

std::vector<std::vector<int>> bucket_by_face(const IntrinsicTriangulation& tri,
                                             std::vector<TriangulationPoint>& points) {
  std::vector<std::vector<int>> in_face(static_cast<size_t>(tri.face_count()));
  for (size_t id = 0; id < points.size(); ++id) {
    check_face(tri, points[id].face);
    points[id].weights = normalised(points[id].weights);
    in_face[static_cast<size_t>(points[id].face)].push_back(static_cast<int>(id));
  }
  return in_face;
}

}  // namespace

Eigen::Vector3d barycentric_at(const IntrinsicTriangulation& tri, const TriangulationPoint& point,
                               const Eigen::VectorXd& u) {
  check_face(tri, point.face);
  check_scale_factors(tri, u);
  Eigen::Vector3d log_scale;
  for (int k = 0; k < 3; ++k) log_scale[k] = -u[corner_vertex(tri, point.face, k)];
  const Eigen::Vector3d scale = (log_scale.array() - log_scale.maxCoeff()).exp();
  return normalised(point.weights.cwiseProduct(scale));
}

TriangulationPoint point_at_barycentric(const IntrinsicTriangulation& tri, int face,
                                        const Eigen::Vector3d& barycentric,
                                        const Eigen::VectorXd& u) {
  check_face(tri, face);
  check_scale_factors(tri, u);
  if ((barycentric.array() < 0).any()) {
    throw InvalidInputError("intrinsic point: negative barycentric coordinates");
  }
  Eigen::Vector3d log_scale;
  for (int k = 0; k < 3; ++k) log_scale[k] = u[corner_vertex(tri, face, k)];
  const Eigen::Vector3d scale = (log_scale.array() - log_scale.maxCoeff()).exp();
  return {face, normalised(barycentric.cwiseProduct(scale))};
}

TriangulationPoint vertex_point(const IntrinsicTriangulation& tri, int v) {
  if (v < 0 || v >= tri.vertex_count) {
    throw InvalidInputError("intrinsic point: vertex " + std::to_string(v) + " of " +
                            std::to_string(tri.vertex_count));
  }
  const auto slot = std::find(tri.tail.begin(), tri.tail.end(), v) - tri.tail.begin();
  if (slot == static_cast<std::ptrdiff_t>(tri.tail.size())) {
    throw InvalidInputError("intrinsic point: vertex " + std::to_string(v) + " has no face");
  }
  TriangulationPoint p;
  p.face = static_cast<int>(slot / 3);
  p.weights[static_cast<Eigen::Index>(slot % 3)] = 1.0;
  return p;
}

std::vector<TriangulationPoint> vertex_points(const IntrinsicTriangulation& tri) {
  std::vector<TriangulationPoint> points(static_cast<size_t>(tri.vertex_count));
  for (size_t slot = tri.tail.size(); slot-- > 0;) {
    TriangulationPoint& p = points[static_cast<size_t>(tri.tail[slot])];
    p.face = static_cast<int>(slot / 3);
    p.weights = Eigen::Vector3d::Zero();
    p.weights[static_cast<Eigen::Index>(slot % 3)] = 1.0;
  }
  for (size_t v = 0; v < points.size(); ++v) {
    if (points[v].face < 0) {
      throw InvalidInputError("intrinsic point: vertex " + std::to_string(v) + " has no face");
    }
  }
  return points;
}

Eigen::Vector3d point_position(const IntrinsicTriangulation& tri, const Eigen::MatrixX3d& positions,
                               const TriangulationPoint& point) {
  check_face(tri, point.face);
  if (positions.rows() != tri.vertex_count) {
    throw InvalidInputError("intrinsic point: " + std::to_string(positions.rows()) +
                            " positions for " + std::to_string(tri.vertex_count) + " vertices");
  }
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k) {
    x += point.weights[k] * positions.row(corner_vertex(tri, point.face, k)).transpose();
  }
  return x;
}

IntrinsicCorrespondence::IntrinsicCorrespondence(IntrinsicTriangulation initial,
                                                 const std::vector<int>& flip_log)
    : initial_(std::move(initial)), final_(initial_) {
  using T = IntrinsicTriangulation;
  flips_.reserve(flip_log.size());
  for (size_t n = 0; n < flip_log.size(); ++n) {
    const int e = flip_log[n];
    if (e < 0 || e >= final_.edge_count() || !is_flippable(final_, e)) {
      throw InvalidInputError("intrinsic correspondence: flip " + std::to_string(n) + " of edge " +
                              std::to_string(e) + " is not a flip of the " +
                              std::to_string(final_.edge_count()) + "-edge triangulation");
    }
    Flip flip;
    flip.h = final_.edge_halfedge[static_cast<size_t>(e)];
    flip.t = final_.twin[static_cast<size_t>(flip.h)];
    const auto log_of = [&](int slot) {
      return final_.log_length[final_.edge[static_cast<size_t>(slot)]];
    };
    const double ij = final_.log_length[e], jk = log_of(T::next(flip.h)),
                 ki = log_of(T::prev(flip.h)), il = log_of(T::next(flip.t)),
                 lj = log_of(T::prev(flip.t));
    flip_edge(final_, e);
    const double kl = final_.log_length[e];
    flip.alpha = std::exp(lj + kl - ij - ki);
    flip.beta = std::exp(il + kl - ij - jk);
    flip.gamma = -std::exp(il + lj - ki - jk);
    flips_.push_back(flip);
  }
}

std::vector<TriangulationPoint> IntrinsicCorrespondence::to_final(
    std::vector<TriangulationPoint> points) const {
  std::vector<std::vector<int>> in_face = bucket_by_face(initial_, points);
  for (const Flip& flip : flips_) carry(flip, true, points, in_face);
  return points;
}

std::vector<TriangulationPoint> IntrinsicCorrespondence::to_initial(
    std::vector<TriangulationPoint> points) const {
  std::vector<std::vector<int>> in_face = bucket_by_face(final_, points);
  for (auto flip = flips_.rbegin(); flip != flips_.rend(); ++flip) {
    carry(*flip, false, points, in_face);
  }
  return points;
}

}  // namespace ricci
