// SymmetricFactorization's blocked back-substitution split over threads
// (ricci/flow/linear_solver.h): the same solutions as column by column, to rounding.
#include "ricci/flow/linear_solver.h"

#include <gtest/gtest.h>

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
  // 212k unknowns: above the size from which the columns are split over the threads.
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

}  // namespace
