// ricci::routed_flow: the fixed-connectivity flow, the intrinsic Delaunay flow after it fails
// on a closed surface in E2, and each route alone.
#include <gtest/gtest.h>

#include "ricci/intrinsic/routed_flow.h"
#include "ricci/mesh/errors.h"
#include "ricci/mesh/primitives.h"

namespace {

const ricci::Mesh& bumpy_torus() {
  static const ricci::Mesh mesh =
      ricci::make_random_perturbed(ricci::make_torus(30, 10, 2.0, 0.6), 0.3, 5);
  return mesh;
}

TEST(RoutedFlow, AutomaticKeepsAConvergingFixedConnectivityFlow) {
  const ricci::Mesh& mesh = bumpy_torus();
  ricci::RoutedFlowOptions options;
  options.flow.fall_back_to_other_metrics = true;
  const ricci::RoutedFlowResult r =
      ricci::routed_flow(mesh, ricci::uniform_target(mesh, ricci::Geometry::euclidean), options);
  ASSERT_TRUE(r.flow.converged()) << r.flow.message;
  EXPECT_EQ(r.metric, ricci::to_string(r.flow.metric.scheme));
  EXPECT_FALSE(r.intrinsic.has_value());
  EXPECT_EQ(r.flips(), 0);
}

// A genus-2 cone of -4 pi at a vertex of valence 6: past the circle packings' valence bound,
// and one Newton step is not enough for the inversive distances. The intrinsic flow takes over
// and the failures are listed.
TEST(RoutedFlow, AutomaticFallsBackToTheIntrinsicFlowAndSaysWhy) {
  const ricci::Mesh mesh = ricci::make_genus_slab(2);
  const ricci::Targets flat = ricci::single_cone_target(mesh, 0);
  ricci::RoutedFlowOptions options;
  options.flow.max_newton_iterations = 1;
  const ricci::RoutedFlowResult fixed = ricci::routed_flow(mesh, flat, options);
  EXPECT_FALSE(fixed.flow.converged());  // fall_back_to_other_metrics is off
  EXPECT_FALSE(fixed.intrinsic.has_value());

  options.flow.fall_back_to_other_metrics = true;
  const ricci::RoutedFlowResult r = ricci::routed_flow(mesh, flat, options);
  ASSERT_TRUE(r.flow.converged()) << r.flow.message;
  EXPECT_EQ(r.metric, "intrinsic-delaunay");
  ASSERT_TRUE(r.intrinsic.has_value());
  EXPECT_EQ(r.flips(), r.intrinsic->flips);
  EXPECT_FALSE(r.flow.failed_attempts.empty());
  EXPECT_LT(r.flow.max_error, 1e-9);
}

TEST(RoutedFlow, IntrinsicRouteNeedsAClosedSurfaceInE2) {
  const ricci::Mesh disk = ricci::make_disk(4, 12);
  ricci::RoutedFlowOptions options;
  options.route = ricci::FlowRoute::intrinsic_delaunay;
  EXPECT_THROW((void)ricci::routed_flow(
                   disk, ricci::boundary_target(disk, ricci::BoundaryMode::spread_by_length),
                   options),
               ricci::InvalidInputError);
  const ricci::Mesh& torus = bumpy_torus();
  const ricci::RoutedFlowResult r = ricci::routed_flow(
      torus, ricci::uniform_target(torus, ricci::Geometry::euclidean), options);
  ASSERT_TRUE(r.flow.converged()) << r.flow.message;
  EXPECT_EQ(r.metric, "intrinsic-delaunay");
  EXPECT_TRUE(r.flow.failed_attempts.empty());
  options.flow.geometry = ricci::Geometry::hyperbolic;
  EXPECT_THROW((void)ricci::routed_flow(torus, ricci::Targets{}, options), ricci::InvalidInputError);
}

}  // namespace
