// The DMS space over planar patches of real scanned meshes (irregular valences, skinny
// triangles): k-ring patches projected onto their best-fit plane, as a chart would lay them out.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <map>
#include <random>
#include <set>
#include <string>

#include "ricci/mesh/arrays.h"
#include "ricci/mesh/io.h"
#include "spline/basis/orientation.h"
#include "spline/basis/planar_fixtures.h"
#include "spline/basis/planar_space.h"
#include "spline/knots/dms_conditions.h"
#include "spline/knots/knot_cloud.h"
#include "test_paths.h"

namespace spline {
namespace {

// Faces within `rings` rings of `center`, projected onto the least-squares plane; empty when the
// projection folds a triangle.
PlanarTriangulation projected_patch(const ricci::VertexFaceArrays& mesh, int center, int rings) {
  std::set<int> vertices = {center};
  std::set<int> faces;
  for (int r = 0; r < rings; ++r) {
    std::set<int> grown = vertices;
    for (int f = 0; f < mesh.F.rows(); ++f) {
      const Eigen::Vector3i tri = mesh.F.row(f);
      if (vertices.count(tri[0]) || vertices.count(tri[1]) || vertices.count(tri[2])) {
        faces.insert(f);
        for (int k = 0; k < 3; ++k) grown.insert(tri[k]);
      }
    }
    vertices = grown;
  }
  std::map<int, int> local;
  PlanarTriangulation t;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (int f : faces) {
    for (int k = 0; k < 3; ++k) local.emplace(mesh.F(f, k), 0);
  }
  for (auto& entry : local) mean += mesh.V.row(entry.first).transpose();
  mean /= static_cast<double>(local.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (auto& entry : local) {
    const Eigen::Vector3d d = mesh.V.row(entry.first).transpose() - mean;
    covariance += d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  const Eigen::Vector3d e1 = solver.eigenvectors().col(2), e2 = solver.eigenvectors().col(1);
  for (auto& entry : local) {
    entry.second = static_cast<int>(t.positions.size());
    const Eigen::Vector3d d = mesh.V.row(entry.first).transpose() - mean;
    t.positions.emplace_back(d.dot(e1), d.dot(e2));
  }
  int clockwise = 0;
  for (int f : faces) {
    t.triangles.emplace_back(local[mesh.F(f, 0)], local[mesh.F(f, 1)], local[mesh.F(f, 2)]);
    const Eigen::Vector3i& tri = t.triangles.back();
    clockwise += orient2d(t.positions[tri[0]], t.positions[tri[1]], t.positions[tri[2]]) < 0;
  }
  if (2 * clockwise > static_cast<int>(t.triangles.size())) {
    for (Eigen::Vector3i& tri : t.triangles) std::swap(tri[1], tri[2]);
  }
  for (const Eigen::Vector3i& tri : t.triangles) {
    if (orient2d(t.positions[tri[0]], t.positions[tri[1]], t.positions[tri[2]]) <= 0) return {};
  }
  return t;
}

class RealMeshPatch : public ::testing::TestWithParam<std::string> {};

TEST_P(RealMeshPatch, PartitionOfUnityAndReproduction) {
  const ricci::VertexFaceArrays mesh =
      ricci::to_arrays(ricci::read_mesh(msp_test::test_mesh(GetParam())));
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> pick(0, static_cast<int>(mesh.V.rows()) - 1);
  int patches = 0;
  for (int attempt = 0; attempt < 200 && patches < 3; ++attempt) {
    const PlanarTriangulation t = projected_patch(mesh, pick(rng), 4);
    if (t.triangles.empty()) continue;
    const std::vector<int> inner = testing::inner_triangles(t);
    if (inner.size() < 10) continue;
    ++patches;
    for (int n = 2; n <= 4; ++n) {
      const std::vector<KnotCloud> clouds = make_knot_clouds(t, n);
      ASSERT_TRUE(check_dms_conditions(t, clouds).satisfied);
      const PlanarDmsSpace space(t, clouds);
      const Eigen::Vector2d center = t.positions[0];
      BivariatePolynomial p = monomial(n, 0, n);  // x^n about the patch, the hardest monomial
      p.origin = center;
      const Eigen::MatrixXd control = space.control_points_of(p);
      for (int i : inner) {
        const Eigen::Vector2d u = testing::random_point_in(t, i, rng);
        double sum = 0.0;
        for (const BasisSample& s : space.evaluate_basis(u)) sum += s.jet.value;
        ASSERT_NEAR(sum, 1.0, 1e-12) << GetParam() << " degree " << n;
        const double exact = evaluate(p, u)[0];
        ASSERT_NEAR(space.evaluate(control, u).value[0], exact, 1e-10 * (1.0 + std::abs(exact)))
            << GetParam() << " degree " << n;
      }
    }
  }
  EXPECT_EQ(patches, 3) << GetParam() << ": not enough flat patches";
}

INSTANTIATE_TEST_SUITE_P(Models, RealMeshPatch,
                         ::testing::Values("closed_g0/bunny_igl.off.gz", "closed_g0/camel.off.gz",
                                           "open/lion.off.gz", "open/head.off"));

}  // namespace
}  // namespace spline
