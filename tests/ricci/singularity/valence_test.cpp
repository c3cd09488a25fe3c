#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "ricci/mesh/errors.h"
#include "ricci/mesh/io.h"
#include "ricci/singularity/valence.h"
#include "test_paths.h"

namespace {

using ricci::Mesh;

double angle_sum(const Mesh& mesh, ricci::VertexHandle v) {
  double sum = 0;
  for (auto h : mesh.voh_range(v)) {
    if (mesh.is_boundary(h)) continue;
    auto a = mesh.point(mesh.to_vertex_handle(h)) - mesh.point(v);
    auto b = mesh.point(mesh.to_vertex_handle(mesh.next_halfedge_handle(h))) - mesh.point(v);
    sum += std::atan2(OpenMesh::cross(a, b).norm(), OpenMesh::dot(a, b));
  }
  return sum;
}

double total_area(const Mesh& mesh) {
  double area = 0;
  for (auto f : mesh.faces()) area += mesh.calc_face_area(f);
  return area;
}

Mesh read_test_mesh(const std::string& relative) {
  return ricci::read_mesh(msp_test::test_mesh(relative));
}

TEST(Valence, RequiredConeValenceFollowsThePaperBound) {
  EXPECT_EQ(ricci::required_cone_valence(-4 * M_PI), 12);  // genus 2
  EXPECT_EQ(ricci::required_cone_valence(-8 * M_PI), 20);  // genus 3
  EXPECT_EQ(ricci::required_cone_valence(0.0), 4);         // genus 1
}

void expect_geometry_kept(const Mesh& before, const ricci::ValenceResult& r) {
  EXPECT_NEAR(total_area(r.mesh), total_area(before), 1e-12 * total_area(before));
  EXPECT_EQ(euler_characteristic(r.mesh), euler_characteristic(before));
  EXPECT_EQ(static_cast<int>(r.mesh.n_vertices()), static_cast<int>(before.n_vertices()) + r.splits);
  for (auto v : before.vertices()) {
    EXPECT_NEAR(angle_sum(r.mesh, v), angle_sum(before, v), 1e-9) << "vertex " << v.idx();
  }
  for (int i = static_cast<int>(before.n_vertices()); i < static_cast<int>(r.mesh.n_vertices()); ++i) {
    EXPECT_NEAR(angle_sum(r.mesh, r.mesh.vertex_handle(i)), 2 * M_PI, 1e-9) << "new vertex " << i;
  }
  for (auto v : r.mesh.vertices()) EXPECT_TRUE(r.mesh.is_manifold(v));
}

TEST(Valence, Genus2ConeReachesTwelveNeighboursWithGeometryUnchanged) {
  Mesh mesh = read_test_mesh("closed_g2/eight.off");
  ricci::ValenceOptions options;
  options.cone_curvature = -4 * M_PI;
  auto r = ricci::modify_valence(mesh, mesh.vertex_handle(0), options);
  EXPECT_GE(r.cone_valence_after, 12);
  EXPECT_GT(r.splits, 0);
  EXPECT_EQ(r.ring_vertices_below, 0);
  for (auto q : ricci::ring_neighbourhood(r.mesh, r.cone, 3)) {
    if (q.idx() < static_cast<int>(mesh.n_vertices())) {
      EXPECT_GE(r.mesh.valence(q), 6u);
    }
  }
  expect_geometry_kept(mesh, r);
}

TEST(Valence, Genus3ConeReachesTwentyNeighbours) {
  Mesh mesh = read_test_mesh("closed_g3/helmet.off");
  ricci::ValenceOptions options;
  options.cone_curvature = -8 * M_PI;
  auto r = ricci::modify_valence(mesh, mesh.vertex_handle(17), options);
  EXPECT_GE(r.cone_valence_after, 20);
  expect_geometry_kept(mesh, r);
}

TEST(Valence, NothingToDoLeavesTheMeshAlone) {
  Mesh mesh = read_test_mesh("closed_g1/knot1.off.gz");
  ricci::ValenceOptions options;
  options.ring_valence = 0;
  auto r = ricci::modify_valence(mesh, mesh.vertex_handle(0), options);
  EXPECT_EQ(r.splits, 0);
  EXPECT_EQ(r.mesh.n_vertices(), mesh.n_vertices());
}

TEST(Valence, BoundaryOrMissingConeIsRefused) {
  Mesh mesh = read_test_mesh("open/head.off");
  ricci::VertexHandle boundary_vertex;
  for (auto v : mesh.vertices()) {
    if (mesh.is_boundary(v)) {
      boundary_vertex = v;
      break;
    }
  }
  ASSERT_TRUE(boundary_vertex.is_valid());
  EXPECT_THROW((void)ricci::modify_valence(mesh, boundary_vertex), ricci::InvalidInputError);
  EXPECT_THROW((void)ricci::modify_valence(mesh, ricci::VertexHandle(1 << 30)), ricci::InvalidInputError);
}

}  // namespace
