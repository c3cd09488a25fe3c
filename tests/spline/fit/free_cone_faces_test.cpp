// ScanFitOptions::free_cone_faces_from_genus / free_cone_rings: next to a large cone the fit
// drops the fairing constraints on the faces with a corner within free_cone_rings rings of the
// cone (generated genus 10: the constrained fit folds there). Checked on the genus-2 "eight"
// with the rule lowered to genus 2: exactly those faces are freed, the fit still satisfies the
// constraints between the other faces, and it does not satisfy them across the freed ones.
#include <gtest/gtest.h>

#include <vector>

#include "ricci/mesh/io.h"
#include "spline/fair/fair.h"
#include "spline/fit/fit.h"
#include "test_paths.h"

namespace spline {
namespace {

// Faces of `mesh` with a corner within `rings` edges of `cone` (breadth-first over edges).
int faces_near(const ricci::Mesh& mesh, int cone, int rings) {
  std::vector<int> ring(mesh.n_vertices(), -1);
  ring[static_cast<std::size_t>(cone)] = 0;
  for (int r = 0; r < rings; ++r)
    for (auto v : mesh.vertices())
      if (ring[v.idx()] == r)
        for (auto w : mesh.vv_range(v))
          if (ring[w.idx()] < 0) ring[w.idx()] = r + 1;
  int count = 0;
  for (auto f : mesh.faces()) {
    bool near = false;
    for (auto v : mesh.fv_range(f)) near = near || ring[v.idx()] >= 0;
    count += near;
  }
  return count;
}

// max |C c| over the rows of the r = 1 fairing constraints between faces marked in `active`.
double constraint_residual(const ScanFitResult& fit, const std::vector<char>& active) {
  FairOptions fair;
  fair.r = 1;
  fair.active_faces = active;
  const Eigen::SparseMatrix<double> c = fairing_constraints(*fit.spline.space, fair);
  return (c * fit.spline.control_points).cwiseAbs().maxCoeff();
}

TEST(FreeConeFaces, FacesNextToTheConeAreFittedWithoutTheFairing) {
  const ricci::Mesh dense = ricci::read_mesh(msp_test::test_mesh("closed_g2/eight.off"));
  ScanFitOptions options;
  options.free_cone_faces_from_genus = 2;
  options.free_cone_rings = 3;
  const ScanFitResult fit = fit_scan(dense, options);
  const auto& problem = fit.atlas.problem;
  ASSERT_GE(problem.cone, 0);
  EXPECT_EQ(fit.unconstrained_faces, faces_near(problem.mesh, problem.cone, 3));
  EXPECT_GT(fit.unconstrained_faces, 0);
  const std::vector<char>& constrained = fit.fit_options.constraint_faces;
  ASSERT_EQ(static_cast<int>(constrained.size()), static_cast<int>(problem.mesh.n_faces()));
  const double scale = fit.spline.control_points.cwiseAbs().maxCoeff();
  const double kept = constraint_residual(fit, constrained);
  const double all = constraint_residual(fit, {});
  EXPECT_LT(kept, 1e-6 * scale);  // the fairing holds between the constrained faces
  EXPECT_GT(all, 1e3 * kept);     // and not across the freed ones

  // Below the genus the rule starts at, every face is constrained.
  options.free_cone_faces_from_genus = 3;
  const ScanFitResult full = fit_scan(dense, options);
  EXPECT_EQ(full.unconstrained_faces, 0);
  EXPECT_TRUE(full.fit_options.constraint_faces.empty());
  EXPECT_LT(constraint_residual(full, {}), 1e-6 * scale);
}

}  // namespace
}  // namespace spline
