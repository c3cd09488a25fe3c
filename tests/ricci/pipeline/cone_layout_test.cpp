// Issue 4/8: the fundamental domain of a genus-3 surface with one 10*pi cone is laid out
// exactly. The flat metric shrinks like r^4 at such a cone, so edges next to its 12 copies are
// down to 1e-17 of the domain: every face must still be positively oriented and every edge,
// the tiniest included, equal to the metric's to 1e-9 relative.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "ricci/mesh/io.h"
#include "ricci/pipeline/one_cone_atlas.h"
#include "ricci/util/cross2d.h"
#include "test_paths.h"

namespace {

struct Case {
  const char* path;  // "models/..." (bundled) or relative to tests/data/meshes
  int singular_vertex;  // -1: automatic choice
  double shortest_edge;  // an upper bound of the shortest edge / domain diameter (the premise)
};

std::string resolve(const std::string& path) {
  if (path.rfind("models/", 0) == 0) return msp_test::bundled_model(path.substr(7));
  return msp_test::test_mesh(path);
}

class TenPiConeLayout : public ::testing::TestWithParam<Case> {};

TEST_P(TenPiConeLayout, EveryFacePositiveEveryEdgeExact) {
  const Case& c = GetParam();
  ricci::OneConeAtlasOptions options;
  options.singular_vertex = c.singular_vertex;
  // The fixed-connectivity flows' metric, whose edges at the cone are the tiniest (the
  // intrinsic flow's flips keep them longer).
  options.intrinsic_first = false;
  const ricci::OneConeAtlasResult r = ricci::build_one_cone_atlas(ricci::read_mesh(resolve(c.path)), options);
  ASSERT_EQ(r.problem.kind, ricci::OneConeKind::SingleCone);
  EXPECT_NEAR(2 * M_PI - r.flow.curvature[r.problem.cone], 10 * M_PI, 1e-9) << c.path;

  const ricci::Mesh& m = r.problem.mesh;
  const ricci::Mesh& sliced = r.atlas.sliced.mesh;
  const ricci::LayoutE2Result& layout = r.atlas.layout;
  int flipped = 0, zero = 0;
  for (auto f : sliced.faces()) {
    int v[3], k = 0;
    for (auto w : sliced.fv_range(f)) v[k++] = w.idx();
    const double area =
        ricci::cross2d(layout.edge_vector(v[0], v[1]), layout.edge_vector(v[0], v[2]));
    flipped += area < 0;
    zero += area == 0;
  }
  EXPECT_EQ(flipped, 0) << c.path;
  EXPECT_EQ(zero, 0) << c.path;
  EXPECT_EQ(layout.flipped_faces, 0) << c.path;

  double worst = 0, shortest = 1e300;
  for (auto e : sliced.edges()) {
    const auto h = sliced.halfedge_handle(e, 0);
    const int a = sliced.from_vertex_handle(h).idx(), b = sliced.to_vertex_handle(h).idx();
    const auto original = m.find_halfedge(m.vertex_handle(r.atlas.sliced.to_original_vertex[a]),
                                          m.vertex_handle(r.atlas.sliced.to_original_vertex[b]));
    const double l = r.flow.lengths[m.edge_handle(original).idx()];
    worst = std::max(worst, std::abs(layout.edge_vector(a, b).norm() - l) / l);
    shortest = std::min(shortest, l);
  }
  EXPECT_LT(worst, 1e-9) << c.path;
  EXPECT_NEAR(layout.max_relative_length_error, worst, 1e-15) << c.path;
  // The premise: edges far below the rounding of double coordinates at the cone's copies.
  EXPECT_LT(shortest / r.atlas.domain_diameter, c.shortest_edge) << c.path;
  EXPECT_LT(r.relative_transition_residual(), 1e-9) << c.path;
  EXPECT_EQ(r.atlas.uncovered_faces, 0) << c.path;
}

INSTANTIATE_TEST_SUITE_P(GenusThree, TenPiConeLayout,
                         ::testing::Values(Case{"models/genus3.off", 0, 1e-9},
                                           Case{"bench/genus3_10k.obj.gz", 0, 1e-12},
                                           Case{"models/genus3.off", -1, 1e-6}));

}  // namespace
