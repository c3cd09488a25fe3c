// The conformal flow with intrinsic Delaunay flips (ricci/intrinsic/conformal_flow.h): one cone
// of curvature 2 pi chi converges at genus 4 to 10, every other vertex flat, Gauss-Bonnet in
// closed form, and the flat metric lays out as a one-cone atlas with rigid transitions.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "ricci/intrinsic/conformal_flow.h"
#include "ricci/intrinsic/point_tracking.h"
#include "ricci/mesh/arrays.h"
#include "ricci/mesh/errors.h"
#include "ricci/mesh/io.h"
#include "ricci/mesh/primitives.h"
#include "ricci/mesh/simplify.h"
#include "ricci/metric/curvature.h"
#include "ricci/metric/polish_e2.h"
#include "ricci/pipeline/one_cone_atlas.h"
#include "ricci/singularity/one_cone.h"

namespace {

// The curvature of the final triangulation, recomputed from its lengths.
Eigen::VectorXd recomputed_curvature(const ricci::IntrinsicFlowResult& r) {
  Eigen::MatrixX3d angles;
  EXPECT_TRUE(ricci::intrinsic_corner_angles(r.triangulation, r.u, angles));
  return ricci::intrinsic_curvature(r.triangulation, angles);
}

// The eight (closed genus 2) with its one cone at vertex 0.
ricci::OneConeProblem eight_cone_at_vertex_0() {
  return ricci::prepare_one_cone(
      ricci::read_mesh(std::string(MSP_TEST_DATA) + "/meshes/closed_g2/eight.off"), 0);
}

// Two flows to `targets` ended at one metric: a's curvature is the target's, and with one
// pinned vertex the log scale factors agree.
void expect_same_metric(const ricci::IntrinsicFlowResult& a, const ricci::IntrinsicFlowResult& b,
                        const ricci::Targets& targets) {
  EXPECT_LT((recomputed_curvature(a) - targets.curvature).cwiseAbs().maxCoeff(), 1e-12);
  ASSERT_EQ(a.pinned_vertex, b.pinned_vertex);
  EXPECT_LT((a.u - b.u).cwiseAbs().maxCoeff(), 1e-10);
}

TEST(IntrinsicConformalFlow, FlattensABumpyTorus) {
  const ricci::Mesh mesh =
      ricci::make_random_perturbed(ricci::make_torus(40, 12, 2.0, 0.6), 0.3, 3);
  const ricci::IntrinsicFlowResult r = ricci::intrinsic_conformal_flow(
      mesh, ricci::uniform_target(mesh, ricci::Geometry::euclidean));
  ASSERT_TRUE(r.converged()) << r.message;
  const Eigen::VectorXd K = recomputed_curvature(r);
  EXPECT_LT(K.cwiseAbs().maxCoeff(), 1e-10);  // every vertex's angles sum to 2 pi
  EXPECT_EQ(r.triangulation.vertex_count, static_cast<int>(mesh.n_vertices()));
}

TEST(IntrinsicConformalFlow, RefusesATargetBreakingGaussBonnet) {
  const ricci::Mesh mesh = ricci::make_genus_slab(4);
  ricci::Targets targets = ricci::single_cone_target(mesh, 0);
  targets.curvature[0] += 0.5;
  try {
    (void)ricci::intrinsic_conformal_flow(mesh, targets);
    FAIL() << "no exception";
  } catch (const ricci::InfeasibleTargetError& e) {
    EXPECT_NE(std::string(e.what()).find("Gauss-Bonnet"), std::string::npos) << e.what();
  }
}

class OneConeEveryGenus : public ::testing::TestWithParam<int> {};

TEST_P(OneConeEveryGenus, ConvergesAndLaysOutAsAnAtlas) {
  const int genus = GetParam();
  // As the one-cone pipeline runs it: valence modification, then two levels of refinement
  // within 6 rings of the cone (the flat metric scales like rho^(2g - 2) there).
  ricci::OneConeProblem problem = ricci::prepare_one_cone(ricci::make_genus_slab(genus, 2, 4), 0);
  (void)ricci::refine_around_cone(problem, {2, 6});
  const ricci::Mesh& mesh = problem.mesh;
  const int cone = problem.cone;
  const ricci::IntrinsicFlowResult r = ricci::intrinsic_conformal_flow(mesh, problem.targets);
  // Vertex 0 is a valence-3 corner: needles next to the cone put the double evaluation's
  // rounding floor near the tolerance, and the flow may end on that plateau (its documented
  // stop), which the pipeline's long-double polish passes. Either way the metric is checked
  // after that polish.
  ASSERT_TRUE(r.converged() || (r.status == ricci::FlowStatus::stalled && r.max_error < 1e-8))
      << r.message;
  EXPECT_GT(r.flips, 0);
  const ricci::IntrinsicMesh domain =
      ricci::to_mesh(r.triangulation, r.u, ricci::to_arrays(mesh).V);
  const ricci::PolishE2Result polished =
      ricci::polish_e2_lengths(domain.mesh, domain.lengths, problem.targets.curvature);
  EXPECT_LT(polished.error_after, 1e-12);
  const Eigen::VectorXd K = ricci::vertex_curvature(domain.mesh, polished.lengths, ricci::Geometry::euclidean);
  const double chi = 2.0 - 2.0 * genus;
  EXPECT_NEAR(K.sum(), 2 * M_PI * chi, 1e-8);
  EXPECT_NEAR(K[cone], 2 * M_PI * chi, 1e-9);  // cone angle 2 pi (2g - 1)
  Eigen::VectorXd flat = K;
  flat[cone] = 0;
  EXPECT_LT(flat.cwiseAbs().maxCoeff(), 1e-9);
}

// The pipeline's route (ricci/pipeline/one_cone_atlas.h): the metric polished in long double,
// then the cut graph, layout and atlas on the flipped triangulation.
TEST(IntrinsicOneConeAtlas, Genus4OnTheFlippedTriangulation) {
  const int genus = 4;
  ricci::OneConeAtlasOptions options;
  options.singular_vertex = 0;
  options.route = ricci::FlowRoute::intrinsic_delaunay;
  options.cone_refinement = {2, 6};
  const ricci::OneConeAtlasResult r =
      ricci::build_one_cone_atlas(ricci::make_genus_slab(genus, 2, 4), options);
  ASSERT_TRUE(r.intrinsic);
  EXPECT_GT(r.intrinsic_flips, 0);
  EXPECT_NEAR(r.flow.curvature[r.problem.cone], 2 * M_PI * (2 - 2 * genus), 1e-9);
  EXPECT_EQ(r.atlas.layout.flipped_faces, 0);
  EXPECT_EQ(r.atlas.uncovered_faces, 0);
  EXPECT_LT(r.relative_transition_residual(), 1e-9);
  EXPECT_LT(r.atlas.domain_max_absolute_length_error / r.atlas.domain_diameter, 1e-9);
}

// Points of the surface placed on the flipped triangulation (place_on_problem_mesh): placed on
// the faces the flow started from, carried through its flips, each lands in a face of the
// atlas' mesh with barycentric coordinates of the flat metric; carried back, every one
// reproduces its 3D position, and every vertex lands on its own corner.
TEST(IntrinsicOneConeAtlas, PlacedPointsKeepTheir3DPositionsThroughTheFlips) {
  const int genus = 4;
  ricci::OneConeAtlasOptions options;
  options.singular_vertex = 0;
  options.route = ricci::FlowRoute::intrinsic_delaunay;
  options.keep_flip_record = true;
  const ricci::Mesh slab = ricci::make_genus_slab(genus, 2, 4);
  const ricci::OneConeAtlasResult r = ricci::build_one_cone_atlas(slab, options);
  ASSERT_TRUE(r.intrinsic);
  ASSERT_FALSE(r.flip_record.empty());
  ASSERT_EQ(static_cast<int>(r.flip_record.flip_log.size()), r.intrinsic_flips);
  const ricci::Mesh& initial = ricci::placement_mesh(r);
  ASSERT_EQ(&initial, &r.flip_record.initial);
  ASSERT_EQ(initial.n_vertices(), r.problem.mesh.n_vertices());
  ASSERT_EQ(initial.n_faces(), r.problem.mesh.n_faces());

  // Queries: every vertex, then 3 points inside each face, of the starting faces.
  const Eigen::MatrixX3d V = ricci::to_arrays(initial).V;
  const auto nv = static_cast<Eigen::Index>(initial.n_vertices());
  Eigen::MatrixX3d queries(nv + 3 * static_cast<Eigen::Index>(initial.n_faces()), 3);
  queries.topRows(nv) = V;
  Eigen::Index row = nv;
  const Eigen::Matrix3d weights{{0.6, 0.3, 0.1}, {0.2, 0.2, 0.6}, {0.45, 0.1, 0.45}};
  for (auto f : initial.faces()) {
    Eigen::Matrix3d corners;
    int k = 0;
    for (auto v : initial.fv_range(f)) corners.col(k++) = V.row(v.idx()).transpose();
    for (int q = 0; q < 3; ++q) queries.row(row++) = (corners * weights.col(q)).transpose();
  }
  const std::vector<ricci::SurfacePoint> start = ricci::closest_points(initial, queries);
  const std::vector<ricci::SurfacePoint> placed = ricci::place_on_problem_mesh(r, start);
  ASSERT_EQ(placed.size(), start.size());

  // Back through the flips from the placed face and flat coordinates.
  const ricci::IntrinsicCorrespondence map(r.flip_record.triangulation, r.flip_record.flip_log);
  const ricci::IntrinsicTriangulation& end = map.final_triangulation();
  std::vector<ricci::TriangulationPoint> back(placed.size());
  const double diagonal = (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
  int moved = 0;
  for (std::size_t n = 0; n < placed.size(); ++n) {
    const ricci::SurfacePoint& p = placed[n];
    ASSERT_GE(p.face, 0);
    ASSERT_LT(p.face, static_cast<int>(r.problem.mesh.n_faces()));
    EXPECT_NEAR(p.barycentric.sum(), 1.0, 1e-12);
    EXPECT_GE(p.barycentric.minCoeff(), -1e-12);
    std::vector<int> corners;
    for (auto v : r.problem.mesh.fv_range(r.problem.mesh.face_handle(p.face)))
      corners.push_back(v.idx());
    Eigen::Vector3d b;
    for (int k = 0; k < 3; ++k) {
      const int v = end.tail[static_cast<std::size_t>(3 * p.face + k)];
      const auto at = std::find(corners.begin(), corners.end(), v) - corners.begin();
      ASSERT_LT(at, 3) << "face " << p.face << " is not the triangulation's";
      b[k] = p.barycentric[at];
    }
    back[n] = ricci::point_at_barycentric(end, p.face, b.cwiseMax(0.0), r.flip_record.u);
    if (p.face != start[n].face) ++moved;
    if (static_cast<Eigen::Index>(n) < nv) {
      Eigen::Index k = 0;
      EXPECT_NEAR(p.barycentric.maxCoeff(&k), 1.0, 1e-9) << "vertex " << n;
      EXPECT_EQ(corners[static_cast<std::size_t>(k)], static_cast<int>(n));
    }
  }
  EXPECT_GT(moved, static_cast<int>(placed.size()) / 10);  // the flips carried many of them
  back = map.to_initial(std::move(back));
  double worst = 0.0;
  for (std::size_t n = 0; n < back.size(); ++n) {
    const Eigen::Vector3d x = ricci::point_position(map.initial(), V, back[n]);
    worst = std::max(worst, (x - start[n].point).norm() / diagonal);
  }
  EXPECT_LT(worst, 1e-9);

  // A point on no face of the starting mesh is refused with the placement's error.
  for (const int face : {-1, static_cast<int>(initial.n_faces())}) {
    std::vector<ricci::SurfacePoint> bad(1);
    bad[0].face = face;
    bad[0].barycentric = Eigen::Vector3d::Constant(1.0 / 3.0);
    EXPECT_THROW((void)ricci::place_on_problem_mesh(r, bad), ricci::InvalidInputError);
  }

  // Without the record the points stay where they were put, on the atlas' own faces.
  options.keep_flip_record = false;
  const ricci::OneConeAtlasResult plain = ricci::build_one_cone_atlas(slab, options);
  EXPECT_TRUE(plain.flip_record.empty());
  EXPECT_EQ(&ricci::placement_mesh(plain), &plain.problem.mesh);
  const std::vector<ricci::SurfacePoint> same = ricci::place_on_problem_mesh(plain, start);
  for (std::size_t n = 0; n < same.size(); ++n) {
    EXPECT_EQ(same[n].face, start[n].face);
    EXPECT_EQ(same[n].barycentric, start[n].barycentric);
  }
}

// Chord steps (IntrinsicFlowOptions::chord_forcing_cap): conjugate gradients on the last
// factorisation instead of a factorisation per step reach the metric full Newton reaches,
// with fewer factorisations.
TEST(IntrinsicConformalFlow, ChordStepsReachFullNewtonsMetric) {
  const ricci::OneConeProblem problem = eight_cone_at_vertex_0();
  ricci::IntrinsicFlowOptions chord;
  chord.tolerance = 1e-12;
  ricci::IntrinsicFlowOptions full = chord;
  full.chord_forcing_cap = 0;             // no chord steps far from the answer...
  full.nearby_factorization_below = 0;    // ...nor near it: a factorisation per step
  const ricci::IntrinsicFlowResult a = ricci::intrinsic_conformal_flow(problem.mesh, problem.targets, chord);
  const ricci::IntrinsicFlowResult b = ricci::intrinsic_conformal_flow(problem.mesh, problem.targets, full);
  ASSERT_TRUE(a.converged()) << a.message;
  ASSERT_TRUE(b.converged()) << b.message;
  EXPECT_EQ(b.factorizations, b.iterations);
  EXPECT_LT(a.factorizations, b.factorizations);
  EXPECT_GT(a.linear_work.back_substitutions, a.factorizations);
  expect_same_metric(a, b, problem.targets);
}

// A Laplacian a few flips from the last analysed one is analysed with that analysis' ordering
// (IntrinsicFlowOptions::ordering_reuse_flips); without the reuse every new pattern is ordered
// afresh. The metric is the same either way.
TEST(IntrinsicConformalFlow, FewFlipsKeepTheLastOrdering) {
  const ricci::OneConeProblem problem = eight_cone_at_vertex_0();
  ricci::IntrinsicFlowOptions reuse;
  reuse.tolerance = 1e-12;
  reuse.solver = ricci::LinearSolver::cholmod_supernodal;  // (orderings are CHOLMOD's)
  reuse.chord_forcing_cap = 0;           // a factorisation per step: patterns to compare
  reuse.nearby_factorization_below = 0;
  ricci::IntrinsicFlowOptions fresh = reuse;
  fresh.ordering_reuse_flips = -1;
  const ricci::IntrinsicFlowResult a = ricci::intrinsic_conformal_flow(problem.mesh, problem.targets, reuse);
  const ricci::IntrinsicFlowResult b = ricci::intrinsic_conformal_flow(problem.mesh, problem.targets, fresh);
  ASSERT_TRUE(a.converged()) << a.message;
  ASSERT_TRUE(b.converged()) << b.message;
  EXPECT_GE(a.orderings_reused, 1);
  EXPECT_EQ(b.orderings_reused, 0);
  expect_same_metric(a, b, problem.targets);
}

// The long-double polish's goal (polish_e2_lengths' good_enough, the pipeline's kPolishGoal):
// it stops at the step that reaches it, where without a goal it steps on until a step gains
// nothing (the evaluation's floor), spending at least one more back-substitution.
TEST(IntrinsicConformalFlow, PolishStopsOnceGoodEnough) {
  const ricci::OneConeProblem problem = eight_cone_at_vertex_0();
  ricci::IntrinsicFlowOptions options;
  options.tolerance = 1e-6;  // handed over early: the polish has steps to take
  const ricci::IntrinsicFlowResult r =
      ricci::intrinsic_conformal_flow(problem.mesh, problem.targets, options);
  ASSERT_TRUE(r.converged()) << r.message;
  ASSERT_GT(r.max_error, 1e-12);
  const ricci::IntrinsicMesh domain =
      ricci::to_mesh(r.triangulation, r.u, ricci::to_arrays(problem.mesh).V);
  const ricci::NearbyLaplacian nearby{r.laplacian_factorization.get(), r.pinned_vertex};
  const Eigen::VectorXd& target = problem.targets.curvature;
  const ricci::PolishE2Result goal =
      ricci::polish_e2_lengths(domain.mesh, domain.lengths, target, 6, nearby, 1e-12);
  const ricci::PolishE2Result floor =
      ricci::polish_e2_lengths(domain.mesh, domain.lengths, target, 6, nearby);
  EXPECT_LE(goal.error_after, 1e-12);
  EXPECT_GE(goal.iterations, 1);
  EXPECT_LE(goal.iterations, floor.iterations);
  EXPECT_LE(floor.error_after, goal.error_after);
  EXPECT_GT(floor.linear_work.back_substitutions, goal.linear_work.back_substitutions);
  // The goal's metric: its curvature, recomputed in double, within the goal and rounding.
  const Eigen::VectorXd K =
      ricci::vertex_curvature(domain.mesh, goal.lengths, ricci::Geometry::euclidean);
  EXPECT_LT((K - target).cwiseAbs().maxCoeff(), 1e-11);
}

INSTANTIATE_TEST_SUITE_P(Genus, OneConeEveryGenus, ::testing::Values(4, 6));

}  // namespace

namespace {

// A warm start (intrinsic_conformal_flow's warm_u) on the way to the answer is taken and ends
// at the cold start's metric in fewer Newton steps; one farther from the target than u = 0 is
// rejected (the cold start runs) and ends there too.
TEST(IntrinsicConformalFlow, WarmStartReachesTheColdStartsMetric) {
  const ricci::OneConeProblem problem = eight_cone_at_vertex_0();
  ricci::IntrinsicFlowOptions options;
  options.tolerance = 1e-12;
  const ricci::IntrinsicTriangulation initial = ricci::make_intrinsic_triangulation(
      problem.mesh, ricci::mesh_edge_lengths(problem.mesh));
  const Eigen::VectorXd& target = problem.targets.curvature;
  const ricci::IntrinsicFlowResult cold = ricci::intrinsic_conformal_flow(initial, target, options);
  ASSERT_TRUE(cold.converged()) << cold.message;
  EXPECT_EQ(cold.warm_start, ricci::WarmStart::none);

  // Runs Newton from `start`: it converges to the cold start's metric, beginning as expected.
  auto from = [&](const Eigen::VectorXd& start, ricci::WarmStart expected) {
    ricci::IntrinsicFlowResult result =
        ricci::intrinsic_conformal_flow(initial, target, start, options);
    EXPECT_TRUE(result.converged()) << result.message;
    EXPECT_EQ(result.warm_start, expected);
    expect_same_metric(result, cold, problem.targets);
    return result;
  };
  const ricci::IntrinsicFlowResult warm = from(0.5 * cold.u, ricci::WarmStart::taken);
  EXPECT_LT(warm.warm_start_error, warm.cold_start_error);
  EXPECT_LT(warm.iterations, cold.iterations);
  // Far past the answer (and shifted: the pinned vertex takes it back to 0).
  const ricci::IntrinsicFlowResult rejected =
      from((8.0 * cold.u).array() + 3.0, ricci::WarmStart::rejected);
  EXPECT_GE(rejected.warm_start_error, rejected.cold_start_error);
  EXPECT_EQ(rejected.iterations, cold.iterations);

  EXPECT_THROW((void)ricci::intrinsic_conformal_flow(initial, target, Eigen::VectorXd::Zero(3)),
               ricci::InvalidInputError);
}

}  // namespace
