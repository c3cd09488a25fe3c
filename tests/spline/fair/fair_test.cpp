// Fairing (manifold-splines eq. 14): polynomials pass unchanged, constraints are met, r = 0
// shares the edge control points, and the result is the nearest constrained point (projection).
#include <gtest/gtest.h>

#include <random>

#include "ricci/mesh/errors.h"
#include "spline/fair/fair.h"
#include "spline/manifold/manifold_fixtures.h"

namespace spline {
namespace {

using testing::small_space;

// A random vector polynomial of degree n in chart 0 and the faces whose neighbourhood chart 0
// holds (where control_points_of reproduces it consistently with every neighbourhood chart).
struct PolynomialPatch {
  Eigen::MatrixX3d control_points;
  std::vector<char> active;
};
PolynomialPatch polynomial_patch(const ManifoldSplineSpace& space, int n) {
  BivariatePolynomial p;
  p.degree = n;
  std::srand(static_cast<unsigned>(3 + n));
  p.coefficients = Eigen::MatrixXd::Random(monomial_count(n), 3);
  p.origin = space.chart_point(0, space.domain_faces()[0], Eigen::Vector3d::Constant(1.0 / 3));
  p.scale = space.atlas().domain_diameter;
  PolynomialPatch patch{space.control_points_of(p, 0),
                        std::vector<char>(static_cast<std::size_t>(space.face_count()), 0)};
  for (int f : space.domain_faces()) patch.active[f] = space.holds_neighbourhood(0, f);
  return patch;
}

TEST(Fairing, LeavesAPolynomialUnchanged) {
  for (const char* model : {"genus1.off", "genus2.off"}) {
    for (int n = 2; n <= 5; ++n) {
      const auto space = small_space(model, n);
      const PolynomialPatch patch = polynomial_patch(*space, n);
      for (int r = 0; r < n; ++r) {
        FairOptions options;
        options.r = r;
        options.active_faces = patch.active;
        const FairResult result = fair(*space, patch.control_points, options);
        EXPECT_GT(result.constraints, 1000);
        const double scale = patch.control_points.cwiseAbs().maxCoeff();
        EXPECT_LT(result.max_change, 1e-10 * scale) << model << " n=" << n << " r=" << r;
      }
    }
  }
}

TEST(Fairing, ConstantSurfaceOnTheWholeManifoldIsUnchanged) {
  const auto space = small_space("genus2.off", 3);
  const Eigen::MatrixX3d c =
      Eigen::RowVector3d(1.5, -2.0, 0.25).replicate(space->function_count(), 1);
  for (int r = 0; r < 3; ++r) {
    FairOptions options;
    options.r = r;
    const FairResult result = fair(*space, c, options);
    EXPECT_LT(result.max_change, 1e-11) << "r=" << r;
  }
}

// Random control points: after fairing every constraint holds, r = 0 makes the two faces' edge
// control points equal, and the change is the orthogonal projection (c - c~ is orthogonal to
// the constraint null space, checked against feasible directions: polynomial patches).
TEST(Fairing, MeetsTheConstraintsAndProjects) {
  for (int n = 2; n <= 3; ++n) {
    const auto space = small_space("genus2.off", n);
    std::srand(static_cast<unsigned>(n));
    const Eigen::MatrixX3d c = Eigen::MatrixX3d::Random(space->function_count(), 3);
    for (int r = 0; r < n; ++r) {
      FairOptions options;
      options.r = r;
      const FairResult result = fair(*space, c, options);
      const auto constraints = fairing_constraints(*space, options);
      const Eigen::MatrixX3d residual = constraints * result.control_points;
      EXPECT_LT(residual.cwiseAbs().maxCoeff(), 1e-8) << "n=" << n << " r=" << r;
      EXPECT_GT(result.max_change, 1e-3);  // random points are not feasible
      // Orthogonal projection: idempotent and symmetric (<P a, b> = <a, P b>).
      const FairResult again = fair(*space, result.control_points, options);
      // r = n - 1 ties all but one control point of each face to each neighbour: C then has
      // singular values near 1e-5 and a residual of 1e-9 leaves ~1e-6 along them.
      EXPECT_LT(again.max_change, r == n - 1 ? 1e-5 : 1e-8) << "n=" << n << " r=" << r;
      const Eigen::MatrixX3d other = Eigen::MatrixX3d::Random(c.rows(), 3);
      const FairResult projected_other = fair(*space, other, options);
      const double asymmetry = (result.control_points.cwiseProduct(other)).sum() -
                               (c.cwiseProduct(projected_other.control_points)).sum();
      EXPECT_LT(std::abs(asymmetry), 1e-8 * c.norm() * other.norm()) << "n=" << n << " r=" << r;
      if (r != 0) continue;
      // Shared edge control points: beta_k = 0 of face f equals the same arguments' point of g.
      int checked = 0;
      const auto betas = multi_indices(n);
      for (int f : space->domain_faces()) {
        for (int k = 0; k < 3; ++k) {
          const int g = space->neighbour(f, k);
          if (g < 0 || !space->in_domain(g)) continue;
          // Corner of g opposite the shared edge: the one not shared with f.
          for (int b = 0; b < static_cast<int>(betas.size()); ++b) {
            if (betas[b][k] != 0) continue;
            const auto fc = space->face_clouds(space->chart_of(f), f);
            const auto gc = space->face_clouds(space->chart_of(f), g);
            const auto args = control_point_arguments(fc[0], fc[1], fc[2], betas[b]);
            // Find g's multi-index with the same argument multiset.
            for (int e = 0; e < static_cast<int>(betas.size()); ++e) {
              auto other = control_point_arguments(gc[0], gc[1], gc[2], betas[e]);
              bool same = other.size() == args.size();
              for (std::size_t i = 0; same && i < args.size(); ++i) {
                bool found = false;
                for (auto& x : other) {
                  if ((x - args[i]).norm() < 1e-12 * space->atlas().domain_diameter) {
                    x.setConstant(1e300);
                    found = true;
                    break;
                  }
                }
                same = found;
              }
              if (!same) continue;
              EXPECT_LT((result.control_points.row(space->function_index(f, b)) -
                         result.control_points.row(space->function_index(g, e)))
                            .norm(),
                        1e-9);
              ++checked;
            }
          }
        }
      }
      EXPECT_GT(checked, 1000);
    }
  }
}

TEST(Fairing, BadInputThrows) {
  const auto space = small_space("genus1.off", 3);
  FairOptions options;
  options.r = 3;
  EXPECT_THROW((void)fair(*space, Eigen::MatrixX3d::Zero(space->function_count(), 3), options),
               ricci::InvalidInputError);
  options.r = 1;
  EXPECT_THROW((void)fair(*space, Eigen::MatrixX3d::Zero(5, 3), options), ricci::InvalidInputError);
}

}  // namespace
}  // namespace spline
