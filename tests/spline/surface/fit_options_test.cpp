// spline::check_options: the ranges msp fit and the Python fit both enforce, in the caller's
// spelling of the option.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>

#include "ricci/mesh/errors.h"
#include "spline/surface/fit_surface.h"

namespace spline {
namespace {

std::string refusal(const FitSurfaceOptions& o,
                    const std::function<std::string(const std::string&)>& name = {}) {
  try {
    check_options(o, name);
  } catch (const ricci::InvalidInputError& e) {
    return e.what();
  }
  return "";
}

TEST(CheckOptions, DefaultsPassAndEachRangeIsEnforced) {
  EXPECT_EQ(refusal(FitSurfaceOptions{}), "");
  auto with = [](auto change) {
    FitSurfaceOptions o;
    change(o);
    return refusal(o);
  };
  EXPECT_EQ(with([](auto& o) { o.domain_faces = 0; }), "domain_faces must be positive");
  EXPECT_NE(with([](auto& o) { o.degree = kMaxDmsDegree + 1; }), "");
  EXPECT_NE(with([](auto& o) { o.fairness = o.degree; }), "");
  EXPECT_EQ(with([](auto& o) { o.fairness = -1; }), "");
  // msp fit's default order suits every degree: 0 below 3, then 1.
  for (int degree = 1; degree <= kMaxDmsDegree; ++degree) {
    EXPECT_EQ(with([&](auto& o) {
                o.degree = degree;
                o.fairness = default_fairness(degree);
              }),
              "")
        << "degree " << degree;
  }
  EXPECT_EQ(default_fairness(2), 0);
  EXPECT_EQ(default_fairness(3), 1);
  // Left empty, the order follows the degree.
  FitSurfaceOptions quadratic;
  quadratic.degree = 2;
  EXPECT_EQ(quadratic.fairness_order(), 0);
  EXPECT_EQ(FitSurfaceOptions{}.fairness_order(), 1);
  EXPECT_NE(with([](auto& o) { o.smoothing = -1e-3; }), "");
  EXPECT_NE(with([](auto& o) { o.density = 65; }), "");
  EXPECT_NE(with([](auto& o) { o.cone_refinement.levels = 5; }), "");
  EXPECT_NE(with([](auto& o) { o.refinement_rounds = 9; }), "");
  EXPECT_NE(with([](auto& o) { o.tolerance = 1.0; }), "");
  EXPECT_NE(with([](auto& o) { o.max_surface_deviation = -0.1; }), "");
  EXPECT_NE(with([](auto& o) { o.smoothing = std::nan(""); }), "");
  EXPECT_NE(with([](auto& o) { o.small_hole_diameter = -1e-3; }), "");
  EXPECT_NE(with([](auto& o) { o.small_hole_diameter = std::nan(""); }), "");
  EXPECT_EQ(with([](auto& o) { o.small_hole_diameter = 0.0; }), "");
  EXPECT_NE(with([](auto& o) { o.fold_rms_goal = -1e-3; }), "");
  EXPECT_NE(with([](auto& o) { o.fold_rms_goal = 1.0; }), "");
  EXPECT_EQ(with([](auto& o) { o.fold_rms_goal = 0.0; }), "");
  EXPECT_NE(with([](auto& o) { o.fold_free_rms = -1e-3; }), "");
  EXPECT_NE(with([](auto& o) { o.fold_free_rms = 1.0; }), "");
  EXPECT_NE(with([](auto& o) { o.fold_free_rms = std::nan(""); }), "");
  EXPECT_EQ(with([](auto& o) { o.fold_free_rms = 0.0; }), "");
  EXPECT_NE(with([](auto& o) { o.crease_fold_rms_growth = 0.5; }), "");
}

TEST(CheckOptions, NamesTheOptionTheCallersWay) {
  FitSurfaceOptions o;
  o.refinement_rounds = -1;
  EXPECT_EQ(refusal(o, [](const std::string& field) { return "--" + field; }),
            "--refinement_rounds must be in [0, 8]");
  EXPECT_THROW((void)fit_surface(ricci::Mesh{}, o), ricci::InvalidInputError);
}

// The delivered surface must have the input's topology: a genus-8 input closed as genus 6 (two
// handles capped by patches, as generated genus 8 was) is named, a matching one is not.
TEST(TopologyMismatch, NamesAnotherGenusAndPassesTheInputs) {
  FittedSurface fitted;
  fitted.input.genus = 8;
  WatertightReport closed;
  closed.vertices = 100;
  closed.faces = 228;
  closed.edges = 342;
  closed.euler_characteristic = -14;
  fitted.topology = fitted.float_topology = closed;
  ASSERT_TRUE(closed.manifold());
  EXPECT_EQ(topology_mismatch(fitted), "");
  fitted.topology.euler_characteristic = -10;
  EXPECT_EQ(topology_mismatch(fitted),
            "the surface has Euler characteristic -10 (genus 6), the input -14 (genus 8): a "
            "patch capped a handle");
  fitted.topology = closed;
  fitted.float_topology.boundary_loops = 1;
  EXPECT_NE(topology_mismatch(fitted).find("(welded as float) has 1 boundary loops, 0"),
            std::string::npos);
  fitted.float_topology = closed;
  fitted.topology.nonmanifold_edges = 2;
  EXPECT_EQ(topology_mismatch(fitted), "the surface is not a manifold");
}

}  // namespace
}  // namespace spline
