#include "spline/knots/dms_conditions.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "ricci/mesh/errors.h"
#include "ricci/util/cross2d.h"
#include "spline/basis/multi_index.h"
#include "spline/basis/orientation.h"

namespace spline {
namespace {

double signed_double_area(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                          const Eigen::Vector2d& c) {
  return ricci::cross2d(b - a, c - a);
}

// Sutherland-Hodgman: the part of the convex polygon left of the directed line a -> b.
std::vector<Eigen::Vector2d> clip(const std::vector<Eigen::Vector2d>& polygon,
                                  const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  std::vector<Eigen::Vector2d> out;
  const Eigen::Vector2d e = b - a;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Eigen::Vector2d& p = polygon[i];
    const Eigen::Vector2d& q = polygon[(i + 1) % polygon.size()];
    const double sp = ricci::cross2d(e, p - a), sq = ricci::cross2d(e, q - a);
    if (sp >= 0.0) out.push_back(p);
    if ((sp > 0.0 && sq < 0.0) || (sp < 0.0 && sq > 0.0)) out.push_back(p + (sp / (sp - sq)) * (q - p));
  }
  return out;
}

double polygon_area(const std::vector<Eigen::Vector2d>& polygon) {
  double twice = 0.0;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    twice += ricci::cross2d(polygon[i], polygon[(i + 1) % polygon.size()]);
  }
  return 0.5 * twice;
}

// Smallest |det| / diameter^2 over triples of the knot set.
double general_position(const std::vector<Eigen::Vector2d>& set) {
  double diameter2 = 0.0;
  for (std::size_t i = 0; i < set.size(); ++i) {
    for (std::size_t j = i + 1; j < set.size(); ++j) {
      diameter2 = std::max(diameter2, (set[j] - set[i]).squaredNorm());
    }
  }
  double smallest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < set.size(); ++i) {
    for (std::size_t j = i + 1; j < set.size(); ++j) {
      for (std::size_t k = j + 1; k < set.size(); ++k) {
        if (orient2d(set[i], set[j], set[k]) == 0) return 0.0;
        smallest = std::min(smallest, std::abs(signed_double_area(set[i], set[j], set[k])));
      }
    }
  }
  return smallest / diameter2;
}

}  // namespace

DmsConditionReport check_dms_conditions(const PlanarTriangulation& triangulation,
                                        const std::vector<KnotCloud>& clouds) {
  validate(triangulation);
  if (clouds.size() != triangulation.positions.size()) {
    throw ricci::InvalidInputError("DMS conditions: " + std::to_string(clouds.size()) +
                                   " clouds for " + std::to_string(triangulation.positions.size()) +
                                   " vertices");
  }
  DmsConditionReport report;
  if (clouds.empty()) return report;
  const int n = clouds[0].degree();
  for (const KnotCloud& c : clouds) {
    if (c.degree() != n || n < 1) {
      throw ricci::InvalidInputError("DMS conditions: knot clouds of unequal degrees");
    }
  }
  for (std::size_t t = 0; t < triangulation.triangles.size(); ++t) {
    const Eigen::Vector3i& tri = triangulation.triangles[t];
    const KnotCloud* c[3] = {&clouds[static_cast<std::size_t>(tri[0])],
                             &clouds[static_cast<std::size_t>(tri[1])],
                             &clouds[static_cast<std::size_t>(tri[2])]};
    const double reference = signed_double_area(c[0]->knots[0], c[1]->knots[0], c[2]->knots[0]);
    std::vector<Eigen::Vector2d> region = {c[0]->knots[0], c[1]->knots[0], c[2]->knots[0]};
    bool ok = true;
    for (int degree = 0; degree <= n; ++degree) {
      for (const Eigen::Vector3i& beta : multi_indices(degree)) {
        const Eigen::Vector2d& a = c[0]->knots[static_cast<std::size_t>(beta[0])];
        const Eigen::Vector2d& b = c[1]->knots[static_cast<std::size_t>(beta[1])];
        const Eigen::Vector2d& d = c[2]->knots[static_cast<std::size_t>(beta[2])];
        report.min_orientation_ratio =
            std::min(report.min_orientation_ratio, signed_double_area(a, b, d) / reference);
        if (orient2d(a, b, d) <= 0) {
          ok = false;
          continue;
        }
        region = clip(clip(clip(region, a, b), b, d), d, a);
      }
    }
    const double region_ratio = region.size() < 3 ? 0.0 : polygon_area(region) / (0.5 * reference);
    report.min_knot_region_ratio = std::min(report.min_knot_region_ratio, region_ratio);
    if (!(region_ratio > 0.0)) ok = false;
    for (const Eigen::Vector3i& beta : multi_indices(n)) {
      std::vector<Eigen::Vector2d> set;
      for (int v = 0; v < 3; ++v) {
        for (int j = 0; j <= beta[v]; ++j) set.push_back(c[v]->knots[static_cast<std::size_t>(j)]);
      }
      report.min_general_position = std::min(report.min_general_position, general_position(set));
    }
    if (!ok) {
      report.satisfied = false;
      report.failing_triangles.push_back(static_cast<int>(t));
    }
  }
  return report;
}

}  // namespace spline
