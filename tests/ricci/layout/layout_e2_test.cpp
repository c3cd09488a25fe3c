#include "ricci/layout/layout_e2.h"

#include <gtest/gtest.h>

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
