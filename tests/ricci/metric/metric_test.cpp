#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include <ricci/mesh/errors.h>
#include <ricci/mesh/io.h>
#include <ricci/metric/circle_packing.h>
#include <ricci/metric/curvature.h>
#include <ricci/metric/least_squares_fit.h>
#include <ricci/metric/subdivide.h>

#include "ricci/test_meshes.h"
#include "test_paths.h"

namespace ricci {
namespace {

const Geometry kGeometries[] = {Geometry::euclidean, Geometry::hyperbolic, Geometry::spherical};

// Lengths suitable for every geometry: the unit sphere's chords are short enough for S2.
EdgeLengths sphere_lengths(const Mesh& mesh) { return mesh_edge_lengths(mesh); }

TEST(TriangleAngles, EquilateralInEachGeometry) {
  const double l = 0.8, side[3] = {l, l, l};
  double theta[3];
  ASSERT_TRUE(triangle_angles(Geometry::euclidean, side, theta));
  EXPECT_NEAR(theta[0], M_PI / 3, 1e-15);
  ASSERT_TRUE(triangle_angles(Geometry::hyperbolic, side, theta));
  // Hyperbolic cosine law with equal sides: cos θ = cosh l / (1 + cosh l).
  EXPECT_NEAR(std::cos(theta[1]), std::cosh(l) / (1 + std::cosh(l)), 1e-15);
  ASSERT_TRUE(triangle_angles(Geometry::spherical, side, theta));
  EXPECT_NEAR(std::cos(theta[2]), std::cos(l) / (1 + std::cos(l)), 1e-15);
}

TEST(TriangleAngles, NeedleAngleIsAccurateWhereAcosIsNot) {
  // Isosceles needle: the apex angle is 2 asin(ε/2), about ε; acos(1 - ε²/2) loses it.
  const double eps = 1e-9, l[3] = {eps, 1.0, 1.0};
  double theta[3], c[3], s[3];
  ASSERT_TRUE(triangle_angles(Geometry::euclidean, l, theta, c, s));
  EXPECT_NEAR(theta[0] / (2 * std::asin(eps / 2)), 1.0, 1e-12);
  EXPECT_NEAR(theta[0] + theta[1] + theta[2], M_PI, 1e-15);
  EXPECT_NEAR(s[0] / std::sin(theta[0]), 1.0, 1e-12);
}

// The E2 angles with all three arc tangents, closed on the largest computed angle (the
// formula before the largest one's arc tangent was skipped).
void reference_e2_angles(const double l[3], double theta[3]) {
  double d[3];
  for (int k = 0; k < 3; ++k) {
    const double a = l[(k + 1) % 3], b = l[(k + 2) % 3];
    d[k] = 0.5 * ((std::max(a, b) - l[k]) + std::min(a, b));
  }
  const double s = 0.5 * (l[0] + l[1] + l[2]);
  for (int k = 0; k < 3; ++k) {
    const double x2 = s * d[k], y2 = d[(k + 1) % 3] * d[(k + 2) % 3];
    theta[k] = 2.0 * std::atan2(std::sqrt(y2), std::sqrt(x2));
  }
  const int big = theta[0] >= theta[1] ? (theta[0] >= theta[2] ? 0 : 2)
                                       : (theta[1] >= theta[2] ? 1 : 2);
  theta[big] = M_PI - (theta[(big + 1) % 3] + theta[(big + 2) % 3]);
}

TEST(TriangleAngles, LargestAngleClosedWithoutItsArcTangentIsTheSameBits) {
  // Random triangles, needles, caps, near-isosceles (the longest side within 1e-6 and 1e-15
  // of another) and exact ties: the same doubles as with all three arc tangents.
  std::mt19937_64 random(19);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int compared = 0;
  for (int i = 0; i < 200000; ++i) {
    double l[3] = {unit(random), unit(random), unit(random)};
    switch (i % 5) {
      case 1: l[0] = l[1] + l[2] * std::pow(10.0, -16.0 * unit(random)); break;  // cap
      case 2: l[i % 3] = l[(i + 1) % 3] * (1.0 + 2e-6 * (unit(random) - 0.5)); break;
      case 3: l[i % 3] = l[(i + 1) % 3] * (1.0 + 1e-15 * std::floor(8 * unit(random))); break;
      case 4: l[0] = l[1] = 1.0 - 1e-9 * unit(random); l[2] *= 1e-8; break;  // needle
      default: break;
    }
    double theta[3], expected[3];
    if (!triangle_angles(Geometry::euclidean, l, theta)) continue;
    reference_e2_angles(l, expected);
    for (int k = 0; k < 3; ++k) {
      ASSERT_EQ(theta[k], expected[k]) << "sides " << l[0] << " " << l[1] << " " << l[2];
    }
    ++compared;
  }
  EXPECT_GT(compared, 100000);
}

TEST(TriangleAngles, RejectsTriangleInequalityAndLongSphericalPerimeter) {
  double theta[3];
  const double flat[3] = {1.0, 2.0, 3.0};
  EXPECT_FALSE(triangle_angles(Geometry::euclidean, flat, theta));
  const double big[3] = {2.2, 2.2, 2.2};  // perimeter 6.6 > 2π
  EXPECT_FALSE(triangle_angles(Geometry::spherical, big, theta));
  EXPECT_TRUE(triangle_angles(Geometry::hyperbolic, big, theta));
}

TEST(CirclePacking, InversiveDistanceReproducesLengthsInEveryGeometry) {
  Mesh mesh = testing::sphere(2);
  testing::jitter(mesh, 0.03, 7);
  const MeshTables t = build_mesh_tables(mesh);
  const EdgeLengths l = sphere_lengths(mesh);
  for (Geometry g : kGeometries) {
    for (RadiusInit r : {RadiusInit::mean, RadiusInit::min}) {
      const CirclePackingMetric m = initial_metric(t, l, g, Scheme::inversive_distance, r);
      const EdgeLengths back = circle_packing_lengths(t, m);
      EXPECT_LT(((back - l).array() / l.array()).abs().maxCoeff(), 1e-12) << to_string(g);
      if (r == RadiusInit::min) {
        EXPECT_GE(m.eta.minCoeff(), 1.0 - 1e-12) << to_string(g);
      }
    }
  }
}

TEST(CirclePacking, ThurstonWeightsAreClampedAndCombinatorialIsUniform) {
  const Mesh mesh = read_mesh(msp_test::test_mesh("closed_g1/kitten_nf20k.off.gz"));
  const MeshTables t = build_mesh_tables(mesh);
  const EdgeLengths l = mesh_edge_lengths(mesh);
  const CirclePackingMetric cp =
      initial_metric(t, l, Geometry::euclidean, Scheme::circle_packing, RadiusInit::mean);
  EXPECT_GE(cp.eta.minCoeff(), 0.0);
  EXPECT_LE(cp.eta.maxCoeff(), 1.0);
  const CirclePackingMetric comb =
      initial_metric(t, l, Geometry::euclidean, Scheme::combinatorial, RadiusInit::mean);
  const EdgeLengths lc = circle_packing_lengths(t, comb);
  EXPECT_NEAR(lc.minCoeff(), 2.0, 1e-15);
  EXPECT_NEAR(lc.maxCoeff(), 2.0, 1e-15);
}

TEST(CirclePacking, LeastSquaresFitIsNoWorseThanMeanRadii) {
  const Mesh mesh = read_mesh(msp_test::test_mesh("closed_g1/knot1.off.gz"));
  const MeshTables t = build_mesh_tables(mesh);
  const EdgeLengths l = mesh_edge_lengths(mesh);
  const CirclePackingMetric mean =
      initial_metric(t, l, Geometry::euclidean, Scheme::circle_packing, RadiusInit::mean);
  const CirclePackingMetric fit =
      initial_metric(t, l, Geometry::euclidean, Scheme::circle_packing, RadiusInit::least_squares);
  const double cost_mean = circle_packing_fit_cost(t, l, Geometry::euclidean, mean.gamma);
  const double cost_fit = circle_packing_fit_cost(t, l, Geometry::euclidean, fit.gamma);
  ASSERT_GT(cost_mean, 0.0);
  EXPECT_LT(cost_fit, 0.5 * cost_mean);
  // The cost is what the clamped lengths actually miss.
  const EdgeLengths lf = circle_packing_lengths(t, fit);
  EXPECT_NEAR((lf - l).squaredNorm(), cost_fit, 1e-12 * (1 + cost_fit));
}

TEST(CirclePacking, LengthDerivativeMatchesFiniteDifferences) {
  for (Geometry g : kGeometries) {
    for (double eta : {-0.5, 0.3, 1.0, 4.0}) {
      const double a = 0.4, b = 0.7, h = 1e-6;
      const double ua = u_from_radius(g, a);
      const double l = circle_edge_length(g, a, b, eta);
      const double fd = (circle_edge_length(g, radius_from_u(g, ua + h), b, eta) -
                         circle_edge_length(g, radius_from_u(g, ua - h), b, eta)) / (2 * h);
      EXPECT_NEAR(circle_edge_length_du(g, a, b, eta, l), fd, 1e-9 * l) << to_string(g) << " " << eta;
      EXPECT_NEAR(circle_edge_eta(g, a, b, l), eta, 1e-12);
    }
  }
}

// Gauss-Bonnet on every class of test mesh: closed genus 0..9 and open surfaces.
class GaussBonnetOnModels : public ::testing::TestWithParam<const char*> {};

TEST_P(GaussBonnetOnModels, HoldsInEveryGeometry) {
  const Mesh mesh = read_mesh(msp_test::test_mesh(GetParam()));
  const MeshTables t = build_mesh_tables(mesh);
  EdgeLengths l = mesh_edge_lengths(mesh);
  EXPECT_LT(std::abs(gauss_bonnet_residual(t, l, Geometry::euclidean)), 1e-8 * t.num_vertices());
  // Short lengths are valid in H2 and S2 too (mean edge 0.01).
  l *= 0.01 / l.mean();
  EXPECT_LT(std::abs(gauss_bonnet_residual(t, l, Geometry::hyperbolic)), 1e-8 * t.num_vertices());
  EXPECT_LT(std::abs(gauss_bonnet_residual(t, l, Geometry::spherical)), 1e-8 * t.num_vertices());
  // The E2 curvature of the embedded mesh alone sums to 2πχ.
  EXPECT_NEAR(vertex_curvature(t, mesh_edge_lengths(mesh), Geometry::euclidean).sum(),
              2 * M_PI * t.euler_characteristic, 1e-8 * t.num_vertices());
}

INSTANTIATE_TEST_SUITE_P(
    Models, GaussBonnetOnModels,
    ::testing::Values("closed_g0/knight_decimated.off", "closed_g0/spot.obj.gz",
                      "closed_g1/elk.off", "closed_g1/knot1.off.gz", "closed_g2/eight.off",
                      "closed_g2/joint.off",
                      "closed_g3/helmet.off", "closed_g3/block.off", "closed_g4plus/anchor.off",
                      "closed_g4plus/couplingdown.off", "open/head.off", "open/eight_hole.off",
                      "open/holes.off.gz"));

TEST(MeshTables, RecordTopology) {
  const MeshTables disk = build_mesh_tables(testing::square(4));
  EXPECT_EQ(disk.euler_characteristic, 1);
  ASSERT_EQ(disk.boundary_loops.size(), 1u);
  EXPECT_EQ(disk.boundary_loops[0].size(), 16u);
  const MeshTables torus = build_mesh_tables(testing::torus(6, 5));
  EXPECT_EQ(torus.euler_characteristic, 0);
  EXPECT_TRUE(torus.boundary_loops.empty());
  EXPECT_EQ(torus.valence.sum(), 3 * torus.num_faces());
}

TEST(Subdivide, MidpointKeepsTopologyAndHalvesLengths) {
  const Mesh mesh = read_mesh(msp_test::test_mesh("closed_g2/eight.off"));
  const Mesh fine = subdivide_midpoint(mesh);
  EXPECT_EQ(fine.n_vertices(), mesh.n_vertices() + mesh.n_edges());
  EXPECT_EQ(fine.n_faces(), 4 * mesh.n_faces());
  EXPECT_EQ(build_mesh_tables(fine).euler_characteristic, build_mesh_tables(mesh).euler_characteristic);
  EXPECT_NEAR(mesh_edge_lengths(fine).sum(),
              mesh_edge_lengths(mesh).sum() + 0.5 * [&] {
                // Interior edges of each face: three half-length copies of its sides.
                double s = 0;
                const MeshTables t = build_mesh_tables(mesh);
                const EdgeLengths l = mesh_edge_lengths(mesh);
                for (int f = 0; f < t.num_faces(); ++f)
                  for (int k = 0; k < 3; ++k) s += l[t.face_edges(f, k)];
                return s;
              }(),
              1e-9 * mesh_edge_lengths(mesh).sum());
}

TEST(Curvature, BadLengthsThrowNamingTheFace) {
  const Mesh mesh = testing::square(2);
  const MeshTables t = build_mesh_tables(mesh);
  EdgeLengths l = mesh_edge_lengths(mesh);
  l[t.face_edges(3, 0)] = 10.0;
  try {
    (void)corner_angles(t, l, Geometry::euclidean);
    FAIL() << "expected InvalidInputError";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("face"), std::string::npos);
  }
  EXPECT_THROW((void)corner_angles(t, EdgeLengths(3), Geometry::euclidean), InvalidInputError);
}

}  // namespace
}  // namespace ricci
