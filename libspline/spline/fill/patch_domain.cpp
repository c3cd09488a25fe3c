#include "spline/fill/patch_domain.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "ricci/mesh/errors.h"
#include "ricci/util/cross2d.h"

namespace spline::fill_detail {
namespace {

double orientation(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return ricci::cross2d(b - a, c - a);
}

// Polar angles of a closed ring around `center`, unwrapped to increase from about `start`.
std::vector<double> unwrapped_angles(const std::vector<Eigen::Vector2d>& points,
                                     const std::vector<int>& ring, int first,
                                     const Eigen::Vector2d& center, double start) {
  const int n = static_cast<int>(ring.size());
  std::vector<double> angles(n + 1);
  double previous = start;
  for (int k = 0; k <= n; ++k) {
    const Eigen::Vector2d d = points[ring[(first + k) % n]] - center;
    double angle = std::atan2(d.y(), d.x());
    while (angle < previous - M_PI) angle += 2.0 * M_PI;
    while (angle > previous + M_PI) angle -= 2.0 * M_PI;
    angles[k] = angle;
    previous = angle;
  }
  return angles;
}

// Triangulates the strip between two closed counter-clockwise rings (outer a, inner b, both
// star-shaped from `center`) given as vertex ids into `points`: walk both rings once in step by
// polar angle (advance the ring whose next point comes first), taking the other diagonal when
// the preferred triangle would not be counter-clockwise.
void stitch(const std::vector<Eigen::Vector2d>& points, const Eigen::Vector2d& center,
            const std::vector<int>& a, const std::vector<int>& b,
            std::vector<Eigen::Vector3i>& triangles) {
  const int na = static_cast<int>(a.size()), nb = static_cast<int>(b.size());
  // Start the inner ring at its point nearest to a[0].
  int j0 = 0;
  for (int j = 1; j < nb; ++j) {
    if ((points[b[j]] - points[a[0]]).squaredNorm() <
        (points[b[j0]] - points[a[0]]).squaredNorm()) {
      j0 = j;
    }
  }
  const Eigen::Vector2d d0 = points[a[0]] - center;
  const double start = std::atan2(d0.y(), d0.x());
  const auto angle_a = unwrapped_angles(points, a, 0, center, start);
  const auto angle_b = unwrapped_angles(points, b, j0, center, start);
  auto A = [&](int i) { return a[i % na]; };
  auto B = [&](int j) { return b[(j0 + j) % nb]; };
  int i = 0, j = 0;
  while (i < na || j < nb) {
    const double tiny = 1e-12 * (points[A(i)] - points[B(j)]).squaredNorm();
    const bool valid_a = i < na && orientation(points[A(i)], points[A(i + 1)], points[B(j)]) > tiny;
    const bool valid_b = j < nb && orientation(points[A(i)], points[B(j + 1)], points[B(j)]) > tiny;
    bool advance_a;
    if (i >= na) {
      advance_a = false;
    } else if (j >= nb) {
      advance_a = true;
    } else if (valid_a && valid_b) {
      advance_a = angle_a[i + 1] <= angle_b[j + 1];
    } else {
      advance_a = valid_a;
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

PlanarTriangulation triangle_grid(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi,
                                  double spacing) {
  const double row_height = 0.5 * std::sqrt(3.0) * spacing;
  const int columns = static_cast<int>(std::ceil((hi.x() - lo.x()) / spacing)) + 2;
  const int rows = static_cast<int>(std::ceil((hi.y() - lo.y()) / row_height)) + 1;
  if (columns * static_cast<double>(rows) > 4e6) {
    throw ricci::InvalidInputError("hole fill: a patch grid of " + std::to_string(columns) + " x " +
                                   std::to_string(rows) + " vertices is too large");
  }
  PlanarTriangulation t;
  auto id = [&](int i, int r) { return r * (columns + 1) + i; };
  // A seeded jitter of 0.08 sides moves the vertices off the lattice: the knot-cloud rule turns
  // each cloud away from its vertex's edge directions, and on an exact lattice those directions
  // tie, so rounding (a translated or scaled hole) would pick other clouds and another patch.
  std::uint64_t state = 0x9e3779b97f4a7c15ull;
  auto jitter = [&state]() {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(state >> 11) / 9007199254740992.0 - 0.5;  // in [-0.5, 0.5)
  };
  for (int r = 0; r <= rows; ++r) {
    const double shift = (r % 2) ? 0.5 : 0.0;
    for (int i = 0; i <= columns; ++i) {
      const double x = -1.0 + shift + i + 0.16 * jitter();
      const double y = (r + 0.16 * jitter() / std::sqrt(3.0) * 2.0) * 0.5 * std::sqrt(3.0);
      t.positions.emplace_back(lo.x() + spacing * x, lo.y() + spacing * y);
    }
  }
  for (int r = 0; r < rows; ++r) {
    for (int i = 0; i < columns; ++i) {
      if (r % 2 == 0) {  // this row unshifted, the next shifted right by half a side
        t.triangles.emplace_back(id(i, r), id(i + 1, r), id(i, r + 1));
        t.triangles.emplace_back(id(i + 1, r), id(i + 1, r + 1), id(i, r + 1));
      } else {
        t.triangles.emplace_back(id(i, r), id(i + 1, r + 1), id(i, r + 1));
        t.triangles.emplace_back(id(i, r), id(i + 1, r), id(i + 1, r + 1));
      }
    }
  }
  return t;
}

PolygonRegion::PolygonRegion(const std::vector<Eigen::Vector2d>& polygon, double cell)
    : points_(polygon), cell_(cell) {
  Eigen::Vector2d hi = polygon[0];
  lo_ = polygon[0];
  for (const auto& p : polygon) {
    lo_ = lo_.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  columns_ = static_cast<int>((hi.x() - lo_.x()) / cell_) + 1;
  rows_ = static_cast<int>((hi.y() - lo_.y()) / cell_) + 1;
  strips_.resize(static_cast<std::size_t>(rows_));
  cells_.resize(static_cast<std::size_t>(rows_) * columns_);
  const int n = static_cast<int>(points_.size());
  auto column = [&](double x) {
    return std::clamp(static_cast<int>((x - lo_.x()) / cell_), 0, columns_ - 1);
  };
  auto row = [&](double y) {
    return std::clamp(static_cast<int>((y - lo_.y()) / cell_), 0, rows_ - 1);
  };
  for (int e = 0; e < n; ++e) {
    const Eigen::Vector2d a = points_[e], b = points_[(e + 1) % n];
    const int r0 = row(std::min(a.y(), b.y())), r1 = row(std::max(a.y(), b.y()));
    const int c0 = column(std::min(a.x(), b.x())), c1 = column(std::max(a.x(), b.x()));
    for (int r = r0; r <= r1; ++r) {
      strips_[static_cast<std::size_t>(r)].push_back(e);
      for (int c = c0; c <= c1; ++c)
        cells_[static_cast<std::size_t>(r) * columns_ + c].push_back(e);
    }
  }
}

bool PolygonRegion::contains(const Eigen::Vector2d& p) const {
  const double y = (p.y() - lo_.y()) / cell_;
  if (!(y >= 0.0) || y >= rows_) return false;
  const int n = static_cast<int>(points_.size());
  bool inside = false;
  for (int e : strips_[static_cast<std::size_t>(y)]) {
    const Eigen::Vector2d& a = points_[e];
    const Eigen::Vector2d& b = points_[(e + 1) % n];
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < a.x() + (p.y() - a.y()) / (b.y() - a.y()) * (b.x() - a.x()))
      inside = !inside;
  }
  return inside;
}

double PolygonRegion::edge_distance(int e, const Eigen::Vector2d& p) const {
  const Eigen::Vector2d& a = points_[e];
  const Eigen::Vector2d& b = points_[(e + 1) % points_.size()];
  const Eigen::Vector2d d = b - a;
  const double length = d.squaredNorm();
  const double s = length > 0.0 ? std::clamp((p - a).dot(d) / length, 0.0, 1.0) : 0.0;
  return (a + s * d - p).norm();
}

double PolygonRegion::distance(const Eigen::Vector2d& p, double limit) const {
  // The cells within `limit` of p: an edge nearer than limit has a point in one of them.
  const int c0 = static_cast<int>(std::floor((p.x() - limit - lo_.x()) / cell_));
  const int c1 = static_cast<int>(std::floor((p.x() + limit - lo_.x()) / cell_));
  const int r0 = static_cast<int>(std::floor((p.y() - limit - lo_.y()) / cell_));
  const int r1 = static_cast<int>(std::floor((p.y() + limit - lo_.y()) / cell_));
  double best = limit;
  for (int r = std::max(r0, 0); r <= std::min(r1, rows_ - 1); ++r) {
    for (int c = std::max(c0, 0); c <= std::min(c1, columns_ - 1); ++c) {
      for (int e : cells_[static_cast<std::size_t>(r) * columns_ + c])
        best = std::min(best, edge_distance(e, p));
    }
  }
  return best;
}

bool is_simple(const std::vector<Eigen::Vector2d>& polygon) {
  const int m = static_cast<int>(polygon.size());
  auto side = [](const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& r) {
    const double v = orientation(p, q, r);
    return (v > 0) - (v < 0);
  };
  for (int i = 0; i < m; ++i) {
    const Eigen::Vector2d a = polygon[i], b = polygon[(i + 1) % m];
    for (int j = i + 2; j < m; ++j) {
      if (i == 0 && j == m - 1) continue;  // adjacent through the wrap
      const Eigen::Vector2d c = polygon[j], d = polygon[(j + 1) % m];
      if (std::max(a.x(), b.x()) < std::min(c.x(), d.x()) ||
          std::max(c.x(), d.x()) < std::min(a.x(), b.x()) ||
          std::max(a.y(), b.y()) < std::min(c.y(), d.y()) ||
          std::max(c.y(), d.y()) < std::min(a.y(), b.y())) {
        continue;
      }
      if (side(a, b, c) * side(a, b, d) <= 0 && side(c, d, a) * side(c, d, b) <= 0) return false;
    }
  }
  return true;
}

double star_margin(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& c) {
  double worst = INFINITY;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Eigen::Vector2d a = polygon[i] - c, b = polygon[(i + 1) % polygon.size()] - c;
    worst = std::min(worst, ricci::cross2d(a, b) / (a.norm() * b.norm() + 1e-300));
  }
  return worst;
}

bool star_center(const std::vector<Eigen::Vector2d>& polygon, Eigen::Vector2d& center) {
  std::vector<Eigen::Vector2d> candidates;
  const double area = polygon_area(polygon);
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero(), mean = Eigen::Vector2d::Zero();
  Eigen::Vector2d lo = polygon[0], hi = polygon[0];
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Eigen::Vector2d a = polygon[i], b = polygon[(i + 1) % polygon.size()];
    centroid += (a + b) * ricci::cross2d(a, b);
    mean += a;
    lo = lo.cwiseMin(a);
    hi = hi.cwiseMax(a);
  }
  candidates.push_back(centroid / (6.0 * area));
  candidates.push_back(mean / static_cast<double>(polygon.size()));
  const int n = 12;
  for (int i = 1; i < n; ++i) {
    for (int j = 1; j < n; ++j)
      candidates.emplace_back(lo.x() + (hi.x() - lo.x()) * i / n,
                              lo.y() + (hi.y() - lo.y()) * j / n);
  }
  double best = 0.0;
  bool found = false;
  for (const auto& c : candidates) {
    // The centroid and mean win ties (they come first): a centre well inside gives rounder rings.
    const double margin = star_margin(polygon, c);
    if (margin > best * (found ? 2.0 : 1.0)) {
      best = margin;
      center = c;
      found = true;
    }
  }
  return found;
}

Eigen::Vector2d polygon_mean(const std::vector<Eigen::Vector2d>& polygon) {
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  for (const auto& p : polygon) sum += p;
  return sum / static_cast<double>(std::max<std::size_t>(polygon.size(), 1));
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
    sum += ricci::cross2d(polygon[i], polygon[(i + 1) % polygon.size()]);
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
    stitch(t.positions, center, ring, inner, t.triangles);
    ring = std::move(inner);
  }
  const int c = static_cast<int>(t.positions.size());
  t.positions.push_back(center);
  for (std::size_t i = 0; i < ring.size(); ++i)
    t.triangles.emplace_back(ring[i], ring[(i + 1) % ring.size()], c);
  return t;
}

RimChartEdge rim_chart_edge(const ManifoldSplineSpace& space, const RimEdge& edge) {
  RimChartEdge out;
  out.chart = space.chart_of(edge.face);
  const Eigen::Matrix<double, 3, 2> corners = space.atlas().face_positions(out.chart, edge.face);
  out.start = corners.row(rim_edge_start_corner(edge)).transpose();
  out.end = corners.row(rim_edge_end_corner(edge)).transpose();
  const Eigen::Vector2d opposite = corners.row(edge.corner).transpose();
  out.tie.direction = (opposite - 0.5 * (out.start + out.end)).normalized();
  return out;
}

RimSample sample_rim(const ManifoldSpline& spline, const RimEdge& edge, double t) {
  const RimChartEdge in_chart = rim_chart_edge(*spline.space, edge);
  RimSample sample;
  sample.jet = spline.evaluate({edge.face, rim_edge_barycentric(edge, t)}, in_chart.chart,
                               in_chart.tie);
  const Eigen::Vector2d e = in_chart.end - in_chart.start;
  sample.chart_length = e.norm();
  const Eigen::Vector2d out = Eigen::Vector2d(e.y(), -e.x()) / sample.chart_length;
  sample.outward_derivative = out.x() * sample.jet.du + out.y() * sample.jet.dv;
  sample.along_derivative = e.x() * sample.jet.du + e.y() * sample.jet.dv;
  return sample;
}

std::vector<double> rim_edge_parameters(int per_edge) {
  const double step = 1.0 / per_edge;
  const double fine = step / kRimEndRefinement;
  std::vector<double> t;
  for (int i = 0; i <= per_edge; ++i) t.push_back(static_cast<double>(i) * step);
  const int near_end = std::min(kRimEndIntervals, per_edge) * kRimEndRefinement;
  for (int i = 1; i < near_end; ++i) {
    if (i % kRimEndRefinement == 0) continue;  // on the uniform grid already
    t.push_back(static_cast<double>(i) * fine);
    t.push_back(1.0 - static_cast<double>(i) * fine);
  }
  for (int k = 1; k <= kRimEndSamples; ++k) {
    t.push_back(std::ldexp(fine, -k));
    t.push_back(1.0 - std::ldexp(fine, -k));
  }
  std::sort(t.begin(), t.end());
  t.erase(std::unique(t.begin(), t.end()), t.end());
  return t;
}

}  // namespace spline::fill_detail
