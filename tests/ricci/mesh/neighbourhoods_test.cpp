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
