#include "spline/surface/evaluate.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "ricci/mesh/errors.h"
#include "spline/tessellate/parallel_for.h"

namespace spline {
namespace {

using ricci::InvalidInputError;

// Distance from u to the segment a-b.
double segment_distance(const Eigen::Vector2d& u, const Eigen::Vector2d& a,
                        const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((u - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + t * ab - u).norm();
}

// The validated barycentric coordinates of `point` on the surface (divided by their sum).
Eigen::Vector3d checked_barycentric(const SplineSurface& surface, const DomainPoint& point) {
  const ManifoldSplineSpace& space = *surface.spline.space;
  const std::string where = "surface evaluation: face " + std::to_string(point.face);
  if (point.face < 0 || point.face >= space.face_count()) {
    throw InvalidInputError(where + " is out of range (the domain has " +
                            std::to_string(space.face_count()) + " faces)");
  }
  if (!space.in_domain(point.face)) {
    throw InvalidInputError(where + " is outside the spline's domain (the cone's hole)");
  }
  if (!surface.skipped_faces.empty() && surface.skipped_faces[point.face] != 0) {
    throw InvalidInputError(where + " is skipped (a fill patch covers it)");
  }
  const Eigen::Vector3d& b = point.barycentric;
  if (!b.allFinite()) throw InvalidInputError(where + ": non-finite barycentric coordinates");
  constexpr double kTolerance = 1e-6;
  if (b.minCoeff() < -kTolerance || std::abs(b.sum() - 1.0) > kTolerance) {
    throw InvalidInputError(where + ": barycentric coordinates must be >= 0 and sum to 1");
  }
  return b / b.sum();
}

}  // namespace

Curvatures curvatures(const Eigen::Vector3d& du, const Eigen::Vector3d& dv,
                      const Eigen::Vector3d& duu, const Eigen::Vector3d& duv,
                      const Eigen::Vector3d& dvv) {
  Curvatures c;
  const Eigen::Vector3d cross = du.cross(dv);
  const double area = cross.norm();
  if (!(area > 0.0)) return c;
  const Eigen::Vector3d n = cross / area;
  const double e = du.dot(du), f = du.dot(dv), g = dv.dot(dv);
  const double l = duu.dot(n), m = duv.dot(n), nn = dvv.dot(n);
  const double det = e * g - f * f;  // = area^2, computed from the forms for consistency
  c.gaussian = (l * nn - m * m) / det;
  c.mean = (e * nn - 2.0 * f * m + g * l) / (2.0 * det);
  const double root = std::sqrt(std::max(0.0, c.mean * c.mean - c.gaussian));
  c.k1 = c.mean + root;
  c.k2 = c.mean - root;
  return c;
}

bool in_fill_domain(const HoleFill& fill, const Eigen::Vector2d& u, double tolerance) {
  if (!u.allFinite()) return false;
  std::vector<Eigen::Vector2d> polygon;
  for (const auto& edge : fill.boundary_points) {
    for (std::size_t i = 0; i + 1 < edge.size(); ++i) polygon.push_back(edge[i]);
  }
  if (polygon.size() < 3) return false;
  Eigen::Vector2d lo = polygon[0], hi = polygon[0];
  for (const auto& p : polygon) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double slack = tolerance * (hi - lo).norm();
  bool inside = false;
  double nearest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    const Eigen::Vector2d& a = polygon[i];
    const Eigen::Vector2d& b = polygon[j];
    if ((a.y() > u.y()) != (b.y() > u.y()) &&
        u.x() < (b.x() - a.x()) * (u.y() - a.y()) / (b.y() - a.y()) + a.x()) {
      inside = !inside;
    }
    nearest = std::min(nearest, segment_distance(u, a, b));
  }
  return inside || nearest <= slack;
}

SurfaceDifferential evaluate_surface(const SplineSurface& surface, const DomainPoint& point) {
  SurfaceDifferential d;
  d.location.point = {point.face, checked_barycentric(surface, point)};
  const SurfaceJet jet = surface.spline.evaluate(d.location.point);
  d.chart = jet.chart;
  d.position = jet.position;
  d.du = jet.du;
  d.dv = jet.dv;
  d.duu = jet.duu;
  d.duv = jet.duv;
  d.dvv = jet.dvv;
  d.normal = jet.normal;
  d.curvature = curvatures(d.du, d.dv, d.duu, d.duv, d.dvv);
  return d;
}

SurfaceDifferential evaluate_surface(const SplineSurface& surface,
                                     const SurfaceLocation& location) {
  if (location.fill < 0) return evaluate_surface(surface, location.point);
  if (location.fill >= static_cast<int>(surface.fills.size())) {
    throw InvalidInputError("surface evaluation: fill " + std::to_string(location.fill) +
                            " is out of range (the surface has " +
                            std::to_string(surface.fills.size()) + " fills)");
  }
  const HoleFill& fill = surface.fills[static_cast<std::size_t>(location.fill)];
  const Eigen::Vector2d& u = location.fill_parameter;
  if (!in_fill_domain(fill, u)) {
    throw InvalidInputError("surface evaluation: parameter point of fill " +
                            std::to_string(location.fill) + " is not finite or outside its domain");
  }
  const SplineJet jet = fill.jet(u);
  SurfaceDifferential d;
  d.location.fill = location.fill;
  d.location.fill_parameter = u;
  d.position = jet.value;
  d.du = jet.gradient.col(0);
  d.dv = jet.gradient.col(1);
  d.duu = jet.hessian.col(0);
  d.duv = jet.hessian.col(1);
  d.dvv = jet.hessian.col(2);
  const Eigen::Vector3d n = d.du.cross(d.dv);
  if (n.norm() > 0.0) d.normal = n.normalized();
  d.curvature = curvatures(d.du, d.dv, d.duu, d.duv, d.dvv);
  return d;
}

std::vector<SurfaceDifferential> evaluate_surface(const SplineSurface& surface,
                                                  const std::vector<DomainPoint>& points,
                                                  int threads) {
  std::vector<SurfaceDifferential> out(points.size());
  parallel_for(points.size(), threads,
               [&](std::size_t i) { out[i] = evaluate_surface(surface, points[i]); });
  return out;
}

}  // namespace spline
