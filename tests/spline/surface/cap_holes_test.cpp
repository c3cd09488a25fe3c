// cap_holes without patches (CapHolesOptions::make_patches false, how fit_surface judges a fit
// round before only the delivered one is capped): the rims are those the capping starts from,
// their faces are skipped, nothing is filled, and the tessellation is open exactly there; and
// the screening capping fit_surface ranks rounds by; a capping cancelled by its caller.
#include <gtest/gtest.h>

#include <atomic>
#include <vector>

#include "ricci/mesh/errors.h"
#include "spline/surface/cap_holes.h"
#include "spline/surface/surface_fixtures.h"
#include "spline/surface/tessellate_surface.h"

namespace spline {
namespace {

// The surface as fit_scan leaves it: no fills, no rims, nothing skipped.
SplineSurface uncapped(const SplineSurface& fitted) {
  SplineSurface s;
  s.domain = fitted.domain;
  s.spline = fitted.spline;
  s.singular_vertex = fitted.singular_vertex;
  return s;
}

TEST(CapHoles, WithoutPatchesTheRimsStayOpenAndTheirFacesAreSkipped) {
  const SplineSurface& fitted = testing::small_surface("genus2.off");
  SplineSurface open = uncapped(fitted);
  CapHolesOptions options;
  options.make_patches = false;
  const CapHolesReport report = cap_holes(open, options);
  EXPECT_TRUE(report.failures.empty());
  EXPECT_TRUE(open.fills.empty());
  ASSERT_EQ(open.open_rims.size(), 1u);  // the cone's hole of a closed genus-2 surface
  EXPECT_EQ(open.open_rims[0].kind, Rim::Kind::cone_hole);
  const auto& space = *open.spline.space;
  ASSERT_EQ(open.skipped_faces.size(), open.domain.n_faces());
  for (int f = 0; f < static_cast<int>(open.domain.n_faces()); ++f) {
    if (!space.in_domain(f)) {
      EXPECT_TRUE(open.skipped_faces[static_cast<std::size_t>(f)]);
    }
  }
  for (int f : open.open_rims[0].covered_faces)
    EXPECT_TRUE(open.skipped_faces[static_cast<std::size_t>(f)]);

  // Capped, the hole is the same or grown (a flipping patch is retried on a bigger hole).
  SplineSurface capped = uncapped(fitted);
  (void)cap_holes(capped, CapHolesOptions{});
  ASSERT_EQ(capped.fills.size(), 1u);
  EXPECT_TRUE(capped.open_rims.empty());
  for (std::size_t f = 0; f < open.skipped_faces.size(); ++f) {
    if (open.skipped_faces[f]) {
      EXPECT_TRUE(capped.skipped_faces[f]) << f;
    }
  }

  // The open surface tessellates to the genus-2 surface with one hole, the capped one closed.
  TessellationOptions tess;
  tess.density = 3;
  std::vector<PatchTessellation> patches;
  const Tessellation t = tessellate_surface(open, tess, patches);
  EXPECT_TRUE(patches.empty());
  const WatertightReport topology = check_watertight(t.triangles, t.positions);
  EXPECT_TRUE(topology.matches(2, 1));
  const Tessellation closed = tessellate_surface(capped, tess, patches);
  EXPECT_TRUE(check_watertight(closed.triangles, closed.positions).matches(2, 0));
}

// CapHolesOptions::cancel (fit_surface's early capping of a round that folds): a capping whose
// flag is set stops at its first check and throws ricci::Cancelled, and so does fill_rim; with
// the flag given but clear, the capping is the plain one, bit for bit.
TEST(CapHoles, ACancelledCappingThrowsAndAClearFlagChangesNothing) {
  const SplineSurface& fitted = testing::small_surface("genus2.off");
  std::atomic<bool> stop{true};
  CapHolesOptions options;
  options.cancel = &stop;
  SplineSurface cancelled = uncapped(fitted);
  EXPECT_THROW((void)cap_holes(cancelled, options), ricci::Cancelled);
  FillOptions fill;
  fill.cancel = &stop;
  CapHolesOptions open;
  open.make_patches = false;
  SplineSurface rims = uncapped(fitted);
  (void)cap_holes(rims, open);
  ASSERT_EQ(rims.open_rims.size(), 1u);
  EXPECT_THROW((void)fill_rim(fitted.spline, fitted.domain, rims.open_rims[0], fill),
               ricci::Cancelled);

  stop = false;
  SplineSurface flagged = uncapped(fitted);
  const CapHolesReport flagged_report = cap_holes(flagged, options);
  SplineSurface plain = uncapped(fitted);
  const CapHolesReport plain_report = cap_holes(plain, CapHolesOptions{});
  EXPECT_EQ(flagged_report.max_normal_jump_deg, plain_report.max_normal_jump_deg);
  ASSERT_EQ(flagged.fills.size(), 1u);
  ASSERT_EQ(plain.fills.size(), 1u);
  EXPECT_TRUE((flagged.fills[0].control_points.array() ==
               plain.fills[0].control_points.array()).all());
  EXPECT_TRUE((flagged.spline.control_points.array() ==
               plain.spline.control_points.array()).all());
}

// The screening capping (CapHolesOptions::screening, how fit_surface ranks rounds before the one
// delivered is capped in full): with the genus-8 limits (vertex rounds and a reach) the cone
// hole keeps the rim the first find_rims gives and gets exactly the uniform-grid patch of
// fill_rim on it; the surface is closed as the full capping's is.
TEST(CapHoles, ScreeningMakesOneUniformPatchOnTheFirstRim) {
  EXPECT_FALSE(retries_cone_hole(cone_hole_limits(3)));
  EXPECT_TRUE(retries_cone_hole(cone_hole_limits(4)));
  EXPECT_TRUE(retries_cone_hole(cone_hole_limits(8)));
  const SplineSurface& fitted = testing::small_surface("genus2.off");
  CapHolesOptions options;
  options.cone_hole = cone_hole_limits(8);
  options.make_patches = false;
  SplineSurface open = uncapped(fitted);
  (void)cap_holes(open, options);
  ASSERT_EQ(open.open_rims.size(), 1u);
  const Rim& first = open.open_rims[0];

  options.make_patches = true;
  options.screening = true;
  SplineSurface screened = uncapped(fitted);
  const CapHolesReport report = cap_holes(screened, options);
  EXPECT_TRUE(report.failures.empty());
  ASSERT_EQ(screened.fills.size(), 1u);
  const HoleFill& fill = screened.fills[0];
  ASSERT_LT(fill.max_normal_jump_deg, 90.0);  // no flip, so no retry on a bigger hole
  EXPECT_EQ(fill.rim.covered_faces, first.covered_faces);
  FillOptions uniform;
  uniform.corner_refinement = 1;
  const HoleFill expected = fill_rim(fitted.spline, fitted.domain, first, uniform);
  EXPECT_EQ(fill.space->function_count(), expected.space->function_count());
  EXPECT_EQ(fill.control_points.rows(), expected.control_points.rows());
  EXPECT_LT((fill.control_points - expected.control_points).cwiseAbs().maxCoeff(), 1e-12);

  TessellationOptions tess;
  tess.density = 3;
  std::vector<PatchTessellation> patches;
  const Tessellation closed = tessellate_surface(screened, tess, patches);
  EXPECT_TRUE(check_watertight(closed.triangles, closed.positions).matches(2, 0));
}

// ConeHoleLimits::compare_uniform (from genus 8): the holes tried are compared on uniform grids
// and the chosen one is filled again with the corner-refined patch, whichever of the two meets
// the surface better delivered (fill_rim's own choice, or the uniform patch when that is better).
TEST(CapHoles, ComparedOnUniformGridsTheChosenHoleGetsTheBetterPatch) {
  const SplineSurface& fitted = testing::small_surface("genus2.off");
  CapHolesOptions options;
  options.cone_hole = cone_hole_limits(8);
  ASSERT_TRUE(options.cone_hole.compare_uniform);
  EXPECT_FALSE(cone_hole_limits(7).compare_uniform);
  SplineSurface capped = uncapped(fitted);
  (void)cap_holes(capped, options);
  ASSERT_EQ(capped.fills.size(), 1u);
  const HoleFill& fill = capped.fills[0];
  FillOptions uniform_options;
  uniform_options.corner_refinement = 1;
  const HoleFill uniform = fill_rim(fitted.spline, fitted.domain, fill.rim, uniform_options);
  const HoleFill full = fill_rim(fitted.spline, fitted.domain, fill.rim);
  const HoleFill& better =
      full.max_normal_jump_deg < uniform.max_normal_jump_deg ? full : uniform;
  ASSERT_EQ(fill.control_points.rows(), better.control_points.rows());
  EXPECT_LT((fill.control_points - better.control_points).cwiseAbs().maxCoeff(), 1e-12);
}

// cone_hole_limits with the fairing dropped next to the cone (fit_surface does it when
// FittedSurface::fit_unconstrained_faces > 0): the same limits without the reach, so the hole
// stops at the caps (8 layers, a quarter of the domain); below genus 8 nothing changes.
TEST(CapHoles, NoReachWhereTheFitDropsTheFairingAtTheCone) {
  for (int genus : {2, 4, 7, 8, 10, 11}) {
    const ConeHoleLimits kept = cone_hole_limits(genus);
    const ConeHoleLimits freed = cone_hole_limits(genus, true);
    EXPECT_EQ(freed.reach_layers, 0) << genus;
    EXPECT_EQ(freed.max_layers, kept.max_layers) << genus;
    EXPECT_EQ(freed.max_cover_fraction, kept.max_cover_fraction) << genus;
    EXPECT_EQ(freed.margin_layers, kept.margin_layers) << genus;
    EXPECT_EQ(freed.vertex_rounds, kept.vertex_rounds) << genus;
    EXPECT_EQ(freed.compare_uniform, kept.compare_uniform) << genus;
    EXPECT_EQ(retries_cone_hole(freed), genus >= 4) << genus;
  }
  EXPECT_GT(cone_hole_limits(10).reach_layers, 0);

  // On a surface the cone hole found without the reach is never larger than with it.
  const SplineSurface& fitted = testing::small_surface("genus2.off");
  CapHolesOptions options;
  options.cone_hole = cone_hole_limits(10, true);
  options.make_patches = false;
  SplineSurface open = uncapped(fitted);
  (void)cap_holes(open, options);
  ASSERT_EQ(open.open_rims.size(), 1u);
  EXPECT_EQ(open.open_rims[0].kind, Rim::Kind::cone_hole);
  SplineSurface reached = uncapped(fitted);
  options.cone_hole = cone_hole_limits(10);
  (void)cap_holes(reached, options);
  ASSERT_EQ(reached.open_rims.size(), 1u);
  EXPECT_LE(open.open_rims[0].covered_faces.size(), reached.open_rims[0].covered_faces.size());
}

}  // namespace
}  // namespace spline
