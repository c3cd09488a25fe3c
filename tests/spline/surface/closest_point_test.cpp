// Global closest point on a fitted surface with its cone patch: never farther than any vertex of
// a fine tessellation, the residual normal to the surface, surface points found at distance 0.
#include "spline/surface/closest_point.h"

#include <gtest/gtest.h>

#include <limits>
#include <random>

#include "ricci/mesh/errors.h"
#include "spline/tessellate/tessellate.h"
#include "spline/tessellate/tessellate_fill.h"
#include "surface_fixtures.h"

namespace spline {
namespace {

using testing::small_surface;

// Welded tessellation of the spline and its fills at density d.
Tessellation fine_tessellation(const SplineSurface& s, int d) {
  TessellationOptions options;
  options.density = d;
  options.skip_faces = s.skipped_faces;
  Tessellation t = tessellate(s.spline, s.domain, options);
  for (std::size_t i = 0; i < s.fills.size(); ++i) {
    append_fill(t, s.fills[i], tessellate_fill(s.fills[i], d), static_cast<int>(i));
  }
  return t;
}

TEST(ClosestPoint, GlobalOnAFittedGenus2Surface) {
  const SplineSurface& s = small_surface("genus2.off");
  const Tessellation t = fine_tessellation(s, 12);
  const double diagonal =
      (t.positions.colwise().maxCoeff() - t.positions.colwise().minCoeff()).norm();
  const ClosestPointIndex index(s);
  std::mt19937 rng(11);
  std::uniform_int_distribution<Eigen::Index> pick(0, t.positions.rows() - 1);
  std::normal_distribution<double> gauss(0.0, 1.0);
  Eigen::MatrixX3d targets(200, 3);
  for (Eigen::Index i = 0; i < targets.rows(); ++i) {
    const Eigen::Vector3d offset(gauss(rng), gauss(rng), gauss(rng));
    // Near the surface, and some far (a tenth of the targets a diagonal away).
    const double size = i % 10 == 0 ? 0.5 : 0.03;
    targets.row(i) = t.positions.row(pick(rng)) + size * diagonal * offset.transpose();
  }
  const std::vector<ClosestPoint> found = index.find_all(targets);
  int on_fill = 0, interior = 0;
  for (Eigen::Index i = 0; i < targets.rows(); ++i) {
    const Eigen::Vector3d q = targets.row(i).transpose();
    const ClosestPoint& c = found[static_cast<std::size_t>(i)];
    const double vertex_distance =
        (t.positions.rowwise() - q.transpose()).rowwise().norm().minCoeff();
    EXPECT_LE(c.distance, vertex_distance + 1e-12 * diagonal)
        << "target " << i << " candidates " << c.candidates << " fill " << c.location.fill
        << " face " << c.location.point.face;
    const SurfaceDifferential e = evaluate_surface(s, c.location);
    EXPECT_NEAR((e.position - c.position).norm(), 0.0, 1e-12 * diagonal);
    EXPECT_NEAR((q - c.position).norm(), c.distance, 1e-12 * diagonal);
    if (c.location.fill >= 0) ++on_fill;
    // The residual is normal to the surface where the foot point is inside a face or patch.
    bool inside = c.location.point.barycentric.minCoeff() > 1e-9;
    if (c.location.fill >= 0) {
      const HoleFill& fill = s.fills[static_cast<std::size_t>(c.location.fill)];
      const double step = 1e-6 * (fill.corners[0] - fill.center).norm();
      inside = true;
      for (const Eigen::Vector2d& d : {Eigen::Vector2d(step, 0.0), Eigen::Vector2d(-step, 0.0),
                                       Eigen::Vector2d(0.0, step), Eigen::Vector2d(0.0, -step)}) {
        inside = inside && in_fill_domain(fill, c.location.fill_parameter + d, 0.0);
      }
    }
    if (!inside || c.distance < 1e-9 * diagonal) continue;
    ++interior;
    const Eigen::Vector3d r = (q - c.position) / c.distance;
    EXPECT_LT(std::abs(r.dot(e.du.normalized())), 1e-7) << "target " << i;
    EXPECT_LT(std::abs(r.dot(e.dv.normalized())), 1e-7) << "target " << i;
  }
  EXPECT_GT(interior, 150);
  RecordProperty("on_fill", on_fill);
}

TEST(ClosestPoint, FindsSurfacePointsAtDistanceZero) {
  const SplineSurface& s = small_surface("genus2.off");
  const ClosestPointIndex index(s);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.05, 1.0);
  int checked = 0;
  double scale = 0.0;
  for (int f : s.spline.space->domain_faces()) {
    if (s.skipped_faces[f]) continue;
    const Eigen::Vector3d centre = Eigen::Vector3d::Constant(1.0 / 3.0);
    scale = std::max(scale, s.spline.evaluate({f, centre}).position.norm());
  }
  for (int f : s.spline.space->domain_faces()) {
    if (s.skipped_faces[f] || f % 7 != 0) continue;
    Eigen::Vector3d b(u(rng), u(rng), u(rng));
    const Eigen::Vector3d p = s.spline.evaluate({f, b / b.sum()}).position;
    const ClosestPoint c = index.find(p);
    EXPECT_LT(c.distance, 1e-9 * scale) << "face " << f;
    ++checked;
  }
  ASSERT_FALSE(s.fills.empty());
  const Eigen::Vector3d p = s.fills[0].evaluate(s.fills[0].center).position;
  const ClosestPoint c = index.find(p);
  EXPECT_LT(c.distance, 1e-9 * scale);
  EXPECT_EQ(c.location.fill, 0);
  EXPECT_GT(checked, 20);
}

TEST(ClosestPoint, BadInputThrows) {
  const SplineSurface& s = small_surface("genus2.off");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW((void)closest_point(s, Eigen::Vector3d(nan, 0, 0)), ricci::InvalidInputError);
  ClosestPointOptions options;
  options.density = 0;
  EXPECT_THROW((void)ClosestPointIndex(s, options), ricci::InvalidInputError);
}

}  // namespace
}  // namespace spline
