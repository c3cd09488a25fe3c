// The parameter correction's kept basis samples (spline/fit/correction.h): taken instead of
// evaluating again, they must give the very bits an evaluation gives.
#include <gtest/gtest.h>

#include <random>

#include "spline/fit/correction.h"
#include "spline/fit/fit.h"
#include "spline/fit/normal_equations.h"
#include "spline/manifold/manifold_fixtures.h"

namespace spline {
namespace {

using testing::small_atlas;
using testing::small_space;

struct Data {
  std::vector<DomainPoint> parameters;
  Eigen::MatrixX3d points;
  std::vector<detail::FaceRowsSpec> rows;
};

// Two points a face, off the spline by a nudge of their parameters and a normal offset, and a
// last point outside the domain (face -1).
Data nudged_data(const ManifoldSplineSpace& space, const ManifoldSpline& spline) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(0.05, 1.0);
  Data d;
  std::vector<Eigen::Vector3d> targets;
  for (int f : space.domain_faces()) {
    for (int i = 0; i < 2; ++i) {
      Eigen::Vector3d truth(unit(rng), unit(rng), unit(rng));
      Eigen::Vector3d start(unit(rng), unit(rng), unit(rng));
      truth /= truth.sum();
      start = 0.9 * truth + 0.1 * start / start.sum();
      const SurfaceJet jet = spline.evaluate({f, truth});
      d.parameters.push_back({f, start});
      targets.push_back(jet.position + 1e-3 * jet.normal);
    }
  }
  d.parameters.push_back({-1, Eigen::Vector3d::Constant(1.0 / 3.0)});
  targets.push_back(Eigen::Vector3d::Zero());
  d.points.resize(static_cast<Eigen::Index>(targets.size()), 3);
  for (std::size_t k = 0; k < targets.size(); ++k)
    d.points.row(static_cast<Eigen::Index>(k)) = targets[k].transpose();
  d.rows.resize(static_cast<std::size_t>(space.domain_face_count()));
  for (std::size_t k = 0; k + 1 < d.parameters.size(); ++k)
    d.rows[space.domain_index(d.parameters[k].face)].points.push_back(static_cast<int>(k));
  return d;
}

bool same_bits(const detail::NormalEquations& a, const detail::NormalEquations& b) {
  if (a.lower.nonZeros() != b.lower.nonZeros()) return false;
  const Eigen::MatrixXd la(a.lower), lb(b.lower);
  return (la.array() == lb.array()).all() && (a.rhs.array() == b.rhs.array()).all();
}

// The samples kept for point k are evaluate_basis' at `at`, bit for bit (gradients if kept).
void expect_kept_as_evaluated(const ManifoldSplineSpace& space,
                              const detail::PointBasisValues& kept, std::size_t k,
                              const DomainPoint& at) {
  const auto evaluated = space.evaluate_basis(at, -1, {}, BasisDerivatives::first);
  ASSERT_EQ(kept.count[k], static_cast<int>(evaluated.size())) << k;
  const auto block = static_cast<std::size_t>(kept.block[k]);
  for (int i = 0; i < kept.count[k]; ++i) {
    const auto e = static_cast<std::size_t>(kept.first[k] + i);
    EXPECT_EQ(kept.function[block][e], evaluated[i].function) << k;
    EXPECT_EQ(kept.value[block][e], evaluated[i].jet.value) << k;
    if (!kept.gradient.empty()) {
      EXPECT_EQ(kept.gradient[block][e], evaluated[i].jet.gradient) << k;
    }
  }
}

TEST(Correction, KeptSamplesGiveTheBitsOfEvaluatingAgain) {
  const auto space = small_space("genus2.off", 3);
  const ricci::Mesh& mesh = small_atlas("genus2.off").problem.mesh;
  const Eigen::MatrixX3d initial = piecewise_linear_control_points(*space, mesh);
  const ManifoldSpline spline{space, initial};
  const Data d = nudged_data(*space, spline);

  // The fit's assembly keeping gradients: the same normal equations as without.
  detail::NormalEquations with_gradients = detail::assemble_normal_equations(
      *space, d.rows, d.parameters, d.points, 1e-3, initial, 2, nullptr, true);
  const detail::NormalEquations plain = detail::assemble_normal_equations(
      *space, d.rows, d.parameters, d.points, 1e-3, initial, 2);
  EXPECT_TRUE(same_bits(with_gradients, plain));
  const detail::PointBasisValues start =
      detail::take_data_rows(with_gradients, d.rows, d.parameters);
  ASSERT_FALSE(start.gradient.empty());
  for (std::size_t k = 0; k + 1 < d.parameters.size(); ++k) {
    ASSERT_TRUE(start.holds_gradients(k, d.parameters[k]));
    expect_kept_as_evaluated(*space, start, k, d.parameters[k]);
  }
  EXPECT_FALSE(start.holds(d.parameters.size() - 1, d.parameters.back()));

  // The correction from the kept starts, keeping its ends: the parameters of the plain one.
  const CorrectedParameters expected = correct_parameters(spline, d.parameters, d.points, 2, 2);
  detail::PointBasisValues ends;
  const CorrectedParameters corrected = detail::correct_parameters_keeping(
      spline, d.parameters, d.points, 2, 2, &start, &ends);
  EXPECT_EQ(corrected.moved, expected.moved);
  EXPECT_GT(corrected.moved, static_cast<int>(d.parameters.size() / 2));
  int kept = 0;
  for (std::size_t k = 0; k < d.parameters.size(); ++k) {
    EXPECT_EQ(corrected.parameters[k].face, expected.parameters[k].face) << k;
    EXPECT_EQ(corrected.parameters[k].barycentric, expected.parameters[k].barycentric) << k;
    if (!ends.holds(k, corrected.parameters[k])) continue;
    ++kept;
    expect_kept_as_evaluated(*space, ends, k, corrected.parameters[k]);
  }
  EXPECT_GT(kept, static_cast<int>(0.9 * static_cast<double>(d.parameters.size() - 1)));

  // The refit's assembly taking the ends: the same normal equations as evaluating them.
  std::vector<detail::FaceRowsSpec> rows(d.rows.size());
  for (std::size_t k = 0; k + 1 < corrected.parameters.size(); ++k) {
    rows[space->domain_index(corrected.parameters[k].face)].points.push_back(
        static_cast<int>(k));
  }
  const detail::NormalEquations taken = detail::assemble_normal_equations(
      *space, rows, corrected.parameters, d.points, 1e-3, initial, 2, &ends);
  const detail::NormalEquations evaluated = detail::assemble_normal_equations(
      *space, rows, corrected.parameters, d.points, 1e-3, initial, 2);
  EXPECT_TRUE(same_bits(taken, evaluated));
}

}  // namespace
}  // namespace spline
