// Surface evaluation: curvatures of a reproduced quadric in closed form, agreement with the
// spline's own evaluation, fill patches, bad input.
#include "spline/surface/evaluate.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <random>

#include "ricci/mesh/errors.h"
#include "surface_fixtures.h"

namespace spline {
namespace {

using testing::small_surface;

// A point of `face` drawn at random (inside, away from the edges).
DomainPoint random_point(int face, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.05, 1.0);
  Eigen::Vector3d b(u(rng), u(rng), u(rng));
  return {face, b / b.sum()};
}

TEST(SurfaceEvaluate, CurvatureOfAReproducedParaboloidIsExact) {
  const SplineSurface& fitted = small_surface("genus2.off");
  const ManifoldSplineSpace& space = *fitted.spline.space;
  // The chart evaluating the most faces, and the quadric graph (x, y, h) over it.
  std::map<int, int> count;
  for (int f : space.domain_faces()) ++count[space.chart_of(f)];
  int chart = count.begin()->first;
  for (const auto& [c, k] : count)
    if (k > count[chart]) chart = c;
  int face0 = -1;
  for (int f : space.domain_faces())
    if (space.chart_of(f) == chart) face0 = f;
  const auto corners = space.atlas().face_positions(chart, face0);
  const double s = (corners.row(1) - corners.row(0)).norm() * 4.0;
  const Eigen::Vector2d o = corners.colwise().mean().transpose();
  const double a = 0.7, b = -0.3, c = 0.4, d = 0.2;  // h = a X^2 + b Y^2 + c X Y + d X
  BivariatePolynomial p;
  p.degree = 2;
  p.origin = o;
  p.scale = s;
  p.coefficients = Eigen::MatrixXd::Zero(monomial_count(2), 3);
  p.coefficients(monomial_index(0, 0), 0) = o.x();
  p.coefficients(monomial_index(1, 0), 0) = s;
  p.coefficients(monomial_index(0, 0), 1) = o.y();
  p.coefficients(monomial_index(0, 1), 1) = s;
  p.coefficients(monomial_index(2, 0), 2) = a;
  p.coefficients(monomial_index(0, 2), 2) = b;
  p.coefficients(monomial_index(1, 1), 2) = c;
  p.coefficients(monomial_index(1, 0), 2) = d;
  SplineSurface quadric;
  quadric.spline = {fitted.spline.space, space.control_points_of(p, chart)};
  std::mt19937 rng(7);
  int checked = 0;
  for (int f : space.domain_faces()) {
    if (space.chart_of(f) != chart) continue;
    const DomainPoint point = random_point(f, rng);
    if (!is_partition_of_unity(space.evaluate_basis(point))) continue;  // next to the hole
    const SurfaceDifferential e = evaluate_surface(quadric, point);
    ASSERT_EQ(e.chart, chart);
    const double x = (e.position.x() - o.x()) / s, y = (e.position.y() - o.y()) / s;
    const double hx = (2 * a * x + c * y + d) / s, hy = (2 * b * y + c * x) / s;
    const double hxx = 2 * a / (s * s), hyy = 2 * b / (s * s), hxy = c / (s * s);
    const double w2 = 1.0 + hx * hx + hy * hy;
    const double k = (hxx * hyy - hxy * hxy) / (w2 * w2);
    const double h =
        ((1 + hx * hx) * hyy - 2 * hx * hy * hxy + (1 + hy * hy) * hxx) / (2 * std::pow(w2, 1.5));
    const double scale = 1.0 / (s * s);
    EXPECT_NEAR(e.position.z(), a * x * x + b * y * y + c * x * y + d * x, 1e-10);
    EXPECT_NEAR(e.curvature.gaussian, k, 1e-8 * scale);
    EXPECT_NEAR(e.curvature.mean, h, 1e-8 * std::sqrt(scale));
    EXPECT_NEAR(e.curvature.k1 + e.curvature.k2, 2 * h, 1e-8 * std::sqrt(scale));
    EXPECT_NEAR(e.curvature.k1 * e.curvature.k2, k, 1e-8 * scale);
    EXPECT_GE(e.curvature.k1, e.curvature.k2);
    EXPECT_NEAR(e.normal.dot(Eigen::Vector3d(-hx, -hy, 1.0).normalized()), 1.0, 1e-10);
    ++checked;
  }
  EXPECT_GT(checked, 20);
}

TEST(SurfaceEvaluate, CurvaturesOfASphereFollowTheConvention) {
  // F(u, v) = R (cos u cos v, sin u cos v, sin v): F_u x F_v points outwards, so K = 1 / R^2
  // and H = -1 / R; with u and v swapped the normal points inwards and H = +1 / R.
  const double r = 2.0, u = 0.3, v = 0.4;
  const Eigen::Vector3d fu(-std::sin(u) * std::cos(v), std::cos(u) * std::cos(v), 0.0);
  const Eigen::Vector3d fv(-std::cos(u) * std::sin(v), -std::sin(u) * std::sin(v), std::cos(v));
  const Eigen::Vector3d fuu(-std::cos(u) * std::cos(v), -std::sin(u) * std::cos(v), 0.0);
  const Eigen::Vector3d fuv(std::sin(u) * std::sin(v), -std::cos(u) * std::sin(v), 0.0);
  const Eigen::Vector3d fvv(-std::cos(u) * std::cos(v), -std::sin(u) * std::cos(v),
                            -std::sin(v));
  const Eigen::Vector3d position(std::cos(u) * std::cos(v), std::sin(u) * std::cos(v),
                                 std::sin(v));
  ASSERT_GT(fu.cross(fv).dot(position), 0.0);  // outwards
  const Curvatures outward = curvatures(r * fu, r * fv, r * fuu, r * fuv, r * fvv);
  EXPECT_NEAR(outward.gaussian, 1.0 / (r * r), 1e-14);
  EXPECT_NEAR(outward.mean, -1.0 / r, 1e-14);
  EXPECT_NEAR(outward.k1, -1.0 / r, 1e-7);
  EXPECT_NEAR(outward.k2, -1.0 / r, 1e-7);
  const Curvatures inward = curvatures(r * fv, r * fu, r * fvv, r * fuv, r * fuu);
  EXPECT_NEAR(inward.gaussian, 1.0 / (r * r), 1e-14);
  EXPECT_NEAR(inward.mean, 1.0 / r, 1e-14);
}

TEST(SurfaceEvaluate, MatchesTheSplinesOwnEvaluationAndTheBatch) {
  const SplineSurface& s = small_surface("genus2.off");
  std::mt19937 rng(3);
  std::vector<DomainPoint> points;
  for (int f : s.spline.space->domain_faces()) {
    if (s.skipped_faces[f] == 0) points.push_back(random_point(f, rng));
  }
  const std::vector<SurfaceDifferential> batch = evaluate_surface(s, points, 2);
  ASSERT_EQ(batch.size(), points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const SurfaceDifferential& e = batch[i];
    // The coordinates divided by their sum (a rounding step away from points[i]).
    EXPECT_LT((e.location.point.barycentric - points[i].barycentric).norm(), 1e-15);
    const SurfaceJet jet = s.spline.evaluate(e.location.point);
    EXPECT_EQ(e.position, jet.position);
    EXPECT_EQ(e.du, jet.du);
    EXPECT_EQ(e.dvv, jet.dvv);
    EXPECT_EQ(e.normal, jet.normal);
    EXPECT_EQ(e.chart, jet.chart);
    EXPECT_EQ(e.location.point.face, points[i].face);
    EXPECT_TRUE(std::isfinite(e.curvature.gaussian) && std::isfinite(e.curvature.mean));
    const SurfaceDifferential one = evaluate_surface(s, points[i]);
    EXPECT_EQ(one.position, e.position);
    EXPECT_EQ(one.curvature.mean, e.curvature.mean);
  }
}

TEST(SurfaceEvaluate, FillPatchesEvaluateInTheirDomain) {
  const SplineSurface& s = small_surface("genus2.off");
  ASSERT_FALSE(s.fills.empty());
  const HoleFill& fill = s.fills[0];
  SurfaceLocation at;
  at.fill = 0;
  at.fill_parameter = fill.center;
  const SurfaceDifferential e = evaluate_surface(s, at);
  const PatchPoint p = fill.evaluate(fill.center);
  EXPECT_EQ(e.position, p.position);
  EXPECT_NEAR(e.normal.dot(p.normal), 1.0, 1e-12);
  EXPECT_EQ(e.chart, -1);
  EXPECT_TRUE(std::isfinite(e.curvature.gaussian) && std::isfinite(e.curvature.mean));
  EXPECT_TRUE(in_fill_domain(fill, fill.center));
  EXPECT_TRUE(in_fill_domain(fill, fill.corners[0]));
  at.fill_parameter = fill.center + 100.0 * (fill.corners[0] - fill.center);
  EXPECT_FALSE(in_fill_domain(fill, at.fill_parameter));
  EXPECT_THROW((void)evaluate_surface(s, at), ricci::InvalidInputError);
  at.fill = static_cast<int>(s.fills.size());
  at.fill_parameter = fill.center;
  EXPECT_THROW((void)evaluate_surface(s, at), ricci::InvalidInputError);
}

TEST(SurfaceEvaluate, BadPointsThrow) {
  const SplineSurface& s = small_surface("genus2.off");
  const ManifoldSplineSpace& space = *s.spline.space;
  int skipped = -1, kept = -1;
  for (int f = 0; f < space.face_count(); ++f) (s.skipped_faces[f] ? skipped : kept) = f;
  ASSERT_GE(skipped, 0);
  ASSERT_GE(kept, 0);
  const Eigen::Vector3d third = Eigen::Vector3d::Constant(1.0 / 3.0);
  using ricci::InvalidInputError;
  EXPECT_THROW((void)evaluate_surface(s, DomainPoint{-1, third}), InvalidInputError);
  EXPECT_THROW((void)evaluate_surface(s, DomainPoint{space.face_count(), third}),
               InvalidInputError);
  EXPECT_THROW((void)evaluate_surface(s, DomainPoint{skipped, third}), InvalidInputError);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW((void)evaluate_surface(s, DomainPoint{kept, {nan, 0.5, 0.5}}), InvalidInputError);
  EXPECT_THROW((void)evaluate_surface(s, DomainPoint{kept, {0.5, 0.5, 0.5}}), InvalidInputError);
  EXPECT_THROW((void)evaluate_surface(s, DomainPoint{kept, {1.5, -0.5, 0.0}}), InvalidInputError);
  EXPECT_THROW((void)evaluate_surface(s, std::vector<DomainPoint>{{kept, third}, {-1, third}}),
               InvalidInputError);
  EXPECT_NO_THROW((void)evaluate_surface(s, DomainPoint{kept, {1.0, 0.0, 0.0}}));
}

}  // namespace
}  // namespace spline
