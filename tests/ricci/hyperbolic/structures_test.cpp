// The other uniformizations: the flat torus (translations, modulus), the sphere (embedding on
// S2) and open surfaces through their double cover.
#include <gtest/gtest.h>

#include <ricci/hyperbolic/uniformize.h>
#include <ricci/mesh/errors.h>
#include <ricci/mesh/io.h>
#include <ricci/mesh/primitives.h>
#include <ricci/metric/curvature.h>
#include <ricci/metric/mesh_tables.h>
#include <ricci/spherical/sphere_layout.h>
#include <ricci/topology/double_cover.h>
#include "test_paths.h"

namespace ricci {
namespace {


Mesh scaled(Mesh mesh, double s) {
  for (auto v : mesh.vertices()) mesh.set_point(v, mesh.point(v) * s);
  return mesh;
}

TEST(FlatTorus, TorusOfRevolutionHasTheAnalyticModulusAndScaleInvariance) {
  // ds² = (R + r cos v)² du² + r² dv² is conformal to a rectangle with sides 2π and
  // 2π r / sqrt(R² - r²): tau = i sqrt(R² - r²) / r up to the lattice's SL(2, Z).
  const double R = 3.0, r = 1.0;
  const Mesh mesh = make_torus(60, 24, R, r);
  const Uniformization u = uniformize(mesh);
  ASSERT_TRUE(u.converged()) << u.flow.message;
  EXPECT_EQ(u.geometry, Geometry::euclidean);
  EXPECT_LT(u.flow.max_error, 1e-10);
  ASSERT_EQ(u.translations.size(), 2u);
  // Pure translations: the flat torus has no rotational holonomy; they commute.
  for (const Mobius& g : u.group.generators) EXPECT_LT(std::abs(g.theta()), 1e-9);
  EXPECT_LT(u.group.relation_residual, 1e-9);
  EXPECT_GT(u.modulus.imag(), 0.0);
  EXPECT_NEAR(u.reduced_modulus.real(), 0.0, 2e-3);
  EXPECT_NEAR(u.reduced_modulus.imag(), std::sqrt(R * R - r * r) / r, 2e-2);
  // The modulus is conformal: scaling the mesh by 1e3 leaves it unchanged.
  const Uniformization big = uniformize(scaled(mesh, 1e3));
  ASSERT_TRUE(big.converged());
  EXPECT_LT(std::abs(big.modulus - u.modulus), 1e-9);
  EXPECT_NEAR(std::abs(big.translations[0]) / std::abs(u.translations[0]), 1e3, 1e-6);
}

TEST(FlatTorus, KnotModelIsFlatWithCommutingTranslations) {
  const Uniformization u = uniformize(read_mesh(msp_test::test_mesh("closed_g1/knot1.off.gz")));
  ASSERT_TRUE(u.converged()) << u.flow.message;
  EXPECT_EQ(u.layout.flipped_faces, 0);
  EXPECT_LT(u.layout.max_relative_length_error, 1e-9);
  EXPECT_LT(u.pairings.max_spread, 1e-9);
  EXPECT_LT(u.group.relation_residual, 1e-9);
  EXPECT_GT(u.reduced_modulus.imag(), std::sqrt(3.0) / 2 - 1e-12);
  EXPECT_LE(std::abs(u.reduced_modulus.real()), 0.5 + 1e-12);
}

TEST(Sphere, EmbeddingIsIsometricToTheFlowMetricOnTheUnitSphere) {
  const Mesh mesh = make_random_perturbed(make_icosphere(3), 0.3, 7);
  UniformizeOptions options;
  options.centre_sphere = false;
  const Uniformization u = uniformize(mesh, options);
  ASSERT_TRUE(u.converged()) << u.flow.message;
  EXPECT_EQ(u.geometry, Geometry::spherical);
  EXPECT_LT(u.flow.max_error, 1e-10);
  EXPECT_LT(u.sphere.max_radius_error, 1e-12);
  EXPECT_EQ(u.sphere.flipped_faces, 0);
  EXPECT_LT(u.sphere.max_relative_length_error, 1e-9);
  // Corner angles of the embedded spherical triangles equal the flow metric's.
  const MeshTables tables = build_mesh_tables(u.surface);
  const Eigen::MatrixX3d angles = corner_angles(tables, u.flow.lengths, Geometry::spherical);
  double worst = 0.0;
  for (int f = 0; f < tables.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d p = u.sphere.positions.row(tables.face_vertices(f, k));
      const Eigen::Vector3d a = u.sphere.positions.row(tables.face_vertices(f, (k + 1) % 3));
      const Eigen::Vector3d b = u.sphere.positions.row(tables.face_vertices(f, (k + 2) % 3));
      // Angle between the great circles p-a and p-b: between the tangent directions at p.
      const Eigen::Vector3d ta = (a - a.dot(p) * p).normalized(), tb = (b - b.dot(p) * p).normalized();
      worst = std::max(worst, std::abs(std::atan2(ta.cross(tb).norm(), ta.dot(tb)) - angles(f, k)));
    }
  }
  EXPECT_LT(worst, 1e-9);
}

TEST(Sphere, CentringMovesTheCentroidToTheOriginAndKeepsOrientation) {
  const Mesh mesh = read_mesh(msp_test::test_mesh("closed_g0/bunny_npm_closed.off"));
  const Uniformization u = uniformize(mesh);
  ASSERT_TRUE(u.converged()) << u.flow.message;
  EXPECT_LT(u.sphere.max_radius_error, 1e-12);
  EXPECT_EQ(u.sphere.flipped_faces, 0);
  EXPECT_LT(u.sphere.centroid_norm, 1e-6);
}

TEST(DoubleCover, IsClosedOrientableOfGenus2gPlusBMinus1) {
  struct Case {
    Mesh mesh;
    int genus;
  };
  std::vector<Case> cases;
  cases.push_back({make_disk(4, 6), 0});
  cases.push_back({make_planar_grid(4, 3, 1.0, 1.0), 0});  // corner diagonals are chords
  cases.push_back({make_annulus(3, 12), 1});
  cases.push_back({make_open_genus(1, 2, 2), 3});
  cases.push_back({read_mesh(msp_test::test_mesh("open/eight_hole.off")), 4});
  cases.push_back({read_mesh(msp_test::test_mesh("open/head.off")), 2});
  for (const Case& c : cases) {
    const SurfaceTopology before = surface_topology(c.mesh);
    ASSERT_EQ(2 * before.genus + before.boundary_loops - 1, c.genus);
    const DoubleCover d = double_cover(c.mesh);
    const SurfaceTopology t = surface_topology(d.mesh);
    EXPECT_EQ(t.boundary_loops, 0);
    EXPECT_TRUE(t.manifold);
    EXPECT_EQ(t.components, 1);
    EXPECT_EQ(t.genus, c.genus);
    EXPECT_EQ(t.faces, 2 * static_cast<int>(d.original.n_faces()));
    EXPECT_EQ(static_cast<int>(d.original.n_faces()), before.faces + 2 * d.split_edges);
    // Orientable and consistently oriented: every edge is used once in each direction.
    for (auto e : d.mesh.edges()) {
      EXPECT_FALSE(d.mesh.is_boundary(e));
    }
    // Mirror copies sit on the same points; the boundary is shared.
    for (auto v : d.original.vertices()) {
      EXPECT_EQ(d.to_original_vertex[d.mirror_vertex[v.idx()]], v.idx());
    }
  }
  EXPECT_GT(double_cover(make_planar_grid(4, 3, 1.0, 1.0)).split_edges, 0);
  EXPECT_EQ(double_cover(make_disk(4, 6)).split_edges, 0);
  EXPECT_THROW((void)double_cover(make_icosphere(1)), TopologyError);
}

TEST(DoubleCover, UniformizationMakesTheBoundaryGeodesic) {
  // head.off: genus 0 with 3 holes, its double has genus 2 (H2). On the double every vertex is
  // flat; by the mirror symmetry each boundary vertex then has angle π on the original side,
  // i.e. zero geodesic curvature.
  const Mesh mesh = read_mesh(msp_test::test_mesh("open/head.off"));
  const Uniformization u = uniformize(mesh);
  ASSERT_TRUE(u.converged()) << u.flow.message;
  EXPECT_TRUE(u.doubled);
  EXPECT_EQ(u.genus, 2);
  EXPECT_EQ(u.geometry, Geometry::hyperbolic);
  const MeshTables tables = build_mesh_tables(u.surface);
  const Eigen::MatrixX3d angles = corner_angles(tables, u.flow.lengths, Geometry::hyperbolic);
  Eigen::VectorXd original_side = Eigen::VectorXd::Zero(mesh.n_vertices());
  for (int f = 0; f < static_cast<int>(mesh.n_faces()); ++f) {
    for (int k = 0; k < 3; ++k) original_side[tables.face_vertices(f, k)] += angles(f, k);
  }
  double worst = 0.0;
  int boundary = 0;
  for (auto v : mesh.vertices()) {
    if (!mesh.is_boundary(v)) continue;
    ++boundary;
    worst = std::max(worst, std::abs(original_side[v.idx()] - M_PI));
  }
  EXPECT_GT(boundary, 0);
  EXPECT_LT(worst, 1e-9);
  EXPECT_LT(u.group.relation_residual, 1e-8);
}

}  // namespace
}  // namespace ricci
