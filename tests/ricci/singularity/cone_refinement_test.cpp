// refine_around_cone: denser sampling around the single cone, the surface, topology and cone
// kept, the flow and the atlas as exact as without it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "ricci/mesh/errors.h"
#include "ricci/mesh/io.h"
#include "ricci/mesh/primitives.h"
#include "ricci/pipeline/one_cone_atlas.h"
#include "ricci/singularity/one_cone.h"
#include "test_paths.h"

namespace {

ricci::Mesh read_test_mesh(const std::string& relative) {
  return ricci::read_mesh(msp_test::test_mesh(relative));
}

double total_area(const ricci::Mesh& mesh) {
  double area = 0.0;
  for (auto f : mesh.faces()) area += mesh.calc_face_area(f);
  return area;
}

double longest_spoke(const ricci::Mesh& mesh, int cone) {
  double longest = 0.0;
  for (auto h : mesh.voh_range(mesh.vertex_handle(cone)))
    longest = std::max(longest, mesh.calc_edge_length(h));
  return longest;
}

TEST(ConeRefinement, DenserAtTheConeWithTheSurfaceTopologyAndConeKept) {
  const ricci::OneConeProblem before =
      ricci::prepare_one_cone(read_test_mesh("closed_g2/eight.off"), 5);
  ricci::OneConeProblem after = before;
  const ricci::ConeRefinement done = ricci::refine_around_cone(after, {2, 6});

  EXPECT_EQ(done.levels, 2);
  EXPECT_EQ(done.added_faces,
            static_cast<int>(after.mesh.n_faces()) - static_cast<int>(before.mesh.n_faces()));
  EXPECT_GT(done.added_faces, static_cast<int>(before.mesh.n_faces()) / 2);
  // The same surface (midpoints on the edges) and topology, the cone where it was.
  EXPECT_NEAR(total_area(after.mesh), total_area(before.mesh), 1e-12 * total_area(before.mesh));
  EXPECT_EQ(ricci::surface_topology(after.mesh).genus, 2);
  EXPECT_EQ(ricci::surface_topology(after.mesh).boundary_loops, 0);
  EXPECT_EQ(after.cone, before.cone);
  EXPECT_EQ(after.mesh.point(after.mesh.vertex_handle(after.cone)),
            before.mesh.point(before.mesh.vertex_handle(before.cone)));
  EXPECT_EQ(after.mesh.valence(after.mesh.vertex_handle(after.cone)),
            before.mesh.valence(before.mesh.vertex_handle(before.cone)));
  // Two levels: the cone's edges are a quarter of their length.
  EXPECT_NEAR(longest_spoke(after.mesh, after.cone), longest_spoke(before.mesh, before.cone) / 4,
              1e-12 * longest_spoke(before.mesh, before.cone));
  // Old vertices keep their input index, new ones have none.
  ASSERT_EQ(after.input_vertex.size(), after.mesh.n_vertices());
  EXPECT_TRUE(std::equal(before.input_vertex.begin(), before.input_vertex.end(),
                         after.input_vertex.begin()));
  EXPECT_TRUE(std::all_of(after.input_vertex.begin() + static_cast<long>(before.input_vertex.size()),
                          after.input_vertex.end(), [](int v) { return v == -1; }));
  // Gauss-Bonnet: all the curvature at the cone.
  ASSERT_EQ(after.targets.curvature.size(), static_cast<long>(after.mesh.n_vertices()));
  EXPECT_DOUBLE_EQ(after.targets.curvature[after.cone], -4 * M_PI);
  EXPECT_NEAR(after.targets.curvature.sum(), -4 * M_PI, 1e-12);
}

TEST(ConeRefinement, OnlySingleConesAndValidOptions) {
  ricci::OneConeProblem torus =
      ricci::prepare_one_cone(read_test_mesh("closed_g1/knot1.off.gz"), 0);
  const auto faces = torus.mesh.n_faces();
  EXPECT_EQ(ricci::refine_around_cone(torus, {2, 6}).levels, 0);
  EXPECT_EQ(torus.mesh.n_faces(), faces);
  ricci::OneConeProblem cone = ricci::prepare_one_cone(read_test_mesh("closed_g2/eight.off"), 5);
  EXPECT_EQ(ricci::refine_around_cone(cone, {0, 6}).added_faces, 0);
  EXPECT_THROW((void)ricci::refine_around_cone(cone, {-1, 6}), ricci::InvalidInputError);
  EXPECT_THROW((void)ricci::refine_around_cone(cone, {1, 0}), ricci::InvalidInputError);
}

// Whether each vertex of `mesh` is fewer than `rings` edges from `cone`.
std::vector<char> within_rings(const ricci::Mesh& mesh, int cone, int rings) {
  std::vector<char> near(mesh.n_vertices(), 0);
  std::vector<int> frontier{cone};
  near[static_cast<size_t>(cone)] = 1;
  for (int ring = 1; ring < rings; ++ring) {
    std::vector<int> next;
    for (int v : frontier) {
      for (auto w : mesh.vv_range(mesh.vertex_handle(v))) {
        if (!near[static_cast<size_t>(w.idx())]) next.push_back(w.idx());
        near[static_cast<size_t>(w.idx())] = 1;
      }
    }
    frontier = std::move(next);
  }
  return near;
}

// The chart ratios (2g - 1) |ln(rho_b / rho_a)| (rho: 3D distance from the cone) of the edges off
// the cone's faces whose ends are both `near` (vertices past near's size count as near), sorted.
std::vector<double> chart_logs(const ricci::OneConeProblem& problem,
                               const std::vector<char>& near) {
  const ricci::Mesh& mesh = problem.mesh;
  const auto apex = mesh.point(mesh.vertex_handle(problem.cone));
  const auto is_near = [&](int v) {
    return static_cast<size_t>(v) >= near.size() || near[static_cast<size_t>(v)];
  };
  std::vector<double> logs;
  for (auto e : mesh.edges()) {
    const auto h = mesh.halfedge_handle(e, 0);
    const auto a = mesh.from_vertex_handle(h);
    const auto b = mesh.to_vertex_handle(h);
    if (a.idx() == problem.cone || b.idx() == problem.cone ||
        mesh.opposite_vh(h).idx() == problem.cone ||
        mesh.opposite_he_opposite_vh(h).idx() == problem.cone || !is_near(a.idx()) ||
        !is_near(b.idx())) {
      continue;
    }
    const double rho_a = (mesh.point(a) - apex).norm();
    const double rho_b = (mesh.point(b) - apex).norm();
    logs.push_back((2.0 * problem.genus - 1.0) * std::abs(std::log(rho_b / rho_a)));
  }
  std::sort(logs.begin(), logs.end());
  return logs;
}

// How many of the sorted `logs` exceed `bound`.
long above(const std::vector<double>& logs, double bound) {
  return logs.end() - std::upper_bound(logs.begin(), logs.end(), bound);
}

// The radial grading (genus 2 here, by radial_from_genus): the surface, topology, cone and
// input vertices kept, and the edges near the cone graded to the chart ratio asked for.
TEST(ConeRefinement, RadialGradingShrinksTheChartRatioNearTheCone) {
  const ricci::OneConeProblem before =
      ricci::prepare_one_cone(read_test_mesh("closed_g2/eight.off"), 5);
  ricci::ConeRefinementOptions options{1, 3};
  ricci::OneConeProblem plain = before;
  (void)ricci::refine_around_cone(plain, options);
  options.radial_from_genus = 2;
  options.radial_levels = 12;
  options.radial_rings = 4;
  options.radial_chart_log = 0.5;
  ricci::OneConeProblem graded = before;
  const ricci::ConeRefinement done = ricci::refine_around_cone(graded, options);

  EXPECT_GT(done.radial_splits, 0);
  EXPECT_EQ(done.added_faces,
            static_cast<int>(graded.mesh.n_faces()) - static_cast<int>(before.mesh.n_faces()));
  EXPECT_EQ(graded.mesh.n_faces(),
            plain.mesh.n_faces() + 2 * static_cast<size_t>(done.radial_splits));
  EXPECT_NEAR(total_area(graded.mesh), total_area(before.mesh), 1e-12 * total_area(before.mesh));
  EXPECT_EQ(ricci::surface_topology(graded.mesh).genus, 2);
  EXPECT_EQ(graded.cone, before.cone);
  EXPECT_EQ(graded.mesh.valence(graded.mesh.vertex_handle(graded.cone)),
            plain.mesh.valence(plain.mesh.vertex_handle(plain.cone)));
  // Within the graded rings: the plain refinement's edges above the bound are split until a few
  // (next to the cone's faces, where each split joins a close vertex again) remain, and the
  // largest ratio falls.
  const std::vector<char> near = within_rings(plain.mesh, plain.cone, options.radial_rings);
  const std::vector<double> plain_logs = chart_logs(plain, near);
  const std::vector<double> graded_logs = chart_logs(graded, near);
  ASSERT_FALSE(plain_logs.empty());
  ASSERT_FALSE(graded_logs.empty());
  EXPECT_GT(above(plain_logs, options.radial_chart_log), 50);
  EXPECT_LT(above(graded_logs, options.radial_chart_log),
            above(plain_logs, options.radial_chart_log) / 5);
  EXPECT_LT(graded_logs.back(), 0.5 * plain_logs.back());
  ASSERT_EQ(graded.input_vertex.size(), graded.mesh.n_vertices());
  const auto first_added =
      graded.input_vertex.begin() + static_cast<long>(before.input_vertex.size());
  EXPECT_TRUE(std::all_of(first_added, graded.input_vertex.end(), [](int v) { return v == -1; }));
  EXPECT_NEAR(graded.targets.curvature.sum(), -4 * M_PI, 1e-12);
  // Below radial_from_genus the refinement is the plain one.
  options.radial_from_genus = 3;
  ricci::OneConeProblem below = before;
  EXPECT_EQ(ricci::refine_around_cone(below, options).radial_splits, 0);
  EXPECT_EQ(below.mesh.n_faces(), plain.mesh.n_faces());
  options.radial_chart_log = 0.0;
  EXPECT_THROW((void)ricci::refine_around_cone(below, options), ricci::InvalidInputError);
}

// The refined problems flow to the cone and lay out as exactly as the plain ones
// (one_cone_atlas_test.cpp): genus 2 and the 10 pi cone of genus 3.
TEST(ConeRefinement, RefinedAtlasIsExact) {
  for (const char* path : {"closed_g2/eight.off", "closed_g3/elephant_cgal.off"}) {
    ricci::OneConeAtlasOptions options;
    options.cone_refinement.levels = 2;
    const ricci::OneConeAtlasResult r = ricci::build_one_cone_atlas(read_test_mesh(path), options);
    EXPECT_GT(r.cone_refinement.added_faces, 0) << path;
    EXPECT_LT(r.flow.max_error, 1e-9) << path;
    const int chi = 2 - 2 * r.problem.genus;
    EXPECT_NEAR(2 * M_PI - r.flow.curvature[r.problem.cone], 2 * M_PI - 2 * M_PI * chi, 1e-9)
        << path;
    EXPECT_EQ(r.atlas.layout.flipped_faces, 0) << path;
    EXPECT_EQ(r.atlas.uncovered_faces, 0) << path;
    EXPECT_LT(r.relative_transition_residual(), 1e-9) << path;
  }
}

}  // namespace
