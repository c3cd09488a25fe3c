// The patch's thin-plate Gram matrix assembled in triangle blocks (thin_plate_normal) against
// the Gram matrix of the thin-plate rows it replaces, and the normal-equation solve.
#include <gtest/gtest.h>

#include <Eigen/SparseCore>
#include <cmath>
#include <utility>
#include <vector>

#include "ricci/mesh/errors.h"
#include "spline/basis/blossom.h"
#include "spline/fill/fill_system.h"

namespace spline::fill_detail {
namespace {

// A patch space over a scalloped heptagon, refined around its corners as a cone patch's.
std::shared_ptr<const PlanarDmsSpace> heptagon_space() {
  std::vector<Eigen::Vector2d> boundary;
  for (int j = 0; j < 7; ++j) {
    const double angle = 2.0 * M_PI * j / 7.0;
    const double radius = j % 2 == 0 ? 1.0 : 0.8;
    boundary.emplace_back(radius * std::cos(angle), radius * std::sin(angle));
  }
  return patch_space(boundary, 0.35, 3, KnotCloudOptions{}, boundary, 4);
}

Eigen::SparseMatrix<double> row_gram(const PlanarDmsSpace& space, double weight) {
  System rows;
  add_thin_plate_rows(rows, space, weight);
  Eigen::SparseMatrix<double> a(rows.next_row(), space.function_count());
  a.setFromTriplets(rows.entries.begin(), rows.entries.end());
  return a.transpose() * a;
}

TEST(ThinPlateNormal, EqualsTheGramMatrixOfTheRows) {
  const auto space = heptagon_space();
  const double weight = 0.37;
  const Eigen::SparseMatrix<double> blocks = thin_plate_normal(*space, weight);
  const Eigen::SparseMatrix<double> rows = row_gram(*space, weight);
  ASSERT_EQ(blocks.rows(), space->function_count());
  ASSERT_EQ(blocks.cols(), space->function_count());
  const double scale = Eigen::MatrixXd(rows).cwiseAbs().maxCoeff();
  ASSERT_GT(scale, 0.0);
  const Eigen::MatrixXd difference = Eigen::MatrixXd(blocks) - Eigen::MatrixXd(rows);
  EXPECT_LT(difference.cwiseAbs().maxCoeff(), 1e-12 * scale);
  // No entry outside the rows' pattern, the same count of nonzeros, exactly symmetric.
  for (int k = 0; k < blocks.outerSize(); ++k) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(blocks, k); it; ++it)
      EXPECT_NE(rows.coeff(it.row(), it.col()), 0.0) << it.row() << ", " << it.col();
  }
  EXPECT_EQ(blocks.nonZeros(), rows.nonZeros());
  const Eigen::SparseMatrix<double> transpose = blocks.transpose();
  EXPECT_EQ((Eigen::MatrixXd(blocks) - Eigen::MatrixXd(transpose)).cwiseAbs().maxCoeff(), 0.0);
}

// normal_equations adds the rim rows' Gram matrix inside the block assembly: the same pattern
// and the same bits as Eigen's sparse sum, including entries only one side has, a stored zero
// of the rows and entries outside the thin plate's pattern.
TEST(ThinPlateNormal, AddsAMatrixAsEigensSumWould) {
  const auto space = heptagon_space();
  const int n = space->function_count();
  std::vector<Eigen::Triplet<double>> entries;
  for (int i = 0; i < n; i += 3) {
    entries.emplace_back(i, i, 0.5 + 1e-3 * i);
    entries.emplace_back(i, n - 1 - i, -0.25);  // far off the thin plate's band
    entries.emplace_back(n - 1 - i, i, -0.25);
  }
  entries.emplace_back(1, 2, 0.0);  // a stored zero
  entries.emplace_back(2, 1, 0.0);
  Eigen::SparseMatrix<double> plus(n, n);
  plus.setFromTriplets(entries.begin(), entries.end());
  const double weight = 0.37;
  const Eigen::SparseMatrix<double> merged = thin_plate_normal(*space, weight, &plus);
  Eigen::SparseMatrix<double> expected = plus;
  expected += thin_plate_normal(*space, weight);
  ASSERT_TRUE(merged.isCompressed());
  ASSERT_EQ(merged.nonZeros(), expected.nonZeros());
  for (int k = 0; k <= n; ++k)
    ASSERT_EQ(merged.outerIndexPtr()[k], expected.outerIndexPtr()[k]) << "column " << k;
  for (Eigen::Index e = 0; e < merged.nonZeros(); ++e) {
    ASSERT_EQ(merged.innerIndexPtr()[e], expected.innerIndexPtr()[e]) << "entry " << e;
    ASSERT_EQ(std::signbit(merged.valuePtr()[e]), std::signbit(expected.valuePtr()[e]));
    ASSERT_EQ(merged.valuePtr()[e], expected.valuePtr()[e]) << "entry " << e;
  }
}

// The thin plate measures bending: an affine map has none, a quadratic a definite amount
// (2 |f_xx|^2 + ... per unit area). Points just inside a missing function's support kept an
// affine map's energy at 7e-5 of x^2's.
TEST(ThinPlateNormal, AnAffineMapHasNoEnergy) {
  const auto space = heptagon_space();
  const Eigen::SparseMatrix<double> gram = thin_plate_normal(*space, 1.0);
  const auto energy = [&](int a, int b) {
    const Eigen::VectorXd c = space->control_points_of(monomial(a, b, space->degree())).col(0);
    return c.dot(gram * c);
  };
  const double bending = energy(2, 0);
  ASSERT_GT(bending, 0.0);
  EXPECT_GT(energy(1, 1), 0.1 * bending);
  EXPECT_GT(energy(0, 2), 0.1 * bending);
  for (const auto& [a, b] : {std::pair{0, 0}, std::pair{1, 0}, std::pair{0, 1}})
    EXPECT_LT(std::abs(energy(a, b)), 1e-8 * bending) << "x^" << a << " y^" << b;
}

TEST(SolveNormalEquations, SolvesAndRefusesAnIndefiniteMatrix) {
  const auto space = heptagon_space();
  Eigen::SparseMatrix<double> normal = thin_plate_normal(*space, 1.0);
  for (int i = 0; i < normal.rows(); ++i) normal.coeffRef(i, i) += 1e-3;
  const Eigen::MatrixXd expected = Eigen::MatrixXd::Random(normal.rows(), 2);
  const Eigen::MatrixXd rhs = normal * expected;
  const Eigen::MatrixXd x = solve_normal_equations(normal, rhs, "test patch");
  EXPECT_LT((normal * x - rhs).norm(), 1e-12 * rhs.norm());
  EXPECT_LT((x - expected).norm(), 1e-6 * expected.norm());
  Eigen::SparseMatrix<double> indefinite = normal;
  indefinite.coeffRef(5, 5) = -1.0;
  try {
    (void)solve_normal_equations(indefinite, rhs, "test patch");
    ADD_FAILURE() << "no throw";
  } catch (const ricci::SolverError& e) {
    EXPECT_NE(std::string(e.what()).find("normal equations of the test patch"), std::string::npos);
  }
}

// patch_space with a refinement per corner: one for all gives the single refinement's space to
// the bit; refining one corner alone adds triangles near it only (between the uniform grid and
// every corner refined), and the smallest side next to it is spacing / 8.
TEST(PatchSpace, RefinesEachCornerByItsOwnFactor) {
  std::vector<Eigen::Vector2d> boundary;
  for (int j = 0; j < 7; ++j) {
    const double angle = 2.0 * M_PI * j / 7.0;
    boundary.emplace_back(std::cos(angle), std::sin(angle));
  }
  const double spacing = 0.35;
  const auto space = [&](const std::vector<int>& refinements) {
    return patch_space(boundary, spacing, 3, KnotCloudOptions{}, boundary, refinements);
  };
  const auto same = space(std::vector<int>(7, 8));
  const auto single = patch_space(boundary, spacing, 3, KnotCloudOptions{}, boundary, 8);
  EXPECT_EQ(same->triangulation().positions, single->triangulation().positions);
  EXPECT_EQ(same->triangulation().triangles, single->triangulation().triangles);
  std::vector<int> one(7, 1);
  one[3] = 8;
  const auto refined_one = space(one);
  const auto uniform = space(std::vector<int>(7, 1));
  EXPECT_LT(uniform->triangle_count(), refined_one->triangle_count());
  EXPECT_LT(refined_one->triangle_count(), same->triangle_count());
  // Sides: the shortest edge of a triangle with a vertex at a corner.
  const auto& t = refined_one->triangulation();
  std::vector<double> shortest(7, INFINITY);
  for (const Eigen::Vector3i& tri : t.triangles) {
    for (int c = 0; c < 7; ++c) {
      for (int k = 0; k < 3; ++k) {
        if ((t.positions[tri[k]] - boundary[c]).norm() > 0.5 * spacing) continue;
        for (int e = 0; e < 3; ++e) {
          const double side = (t.positions[tri[e]] - t.positions[tri[(e + 1) % 3]]).norm();
          shortest[c] = std::min(shortest[c], side);
        }
      }
    }
  }
  EXPECT_LT(shortest[3], 0.25 * spacing);
  for (int c = 0; c < 7; ++c) {
    if (c == 3) continue;
    EXPECT_GT(shortest[c], 0.4 * spacing) << c;
  }
}

}  // namespace
}  // namespace spline::fill_detail
