// The patch's thin-plate Gram matrix assembled in triangle blocks (thin_plate_normal) against
// the Gram matrix of the thin-plate rows it replaces, and the normal-equation solve.
#include <gtest/gtest.h>

#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "ricci/mesh/errors.h"
#include "spline/basis/blossom.h"
#include "spline/fill/fill_system.h"
#include "spline/fill/patch_domain.h"
#include "spline/planar/triangulation.h"

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

// The heptagon's boundary of heptagon_space, counter-clockwise.
std::vector<Eigen::Vector2d> heptagon_boundary() {
  std::vector<Eigen::Vector2d> boundary;
  for (int j = 0; j < 7; ++j) {
    const double angle = 2.0 * M_PI * j / 7.0;
    const double radius = j % 2 == 0 ? 1.0 : 0.8;
    boundary.emplace_back(radius * std::cos(angle), radius * std::sin(angle));
  }
  return boundary;
}

// The bucketed inside test and distance agree with a scan of every edge, on a scalloped
// polygon of many points and on points inside, outside and far from it.
TEST(PolygonRegion, AgreesWithEveryEdgeScanned) {
  std::vector<Eigen::Vector2d> polygon;
  for (int k = 0; k < 400; ++k) {
    const double angle = 2.0 * M_PI * k / 400.0;
    const double radius = 1.0 + 0.3 * std::sin(7.0 * angle);
    polygon.emplace_back(radius * std::cos(angle), 0.6 * radius * std::sin(angle));
  }
  const PolygonRegion region(polygon, 0.07);
  int inside = 0;
  for (int i = 0; i < 60; ++i) {
    for (int j = 0; j < 60; ++j) {
      const Eigen::Vector2d p(-1.6 + 3.2 * (i + 0.31) / 60, -1.1 + 2.2 * (j + 0.57) / 60);
      bool crossing = false;
      double nearest = INFINITY;
      for (std::size_t e = 0; e < polygon.size(); ++e) {
        const Eigen::Vector2d a = polygon[e], b = polygon[(e + 1) % polygon.size()];
        if ((a.y() > p.y()) != (b.y() > p.y()) &&
            p.x() < a.x() + (p.y() - a.y()) / (b.y() - a.y()) * (b.x() - a.x()))
          crossing = !crossing;
        const double s = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
        nearest = std::min(nearest, (a + s * (b - a) - p).norm());
      }
      EXPECT_EQ(region.contains(p), crossing) << p.transpose();
      EXPECT_NEAR(region.distance(p, 0.25), std::min(nearest, 0.25), 1e-14) << p.transpose();
      inside += crossing;
    }
  }
  EXPECT_GT(inside, 600);
  EXPECT_LT(inside, 3000);
}

// The plain rule on triangles well outside D: only there, and (its weights scaled to the full
// rule's) it integrates a quadratic's bending (constant curvature, no spikes) as the full rule
// does, while the matrix differs.
TEST(ThinPlateNormal, PlainRuleTrianglesLieOutsideAndKeepAQuadraticsEnergy) {
  const auto space = heptagon_space();
  const auto boundary = heptagon_boundary();
  const std::vector<char> plain = plain_rule_triangles(*space, boundary, 0.2);
  const PolygonRegion region(boundary, 0.1);
  const auto& t = space->triangulation();
  int flagged = 0;
  for (std::size_t k = 0; k < plain.size(); ++k) {
    if (!plain[k]) continue;
    ++flagged;
    const Eigen::Vector3i& v = t.triangles[k];
    const Eigen::Vector2d c = (t.positions[v[0]] + t.positions[v[1]] + t.positions[v[2]]) / 3.0;
    EXPECT_FALSE(region.contains(c));
    EXPECT_GT(region.distance(c, 1.0), 0.2);
  }
  EXPECT_GT(flagged, 0);
  EXPECT_LT(flagged, space->triangle_count());
  const std::vector<char> none = plain_rule_triangles(*space, boundary, -1.0);
  EXPECT_EQ(std::count(none.begin(), none.end(), 1), 0);

  // Within 0.35 of D (the grid reaches 0.7 past D's box), every point of the full rule passes
  // the partition-of-unity test; farther out the full rule's corner points next to the grid's
  // outer vertices are left out, the plain rule's points less often.
  const std::vector<char> far = plain_rule_triangles(*space, boundary, 0.35);
  std::vector<char> band(plain.size(), 0);
  for (std::size_t k = 0; k < plain.size(); ++k) band[k] = plain[k] && !far[k];
  EXPECT_GT(std::count(band.begin(), band.end(), 1), 0);
  const Eigen::SparseMatrix<double> full = thin_plate_normal(*space, 1.0);
  const Eigen::SparseMatrix<double> mixed = thin_plate_normal(*space, 1.0, nullptr, &band);
  const Eigen::SparseMatrix<double> unflagged = thin_plate_normal(*space, 1.0, nullptr, &none);
  EXPECT_EQ((Eigen::MatrixXd(unflagged) - Eigen::MatrixXd(full)).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_GT((Eigen::MatrixXd(mixed) - Eigen::MatrixXd(full)).cwiseAbs().maxCoeff(), 0.0);
  for (const auto& [a, b] : {std::pair{2, 0}, std::pair{1, 1}, std::pair{0, 2}}) {
    const Eigen::VectorXd c = space->control_points_of(monomial(a, b, space->degree())).col(0);
    const double expected = c.dot(full * c);
    ASSERT_GT(expected, 0.0);
    EXPECT_NEAR(c.dot(mixed * c), expected, 1e-9 * expected) << "x^" << a << " y^" << b;
  }
  // An affine map still has no energy.
  const Eigen::VectorXd x = space->control_points_of(monomial(1, 0, space->degree())).col(0);
  const Eigen::VectorXd xx = space->control_points_of(monomial(2, 0, space->degree())).col(0);
  EXPECT_LT(std::abs(x.dot(mixed * x)), 1e-8 * xx.dot(mixed * xx));
}

// Grading the corner refinement faster outside D leaves fewer triangles, and every triangle
// whose centroid is in D still meets the inside size (refinement + distance from a corner).
TEST(PatchSpace, GradesFasterOutsideTheBoundaryOnly) {
  const auto boundary = heptagon_boundary();
  const double spacing = 0.35;
  const std::vector<int> refinements(7, 8);
  const auto same = patch_space(boundary, spacing, 3, KnotCloudOptions{}, boundary, refinements);
  const auto graded =
      patch_space(boundary, spacing, 3, KnotCloudOptions{}, boundary, refinements, 2.0);
  EXPECT_LT(graded->triangle_count(), same->triangle_count());
  const PolygonRegion region(boundary, 0.1);
  const auto& t = graded->triangulation();
  int inside = 0;
  for (const Eigen::Vector3i& v : t.triangles) {
    const Eigen::Vector2d c = (t.positions[v[0]] + t.positions[v[1]] + t.positions[v[2]]) / 3.0;
    if (!region.contains(c)) continue;
    ++inside;
    double size = INFINITY;
    for (const auto& corner : boundary) size = std::min(size, spacing / 8 + (c - corner).norm());
    if (!(size < spacing)) continue;
    double longest = 0.0;
    for (int e = 0; e < 3; ++e)
      longest = std::max(longest, (t.positions[v[e]] - t.positions[v[(e + 1) % 3]]).norm());
    EXPECT_LE(longest, size) << c.transpose();
  }
  EXPECT_GT(inside, 0);
}

}  // namespace
}  // namespace spline::fill_detail

namespace spline::fill_detail {
namespace {

// An L-shaped D: the box of its boundary holds a square of triangles far from it.
std::vector<Eigen::Vector2d> l_boundary() {
  return {{0.0, 0.0}, {3.0, 0.0}, {3.0, 0.6}, {0.6, 0.6}, {0.6, 3.0}, {0.0, 3.0}};
}

// A grid trimmed to keep_distance around D keeps one fan per vertex, no triangle far from D,
// and the same basis on D (the same functions with the same values: the clouds there keep
// their seeds and rings), so the partition of unity holds on D.
TEST(PatchSpace, TrimmedGridKeepsTheBasisOnTheBoundedRegion) {
  const auto boundary = l_boundary();
  const double spacing = 0.2;
  const std::vector<int> refinements(boundary.size(), 4);
  const auto box = patch_space(boundary, spacing, 3, KnotCloudOptions{}, boundary, refinements);
  const auto trimmed = patch_space(boundary, spacing, 3, KnotCloudOptions{}, boundary,
                                   refinements, 1.0, 2.0 * spacing);
  EXPECT_LT(trimmed->triangle_count(), 0.8 * box->triangle_count());
  const auto& t = trimmed->triangulation();
  EXPECT_NO_THROW((void)vertex_rings(t));
  const PolygonRegion region(boundary, spacing);
  for (const Eigen::Vector3i& v : t.triangles) {
    const Eigen::Vector2d c = (t.positions[v[0]] + t.positions[v[1]] + t.positions[v[2]]) / 3.0;
    EXPECT_TRUE(region.contains(c) || region.distance(c, 4.0 * spacing) < 3.0 * spacing)
        << c.transpose();
  }
  int points = 0;
  for (double x = 0.013; x < 3.0; x += 0.0731) {
    for (double y = 0.017; y < 3.0; y += 0.0797) {
      const Eigen::Vector2d u(x, y);
      if (!region.contains(u)) continue;
      ++points;
      std::vector<double> a, b;
      double sum = 0.0;
      for (const auto& s : box->evaluate_basis(u)) a.push_back(s.jet.value);
      for (const auto& s : trimmed->evaluate_basis(u)) {
        b.push_back(s.jet.value);
        sum += s.jet.value;
      }
      std::sort(a.begin(), a.end());
      std::sort(b.begin(), b.end());
      ASSERT_EQ(a.size(), b.size()) << u.transpose();
      for (std::size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(a[i], b[i], 1e-12) << u.transpose();
      EXPECT_NEAR(sum, 1.0, 1e-9) << u.transpose();
    }
  }
  EXPECT_GT(points, 300);
}

}  // namespace
}  // namespace spline::fill_detail
