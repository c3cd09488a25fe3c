#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "ricci/mesh/flat_flips.h"
#include "ricci/mesh/primitives.h"

namespace {

// An n x n grid sheared by x += 0.9 y and triangulated along the (i, j)-(i+1, j+1) diagonals,
// which the shear makes the long ones: every interior diagonal is not Delaunay. `height` lifts
// the grid off the plane z = 0.
ricci::Mesh sheared_grid(int n, const std::function<double(double, double)>& height) {
  ricci::Mesh mesh;
  std::vector<ricci::VertexHandle> v;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      const double x = i + 0.9 * j, y = j;
      v.push_back(mesh.add_vertex({x, y, height(x, y)}));
    }
  }
  auto at = [&](int i, int j) { return v[static_cast<size_t>(j * (n + 1) + i)]; };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      mesh.add_face(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      mesh.add_face(at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
  }
  return mesh;
}

TEST(FlatFlips, PlanarGridBecomesDelaunayWithItsVerticesInPlace) {
  ricci::Mesh mesh = sheared_grid(8, [](double, double) { return 0.0; });
  const ricci::Mesh before = mesh;
  const ricci::FlatFlipResult r = ricci::flip_flat_edges_to_delaunay(mesh);
  // Every diagonal but the two at the corners (0, 0) and (8, 8), whose flip would leave the
  // corner vertex with valence 2.
  EXPECT_EQ(r.flips, 8 * 8 - 2);
  EXPECT_EQ(r.non_delaunay_left, 2);
  EXPECT_EQ(r.max_normal_angle_flipped, 0.0);
  ASSERT_EQ(mesh.n_vertices(), before.n_vertices());
  EXPECT_EQ(mesh.n_faces(), before.n_faces());
  for (auto vh : mesh.vertices()) EXPECT_EQ(mesh.point(vh), before.point(before.vertex_handle(vh.idx())));
  // Same plane, same orientation, same total area: the surface is unchanged.
  double area = 0, area_before = 0;
  for (auto f : mesh.faces()) {
    std::vector<Eigen::Vector3d> p;
    for (auto vh : mesh.fv_range(f)) p.push_back(ricci::to_eigen(mesh.point(vh)));
    const Eigen::Vector3d n = (p[1] - p[0]).cross(p[2] - p[0]);
    EXPECT_GT(n.z(), 0.0);
    area += 0.5 * n.norm();
  }
  for (auto f : before.faces()) {
    std::vector<Eigen::Vector3d> p;
    for (auto vh : before.fv_range(f)) p.push_back(ricci::to_eigen(before.point(vh)));
    area_before += 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).norm();
  }
  EXPECT_NEAR(area, area_before, 1e-12 * area_before);
}

TEST(FlatFlips, BentFacesAreLeftAlone) {
  // A parabolic sheet: neighbouring faces differ by ~0.1 rad, far above the tolerance.
  ricci::Mesh mesh = sheared_grid(8, [](double x, double) { return 0.05 * x * x; });
  const ricci::FlatFlipResult r = ricci::flip_flat_edges_to_delaunay(mesh);
  EXPECT_EQ(r.flips, 0);
  EXPECT_GT(r.non_delaunay_left, 0);
  // A wide enough tolerance flips them, and never across a larger bend than it allows.
  ricci::FlatFlipOptions wide;
  wide.max_normal_angle = 0.5;
  const ricci::FlatFlipResult w = ricci::flip_flat_edges_to_delaunay(mesh, wide);
  EXPECT_GT(w.flips, 0);
  EXPECT_LE(w.max_normal_angle_flipped, wide.max_normal_angle);
}

}  // namespace

namespace {

// A cap: the apex (0.5, 1e-4) sits just off the long edge (0,0)-(1,0), whose other face bends
// away by 60 degrees: too bent for the normal test, but the flip moves the surface by 1e-4 only.
TEST(FlatFlips, CapsFlipByTheirSmallDeviation) {
  ricci::Mesh cap;
  auto a = cap.add_vertex({0, 0, 0}), b = cap.add_vertex({1, 0, 0}), apex = cap.add_vertex({0.5, 1e-4, 0}),
       below = cap.add_vertex({0.5, -0.25, -0.43});
  auto left = cap.add_vertex({-0.5, 0.5, 0}), right = cap.add_vertex({1.5, 0.5, 0}), bottom = cap.add_vertex({0.5, -1, 0});
  cap.add_face(a, b, apex);
  cap.add_face(b, a, below);
  cap.add_face(a, apex, left);
  cap.add_face(apex, b, right);
  cap.add_face(a, left, bottom);
  cap.add_face(a, bottom, below);
  cap.add_face(below, bottom, b);
  cap.add_face(b, bottom, right);
  ricci::Mesh by_angle = cap;
  EXPECT_EQ(ricci::flip_flat_edges_to_delaunay(by_angle).flips, 0);
  ricci::FlatFlipOptions thin;
  thin.max_relative_deviation = 0.01;
  const ricci::FlatFlipResult r = ricci::flip_flat_edges_to_delaunay(cap, thin);
  EXPECT_GE(r.flips, 1);
  bool joined = false;  // the apex now reaches the vertex below the long edge
  for (auto w : cap.vv_range(apex)) joined = joined || w == below;
  EXPECT_TRUE(joined);
  // The protected vertex's edges stay.
  ricci::Mesh guarded = by_angle;
  thin.protected_vertex = apex.idx();
  thin.protected_rings = 0;
  EXPECT_EQ(ricci::flip_flat_edges_to_delaunay(guarded, thin).flips, 0);
}

}  // namespace
