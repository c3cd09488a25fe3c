#include "spline/fill/patch_domain.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "ricci/mesh/errors.h"

namespace spline::fill_detail {
namespace {

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

double orientation(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return cross(b - a, c - a);
}

// Triangulates the strip between two closed counter-clockwise rings (outer a, inner b) given as
// vertex ids into `points`: walk both rings once, each step closing a triangle with the shorter
// of the two possible diagonals among those that are counter-clockwise.
void stitch(const std::vector<Eigen::Vector2d>& points, const std::vector<int>& a,
            const std::vector<int>& b, std::vector<Eigen::Vector3i>& triangles) {
  const int na = static_cast<int>(a.size()), nb = static_cast<int>(b.size());
  // Start the inner ring at its point nearest to a[0].
  int j0 = 0;
  for (int j = 1; j < nb; ++j) {
    if ((points[b[j]] - points[a[0]]).squaredNorm() <
        (points[b[j0]] - points[a[0]]).squaredNorm()) {
      j0 = j;
    }
  }
  auto A = [&](int i) { return a[i % na]; };
  auto B = [&](int j) { return b[(j0 + j) % nb]; };
  int i = 0, j = 0;
  while (i < na || j < nb) {
    const bool can_a = i < na;
    const bool can_b = j < nb;
    const double tiny = 1e-12 * (points[A(i)] - points[B(j)]).squaredNorm();
    const bool valid_a = can_a && orientation(points[A(i)], points[A(i + 1)], points[B(j)]) > tiny;
    const bool valid_b = can_b && orientation(points[A(i)], points[B(j + 1)], points[B(j)]) > tiny;
    bool advance_a;
    if (valid_a && valid_b) {
      advance_a = (points[A(i + 1)] - points[B(j)]).squaredNorm() <=
                  (points[A(i)] - points[B(j + 1)]).squaredNorm();
    } else {
      advance_a = valid_a || !can_b;
    }
    if (advance_a) {
      triangles.emplace_back(A(i), A(i + 1), B(j));
      ++i;
    } else {
      triangles.emplace_back(A(i), B(j + 1), B(j));
      ++j;
    }
  }
}

}  // namespace

std::vector<Eigen::Vector2d> circle_layout(const std::vector<double>& lengths) {
  const int m = static_cast<int>(lengths.size());
  double total = 0.0;
  for (double l : lengths) total += l;
  if (m < 3 || !(total > 0.0) || !std::isfinite(total)) {
    throw ricci::InvalidInputError("hole fill: a rim of " + std::to_string(m) +
                                   " edges and length " + std::to_string(total) +
                                   " cannot be laid out");
  }
  const double radius = total / (2.0 * M_PI);
  std::vector<Eigen::Vector2d> corners;
  double share = 0.0;
  for (int j = 0; j < m; ++j) {
    const double angle = -2.0 * M_PI * share;  // clockwise in rim order
    corners.emplace_back(radius * std::cos(angle), radius * std::sin(angle));
    share += 0.8 * lengths[j] / total + 0.2 / m;
  }
  return corners;
}

double polygon_perimeter(const std::vector<Eigen::Vector2d>& polygon) {
  double sum = 0.0;
  for (std::size_t i = 0; i < polygon.size(); ++i)
    sum += (polygon[(i + 1) % polygon.size()] - polygon[i]).norm();
  return sum;
}

double polygon_area(const std::vector<Eigen::Vector2d>& polygon) {
  double sum = 0.0;
  for (std::size_t i = 0; i < polygon.size(); ++i)
    sum += cross(polygon[i], polygon[(i + 1) % polygon.size()]);
  return 0.5 * sum;
}

std::vector<Eigen::Vector2d> sample_scaled_polygon(const std::vector<Eigen::Vector2d>& polygon,
                                                   const Eigen::Vector2d& center, double scale,
                                                   int n) {
  const std::size_t m = polygon.size();
  const double perimeter = polygon_perimeter(polygon);
  std::vector<Eigen::Vector2d> out;
  out.reserve(n);
  std::size_t edge = 0;
  double edge_start = 0.0;  // arc length at the start of `edge`
  for (int i = 0; i < n; ++i) {
    const double s = perimeter * i / n;
    while (edge + 1 < m && edge_start + (polygon[(edge + 1) % m] - polygon[edge]).norm() <= s) {
      edge_start += (polygon[(edge + 1) % m] - polygon[edge]).norm();
      ++edge;
    }
    const Eigen::Vector2d p = polygon[edge], q = polygon[(edge + 1) % m];
    const double length = (q - p).norm();
    const double t = length > 0.0 ? std::clamp((s - edge_start) / length, 0.0, 1.0) : 0.0;
    out.push_back(center + scale * ((1.0 - t) * p + t * q - center));
  }
  return out;
}

std::vector<double> ring_scales(double start, double step) {
  std::vector<double> scales;
  for (double s = start; s > 0.75 * step; s -= step) scales.push_back(s);
  return scales;
}

PlanarTriangulation nested_rings(const std::vector<Eigen::Vector2d>& outer,
                                 const std::vector<Eigen::Vector2d>& shape,
                                 const Eigen::Vector2d& center, const std::vector<double>& scales,
                                 double spacing) {
  PlanarTriangulation t;
  t.positions = outer;
  std::vector<int> ring(outer.size());
  for (std::size_t i = 0; i < outer.size(); ++i) ring[i] = static_cast<int>(i);
  const double perimeter = polygon_perimeter(shape);
  for (double s : scales) {
    const int n = std::max(3, static_cast<int>(std::lround(perimeter * s / spacing)));
    // A ring with as many points as the one outside it would only add slivers near the centre.
    if (n < 3 || s <= 0.0) break;
    std::vector<int> inner;
    for (const auto& p : sample_scaled_polygon(shape, center, s, n)) {
      inner.push_back(static_cast<int>(t.positions.size()));
      t.positions.push_back(p);
    }
    stitch(t.positions, ring, inner, t.triangles);
    ring = std::move(inner);
  }
  const int c = static_cast<int>(t.positions.size());
  t.positions.push_back(center);
  for (std::size_t i = 0; i < ring.size(); ++i)
    t.triangles.emplace_back(ring[i], ring[(i + 1) % ring.size()], c);
  return t;
}

RimSample sample_rim(const ManifoldSpline& spline, const RimEdge& edge, double t) {
  const ManifoldSplineSpace& space = *spline.space;
  const int chart = space.chart_of(edge.face);
  const Eigen::Matrix<double, 3, 2> corners = space.atlas().face_positions(chart, edge.face);
  const Eigen::Vector2d a = corners.row(rim_edge_start_corner(edge)).transpose();
  const Eigen::Vector2d b = corners.row(rim_edge_end_corner(edge)).transpose();
  const Eigen::Vector2d opposite = corners.row(edge.corner).transpose();
  TieBreak tie;
  tie.direction = (opposite - 0.5 * (a + b)).normalized();
  RimSample sample;
  sample.jet = spline.evaluate({edge.face, rim_edge_barycentric(edge, t)}, chart, tie);
  const Eigen::Vector2d e = b - a;
  sample.chart_length = e.norm();
  const Eigen::Vector2d out = Eigen::Vector2d(e.y(), -e.x()) / sample.chart_length;
  sample.outward_derivative = out.x() * sample.jet.du + out.y() * sample.jet.dv;
  return sample;
}

}  // namespace spline::fill_detail
