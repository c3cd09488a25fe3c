#include "spline/fill/puncture.h"

#include <gtest/gtest.h>
#include <algorithm>
#include <cmath>
#include <limits>

#include "ricci/mesh/errors.h"
#include "ricci/mesh/io.h"
#include "ricci/mesh/simplify.h"
#include "ricci/pipeline/one_cone_atlas.h"
#include "msp/report/fit_report.h"
#include "ricci/test_meshes.h"
#include "spline/fit/fit.h"
#include "spline/surface/fit_surface.h"
#include "test_paths.h"

namespace spline {
namespace {

TEST(StarNormalSpread, ZeroOnAPlane) {
  const ricci::Mesh square = ricci::testing::square(6);
  const int centre = 3 * 7 + 3;  // (0.5, 0.5): rows of 7 vertices
  for (int rings = 1; rings <= 3; ++rings)
    EXPECT_NEAR(star_normal_spread_deg(square, centre, rings), 0.0, 1e-9);
}

// The octahedron's vertex (0, 0, 1): its four faces' normals (+-1, +-1, 1) / sqrt(3) lie
// acos(1 / sqrt(3)) from their mean (0, 0, 1).
TEST(StarNormalSpread, OctahedronVertexStar) {
  const ricci::Mesh octahedron = ricci::testing::sphere(0);
  const double expected = std::acos(1.0 / std::sqrt(3.0)) * 180.0 / M_PI;
  EXPECT_NEAR(star_normal_spread_deg(octahedron, 4, 1), expected, 1e-9);
}

// On a refined sphere the neighbourhood turns more with every ring, and a scaled copy spreads
// the same.
TEST(StarNormalSpread, GrowsWithTheRingsAndIgnoresScale) {
  ricci::Mesh sphere = ricci::testing::sphere(3);
  const double one = star_normal_spread_deg(sphere, 4, 1);
  const double two = star_normal_spread_deg(sphere, 4, 2);
  const double three = star_normal_spread_deg(sphere, 4, 3);
  EXPECT_GT(one, 0.0);
  EXPECT_LT(one, two);
  EXPECT_LT(two, three);
  EXPECT_LT(three, 90.0);
  for (auto v : sphere.vertices()) sphere.set_point(v, sphere.point(v) * 1e3);
  EXPECT_NEAR(star_normal_spread_deg(sphere, 4, 3), three, 1e-9);
}

TEST(StarNormalSpread, BadInputThrows) {
  const ricci::Mesh sphere = ricci::testing::sphere(1);
  EXPECT_THROW((void)star_normal_spread_deg(sphere, -1, 2), ricci::InvalidInputError);
  EXPECT_THROW((void)star_normal_spread_deg(sphere, static_cast<int>(sphere.n_vertices()), 2),
               ricci::InvalidInputError);
  EXPECT_THROW((void)star_normal_spread_deg(sphere, 0, 0), ricci::InvalidInputError);
  PunctureChoiceOptions bad;
  bad.min_spread_gain = 1.5;
  EXPECT_THROW((void)choose_puncture(sphere, {}, bad), ricci::InvalidInputError);
}

// The low-resolution bunny's fit domain (the scan fit's simplification to its default size):
// the distortion's choice sits where its three rings turn over 87 degrees; a vertex verified
// within 1.3% of its distortion turns over 62. The puncture is the flattest candidate within
// the tolerance, within the tolerance of the least distortion, and flatter by the gain asked.
TEST(ChoosePuncture, FlattestCandidateWithinTheDistortionTolerance) {
  const ricci::Mesh scan =
      ricci::read_mesh(msp_test::test_mesh("closed_g0/bunny_npm_closed.off"));
  const ScanFitOptions fit;
  ricci::SimplifyOptions simplify;
  simplify.target_faces = fit.domain_faces;
  const ricci::Mesh domain = ricci::simplify_mesh(scan, simplify).mesh;
  const PunctureChoiceOptions options = fit.puncture;
  const PunctureChoice p =
      choose_puncture(domain, ricci::singularity_options(domain, fit.atlas), options);
  ASSERT_GE(p.vertex, 0);
  ASSERT_FALSE(p.choice.verified.empty());
  double best = std::numeric_limits<double>::infinity();
  for (const auto& s : p.choice.verified) best = std::min(best, s.area_distortion);
  EXPECT_EQ(p.distortion_vertex, p.choice.vertex);
  EXPECT_LE(p.area_distortion, (1.0 + options.distortion_tolerance) * best);
  EXPECT_DOUBLE_EQ(p.normal_spread_deg, star_normal_spread_deg(domain, p.vertex, options.rings));
  EXPECT_DOUBLE_EQ(p.distortion_spread_deg,
                   star_normal_spread_deg(domain, p.distortion_vertex, options.rings));
  for (const auto& s : p.choice.verified) {
    if (s.area_distortion > (1.0 + options.distortion_tolerance) * best) continue;
    EXPECT_LE(p.normal_spread_deg, star_normal_spread_deg(domain, s.vertex, options.rings))
        << "candidate " << s.vertex;
  }
  EXPECT_GE(p.candidates, 2);
  EXPECT_NE(p.vertex, p.distortion_vertex);
  EXPECT_LE(p.normal_spread_deg, (1.0 - options.min_spread_gain) * p.distortion_spread_deg);

  // Off: the distortion's choice.
  PunctureChoiceOptions off = options;
  off.min_spread_gain = 1.0;
  const PunctureChoice kept =
      choose_puncture(domain, ricci::singularity_options(domain, fit.atlas), off);
  EXPECT_EQ(kept.vertex, kept.distortion_vertex);
}

// The fit itself, at the defaults: the bunny's puncture patch meets the surface within 0.4
// degrees (0.6 with the puncture at the distortion's choice).
TEST(ChoosePuncture, FitPutsThePunctureWhereThePatchMeetsTheSurface) {
  const ricci::Mesh scan =
      ricci::read_mesh(msp_test::test_mesh("closed_g0/bunny_npm_closed.off"));
  const FittedSurface r = fit_surface(scan, FitSurfaceOptions{});
  ASSERT_EQ(r.input.genus, 0);
  EXPECT_TRUE(r.watertight);
  EXPECT_EQ(r.fallback_fills, 0);
  EXPECT_LT(r.fill_normal_jump_deg, 0.4);
  // The report says where the puncture went and why.
  ASSERT_GE(r.puncture.vertex, 0);
  EXPECT_EQ(r.atlas.chosen_vertex, r.puncture.vertex);
  EXPECT_LT(r.puncture.normal_spread_deg, r.puncture.distortion_spread_deg);
  const nlohmann::json report = msp::fit_report_json("bunny", r, FitSurfaceOptions{});
  const nlohmann::json& flat = report["singularities"][0]["flatness_choice"];
  EXPECT_EQ(flat["normal_spread_deg"].get<double>(), r.puncture.normal_spread_deg);
  EXPECT_EQ(flat["least_distortion_vertex"].get<int>(), r.puncture.distortion_vertex);
  EXPECT_EQ(flat["moved"].get<bool>(), r.puncture.vertex != r.puncture.distortion_vertex);
}

}  // namespace
}  // namespace spline
