#include "ricci/topology/cut_graph.h"

#include <gtest/gtest.h>

#include "ricci/mesh/errors.h"
#include "ricci/mesh/io.h"
#include "ricci/mesh/primitives.h"
#include "ricci/topology/polygon_word.h"
#include "ricci/topology/slice.h"
#include "ricci/topology/test_grids.h"
#include "test_paths.h"

namespace ricci {
namespace {

/// Checks everything the cut graph promises on `mesh` rooted at `root`; returns the slice.
SlicedMesh expect_valid_cut(const Mesh& mesh, const CutGraph& cut, int genus, int boundaries) {
  EXPECT_EQ(cut.genus, genus);
  EXPECT_EQ(cut.boundary_loop_count, boundaries);
  EXPECT_EQ(static_cast<int>(cut.loops.size()), 2 * genus);
  const bool root_on_boundary = cut.boundary_loop_of_vertex[cut.root.idx()] >= 0;
  EXPECT_EQ(static_cast<int>(cut.boundary_connectors.size()),
            boundaries - (root_on_boundary ? 1 : 0));
  for (const auto& loop : cut.loops) {
    EXPECT_FALSE(loop.halfedges.empty());
    if (boundaries == 0) {
      EXPECT_EQ(mesh.from_vertex_handle(loop.halfedges.front()), cut.root);
      EXPECT_EQ(mesh.to_vertex_handle(loop.halfedges.back()), cut.root);
      for (size_t k = 0; k + 1 < loop.halfedges.size(); ++k) {
        EXPECT_EQ(mesh.to_vertex_handle(loop.halfedges[k]),
                  mesh.from_vertex_handle(loop.halfedges[k + 1]));
      }
    }
  }
  SlicedMesh sliced = slice_along(mesh, cut.is_cut_edge);
  EXPECT_NO_THROW(check_disk(sliced));
  EXPECT_EQ(sliced.euler_characteristic, 1);
  EXPECT_EQ(sliced.boundary_loop_count, 1);
  EXPECT_EQ(sliced.mesh.n_faces(), mesh.n_faces());
  // Every cut edge becomes two boundary edges; every original boundary edge stays one.
  int cut_edges = 0, boundary_edges = 0, sliced_boundary = 0;
  for (auto e : mesh.edges()) {
    cut_edges += cut.is_cut_edge[e.idx()];
    boundary_edges += mesh.is_boundary(e);
  }
  for (auto e : sliced.mesh.edges()) sliced_boundary += sliced.mesh.is_boundary(e);
  EXPECT_EQ(sliced_boundary, 2 * cut_edges + boundary_edges);
  EXPECT_EQ(static_cast<int>(sliced.cut_sides.size()), cut_edges);
  // Corner copies are consistent: a sliced vertex is a copy of the original corner vertex.
  for (auto h : mesh.halfedges()) {
    if (mesh.is_boundary(h)) continue;
    const int copy = sliced.corner_vertex[h.idx()];
    EXPECT_EQ(sliced.to_original_vertex[copy], mesh.to_vertex_handle(h).idx());
    const HalfedgeHandle sh(sliced.from_original_halfedge[h.idx()]);
    EXPECT_EQ(sliced.mesh.to_vertex_handle(sh).idx(), copy);
    EXPECT_EQ(sliced.to_original_halfedge[sh.idx()], h.idx());
  }
  return sliced;
}

/// The canonical basis has 2g generators and its relator, expanded in the loops, is the
/// polygon's loop word again (a free-group identity, checked after cyclic reduction).
void expect_canonical_basis_of(const FundamentalPolygon& polygon, int genus) {
  const CanonicalBasis basis = canonical_basis(polygon.word);
  ASSERT_EQ(static_cast<int>(basis.generators.size()), 2 * genus);
  LoopWord relator, loop_word;
  auto append_inverse = [&](const LoopWord& w) {
    for (auto it = w.rbegin(); it != w.rend(); ++it) {
      PolygonLetter l = *it;
      l.sign = -l.sign;
      relator.push_back(l);
    }
  };
  for (int i = 0; i < genus; ++i) {
    const LoopWord& a = basis.generators[2 * i];
    const LoopWord& b = basis.generators[2 * i + 1];
    relator.insert(relator.end(), a.begin(), a.end());
    relator.insert(relator.end(), b.begin(), b.end());
    append_inverse(a);
    append_inverse(b);
  }
  for (const auto& l : polygon.word) {
    if (l.kind == PolygonLetter::Kind::loop) loop_word.push_back(l);
  }
  EXPECT_TRUE(same_cyclic_word(cyclically_reduced(relator), cyclically_reduced(loop_word)));
}

TEST(CutGraph, CanonicalBasisOfHandMadeWords) {
  auto letter = [](int index, int sign) {
    PolygonLetter l;
    l.index = index;
    l.sign = sign;
    return l;
  };
  // Already canonical: the basis is the loops themselves.
  const LoopWord torus{letter(0, 1), letter(1, 1), letter(0, -1), letter(1, -1)};
  const CanonicalBasis b1 = canonical_basis(torus);
  ASSERT_EQ(b1.generators.size(), 2u);
  EXPECT_EQ(b1.generators[0], LoopWord{letter(0, 1)});
  EXPECT_EQ(b1.generators[1], LoopWord{letter(1, 1)});
  // The genus-2 word tree-cotree gives on eight.off rooted at vertex 0 (valence-modified):
  // c a^-1 b^-1 a d c^-1 b d^-1.
  FundamentalPolygon p;
  p.word = {letter(2, 1), letter(0, -1), letter(1, -1), letter(0, 1),
            letter(3, 1), letter(2, -1), letter(1, 1),  letter(3, -1)};
  EXPECT_FALSE(is_canonical_word(p.word));
  expect_canonical_basis_of(p, 2);
  // A letter linked with no other is not a one-vertex surface word.
  const LoopWord unlinked{letter(0, 1), letter(0, -1), letter(1, 1), letter(1, -1)};
  EXPECT_THROW((void)canonical_basis(unlinked), TopologyError);
}

TEST(CutGraph, FlatTorusGridGivesTwoLoopsAndACanonicalSquare) {
  const Mesh mesh = make_flat_torus_grid(12, 9, 3.0, 2.0);
  const Eigen::VectorXd lengths = flat_torus_edge_lengths(mesh, 12, 9, 3.0, 2.0);
  const CutGraph cut = compute_cut_graph(mesh, VertexHandle(40), lengths);
  const SlicedMesh sliced = expect_valid_cut(mesh, cut, 1, 0);
  const FundamentalPolygon polygon = fundamental_polygon_word(mesh, cut, sliced);
  ASSERT_EQ(polygon.word.size(), 4u);
  EXPECT_TRUE(polygon.canonical);
  // Greedy shortest loops on a flat 3 x 2 torus are the two straight period loops.
  std::vector<double> loop_lengths{cut.loops[0].length, cut.loops[1].length};
  std::sort(loop_lengths.begin(), loop_lengths.end());
  EXPECT_NEAR(loop_lengths[0], 2.0, 1e-12);
  EXPECT_NEAR(loop_lengths[1], 3.0, 1e-12);
}

TEST(CutGraph, ClosedGenusZeroHasNoLoopsAndDoesNotSliceToADisk) {
  Mesh tetra;
  VertexHandle v[4];
  for (int i = 0; i < 4; ++i) {
    v[i] = tetra.add_vertex(Mesh::Point(i == 1, i == 2, i == 3));
  }
  tetra.add_face(v[0], v[2], v[1]);
  tetra.add_face(v[0], v[1], v[3]);
  tetra.add_face(v[0], v[3], v[2]);
  tetra.add_face(v[1], v[2], v[3]);
  const CutGraph cut = compute_cut_graph(tetra, v[0]);
  EXPECT_EQ(cut.genus, 0);
  EXPECT_TRUE(cut.loops.empty());
  const SlicedMesh sliced = slice_along(tetra, cut.is_cut_edge);
  EXPECT_THROW(check_disk(sliced), TopologyError);
}

TEST(CutGraph, PlanarGridIsAlreadyADisk) {
  const Mesh grid = test::planar_grid(6, 5, 3.0, 2.0);
  // Rooted on the boundary nothing needs cutting; rooted inside, one path reaches the boundary.
  const CutGraph on_boundary = compute_cut_graph(grid, VertexHandle(3));
  expect_valid_cut(grid, on_boundary, 0, 1);
  for (char c : on_boundary.is_cut_edge) EXPECT_EQ(c, 0);
  const CutGraph inside = compute_cut_graph(grid, VertexHandle(17));
  expect_valid_cut(grid, inside, 0, 1);
  ASSERT_EQ(inside.boundary_connectors.size(), 1u);
  EXPECT_EQ(grid.from_vertex_handle(inside.boundary_connectors[0].halfedges.front()),
            VertexHandle(17));
}

TEST(CutGraph, BadInputThrows) {
  const Mesh mesh = make_flat_torus_grid(4, 4, 1.0, 1.0);
  EXPECT_THROW((void)compute_cut_graph(mesh, VertexHandle(99)), InvalidInputError);
  EXPECT_THROW((void)compute_cut_graph(mesh, VertexHandle(0), Eigen::VectorXd::Ones(3)),
               InvalidInputError);
  Eigen::VectorXd lengths = Eigen::VectorXd::Ones(mesh.n_edges());
  lengths[5] = -1.0;
  EXPECT_THROW((void)compute_cut_graph(mesh, VertexHandle(0), lengths), InvalidInputError);
  std::vector<char> flags(mesh.n_edges() + 1, 0);
  EXPECT_THROW((void)slice_along(mesh, flags), InvalidInputError);
}

struct ModelCase {
  const char* path;
  int genus;
  int boundaries;
};

class CutGraphOnModels : public ::testing::TestWithParam<ModelCase> {};

TEST_P(CutGraphOnModels, SlicesIntoADiskWithTwoGLoops) {
  const ModelCase c = GetParam();
  const Mesh mesh = read_mesh(msp_test::test_mesh(c.path));
  // Two roots: vertex 0 and one in the middle of the index range (often elsewhere on the shape).
  for (int root : {0, static_cast<int>(mesh.n_vertices() / 2)}) {
    SCOPED_TRACE(std::string(c.path) + " root " + std::to_string(root));
    const CutGraph cut = compute_cut_graph(mesh, VertexHandle(root));
    const SlicedMesh sliced = expect_valid_cut(mesh, cut, c.genus, c.boundaries);
    const FundamentalPolygon polygon = fundamental_polygon_word(mesh, cut, sliced);
    int loop_letters = 0;
    for (const auto& l : polygon.word) loop_letters += l.kind == PolygonLetter::Kind::loop;
    EXPECT_EQ(loop_letters, 4 * c.genus);
    if (c.genus <= 1) {
      EXPECT_TRUE(polygon.canonical);
    }
    expect_canonical_basis_of(polygon, c.genus);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Models, CutGraphOnModels,
    ::testing::Values(
        ModelCase{"closed_g1/kitten_nf20k.off.gz", 1, 0},
        ModelCase{"closed_g1/knot1.off.gz", 1, 0}, ModelCase{"closed_g2/eight.off", 2, 0},
        ModelCase{"closed_g2/joint.off", 2, 0}, ModelCase{"closed_g3/genus3.off.gz", 3, 0},
        ModelCase{"closed_g4plus/fertility.off.gz", 4, 0},
        ModelCase{"closed_g4plus/couplingdown.off", 9, 0}, ModelCase{"open/head.off", 0, 3},
        ModelCase{"open/holes.off.gz", 0, 7}, ModelCase{"open/eight_hole.off", 2, 1},
        ModelCase{"open/eight_open.off", 0, 4}, ModelCase{"open/beetle.off.gz", 0, 11}),
    [](const auto& info) {
      std::string name = info.param.path;
      for (char& ch : name) {
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
      }
      return name;
    });

TEST(CentralVertex, MinimisesTheLargestDistanceOnAStripAndAGenusSlab) {
  // A 40 x 4 strip: the largest distance is least at the middle column (x = 20).
  const Mesh strip = make_planar_grid(40, 4, 40.0, 4.0);
  const VertexHandle c = central_vertex(strip);
  EXPECT_NEAR(strip.point(c)[0], 20.0, 1.0);
  // A chain of six tori: the centre lies halfway along the chain, not at vertex 0 (its end).
  const Mesh slab = make_genus_slab(6);
  double lo = INFINITY, hi = -INFINITY;
  for (auto v : slab.vertices()) {
    lo = std::min(lo, static_cast<double>(slab.point(v)[0]));
    hi = std::max(hi, static_cast<double>(slab.point(v)[0]));
  }
  const double x = slab.point(central_vertex(slab))[0];
  EXPECT_NEAR(x, 0.5 * (lo + hi), 0.2 * (hi - lo));
  EXPECT_THROW((void)central_vertex(strip, Eigen::VectorXd::Ones(3)), InvalidInputError);
}

TEST(SpreadVertices, FarthestPointSamplesOfAStrip) {
  // A 40 x 4 strip from its middle: the two ends next (x = 0 and 40, either order), then
  // near the quarter points (graph distances on the grid: within 2.5); all distinct, and no
  // more samples than vertices.
  const Mesh strip = make_planar_grid(40, 4, 40.0, 4.0);
  const VertexHandle middle = central_vertex(strip);
  const std::vector<VertexHandle> s = spread_vertices(strip, middle, {}, 5);
  ASSERT_EQ(s.size(), 5u);
  EXPECT_EQ(s[0], middle);
  EXPECT_NEAR(std::abs(strip.point(s[1])[0] - strip.point(s[2])[0]), 40.0, 1e-12);
  for (int k : {3, 4}) {
    const double x = strip.point(s[static_cast<size_t>(k)])[0];
    EXPECT_NEAR(std::min(std::abs(x - 10.0), std::abs(x - 30.0)), 0.0, 2.5) << k;
  }
  for (size_t i = 0; i < s.size(); ++i) {
    for (size_t j = i + 1; j < s.size(); ++j) EXPECT_NE(s[i], s[j]);
  }
  const Mesh grid = make_planar_grid(1, 1, 1.0, 1.0);
  EXPECT_EQ(spread_vertices(grid, VertexHandle(0), {}, 10).size(), grid.n_vertices());
  EXPECT_THROW((void)spread_vertices(strip, VertexHandle(-1)), InvalidInputError);
}

}  // namespace
}  // namespace ricci
