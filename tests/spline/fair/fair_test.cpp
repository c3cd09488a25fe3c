// Fairing (manifold-splines eq. 14): polynomials pass unchanged, constraints are met, r = 0
// shares the edge control points, and the result is the nearest constrained point (projection).
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <random>
#include <set>

#include "ricci/mesh/errors.h"
#include "ricci/topology/slice.h"
#include "spline/fair/constrained_solve.h"
#include "spline/basis/blossom.h"
#include "spline/basis/multi_index.h"
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
      // At r = n - 1 those ~1e-6 errors along C's near-singular directions bound the symmetry
      // too (the atlas' rounding moved it between 1e-9 and 1.4e-8 relative).
      const double symmetry_bound = r == n - 1 ? 1e-6 : 1e-8;
      EXPECT_LT(std::abs(asymmetry), symmetry_bound * c.norm() * other.norm())
          << "n=" << n << " r=" << r;
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

// Eq. 14's rows are C^r-like conditions: on a closed torus domain the space {C c = 0} has, per
// coordinate, the dimension of the shared control points for r = 0 (V + 2E + F for cubics: one
// per argument multiset) and of generic C^1 cubics for r = 1 (3V + F - E_interior, = F on a
// torus), with a clear gap in the singular values (no near-dependent rows from the charts).
TEST(Fairing, ConstraintSpaceHasTheDimensionOfSharedPointsAndC1Cubics) {
  const auto space = small_space("genus1.off", 3, 150);
  const ricci::Mesh& mesh = testing::small_atlas("genus1.off", 150).problem.mesh;
  std::set<int> vertices;
  std::set<std::pair<int, int>> edges;
  int interior = 0;
  for (int f : space->domain_faces()) {
    const auto hs = ricci::face_halfedges(mesh, mesh.face_handle(f));
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.from_vertex_handle(hs[k]).idx(), b = mesh.to_vertex_handle(hs[k]).idx();
      vertices.insert(a);
      edges.insert({std::min(a, b), std::max(a, b)});
      const int g = space->neighbour(f, k);
      if (g >= 0 && space->in_domain(g)) ++interior;
    }
  }
  const int v = static_cast<int>(vertices.size()), e = static_cast<int>(edges.size());
  const int f = space->domain_face_count();
  interior /= 2;
  ASSERT_GT(f, 100);
  for (int r = 0; r <= 1; ++r) {
    FairOptions options;
    options.r = r;
    const Eigen::SparseMatrix<double> c = fairing_constraints(*space, options);
    const Eigen::MatrixXd ctc = Eigen::MatrixXd(Eigen::SparseMatrix<double>(c.transpose() * c));
    const Eigen::VectorXd sigma =
        Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(ctc, Eigen::EigenvaluesOnly)
            .eigenvalues()
            .cwiseMax(0.0)
            .cwiseSqrt();
    const auto below = [&](double t) {
      return static_cast<int>((sigma.array() < t * sigma.maxCoeff()).count());
    };
    const int expected = r == 0 ? v + 2 * e + f : 3 * v + f - interior;
    EXPECT_EQ(below(1e-6), expected) << "r=" << r;  // sqrt of eigenvalue rounding ~1e-8
    EXPECT_EQ(below(1e-2), expected) << "r=" << r;  // the gap
  }
}

// Fig. 13 on two triangles: fairing with only I and J active, r = 1. For each (p, q), p + q =
// n - 1, with a = (t_{1,0..p-1}, t_{2,0..q-1}) the knots of the shared edge's clouds, the
// control points P(a, t_{1,p}), P(a, t_{2,q}) (shared by I and J), P^I(a, v0) and P^J(a, v3) are
// afterwards the images of four points under one affine map of the plane: coplanar (the paper's
// six highlighted points, two pairs coinciding), and the fourth is the affine combination of the
// other three with v3's barycentric coordinates. Random control points are neither.
TEST(Fairing, RowsOfR1MakeFig13PointsAnAffineImageOnTwoTriangles) {
  const int n = 3;
  const auto space = small_space("genus2.off", n);
  int face = -1;
  for (int f : space->domain_faces()) {
    const int g = space->neighbour(f, 0);
    if (g >= 0 && space->in_domain(g)) {
      face = f;
      break;
    }
  }
  ASSERT_GE(face, 0);
  const int other = space->neighbour(face, 0);
  const int chart = space->chart_of(face);
  const auto own = space->face_clouds(chart, face);
  const auto theirs = space->face_clouds(chart, other);
  // J's corners at I's corners 1 and 2, and its apex.
  std::array<int, 3> corner{-1, -1, -1};
  for (int k = 0; k < 3; ++k) {
    for (int a = 1; a <= 2; ++a) {
      if ((theirs[k].knots[0] - own[a].knots[0]).norm() < 1e-12) corner[a] = k;
    }
  }
  ASSERT_GE(corner[1], 0);
  ASSERT_GE(corner[2], 0);
  corner[0] = 3 - corner[1] - corner[2];
  const Eigen::Vector2d v3 = theirs[corner[0]].knots[0];

  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Eigen::MatrixX3d c(space->function_count(), 3);
  for (Eigen::Index i = 0; i < c.rows(); ++i) c.row(i) << unit(rng), unit(rng), unit(rng);
  FairOptions options;
  options.r = 1;
  options.active_faces.assign(static_cast<std::size_t>(space->face_count()), 0);
  options.active_faces[face] = options.active_faces[other] = 1;
  const FairResult result = fair(*space, c, options);
  EXPECT_EQ(result.constraints, 2 * 7);  // each side: 4 rows beta_k = 0, 3 rows beta_k = 1

  const auto point = [&](const Eigen::MatrixX3d& x, int f, const std::array<int, 3>& at,
                         const Eigen::Vector3i& b) -> Eigen::Vector3d {
    Eigen::Vector3i beta;
    for (int k = 0; k < 3; ++k) beta[at[k]] = b[k];
    return x.row(space->function_index(f, multi_index_position(beta))).transpose();
  };
  const std::array<int, 3> identity{0, 1, 2};
  const double scale = c.cwiseAbs().maxCoeff();
  double random_volume = 0.0;
  for (int p = 0; p < n; ++p) {
    const int q = n - 1 - p;
    const Eigen::Vector2d x1 = own[1].knots[p], x2 = own[2].knots[q], x0 = own[0].knots[0];
    // v3 = l0 x0 + l1 x1 + l2 x2.
    Eigen::Matrix3d m;
    m << x0.x(), x1.x(), x2.x(), x0.y(), x1.y(), x2.y(), 1.0, 1.0, 1.0;
    const Eigen::Vector3d l = m.lu().solve(Eigen::Vector3d(v3.x(), v3.y(), 1.0));
    for (const bool faired : {false, true}) {
      const Eigen::MatrixX3d& x = faired ? result.control_points : c;
      const Eigen::Vector3d i1 = point(x, face, identity, {0, p + 1, q});
      const Eigen::Vector3d i2 = point(x, face, identity, {0, p, q + 1});
      const Eigen::Vector3d i0 = point(x, face, identity, {1, p, q});
      const Eigen::Vector3d j1 = point(x, other, corner, {0, p + 1, q});
      const Eigen::Vector3d j2 = point(x, other, corner, {0, p, q + 1});
      const Eigen::Vector3d j0 = point(x, other, corner, {1, p, q});
      const double volume = std::abs((i2 - i1).cross(i0 - i1).dot(j0 - i1));
      if (!faired) {
        random_volume = std::max(random_volume, volume);
        continue;
      }
      EXPECT_LT((i1 - j1).norm(), 1e-10 * scale) << "p=" << p;
      EXPECT_LT((i2 - j2).norm(), 1e-10 * scale) << "p=" << p;
      EXPECT_LT(volume, 1e-9 * std::pow(scale, 3)) << "p=" << p;
      EXPECT_LT((j0 - (l[0] * i0 + l[1] * i1 + l[2] * i2)).norm(), 1e-9 * scale) << "p=" << p;
    }
  }
  EXPECT_GT(random_volume, 1e-2 * std::pow(scale, 3));
  // Faces other than I and J are not touched.
  for (int f : space->domain_faces()) {
    if (f == face || f == other) continue;
    for (int b = 0; b < space->functions_per_face(); ++b) {
      const int i = space->function_index(f, b);
      ASSERT_EQ(result.control_points.row(i), c.row(i));
    }
  }
}

// solve_constrained: merged rows x_i = x_j are exact, the other rows reach the tolerance, and
// the result is the KKT point (gradient K x - b orthogonal to the feasible set).
TEST(ConstrainedSolve, MatchesADenseNullSpaceSolution) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const int n = 40;
  Eigen::MatrixXd a(n + 10, n);
  for (Eigen::Index i = 0; i < a.size(); ++i) a.data()[i] = unit(rng);
  const Eigen::MatrixXd k = a.transpose() * a;
  Eigen::MatrixX3d b(n, 3);
  for (Eigen::Index i = 0; i < b.size(); ++i) b.data()[i] = unit(rng);
  // Rows: x0 = x1, x1 = x2 (merged), a general row, and the same general row twice (dependent).
  std::vector<Eigen::Triplet<double>> t{{0, 0, 1.0},  {0, 1, -1.0}, {1, 1, 1.0}, {1, 2, -1.0},
                                        {2, 3, 0.7},  {2, 4, -0.2}, {2, 5, 0.4}, {3, 3, 1.4},
                                        {3, 4, -0.4}, {3, 5, 0.8},  {4, 6, 1.0}, {4, 9, 0.5}};
  Eigen::SparseMatrix<double> c(5, n);
  c.setFromTriplets(t.begin(), t.end());
  const Eigen::SparseMatrix<double> lower = Eigen::MatrixXd(k.triangularView<Eigen::Lower>()).sparseView();
  const ConstrainedSolution s = solve_constrained(lower, b, c, {});
  EXPECT_EQ(s.merged_rows, 2);
  EXPECT_EQ(s.reduced_unknowns, n - 2);
  EXPECT_LT(s.max_residual, 1e-11);
  // Null space of dense C, then the reduced normal equations.
  const Eigen::MatrixXd cd = Eigen::MatrixXd(c);
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(cd);
  const Eigen::MatrixXd z = lu.kernel();
  ASSERT_EQ(z.cols(), n - 4);
  const Eigen::MatrixXd y = (z.transpose() * k * z).ldlt().solve(z.transpose() * b);
  const Eigen::MatrixXd x = z * y;
  EXPECT_LT((s.x - x).cwiseAbs().maxCoeff(), 1e-9 * x.cwiseAbs().maxCoeff());
}

// A reduction of C built once (reduce_constraints) serves solves against several K, each giving
// exactly what solve_constrained builds for itself; a reduction of another C is refused.
TEST(ConstrainedSolve, ReducedConstraintsServeSeveralMatrices) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const int n = 30;
  std::vector<Eigen::Triplet<double>> t{{0, 0, 1.0}, {0, 1, -1.0}, {1, 2, 0.3}, {1, 3, -0.9},
                                        {2, 7, 1.0}, {2, 8, -1.0}, {3, 2, 0.6}, {3, 3, -1.8}};
  Eigen::SparseMatrix<double> c(4, n);
  c.setFromTriplets(t.begin(), t.end());
  const ReducedConstraints reduced = reduce_constraints(c);
  EXPECT_EQ(reduced.classes, n - 2);
  EXPECT_EQ(reduced.c_r.rows(), 2);
  EXPECT_EQ(reduced.ctc_lower.rows(), n - 2);
  for (int trial = 0; trial < 2; ++trial) {
    Eigen::MatrixXd a(n + 5, n);
    for (Eigen::Index i = 0; i < a.size(); ++i) a.data()[i] = unit(rng);
    const Eigen::MatrixXd k = a.transpose() * a;
    Eigen::MatrixX3d b(n, 3), reference(n, 3);
    for (Eigen::Index i = 0; i < b.size(); ++i) b.data()[i] = unit(rng);
    for (Eigen::Index i = 0; i < reference.size(); ++i) reference.data()[i] = unit(rng);
    const Eigen::SparseMatrix<double> lower =
        Eigen::MatrixXd(k.triangularView<Eigen::Lower>()).sparseView();
    const ConstrainedSolution own = solve_constrained(lower, b, c, reference);
    const ConstrainedSolution shared = solve_constrained(lower, b, c, reduced, reference);
    EXPECT_LT(own.max_residual, 1e-10);
    EXPECT_EQ(shared.iterations, own.iterations);
    EXPECT_EQ(shared.merged_rows, own.merged_rows);
    EXPECT_EQ(shared.remaining_rows, own.remaining_rows);
    EXPECT_EQ(shared.penalty, own.penalty);
    EXPECT_TRUE((shared.x.array() == own.x.array()).all());
  }
  Eigen::SparseMatrix<double> other(3, n);
  other.setFromTriplets(t.begin(), t.begin() + 4);
  const Eigen::SparseMatrix<double> identity =
      Eigen::MatrixXd(Eigen::MatrixXd::Identity(n, n)).sparseView();
  EXPECT_THROW((void)solve_constrained(identity, Eigen::MatrixX3d::Zero(n, 3), other, reduced, {}),
               ricci::InvalidInputError);
}

// Every row of C is its definition, built pair by pair: for face I, the edge opposite corner k
// and its neighbour J, and beta with beta_k <= r, +1 at c_{I,beta} and minus the blossom of J's
// polynomial (as a map of J's control points, in I's neighbourhood chart) at beta's arguments.
// fairing_constraints builds each J's map once per chart; the rows must not change by a bit.
TEST(Fairing, ConstraintRowsAreTheBlossomsOfTheNeighboursPolynomials) {
  for (int n = 3; n <= 4; ++n) {
    const auto space = small_space("genus2.off", n);
    const int m = space->functions_per_face();
    const std::vector<Eigen::Vector3i> betas = multi_indices(n);
    const Eigen::MatrixXd identity = Eigen::MatrixXd::Identity(m, m);
    for (int r = 0; r < n; ++r) {
      FairOptions options;
      options.r = r;
      const Eigen::SparseMatrix<double, Eigen::RowMajor> c = fairing_constraints(*space, options);
      Eigen::SparseMatrix<double, Eigen::RowMajor> expected(c.rows(), c.cols());
      std::vector<Eigen::Triplet<double>> triplets;
      int row = 0;
      std::set<int> charts;
      for (int face : space->domain_faces()) {
        const int chart = space->chart_of(face);
        const auto own = space->face_clouds(chart, face);
        for (int k = 0; k < 3; ++k) {
          const int other = space->neighbour(face, k);
          if (other < 0 || !space->in_domain(other)) continue;
          charts.insert(chart);
          const auto theirs = space->face_clouds(chart, other);
          const BivariatePolynomial map =
              polynomial_from_control_points(theirs[0], theirs[1], theirs[2], identity);
          for (int b = 0; b < m; ++b) {
            if (betas[b][k] > r) continue;
            const Eigen::VectorXd w =
                blossom(map, control_point_arguments(own[0], own[1], own[2], betas[b]));
            triplets.emplace_back(row, space->function_index(face, b), 1.0);
            for (int g = 0; g < m; ++g) {
              if (std::abs(w[g]) > 1e-13)
                triplets.emplace_back(row, space->function_index(other, g), -w[g]);
            }
            ++row;
          }
        }
      }
      ASSERT_GT(charts.size(), 1u);  // pairs evaluated in more than one chart
      ASSERT_EQ(row, c.rows());
      expected.setFromTriplets(triplets.begin(), triplets.end());
      EXPECT_EQ(c.nonZeros(), expected.nonZeros()) << "n=" << n << " r=" << r;
      const Eigen::SparseMatrix<double, Eigen::RowMajor> difference = c - expected;
      EXPECT_EQ(difference.coeffs().cwiseAbs().maxCoeff(), 0.0) << "n=" << n << " r=" << r;
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
