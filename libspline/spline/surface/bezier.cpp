#include "spline/surface/bezier.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "ricci/mesh/errors.h"
#include "ricci/topology/slice.h"
#include "spline/basis/blossom.h"
#include "spline/basis/multi_index.h"
#include "spline/basis/triangle_basis.h"
#include "spline/tessellate/parallel_for.h"

namespace spline {
namespace {

using ricci::InvalidInputError;
using Polygon = std::vector<Eigen::Vector2d>;  // convex, counter-clockwise

// Coordinates of the face's plane: (lambda_1, lambda_2); the face is (0,0), (1,0), (0,1).
constexpr double kEps = 1e-12;

struct Segment {
  Eigen::Vector2d a, b;
};

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// The parameter range [lo, hi] of a + t (b - a) inside the convex polygon (shrunk by kEps);
// lo > hi when the segment misses its interior.
std::pair<double, double> clip(const Segment& s, const Polygon& polygon) {
  double lo = 0.0, hi = 1.0;
  const Eigen::Vector2d d = s.b - s.a;
  for (std::size_t i = 0; i < polygon.size() && lo <= hi; ++i) {
    const Eigen::Vector2d& p = polygon[i];
    const Eigen::Vector2d e = polygon[(i + 1) % polygon.size()] - p;
    // Inside: cross(e, x - p) > kEps |e|, with x = a + t d: f0 + t f1.
    const double f0 = cross2(e, s.a - p) - kEps * e.norm();
    const double f1 = cross2(e, d);
    if (std::abs(f1) < 1e-300) {
      if (f0 <= 0.0) return {1.0, 0.0};
    } else if (f1 > 0.0) {
      lo = std::max(lo, -f0 / f1);
    } else {
      hi = std::min(hi, -f0 / f1);
    }
  }
  return {lo, hi};
}

// Splits `polygon` by the segment's line when the segment crosses its interior.
bool split(const Polygon& polygon, const Segment& s, Polygon& left, Polygon& right) {
  const Eigen::Vector2d d = s.b - s.a;
  const double length = d.norm();
  if (!(length > kEps)) return false;
  const Eigen::Vector2d normal(-d.y() / length, d.x() / length);
  std::vector<double> h(polygon.size());
  double most = -1.0, least = 1.0;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    h[i] = normal.dot(polygon[i] - s.a);
    most = std::max(most, h[i]);
    least = std::min(least, h[i]);
  }
  if (!(most > kEps && least < -kEps)) return false;
  const auto [lo, hi] = clip(s, polygon);
  if (!((hi - lo) * length > kEps)) return false;
  left.clear();
  right.clear();
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const std::size_t j = (i + 1) % polygon.size();
    if (h[i] >= -kEps) left.push_back(polygon[i]);
    if (h[i] <= kEps) right.push_back(polygon[i]);
    if ((h[i] > kEps && h[j] < -kEps) || (h[i] < -kEps && h[j] > kEps)) {
      const Eigen::Vector2d x = polygon[i] + h[i] / (h[i] - h[j]) * (polygon[j] - polygon[i]);
      left.push_back(x);
      right.push_back(x);
    }
  }
  return left.size() >= 3 && right.size() >= 3;
}


// The segments between knots of one knot set of the functions reaching `face`, in the face's
// (lambda_1, lambda_2) coordinates, those that meet the face; without repeats.
std::vector<Segment> knot_segments(const ManifoldSplineSpace& space, int face) {
  const int chart = space.chart_of(face);
  const auto corners = space.atlas().face_positions(chart, face);
  const int n = space.degree();
  const Polygon triangle{{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}};
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> raw;
  const auto add = [&](const Eigen::Vector2d& x, const Eigen::Vector2d& y) {
    const Eigen::Vector2d a = barycentric_in(corners, x).tail<2>();
    const Eigen::Vector2d b = barycentric_in(corners, y).tail<2>();
    const auto [lo, hi] = clip({a, b}, triangle);
    if (!((hi - lo) * (b - a).norm() > kEps)) return;
    const bool ordered = a.x() < b.x() || (a.x() == b.x() && a.y() <= b.y());
    raw.emplace_back(ordered ? a : b, ordered ? b : a);
  };
  for (int j : space.reaching_faces(face)) {
    const std::array<KnotCloud, 3> clouds = space.face_clouds(chart, j);
    // A pair of knots shares a knot set V_beta = {t_{0,0..beta0}, t_{1,..}, t_{2,..}} when both
    // are of one cloud, or of clouds k and l at positions a, b with a + b <= n.
    for (int k = 0; k < 3; ++k) {
      for (int a = 0; a <= n; ++a) {
        for (int b = a + 1; b <= n; ++b) add(clouds[k].knots[a], clouds[k].knots[b]);
        for (int l = k + 1; l < 3; ++l) {
          for (int b = 0; a + b <= n; ++b) add(clouds[k].knots[a], clouds[l].knots[b]);
        }
      }
    }
  }
  const auto less = [](const auto& p, const auto& q) {
    const auto key = [](const auto& s) {
      return std::array<double, 4>{s.first.x(), s.first.y(), s.second.x(), s.second.y()};
    };
    return key(p) < key(q);
  };
  std::sort(raw.begin(), raw.end(), less);
  raw.erase(std::unique(raw.begin(), raw.end()), raw.end());
  std::vector<Segment> out;
  out.reserve(raw.size());
  for (const auto& [a, b] : raw) out.push_back({a, b});
  return out;
}

// The face's convex polynomial cells cut by its knot segments (see the header comment), in
// (lambda_1, lambda_2).
std::vector<Polygon> convex_cells(const std::vector<Segment>& segments) {
  std::vector<Polygon> cells{{{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}}}, next;
  Polygon left, right;
  for (const Segment& s : segments) {
    next.clear();
    for (const Polygon& cell : cells) {
      if (split(cell, s, left, right)) {
        next.push_back(left);
        next.push_back(right);
      } else {
        next.push_back(cell);
      }
    }
    std::swap(cells, next);
  }
  return cells;
}

// Appends the fan triangles of a convex cell with an interior (columns: barycentric corners).
void fan(const Polygon& cell, std::vector<Eigen::Matrix3d>& triangles) {
  for (std::size_t i = 1; i + 1 < cell.size(); ++i) {
    const Eigen::Vector2d &a = cell[0], &b = cell[i], &c = cell[i + 1];
    if (!(cross2(b - a, c - a) > 1e-24)) continue;  // no interior
    Eigen::Matrix3d t;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector2d& p = k == 0 ? a : (k == 1 ? b : c);
      t.col(k) << 1.0 - p.x() - p.y(), p.x(), p.y();
    }
    triangles.push_back(t);
  }
}

double factorial(int k) {
  double f = 1.0;
  for (int i = 2; i <= k; ++i) f *= i;
  return f;
}

// The spline's polynomial piece at chart point u of `face` (strictly inside one polynomial
// cell) as its Taylor expansion there, in the frame X = (x - u) / scale: the partial derivatives
// of every order k <= n from the directional derivatives D_d^k S along n + 1 directions (the
// simplex-spline recurrence gives them exactly), by least squares on the polarization identity
// D_d^k S = sum_i C(k, i) d_x^(k - i) d_y^i d^k S / dx^(k - i) dy^i.
BivariatePolynomial piece_at(const ManifoldSpline& spline, int chart, int face,
                             const Eigen::Vector2d& u, double scale) {
  const ManifoldSplineSpace& space = *spline.space;
  const ManifoldSplineSpace::ChartSpace& cs = space.chart_space(chart);
  const int n = space.degree();
  const int own = cs.triangle_of_row[static_cast<std::size_t>(
      space.atlas().charts[static_cast<std::size_t>(chart)].slot(face))];
  const auto stride = static_cast<std::size_t>(n + 1);
  std::vector<Eigen::Vector2d> directions;
  for (int j = 0; j <= n; ++j) {
    const double angle = M_PI * (j + 0.5) / (n + 1);
    directions.emplace_back(std::cos(angle), std::sin(angle));
  }
  // derivative[j](k, :) = D_{d_j}^k S (u), in units of scale^k.
  std::vector<Eigen::MatrixX3d> derivative(directions.size(), Eigen::MatrixX3d::Zero(n + 1, 3));
  std::vector<double> values, scratch;
  for (int a = cs.around_start[static_cast<std::size_t>(own)];
       a < cs.around_start[static_cast<std::size_t>(own) + 1]; ++a) {
    const int t = cs.around[static_cast<std::size_t>(a)];
    const TriangleBasis& basis = cs.space->triangle_basis(t);
    if (!basis.in_hull(u)) continue;
    const int owner = cs.face_of_triangle[static_cast<std::size_t>(t)];
    for (std::size_t j = 0; j < directions.size(); ++j) {
      basis.evaluate_directional(u, directions[j], n, {}, values, scratch);
      for (int i = 0; i < basis.size(); ++i) {
        const Eigen::RowVector3d c = spline.control_points.row(space.function_index(owner, i));
        double power = 1.0;
        for (int k = 0; k <= n; ++k, power *= scale) {
          derivative[j].row(k) += power * values[static_cast<std::size_t>(i) * stride + k] * c;
        }
      }
    }
  }
  BivariatePolynomial p;
  p.degree = n;
  p.origin = u;
  p.scale = scale;
  p.coefficients = Eigen::MatrixXd::Zero(monomial_count(n), 3);
  for (int k = 0; k <= n; ++k) {
    Eigen::MatrixXd system(static_cast<Eigen::Index>(directions.size()), k + 1);
    Eigen::MatrixXd rhs(static_cast<Eigen::Index>(directions.size()), 3);
    for (std::size_t j = 0; j < directions.size(); ++j) {
      const auto row = static_cast<Eigen::Index>(j);
      for (int i = 0; i <= k; ++i) {
        system(row, i) = factorial(k) / (factorial(i) * factorial(k - i)) *
                         std::pow(directions[j].x(), k - i) * std::pow(directions[j].y(), i);
      }
      rhs.row(row) = derivative[j].row(k);
    }
    const Eigen::MatrixXd partials = system.colPivHouseholderQr().solve(rhs);
    for (int i = 0; i <= k; ++i) {  // X^(k - i) Y^i / ((k - i)! i!)
      p.coefficients.row(monomial_index(k - i, i)) =
          partials.row(i) / (factorial(k - i) * factorial(i));
    }
  }
  return p;
}

// Bezier control points of p over the chart triangle with these corners: the blossom at
// (c_0^b0, c_1^b1, c_2^b2) for every beta.
Eigen::MatrixX3d bezier_control_points(const BivariatePolynomial& p,
                                       const std::array<Eigen::Vector2d, 3>& corners) {
  const std::vector<Eigen::Vector3i> betas = multi_indices(p.degree);
  Eigen::MatrixX3d out(static_cast<Eigen::Index>(betas.size()), 3);
  std::vector<Eigen::Vector2d> arguments;
  for (std::size_t b = 0; b < betas.size(); ++b) {
    arguments.clear();
    for (int k = 0; k < 3; ++k) arguments.insert(arguments.end(), betas[b][k], corners[k]);
    out.row(static_cast<Eigen::Index>(b)) = blossom(p, arguments).transpose();
  }
  return out;
}

}  // namespace

std::vector<Eigen::Matrix3d> polynomial_cells(const ManifoldSplineSpace& space, int face) {
  if (face < 0 || face >= space.face_count() || !space.in_domain(face)) {
    throw InvalidInputError("polynomial_cells: face " + std::to_string(face) +
                            " is not in the spline's domain");
  }
  std::vector<Eigen::Matrix3d> triangles;
  for (const Polygon& cell : convex_cells(knot_segments(space, face))) fan(cell, triangles);
  return triangles;
}

BezierExport bezier_patches(const SplineSurface& surface, const BezierOptions& options) {
  const ManifoldSplineSpace& space = *surface.spline.space;
  const int n = space.degree();
  std::vector<int> faces;
  for (int f : space.domain_faces()) {
    const auto index = static_cast<std::size_t>(f);
    if (surface.skipped_faces.empty() || surface.skipped_faces[index] == 0) faces.push_back(f);
  }
  std::vector<std::vector<BezierPatch>> per_face(faces.size());
  std::vector<int> segments(faces.size(), 0);
  parallel_for(faces.size(), options.threads, [&](std::size_t i) {
    const int face = faces[i];
    const auto hs = ricci::face_halfedges(surface.domain, surface.domain.face_handle(face));
    std::array<int, 3> vertices{};
    for (int k = 0; k < 3; ++k) vertices[k] = surface.domain.to_vertex_handle(hs[k]).idx();
    const std::vector<Segment> cuts = knot_segments(space, face);
    segments[i] = static_cast<int>(cuts.size());
    const int chart = space.chart_of(face);
    std::vector<Eigen::Matrix3d> triangles;
    for (const Polygon& cell : convex_cells(cuts)) {
      triangles.clear();
      fan(cell, triangles);
      if (triangles.empty()) continue;
      // One piece per cell, taken at the cell's vertex centroid (inside: the cell is convex).
      Eigen::Vector2d centre_bary = Eigen::Vector2d::Zero();
      for (const Eigen::Vector2d& v : cell) centre_bary += v;
      centre_bary /= static_cast<double>(cell.size());
      const Eigen::Vector3d centre_b(1.0 - centre_bary.x() - centre_bary.y(), centre_bary.x(),
                                     centre_bary.y());
      const Eigen::Vector2d centre = space.chart_point(chart, face, centre_b);
      double size = 0.0;
      for (const Eigen::Vector2d& v : cell) {
        const Eigen::Vector3d b(1.0 - v.x() - v.y(), v.x(), v.y());
        size = std::max(size, 2.0 * (space.chart_point(chart, face, b) - centre).norm());
      }
      const BivariatePolynomial piece = piece_at(surface.spline, chart, face, centre, size);
      for (const Eigen::Matrix3d& t : triangles) {
        BezierPatch patch;
        patch.face = face;
        patch.vertices = vertices;
        patch.corners = t;
        std::array<Eigen::Vector2d, 3> corners;
        for (int k = 0; k < 3; ++k) corners[k] = space.chart_point(chart, face, t.col(k));
        patch.control_points = bezier_control_points(piece, corners);
        per_face[i].push_back(std::move(patch));
      }
    }
  });
  BezierExport out;
  out.degree = n;
  out.faces = static_cast<int>(faces.size());
  for (std::size_t i = 0; i < faces.size(); ++i) {
    out.knot_segments += segments[i];
    for (auto& p : per_face[i]) out.patches.push_back(std::move(p));
  }
  return out;
}

Eigen::Vector3d bezier_blossom(const Eigen::MatrixX3d& control_points, int degree,
                               const std::vector<Eigen::Vector3d>& arguments) {
  if (degree < 0 || control_points.rows() != multi_index_count(degree) ||
      static_cast<int>(arguments.size()) != degree) {
    throw InvalidInputError("bezier_blossom: " + std::to_string(control_points.rows()) +
                            " control points and " + std::to_string(arguments.size()) +
                            " arguments for degree " + std::to_string(degree));
  }
  Eigen::MatrixX3d level = control_points;
  for (int r = 0; r < degree; ++r) {
    const int m = degree - r - 1;
    const Eigen::Vector3d& a = arguments[static_cast<std::size_t>(r)];
    Eigen::MatrixX3d next(multi_index_count(m), 3);
    for (const Eigen::Vector3i& g : multi_indices(m)) {
      Eigen::RowVector3d v = Eigen::RowVector3d::Zero();
      for (int k = 0; k < 3; ++k) {
        Eigen::Vector3i up = g;
        ++up[k];
        v += a[k] * level.row(multi_index_position(up));
      }
      next.row(multi_index_position(g)) = v;
    }
    level = std::move(next);
  }
  return level.row(0).transpose();
}

Eigen::Vector3d evaluate_bezier(const Eigen::MatrixX3d& control_points, int degree,
                                const Eigen::Vector3d& lambda) {
  return bezier_blossom(control_points, degree,
                        std::vector<Eigen::Vector3d>(static_cast<std::size_t>(degree), lambda));
}

Eigen::Vector3d bezier_derivative(const Eigen::MatrixX3d& control_points, int degree,
                                  const Eigen::Vector3d& lambda, const Eigen::Vector3d& direction,
                                  int order) {
  if (order < 0 || order > degree) {
    throw InvalidInputError("bezier_derivative: order " + std::to_string(order) +
                            " outside 0.." + std::to_string(degree));
  }
  std::vector<Eigen::Vector3d> arguments(static_cast<std::size_t>(degree), lambda);
  double factor = 1.0;
  for (int k = 0; k < order; ++k) {
    arguments[static_cast<std::size_t>(k)] = direction;
    factor *= degree - k;
  }
  return factor * bezier_blossom(control_points, degree, arguments);
}

}  // namespace spline
