// The CGAL generator: requested genus and boundary loops, size near the target, good triangles,
// outward orientation, vertices on the implicit surface, determinism, and option checks.
#include <gtest/gtest.h>

#include <cmath>

#include "ricci/mesh/errors.h"
#include "ricci/mesh/generate.h"
#include "ricci/mesh/primitives.h"

namespace ricci {
namespace {

void expect_generated(const GenerateOptions& options) {
  SCOPED_TRACE(describe_surface(options));
  const Mesh mesh = generate_surface(options);
  const SurfaceTopology t = surface_topology(mesh);
  EXPECT_TRUE(t.manifold);
  EXPECT_EQ(t.components, 1);
  EXPECT_EQ(t.genus, options.genus);
  EXPECT_EQ(t.boundary_loops, options.holes);
  EXPECT_NEAR(t.faces, options.target_faces, 0.15 * options.target_faces);
  EXPECT_GT(min_corner_angle_degrees(mesh), 15.0);
  if (options.holes == 0) {
    EXPECT_GT(signed_volume(mesh), 0);
  }
}

TEST(Generate, ClosedTorusAndOpenDoubleTorus) {
  GenerateOptions torus;
  torus.genus = 1;
  torus.target_faces = 600;
  expect_generated(torus);

  GenerateOptions open;
  open.genus = 2;
  open.holes = 1;
  open.target_faces = 800;
  expect_generated(open);
}

// Signed distance to the generator's genus-1 torus (R = 1, r = 0.35 around the z axis).
double torus_distance(const OpenMesh::Vec3d& p) {
  const double q = std::hypot(p[0], p[1]) - 1.0;
  return std::hypot(q, p[2]) - 0.35;
}

TEST(Generate, VerticesLieOnTheImplicitSurfaceAndTheCutPlane) {
  GenerateOptions o;
  o.genus = 1;
  o.holes = 1;
  o.target_faces = 500;
  const Mesh mesh = generate_surface(o);
  ASSERT_EQ(surface_topology(mesh).boundary_loops, 1);
  double max_x = -1e300;
  for (auto v : mesh.vertices()) {
    EXPECT_NEAR(torus_distance(mesh.point(v)), 0.0, 1e-10) << "vertex " << v.idx();
    max_x = std::max(max_x, mesh.point(v)[0]);
  }
  // The +x cap is cut hole_depth deep from the torus's extreme x = R + r, up to the Mesh_3
  // approximation of that extreme; every boundary vertex sits exactly on that plane.
  EXPECT_NEAR(max_x, 1.35 - o.hole_depth, 1e-3);
  int boundary_vertices = 0;
  for (auto v : mesh.vertices()) {
    if (!v.is_boundary()) continue;
    ++boundary_vertices;
    EXPECT_EQ(mesh.point(v)[0], max_x);
  }
  EXPECT_GT(boundary_vertices, 8);
}

TEST(Generate, ClosedBlobIsDeterministicForASeed) {
  GenerateOptions blob;
  blob.genus = 0;
  blob.target_faces = 400;
  blob.seed = 3;
  expect_generated(blob);
  const Mesh a = generate_surface(blob);
  const Mesh b = generate_surface(blob);
  ASSERT_EQ(a.n_vertices(), b.n_vertices());
  ASSERT_EQ(a.n_faces(), b.n_faces());
  for (auto v : a.vertices()) EXPECT_EQ(a.point(v), b.point(v));
}

// Beyond genus 3 (the intrinsic flow's surfaces): a row of tori fused into one genus-g surface.
TEST(Generate, ClosedGenus4And10) {
  for (int genus : {4, kMaxGeneratedGenus}) {
    GenerateOptions o;
    o.genus = genus;
    o.target_faces = 4000;
    expect_generated(o);
  }
}

TEST(Generate, RejectsBadOptions) {
  GenerateOptions o;
  o.genus = -1;
  EXPECT_THROW((void)generate_surface(o), InvalidInputError);
  o.genus = kMaxGeneratedGenus + 1;
  EXPECT_THROW((void)generate_surface(o), InvalidInputError);
  o = {};
  o.holes = 3;
  EXPECT_THROW((void)generate_surface(o), InvalidInputError);
  o = {};
  o.target_faces = 50;
  EXPECT_THROW((void)generate_surface(o), InvalidInputError);
  o = {};
  o.hole_depth = -1;
  o.holes = 1;
  EXPECT_THROW((void)generate_surface(o), InvalidInputError);
}

TEST(Generate, MinCornerAngleOfKnownMeshes) {
  EXPECT_NEAR(min_corner_angle_degrees(make_planar_grid(3, 3, 1, 1)), 45.0, 1e-12);
  EXPECT_NEAR(min_corner_angle_degrees(make_tetrahedron()), 60.0, 1e-12);
}

}  // namespace
}  // namespace ricci
