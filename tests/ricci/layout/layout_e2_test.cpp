#include "ricci/layout/layout_e2.h"

#include <gtest/gtest.h>

#include <cmath>

#include "ricci/atlas/rigid_motion.h"
#include "ricci/mesh/errors.h"
#include "ricci/mesh/primitives.h"
#include "ricci/topology/cut_graph.h"
#include "ricci/topology/slice.h"
#include "ricci/topology/test_grids.h"

namespace ricci {
namespace {

TEST(LayoutE2, PlaceThirdVertexMeetsBothCirclesOnTheLeft) {
  const Eigen::Vector2d a(1.0, 2.0), b(4.0, 6.0);  // |ab| = 5
  const Eigen::Vector2d c = place_third_vertex(a, b, 3.0, 4.0);
  EXPECT_NEAR((c - a).norm(), 3.0, 1e-14);
  EXPECT_NEAR((c - b).norm(), 4.0, 1e-14);
  const Eigen::Vector2d ab = b - a, ac = c - a;
  EXPECT_GT(ab.x() * ac.y() - ab.y() * ac.x(), 0.0);
}

TEST(LayoutE2, PlanarGridIsReproducedUpToARigidMotion) {
  const Mesh grid = test::planar_grid(20, 15, 4.0, 3.0);
  const Eigen::VectorXd lengths = checked_edge_lengths(grid, {});
  const LayoutE2Result layout = layout_e2(grid, lengths);
  EXPECT_EQ(layout.flipped_faces, 0);
  EXPECT_GT(layout.min_signed_area, 0.0);
  EXPECT_LT(layout.max_relative_length_error, 1e-13);
  Eigen::MatrixX2d original(grid.n_vertices(), 2);
  for (auto v : grid.vertices()) {
    original.row(v.idx()) = Eigen::RowVector2d(grid.point(v)[0], grid.point(v)[1]);
  }
  double residual = 1.0;
  (void)fit_rigid_motion(layout.positions, original, &residual);
  EXPECT_LT(residual, 1e-12 * 5.0);
  EXPECT_LE(layout.max_vertex_angle, 2.0 * M_PI + 1e-12);
}

// Every face halfedge's developed direction is the direction of its edge vector, and it does
// not change when the lengths shrink to 1e-40 (far below the double-double positions' 1e-32 of
// a chart of size 1, where edge_vector is rounding).
TEST(LayoutE2, DevelopedDirectionsAreTheEdgeDirectionsAtAnyScale) {
  const Mesh grid = test::planar_grid(12, 9, 4.0, 3.0);
  const Eigen::VectorXd lengths = checked_edge_lengths(grid, {});
  const LayoutE2Result layout = layout_e2(grid, lengths);
  ASSERT_EQ(layout.halfedge_directions.size(), static_cast<Eigen::Index>(grid.n_halfedges()));
  int checked = 0;
  for (auto h : grid.halfedges()) {
    if (!grid.face_handle(h).is_valid()) continue;
    const Eigen::Vector2d v = layout.edge_vector(grid.from_vertex_handle(h).idx(),
                                                 grid.to_vertex_handle(h).idx());
    const double angle = std::atan2(v.y(), v.x());
    EXPECT_LT(std::abs(std::remainder(layout.halfedge_directions[h.idx()] - angle, 2 * M_PI)),
              1e-13);
    ++checked;
  }
  EXPECT_EQ(checked, 3 * static_cast<int>(grid.n_faces()));
  const LayoutE2Result tiny = layout_e2(grid, 1e-40 * lengths);
  EXPECT_LT((tiny.halfedge_directions - layout.halfedge_directions).cwiseAbs().maxCoeff(), 1e-14);
}

TEST(LayoutE2, ScalingTheLengthsScalesTheLayout) {
  const Mesh grid = test::planar_grid(8, 8, 1.0, 1.0);
  const Eigen::VectorXd lengths = checked_edge_lengths(grid, {});
  LayoutE2Options options;
  options.seed_face = 5;
  const LayoutE2Result small = layout_e2(grid, lengths, options);
  for (double scale : {1e-8, 1e8}) {
    const LayoutE2Result big = layout_e2(grid, scale * lengths, options);
    EXPECT_LT((big.positions / scale - small.positions).cwiseAbs().maxCoeff(), 1e-13);
    EXPECT_LT(big.max_relative_length_error, 1e-13);
  }
}

TEST(LayoutE2, FlatTorusFundamentalDomainIsExact) {
  const int nx = 16, ny = 12;
  const Mesh torus = make_flat_torus_grid(nx, ny, 4.0, 3.0);
  const Eigen::VectorXd lengths = flat_torus_edge_lengths(torus, nx, ny, 4.0, 3.0);
  const CutGraph cut = compute_cut_graph(torus, VertexHandle(0), lengths);
  const SlicedMesh disk = slice_along(torus, cut.is_cut_edge);
  check_disk(disk);
  const LayoutE2Result layout = layout_e2(disk.mesh, sliced_edge_lengths(disk, lengths));
  EXPECT_EQ(layout.flipped_faces, 0);
  EXPECT_LT(layout.max_relative_length_error, 1e-12);
  // The sliced torus covers one period: its area is width * height.
  double area = 0.0;
  for (auto f : disk.mesh.faces()) {
    const auto h = disk.mesh.halfedge_handle(f);
    const Eigen::Vector2d a = layout.positions.row(disk.mesh.from_vertex_handle(h).idx());
    const Eigen::Vector2d b = layout.positions.row(disk.mesh.to_vertex_handle(h).idx());
    const Eigen::Vector2d c =
        layout.positions.row(disk.mesh.to_vertex_handle(disk.mesh.next_halfedge_handle(h)).idx());
    area += 0.5 * ((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
  }
  EXPECT_NEAR(area, 12.0, 1e-11);
  EXPECT_LE(layout.max_vertex_angle, 2.0 * M_PI + 1e-12);
}

// A planar strip of 2n needles (rungs 1e-5 against a spacing of 1, jittered), whose growth
// crosses a rung, the needles' short edge, every second face: the rounding of a direction taken
// from the rung's end positions would be multiplied by l/d = 1e5 at each rung.
Mesh needle_strip(int n, double height) {
  Mesh mesh;
  for (int i = 0; i <= n; ++i) {
    const double x = i + 0.2 * std::sin(1.7 * i);
    mesh.add_vertex(Mesh::Point(x, 0.0, 0.0));
    mesh.add_vertex(Mesh::Point(x + 0.1 * std::cos(1.3 * i), height * (1.0 + 0.5 * std::sin(2.3 * i)), 0.0));
  }
  for (int i = 0; i < n; ++i) {
    mesh.add_face(VertexHandle(2 * i), VertexHandle(2 * i + 2), VertexHandle(2 * i + 1));
    mesh.add_face(VertexHandle(2 * i + 2), VertexHandle(2 * i + 3), VertexHandle(2 * i + 1));
  }
  return mesh;
}

// Residual of the best rigid motion from the layout to the strip's own plane, over its length.
double strip_residual(const Mesh& strip, const LayoutE2Result& layout, int n) {
  Eigen::MatrixX2d original(strip.n_vertices(), 2);
  for (auto v : strip.vertices()) {
    original.row(v.idx()) = Eigen::RowVector2d(strip.point(v)[0], strip.point(v)[1]);
  }
  double residual = 1.0;
  (void)fit_rigid_motion(layout.positions, original, &residual);
  return residual / n;
}

TEST(LayoutE2, AChainOfNeedlesCrossedByTheirShortEdgesKeepsItsDigits) {
  const int n = 2000;
  const Mesh strip = needle_strip(n, 1e-5);
  const Eigen::VectorXd lengths = checked_edge_lengths(strip, {});
  LayoutE2Options options;
  options.seed_face = 0;  // the longest path: 4000 faces, 2000 rungs
  const LayoutE2Result layout = layout_e2(strip, lengths, options);
  EXPECT_EQ(layout.flipped_faces, 0);
  // Positions from directions carried across the faces: 2.7e-15 (directions from the rungs'
  // end positions, as the growth did before: 2.8e-12).
  EXPECT_LT(layout.max_relative_length_error, 1e-14);
  // The double lengths themselves are not flat to better than ~1e-16 l/d per needle: the strip
  // is reproduced to 2.3e-11 of its length (2.9e-10 before).
  EXPECT_LT(strip_residual(strip, layout, n), 1e-10);

  // Its lengths in long double (hi + lo from the same positions): flat to ~1e-19 l/d; the strip
  // is reproduced to 4.1e-14 of its length.
  Eigen::VectorXd hi(strip.n_edges()), lo(strip.n_edges());
  for (auto e : strip.edges()) {
    const auto h = strip.halfedge_handle(e, 0);
    const auto a = strip.point(strip.from_vertex_handle(h)), b = strip.point(strip.to_vertex_handle(h));
    const long double l = std::hypot(static_cast<long double>(a[0]) - b[0], static_cast<long double>(a[1]) - b[1]);
    hi[e.idx()] = static_cast<double>(l);
    lo[e.idx()] = static_cast<double>(l - hi[e.idx()]);
  }
  const LayoutE2Result exact = layout_e2(strip, hi, lo, options);
  EXPECT_EQ(exact.flipped_faces, 0);
  EXPECT_LT(strip_residual(strip, exact, n), 2e-13);
  EXPECT_THROW((void)layout_e2(strip, hi, lo.head(3), options), InvalidInputError);
}

TEST(LayoutE2, DevelopDirectionsTurnsByTheCornerAngles) {
  // The 3-4-5 triangle a = (0, 0), b = (4, 0), w = (4, 3): a->w at atan(3/4), b->w at pi/2.
  const DevelopedDirections d = develop_directions(0.0L, 4.0L, 5.0L, 3.0L);
  EXPECT_NEAR(static_cast<double>(d.a_to_w), std::atan2(3.0, 4.0), 1e-15);
  EXPECT_NEAR(static_cast<double>(d.b_to_w), M_PI / 2.0, 1e-15);
  const DevelopedDirections turned = develop_directions(1.0L, 4.0L, 5.0L, 3.0L);
  EXPECT_NEAR(static_cast<double>(turned.a_to_w - d.a_to_w), 1.0, 1e-15);
}

TEST(LayoutE2, BadInputThrows) {
  const Mesh grid = test::planar_grid(3, 3, 1.0, 1.0);
  Eigen::VectorXd lengths = checked_edge_lengths(grid, {});
  EXPECT_THROW((void)layout_e2(grid, lengths.head(4)), InvalidInputError);
  lengths[0] = 10.0;  // breaks the triangle inequality of its faces
  EXPECT_THROW((void)layout_e2(grid, lengths), InvalidInputError);
  LayoutE2Options options;
  options.seed_face = 1000;
  EXPECT_THROW((void)layout_e2(grid, checked_edge_lengths(grid, {}), options), InvalidInputError);
}

}  // namespace
}  // namespace ricci
