// The circle domain: a planar disk with circular holes (already a circle
// domain, normalised) comes back as itself; conformal images give the same module.
#include <gtest/gtest.h>

#include <cmath>

#include <ricci/analysis/conformal_module.h>
#include <ricci/mesh/primitives.h>

#include "ricci/analysis/analysis_meshes.h"

namespace ricci {
namespace {

using testing::TestCircle;

/// The module vector (r1, x2, r2, x3, y3, r3, ...) of a normalised circle domain: holes[0]
/// centred at 0, holes[1] on the positive real axis, holes by decreasing radius.
std::vector<double> expected_module(const std::vector<TestCircle>& holes) {
  std::vector<double> values;
  for (size_t k = 0; k < holes.size(); ++k) {
    if (k >= 2) values.push_back(holes[k].x);
    if (k >= 1) values.push_back(k == 1 ? holes[k].x : holes[k].y);
    values.push_back(holes[k].r);
  }
  return values;
}

const std::vector<TestCircle> kFiveHoles = {
    {0, 0, 0.22}, {0.55, 0, 0.14}, {-0.4, 0.5, 0.12}, {-0.45, -0.45, 0.1}, {0.2, -0.7, 0.08}};

/// The module of `mesh` (a conformal image of the domain with `holes`) is the domain's.
void expect_circle_domain(const Mesh& mesh, const std::vector<TestCircle>& holes, double tolerance,
                          const ModuleOptions& options = {}) {
  const SurfaceTopology topology = surface_topology(mesh);
  ASSERT_TRUE(topology.manifold);
  ASSERT_EQ(topology.boundary_loops, static_cast<int>(holes.size()) + 1);
  const ModuleResult result = conformal_module(mesh, options);
  ASSERT_TRUE(result.converged) << result.message;
  EXPECT_EQ(result.kind, ModuleKind::CircleDomain);
  EXPECT_EQ(result.preparation,
            options.intrinsic_circle_domain ? "intrinsic Delaunay" : "as given");
  const std::vector<double> expected = expected_module(holes);
  ASSERT_EQ(result.values.size(), expected.size());
  std::cout << mesh.n_faces() << " faces, " << result.circle_iterations << " target updates, "
            << result.flow_iterations << " Newton iterations, roundness " << result.roundness
            << ", " << result.seconds << " s\n";
  for (size_t i = 0; i < expected.size(); ++i) {
    EXPECT_NEAR(result.values[i], expected[i], tolerance) << result.names[i];
  }
}

TEST(CircleDomain, TwoHoles) {
  const std::vector<TestCircle> holes = {{0, 0, 0.3}, {0.62, 0, 0.15}};
  expect_circle_domain(testing::circle_domain_mesh(holes, 0.02), holes, 1e-3);
}

TEST(CircleDomain, FiveHoles) {
  expect_circle_domain(testing::circle_domain_mesh(kFiveHoles, 0.02), kFiveHoles, 1e-3);
}

TEST(CircleDomain, IntrinsicDelaunayFlowGivesTheSameDomain) {
  // The flow with intrinsic flips on the double cover (another discrete conformal structure, the
  // route for lion.off): the five holes again, and on the stereographic image, whose faces the
  // flips change, and the drawn domain has every face counter-clockwise.
  ModuleOptions options;
  options.intrinsic_circle_domain = true;
  const Mesh plane = testing::circle_domain_mesh(kFiveHoles, 0.02);
  expect_circle_domain(plane, kFiveHoles, 1e-3, options);
  const Mesh sphere =
      testing::mapped(plane, [](const Eigen::Vector3d& p) { return testing::onto_sphere(p, 2.0); });
  const ModuleResult result = conformal_module(sphere, options);
  ASSERT_TRUE(result.converged) << result.message;
  const std::vector<double> expected = expected_module(kFiveHoles);
  ASSERT_EQ(result.values.size(), expected.size());
  for (size_t i = 0; i < expected.size(); ++i) {
    EXPECT_NEAR(result.values[i], expected[i], 1e-3) << result.names[i];
  }
  const CanonicalDomain& domain = result.domain;
  ASSERT_GE(domain.positions.rows(), static_cast<Eigen::Index>(sphere.n_vertices()));
  for (Eigen::Index f = 0; f < domain.faces.rows(); ++f) {
    const Eigen::Vector2d a = domain.positions.row(domain.faces(f, 0));
    const Eigen::Vector2d b = domain.positions.row(domain.faces(f, 1));
    const Eigen::Vector2d c = domain.positions.row(domain.faces(f, 2));
    EXPECT_GT((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x(), 0) << "face " << f;
  }
}

TEST(CircleDomain, ConformalImagesKeepTheModule) {
  // A disk automorphism (circles stay circles, but the sampling and the normalisation change)
  // and the stereographic image on the sphere; both keep the holes' order by length.
  const Mesh plane = testing::circle_domain_mesh(kFiveHoles, 0.02);
  expect_circle_domain(testing::mapped(plane,
                                       [](const Eigen::Vector3d& p) {
                                         return testing::mobius(p, {0.05, -0.03});
                                       }),
                       kFiveHoles, 1e-3);
  expect_circle_domain(
      testing::mapped(plane, [](const Eigen::Vector3d& p) { return testing::onto_sphere(p, 2.0); }),
      kFiveHoles, 1e-3);
}

TEST(HyperbolicModule, SymmetricHolesHaveEqualLengthsAndScaleDoesNothing) {
  // The domain is symmetric under z -> -z (up to the jittered lattice): equal hole lengths.
  const Mesh mesh = testing::circle_domain_mesh({{-0.4, 0, 0.2}, {0.4, 0, 0.2}}, 0.03);
  ModuleOptions options;
  options.force_kind = true;
  options.kind = ModuleKind::Hyperbolic;
  const ModuleResult result = conformal_module(mesh, options);
  ASSERT_TRUE(result.converged) << result.message;
  ASSERT_EQ(result.values.size(), 3u);
  EXPECT_GT(result.values[0], result.values[1]);
  EXPECT_NEAR(result.values[1], result.values[2], 1e-2 * result.values[1]);
  const ModuleResult scaled = conformal_module(
      testing::mapped(mesh, [](const Eigen::Vector3d& p) { return Eigen::Vector3d(1e3 * p); }),
      options);
  for (size_t i = 0; i < 3; ++i) EXPECT_NEAR(scaled.values[i], result.values[i], 1e-9);
}

TEST(FuchsianModule, GenusTwoIsFlaggedNotInvariant) {
  const ModuleResult result = conformal_module(make_genus_slab(2, 2, 4));
  ASSERT_TRUE(result.converged) << result.message;
  EXPECT_EQ(result.kind, ModuleKind::Fuchsian);
  EXPECT_EQ(result.values.size(), 4u);
  EXPECT_FALSE(result.invariant);
  for (double length : result.values) EXPECT_GT(length, 0.0);
}

}  // namespace
}  // namespace ricci
