// Planar DMS spaces: partition of unity, polynomial reproduction from blossoms, exactness on edges
// and vertices, small clouds, support, invariance under rigid motions and scaling, bad input.
#include "spline/basis/planar_space.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "ricci/mesh/errors.h"
#include "spline/basis/planar_fixtures.h"
#include "spline/knots/dms_conditions.h"
#include "spline/knots/knot_cloud.h"

namespace spline {
namespace {

using testing::inner_triangles;
using testing::perturbed_grid;
using testing::random_point_in;
using testing::ring_disk;

PlanarDmsSpace make_space(const PlanarTriangulation& t, int degree, double radius_fraction = 0.4,
                          std::uint64_t seed = 1) {
  KnotCloudOptions options;
  options.radius_fraction = radius_fraction;
  options.seed = seed;
  return PlanarDmsSpace(t, make_knot_clouds(t, degree, options));
}

std::vector<PlanarTriangulation> fixtures(unsigned seed) {
  return {perturbed_grid(6, 0.3, seed), ring_disk(3, seed)};
}

struct Sums {
  double value = 0.0;
  Eigen::Vector2d gradient = Eigen::Vector2d::Zero();
  Eigen::Vector3d hessian = Eigen::Vector3d::Zero();
  double gradient_scale = 0.0;  // sum of |gradient| of the terms (cancellation scale)
};

Sums sum_basis(const PlanarDmsSpace& space, const Eigen::Vector2d& u, const TieBreak& tie = {}) {
  Sums s;
  for (const BasisSample& b : space.evaluate_basis(u, tie)) {
    s.value += b.jet.value;
    s.gradient += b.jet.gradient;
    s.hessian += b.jet.hessian;
    s.gradient_scale += b.jet.gradient.norm();
  }
  return s;
}

TEST(PlanarDmsSpace, PartitionOfUnityInTheInterior) {
  for (int n = 2; n <= 5; ++n) {
    for (const PlanarTriangulation& t : fixtures(100 + n)) {
      const PlanarDmsSpace space = make_space(t, n);
      std::mt19937 rng(n);
      for (int i : inner_triangles(t)) {
        for (int k = 0; k < 6; ++k) {
          const Sums s = sum_basis(space, random_point_in(t, i, rng));
          ASSERT_NEAR(s.value, 1.0, 1e-12) << "degree " << n << " triangle " << i;
          ASSERT_NEAR(s.gradient.norm(), 0.0, 1e-10) << "degree " << n;
          ASSERT_NEAR(s.hessian.norm(), 0.0, 1e-8) << "degree " << n;
        }
      }
    }
  }
}

TEST(PlanarDmsSpace, PartitionOfUnityExactlyOnEdgesAndVertices) {
  const TieBreak ties[] = {TieBreak{}, TieBreak{{0.0, -1.0}}, TieBreak{{-0.6, 0.8}}};
  for (int n = 2; n <= 5; ++n) {
    const PlanarTriangulation t = perturbed_grid(5, 0.3, 7 + n);
    const PlanarDmsSpace space = make_space(t, n);
    std::mt19937 rng(n);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int i : inner_triangles(t)) {
      const Eigen::Vector3i& tri = t.triangles[static_cast<std::size_t>(i)];
      std::vector<Eigen::Vector2d> points;
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector2d& p = t.positions[tri[k]];
        const Eigen::Vector2d& q = t.positions[tri[(k + 1) % 3]];
        points.push_back(p);                                       // a vertex = knot t_{v,0}
        points.push_back(p + unit(rng) * (q - p));                 // on a domain edge
        points.push_back(space.clouds()[tri[k]].knots[1]);         // another knot
      }
      for (const Eigen::Vector2d& u : points) {
        for (const TieBreak& tie : ties) {
          const Sums s = sum_basis(space, u, tie);
          ASSERT_NEAR(s.value, 1.0, 1e-12) << "degree " << n;
          ASSERT_NEAR(s.gradient.norm(), 0.0, 1e-10) << "degree " << n;
        }
      }
    }
  }
}

TEST(PlanarDmsSpace, ReproducesEveryMonomialFromBlossoms) {
  for (int n = 2; n <= 5; ++n) {
    for (const PlanarTriangulation& t : fixtures(200 + n)) {
      const PlanarDmsSpace space = make_space(t, n);
      std::mt19937 rng(n);
      std::vector<Eigen::Vector2d> points;
      for (int i : inner_triangles(t)) points.push_back(random_point_in(t, i, rng));
      for (int a = 0; a <= n; ++a) {
        for (int b = 0; a + b <= n; ++b) {
          const BivariatePolynomial p = monomial(a, b, n);
          const Eigen::MatrixXd control = space.control_points_of(p);
          for (const Eigen::Vector2d& u : points) {
            const SplineJet f = space.evaluate(control, u);
            const double x = u.x(), y = u.y();
            const double exact = std::pow(x, a) * std::pow(y, b);
            const double dx = a > 0 ? a * std::pow(x, a - 1) * std::pow(y, b) : 0.0;
            const double dy = b > 0 ? b * std::pow(x, a) * std::pow(y, b - 1) : 0.0;
            const double dxx = a > 1 ? a * (a - 1) * std::pow(x, a - 2) * std::pow(y, b) : 0.0;
            const double dxy = a > 0 && b > 0 ? a * b * std::pow(x, a - 1) * std::pow(y, b - 1) : 0.0;
            const double dyy = b > 1 ? b * (b - 1) * std::pow(x, a) * std::pow(y, b - 2) : 0.0;
            ASSERT_NEAR(f.value[0], exact, 1e-10) << "x^" << a << " y^" << b;
            ASSERT_NEAR(f.gradient(0, 0), dx, 1e-8);
            ASSERT_NEAR(f.gradient(0, 1), dy, 1e-8);
            ASSERT_NEAR(f.hessian(0, 0), dxx, 1e-6);
            ASSERT_NEAR(f.hessian(0, 1), dxy, 1e-6);
            ASSERT_NEAR(f.hessian(0, 2), dyy, 1e-6);
          }
        }
      }
    }
  }
}

TEST(PlanarDmsSpace, ReproducesVectorPolynomialsInALocalFrame) {
  const int n = 3;
  const PlanarTriangulation t = perturbed_grid(5, 0.3, 5);
  const PlanarDmsSpace space = make_space(t, n);
  BivariatePolynomial p;
  p.degree = n;
  p.origin = Eigen::Vector2d(0.4, 0.6);
  p.scale = 0.7;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  p.coefficients = Eigen::MatrixXd::NullaryExpr(monomial_count(n), 3, [&]() { return unit(rng); });
  const Eigen::MatrixXd control = space.control_points_of(p);
  for (int i : inner_triangles(t)) {
    const Eigen::Vector2d u = random_point_in(t, i, rng);
    EXPECT_LT((space.evaluate(control, u).value - evaluate(p, u)).norm(), 1e-10);
  }
}

// Three columns (a patch in space, evaluated with fixed-size sums and straight from a MatrixX3d)
// give the same bits as each column alone through the general path, value and derivatives.
TEST(PlanarDmsSpace, ThreeColumnsEvaluateAsEachColumnAlone) {
  const PlanarTriangulation t = perturbed_grid(5, 0.3, 7);
  const PlanarDmsSpace space = make_space(t, 3);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const Eigen::MatrixX3d control =
      Eigen::MatrixX3d::NullaryExpr(space.function_count(), 3, [&]() { return unit(rng); });
  for (int i : inner_triangles(t)) {
    const Eigen::Vector2d u = random_point_in(t, i, rng);
    const SplineJet all = space.evaluate(control, u);
    ASSERT_EQ(all.value.size(), 3);
    for (int c = 0; c < 3; ++c) {
      const Eigen::MatrixXd column = control.col(c);
      const SplineJet one = space.evaluate(column, u);
      EXPECT_EQ(all.value[c], one.value[0]);
      EXPECT_EQ(all.gradient.row(c), one.gradient.row(0));
      EXPECT_EQ(all.hessian.row(c), one.hessian.row(0));
    }
  }
}

// Cloud radius about 1e-6 of the edge length: still a partition of unity, also at points inside
// the clouds, where the functions vary on the scale of the cloud.
TEST(PlanarDmsSpace, TinyCloudsKeepPartitionOfUnity) {
  for (int n = 2; n <= 5; ++n) {
    const PlanarTriangulation t = perturbed_grid(5, 0.3, 300 + n);
    // Inradius ~0.05 and edges ~0.2 here: a fraction of 5e-6 gives radius ~1e-6 of the edge.
    const PlanarDmsSpace space = make_space(t, n, 5e-6);
    std::mt19937 rng(n);
    std::uniform_real_distribution<double> unit(-1.5, 1.5);
    for (int i : inner_triangles(t)) {
      for (int k = 0; k < 4; ++k) {
        const Sums s = sum_basis(space, random_point_in(t, i, rng));
        ASSERT_NEAR(s.value, 1.0, 1e-12) << "degree " << n;
        ASSERT_TRUE(s.gradient.allFinite() && s.hessian.allFinite());
      }
      const int v = t.triangles[static_cast<std::size_t>(i)][0];
      const double radius = (space.clouds()[v].knots[1] - t.positions[v]).norm();
      for (int k = 0; k < 10; ++k) {
        const Eigen::Vector2d u = t.positions[v] + radius * Eigen::Vector2d(unit(rng), unit(rng));
        const Sums s = sum_basis(space, u);
        ASSERT_NEAR(s.value, 1.0, 1e-12) << "degree " << n << " inside the cloud of " << v;
        ASSERT_LT(s.gradient.norm(), 1e-12 * s.gradient_scale) << "degree " << n;
      }
    }
  }
}

// A knot nearly collinear (1e-13 off) with its vertex and a neighbour, i.e. with knots sharing
// its knot sets: finite values, still a partition of unity.
TEST(PlanarDmsSpace, NearlyCollinearKnotsStayFinite) {
  const int n = 3;
  const PlanarTriangulation t = perturbed_grid(4, 0.2, 17);
  std::vector<KnotCloud> clouds = make_knot_clouds(t, n);
  const std::vector<VertexRing> rings = vertex_rings(t);
  const std::vector<bool> interior = testing::interior_vertices(t);
  std::size_t v = 0;
  while (!interior[v]) ++v;
  const Eigen::Vector2d edge = (t.positions[rings[v].neighbours[0]] - t.positions[v]).normalized();
  const double radius = (clouds[v].knots[1] - t.positions[v]).norm();
  clouds[v].knots[1] =
      t.positions[v] + radius * edge + 1e-13 * Eigen::Vector2d(-edge.y(), edge.x());
  ASSERT_TRUE(check_dms_conditions(t, clouds).satisfied);
  const PlanarDmsSpace space(t, clouds);
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> unit(-0.05, 0.05);
  for (int k = 0; k < 300; ++k) {
    const Eigen::Vector2d u = t.positions[v] + Eigen::Vector2d(unit(rng), unit(rng));
    const Sums s = sum_basis(space, u);
    ASSERT_TRUE(std::isfinite(s.value) && s.gradient.allFinite() && s.hessian.allFinite());
    EXPECT_NEAR(s.value, 1.0, 1e-9);
  }
}

TEST(PlanarDmsSpace, EvaluatedFunctionsLieInTheSupportQuery) {
  const int n = 3;
  const PlanarTriangulation t = ring_disk(3, 9);
  const PlanarDmsSpace space = make_space(t, n);
  std::mt19937 rng(2);
  for (int i = 0; i < space.triangle_count(); ++i) {
    const Eigen::Vector2d u = random_point_in(t, i, rng);
    const std::vector<BasisFunctionId> support = space.support(u);
    for (const BasisSample& s : space.evaluate_basis(u)) {
      const bool listed = std::any_of(support.begin(), support.end(), [&](const BasisFunctionId& id) {
        return id.triangle == s.triangle && id.beta == s.beta;
      });
      EXPECT_TRUE(listed) << "function (" << s.triangle << ", " << s.beta << ")";
    }
    // A point's own triangle contributes, and the support stays local (own + nearby triangles).
    EXPECT_TRUE(std::any_of(support.begin(), support.end(),
                            [&](const BasisFunctionId& id) { return id.triangle == i; }));
    EXPECT_LT(support.size(), 15u * static_cast<std::size_t>(space.functions_per_triangle()));
  }
  EXPECT_TRUE(space.evaluate_basis(Eigen::Vector2d(100.0, 100.0)).empty());
  EXPECT_TRUE(space.support(Eigen::Vector2d(100.0, 100.0)).empty());
  // Points whose grid cell is past the range of int (the cell index is clamped before it is
  // converted: a sanitized build traps the overflowing conversion) have no functions either.
  const double huge = std::numeric_limits<double>::max();
  for (const Eigen::Vector2d& u : {Eigen::Vector2d(1e12, -1e12), Eigen::Vector2d(-huge, huge),
                                  Eigen::Vector2d(huge, huge), Eigen::Vector2d(0.0, -huge)}) {
    EXPECT_TRUE(space.evaluate_basis(u).empty()) << u.transpose();
    EXPECT_TRUE(space.support(u).empty()) << u.transpose();
  }
}

// Moving the whole configuration by a rigid motion (or scaling it) moves the functions with it:
// the property charts of the affine atlas rely on.
TEST(PlanarDmsSpace, InvariantUnderRigidMotionsAndScaling) {
  const int n = 4;
  const PlanarTriangulation t = perturbed_grid(4, 0.3, 21);
  const std::vector<KnotCloud> clouds = make_knot_clouds(t, n);
  const PlanarDmsSpace space(t, clouds);
  for (const double scale : {1.0, 1e-4, 1e4}) {
    const double angle = 0.7;
    Eigen::Matrix2d rotation;
    rotation << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
    const Eigen::Vector2d shift = scale * Eigen::Vector2d(3.0, -5.0);
    auto motion = [&](const Eigen::Vector2d& x) -> Eigen::Vector2d {
      return scale * (rotation * x) + shift;
    };
    PlanarTriangulation moved = t;
    std::vector<KnotCloud> moved_clouds;
    for (Eigen::Vector2d& p : moved.positions) p = motion(p);
    for (const KnotCloud& c : clouds) moved_clouds.push_back(transformed(c, scale * rotation, shift));
    const PlanarDmsSpace other(moved, moved_clouds);
    std::mt19937 rng(4);
    for (int i : inner_triangles(t)) {
      const Eigen::Vector2d u = random_point_in(t, i, rng);
      const std::vector<BasisSample> a = space.evaluate_basis(u);
      const std::vector<BasisSample> b = other.evaluate_basis(motion(u));
      ASSERT_EQ(a.size(), b.size());
      for (std::size_t k = 0; k < a.size(); ++k) {
        ASSERT_EQ(a[k].triangle, b[k].triangle);
        ASSERT_EQ(a[k].beta, b[k].beta);
        EXPECT_NEAR(a[k].jet.value, b[k].jet.value, 1e-11);
        const Eigen::Vector2d g = rotation * a[k].jet.gradient / scale;
        EXPECT_NEAR((g - b[k].jet.gradient).norm(), 0.0, 1e-9 * (1.0 + g.norm()));
      }
    }
  }
}

TEST(PlanarDmsSpace, RejectsBadInput) {
  const PlanarTriangulation t = perturbed_grid(2, 0.0, 1);
  std::vector<KnotCloud> clouds = make_knot_clouds(t, 2);
  EXPECT_THROW(PlanarDmsSpace(t, std::vector<KnotCloud>(clouds.begin(), clouds.end() - 1)),
               ricci::InvalidInputError);
  std::vector<KnotCloud> moved = clouds;
  moved[0].knots[0] += Eigen::Vector2d(1e-3, 0.0);
  EXPECT_THROW(PlanarDmsSpace(t, moved), ricci::InvalidInputError);
  std::vector<KnotCloud> mixed = clouds;
  mixed[1].knots.pop_back();
  EXPECT_THROW(PlanarDmsSpace(t, mixed), ricci::InvalidInputError);
  PlanarTriangulation flipped = t;
  std::swap(flipped.triangles[0][1], flipped.triangles[0][2]);
  EXPECT_THROW(PlanarDmsSpace(flipped, clouds), ricci::InvalidInputError);
  const PlanarDmsSpace space(t, clouds);
  EXPECT_THROW((void)space.evaluate(Eigen::MatrixXd::Zero(3, 1), {0.5, 0.5}),
               ricci::InvalidInputError);
  EXPECT_THROW(make_knot_clouds(t, 0), ricci::InvalidInputError);
  EXPECT_THROW(make_knot_clouds(t, kMaxDmsDegree + 1), ricci::InvalidInputError);
}

}  // namespace
}  // namespace spline
