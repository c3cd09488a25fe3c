// The atlas on flat metrics computed by the Ricci flow (genus 1, 2, open genus 2).
#include <gtest/gtest.h>

#include "ricci/atlas/atlas.h"
#include "ricci/atlas/chart_develop.h"
#include "ricci/flow/flow.h"
#include "ricci/mesh/io.h"
#include "ricci/singularity/one_cone.h"
#include "ricci/topology/test_grids.h"
#include "test_paths.h"

namespace ricci {
namespace {

struct FlatMetric {
  Mesh mesh;
  VertexHandle cone;
  Eigen::VectorXd lengths;
};

/// The one-cone problem around `cone` (valence-modified for genus >= 2) solved by the
/// pipeline's flow with its metric fall-backs; the root is the cone, or `cone` itself when the
/// surface needs none (genus 1, open).
FlatMetric one_cone_metric(const std::string& model, int cone) {
  const OneConeProblem problem = prepare_one_cone(read_mesh(msp_test::test_mesh(model)), cone);
  const FlowResult flow_result = solve_one_cone_flow(problem, one_cone_flow_options());
  EXPECT_TRUE(flow_result.converged()) << flow_result.message;
  FlatMetric m;
  m.mesh = problem.mesh;
  m.cone = VertexHandle(problem.cone >= 0 ? problem.cone : cone);
  m.lengths = flow_result.lengths;
  return m;
}

/// Checks shared by every flat metric: covered neighbourhoods, valid layout, tight transitions.
/// `relative_length_tolerance` bounds the domain's relative edge-length error; near a large cone
/// the edges shrink so much that the coordinates' rounding (about 1e-16 times the diameter)
/// dominates, which the absolute check covers (its bound is the flow's closure error).
void expect_sound_atlas(const FlatMetric& m, const AffineAtlas& atlas,
                        double relative_length_tolerance = 1e-9) {
  EXPECT_EQ(atlas.uncovered_faces, 0);
  EXPECT_EQ(atlas.layout.flipped_faces, 0);
  EXPECT_LT(atlas.domain_max_relative_length_error, relative_length_tolerance);
  EXPECT_LT(atlas.domain_max_absolute_length_error, 1e-10 * atlas.domain_diameter);
  EXPECT_LT(atlas.max_transition_residual, 1e-9 * atlas.domain_diameter);
  EXPECT_LT(atlas.max_side_pairing_residual, 1e-9 * atlas.domain_diameter);
  for (auto f : m.mesh.faces()) {
    const int c = atlas.chart_of_face_neighbourhood(f.idx());
    if (!atlas.in_domain[f.idx()]) continue;
    ASSERT_GE(c, 0);
    for (int g : detail::face_neighbourhood(m.mesh, f.idx(), atlas.in_domain)) {
      const auto p = atlas.face_positions(c, g);
      const Eigen::Vector2d u = p.row(1) - p.row(0), v = p.row(2) - p.row(0);
      EXPECT_GT(u.x() * v.y() - u.y() * v.x(), 0.0);
    }
  }
}

/// The loops' holonomy is a representation: the polygon's relator and the canonical relator
/// [a1,b1]...[ag,bg] both map to the identity.
/// `tolerance` is relative to the domain diameter: the relator's image is off the identity by
/// about the flow's curvature residual summed over the vertices it encloses, times the diameter.
void expect_holonomy_representation(const AffineAtlas& atlas, int genus, double tolerance = 1e-9) {
  ASSERT_EQ(static_cast<int>(atlas.loop_holonomy.size()), 2 * genus);
  ASSERT_EQ(static_cast<int>(atlas.canonical_holonomy.size()), 2 * genus);
  EXPECT_LT(atlas.relator_holonomy_angle, tolerance);
  EXPECT_LT(atlas.relator_holonomy_translation, tolerance * atlas.domain_diameter);
  RigidMotion2 product;
  for (int i = 0; i < genus; ++i) {
    const RigidMotion2& a = atlas.canonical_holonomy[2 * i];
    const RigidMotion2& b = atlas.canonical_holonomy[2 * i + 1];
    product = product.after(a).after(b).after(a.inverse()).after(b.inverse());
  }
  EXPECT_LT(std::abs(product.angle), tolerance);
  EXPECT_LT(product.translation.norm(), tolerance * atlas.domain_diameter);
}

TEST(AtlasOnFlow, GenusTwoConeMetric) {
  const FlatMetric m = one_cone_metric("closed_g2/eight.off", 0);
  const AffineAtlas atlas = build_affine_atlas(m.mesh, m.lengths, m.cone);
  EXPECT_TRUE(atlas.root_is_cone);
  EXPECT_NEAR(atlas.root_curvature, -4.0 * M_PI, 1e-8);
  EXPECT_EQ(atlas.cut.loops.size(), 4u);
  expect_sound_atlas(m, atlas);
  // The holonomy of a genus-2 flat cone metric is not all translations.
  double max_angle = 0.0;
  for (const auto& s : atlas.side_pairings)
    max_angle = std::max(max_angle, std::abs(s.motion.angle));
  EXPECT_GT(max_angle, 1e-3);
  expect_holonomy_representation(atlas, 2);
}

TEST(AtlasOnFlow, GenusThreeConeMetric) {
  const FlatMetric m = one_cone_metric("closed_g3/elephant_cgal.off", 0);
  const AffineAtlas atlas = build_affine_atlas(m.mesh, m.lengths, m.cone);
  EXPECT_TRUE(atlas.root_is_cone);
  EXPECT_NEAR(atlas.root_curvature, -8.0 * M_PI, 1e-8);
  EXPECT_EQ(atlas.cut.loops.size(), 6u);
  // The 10 pi cone shrinks its ring's outer edges to ~1e-8 of the diameter: a few ulps of the
  // coordinates are then ~1e-7 of those edges (the absolute check still holds).
  expect_sound_atlas(m, atlas, 1e-6);
  // 6k vertices with residuals up to 1e-10 each: the relator's image is ~1e-9 of the diameter.
  expect_holonomy_representation(atlas, 3, 1e-8);
}

TEST(AtlasOnFlow, GenusOneFlatMetricHasTranslationsOnly) {
  const FlatMetric m = one_cone_metric("closed_g1/knot1.off.gz", 0);
  const AffineAtlas atlas = build_affine_atlas(m.mesh, m.lengths, m.cone);
  EXPECT_FALSE(atlas.root_is_cone);
  expect_sound_atlas(m, atlas);
  for (const auto& t : atlas.transitions) EXPECT_LT(std::abs(t.motion.angle), 1e-9);
  for (const auto& s : atlas.side_pairings) EXPECT_LT(std::abs(s.motion.angle), 1e-9);
  expect_holonomy_representation(atlas, 1);
  for (const auto& h : atlas.loop_holonomy) EXPECT_LT(std::abs(h.angle), 1e-9);
}

TEST(AtlasOnFlow, OpenGenusTwoWithBoundaryCurvature) {
  const FlatMetric m = one_cone_metric("open/eight_hole.off", 0);
  const AffineAtlas atlas = build_affine_atlas(m.mesh, m.lengths, m.cone);
  EXPECT_FALSE(atlas.root_is_cone);
  EXPECT_EQ(atlas.cut.loops.size(), 4u);
  expect_sound_atlas(m, atlas);
}

}  // namespace
}  // namespace ricci
