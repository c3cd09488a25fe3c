// Fitting control points to points, closest-point projection onto the spline, and the scan
// pipeline (simplify, atlas, fit, fair) on a bundled model.
#include <gtest/gtest.h>

#include <random>

#include "ricci/mesh/errors.h"
#include "ricci/mesh/simplify.h"
#include "ricci/topology/slice.h"
#include "spline/fit/fit.h"
#include "spline/manifold/manifold_fixtures.h"

namespace spline {
namespace {

using testing::small_atlas;
using testing::small_space;

Eigen::Vector3d random_barycentric(std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(0.02, 1.0);
  Eigen::Vector3d b(unit(rng), unit(rng), unit(rng));
  return b / b.sum();
}

Eigen::Vector3d mesh_point(const ricci::Mesh& mesh, int face, const Eigen::Vector3d& bary) {
  const auto hs = ricci::face_halfedges(mesh, mesh.face_handle(face));
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k)
    p += bary[k] * ricci::to_eigen(mesh.point(mesh.to_vertex_handle(hs[k])));
  return p;
}

double mean_edge_3d(const ricci::Mesh& mesh) {
  double sum = 0.0;
  for (auto e : mesh.edges()) sum += mesh.calc_edge_length(e);
  return sum / static_cast<double>(mesh.n_edges());
}

// closest_points' barycentric coordinates follow the atlas' corner order (face_halfedges).
TEST(Fit, ClosestPointBarycentricsUseTheCornerOrder) {
  const ricci::Mesh& mesh = small_atlas("genus2.off").problem.mesh;
  Eigen::MatrixX3d queries(20, 3);
  std::vector<Eigen::Vector3d> bary;
  std::mt19937 rng(1);
  for (int i = 0; i < 20; ++i) {
    bary.push_back(random_barycentric(rng));
    queries.row(i) = mesh_point(mesh, 7 * i, bary.back()).transpose();
  }
  const auto closest = ricci::closest_points(mesh, queries);
  for (int i = 0; i < 20; ++i) {
    ASSERT_EQ(closest[i].face, 7 * i);
    EXPECT_LT((closest[i].barycentric - bary[i]).norm(), 1e-9);
  }
}

// The piecewise-linear initial control points give a surface near the mesh.
TEST(Fit, InitialControlPointsFollowTheMesh) {
  for (int n = 2; n <= 4; ++n) {
    const auto space = small_space("genus2.off", n);
    const ricci::Mesh& mesh = small_atlas("genus2.off").problem.mesh;
    const ManifoldSpline spline{space, piecewise_linear_control_points(*space, mesh)};
    double worst = 0.0;
    for (int f : space->domain_faces()) {
      const Eigen::Vector3d centre = Eigen::Vector3d::Constant(1.0 / 3.0);
      worst = std::max(
          worst, (spline.evaluate({f, centre}).position - mesh_point(mesh, f, centre)).norm());
    }
    EXPECT_LT(worst, 0.25 * mean_edge_3d(mesh)) << "n=" << n;
  }
}

// Points sampled from a spline are fitted back exactly (pure least squares, no smoothing).
TEST(Fit, RecoversASplineFromItsSamples) {
  for (int n = 2; n <= 3; ++n) {
    const auto space = small_space("genus1.off", n);
    const ricci::Mesh& mesh = small_atlas("genus1.off").problem.mesh;
    const ManifoldSpline truth{space, piecewise_linear_control_points(*space, mesh)};
    std::mt19937 rng(n);
    std::vector<DomainPoint> parameters;
    for (int f : space->domain_faces()) {
      for (int i = 0; i < 2 * space->functions_per_face(); ++i)
        parameters.push_back({f, random_barycentric(rng)});
    }
    Eigen::MatrixX3d points(static_cast<Eigen::Index>(parameters.size()), 3);
    for (std::size_t k = 0; k < parameters.size(); ++k) {
      points.row(static_cast<Eigen::Index>(k)) = truth.evaluate(parameters[k]).position.transpose();
    }
    FitOptions options;
    options.smoothing = 0.0;
    options.anchor = 0.0;
    const FitResult fit = fit_control_points(
        *space, parameters, points, Eigen::MatrixX3d::Zero(space->function_count(), 3), options);
    const double scale = truth.control_points.cwiseAbs().maxCoeff();
    EXPECT_LT((fit.control_points - truth.control_points).cwiseAbs().maxCoeff(), 1e-8 * scale)
        << "n=" << n;
    EXPECT_LT(fit.max_at_parameters, 1e-9 * scale);
  }
}

// A point at distance d along the normal of F(u) projects back to F(u) from a nearby start.
TEST(Fit, ProjectionFindsTheFootPoint) {
  const auto space = small_space("genus2.off", 3);
  const ricci::Mesh& mesh = small_atlas("genus2.off").problem.mesh;
  const ManifoldSpline spline{space, piecewise_linear_control_points(*space, mesh)};
  const double d = 0.01 * mean_edge_3d(mesh);
  std::mt19937 rng(5);
  int tested = 0;
  double worst = 0.0;
  for (int f : space->domain_faces()) {
    if (f % 5 != 0) continue;
    const DomainPoint foot{f, random_barycentric(rng)};
    const SurfaceJet jet = spline.evaluate(foot);
    const Eigen::Vector3d target = jet.position + d * jet.normal;
    const DomainPoint start{f,
                            (foot.barycentric + Eigen::Vector3d(0.05, -0.03, -0.02)).cwiseMax(0.0)};
    const Projection p =
        project_to_spline(spline, {f, start.barycentric / start.barycentric.sum()}, target, 8);
    worst = std::max(worst, std::abs(p.distance - d) / d);
    ++tested;
  }
  EXPECT_GT(tested, 50);
  EXPECT_LT(worst, 1e-3);
}

// The whole pipeline on the bundled genus-1 model (3000 faces) with a 600-face domain: the fitted
// and faired cubic spline stays within a small fraction of the bounding-box diagonal.
TEST(Fit, ScanPipelineFitsTheBundledTorus) {
  const ricci::Mesh dense = ricci::read_mesh(std::string(MSP_SOURCE_DIR) + "/models/genus1.off");
  ScanFitOptions options;
  options.domain_faces = 600;
  const ScanFitResult result = fit_scan(dense, options);
  Eigen::MatrixX3d points(static_cast<Eigen::Index>(dense.n_vertices()), 3);
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = -lo;
  for (auto v : dense.vertices()) {
    const Eigen::Vector3d p = ricci::to_eigen(dense.point(v));
    points.row(v.idx()) = p.transpose();
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double diagonal = (hi - lo).norm();
  const FitErrors errors = fit_errors(result.spline, result.vertex_parameters, points);
  EXPECT_EQ(errors.points, static_cast<int>(dense.n_vertices()));  // genus 1: no hole
  EXPECT_LT(errors.rms, 2e-3 * diagonal);
  EXPECT_LT(errors.max, 1e-2 * diagonal);
  EXPECT_LT(result.fairing.max_constraint_residual, 1e-9 * diagonal);
}

TEST(Fit, BadInputThrows) {
  const auto space = small_space("genus1.off", 2);
  EXPECT_THROW((void)fit_control_points(*space, {{0, Eigen::Vector3d::Constant(1.0 / 3)}},
                                        Eigen::MatrixX3d::Zero(2, 3),
                                        Eigen::MatrixX3d::Zero(space->function_count(), 3)),
               ricci::InvalidInputError);
  EXPECT_THROW((void)fit_control_points(*space, {{-1, Eigen::Vector3d::Constant(1.0 / 3)}},
                                        Eigen::MatrixX3d::Zero(1, 3),
                                        Eigen::MatrixX3d::Zero(space->function_count(), 3)),
               ricci::InvalidInputError);
}

}  // namespace
}  // namespace spline
