#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "ricci/mesh/io.h"
#include "ricci/singularity/choose.h"
#include "test_paths.h"

namespace {

ricci::Mesh read_test_mesh(const std::string& relative) {
  return ricci::read_mesh(msp_test::test_mesh(relative));
}

// The paper's brute force: one full flow per vertex.
double brute_force_best(const ricci::Mesh& mesh, int& best_vertex) {
  double best = std::numeric_limits<double>::infinity();
  for (auto v : mesh.vertices()) {
    double d = ricci::one_cone_area_distortion(mesh, v.idx());
    if (d < best) {
      best = d;
      best_vertex = v.idx();
    }
  }
  return best;
}

// `fewer_flows`: how many times fewer flows than the brute force the choice must run (on a few
// hundred vertices it verifies V / 20 candidates plus the descents, so about 4-10x).
void expect_close_to_brute_force(const std::string& model, int fewer_flows = 4) {
  ricci::Mesh mesh = read_test_mesh(model);
  auto choice = ricci::choose_singularity(mesh);
  int brute_vertex = -1;
  double brute = brute_force_best(mesh, brute_vertex);
  ASSERT_TRUE(std::isfinite(brute)) << model;
  EXPECT_LE(choice.area_distortion, 1.02 * brute)
      << model << ": chose " << choice.vertex << ", brute force " << brute_vertex;
  EXPECT_LT(choice.flows_run * fewer_flows, static_cast<int>(mesh.n_vertices())) << model;
  std::cout << model << ": chose vertex " << choice.vertex << " (distortion " << choice.area_distortion
            << ", " << choice.flows_run << " flows); brute force vertex " << brute_vertex << " ("
            << brute << ", " << mesh.n_vertices() << " flows)\n";
}

TEST(ChooseSingularity, MatchesBruteForceOnGenusTwo) { expect_close_to_brute_force("closed_g2/eight_cgal.off"); }

// A CAD mesh with slivers, where the linear model ranks the optimum 76th of 221 (multi-start
// descent finds it), and a quad-derived mesh whose optimum ranks 9th.
TEST(ChooseSingularity, MatchesBruteForceOnCadGenusTwo) {
  expect_close_to_brute_force("closed_g2/joint.off");
  expect_close_to_brute_force("closed_g2/double-torus-example_quad.off");
}

TEST(ChooseSingularity, MatchesBruteForceOnGenusZero) {
  expect_close_to_brute_force("closed_g0/knight_decimated.off");
}

TEST(ChooseSingularity, GenusOneAndOpenSurfacesNeedNoVertex) {
  auto choice = ricci::choose_singularity(read_test_mesh("closed_g1/knot1.off.gz"));
  EXPECT_EQ(choice.vertex, -1);
  EXPECT_EQ(choice.flows_run, 1);
  EXPECT_TRUE(std::isfinite(choice.area_distortion));
}

TEST(ChooseSingularity, LinearRankingCoversEveryInteriorVertexSorted) {
  auto mesh = read_test_mesh("closed_g2/eight.off");
  auto ranked = ricci::rank_singularities(mesh);
  EXPECT_EQ(ranked.size(), mesh.n_vertices());
  EXPECT_TRUE(std::is_sorted(ranked.begin(), ranked.end(), [](const auto& a, const auto& b) {
    return a.area_distortion < b.area_distortion;
  }));
  for (const auto& s : ranked) EXPECT_TRUE(std::isfinite(s.area_distortion));
}

}  // namespace
