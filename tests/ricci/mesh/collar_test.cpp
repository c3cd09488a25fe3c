// add_boundary_collar: ghost rings outside the boundary keep the topology, the orientation and
// the original faces, lie in the tangent plane, and leave closed meshes alone.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <Eigen/Geometry>

#include "ricci/mesh/boundary_follow.h"
#include "ricci/mesh/collar.h"
#include "ricci/mesh/errors.h"
#include "ricci/mesh/io.h"
#include "ricci/mesh/primitives.h"
#include "ricci/mesh/simplify.h"
#include "test_paths.h"

namespace ricci {
namespace {

int boundary_vertices(const Mesh& mesh) {
  int count = 0;
  for (auto v : mesh.vertices()) count += mesh.is_boundary(v);
  return count;
}

double min_area(const Mesh& mesh) {
  double smallest = INFINITY;
  for (auto f : mesh.faces()) {
    std::array<Eigen::Vector3d, 3> p;
    int k = 0;
    for (auto v : mesh.fv_range(f)) p[static_cast<std::size_t>(k++)] = to_eigen(mesh.point(v));
    smallest = std::min(smallest, 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).z());
  }
  return smallest;
}

TEST(BoundaryCollar, AnAnnulusKeepsItsTopologyAndGrowsOutwardsInItsPlane) {
  const Mesh annulus = make_annulus(4, 24, 0.5, 1.0);
  const int b = boundary_vertices(annulus);  // both circles
  const CollarResult collar = add_boundary_collar(annulus);
  const Mesh& m = collar.mesh;
  EXPECT_EQ(collar.original_faces, static_cast<int>(annulus.n_faces()));
  EXPECT_EQ(static_cast<int>(m.n_faces()), collar.original_faces + 2 * 2 * b);
  EXPECT_EQ(static_cast<int>(m.n_vertices()), collar.original_vertices + 2 * b);
  // Euler characteristic and boundary count kept (annulus: chi = 0, two loops).
  const int chi = static_cast<int>(m.n_vertices()) - static_cast<int>(m.n_edges()) +
                  static_cast<int>(m.n_faces());
  EXPECT_EQ(chi, 0);
  EXPECT_EQ(boundary_vertices(m), b);
  // Original faces and positions untouched; rings numbered outwards.
  for (int f = 0; f < collar.original_faces; ++f) EXPECT_EQ(collar.ring[f], 0);
  for (int f = collar.original_faces; f < static_cast<int>(m.n_faces()); ++f) {
    EXPECT_GE(collar.ring[f], 1);
    EXPECT_LE(collar.ring[f], 2);
  }
  for (auto v : annulus.vertices()) EXPECT_EQ(m.point(v), annulus.point(v));
  // Planar input: the collar stays in z = 0, counter-clockwise like the annulus (no fold), and
  // every new vertex is outside the annulus' ring: radius < 0.5 or > 1.
  EXPECT_GT(min_area(m), 0.0);
  for (int v = collar.original_vertices; v < static_cast<int>(m.n_vertices()); ++v) {
    const Eigen::Vector3d p = to_eigen(m.point(VertexHandle(v)));
    EXPECT_EQ(p.z(), 0.0);
    const double r = std::hypot(p.x(), p.y());
    EXPECT_TRUE(r < 0.5 - 1e-3 || r > 1.0 + 1e-3) << r;
  }
}

TEST(BoundaryCollar, ClosedMeshesComeBackUnchangedAndBadOptionsThrow) {
  const Mesh sphere = make_icosphere(1);
  const CollarResult collar = add_boundary_collar(sphere);
  EXPECT_EQ(collar.mesh.n_faces(), sphere.n_faces());
  EXPECT_EQ(collar.mesh.n_vertices(), sphere.n_vertices());
  CollarOptions bad;
  bad.rings = 0;
  EXPECT_THROW((void)add_boundary_collar(sphere, bad), InvalidInputError);
  bad.rings = 1;
  bad.width = 0.0;
  EXPECT_THROW((void)add_boundary_collar(sphere, bad), InvalidInputError);
}

}  // namespace
}  // namespace ricci

// follow_boundary: a coarse disk (2 rings, 16 boundary vertices) against a fine one (12 rings,
// 96): the coarse chords lie 1 - cos(pi / 16) = 0.019 from the unit circle, 0.68% of the
// diagonal; splitting the boundary edges brings both boundaries within the tolerance.
namespace ricci {
namespace {

TEST(FollowBoundary, ACoarseCircleFollowsAFineOneWithinTheTolerance) {
  const Mesh fine = make_disk(12, 8);
  Mesh coarse = make_disk(2, 8);
  const auto faces_before = coarse.n_faces();
  BoundaryFollowOptions options;
  options.tolerance = 0.002;
  const BoundaryFollowResult r = follow_boundary(coarse, fine, options);
  EXPECT_GT(r.distance_before, 0.006);
  EXPECT_LE(r.distance_after, options.tolerance);
  EXPECT_GT(r.splits, 0);
  EXPECT_EQ(coarse.n_faces(), faces_before + static_cast<std::size_t>(r.splits));
  // Still a planar disk, counter-clockwise (nothing folded), chi = 1.
  EXPECT_GT(min_area(coarse), 0.0);
  const int chi = static_cast<int>(coarse.n_vertices()) - static_cast<int>(coarse.n_edges()) +
                  static_cast<int>(coarse.n_faces());
  EXPECT_EQ(chi, 1);
  // Closed meshes: nothing to follow.
  Mesh sphere = make_icosphere(1);
  EXPECT_EQ(follow_boundary(sphere, fine).splits, 0);
  EXPECT_THROW((void)follow_boundary(coarse, fine, BoundaryFollowOptions{0.0, 3}),
               InvalidInputError);
}

}  // namespace
}  // namespace ricci

// follow_boundary checks every move and split against the faces' normals before it began, so
// that steps each within the bound cannot add up to a face turned over: on mech-holes-shark.off
// (a coarse scan whose boundary zigzags across a crease) checks against the current normals
// left needles along the boundary, pairs of faces pointing opposite ways.
namespace ricci {
namespace {

int edges_over_120_deg(const Mesh& mesh) {
  int count = 0;
  for (auto e : mesh.edges()) {
    if (mesh.is_boundary(e)) continue;
    const auto h = mesh.halfedge_handle(e, 0);
    const auto normal = [&](HalfedgeHandle g) {
      std::array<Eigen::Vector3d, 3> p;
      int k = 0;
      for (auto v : mesh.fv_range(mesh.face_handle(g)))
        p[static_cast<std::size_t>(k++)] = to_eigen(mesh.point(v));
      return Eigen::Vector3d((p[1] - p[0]).cross(p[2] - p[0]).normalized());
    };
    count += normal(h).dot(normal(mesh.opposite_halfedge_handle(h))) < -0.5;
  }
  return count;
}

TEST(FollowBoundary, NoFaceTurnsOverOnAZigzagBoundary) {
  const Mesh dense = read_mesh(msp_test::test_mesh("open/mech-holes-shark.off.gz"));
  SimplifyOptions simplify;
  simplify.target_faces = 2000;
  Mesh coarse = simplify_mesh(dense, simplify).mesh;
  ASSERT_EQ(edges_over_120_deg(coarse), 0);
  const BoundaryFollowResult r = follow_boundary(coarse, dense);
  EXPECT_GT(r.splits, 100);
  // The splits leave the outer loop's zigzag tangled (0.76%); its band is rebuilt.
  EXPECT_EQ(r.loops_rebuilt, 1);
  EXPECT_LT(r.distance_after, BoundaryFollowOptions{}.band.rebuild_above);
  EXPECT_EQ(edges_over_120_deg(coarse), 0);
}

}  // namespace
}  // namespace ricci

// follow_boundary spreads boundary vertices that bunch along the dense boundary: a coarse disk
// whose odd boundary vertices were slid along the circle to 0.15 of a gap from their even
// neighbour (the pairs a zigzag scan's V-notches leave) comes back with every gap at least a
// third of the mean, still on the circle, no face turned; without `spread` the pairs stay.
namespace ricci {
namespace {

std::vector<double> sorted_boundary_angles(const Mesh& mesh) {
  std::vector<double> angles;
  for (auto v : mesh.vertices()) {
    if (!mesh.is_boundary(v)) continue;
    const auto p = mesh.point(v);
    angles.push_back(std::atan2(p[1], p[0]));
  }
  std::sort(angles.begin(), angles.end());
  return angles;
}

double smallest_gap(const std::vector<double>& sorted) {
  double gap = sorted.front() + 2.0 * M_PI - sorted.back();
  for (std::size_t i = 1; i < sorted.size(); ++i) gap = std::min(gap, sorted[i] - sorted[i - 1]);
  return gap;
}

Mesh bunched_disk() {
  Mesh disk = make_disk(4, 8);  // 32 boundary vertices on the unit circle
  const double gap = 2.0 * M_PI / 32.0;
  for (auto v : disk.vertices()) {
    if (!disk.is_boundary(v)) continue;
    const auto p = disk.point(v);
    const double angle = std::atan2(p[1], p[0]);
    const long k = std::lround(angle / gap);
    if (k % 2 == 0) continue;
    const double moved = static_cast<double>(k - 1) * gap + 0.15 * gap;
    disk.set_point(v, Mesh::Point(std::cos(moved), std::sin(moved), 0.0));
  }
  return disk;
}

TEST(FollowBoundary, BunchedBoundaryVerticesAreSpreadAlongTheDenseBoundary) {
  const Mesh fine = make_disk(24, 8);
  const double mean = 2.0 * M_PI / 32.0;
  BoundaryFollowOptions options;
  options.tolerance = 0.05;  // wide: no split, only the moves
  options.max_rounds = 1;
  options.band.rebuild_above = 0.0;  // no band rebuilt
  Mesh kept = bunched_disk();
  ASSERT_GT(min_area(kept), 0.0);
  ASSERT_LT(smallest_gap(sorted_boundary_angles(kept)), 0.2 * mean);
  options.spread = false;
  EXPECT_EQ(follow_boundary(kept, fine, options).spread, 0);
  EXPECT_LT(smallest_gap(sorted_boundary_angles(kept)), 0.2 * mean);

  Mesh spread = bunched_disk();
  options.spread = true;
  const BoundaryFollowResult r = follow_boundary(spread, fine, options);
  EXPECT_EQ(r.splits, 0);
  EXPECT_GT(r.spread, 0);
  EXPECT_GE(smallest_gap(sorted_boundary_angles(spread)), mean / 3.0 - 1e-9);
  EXPECT_GT(min_area(spread), 0.0);
  for (auto v : spread.vertices()) {
    if (!spread.is_boundary(v)) continue;
    const auto p = spread.point(v);
    EXPECT_NEAR(std::hypot(p[0], p[1]), 1.0, 0.01);  // on the fine circle's chords
  }
}

}  // namespace
}  // namespace ricci
