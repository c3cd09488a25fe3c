// Regression over real and bundled meshes of genus 0-3, closed and open: the one-cone atlas must
// come out with the curvature reached, no flipped face, rigid transitions and the right cone.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "ricci/mesh/arrays.h"
#include "ricci/mesh/errors.h"
#include "ricci/mesh/io.h"
#include "ricci/pipeline/one_cone_atlas.h"
#include "test_paths.h"

namespace {

struct Case {
  const char* path;  // "models/..." (bundled) or relative to tests/data/meshes
  int singular_vertex;
};

std::string resolve(const std::string& path) {
  if (path.rfind("models/", 0) == 0) return msp_test::bundled_model(path.substr(7));
  return msp_test::test_mesh(path);
}

// Edge-length errors of the laid-out fundamental domain against the flat metric: the largest
// absolute error (relative to the domain diameter) and the largest relative error over every
// edge. Near a cone of angle 2*pi*(2g - 1) the flat metric shrinks like r^(2g - 1), so edges
// there are down to 1e-17 of the diameter: the layout's double-double positions (edge_vector)
// keep them to full relative accuracy.
struct LayoutErrors {
  double absolute = 0.0, relative = 0.0;
};

LayoutErrors layout_errors(const ricci::OneConeAtlasResult& r) {
  const ricci::Mesh& m = r.problem.mesh;
  const auto& sliced = r.atlas.sliced;
  LayoutErrors errors;
  for (auto e : sliced.mesh.edges()) {
    auto h = sliced.mesh.halfedge_handle(e, 0);
    int a = sliced.mesh.from_vertex_handle(h).idx(), b = sliced.mesh.to_vertex_handle(h).idx();
    auto original = m.find_halfedge(m.vertex_handle(sliced.to_original_vertex[a]),
                                    m.vertex_handle(sliced.to_original_vertex[b]));
    double l = r.flow.lengths[m.edge_handle(original).idx()];
    double error = std::abs(r.atlas.layout.edge_vector(a, b).norm() - l);
    errors.absolute = std::max(errors.absolute, error / r.atlas.domain_diameter);
    errors.relative = std::max(errors.relative, error / l);
  }
  return errors;
}

class OneConeAtlasRegression : public ::testing::TestWithParam<Case> {};

TEST_P(OneConeAtlasRegression, FlatOneConeAtlasIsExact) {
  const Case& c = GetParam();
  ricci::Mesh mesh = ricci::read_mesh(resolve(c.path));
  ricci::OneConeAtlasOptions options;
  options.singular_vertex = c.singular_vertex;
  ricci::OneConeAtlasResult r = ricci::build_one_cone_atlas(mesh, options);

  EXPECT_LT(r.flow.max_error, 1e-9) << c.path;
  // The long-double polish never makes the metric worse and ends near the lengths' rounding.
  EXPECT_LE(r.polish.error_after, r.polish.error_before) << c.path;
  EXPECT_LT(r.polish.error_after, 1e-12) << c.path;
  EXPECT_EQ(r.atlas.layout.flipped_faces, 0) << c.path;
  LayoutErrors errors = layout_errors(r);
  EXPECT_LT(errors.absolute, 1e-11) << c.path;
  EXPECT_LT(errors.relative, 1e-9) << c.path;
  EXPECT_LT(r.relative_transition_residual(), 1e-9) << c.path;
  EXPECT_EQ(r.atlas.uncovered_faces, 0) << c.path;
  const int chi = 2 - 2 * r.problem.genus - r.problem.boundary_loops;
  if (r.problem.kind == ricci::OneConeKind::SingleCone) {
    double cone_angle = 2 * M_PI - r.flow.curvature[r.problem.cone];
    EXPECT_NEAR(cone_angle, 2 * M_PI - 2 * M_PI * chi, 1e-9) << c.path;
    EXPECT_GE(r.problem.mesh.valence(r.problem.mesh.vertex_handle(r.problem.cone)),
              static_cast<unsigned>(ricci::required_cone_valence(2 * M_PI * chi)));
  }
  if (r.problem.kind == ricci::OneConeKind::FlatTorus) {
    for (const auto& s : r.atlas.side_pairings) EXPECT_NEAR(s.motion.angle, 0.0, 1e-9) << c.path;
  }
  // Gauss-Bonnet of the flat metric: all curvature sums to 2*pi*chi of the flowed mesh.
  const auto& m = r.problem.mesh;
  int chi_flowed = static_cast<int>(m.n_vertices()) - static_cast<int>(m.n_edges()) + static_cast<int>(m.n_faces());
  EXPECT_NEAR(r.flow.curvature.sum(), 2 * M_PI * chi_flowed, 1e-8) << c.path;
}

INSTANTIATE_TEST_SUITE_P(
    TestAndBundledModels, OneConeAtlasRegression,
    ::testing::Values(Case{"closed_g0/knight_decimated.off", 0}, Case{"models/genus0.off", 10},
                      Case{"closed_g1/knot1.off.gz", -1}, Case{"closed_g1/elk.off", -1},
                      Case{"models/genus1.off", -1}, Case{"closed_g2/eight.off", 0},
                      Case{"closed_g2/eight_cgal.off", 3}, Case{"models/genus2.off", 0},
                      Case{"closed_g3/elephant_cgal.off", 0}, Case{"models/genus3.off", 0},
                      Case{"open/head.off", -1}, Case{"open/eight_hole.off", -1},
                      Case{"open/intersection_quads.off", -1}, Case{"models/genus2_hole.off", -1},
                      Case{"models/cap_open.off", -1}, Case{"open/lion.off.gz", -1},
                      Case{"open/double-torus-3-holes_quad.off", -1},
                      Case{"open/mech-holes-shark.off.gz", -1}, Case{"closed_g2/joint.off", -1},
                      Case{"closed_g2/femur.off.gz", 1458}));

TEST(OneConeAtlas, AutomaticChoiceRunsFewFlows) {
  ricci::Mesh mesh = ricci::read_mesh(resolve("closed_g2/eight.off"));
  ricci::OneConeAtlasResult r = ricci::build_one_cone_atlas(mesh);
  EXPECT_GE(r.chosen_vertex, 0);
  EXPECT_GT(r.flows_for_choice, 0);
  // eight.off has 768 vertices; the greedy one-ring descent took 40 flows once single cones
  // start with tangent circles near the cone (their area distortion differs slightly).
  EXPECT_LT(r.flows_for_choice, 50);
  EXPECT_LT(r.flow.max_error, 1e-9);
}

// The run's linear work, stage by stage: the choice's linear model is one factorisation and
// its verifying flows each at least one more; the flow's factorisations are its Newton
// factorisations, each followed by a back-substitution; the total is the stages' sum.
TEST(OneConeAtlas, LinearWorkCountsEveryStage) {
  ricci::Mesh mesh = ricci::read_mesh(resolve("closed_g2/eight.off"));
  const ricci::OneConeAtlasResult r = ricci::build_one_cone_atlas(mesh);
  const ricci::OneConeAtlasLinearWork& work = r.linear_work;
  ASSERT_GT(r.flows_for_choice, 0);
  EXPECT_GE(work.choice.factorizations, 1 + r.flows_for_choice);
  EXPECT_GE(work.choice.right_hand_sides, r.solves_for_choice);
  EXPECT_EQ(work.flow.factorizations, r.flow.factorizations);
  EXPECT_GE(work.flow.back_substitutions, work.flow.factorizations);
  EXPECT_GE(work.flow.factorizations, 1);
  EXPECT_EQ(work.polish.factorizations + work.polish.back_substitutions > 0, r.polished);
  const ricci::LinearWork total = work.total();
  EXPECT_EQ(total.factorizations,
            work.choice.factorizations + work.flow.factorizations + work.polish.factorizations);
  EXPECT_EQ(total.solves(), total.factorizations + total.back_substitutions);

  // A given vertex: no choice, no work for it.
  ricci::OneConeAtlasOptions given;
  given.singular_vertex = r.chosen_vertex;
  const ricci::OneConeAtlasResult fixed = ricci::build_one_cone_atlas(mesh, given);
  EXPECT_EQ(fixed.linear_work.choice.solves(), 0);
  EXPECT_EQ(fixed.linear_work.flow.factorizations, fixed.flow.factorizations);
}

}  // namespace

namespace {

// The polish is gated on the flow's double-precision defect: it runs exactly when that defect
// reaches options.polish_threshold, and a skipped polish hands the flow's lengths on unchanged.
TEST(OneConeAtlas, PolishRunsOnlyAboveItsThreshold) {
  ricci::Mesh mesh = ricci::read_mesh(resolve("closed_g2/eight.off"));
  ricci::OneConeAtlasOptions options;
  options.singular_vertex = 0;
  options.intrinsic_first = false;  // the gate of the fixed-connectivity flows' polish
  options.polish_threshold = 0.0;
  const ricci::OneConeAtlasResult always = ricci::build_one_cone_atlas(mesh, options);
  EXPECT_TRUE(always.polished);
  EXPECT_LE(always.polish.error_after, always.polish.error_before);

  options.polish_threshold = std::numeric_limits<double>::infinity();
  const ricci::OneConeAtlasResult never = ricci::build_one_cone_atlas(mesh, options);
  EXPECT_FALSE(never.polished);
  EXPECT_EQ(never.polish.iterations, 0);
  EXPECT_EQ(never.polish.error_after, never.flow.max_error);
  EXPECT_EQ(never.flow.lengths, never.polish.lengths);
  EXPECT_EQ(never.atlas.layout.flipped_faces, 0);
  EXPECT_LT(never.relative_transition_residual(), 1e-9);

  options.polish_threshold = 0.5 * never.flow.max_error;  // just below the defect: polishes
  EXPECT_TRUE(ricci::build_one_cone_atlas(mesh, options).polished);
  options.polish_threshold = 2.0 * never.flow.max_error;  // just above: skips
  EXPECT_FALSE(ricci::build_one_cone_atlas(mesh, options).polished);
}

}  // namespace

namespace {

// From polish_floor_from_faces the intrinsic flow stops as soon as it is below 1e-8 and the
// long-double polish finishes the metric (at 1.6M faces double's floor meets the tolerance):
// here with the size bound lowered to a bundled genus-2 mesh and a tolerance of 1e-13, the
// hand-over must still give a metric within the tolerance, fewer Newton steps than Newton's own
// way to it, and the same atlas: rigid transitions, no flipped face, the same distortion.
TEST(OneConeAtlas, LargeMeshesLeaveTheDoubleFloorToThePolish) {
  const ricci::Mesh mesh = ricci::read_mesh(resolve("closed_g2/eight.off"));
  ricci::OneConeAtlasOptions options;
  options.singular_vertex = 0;
  options.flow.tolerance = 1e-13;
  options.polish_floor_from_faces = std::numeric_limits<int>::max();
  const ricci::OneConeAtlasResult newton = ricci::build_one_cone_atlas(mesh, options);
  options.polish_floor_from_faces = 0;
  const ricci::OneConeAtlasResult handed = ricci::build_one_cone_atlas(mesh, options);
  ASSERT_TRUE(newton.intrinsic && handed.intrinsic);
  ASSERT_TRUE(handed.polished);
  EXPECT_GT(handed.polish.error_before, 1e-13);
  EXPECT_LT(handed.polish.error_before, 1e-8);
  EXPECT_LE(handed.polish.error_after, 1e-13);
  EXPECT_LE(handed.flow.max_error, 1e-13);
  EXPECT_LT(handed.flow.iterations, newton.flow.iterations);
  for (const ricci::OneConeAtlasResult* r : {&newton, &handed}) {
    EXPECT_EQ(r->atlas.layout.flipped_faces, 0);
    EXPECT_LT(r->relative_transition_residual(), 1e-9);
  }
  EXPECT_NEAR(handed.distortion.quasi_conformal_area_mean,
              newton.distortion.quasi_conformal_area_mean, 1e-9);
}

namespace {
// eight.off's options with the cone given, the polish forced and the intrinsic mesh (and cut)
// built beside it.
ricci::OneConeAtlasOptions polish_forced_beside() {
  ricci::OneConeAtlasOptions options;
  options.singular_vertex = 0;
  options.polish_floor_from_faces = 0;  // the polish runs
  options.mesh_beside_polish_below_faces = std::numeric_limits<int>::max();
  return options;
}
}  // namespace

// The intrinsic flow's mesh is built beside the polish (below mesh_beside_polish_below_faces) or
// after it: the same triangulation, removed-edge count, lengths and atlas either way.
TEST(OneConeAtlas, MeshBuiltBesideThePolishEqualsTheOneBuiltAfterIt) {
  const ricci::Mesh mesh = ricci::read_mesh(resolve("closed_g2/eight.off"));
  ricci::OneConeAtlasOptions options = polish_forced_beside();
  const ricci::OneConeAtlasResult beside = ricci::build_one_cone_atlas(mesh, options);
  options.mesh_beside_polish_below_faces = 0;
  const ricci::OneConeAtlasResult after = ricci::build_one_cone_atlas(mesh, options);
  ASSERT_TRUE(beside.intrinsic && after.intrinsic);
  ASSERT_TRUE(beside.polished && after.polished);
  EXPECT_GT(beside.removed_edges, 0);
  EXPECT_EQ(beside.removed_edges, after.removed_edges);
  ASSERT_EQ(beside.problem.mesh.n_faces(), after.problem.mesh.n_faces());
  for (const auto f : beside.problem.mesh.faces()) {
    auto a = beside.problem.mesh.fv_range(f).begin();
    auto b = after.problem.mesh.fv_range(f).begin();
    for (int k = 0; k < 3; ++k, ++a, ++b) EXPECT_EQ(a->idx(), b->idx());
  }
  EXPECT_EQ(beside.flow.lengths, after.flow.lengths);
  EXPECT_EQ(beside.relative_transition_residual(), after.relative_transition_residual());
  EXPECT_EQ(beside.atlas.layout.flipped_faces, 0);
}

// The cut graph and slicing made beside the polish (on the unpolished lengths) cut where the
// atlas stage cuts on the polished ones: the same loops, loop lengths in the polished metric,
// layout and transitions; and build_affine_atlas on the result's mesh and lengths agrees.
TEST(OneConeAtlas, CutBesideThePolishEqualsTheCutAfterIt) {
  const ricci::Mesh mesh = ricci::read_mesh(resolve("closed_g2/eight.off"));
  ricci::OneConeAtlasOptions options = polish_forced_beside();
  const ricci::OneConeAtlasResult beside = ricci::build_one_cone_atlas(mesh, options);
  options.cut_beside_polish = false;
  const ricci::OneConeAtlasResult after = ricci::build_one_cone_atlas(mesh, options);
  ASSERT_TRUE(beside.intrinsic && beside.polished);
  const ricci::CutGraph& a = beside.atlas.cut;
  const ricci::CutGraph& b = after.atlas.cut;
  EXPECT_EQ(a.root, b.root);
  EXPECT_EQ(a.is_cut_edge, b.is_cut_edge);
  ASSERT_EQ(a.loops.size(), 4u);  // genus 2
  ASSERT_EQ(a.loops.size(), b.loops.size());
  for (size_t i = 0; i < a.loops.size(); ++i) {
    EXPECT_EQ(a.loops[i].halfedges, b.loops[i].halfedges);
    EXPECT_EQ(a.loops[i].length, b.loops[i].length);
    double sum = 0.0;
    for (auto h : a.loops[i].halfedges) {
      sum += beside.flow.lengths[beside.problem.mesh.edge_handle(h).idx()];
    }
    EXPECT_EQ(a.loops[i].length, sum);
  }
  EXPECT_EQ(beside.atlas.sliced.mesh.n_vertices(), after.atlas.sliced.mesh.n_vertices());
  EXPECT_EQ(beside.atlas.layout.positions, after.atlas.layout.positions);
  EXPECT_EQ(beside.atlas.charts.size(), after.atlas.charts.size());
  EXPECT_EQ(beside.relative_transition_residual(), after.relative_transition_residual());
  EXPECT_LT(beside.relative_transition_residual(), 1e-9);
  EXPECT_EQ(beside.atlas.layout.flipped_faces, 0);
  // A cut or slicing of another mesh is refused.
  ricci::AffineAtlas wrong;
  wrong.cut = a;
  EXPECT_THROW(ricci::complete_affine_atlas(beside.problem.mesh, beside.flow.lengths,
                                            Eigen::VectorXd(), {}, wrong),
               ricci::InvalidInputError);
}

}  // namespace

namespace {

// genus3_10k (marching cubes, cone of 10pi at vertex 0): the circle packing with tangent
// circles near the cone converges on its own once the line search follows the convex Ricci
// energy (a residual-only search accepted an overshooting first step and the next Hessian was
// singular: three metrics failed and the combinatorial one, which ignores the mesh, was used).
// The circle-packing route alone (the intrinsic flow and the inversive-distance route, tried
// first by default, off).
TEST(OneConeAtlas, TenPiConeOnMarchingCubesKeepsTheMeshConformalMetric) {
  ricci::Mesh mesh = ricci::read_mesh(resolve("bench/genus3_10k.obj.gz"));
  ricci::OneConeAtlasOptions options;
  options.singular_vertex = 0;
  options.intrinsic_first = false;
  options.inversive_distance_route = false;
  const ricci::OneConeAtlasResult r = ricci::build_one_cone_atlas(mesh, options);
  EXPECT_TRUE(r.flow.failed_attempts.empty()) << r.flow.failed_attempts.front();
  EXPECT_EQ(r.flow.metric.scheme, ricci::Scheme::circle_packing);
  EXPECT_LT(r.flow.max_error, 1e-10);
  EXPECT_EQ(r.atlas.layout.flipped_faces, 0);
  EXPECT_LT(r.relative_transition_residual(), 1e-9);
}

// The inversive-distance metric from min radii breaks triangles at the 6pi cone of
// genus2_10k: the flow records which face broke each line search, a valid face index, and
// stops with a triangle-inequality status instead of crawling.
TEST(OneConeAtlas, BrokenTrianglesAreRecorded) {
  ricci::Mesh mesh = ricci::read_mesh(resolve("bench/genus2_10k.obj.gz"));
  const ricci::OneConeProblem problem = ricci::prepare_one_cone(mesh, 0);
  ricci::FlowOptions options = ricci::one_cone_flow_options();
  options.scheme = ricci::Scheme::inversive_distance;
  options.radii = ricci::RadiusInit::min;
  const ricci::FlowResult r = ricci::flow(problem.mesh, problem.targets, options);
  ASSERT_FALSE(r.converged());
  EXPECT_EQ(r.status, ricci::FlowStatus::triangle_inequality);
  ASSERT_FALSE(r.broken_faces.empty());
  EXPECT_LE(r.broken_faces.size(), ricci::kMaxBrokenFacesRecorded);
  for (const ricci::BrokenTrial& b : r.broken_faces) {
    EXPECT_GE(b.face, 0);
    EXPECT_LT(b.face, static_cast<int>(problem.mesh.n_faces()));
    EXPECT_GE(b.iteration, 1);
    EXPECT_LE(b.iteration, r.iterations + 1);
    EXPECT_GE(b.trials, 1);
  }
}

// The staged flow is taken straight away where the one-shot flow is predicted to fail: at the
// 10pi cone of genus3_10k the plain inversive-distance flow's first Newton step is cut below
// 1/64 and gains under 2% (it fails after three such steps); with give_up_on_short_first_step
// the run ends after that one step. A flow whose first step is full is not stopped.
TEST(OneConeAtlas, ShortFirstStepPredictsTheOneShotFailure) {
  ricci::Mesh mesh = ricci::read_mesh(resolve("bench/genus3_10k.obj.gz"));
  const ricci::OneConeProblem problem = ricci::prepare_one_cone(mesh, 0);
  ricci::FlowOptions options = ricci::one_cone_flow_options();
  options.scheme = ricci::Scheme::inversive_distance;
  options.radii = ricci::RadiusInit::mean;
  std::vector<double> steps;
  options.progress = [&](const ricci::FlowProgress& p) { steps.push_back(p.step); };
  const ricci::FlowResult plain = ricci::flow(problem.mesh, problem.targets, options);
  ASSERT_FALSE(plain.converged());
  ASSERT_GE(plain.error_history.size(), 2u);
  ASSERT_LT(steps.front(), 1.0 / 64);
  ASSERT_GT(plain.error_history[1], 0.98 * plain.error_history[0]);
  options.give_up_on_short_first_step = true;
  const ricci::FlowResult predicted = ricci::flow(problem.mesh, problem.targets, options);
  EXPECT_FALSE(predicted.converged());
  EXPECT_EQ(predicted.iterations, 1);
  EXPECT_LT(predicted.iterations, plain.iterations);
  EXPECT_NE(predicted.message.find("predicted"), std::string::npos) << predicted.message;

  const ricci::Mesh torus = ricci::read_mesh(resolve("bench/torus_10k.obj.gz"));
  const ricci::OneConeProblem flat = ricci::prepare_one_cone(torus, -1);
  ricci::FlowOptions easy = ricci::one_cone_flow_options();
  easy.give_up_on_short_first_step = true;
  EXPECT_TRUE(ricci::flow(flat.mesh, flat.targets, easy).converged());
}

}  // namespace

namespace {

ricci::OneConeAtlasOptions cleaned_up_options() {
  ricci::OneConeAtlasOptions options;
  options.singular_vertex = 0;
  options.collapse_short_edges = true;
  options.flip_flat_edges = true;
  options.flat_flips.max_normal_angle = 5.0 * M_PI / 180.0;
  options.flat_flips.max_relative_deviation = 0.01;
  return options;
}

// genus3_10k (marching cubes) has 132 edges under 1% of the median: after their collapse and the
// flat flips (none within 6 rings of the cone, where the valences decide whether Thurston's
// packing reaches the 10pi cone) the default metric still gives an exact atlas, and the problem
// maps its vertices back to the input's.
TEST(OneConeAtlas, CleanedUpSurfaceKeepsTheAtlasExact) {
  const ricci::Mesh mesh = ricci::read_mesh(resolve("bench/genus3_10k.obj.gz"));
  ricci::OneConeAtlasOptions options = cleaned_up_options();
  options.flat_flips.protected_rings = 6;
  const ricci::OneConeAtlasResult r = ricci::build_one_cone_atlas(mesh, options);
  EXPECT_GT(r.short_edges.collapses, 100);
  EXPECT_GT(r.flat_flips.flips, 1000);
  EXPECT_LT(r.flow.max_error, 1e-10);
  EXPECT_EQ(r.atlas.layout.flipped_faces, 0);
  EXPECT_LT(r.relative_transition_residual(), 1e-9);
  EXPECT_EQ(r.problem.input_vertex[static_cast<size_t>(r.problem.cone)], 0);
  EXPECT_EQ(r.problem.chosen_vertex, 0);
  for (auto v : r.problem.mesh.vertices()) {
    const int input = r.problem.input_vertex[static_cast<size_t>(v.idx())];
    if (input >= 0) {
      EXPECT_EQ(r.problem.mesh.point(v), mesh.point(mesh.vertex_handle(input)));
    }
  }
}

// The inversive-distance metric on genus2_10k (marching cubes, 6pi cone), asked for as the
// metric: the plain flow breaks triangles (BrokenTrianglesAreRecorded); the route of
// inversive_distance_route (clean-up, inversive distances >= 0, Thurston's angles within 4 rings
// of the cone, the cone in 4 stages) converges and is nearly conformal (area-weighted QC 1.12,
// median 1.07; CEPS reports 1.03-1.13 on such meshes) where the circle packing gives 1.67, with
// an exact atlas.
TEST(OneConeAtlas, InversiveDistanceRouteIsNearlyConformalAndExact) {
  const ricci::Mesh mesh = ricci::read_mesh(resolve("bench/genus2_10k.obj.gz"));
  ricci::OneConeAtlasOptions options;
  options.singular_vertex = 0;
  options.keep_metric = true;
  options.flow.scheme = ricci::Scheme::inversive_distance;
  options.flow.radii = ricci::RadiusInit::mean;
  EXPECT_TRUE(ricci::takes_inversive_distance_route(mesh, options));
  const ricci::OneConeAtlasResult r = ricci::build_one_cone_atlas(mesh, options);
  EXPECT_EQ(r.flow.metric.scheme, ricci::Scheme::inversive_distance);
  EXPECT_TRUE(r.flow.failed_attempts.empty()) << r.flow.failed_attempts.front();
  EXPECT_GT(r.flat_flips.flips, 1000);
  EXPECT_LT(r.flow.max_error, 1e-10);
  EXPECT_NEAR(2 * M_PI - r.flow.curvature[r.problem.cone], 6 * M_PI, 1e-9);
  EXPECT_LT(r.distortion.quasi_conformal_area_mean, 1.2);
  EXPECT_LT(r.distortion.quasi_conformal_p50, 1.1);
  EXPECT_EQ(r.atlas.layout.flipped_faces, 0);
  EXPECT_LT(r.atlas.layout.max_relative_length_error, 1e-8);
  EXPECT_LT(r.relative_transition_residual(), 1e-9);
}

// The metric routes on a single cone. The intrinsic flow first only by default: not when a
// metric is asked for, with fixed connectivity, when switched off, or on a torus (no cone).
// The inversive-distance route by default or when asked for, never when another metric is asked
// for or there is no cone.
TEST(OneConeAtlas, RoutesByDefaultOrWhenAskedForOnASingleCone) {
  const ricci::Mesh genus2 = ricci::read_mesh(resolve("bench/genus2_10k.obj.gz"));
  const ricci::Mesh torus = ricci::read_mesh(resolve("bench/torus_10k.obj.gz"));
  ricci::OneConeAtlasOptions first;
  EXPECT_TRUE(ricci::takes_intrinsic_flow_first(genus2, first));
  EXPECT_FALSE(ricci::takes_intrinsic_flow_first(torus, first));
  first.keep_metric = true;
  EXPECT_FALSE(ricci::takes_intrinsic_flow_first(genus2, first));
  first.keep_metric = false;
  first.route = ricci::FlowRoute::fixed_connectivity;
  EXPECT_FALSE(ricci::takes_intrinsic_flow_first(genus2, first));
  first.route = ricci::FlowRoute::automatic;
  first.intrinsic_first = false;
  EXPECT_FALSE(ricci::takes_intrinsic_flow_first(genus2, first));

  ricci::OneConeAtlasOptions options;
  EXPECT_TRUE(ricci::takes_inversive_distance_route(genus2, options));  // the default
  EXPECT_FALSE(ricci::takes_inversive_distance_route(torus, options));  // no cone
  options.keep_metric = true;  // circle packing asked for
  EXPECT_FALSE(ricci::takes_inversive_distance_route(genus2, options));
  options.flow.scheme = ricci::Scheme::inversive_distance;
  EXPECT_TRUE(ricci::takes_inversive_distance_route(genus2, options));
  EXPECT_FALSE(ricci::takes_inversive_distance_route(torus, options));  // no cone
  options.inversive_distance_route = false;
  EXPECT_FALSE(ricci::takes_inversive_distance_route(genus2, options));
}

// By default the most conformal route that converges wins: on genus2_10k the intrinsic
// Delaunay flow (the discrete conformal metric), named in flow.metric_name with nothing
// refused. Without it the inversive-distance route runs, no more conformal; with the route off
// too (as when both fail), the circle packing with tangent circles at the cone, far less so.
TEST(OneConeAtlas, DefaultMetricIsTheMostConformalRouteThatConverges) {
  const ricci::Mesh mesh = ricci::read_mesh(resolve("bench/genus2_10k.obj.gz"));
  ricci::OneConeAtlasOptions options;
  options.singular_vertex = 0;
  EXPECT_TRUE(ricci::takes_intrinsic_flow_first(mesh, options));
  const ricci::OneConeAtlasResult best = ricci::build_one_cone_atlas(mesh, options);
  ASSERT_TRUE(best.intrinsic) << best.flow.metric_name;
  EXPECT_EQ(best.flow.metric_name.rfind("intrinsic Delaunay flow", 0), 0u) << best.flow.metric_name;
  EXPECT_TRUE(best.flow.failed_attempts.empty());
  EXPECT_LT(best.distortion.quasi_conformal_area_mean, 1.2);
  EXPECT_EQ(best.atlas.layout.flipped_faces, 0);
  EXPECT_LT(best.relative_transition_residual(), 1e-9);

  options.intrinsic_first = false;
  EXPECT_FALSE(ricci::takes_intrinsic_flow_first(mesh, options));
  const ricci::OneConeAtlasResult route = ricci::build_one_cone_atlas(mesh, options);
  EXPECT_FALSE(route.intrinsic);
  EXPECT_EQ(route.flow.metric_name.rfind("inversive-distance route", 0), 0u) << route.flow.metric_name;
  EXPECT_GE(route.distortion.quasi_conformal_area_mean,
            best.distortion.quasi_conformal_area_mean);
  EXPECT_LT(route.relative_transition_residual(), 1e-9);

  options.inversive_distance_route = false;
  const ricci::OneConeAtlasResult next = ricci::build_one_cone_atlas(mesh, options);
  EXPECT_EQ(next.flow.metric.scheme, ricci::Scheme::circle_packing);
  EXPECT_NE(next.flow.metric_name.find("tangent"), std::string::npos) << next.flow.metric_name;
  EXPECT_GT(next.distortion.quasi_conformal_area_mean, best.distortion.quasi_conformal_area_mean + 0.2);
  EXPECT_EQ(next.atlas.layout.flipped_faces, 0);
}

// Under the 10 pi cone of genus3_10k's vertex 0 the inversive-distance route breaks triangles;
// the intrinsic Delaunay flow (vertex scaling) comes next and wins over the circle packing,
// which is far less conformal, and the route's failure stays listed.
TEST(OneConeAtlas, AfterAFailedRouteTheIntrinsicFlowComesBeforeTheCirclePacking) {
  const ricci::Mesh mesh = ricci::read_mesh(resolve("bench/genus3_10k.obj.gz"));
  ricci::OneConeAtlasOptions options;
  options.singular_vertex = 0;
  options.intrinsic_first = false;  // the order after the route, which the default skips
  const ricci::OneConeAtlasResult best = ricci::build_one_cone_atlas(mesh, options);
  ASSERT_TRUE(best.intrinsic) << best.flow.metric_name;
  EXPECT_EQ(best.flow.metric_name.rfind("intrinsic Delaunay flow", 0), 0u) << best.flow.metric_name;
  ASSERT_FALSE(best.flow.failed_attempts.empty());
  EXPECT_EQ(best.flow.failed_attempts.front().rfind("inversive-distance", 0), 0u)
      << best.flow.failed_attempts.front();
  EXPECT_LT(best.distortion.quasi_conformal_area_mean, 1.3);
  EXPECT_GT(best.distortion.faces, 0.99 * static_cast<double>(best.problem.mesh.n_faces()));
  EXPECT_EQ(best.atlas.layout.flipped_faces, 0);
  EXPECT_LT(best.relative_transition_residual(), 1e-9);
  EXPECT_LT(best.atlas.layout.max_relative_length_error, 1e-9);
  EXPECT_NEAR(best.problem.targets.curvature[best.problem.cone],
              2 * M_PI * (2 - 2 * 3), 1e-12);

  options.intrinsic_before_fixed = false;
  const ricci::OneConeAtlasResult next = ricci::build_one_cone_atlas(mesh, options);
  EXPECT_FALSE(next.intrinsic);
  EXPECT_EQ(next.flow.metric.scheme, ricci::Scheme::circle_packing);
  EXPECT_GT(next.distortion.quasi_conformal_area_mean,
            best.distortion.quasi_conformal_area_mean + 0.3);
}

// On elk (a flat torus whose thin handle breaks the inversive-distance and circle-packing
// triangles) the fixed-connectivity flows converge only on tangent circles, which ignore the
// mesh's shape: by default the intrinsic Delaunay flow runs and wins, far more conformal, and the
// tangent circles are listed as set aside; without intrinsic_before_combinatorial they are kept.
TEST(OneConeAtlas, TheIntrinsicFlowComesBeforeTangentCircles) {
  const ricci::Mesh mesh = ricci::read_mesh(resolve("closed_g1/elk.off"));
  ricci::OneConeAtlasOptions options;
  const ricci::OneConeAtlasResult best = ricci::build_one_cone_atlas(mesh, options);
  ASSERT_TRUE(best.intrinsic) << best.flow.metric_name;
  EXPECT_EQ(best.problem.kind, ricci::OneConeKind::FlatTorus);
  ASSERT_FALSE(best.flow.failed_attempts.empty());
  EXPECT_EQ(best.flow.failed_attempts.back().rfind("combinatorial", 0), 0u)
      << best.flow.failed_attempts.back();
  EXPECT_NE(best.flow.failed_attempts.back().find("set aside"), std::string::npos);
  EXPECT_EQ(best.atlas.layout.flipped_faces, 0);
  EXPECT_LT(best.relative_transition_residual(), 1e-9);
  EXPECT_LT(best.flow.max_error, 1e-10);

  options.intrinsic_before_combinatorial = false;
  const ricci::OneConeAtlasResult tangent = ricci::build_one_cone_atlas(mesh, options);
  EXPECT_FALSE(tangent.intrinsic);
  EXPECT_EQ(tangent.flow.metric.scheme, ricci::Scheme::combinatorial) << tangent.flow.metric_name;
  EXPECT_GT(tangent.distortion.quasi_conformal_area_mean,
            best.distortion.quasi_conformal_area_mean + 0.5);
  for (const std::string& failed : tangent.flow.failed_attempts) {
    EXPECT_EQ(failed.find("set aside"), std::string::npos) << failed;
  }
}

// build_one_cone_atlas(Mesh&&) keeps the input as arrays while the flow runs and rebuilds it
// for a fallback route (genus3_10k's cone 0 with the route first: it fails, the intrinsic flow
// follows on the rebuilt input): the atlas is the const-reference call's, bit for bit, and the
// handed-over mesh is left empty.
TEST(OneConeAtlas, HandedOverMeshGivesTheKeptMeshsAtlas) {
  struct HandOver {
    const char* path;
    int cone;
    bool intrinsic_first;
  };
  for (const HandOver& c : {HandOver{"models/genus2.off", -1, true},
                            HandOver{"bench/genus3_10k.obj.gz", 0, false}}) {
    SCOPED_TRACE(c.path);
    const ricci::Mesh mesh = ricci::read_mesh(resolve(c.path));
    ricci::OneConeAtlasOptions options;
    options.singular_vertex = c.cone;
    options.intrinsic_first = c.intrinsic_first;
    const ricci::OneConeAtlasResult kept = ricci::build_one_cone_atlas(mesh, options);
    ricci::Mesh handed = mesh;
    const ricci::OneConeAtlasResult r = ricci::build_one_cone_atlas(std::move(handed), options);
    EXPECT_EQ(handed.n_vertices(), 0u);  // NOLINT(bugprone-use-after-move): left empty
    EXPECT_EQ(handed.n_faces(), 0u);
    EXPECT_EQ(r.chosen_vertex, kept.chosen_vertex);
    EXPECT_EQ(r.intrinsic, kept.intrinsic);
    EXPECT_EQ(r.flow.metric_name, kept.flow.metric_name);
    EXPECT_EQ(r.flow.failed_attempts, kept.flow.failed_attempts);
    EXPECT_EQ(ricci::to_arrays(r.problem.mesh).F, ricci::to_arrays(kept.problem.mesh).F);
    EXPECT_TRUE(r.flow.lengths == kept.flow.lengths);
    EXPECT_EQ(r.relative_transition_residual(), kept.relative_transition_residual());
    EXPECT_EQ(r.distortion.quasi_conformal_area_mean, kept.distortion.quasi_conformal_area_mean);
    EXPECT_EQ(r.atlas.layout.flipped_faces, 0);
    EXPECT_LT(r.relative_transition_residual(), 1e-9);
    if (!c.intrinsic_first) {  // the fallback ran on the rebuilt input
      ASSERT_TRUE(r.intrinsic);
      ASSERT_FALSE(r.flow.failed_attempts.empty());
      EXPECT_EQ(r.flow.failed_attempts.front().rfind("inversive-distance", 0), 0u);
    }
  }
}

}  // namespace

namespace {

// The intrinsic flow started at half the choice's linear prediction (OneConeAtlasOptions::
// warm_start) reaches the cold start's metric: same cone, the same length on every edge both
// final triangulations have (they may differ where four vertices are nearly co-circular), the
// same area-weighted quasi-conformality, rigid transitions, no flipped face.
TEST(OneConeAtlas, WarmStartFromTheChoiceGivesTheColdStartsAtlas) {
  const ricci::Mesh mesh = ricci::read_mesh(resolve("bench/genus2_10k.obj.gz"));
  ricci::OneConeAtlasOptions options;
  ASSERT_TRUE(ricci::takes_intrinsic_flow_first(mesh, options));
  const ricci::OneConeAtlasResult warm = ricci::build_one_cone_atlas(mesh, options);
  options.warm_start = false;
  const ricci::OneConeAtlasResult cold = ricci::build_one_cone_atlas(mesh, options);
  ASSERT_TRUE(warm.intrinsic);
  ASSERT_TRUE(cold.intrinsic);
  EXPECT_EQ(warm.warm_start, ricci::WarmStart::taken);
  EXPECT_EQ(cold.warm_start, ricci::WarmStart::none);
  EXPECT_EQ(warm.predicted_log_scale.size(), static_cast<Eigen::Index>(mesh.n_vertices()));
  // The model's u has mean zero (to the rounding its 1e-9 diagonal shift amplifies).
  EXPECT_LT(std::abs(warm.predicted_log_scale.mean()),
            1e-6 * warm.predicted_log_scale.cwiseAbs().maxCoeff());
  EXPECT_EQ(warm.chosen_vertex, cold.chosen_vertex);
  EXPECT_LT(warm.flow.iterations, cold.flow.iterations);
  std::map<std::pair<int, int>, double> cold_lengths;
  for (auto e : cold.problem.mesh.edges()) {
    const auto h = cold.problem.mesh.halfedge_handle(e, 0);
    const int a = cold.problem.mesh.from_vertex_handle(h).idx();
    const int b = cold.problem.mesh.to_vertex_handle(h).idx();
    cold_lengths[{std::min(a, b), std::max(a, b)}] = cold.flow.lengths[e.idx()];
  }
  int common = 0;
  double worst = 0.0;
  for (auto e : warm.problem.mesh.edges()) {
    const auto h = warm.problem.mesh.halfedge_handle(e, 0);
    const int a = warm.problem.mesh.from_vertex_handle(h).idx();
    const int b = warm.problem.mesh.to_vertex_handle(h).idx();
    const auto it = cold_lengths.find({std::min(a, b), std::max(a, b)});
    if (it == cold_lengths.end()) continue;
    ++common;
    worst = std::max(worst, std::abs(warm.flow.lengths[e.idx()] / it->second - 1.0));
  }
  EXPECT_GT(common, static_cast<int>(0.99 * static_cast<double>(warm.problem.mesh.n_edges())));
  EXPECT_LT(worst, 1e-9);
  EXPECT_NEAR(warm.distortion.quasi_conformal_area_mean,
              cold.distortion.quasi_conformal_area_mean, 1e-6);
  EXPECT_EQ(warm.atlas.layout.flipped_faces, 0);
  EXPECT_LT(warm.relative_transition_residual(), 1e-9);
}

}  // namespace

namespace {

// The distortion is measured on a thread of its own while the atlas is built: the report is
// the one of the final mesh and metric (the polished lengths on the flipped triangulation),
// and the atlas beside it is whole.
TEST(OneConeAtlas, DistortionMeasuredBesideTheAtlasIsTheFinalMetrics) {
  const ricci::Mesh mesh = ricci::read_mesh(resolve("models/genus2.off"));
  const ricci::OneConeAtlasResult r = ricci::build_one_cone_atlas(mesh);
  ASSERT_TRUE(r.intrinsic);
  ricci::DistortionOptions measure;
  measure.skip_degenerate = true;
  const ricci::DistortionReport alone =
      ricci::measure_distortion(r.problem.mesh, r.flow.lengths, measure);
  EXPECT_EQ(r.distortion.faces, alone.faces);
  EXPECT_EQ(r.distortion.skipped_faces, alone.skipped_faces);
  EXPECT_EQ(r.distortion.quasi_conformal_area_mean, alone.quasi_conformal_area_mean);
  EXPECT_EQ(r.distortion.quasi_conformal_max, alone.quasi_conformal_max);
  EXPECT_GT(r.distortion.faces, 0);
  EXPECT_GE(r.distortion.quasi_conformal_area_mean, 1.0);
  EXPECT_EQ(r.atlas.uncovered_faces, 0);
  EXPECT_EQ(r.atlas.layout.flipped_faces, 0);
  EXPECT_LT(r.relative_transition_residual(), 1e-9);
}

}  // namespace
