// cap_small_holes: loops narrower than the limit get triangles of their own vertices (genus
// kept, one loop fewer each, oriented as the surface), wider loops and closed meshes stay.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "ricci/mesh/arrays.h"
#include "ricci/mesh/errors.h"
#include "ricci/mesh/primitives.h"
#include "ricci/mesh/small_holes.h"

namespace ricci {
namespace {

// The icosphere without the faces listed (each removal a hole of the faces' outline).
Mesh sphere_without(const std::vector<int>& removed) {
  const Mesh sphere = make_icosphere(3);
  const VertexFaceArrays a = to_arrays(sphere);
  Eigen::MatrixX3i F(a.F.rows() - static_cast<Eigen::Index>(removed.size()), 3);
  Eigen::Index row = 0;
  for (Eigen::Index f = 0; f < a.F.rows(); ++f) {
    if (std::find(removed.begin(), removed.end(), static_cast<int>(f)) == removed.end())
      F.row(row++) = a.F.row(f);
  }
  return from_arrays(a.V, F);
}

// Faces whose normal points away from the centre (the sphere is centred at the origin).
int outward_faces(const Mesh& mesh) {
  int count = 0;
  for (auto f : mesh.faces()) {
    std::vector<Eigen::Vector3d> p;
    for (auto v : mesh.fv_range(f)) p.push_back(to_eigen(mesh.point(v)));
    count += (p[1] - p[0]).cross(p[2] - p[0]).dot(p[0] + p[1] + p[2]) > 0;
  }
  return count;
}

TEST(SmallHoles, AMissingTriangleAndAMissingPairAreCappedInTheSurfacesOrientation) {
  const Mesh sphere = make_icosphere(3);
  // Face 0 alone; two faces sharing an edge (a 4-edge hole) somewhere else.
  int pair_a = -1, pair_b = -1;
  for (auto f : sphere.faces()) {
    for (auto g : sphere.ff_range(f)) {
      bool touches_0 = false;
      for (auto v : sphere.fv_range(sphere.face_handle(0)))
        for (auto w : sphere.fv_range(f)) touches_0 |= v == w;
      for (auto v : sphere.fv_range(sphere.face_handle(0)))
        for (auto w : sphere.fv_range(g)) touches_0 |= v == w;
      if (!touches_0 && pair_a < 0) {
        pair_a = f.idx();
        pair_b = g.idx();
      }
    }
  }
  ASSERT_GE(pair_a, 0);
  const Mesh holed = sphere_without({0, pair_a, pair_b});
  ASSERT_EQ(surface_topology(holed).boundary_loops, 2);
  const SmallHoleCaps capped = cap_small_holes(holed, {0.5});
  EXPECT_EQ(capped.capped_loops, 2);
  EXPECT_EQ(capped.cap_faces, 3);
  EXPECT_EQ(capped.mesh.n_vertices(), holed.n_vertices());
  const SurfaceTopology t = surface_topology(capped.mesh);
  EXPECT_EQ(t.boundary_loops, 0);
  EXPECT_EQ(t.genus, 0);
  EXPECT_EQ(outward_faces(capped.mesh), static_cast<int>(capped.mesh.n_faces()));
  int flagged = 0;
  for (char c : capped.capped_vertex) flagged += c;
  EXPECT_EQ(flagged, 3 + 4);
  EXPECT_GT(capped.largest_diameter, 0.0);
  EXPECT_LT(capped.largest_diameter, 0.5);
}

TEST(SmallHoles, LoopsWiderThanTheLimitAndClosedMeshesStay) {
  const Mesh holed = sphere_without({0});
  // The hole's diameter is one edge of a 3-times subdivided unit icosphere (~0.19, 5% of the
  // diagonal 2 sqrt 3): a limit of 1% keeps it.
  const SmallHoleCaps kept = cap_small_holes(holed, {0.01});
  EXPECT_EQ(kept.capped_loops, 0);
  EXPECT_EQ(kept.largest_diameter, 0.0);
  EXPECT_EQ(surface_topology(kept.mesh).boundary_loops, 1);
  const SmallHoleCaps none = cap_small_holes(holed, {0.0});
  EXPECT_EQ(none.capped_loops, 0);
  const SmallHoleCaps closed = cap_small_holes(make_icosphere(2), {0.5});
  EXPECT_EQ(closed.capped_loops, 0);
  EXPECT_EQ(closed.mesh.n_faces(), make_icosphere(2).n_faces());
}

TEST(SmallHoles, ANegativeOrInfiniteLimitThrows) {
  const Mesh holed = sphere_without({0});
  EXPECT_THROW((void)cap_small_holes(holed, {-0.1}), InvalidInputError);
  EXPECT_THROW((void)cap_small_holes(holed, {INFINITY}), InvalidInputError);
}

}  // namespace
}  // namespace ricci
