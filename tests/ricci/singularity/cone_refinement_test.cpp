// refine_around_cone: denser sampling around the single cone, the surface, topology and cone
// kept, the flow and the atlas as exact as without it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

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
