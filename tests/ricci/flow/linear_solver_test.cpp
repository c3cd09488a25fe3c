// The linear solver (ricci/flow/linear_solver.h): SymmetricFactorization's blocked
// back-substitution split over threads gives the same solutions as column by column, to
// rounding; the compact supernode amalgamation stores fewer values and solves to the same
// residual; conjugate gradients preconditioned with a nearby factorisation solve H x = b to the
// asked relative residual from the factorisation of another matrix of the same size, and refuse
// when the steps allowed cannot reach it.
#include "ricci/flow/linear_solver.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace {

// Lower triangle of the 5-point Laplacian of an n x n grid plus `shift` on the diagonal (SPD).
Eigen::SparseMatrix<double> grid_laplacian(int n, double shift) {
  std::vector<Eigen::Triplet<double>> triplets;
  const auto id = [n](int i, int j) { return i * n + j; };
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      triplets.emplace_back(id(i, j), id(i, j), 4.0 + shift);
      if (i + 1 < n) triplets.emplace_back(id(i + 1, j), id(i, j), -1.0);
      if (j + 1 < n) triplets.emplace_back(id(i, j + 1), id(i, j), -1.0);
    }
  }
  Eigen::SparseMatrix<double> lower(n * n, n * n);
  lower.setFromTriplets(triplets.begin(), triplets.end());
  lower.makeCompressed();
  return lower;
}

double relative_residual(const Eigen::SparseMatrix<double>& lower, const Eigen::VectorXd& x,
                         const Eigen::VectorXd& b) {
  const Eigen::VectorXd r = b - lower.selfadjointView<Eigen::Lower>() * x;
  return r.norm() / b.norm();
}

TEST(SymmetricFactorization, BlockedSolveSplitOverThreadsMatchesColumnByColumnAndInPlace) {
  // 212k unknowns: well above the size from which the columns are split over the threads.
  const Eigen::SparseMatrix<double> lower = grid_laplacian(460, 1e-2);
  ricci::SymmetricFactorization solver(ricci::LinearSolver::cholmod_supernodal);
  solver.analyze(lower);
  ASSERT_TRUE(solver.factorize(lower));
  const double mean = -1.0 / static_cast<double>(lower.rows());
  Eigen::MatrixXd b = Eigen::MatrixXd::Constant(lower.rows(), 5, mean);
  for (Eigen::Index j = 0; j < b.cols(); ++j) b(j * 40000 + 7, j) += 1.0;
  const Eigen::MatrixXd x = solver.solve_columns(b);
  ASSERT_EQ(x.cols(), b.cols());
  Eigen::MatrixXd in_place = b;
  solver.solve_columns_in_place(in_place);
  EXPECT_EQ((in_place - x).cwiseAbs().maxCoeff(), 0.0);  // the same split, the same sums
  for (Eigen::Index j = 0; j < b.cols(); ++j) {
    const Eigen::VectorXd column = solver.solve(b.col(j));
    EXPECT_LT((x.col(j) - column).norm(), 1e-12 * column.norm()) << "column " << j;
    EXPECT_LT(relative_residual(lower, x.col(j), b.col(j)), 1e-10) << "column " << j;
  }
}

TEST(SymmetricFactorization, CompactSupernodesStoreLessAndSolveToTheSameResidual) {
  // 40k unknowns: the compact amalgamation asked for from 0 unknowns, against the default
  // (compact from 400k unknowns) and against a threshold just above this size.
  const Eigen::SparseMatrix<double> lower = grid_laplacian(200, 1e-3);
  ricci::SymmetricFactorization standard(ricci::LinearSolver::cholmod_supernodal);
  ricci::SymmetricFactorization compact(ricci::LinearSolver::cholmod_supernodal, 0);
  ricci::SymmetricFactorization just_below(ricci::LinearSolver::cholmod_supernodal,
                                           lower.rows() + 1);
  for (ricci::SymmetricFactorization* f : {&standard, &compact, &just_below}) {
    f->analyze(lower);
    ASSERT_TRUE(f->factorize(lower));
  }
  EXPECT_GT(compact.factor_entries(), 0.0);
  EXPECT_LT(compact.factor_entries(), 0.97 * standard.factor_entries());
  EXPECT_EQ(just_below.factor_entries(), standard.factor_entries());
  EXPECT_EQ(compact.fill(), standard.fill());  // the same nonzeros, fewer explicit zeros
  Eigen::VectorXd b = Eigen::VectorXd::Zero(lower.rows());
  b(123) = 1.0;
  b(31000) = -2.0;
  const Eigen::VectorXd x_standard = standard.solve(b), x_compact = compact.solve(b);
  EXPECT_LT(relative_residual(lower, x_standard, b), 1e-12);
  EXPECT_LT(relative_residual(lower, x_compact, b), 1e-12);
  EXPECT_LT((x_compact - x_standard).norm(), 1e-10 * x_standard.norm());
  EXPECT_EQ((standard.solve(b) - just_below.solve(b)).cwiseAbs().maxCoeff(), 0.0);
  // An analysis on another factorisation's ordering (flips) is compacted too.
  ricci::SymmetricFactorization reused(ricci::LinearSolver::cholmod_supernodal, 0);
  ASSERT_TRUE(reused.analyze(lower, compact.ordering(), compact.fill()));
  EXPECT_LT(reused.factor_entries(), 0.97 * standard.factor_entries());
}

// Lower triangle of the weighted path Laplacian on n vertices plus `shift` on the diagonal
// (weights 1 + amplitude sin(3 i)), symmetric positive definite for shift > 0.
Eigen::SparseMatrix<double> path_laplacian(int n, double amplitude, double shift) {
  std::vector<Eigen::Triplet<double>> t;
  Eigen::VectorXd diagonal = Eigen::VectorXd::Constant(n, shift);
  for (int i = 0; i + 1 < n; ++i) {
    const double w = 1.0 + amplitude * std::sin(3.0 * i);
    t.emplace_back(i + 1, i, -w);
    diagonal[i] += w;
    diagonal[i + 1] += w;
  }
  for (int i = 0; i < n; ++i) t.emplace_back(i, i, diagonal[i]);
  Eigen::SparseMatrix<double> lower(n, n);
  lower.setFromTriplets(t.begin(), t.end());
  lower.makeCompressed();
  return lower;
}

// The preconditioner: the factorisation of a path Laplacian with constant weights, of the same
// size as the tests' matrices, whose weights vary around it.
class PreconditionedCg : public ::testing::Test {
 protected:
  static constexpr int n = 400;

  void SetUp() override {
    nearby.analyze(nearby_matrix);
    ASSERT_TRUE(nearby.factorize(nearby_matrix));
  }

  const Eigen::SparseMatrix<double> nearby_matrix = path_laplacian(n, 0.0, 0.01);
  ricci::SymmetricFactorization nearby{ricci::LinearSolver::eigen_llt};
};

TEST_F(PreconditionedCg, SolvesToTheAskedResidualWithANearbyFactorization) {
  const Eigen::SparseMatrix<double> lower = path_laplacian(n, 0.5, 0.01);
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) b[i] = std::cos(0.1 * i);
  Eigen::VectorXd x;
  ASSERT_TRUE(ricci::solve_by_preconditioned_cg(nearby, lower, b, x, 1e-10, 60));
  EXPECT_LE(relative_residual(lower, x, b), 1e-10);
  // Against the matrix's own factorisation.
  ricci::SymmetricFactorization own(ricci::LinearSolver::eigen_llt);
  own.analyze(lower);
  ASSERT_TRUE(own.factorize(lower));
  EXPECT_LT((x - own.solve(b)).cwiseAbs().maxCoeff(), 1e-6 * x.cwiseAbs().maxCoeff());
  // Each step is one back-substitution with the nearby factorisation; weights off by up to
  // 50% take more than one, far fewer than n (the unpreconditioned bound).
  EXPECT_GT(nearby.work().back_substitutions, 1);
  EXPECT_LT(nearby.work().back_substitutions, 60);
}

TEST_F(PreconditionedCg, RefusesWhenTheStepsCannotReachTheResidual) {
  const Eigen::SparseMatrix<double> lower = path_laplacian(n, 0.9, 0.01);
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(n);
  Eigen::VectorXd x;
  EXPECT_FALSE(ricci::solve_by_preconditioned_cg(nearby, lower, b, x, 1e-14, 3));
  EXPECT_LE(nearby.work().back_substitutions, 3);
}

}  // namespace
