// cap_holes without patches (CapHolesOptions::make_patches false, how fit_surface judges a fit
// round before only the delivered one is capped): the rims are those the capping starts from,
// their faces are skipped, nothing is filled, and the tessellation is open exactly there.
#include <gtest/gtest.h>

#include <vector>

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

}  // namespace
}  // namespace spline
