#include <gtest/gtest.h>

#include <string>

#include "ricci/mesh/errors.h"
#include "ricci/mesh/io.h"
#include "ricci/mesh/simplify.h"

namespace {

ricci::Mesh shared_model(const std::string& relative) {
  return ricci::read_mesh(std::string(MSP_SHARED_MODELS) + "/" + relative);
}

int euler_characteristic(const ricci::Mesh& m) {
  return static_cast<int>(m.n_vertices()) - static_cast<int>(m.n_edges()) + static_cast<int>(m.n_faces());
}

// Open scans keep a slightly worse corner at the boundary, where remeshing cannot relax freely.
void expect_simplified_with_same_topology(const std::string& model, int target, double min_angle = 5.0) {
  ricci::Mesh dense = shared_model(model);
  ricci::SimplifyOptions options;
  options.target_faces = target;
  auto r = ricci::simplify_mesh(dense, options);
  EXPECT_EQ(euler_characteristic(r.mesh), euler_characteristic(dense)) << model;
  EXPECT_NEAR(r.faces_after, target, 0.25 * target) << model;
  EXPECT_GT(r.min_angle_deg, min_angle) << model;
  for (auto v : r.mesh.vertices()) EXPECT_TRUE(r.mesh.is_manifold(v));
}

TEST(Simplify, KeepsGenusOnRealScans) {
  expect_simplified_with_same_topology("closed_g1/kitten_nf20k.off", 2000);
  expect_simplified_with_same_topology("closed_g3/genus3.off", 2000);
  expect_simplified_with_same_topology("closed_g2/cup.off", 2000);
}

TEST(Simplify, KeepsBoundariesOfOpenScans) {
  expect_simplified_with_same_topology("open/lion.off", 2000, 2.0);
}

TEST(Simplify, RefusesTinyTargets) {
  ricci::SimplifyOptions options;
  options.target_faces = 2;
  EXPECT_THROW((void)ricci::simplify_mesh(shared_model("closed_g2/eight.off"), options),
               ricci::InvalidInputError);
}

TEST(ClosestPoints, VerticesProjectOntoThemselvesAndBarycentricsRebuildThePoint) {
  ricci::Mesh mesh = shared_model("closed_g2/eight.off");
  Eigen::MatrixX3d queries(mesh.n_vertices(), 3);
  for (auto v : mesh.vertices()) queries.row(v.idx()) = ricci::to_eigen(mesh.point(v)).transpose();
  queries.array() += 1e-3;  // off the surface a little
  auto points = ricci::closest_points(mesh, queries);
  ASSERT_EQ(points.size(), mesh.n_vertices());
  for (const auto& p : points) {
    EXPECT_LT(p.distance, 2e-3);
    ricci::FaceHandle f = mesh.face_handle(p.face);
    Eigen::Vector3d rebuilt = Eigen::Vector3d::Zero();
    int k = 0;
    for (auto v : mesh.fv_range(f)) rebuilt += p.barycentric[k++] * ricci::to_eigen(mesh.point(v));
    EXPECT_LT((rebuilt - p.point).norm(), 1e-9);
    EXPECT_GT(p.barycentric.minCoeff(), -1e-9);
  }
}

}  // namespace
