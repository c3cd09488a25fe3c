// The Loop baseline: OpenSubdiv limit surface against an independent Loop subdivision written
// here, exact recovery of control points, and fits of real meshes.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "ricci/mesh/errors.h"
#include "ricci/mesh/io.h"
#include "ricci/mesh/primitives.h"
#include "spline/baseline/loop_fit.h"
#include "spline/baseline/loop_surface.h"
#include "test_paths.h"

namespace spline {
namespace {


Eigen::MatrixX3d positions(const ricci::Mesh& mesh) {
  Eigen::MatrixX3d x(static_cast<Eigen::Index>(mesh.n_vertices()), 3);
  for (auto v : mesh.vertices()) x.row(v.idx()) = ricci::to_eigen(mesh.point(v)).transpose();
  return x;
}

// Loop's subdivision (Loop 1987, closed meshes only) written from the paper, not from
// OpenSubdiv: each refined triangle remembers its base face and the (u, v) of its corners, so
// every refined vertex is a known location; after `levels` steps the vertices are pushed to the
// limit with Loop's limit mask chi = 1 / (3 / (8 beta) + n).
struct LimitSamples {
  std::vector<LoopLocation> locations;
  Eigen::MatrixX3d points;
};

double loop_beta(int n) {
  const double c = 0.375 + 0.25 * std::cos(2.0 * M_PI / n);
  return (0.625 - c * c) / n;
}

LimitSamples loop_limit_samples(const ricci::Mesh& control, int levels) {
  struct Tri {
    std::array<int, 3> v;
    int base;
    std::array<Eigen::Vector2d, 3> uv;
  };
  std::vector<Eigen::Vector3d> x;
  for (auto v : control.vertices()) x.push_back(ricci::to_eigen(control.point(v)));
  std::vector<Tri> tris;
  for (auto f : control.faces()) {
    Tri t{{}, f.idx(), {Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 0), Eigen::Vector2d(0, 1)}};
    int k = 0;
    for (auto v : control.fv_range(f)) t.v[static_cast<size_t>(k++)] = v.idx();
    tris.push_back(t);
  }
  auto neighbours_and_opposites = [&](std::vector<std::vector<int>>& nbrs,
                                      std::map<std::pair<int, int>, std::vector<int>>& opposite) {
    nbrs.assign(x.size(), {});
    opposite.clear();
    for (const Tri& t : tris) {
      for (int k = 0; k < 3; ++k) {
        int a = t.v[static_cast<size_t>(k)], b = t.v[static_cast<size_t>((k + 1) % 3)];
        int c = t.v[static_cast<size_t>((k + 2) % 3)];
        opposite[{std::min(a, b), std::max(a, b)}].push_back(c);
        nbrs[static_cast<size_t>(a)].push_back(b);  // each undirected edge once per direction
      }
    }
  };
  std::vector<std::vector<int>> nbrs;
  std::map<std::pair<int, int>, std::vector<int>> opposite;
  for (int level = 0; level < levels; ++level) {
    neighbours_and_opposites(nbrs, opposite);
    std::vector<Eigen::Vector3d> next(x.size());
    for (size_t i = 0; i < x.size(); ++i) {
      const int n = static_cast<int>(nbrs[i].size());
      const double beta = loop_beta(n);
      next[i] = (1.0 - n * beta) * x[i];
      for (int j : nbrs[i]) next[i] += beta * x[static_cast<size_t>(j)];
    }
    std::map<std::pair<int, int>, int> edge_vertex;
    for (const auto& [edge, opp] : opposite) {
      EXPECT_EQ(opp.size(), 2u);
      edge_vertex[edge] = static_cast<int>(next.size());
      next.push_back(
          0.375 * (x[static_cast<size_t>(edge.first)] + x[static_cast<size_t>(edge.second)]) +
          0.125 * (x[static_cast<size_t>(opp[0])] + x[static_cast<size_t>(opp[1])]));
    }
    std::vector<Tri> finer;
    for (const Tri& t : tris) {
      std::array<int, 3> m;
      std::array<Eigen::Vector2d, 3> muv;
      for (size_t k = 0; k < 3; ++k) {
        int a = t.v[k], b = t.v[(k + 1) % 3];
        m[k] = edge_vertex[{std::min(a, b), std::max(a, b)}];
        muv[k] = 0.5 * (t.uv[k] + t.uv[(k + 1) % 3]);
      }
      finer.push_back({{t.v[0], m[0], m[2]}, t.base, {t.uv[0], muv[0], muv[2]}});
      finer.push_back({{t.v[1], m[1], m[0]}, t.base, {t.uv[1], muv[1], muv[0]}});
      finer.push_back({{t.v[2], m[2], m[1]}, t.base, {t.uv[2], muv[2], muv[1]}});
      finer.push_back({{m[0], m[1], m[2]}, t.base, {muv[0], muv[1], muv[2]}});
    }
    x = std::move(next);
    tris = std::move(finer);
  }
  neighbours_and_opposites(nbrs, opposite);
  LimitSamples s;
  s.points.resize(static_cast<Eigen::Index>(x.size()), 3);
  for (size_t i = 0; i < x.size(); ++i) {
    const int n = static_cast<int>(nbrs[i].size());
    const double chi = 1.0 / (3.0 / (8.0 * loop_beta(n)) + n);
    Eigen::Vector3d p = (1.0 - n * chi) * x[i];
    for (int j : nbrs[i]) p += chi * x[static_cast<size_t>(j)];
    s.points.row(static_cast<Eigen::Index>(i)) = p.transpose();
  }
  s.locations.assign(x.size(), {});
  for (const Tri& t : tris) {
    for (size_t k = 0; k < 3; ++k)
      s.locations[static_cast<size_t>(t.v[k])] = {t.base, t.uv[k].x(), t.uv[k].y()};
  }
  return s;
}

ricci::Mesh perturbed_icosphere() {
  return ricci::make_random_perturbed(ricci::make_icosphere(1), 0.15, 7);
}

// OpenSubdiv's limit surface passes through the limit points of the independent subdivision
// at their dyadic (u, v): checks the scheme, the boundary-free masks and the ptex convention.
TEST(LoopSurface, MatchesIndependentLoopLimitPoints) {
  for (const ricci::Mesh& control :
       {perturbed_icosphere(), ricci::read_mesh(msp_test::test_mesh("closed_g2/eight_cgal.off"))}) {
    const LoopSurface surface(control);
    const LimitSamples s = loop_limit_samples(control, 2);
    const Eigen::MatrixX3d patch_points = surface.patch_points(positions(control));
    const double scale = (s.points.colwise().maxCoeff() - s.points.colwise().minCoeff()).norm();
    double worst = 0.0;
    for (size_t i = 0; i < s.locations.size(); ++i) {
      const LoopPoint p = surface.evaluate(patch_points, s.locations[i]);
      worst = std::max(
          worst, (p.position - s.points.row(static_cast<Eigen::Index>(i)).transpose()).norm());
    }
    EXPECT_LT(worst / scale, 1e-12) << control.n_vertices() << " control points";
  }
}

// The design matrix (limit stencils) and the patch evaluation are two OpenSubdiv routes to the
// same surface; rows sum to one (affine invariance); derivatives match central differences.
TEST(LoopSurface, DesignMatrixMatchesPatchEvaluationAndDerivatives) {
  const ricci::Mesh control = perturbed_icosphere();
  const LoopSurface surface(control);
  const Eigen::MatrixX3d x = positions(control);
  const Eigen::MatrixX3d patch_points = surface.patch_points(x);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(0.05, 0.9);
  std::vector<LoopLocation> locations;
  for (int f = 0; f < static_cast<int>(control.n_faces()); ++f) {
    double u = unit(rng), v = unit(rng) * (0.95 - u);
    locations.push_back({f, u, std::max(v, 0.01)});
  }
  const auto a = surface.design_matrix(locations);
  const Eigen::MatrixX3d ax = a * x;
  const double h = 1e-6;
  for (size_t i = 0; i < locations.size(); ++i) {
    const auto e = static_cast<Eigen::Index>(i);
    EXPECT_NEAR(a.row(e).sum(), 1.0, 1e-12);
    const LoopLocation& l = locations[i];
    const LoopPoint p = surface.evaluate(patch_points, l);
    EXPECT_LT((p.position - ax.row(e).transpose()).norm(), 1e-12);
    const Eigen::Vector3d fd_u = (surface.evaluate(patch_points, {l.face, l.u + h, l.v}).position -
                                  surface.evaluate(patch_points, {l.face, l.u - h, l.v}).position) /
                                 (2 * h);
    const Eigen::Vector3d fd_v = (surface.evaluate(patch_points, {l.face, l.u, l.v + h}).position -
                                  surface.evaluate(patch_points, {l.face, l.u, l.v - h}).position) /
                                 (2 * h);
    EXPECT_LT((fd_u - p.du).norm(), 1e-6 * (1.0 + p.du.norm()));
    EXPECT_LT((fd_v - p.dv).norm(), 1e-6 * (1.0 + p.dv.norm()));
  }
}

// Data sampled from the limit surface of a known control mesh (by the independent subdivision)
// give back exactly those control points with lambda = 0.
TEST(LoopFit, RecoversControlPointsOfExactLimitSamples) {
  for (const ricci::Mesh& control :
       {perturbed_icosphere(), ricci::read_mesh(msp_test::test_mesh("closed_g2/eight_cgal.off"))}) {
    const LoopSurface surface(control);
    const LimitSamples s = loop_limit_samples(control, 2);
    const LoopSolve solve = fit_loop_control_points(surface, s.locations, s.points, 0.0);
    const Eigen::MatrixX3d x = positions(control);
    const double scale = (x.colwise().maxCoeff() - x.colwise().minCoeff()).norm();
    EXPECT_LT((solve.control - x).cwiseAbs().maxCoeff() / scale, 1e-8)
        << control.n_vertices() << " control points";
    EXPECT_EQ(solve.smoothness_weight, 0.0);
  }
}

// Boundary interpolation (VTX_BOUNDARY_EDGE_ONLY): the limit curve of a boundary is the cubic
// B-spline of the boundary vertices, so at a boundary vertex it is (prev + 4 v + next) / 6.
TEST(LoopSurface, BoundaryIsCubicBSplineOfBoundaryVertices) {
  const ricci::Mesh control = ricci::make_random_perturbed(ricci::make_disk(4, 12), 0.1, 11);
  const LoopSurface surface(control);
  const Eigen::MatrixX3d patch_points = surface.patch_points(positions(control));
  int checked = 0;
  for (auto h : control.halfedges()) {
    if (!control.is_boundary(h)) continue;
    const auto v = control.to_vertex_handle(h);
    const auto prev = control.from_vertex_handle(h),
               next = control.to_vertex_handle(control.next_halfedge_handle(h));
    const Eigen::Vector3d expected =
        (ricci::to_eigen(control.point(prev)) + 4.0 * ricci::to_eigen(control.point(v)) +
         ricci::to_eigen(control.point(next))) /
        6.0;
    const auto f = control.face_handle(control.opposite_halfedge_handle(h));
    LoopLocation corner_location{f.idx(), 0.0, 0.0};
    for (int k = 0; k < 3; ++k) {
      if (surface.corner(f.idx(), k) == v.idx())
        corner_location = {f.idx(), k == 1 ? 1.0 : 0.0, k == 2 ? 1.0 : 0.0};
    }
    EXPECT_LT((surface.evaluate(patch_points, corner_location).position - expected).norm(), 1e-12);
    ++checked;
  }
  EXPECT_EQ(checked, 48);
}

// The fit commutes with similarities of the data: rows of A sum to one and L kills constants,
// so fitting s R P + t gives s R X + t.
TEST(LoopFit, FitIsAffineEquivariant) {
  const ricci::Mesh control = perturbed_icosphere();
  const LoopSurface surface(control);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<LoopLocation> locations;
  Eigen::MatrixX3d points(6 * static_cast<Eigen::Index>(control.n_faces()), 3);
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const double u = unit(rng), v = unit(rng) * (1.0 - u);
    locations.push_back({static_cast<int>(i / 6), u, v});
    points.row(i) = Eigen::RowVector3d(unit(rng), unit(rng), unit(rng));
  }
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::RowVector3d shift(1e3, -2e3, 5e2);
  const double scale = 1e4;
  const Eigen::MatrixX3d moved = (scale * points * rotation.transpose()).rowwise() + shift;
  const LoopSolve a = fit_loop_control_points(surface, locations, points, 1e-3);
  const LoopSolve b = fit_loop_control_points(surface, locations, moved, 1e-3);
  const Eigen::MatrixX3d expected = (scale * a.control * rotation.transpose()).rowwise() + shift;
  EXPECT_LT((b.control - expected).cwiseAbs().maxCoeff() / scale, 1e-9);
}

// Projection finds the surface again from perturbed parameters: samples on the surface, started
// from the face's centre, end at distance ~0.
TEST(LoopFit, ProjectionReachesPointsOnTheSurface) {
  const ricci::Mesh control = perturbed_icosphere();
  const LoopSurface surface(control);
  const LimitSamples s = loop_limit_samples(control, 2);
  std::vector<LoopLocation> start(s.locations.size());
  for (size_t i = 0; i < start.size(); ++i) start[i] = {s.locations[i].face, 1.0 / 3.0, 1.0 / 3.0};
  const LoopProjection p =
      project_to_loop_surface(surface, positions(control), s.points, start, 20);
  const double scale = (s.points.colwise().maxCoeff() - s.points.colwise().minCoeff()).norm();
  EXPECT_GT(p.start_distances.maxCoeff() / scale, 1e-2);
  EXPECT_LT(p.distances.maxCoeff() / scale, 1e-9);
  EXPECT_TRUE((p.distances.array() <= p.start_distances.array()).all());
}

// Spot (2930 vertices) with about 500 control points.
TEST(LoopFit, FitsClosedGenusZeroScan) {
  const ricci::Mesh dense = ricci::read_mesh(msp_test::test_mesh("closed_g0/spot.obj.gz"));
  LoopFitOptions options;
  options.control_points = 500;
  const LoopFitResult r = fit_loop_surface(dense, options);
  EXPECT_NEAR(r.control_points, 500, 50);
  EXPECT_EQ(r.samples, 2930);
  EXPECT_GT(r.smoothness_weight, 0.0);
  EXPECT_LE(r.rms_relative, r.parameter_rms_relative);
  EXPECT_LE(r.max_relative, r.parameter_max_relative);
  EXPECT_GT(r.rms_relative, 0.0);
  // Measured 1.43e-3 and 1.33e-2 (498 control points, lambda 1e-3, 2 parameter corrections).
  EXPECT_LT(r.rms_relative, 2.2e-3);
  EXPECT_LT(r.max_relative, 2e-2);
}

// head.off: 3 boundary loops; boundary interpolation keeps the fit finite and close.
TEST(LoopFit, FitsOpenScan) {
  const ricci::Mesh dense = ricci::read_mesh(msp_test::test_mesh("open/head.off"));
  LoopFitOptions options;
  options.control_points = 500;
  const LoopFitResult r = fit_loop_surface(dense, options);
  EXPECT_TRUE(std::isfinite(r.rms_relative) && std::isfinite(r.max_relative));
  for (auto v : r.control.vertices()) EXPECT_TRUE(ricci::to_eigen(r.control.point(v)).allFinite());
  // Measured 1.63e-3 and 8.9e-3 (508 control points, lambda 1e-3, 2 parameter corrections).
  EXPECT_LT(r.rms_relative, 2.5e-3);
  EXPECT_LT(r.max_relative, 1.4e-2);
}

TEST(LoopFit, BadInputThrows) {
  const ricci::Mesh dense = ricci::read_mesh(msp_test::test_mesh("closed_g0/knight_decimated.off"));
  LoopFitOptions options;
  EXPECT_THROW((void)fit_loop_surface(ricci::Mesh(), options), ricci::InvalidInputError);
  options.control_points = 3;
  EXPECT_THROW((void)fit_loop_surface(dense, options), ricci::InvalidInputError);
  options.control_points = 100;
  options.projection_steps = -1;
  EXPECT_THROW((void)fit_loop_surface(dense, options), ricci::InvalidInputError);

  const ricci::Mesh control = perturbed_icosphere();
  const LoopSurface surface(control);
  const Eigen::MatrixX3d one_point = Eigen::MatrixX3d::Zero(1, 3);
  // One sample cannot determine 42 control points without the smoothness term.
  EXPECT_THROW((void)fit_loop_control_points(surface, {{0, 0.2, 0.2}}, one_point, 0.0),
               ricci::SolverError);
  EXPECT_THROW((void)fit_loop_control_points(surface, {{0, 0.2, 0.2}}, one_point, -1.0),
               ricci::InvalidInputError);
  EXPECT_THROW((void)surface.design_matrix({{-1, 0.2, 0.2}}), ricci::InvalidInputError);
  EXPECT_THROW((void)surface.design_matrix({{0, 0.8, 0.8}}), ricci::InvalidInputError);
  LoopSurfaceOptions bad;
  bad.isolation_level = 0;
  EXPECT_THROW(LoopSurface(control, bad), ricci::InvalidInputError);
}

}  // namespace
}  // namespace spline
