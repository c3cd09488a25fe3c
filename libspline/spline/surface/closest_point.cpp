#include "spline/surface/closest_point.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>
#include <utility>

#include "ricci/mesh/errors.h"
#include "spline/tessellate/parallel_for.h"

namespace spline {
namespace {

using ricci::InvalidInputError;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

// One triangle of the candidate tessellation: 3D corners, owner (domain face >= 0, or -1 - fill)
// and the corners' parameters (barycentric in the face, or the fill's D in x, y).
struct CandidateTriangle {
  Eigen::Matrix3d corners;     // columns
  Eigen::Matrix3d parameters;  // columns: barycentric (face) or (x, y, 0) (fill)
  int owner = -1;
  double deviation = 0.0;
};

// Closest point of triangle abc (columns) to p: barycentric coordinates (Ericson, RTCD 5.1.5).
Eigen::Vector3d closest_on_triangle(const Eigen::Matrix3d& t, const Eigen::Vector3d& p) {
  const Eigen::Vector3d a = t.col(0), b = t.col(1), c = t.col(2);
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return {1.0, 0.0, 0.0};
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return {0.0, 1.0, 0.0};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    const double v = d1 / (d1 - d3);
    return {1.0 - v, v, 0.0};
  }
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return {0.0, 0.0, 1.0};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    const double w = d2 / (d2 - d6);
    return {1.0 - w, 0.0, w};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0.0, 1.0 - w, w};
  }
  const double denom = va + vb + vc;
  if (!(std::abs(denom) > 0.0)) return {1.0, 0.0, 0.0};  // degenerate: a corner
  const double v = vb / denom, w = vc / denom;
  return {1.0 - v - w, v, w};
}


// A bounding-volume tree over the candidate triangles (median splits, leaves of <= 4).
class TriangleTree {
 public:
  explicit TriangleTree(const std::vector<CandidateTriangle>& triangles) : triangles_(triangles) {
    order_.resize(triangles.size());
    std::iota(order_.begin(), order_.end(), 0);
    if (!order_.empty()) build(0, static_cast<int>(order_.size()));
  }

  // Every triangle whose distance to p is at most `radius` (with its distance).
  void within(const Eigen::Vector3d& p, double radius,
              std::vector<std::pair<double, int>>& out) const {
    if (nodes_.empty()) return;
    std::vector<int> stack{0};
    while (!stack.empty()) {
      const Node& n = nodes_[static_cast<std::size_t>(stack.back())];
      stack.pop_back();
      if (box_distance(n, p) > radius) continue;
      if (n.left < 0) {
        for (int i = n.begin; i < n.end; ++i) {
          const int t = order_[static_cast<std::size_t>(i)];
          const double d = distance(t, p);
          if (d <= radius) out.emplace_back(d, t);
        }
      } else {
        stack.push_back(n.left);
        stack.push_back(n.right);
      }
    }
  }

  // The smallest triangle distance to p (branch and bound).
  [[nodiscard]] double nearest(const Eigen::Vector3d& p) const {
    double best = kInfinity;
    if (nodes_.empty()) return best;
    std::vector<std::pair<double, int>> stack{{box_distance(nodes_[0], p), 0}};
    while (!stack.empty()) {
      const auto [bound, index] = stack.back();
      stack.pop_back();
      if (bound >= best) continue;
      const Node& n = nodes_[static_cast<std::size_t>(index)];
      if (n.left < 0) {
        for (int i = n.begin; i < n.end; ++i) {
          best = std::min(best, distance(order_[static_cast<std::size_t>(i)], p));
        }
        continue;
      }
      const double dl = box_distance(nodes_[static_cast<std::size_t>(n.left)], p);
      const double dr = box_distance(nodes_[static_cast<std::size_t>(n.right)], p);
      // Nearer child last: popped first.
      if (dl < dr) {
        stack.emplace_back(dr, n.right);
        stack.emplace_back(dl, n.left);
      } else {
        stack.emplace_back(dl, n.left);
        stack.emplace_back(dr, n.right);
      }
    }
    return best;
  }

  [[nodiscard]] double distance(int t, const Eigen::Vector3d& p) const {
    const Eigen::Matrix3d& c = triangles_[static_cast<std::size_t>(t)].corners;
    return (c * closest_on_triangle(c, p) - p).norm();
  }

 private:
  struct Node {
    Eigen::Vector3d lo, hi;
    int left = -1, right = -1, begin = 0, end = 0;
  };

  static double box_distance(const Node& n, const Eigen::Vector3d& p) {
    return (p - p.cwiseMax(n.lo).cwiseMin(n.hi)).norm();
  }

  int build(int begin, int end) {
    const int index = static_cast<int>(nodes_.size());
    nodes_.emplace_back();
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(kInfinity), hi = -lo;
    for (int i = begin; i < end; ++i) {
      const Eigen::Matrix3d& c = triangles_[static_cast<std::size_t>(order_[i])].corners;
      lo = lo.cwiseMin(c.rowwise().minCoeff());
      hi = hi.cwiseMax(c.rowwise().maxCoeff());
    }
    nodes_[static_cast<std::size_t>(index)].lo = lo;
    nodes_[static_cast<std::size_t>(index)].hi = hi;
    nodes_[static_cast<std::size_t>(index)].begin = begin;
    nodes_[static_cast<std::size_t>(index)].end = end;
    if (end - begin <= 4) return index;
    int axis = 0;
    (hi - lo).maxCoeff(&axis);
    const int mid = (begin + end) / 2;
    std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                     [&](int x, int y) {
                       return triangles_[static_cast<std::size_t>(x)].corners.row(axis).sum() <
                              triangles_[static_cast<std::size_t>(y)].corners.row(axis).sum();
                     });
    const int left = build(begin, mid);
    const int right = build(mid, end);
    nodes_[static_cast<std::size_t>(index)].left = left;
    nodes_[static_cast<std::size_t>(index)].right = right;
    return index;
  }

  const std::vector<CandidateTriangle>& triangles_;
  std::vector<int> order_;
  std::vector<Node> nodes_;
};

// Largest distance between the surface and the triangle at its centre and edge midpoints
// (`surface` maps a parameter column to the surface point).
template <class Surface>
double deviation(const CandidateTriangle& t, const Surface& surface) {
  double worst = 0.0;
  const std::array<Eigen::Vector3d, 4> at{
      Eigen::Vector3d::Constant(1.0 / 3.0), Eigen::Vector3d(0.5, 0.5, 0.0),
      Eigen::Vector3d(0.0, 0.5, 0.5), Eigen::Vector3d(0.5, 0.0, 0.5)};
  for (const Eigen::Vector3d& w : at) {
    worst = std::max(worst, (surface(Eigen::Vector3d(t.parameters * w)) - t.corners * w).norm());
  }
  return worst;
}

// Unit direction of fill's boundary polygon at its segment nearest to u.
Eigen::Vector2d boundary_direction(const HoleFill& fill, const Eigen::Vector2d& u) {
  double best = kInfinity;
  Eigen::Vector2d direction = Eigen::Vector2d::UnitX();
  for (const auto& edge : fill.boundary_points) {
    for (std::size_t i = 0; i + 1 < edge.size(); ++i) {
      const Eigen::Vector2d d = edge[i + 1] - edge[i];
      const double length2 = d.squaredNorm();
      if (!(length2 > 0.0)) continue;
      const double t = std::clamp((u - edge[i]).dot(d) / length2, 0.0, 1.0);
      const double distance = (edge[i] + t * d - u).norm();
      if (distance < best) {
        best = distance;
        direction = d / std::sqrt(length2);
      }
    }
  }
  return direction;
}

bool tessellated_face(const SplineSurface& s, int face) {
  return s.spline.space->in_domain(face) &&
         (s.skipped_faces.empty() || s.skipped_faces[static_cast<std::size_t>(face)] == 0);
}

// The candidate triangles of one domain face: its barycentric grid of density d.
void face_triangles(const SplineSurface& s, int face, int d,
                    std::vector<CandidateTriangle>& out) {
  const auto id = [d](int i, int j) { return i * (d + 1) - i * (i - 1) / 2 + j; };
  std::vector<Eigen::Vector3d> bary, position;
  for (int i = 0; i <= d; ++i) {
    for (int j = 0; j <= d - i; ++j) {
      bary.emplace_back(static_cast<double>(d - i - j) / d, static_cast<double>(i) / d,
                        static_cast<double>(j) / d);
      position.push_back(
          s.spline.evaluate({face, bary.back()}, -1, {}, BasisDerivatives::none).position);
    }
  }
  const auto add = [&](int a, int b, int c) {
    CandidateTriangle t;
    t.owner = face;
    t.corners << position[a], position[b], position[c];
    t.parameters << bary[a], bary[b], bary[c];
    t.deviation = deviation(t, [&](const Eigen::Vector3d& b) {
      return s.spline.evaluate({face, b}, -1, {}, BasisDerivatives::none).position;
    });
    out.push_back(t);
  };
  for (int i = 0; i < d; ++i) {
    for (int j = 0; j < d - i; ++j) {
      add(id(i, j), id(i + 1, j), id(i, j + 1));
      if (j + 1 < d - i) add(id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
    }
  }
}

// The candidate triangles of fill `index`: tessellate_fill's triangles at density d.
void fill_triangles(const HoleFill& fill, int index, int d, std::vector<CandidateTriangle>& out) {
  const PatchTessellation patch = tessellate_fill(fill, d);
  const auto parameter = [&](int v) -> Eigen::Vector2d {
    if (v >= 0) return patch.parameters.row(v).transpose();
    const int r = -1 - v;
    return fill.parameter(r / d, static_cast<double>(r % d) / d);
  };
  for (Eigen::Index k = 0; k < patch.triangles.rows(); ++k) {
    CandidateTriangle t;
    t.owner = -1 - index;
    for (int c = 0; c < 3; ++c) {
      const int v = patch.triangles(k, c);
      const Eigen::Vector2d u = parameter(v);
      t.parameters.col(c) << u, 0.0;
      t.corners.col(c) = v >= 0 ? Eigen::Vector3d(patch.positions.row(v).transpose())
                                : fill.evaluate(u).position;
    }
    t.deviation = deviation(
        t, [&](const Eigen::Vector3d& u) { return fill.evaluate(u.head<2>()).position; });
    out.push_back(t);
  }
}

// One Newton step's direction for |S - q|^2 / 2: the full Hessian when it is positive definite,
// else Gauss-Newton's J^T J.
Eigen::Vector2d newton_step(const Eigen::Vector3d& r, const Eigen::Vector3d& du,
                            const Eigen::Vector3d& dv, const Eigen::Vector3d& duu,
                            const Eigen::Vector3d& duv, const Eigen::Vector3d& dvv) {
  Eigen::Matrix<double, 3, 2> j;
  j << du, dv;
  const Eigen::Vector2d g = j.transpose() * r;
  Eigen::Matrix2d h = j.transpose() * j;
  Eigen::Matrix2d full = h;
  full(0, 0) += r.dot(duu);
  full(0, 1) += r.dot(duv);
  full(1, 0) += r.dot(duv);
  full(1, 1) += r.dot(dvv);
  if (full(0, 0) > 0.0 && full.determinant() > 0.0) h = full;
  if (!(std::abs(h.determinant()) > 0.0)) return Eigen::Vector2d::Zero();
  return -h.inverse() * g;
}

// Newton's step along a unit parameter direction e for |S - q|^2 / 2 (Gauss-Newton where the
// second derivative is not positive), as a multiple of e.
Eigen::Vector2d line_step(const Eigen::Vector3d& r, const Eigen::Vector3d& du,
                          const Eigen::Vector3d& dv, const Eigen::Vector3d& duu,
                          const Eigen::Vector3d& duv, const Eigen::Vector3d& dvv,
                          const Eigen::Vector2d& e) {
  const Eigen::Vector3d se = e.x() * du + e.y() * dv;
  const Eigen::Vector3d see = e.x() * e.x() * duu + 2.0 * e.x() * e.y() * duv + e.y() * e.y() * dvv;
  const double slope = r.dot(se);
  double curvature = se.squaredNorm() + r.dot(see);
  if (!(curvature > 0.0)) curvature = se.squaredNorm();
  if (!(curvature > 0.0)) return Eigen::Vector2d::Zero();
  return -(slope / curvature) * e;
}

// The distance's gradient in the parameter plane, |J^T r| (the same in every chart: the
// transitions are rigid).
double parameter_gradient(const Eigen::Vector3d& r, const Eigen::Vector3d& du,
                          const Eigen::Vector3d& dv) {
  return Eigen::Vector2d(r.dot(du), r.dot(dv)).norm();
}

// Whether a trial point at squared distance `d` (gradient `g`) is taken from one at `best`
// (gradient `g0`): when it is nearer, or, at the rounding floor of the squared distance (the
// difference below what rounding the positions of magnitude `size` makes of it), when a full
// Newton step halves the gradient. A foot point close to the target (distance 1e-3 of the
// diagonal) has a squared distance flat to rounding while its residual is still 1e-7 off normal.
bool nearer_or_more_normal(double d, double best, double g, double g0, bool full_step,
                           double size) {
  if (d < best) return true;
  const double floor = 8.0 * std::numeric_limits<double>::epsilon() * size * std::sqrt(best);
  return full_step && d <= best + floor && g < 0.5 * g0;
}

}  // namespace

struct ClosestPointIndex::Data {
  const SplineSurface& surface;
  ClosestPointOptions options;
  std::vector<CandidateTriangle> triangles;
  std::unique_ptr<TriangleTree> tree;
  double max_deviation = 0.0;
  double scale = 1.0;  // bounding-box diagonal of the tessellation

  Data(const SplineSurface& s, const ClosestPointOptions& o) : surface(s), options(o) {}

  // Walks from `from` (in `face`) towards chart point u of the face's neighbourhood chart across
  // tessellated faces held by that chart; stops on the region's rim.
  [[nodiscard]] DomainPoint walk(DomainPoint from, const Eigen::Vector2d& u) const {
    const ManifoldSplineSpace& space = *surface.spline.space;
    const int chart = space.chart_of(from.face);
    const ricci::Chart& c = space.atlas().charts[static_cast<std::size_t>(chart)];
    Eigen::Vector2d a = space.chart_point(chart, from.face, from.barycentric);
    int face = from.face;
    for (int hop = 0; hop < 16; ++hop) {
      const auto corners = space.atlas().face_positions(chart, face);
      const Eigen::Vector3d ba = barycentric_in(corners, a);
      const Eigen::Vector3d bu = barycentric_in(corners, u);
      if (bu.minCoeff() >= 0.0) return {face, bu};
      // Where the segment a -> u leaves the face: the first coordinate to reach 0.
      double t_exit = 1.0;
      int k_exit = 0;
      for (int k = 0; k < 3; ++k) {
        if (bu[k] < 0.0) {
          const double t = std::max(0.0, ba[k]) / (std::max(0.0, ba[k]) - bu[k]);
          if (t < t_exit) {
            t_exit = t;
            k_exit = k;
          }
        }
      }
      Eigen::Vector3d exit = ba + t_exit * (bu - ba);
      exit[k_exit] = 0.0;
      exit = exit.cwiseMax(0.0);
      exit /= exit.sum();
      const int next = space.neighbour(face, k_exit);
      if (next < 0 || !tessellated_face(surface, next) || c.slot(next) < 0) return {face, exit};
      a = corners.transpose() * exit;
      face = next;
    }
    const Eigen::Vector3d b = barycentric_in(space.atlas().face_positions(chart, face), a);
    Eigen::Vector3d clamped = b.cwiseMax(0.0);
    return {face, clamped / clamped.sum()};
  }

  [[nodiscard]] ClosestPoint on_spline(DomainPoint point, const Eigen::Vector3d& q) const {
    const ManifoldSplineSpace& space = *surface.spline.space;
    SurfaceJet jet = surface.spline.evaluate(point);
    double best = (jet.position - q).squaredNorm();
    for (int it = 0; it < options.iterations; ++it) {
      Eigen::Vector2d step =
          newton_step(jet.position - q, jet.du, jet.dv, jet.duu, jet.duv, jet.dvv);
      const int chart = space.chart_of(point.face);
      const Eigen::Vector2d u0 = space.chart_point(chart, point.face, point.barycentric);
      // On the region's rim with the step pointing out of it: Newton along the rim edge.
      const auto corners = space.atlas().face_positions(chart, point.face);
      const Eigen::Vector3d ahead = barycentric_in(corners, u0 + step);
      for (int k = 0; k < 3; ++k) {
        if (point.barycentric[k] > 1e-12 || ahead[k] >= 0.0) continue;
        const int g = space.neighbour(point.face, k);
        const ricci::Chart& c = space.atlas().charts[static_cast<std::size_t>(chart)];
        if (g >= 0 && tessellated_face(surface, g) && c.slot(g) >= 0) continue;
        const Eigen::Vector2d e =
            (corners.row((k + 2) % 3) - corners.row((k + 1) % 3)).transpose().normalized();
        step = line_step(jet.position - q, jet.du, jet.dv, jet.duu, jet.duv, jet.dvv, e);
        break;
      }
      bool moved = false;
      for (double f = 1.0; f > 1e-3; f *= 0.5) {
        const DomainPoint next = walk(point, u0 + f * step);
        const SurfaceJet trial = surface.spline.evaluate(next);
        const double d = (trial.position - q).squaredNorm();
        const double g = parameter_gradient(trial.position - q, trial.du, trial.dv);
        const double g0 = parameter_gradient(jet.position - q, jet.du, jet.dv);
        if (nearer_or_more_normal(d, best, g, g0, f == 1.0, scale + q.norm())) {
          moved = d < best * (1.0 - 1e-15) || g < 0.5 * g0 ||
                  (trial.position - jet.position).norm() > 1e-15 * scale;
          best = d;
          point = next;
          jet = trial;
          break;
        }
      }
      if (!moved) break;
    }
    ClosestPoint r;
    r.location.point = point;
    r.position = jet.position;
    r.distance = std::sqrt(best);
    return r;
  }

  [[nodiscard]] ClosestPoint on_fill(int index, Eigen::Vector2d u, const Eigen::Vector3d& q) const {
    const HoleFill& fill = surface.fills[static_cast<std::size_t>(index)];
    SplineJet jet = fill.jet(u);
    double best = (jet.value - q).squaredNorm();
    for (int it = 0; it < options.iterations; ++it) {
      Eigen::Vector2d step =
          newton_step(jet.value - q, jet.gradient.col(0), jet.gradient.col(1),
                      jet.hessian.col(0), jet.hessian.col(1), jet.hessian.col(2));
      // On D's boundary with the step pointing out of D: Newton along the boundary.
      if (!in_fill_domain(fill, u + 1e-9 * step, 0.0)) {
        step = line_step(jet.value - q, jet.gradient.col(0), jet.gradient.col(1),
                         jet.hessian.col(0), jet.hessian.col(1), jet.hessian.col(2),
                         boundary_direction(fill, u));
      }
      bool moved = false;
      for (double f = 1.0; f > 1e-3; f *= 0.5) {
        Eigen::Vector2d next = u + f * step;
        if (!in_fill_domain(fill, next, 0.0)) {
          // Clamp to D's boundary along the step (bisection on the inside test).
          double lo = 0.0, hi = f;
          for (int b = 0; b < 40; ++b) {
            const double mid = 0.5 * (lo + hi);
            (in_fill_domain(fill, u + mid * step, 0.0) ? lo : hi) = mid;
          }
          next = u + lo * step;
        }
        const SplineJet trial = fill.jet(next);
        const double d = (trial.value - q).squaredNorm();
        const double g =
            parameter_gradient(trial.value - q, trial.gradient.col(0), trial.gradient.col(1));
        const double g0 =
            parameter_gradient(jet.value - q, jet.gradient.col(0), jet.gradient.col(1));
        if (nearer_or_more_normal(d, best, g, g0, f == 1.0, scale + q.norm())) {
          moved = d < best * (1.0 - 1e-15) || g < 0.5 * g0 ||
                  (trial.value - jet.value).norm() > 1e-15 * scale;
          best = d;
          u = next;
          jet = trial;
          break;
        }
      }
      if (!moved) break;
    }
    ClosestPoint r;
    r.location.fill = index;
    r.location.fill_parameter = u;
    r.position = jet.value;
    r.distance = std::sqrt(best);
    return r;
  }
};

ClosestPointIndex::ClosestPointIndex(const SplineSurface& surface,
                                     const ClosestPointOptions& options)
    : data_(std::make_unique<Data>(surface, options)) {
  if (options.density < 1 || options.iterations < 1) {
    throw InvalidInputError("closest point: density and iterations must be >= 1");
  }
  const ManifoldSplineSpace& space = *surface.spline.space;
  const std::vector<int>& faces = space.domain_faces();
  const std::size_t parts = faces.size() + surface.fills.size();
  std::vector<std::vector<CandidateTriangle>> per_part(parts);
  parallel_for(parts, options.threads, [&](std::size_t i) {
    if (i < faces.size()) {
      if (tessellated_face(surface, faces[i])) {
        face_triangles(surface, faces[i], options.density, per_part[i]);
      }
    } else {
      const int f = static_cast<int>(i - faces.size());
      fill_triangles(surface.fills[static_cast<std::size_t>(f)], f, options.density,
                     per_part[i]);
    }
  });
  auto& triangles = data_->triangles;
  for (auto& part : per_part) triangles.insert(triangles.end(), part.begin(), part.end());
  if (triangles.empty()) throw InvalidInputError("closest point: the surface has no faces");
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(kInfinity), hi = -lo;
  for (const auto& t : triangles) {
    lo = lo.cwiseMin(t.corners.rowwise().minCoeff());
    hi = hi.cwiseMax(t.corners.rowwise().maxCoeff());
  }
  data_->scale = (hi - lo).norm();
  for (auto& t : triangles) {
    t.deviation = 2.0 * t.deviation + 1e-12 * data_->scale;
    data_->max_deviation = std::max(data_->max_deviation, t.deviation);
  }
  data_->tree = std::make_unique<TriangleTree>(triangles);
}

ClosestPointIndex::~ClosestPointIndex() = default;

int ClosestPointIndex::triangle_count() const {
  return static_cast<int>(data_->triangles.size());
}

ClosestPoint ClosestPointIndex::find(const Eigen::Vector3d& target) const {
  if (!target.allFinite()) throw InvalidInputError("closest point: the target is not finite");
  const Data& d = *data_;
  // Every triangle whose surface piece may be nearer than the nearest triangle's piece.
  const double nearest = d.tree->nearest(target);
  std::vector<std::pair<double, int>> near;
  d.tree->within(target, nearest + 2.0 * d.max_deviation, near);
  // One start per candidate triangle, by lower bound: Newton's method from one triangle of a
  // face or patch can stop in a local minimum (a far target facing a broad patch, a minimum on a
  // rim edge reached from across the face) that a start nearer the minimum does not.
  struct Start {
    double lower;
    int triangle;
  };
  std::vector<Start> starts;
  starts.reserve(near.size());
  for (const auto& [distance, t] : near) {
    starts.push_back({distance - d.triangles[static_cast<std::size_t>(t)].deviation, t});
  }
  std::sort(starts.begin(), starts.end(),
            [](const Start& a, const Start& b) { return a.lower < b.lower; });
  ClosestPoint best;
  best.distance = kInfinity;
  int tried = 0;
  for (const Start& s : starts) {
    if (s.lower > best.distance) break;
    const CandidateTriangle& tri = d.triangles[static_cast<std::size_t>(s.triangle)];
    const Eigen::Vector3d lambda = closest_on_triangle(tri.corners, target);
    const Eigen::Vector3d parameter = tri.parameters * lambda;
    ClosestPoint r = tri.owner >= 0 ? d.on_spline({tri.owner, parameter}, target)
                                    : d.on_fill(-1 - tri.owner, parameter.head<2>(), target);
    ++tried;
    if (r.distance < best.distance) best = r;
  }
  best.candidates = tried;
  return best;
}

std::vector<ClosestPoint> ClosestPointIndex::find_all(const Eigen::MatrixX3d& targets) const {
  std::vector<ClosestPoint> out(static_cast<std::size_t>(targets.rows()));
  parallel_for(out.size(), data_->options.threads, [&](std::size_t i) {
    out[i] = find(Eigen::Vector3d(targets.row(static_cast<Eigen::Index>(i)).transpose()));
  });
  return out;
}

ClosestPoint closest_point(const SplineSurface& surface, const Eigen::Vector3d& target,
                           const ClosestPointOptions& options) {
  return ClosestPointIndex(surface, options).find(target);
}

}  // namespace spline
