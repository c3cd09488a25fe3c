// Next to the one cone of a genus-8 surface (2 pi (2g - 1) = 30 pi) the flat metric shrinks
// faces to ~1e-13 of the central chart's coordinates, whose rounding flips or collapses them.
// Every domain face must still get a neighbourhood chart that holds its neighbourhood as one
// piece with the metric's edge lengths and counter-clockwise (the atlas lays such faces out in
// a frame of their own).
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>

#include "ricci/atlas/chart_develop.h"
#include "ricci/mesh/primitives.h"
#include "ricci/metric/curvature.h"
#include "ricci/pipeline/one_cone_atlas.h"
#include "ricci/test_meshes.h"
#include "ricci/util/cross2d.h"

namespace {

// Whether `chart` places face `face` with the metric's edge lengths (relative `tolerance`) and
// counter-clockwise.
bool placed_faithfully(const ricci::Mesh& mesh, const Eigen::VectorXd& lengths,
                       const ricci::AffineAtlas& atlas, int chart, int face, double tolerance) {
  const Eigen::Matrix<double, 3, 2> p = atlas.face_positions(chart, face);
  const auto hs = ricci::face_halfedges(mesh, ricci::FaceHandle(face));
  for (int k = 0; k < 3; ++k) {
    const double l = lengths[mesh.edge_handle(hs[k]).idx()];
    if (!(std::abs((p.row(k) - p.row((k + 2) % 3)).norm() - l) <= tolerance * l)) return false;
  }
  return ricci::cross2d((p.row(1) - p.row(0)).transpose(), (p.row(2) - p.row(0)).transpose()) > 0.0;
}

TEST(LargeConeCharts, EveryGenus8FaceHasAFaithfulNeighbourhoodChart) {
  const ricci::OneConeAtlasResult result = ricci::testing::genus8_fit_atlas();
  const ricci::Mesh& mesh = result.problem.mesh;
  const ricci::AffineAtlas& atlas = result.atlas;
  const Eigen::VectorXd& lengths = result.flow.lengths;
  ASSERT_TRUE(atlas.root_is_cone);
  EXPECT_NEAR(atlas.root_curvature, 2.0 * M_PI * (2.0 - 2.0 * 8), 1e-6);
  EXPECT_EQ(atlas.uncovered_faces, 0);
  int broken_in_central = 0;
  for (auto f : mesh.faces()) {
    if (!atlas.in_domain[f.idx()]) continue;
    if (!placed_faithfully(mesh, lengths, atlas, 0, f.idx(), 1e-6)) ++broken_in_central;
    const int c = atlas.neighbourhood_chart[f.idx()];
    ASSERT_GE(c, 0) << "face " << f.idx();
    const auto hood = ricci::detail::face_neighbourhood(mesh, f.idx(), atlas.in_domain);
    EXPECT_TRUE(ricci::detail::holds_as_one_piece(mesh, atlas.charts[c], hood));
    for (int g : hood) {
      EXPECT_TRUE(placed_faithfully(mesh, lengths, atlas, c, g, 1e-6))
          << "face " << g << " in the chart of face " << f.idx();
    }
  }
  // The premise: the central chart alone cannot hold them.
  EXPECT_GT(broken_in_central, 0);
}

// The one-cone atlas at genus 8 and 10 (the automatic cone, the intrinsic route), by the closed
// forms: the cone carries the whole curvature 2 pi chi (cone angle 2 pi (2g - 1): 30 pi, 38 pi),
// every other vertex's angles sum to 2 pi, the transitions are rigid motions, and no face of
// the central chart turns over.
class LargeConeAtlas : public ::testing::TestWithParam<int> {};

TEST_P(LargeConeAtlas, HasOneConeAndRigidTransitions) {
  const int genus = GetParam();
  const ricci::OneConeAtlasResult result =
      genus == 8 ? ricci::testing::genus8_fit_atlas()
                 : ricci::testing::generated_fit_atlas(genus, 3000);
  ASSERT_TRUE(result.intrinsic);
  const ricci::Mesh& mesh = result.problem.mesh;
  EXPECT_EQ(ricci::surface_topology(mesh).genus, genus);
  const Eigen::VectorXd K =
      ricci::vertex_curvature(mesh, result.flow.lengths, ricci::Geometry::euclidean);
  const double chi = 2.0 - 2.0 * genus;
  EXPECT_NEAR(K.sum(), 2.0 * M_PI * chi, 1e-9);
  EXPECT_NEAR(K[result.problem.cone], 2.0 * M_PI * chi, 1e-9);
  Eigen::VectorXd flat = K;
  flat[result.problem.cone] = 0.0;
  EXPECT_LT(flat.cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT(std::abs(ricci::gauss_bonnet_residual(mesh, result.flow.lengths,
                                                  ricci::Geometry::euclidean)),
            1e-9);
  EXPECT_EQ(result.atlas.layout.flipped_faces, 0);
  EXPECT_EQ(result.atlas.uncovered_faces, 0);
  EXPECT_LT(result.relative_transition_residual(), 1e-9);
  // rho(relator) is the holonomy around the cone, a rotation by 2 pi (2g - 1): the identity.
  // The side pairings of the cut arcs next to the cone are fitted on the layout's double-double
  // offsets, or, for arcs below 1e-16 of the chart (edges reach 1e-31 of it at genus 10 here,
  // below the double-double positions), with the rotation from the layout's developed
  // directions: measured 9.5e-14 (genus 8) and 1.1e-10 (genus 10) of the diameter; 2.4e-10 and
  // 1.7e-2 with the offsets alone.
  EXPECT_LT(result.atlas.relator_holonomy_angle, 1e-9);
  EXPECT_LT(result.atlas.relator_holonomy_translation / result.atlas.domain_diameter, 1e-9);
}

INSTANTIATE_TEST_SUITE_P(Genus, LargeConeAtlas, ::testing::Values(8, 10));

}  // namespace
