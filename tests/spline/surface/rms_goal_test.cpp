// FitSurfaceOptions::rms_goal: a first fit whose RMS exceeds the goal is refined where it misses
// the scan most and fitted again; one within the goal is delivered exactly as without a goal.
#include <gtest/gtest.h>

#include <cmath>

#include "ricci/mesh/errors.h"
#include "ricci/mesh/primitives.h"
#include "spline/surface/fit_surface.h"

namespace spline {
namespace {

// A unit disk with ripples shorter than a domain face on its half x > 0.
ricci::Mesh half_rippled_disk() {
  ricci::Mesh m = ricci::make_disk(40, 6);
  for (auto v : m.vertices()) {
    auto p = m.point(v);
    if (p[0] > 0.0) p[2] = 0.04 * p[0] * std::sin(25.0 * p[0]) * std::sin(25.0 * p[1]);
    m.set_point(v, p);
  }
  return m;
}

FitSurfaceOptions small_options(double rms_goal) {
  FitSurfaceOptions options;
  options.domain_faces = 400;
  options.density = 3;
  options.rms_goal = rms_goal;
  return options;
}

TEST(FitSurfaceRmsGoal, RefinesOnlyAFitAboveTheGoal) {
  const ricci::Mesh scan = half_rippled_disk();
  const FittedSurface plain = fit_surface(scan, small_options(0.0));
  ASSERT_EQ(plain.refinement.size(), 1u);
  const double diag = plain.bbox_diagonal;
  const double rms = plain.projection_rms / diag;
  ASSERT_GT(rms, 0.0);

  // Within the goal: the same surface, to the last digit.
  const FittedSurface within = fit_surface(scan, small_options(1.2 * rms));
  EXPECT_EQ(within.surface.spline.space->function_count(),
            plain.surface.spline.space->function_count());
  EXPECT_EQ(within.fit_rms, plain.fit_rms);
  EXPECT_EQ(within.fit_max, plain.fit_max);

  // Above it: the first round is the plain fit, the next one a finer domain where the ripples
  // are, and the delivered surface is nearer the scan.
  const FittedSurface refined = fit_surface(scan, small_options(0.8 * rms));
  ASSERT_GE(refined.refinement.size(), 2u);
  const RefinementRound& first = refined.refinement[0];
  const RefinementRound& second = refined.refinement[1];
  EXPECT_NEAR(first.projection_rms / diag, rms, 1e-9);
  EXPECT_GT(second.domain_faces, first.domain_faces);
  EXPECT_LT(refined.projection_rms, 0.8 * rms * diag);
  EXPECT_LT(refined.fit_rms, plain.fit_rms);
  EXPECT_EQ(refined.surface_dihedral.over_90_deg, 0);
  EXPECT_TRUE(refined.watertight);
  // The splits went to the rippled half: the smooth half keeps the plain domain's faces.
  int rippled = 0, smooth = 0;
  const ricci::Mesh& domain = refined.surface.domain;
  for (auto f : domain.faces()) {
    const auto c = domain.calc_face_centroid(f);
    if (std::abs(c[0]) < 0.2) continue;
    (c[0] > 0.0 ? rippled : smooth) += 1;
  }
  EXPECT_GT(rippled, 2 * smooth) << "rippled " << rippled << ", smooth " << smooth;
}

// A goal the refinement does not reach, on a surface that does not fold: the refined round is
// delivered as it is, not refined toward the goal again (that retry is for a surface that folds,
// FitSurfaceHighGenus.genus8).
TEST(FitSurfaceRmsGoal, RefinesOnceWhenTheSurfaceDoesNotFold) {
  const ricci::Mesh scan = half_rippled_disk();
  const FittedSurface plain = fit_surface(scan, small_options(0.0));
  const double diag = plain.bbox_diagonal;
  const double goal = 0.25 * plain.projection_rms / diag;
  const FittedSurface refined = fit_surface(scan, small_options(goal));
  ASSERT_GE(refined.refinement.size(), 2u);
  const RefinementRound& first = refined.refinement[1];
  ASSERT_GT(first.projection_rms / diag, goal);
  EXPECT_GT(first.domain_faces, refined.refinement[0].domain_faces);
  EXPECT_EQ(refined.surface_dihedral.over_90_deg, 0);
  for (std::size_t k = 2; k < refined.refinement.size(); ++k)
    EXPECT_EQ(refined.refinement[k].domain_faces, first.domain_faces) << k;
  EXPECT_EQ(refined.surface.spline.space->domain_face_count(), first.domain_faces);
  EXPECT_TRUE(refined.watertight);
}

TEST(FitSurfaceRmsGoal, OutOfRangeIsRefused) {
  FitSurfaceOptions options;
  options.rms_goal = -1e-3;
  EXPECT_THROW(check_options(options), ricci::InvalidInputError);
  options.rms_goal = 1.0;
  EXPECT_THROW(check_options(options), ricci::InvalidInputError);
}

}  // namespace
}  // namespace spline
