#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "ricci/mesh/errors.h"
#include "ricci/mesh/io.h"
#include "ricci/quality/distortion.h"
#include "test_paths.h"

namespace {

Eigen::VectorXd own_lengths(const ricci::Mesh& mesh) {
  Eigen::VectorXd l(mesh.n_edges());
  for (auto e : mesh.edges()) l[e.idx()] = mesh.calc_edge_length(e);
  return l;
}

ricci::Mesh eight() { return ricci::read_mesh(msp_test::test_mesh("closed_g2/eight.off")); }

TEST(Distortion, OwnMetricHasNoDistortion) {
  auto mesh = eight();
  auto r = ricci::measure_distortion(mesh, own_lengths(mesh));
  EXPECT_EQ(r.faces, static_cast<int>(mesh.n_faces()));
  EXPECT_NEAR(r.area_distortion, 0.0, 1e-20);
  EXPECT_NEAR(r.angle_ratio_p05, 1.0, 1e-12);
  EXPECT_NEAR(r.angle_ratio_p95, 1.0, 1e-12);
  EXPECT_NEAR(r.quasi_conformal_max, 1.0, 1e-9);
}

TEST(Distortion, UniformScalingIsConformalAndAreaPreservingAfterNormalisation) {
  auto mesh = eight();
  auto r = ricci::measure_distortion(mesh, 1e3 * own_lengths(mesh));
  EXPECT_NEAR(r.area_distortion, 0.0, 1e-20);
  EXPECT_NEAR(r.quasi_conformal_mean, 1.0, 1e-9);
}

TEST(Distortion, ScalingOneRegionGivesTheExpectedAreaDistortion) {
  // Conformal (per-vertex) scaling by e^{u} with u = 0 or 1 on half the vertices: faces fully in
  // the scaled half grow by e^2 and keep their angles.
  auto mesh = eight();
  Eigen::VectorXd l = own_lengths(mesh);
  Eigen::VectorXd scaled = l;
  for (auto e : mesh.edges()) {
    auto h = mesh.halfedge_handle(e, 0);
    bool a = mesh.point(mesh.from_vertex_handle(h))[0] > 0;
    bool b = mesh.point(mesh.to_vertex_handle(h))[0] > 0;
    scaled[e.idx()] *= std::exp(0.5 * (a + b) * 0.01);
  }
  auto r = ricci::measure_distortion(mesh, scaled);
  EXPECT_GT(r.area_distortion, 0.0);
  EXPECT_LT(r.area_distortion, 1e-3);
  EXPECT_LT(r.quasi_conformal_max, 1.02);
}

TEST(Distortion, AffineStretchIsMeasuredExactly) {
  // Stretch every vertex by 2 along x: faces in the yz plane distort with ratio up to 2.
  auto mesh = eight();
  ricci::Mesh stretched = mesh;
  for (auto v : stretched.vertices()) stretched.point(v)[0] *= 2.0;
  auto r = ricci::measure_distortion(mesh, own_lengths(stretched));
  EXPECT_LE(r.quasi_conformal_max, 2.0 + 1e-9);
  EXPECT_GT(r.quasi_conformal_max, 1.5);
}

TEST(Distortion, WrongSizeAndDegenerateMetricsAreRefused) {
  auto mesh = eight();
  EXPECT_THROW((void)ricci::measure_distortion(mesh, Eigen::VectorXd::Ones(3)), ricci::InvalidInputError);
  Eigen::VectorXd l = own_lengths(mesh);
  l[0] = 1e6;
  EXPECT_THROW((void)ricci::measure_distortion(mesh, l), ricci::InvalidInputError);
}

// With skip_degenerate the faces of edge 0 (broken by a huge length) are left out and counted;
// the others are measured as before.
TEST(Distortion, DegenerateFacesAreCountedWhenSkipped) {
  auto mesh = eight();
  Eigen::VectorXd l = own_lengths(mesh);
  l[0] = 1e6;
  ricci::DistortionOptions options;
  options.skip_degenerate = true;
  const auto r = ricci::measure_distortion(mesh, l, options);
  EXPECT_EQ(r.skipped_faces, 2);
  EXPECT_EQ(r.faces, static_cast<int>(mesh.n_faces()) - 2);
  EXPECT_NEAR(r.quasi_conformal_max, 1.0, 1e-9);
}

}  // namespace
