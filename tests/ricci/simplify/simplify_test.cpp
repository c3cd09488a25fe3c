#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "ricci/mesh/arrays.h"
#include "ricci/mesh/errors.h"
#include "ricci/mesh/io.h"
#include "ricci/mesh/primitives.h"
#include "ricci/mesh/simplify.h"
#include "ricci/mesh/simplify_quadric.h"
#include "ricci/metric/subdivide.h"
#include "test_paths.h"

namespace {

ricci::Mesh read_test_mesh(const std::string& relative) {
  return ricci::read_mesh(msp_test::test_mesh(relative));
}

// Open scans keep a slightly worse corner at the boundary, where remeshing cannot relax freely.
void expect_simplified_with_same_topology(const std::string& model, int target, double min_angle = 5.0) {
  ricci::Mesh dense = read_test_mesh(model);
  ricci::SimplifyOptions options;
  options.target_faces = target;
  auto r = ricci::simplify_mesh(dense, options);
  EXPECT_EQ(euler_characteristic(r.mesh), euler_characteristic(dense)) << model;
  EXPECT_NEAR(r.faces_after, target, 0.25 * target) << model;
  EXPECT_GT(r.min_angle_deg, min_angle) << model;
  for (auto v : r.mesh.vertices()) EXPECT_TRUE(r.mesh.is_manifold(v));
}

TEST(Simplify, KeepsGenusOnRealScans) {
  expect_simplified_with_same_topology("closed_g1/kitten_nf20k.off.gz", 2000);
  expect_simplified_with_same_topology("closed_g3/genus3.off.gz", 2000);
  expect_simplified_with_same_topology("closed_g2/cup.off.gz", 2000);
}

TEST(Simplify, KeepsBoundariesOfOpenScans) {
  expect_simplified_with_same_topology("open/lion.off.gz", 2000, 2.0);
}

// Largest distance from the result's vertices to the dense surface, over the bbox diagonal.
double max_deviation(const ricci::Mesh& dense, const ricci::Mesh& result) {
  Eigen::MatrixX3d queries(result.n_vertices(), 3);
  for (auto v : result.vertices()) queries.row(v.idx()) = ricci::to_eigen(result.point(v)).transpose();
  Eigen::MatrixX3d points(dense.n_vertices(), 3);
  for (auto v : dense.vertices()) points.row(v.idx()) = ricci::to_eigen(dense.point(v)).transpose();
  double worst = 0.0;
  for (const auto& p : ricci::closest_points(dense, queries)) worst = std::max(worst, p.distance);
  return worst / (points.colwise().maxCoeff() - points.colwise().minCoeff()).norm();
}

// The library's quadric collapse (alone; by default only the first stage) against CGAL's edge_collapse with the same
// policies: same topology, and the shape kept as closely (vertices within 0.5% of the diagonal
// of the scan, and not more than 1.5x CGAL's deviation plus 0.05%).
TEST(Simplify, OwnQuadricCollapseKeepsTheShapeLikeCgal) {
  for (const char* model :
       {"closed_g1/kitten_nf20k.off.gz", "closed_g2/cup.off.gz", "open/lion.off.gz"}) {
    const ricci::Mesh dense = read_test_mesh(model);
    ricci::SimplifyOptions options;
    options.target_faces = 2000;
    options.remesh_iterations = 0;
    options.collapse = ricci::SimplifyOptions::Collapse::quadric;
    const auto own = ricci::simplify_mesh(dense, options);
    options.collapse = ricci::SimplifyOptions::Collapse::cgal;
    const auto cgal = ricci::simplify_mesh(dense, options);
    EXPECT_EQ(euler_characteristic(own.mesh), euler_characteristic(dense)) << model;
    EXPECT_NEAR(own.faces_after, 2000, 20) << model;
    const double a = max_deviation(dense, own.mesh), b = max_deviation(dense, cgal.mesh);
    EXPECT_LT(a, 5e-3) << model;
    RecordProperty(std::string("deviation_") + model, std::to_string(a) + " (CGAL " + std::to_string(b) + ")");
    EXPECT_LT(a, 1.5 * b + 5e-4) << model << ": CGAL " << b;
  }
}

TEST(Simplify, RefusesTinyTargets) {
  ricci::SimplifyOptions options;
  options.target_faces = 2;
  EXPECT_THROW((void)ricci::simplify_mesh(read_test_mesh("closed_g2/eight.off"), options),
               ricci::InvalidInputError);
}

ricci::Mesh decimated(const ricci::Mesh& dense, int target, int regions, int threads) {
  ricci::Mesh mesh = dense;
  ricci::QuadricDecimateOptions options;
  options.regions = regions;
  options.threads = threads;
  (void)ricci::quadric_decimate(mesh, target, options);
  return mesh;
}

// The regions decimated at once (two threads, cuts locked, one queue at the end) keep what one
// queue keeps: the topology (genus, boundary loops), a manifold result at the target, and the
// shape within the bound the own collapse meets against CGAL's.
TEST(QuadricDecimate, RegionsKeepTopologyAndShapeLikeOneQueue) {
  for (const char* model : {"closed_g1/kitten_nf20k.off.gz", "open/lion.off.gz"}) {
    const ricci::Mesh dense = ricci::subdivide_midpoint(read_test_mesh(model));
    const ricci::SurfaceTopology before = ricci::surface_topology(dense);
    const ricci::Mesh one = decimated(dense, 2000, 1, 1);
    for (int regions : {2, 3}) {
      const ricci::Mesh parts = decimated(dense, 2000, regions, 2);
      const ricci::SurfaceTopology after = ricci::surface_topology(parts);
      EXPECT_EQ(after.euler_characteristic, before.euler_characteristic) << model << regions;
      EXPECT_EQ(after.boundary_loops, before.boundary_loops) << model << regions;
      EXPECT_NEAR(static_cast<double>(parts.n_faces()), 2000.0, 2.0) << model << regions;
      for (auto v : parts.vertices()) EXPECT_TRUE(parts.is_manifold(v)) << model << regions;
      const double a = max_deviation(dense, parts), b = max_deviation(dense, one);
      EXPECT_LT(a, 1.5 * b + 5e-4) << model << " regions " << regions << ": one queue " << b;
    }
  }
}

// Each region's collapses touch only its own elements, so the result is the same bits whatever
// the number of threads; the default (regions = 0) keeps one queue below 400,000 faces.
TEST(QuadricDecimate, RegionsGiveTheSameMeshOnAnyThreadCount) {
  const ricci::Mesh dense = ricci::subdivide_midpoint(read_test_mesh("closed_g2/cup.off.gz"));
  const auto same = [](const ricci::Mesh& a, const ricci::Mesh& b) {
    const ricci::VertexFaceArrays x = ricci::to_arrays(a), y = ricci::to_arrays(b);
    return x.V.rows() == y.V.rows() && x.F.rows() == y.F.rows() && x.V == y.V && x.F == y.F;
  };
  const ricci::Mesh serial = decimated(dense, 3000, 2, 1);
  EXPECT_TRUE(same(serial, decimated(dense, 3000, 2, 2)));
  EXPECT_TRUE(same(decimated(dense, 3000, 4, 1), decimated(dense, 3000, 4, 3)));
  EXPECT_FALSE(same(serial, decimated(dense, 3000, 1, 1)));  // the regions did something
  const ricci::Mesh small = read_test_mesh("closed_g2/cup.off.gz");
  EXPECT_TRUE(same(decimated(small, 3000, 0, 2), decimated(small, 3000, 1, 1)));
}

TEST(ClosestPoints, VerticesProjectOntoThemselvesAndBarycentricsRebuildThePoint) {
  ricci::Mesh mesh = read_test_mesh("closed_g2/eight.off");
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
