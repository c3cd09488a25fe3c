#include <gtest/gtest.h>

#include "ricci/mesh/neighbourhoods.h"
#include "ricci/mesh/primitives.h"
#include "ricci/metric/subdivide.h"

namespace {

TEST(FaceNeighbourhoods, AreDisksOnAFineTorus) {
  EXPECT_EQ(ricci::count_non_disk_face_neighbourhoods(ricci::make_torus(24, 12, 2.0, 0.5)), 0);
  EXPECT_EQ(ricci::count_non_disk_face_neighbourhoods(ricci::make_disk(4, 12)), 0);
}

TEST(FaceNeighbourhoods, WrapAroundAThinTubeUntilSubdivided) {
  // Three edges around the tube: the stars of a face's corners close up around it.
  const ricci::Mesh thin = ricci::make_torus(24, 3, 2.0, 0.5);
  const int faces = static_cast<int>(thin.n_faces());
  EXPECT_EQ(ricci::count_non_disk_face_neighbourhoods(thin), faces);
  EXPECT_EQ(ricci::count_non_disk_face_neighbourhoods(ricci::subdivide_midpoint(thin)), 0);
}

}  // namespace

namespace {

TEST(LocalSubdivision, RefinesOnlyTheThinPartAndKeepsTheSurfaceClosed) {
  // A torus whose tube is three edges around: every face wraps, so the red-green refinement
  // splits them all; flag a third of them instead and check the closure leaves no T-junction.
  const ricci::Mesh thin = ricci::make_torus(24, 3, 2.0, 0.5);
  std::vector<char> refine(thin.n_faces(), 0);
  for (std::size_t f = 0; f < refine.size() / 3; ++f) refine[f] = 1;
  const ricci::Mesh out = ricci::subdivide_midpoint_locally(thin, refine);
  EXPECT_GT(out.n_faces(), thin.n_faces());
  EXPECT_LT(out.n_faces(), 4 * thin.n_faces());
  for (auto e : out.edges()) EXPECT_FALSE(out.is_boundary(e));  // closed: no T-junction cracks
  const int chi = static_cast<int>(out.n_vertices()) - static_cast<int>(out.n_edges()) +
                  static_cast<int>(out.n_faces());
  EXPECT_EQ(chi, 0);
  for (std::size_t v = 0; v < thin.n_vertices(); ++v) {
    EXPECT_EQ(out.point(out.vertex_handle(v)), thin.point(thin.vertex_handle(v)));
  }
  // Refining exactly the wrapped faces (here: all) until none is left.
  const ricci::Mesh cured =
      ricci::subdivide_midpoint_locally(thin, ricci::non_disk_face_neighbourhoods(thin));
  EXPECT_EQ(ricci::count_non_disk_face_neighbourhoods(cured), 0);
}

}  // namespace
