// Knot clouds: the placement rule meets the DMS knot-net conditions, stays inside the one-ring,
// avoids edge lines, is deterministic and moves with rigid motions; the checker catches violations.
#include "spline/knots/knot_cloud.h"

#include <gtest/gtest.h>

#include <cmath>

#include "ricci/mesh/errors.h"
#include "spline/basis/multi_index.h"
#include "spline/basis/planar_fixtures.h"
#include "spline/knots/dms_conditions.h"

namespace spline {
namespace {

constexpr double kPi = 3.14159265358979323846;

std::vector<PlanarTriangulation> fixtures() {
  std::vector<PlanarTriangulation> result;
  for (unsigned seed = 1; seed <= 3; ++seed) {
    result.push_back(testing::perturbed_grid(6, 0.4, seed));
    result.push_back(testing::ring_disk(3, seed));
  }
  return result;
}

TEST(KnotClouds, RuleSatisfiesTheDmsConditions) {
  for (const PlanarTriangulation& t : fixtures()) {
    for (int n = 1; n <= kMaxDmsDegree; ++n) {
      for (const double fraction : {0.05, 0.4, 0.49}) {
        KnotCloudOptions options;
        options.radius_fraction = fraction;
        const DmsConditionReport report = check_dms_conditions(t, make_knot_clouds(t, n, options));
        EXPECT_TRUE(report.satisfied) << "degree " << n << " fraction " << fraction;
        EXPECT_TRUE(report.failing_triangles.empty());
        EXPECT_GT(report.min_orientation_ratio, 0.0);
        EXPECT_GT(report.min_knot_region_ratio, 0.0);
        EXPECT_GT(report.min_general_position, 0.0);
      }
    }
  }
}

TEST(KnotClouds, KnotsStayCloseToTheirVertexAwayFromEdgeLines) {
  const PlanarTriangulation t = testing::ring_disk(3, 5);
  const std::vector<VertexRing> rings = vertex_rings(t);
  for (int n = 1; n <= kMaxDmsDegree; ++n) {
    const std::vector<KnotCloud> clouds = make_knot_clouds(t, n);
    for (std::size_t v = 0; v < clouds.size(); ++v) {
      const Eigen::Vector2d& center = t.positions[v];
      ASSERT_EQ(clouds[v].degree(), n);
      EXPECT_EQ(clouds[v].knots[0], center);
      double smallest_inradius = 1e300;
      const auto& ring = rings[v].neighbours;
      const std::size_t fan = rings[v].closed ? ring.size() : ring.size() - 1;
      for (std::size_t i = 0; i < fan; ++i) {
        smallest_inradius = std::min(
            smallest_inradius,
            inradius(center, t.positions[ring[i]], t.positions[ring[(i + 1) % ring.size()]]));
      }
      // Widest gap among n * valence forbidden rotations on a circle of length pi.
      const double clearance_bound = kPi / (2.0 * n * static_cast<double>(ring.size()));
      for (int j = 1; j <= n; ++j) {
        const Eigen::Vector2d offset = clouds[v].knots[j] - center;
        EXPECT_LE(offset.norm(), 0.4 * smallest_inradius * (1 + 1e-12));
        EXPECT_GE(offset.norm(), 0.4 * smallest_inradius * (1 - 0.4) * (1 - 1e-12));
        for (int w : ring) {
          const Eigen::Vector2d e = t.positions[w] - center;
          const double sine = std::abs(offset.x() * e.y() - offset.y() * e.x()) /
                              (offset.norm() * e.norm());
          EXPECT_GE(std::asin(std::min(1.0, sine)), clearance_bound * (1 - 1e-9));
        }
        for (int k = j + 1; k <= n; ++k) {  // no two knots of a cloud on a line through v
          const Eigen::Vector2d other = clouds[v].knots[k] - center;
          EXPECT_GT(std::abs(offset.x() * other.y() - offset.y() * other.x()),
                    1e-3 * offset.norm() * other.norm());
        }
      }
    }
  }
}

TEST(KnotClouds, DeterministicSeededAndMovedByRigidMotions) {
  const PlanarTriangulation t = testing::perturbed_grid(4, 0.3, 9);
  const std::vector<KnotCloud> a = make_knot_clouds(t, 3), b = make_knot_clouds(t, 3);
  KnotCloudOptions other_seed;
  other_seed.seed = 2;
  const std::vector<KnotCloud> c = make_knot_clouds(t, 3, other_seed);
  bool all_same = true;
  for (std::size_t v = 0; v < a.size(); ++v) {
    for (int j = 0; j <= 3; ++j) {
      EXPECT_EQ(a[v].knots[j], b[v].knots[j]);
      all_same = all_same && a[v].knots[j] == c[v].knots[j];
    }
  }
  EXPECT_FALSE(all_same);

  const Eigen::Vector2d center(0.3, -0.2);
  const std::vector<Eigen::Vector2d> ring = {{1.0, 0.1}, {0.4, 0.9}, {-0.7, 0.5}, {-0.6, -0.8},
                                             {0.5, -0.9}};
  const double angle = 1.1;
  Eigen::Matrix2d rotation;
  rotation << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
  const Eigen::Vector2d shift(5.0, -2.0);
  std::vector<Eigen::Vector2d> moved_ring;
  for (const Eigen::Vector2d& p : ring) moved_ring.push_back(rotation * p + shift);
  for (int n = 1; n <= 5; ++n) {
    const KnotCloud original = make_knot_cloud(n, 17, center, ring, true);
    const KnotCloud moved = make_knot_cloud(n, 17, rotation * center + shift, moved_ring, true);
    const KnotCloud expected = transformed(original, rotation, shift);
    for (int j = 0; j <= n; ++j) EXPECT_LT((moved.knots[j] - expected.knots[j]).norm(), 1e-12);
  }
}

TEST(KnotClouds, CheckerReportsViolations) {
  const PlanarTriangulation t = testing::perturbed_grid(4, 0.2, 3);
  std::vector<KnotCloud> clouds = make_knot_clouds(t, 3);
  const std::vector<bool> interior = testing::interior_vertices(t);
  std::size_t v = 0;
  while (!interior[v]) ++v;
  // Push one knot past the middle of an incident edge: some shifted triangle flips over.
  const int w = vertex_rings(t)[v].neighbours[0];
  clouds[v].knots[2] = t.positions[v] + 1.5 * (t.positions[w] - t.positions[v]);
  const DmsConditionReport report = check_dms_conditions(t, clouds);
  EXPECT_FALSE(report.satisfied);
  EXPECT_FALSE(report.failing_triangles.empty());
  EXPECT_LT(report.min_orientation_ratio, 0.0);
  // Three collinear knots in a knot set: general-position margin zero.
  std::vector<KnotCloud> collinear = make_knot_clouds(t, 3);
  collinear[v].knots[2] = 2.0 * collinear[v].knots[1] - collinear[v].knots[0];
  EXPECT_EQ(check_dms_conditions(t, collinear).min_general_position, 0.0);
}

TEST(KnotClouds, RejectsBadInput) {
  const PlanarTriangulation t = testing::perturbed_grid(2, 0.0, 1);
  KnotCloudOptions bad;
  bad.radius_fraction = 0.5;  // beyond the proven range
  EXPECT_THROW(make_knot_clouds(t, 2, bad), ricci::InvalidInputError);
  bad = {};
  bad.radius_jitter = 1.0;
  EXPECT_THROW(make_knot_clouds(t, 2, bad), ricci::InvalidInputError);
  EXPECT_THROW(make_knot_cloud(2, 0, {0, 0}, {{1, 0}}, false), ricci::InvalidInputError);
  EXPECT_THROW(make_knot_cloud(2, 0, {0, 0}, {{1, 0}, {2, 0}}, false), ricci::InvalidInputError);
  std::vector<KnotCloud> clouds = make_knot_clouds(t, 2);
  clouds.pop_back();
  EXPECT_THROW((void)check_dms_conditions(t, clouds), ricci::InvalidInputError);
}

}  // namespace
}  // namespace spline
