// ManifoldSplineSpace::evaluate_basis evaluates only the triangles around the point's face (the
// chart triangles sharing one of its vertices): the same samples, bit for bit, as evaluating every
// triangle of the chart whose clouds reach the point and dropping those not around the face; and
// the values-only evaluation gives the same values. A surface evaluated to a lower derivative
// order gives the full evaluation's bits for what it computes.
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "spline/manifold/manifold_fixtures.h"

namespace spline {
namespace {

using testing::small_space;

TEST(ManifoldEvaluationEquivalence, AroundTheFaceEqualsTheWholeChartFiltered) {
  const auto space = small_space("genus2.off", 3);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int points = 0;
  for (int face : space->domain_faces()) {
    const int chart = space->chart_of(face);
    const auto& cs = space->chart_space(chart);
    const auto& triangles = cs.space->triangulation().triangles;
    const Eigen::Vector3i own = triangles[cs.triangle_of_row[space->atlas().charts[chart].slot(face)]];
    for (int k = 0; k < 4; ++k) {
      Eigen::Vector3d b(unit(rng), unit(rng), unit(rng));
      if (k == 0) b = Eigen::Vector3d::Unit(face % 3);          // a vertex
      if (k == 1) b = Eigen::Vector3d(0.5, 0.5, 0.0);           // an edge
      b /= b.sum();
      const Eigen::Vector2d u = space->chart_point(chart, face, b);
      std::vector<ManifoldBasisSample> expected;
      for (const BasisSample& s : cs.space->evaluate_basis(u)) {
        const Eigen::Vector3i& t = triangles[s.triangle];
        bool shares = false;
        for (int a = 0; a < 3; ++a) shares = shares || (t.array() == own[a]).any();
        if (!shares) continue;
        expected.push_back({space->function_index(cs.face_of_triangle[s.triangle], s.beta), s.jet});
      }
      const auto got = space->evaluate_basis({face, b});
      ASSERT_EQ(got.size(), expected.size()) << "face " << face;
      for (std::size_t i = 0; i < got.size(); ++i) {
        ASSERT_EQ(got[i].function, expected[i].function);
        ASSERT_EQ(got[i].jet.value, expected[i].jet.value);
        ASSERT_EQ(got[i].jet.gradient, expected[i].jet.gradient);
        ASSERT_EQ(got[i].jet.hessian, expected[i].jet.hessian);
      }
      std::size_t j = 0;
      for (const auto& v : space->evaluate_basis({face, b}, -1, {}, BasisDerivatives::none)) {
        while (j < got.size() && got[j].jet.value == 0.0) ++j;  // non-zero derivatives only
        ASSERT_LT(j, got.size());
        ASSERT_EQ(v.function, got[j].function);
        ASSERT_EQ(v.jet.value, got[j].jet.value);
        ++j;
      }
      while (j < got.size() && got[j].jet.value == 0.0) ++j;
      EXPECT_EQ(j, got.size());
      ++points;
    }
  }
  EXPECT_GT(points, 1000);
}

bool same_bits(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::memcmp(a.data(), b.data(), sizeof(double) * 3) == 0;
}

TEST(ManifoldEvaluationEquivalence, LowerDerivativeOrdersGiveTheFullEvaluationsBits) {
  const auto space = small_space("genus2.off", 3);
  std::srand(11);
  const ManifoldSpline spline{space, Eigen::MatrixX3d::Random(space->function_count(), 3)};
  std::mt19937 rng(6);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  int points = 0, other_charts = 0;
  for (int face : space->domain_faces()) {
    // The face's own chart and another one holding its neighbourhood (another frame).
    std::vector<int> charts{space->chart_of(face)};
    for (int c = 0; c < static_cast<int>(space->atlas().charts.size()); ++c) {
      if (c != charts[0] && space->holds_neighbourhood(c, face)) {
        charts.push_back(c);
        break;
      }
    }
    for (int k = 0; k < 3; ++k) {
      Eigen::Vector3d b(unit(rng), unit(rng), unit(rng));
      if (k == 0) b = Eigen::Vector3d(0.5, 0.0, 0.5);  // on an edge
      b /= b.sum();
      for (int chart : charts) {
        const DomainPoint x{face, b};
        const SurfaceJet full = spline.evaluate(x, chart);
        const SurfaceJet first = spline.evaluate(x, chart, {}, BasisDerivatives::first);
        const SurfaceJet none = spline.evaluate(x, chart, {}, BasisDerivatives::none);
        ASSERT_TRUE(same_bits(first.position, full.position)) << "face " << face;
        ASSERT_TRUE(same_bits(first.du, full.du) && same_bits(first.dv, full.dv));
        ASSERT_TRUE(same_bits(first.normal, full.normal)) << "face " << face;
        ASSERT_TRUE(first.duu == zero && first.duv == zero && first.dvv == zero);
        ASSERT_TRUE(same_bits(none.position, full.position)) << "face " << face;
        ASSERT_TRUE(none.du == zero && none.dv == zero && none.normal == zero);
        EXPECT_EQ(first.chart, chart);
        EXPECT_GT(full.duu.norm() + full.duv.norm() + full.dvv.norm(), 0.0);
        other_charts += chart != charts[0];
        ++points;
      }
    }
  }
  EXPECT_GT(points, 1000);
  EXPECT_GT(other_charts, 10);
}

}  // namespace
}  // namespace spline
