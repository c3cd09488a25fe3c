// rebuild_boundary_bands: a coarse disk against a dense one whose rim is a zigzag of
// one-triangle teeth (mech-holes-shark.off's boundary in the plane) ends with the dense loop's
// own vertices as its boundary, every face still facing up, the topology kept; a boundary the
// coarse mesh already follows is left alone.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <set>
#include <vector>

#include <Eigen/Geometry>

#include "ricci/mesh/boundary_band.h"
#include "ricci/mesh/boundary_loops.h"
#include "ricci/mesh/errors.h"
#include "ricci/mesh/primitives.h"

namespace ricci {
namespace {

// make_disk(rings, sectors) with a tooth on every boundary edge: a triangle whose tip lies
// `height` outside the edge's midpoint, so the boundary runs notch, tip, notch, ...
Mesh toothed_disk(int rings, int sectors, double height) {
  Mesh disk = make_disk(rings, sectors);
  std::vector<HalfedgeHandle> rim;
  for (auto h : disk.halfedges())
    if (disk.is_boundary(h)) rim.push_back(h);
  for (auto h : rim) {
    const auto a = disk.from_vertex_handle(h), b = disk.to_vertex_handle(h);
    const Eigen::Vector3d mid = 0.5 * (to_eigen(disk.point(a)) + to_eigen(disk.point(b)));
    const auto tip = disk.add_vertex(to_openmesh(mid + height * mid.normalized()));
    EXPECT_TRUE(disk.add_face(a, b, tip).is_valid());  // on the face-less halfedge a -> b
  }
  return disk;
}

// The smallest z component of a face's unit normal, and the flattest shape (twice the area
// over the longest edge squared).
std::array<double, 2> worst_faces(const Mesh& mesh) {
  std::array<double, 2> worst{1.0, 1.0};
  for (auto f : mesh.faces()) {
    std::array<Eigen::Vector3d, 3> p;
    int k = 0;
    for (auto v : mesh.fv_range(f)) p[static_cast<std::size_t>(k++)] = to_eigen(mesh.point(v));
    const Eigen::Vector3d n = (p[1] - p[0]).cross(p[2] - p[0]);
    const double longest = std::max(
        {(p[1] - p[0]).squaredNorm(), (p[2] - p[1]).squaredNorm(), (p[0] - p[2]).squaredNorm()});
    worst[0] = std::min(worst[0], n.normalized().z());
    worst[1] = std::min(worst[1], n.norm() / longest);
  }
  return worst;
}

std::set<std::array<double, 3>> boundary_points(const Mesh& mesh) {
  std::set<std::array<double, 3>> points;
  for (auto v : mesh.vertices())
    if (mesh.is_boundary(v)) {
      const auto p = mesh.point(v);
      points.insert({p[0], p[1], p[2]});
    }
  return points;
}

TEST(BoundaryBand, AToothedRimIsRebuiltFromTheDenseLoopsVertices) {
  const Mesh dense = toothed_disk(16, 3, 0.08);  // 48 teeth 0.08 high, 0.13 apart
  ASSERT_EQ(find_boundary_loops(dense).size(), 1u);
  ASSERT_GT(worst_faces(dense)[0], 0.99);
  Mesh coarse = make_disk(3, 6);  // 18 boundary vertices on the unit circle
  const int faces_before = static_cast<int>(coarse.n_faces());
  const BoundaryBandResult r = rebuild_boundary_bands(coarse, dense);
  EXPECT_EQ(r.loops_rebuilt, 1);
  EXPECT_EQ(r.faces_removed, 30);  // the outer ring of make_disk(3, 6)
  EXPECT_EQ(static_cast<int>(coarse.n_faces()), faces_before - r.faces_removed + r.faces_added);
  EXPECT_EQ(euler_characteristic(coarse), 1);
  EXPECT_EQ(find_boundary_loops(coarse).size(), 1u);
  const auto [lowest_normal, flattest] = worst_faces(coarse);
  EXPECT_GT(lowest_normal, 0.99);  // no face turned over, none on its edge
  EXPECT_GE(flattest, BoundaryBandOptions{}.min_shape);
  // No three consecutive dense boundary vertices are collinear, so the thinning keeps them all:
  // every tip and notch is a boundary vertex of the rebuilt mesh, and nothing else is.
  EXPECT_EQ(boundary_points(coarse), boundary_points(dense));
}

TEST(BoundaryBand, AFollowedBoundaryIsLeftAlone) {
  const Mesh dense = make_disk(12, 6);
  Mesh coarse = make_disk(12, 6);
  const int faces = static_cast<int>(coarse.n_faces());
  EXPECT_EQ(rebuild_boundary_bands(coarse, dense).loops_rebuilt, 0);
  EXPECT_EQ(static_cast<int>(coarse.n_faces()), faces);
  BoundaryBandOptions bad;
  bad.tolerance = 0.0;
  EXPECT_THROW((void)rebuild_boundary_bands(coarse, dense, bad), InvalidInputError);
}

}  // namespace
}  // namespace ricci
