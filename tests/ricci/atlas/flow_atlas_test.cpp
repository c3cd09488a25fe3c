// The atlas on flat metrics computed by the Ricci flow (genus 1, 2, open genus 2).
#include <gtest/gtest.h>

#include "ricci/atlas/atlas.h"
#include "ricci/atlas/chart_develop.h"
#include "ricci/flow/flow.h"
#include "ricci/flow/targets.h"
#include "ricci/mesh/io.h"
#include "ricci/singularity/valence.h"
#include "ricci/topology/test_grids.h"

namespace ricci {
namespace {

struct FlatMetric {
  Mesh mesh;
  VertexHandle cone;
  Eigen::VectorXd lengths;
};

FlatMetric one_cone_metric(const std::string& model, int cone) {
  FlatMetric m;
  Mesh mesh = read_mesh(test::shared_model(model));
  const int chi = static_cast<int>(mesh.n_vertices()) - static_cast<int>(mesh.n_edges()) +
                  static_cast<int>(mesh.n_faces());
  m.cone = VertexHandle(cone);
  if (chi < 0 && !mesh.is_boundary(m.cone)) {
    ValenceOptions options;
    options.cone_curvature = 2.0 * M_PI * chi;
    m.mesh = modify_valence(mesh, m.cone, options).mesh;
  } else {
    m.mesh = mesh;
  }
  // The first metric that converges, in the flow's recommended order of fall-backs.
  const std::pair<Scheme, RadiusInit> attempts[] = {{Scheme::InversiveDistance, RadiusInit::Mean},
                                                    {Scheme::InversiveDistance, RadiusInit::Min},
                                                    {Scheme::CirclePacking, RadiusInit::Mean},
                                                    {Scheme::Combinatorial, RadiusInit::Mean}};
  FlowResult flow_result;
  for (const auto& [scheme, radii] : attempts) {
    FlowOptions flow_options;
    flow_options.scheme = scheme;
    flow_options.radii = radii;
    flow_result = flow(m.mesh, single_cone_target(m.mesh, cone), flow_options);
    if (flow_result.converged()) break;
  }
  EXPECT_TRUE(flow_result.converged()) << flow_result.message;
  m.lengths = flow_result.lengths;
  return m;
}

/// Checks shared by every flat metric: covered neighbourhoods, valid layout, tight transitions.
void expect_sound_atlas(const FlatMetric& m, const AffineAtlas& atlas) {
  EXPECT_EQ(atlas.uncovered_faces, 0);
  EXPECT_EQ(atlas.layout.flipped_faces, 0);
  EXPECT_LT(atlas.layout.max_relative_length_error, 1e-9);
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

TEST(AtlasOnFlow, GenusTwoConeMetric) {
  const FlatMetric m = one_cone_metric("closed_g2/eight.off", 0);
  const AffineAtlas atlas = build_affine_atlas(m.mesh, m.lengths, m.cone);
  EXPECT_TRUE(atlas.root_is_cone);
  EXPECT_NEAR(atlas.root_curvature, -4.0 * M_PI, 1e-8);
  EXPECT_EQ(atlas.cut.loops.size(), 4u);
  expect_sound_atlas(m, atlas);
  // The holonomy of a genus-2 flat cone metric is not all translations.
  double max_angle = 0.0;
  for (const auto& s : atlas.side_pairings) max_angle = std::max(max_angle, std::abs(s.motion.angle));
  EXPECT_GT(max_angle, 1e-3);
}

TEST(AtlasOnFlow, GenusOneFlatMetricHasTranslationsOnly) {
  const FlatMetric m = one_cone_metric("closed_g1/knot1.off", 0);
  const AffineAtlas atlas = build_affine_atlas(m.mesh, m.lengths, m.cone);
  EXPECT_FALSE(atlas.root_is_cone);
  expect_sound_atlas(m, atlas);
  for (const auto& t : atlas.transitions) EXPECT_LT(std::abs(t.motion.angle), 1e-9);
  for (const auto& s : atlas.side_pairings) EXPECT_LT(std::abs(s.motion.angle), 1e-9);
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
