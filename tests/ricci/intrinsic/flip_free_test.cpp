// From an intrinsic triangulation back to a surface mesh (ricci/intrinsic/flip_free.h): the
// edges flips removed are exactly those whose vertices no edge joins any more, and midpoint
// splits keep the surface, the vertex indices and the Euler characteristic.
#include <gtest/gtest.h>

#include <vector>

#include "ricci/intrinsic/flip_free.h"
#include "ricci/mesh/errors.h"
#include "ricci/mesh/primitives.h"
#include "ricci/metric/mesh_tables.h"
#include "ricci/pipeline/one_cone_atlas.h"

namespace {

TEST(RemovedEdges, NoneBeforeAFlipAndTheFlippedEdgeAfter) {
  const ricci::Mesh mesh = ricci::make_genus_slab(4);
  ricci::IntrinsicTriangulation tri =
      ricci::make_intrinsic_triangulation(mesh, ricci::mesh_edge_lengths(mesh));
  EXPECT_TRUE(ricci::removed_edges(mesh, tri).empty());
  int flipped = -1;
  for (int e = 0; e < tri.edge_count() && flipped < 0; ++e) {
    ricci::IntrinsicTriangulation trial = tri;
    if (!ricci::is_flippable(trial, e)) continue;
    ricci::flip_edge(trial, e);
    // A flip whose new diagonal already is an edge makes a double edge: not wanted here.
    if (!ricci::is_simplicial(trial)) continue;
    tri = trial;
    flipped = e;
  }
  ASSERT_GE(flipped, 0);
  EXPECT_EQ(ricci::removed_edges(mesh, tri), std::vector<int>{flipped});
  ricci::flip_edge(tri, flipped);  // the same diagonal back
  EXPECT_TRUE(ricci::removed_edges(mesh, tri).empty());
}

TEST(RemovedEdges, RefusesAnotherVertexCount) {
  const ricci::Mesh mesh = ricci::make_genus_slab(4);
  const ricci::Mesh other = ricci::make_genus_slab(4, 2);
  const ricci::IntrinsicTriangulation tri =
      ricci::make_intrinsic_triangulation(other, ricci::mesh_edge_lengths(other));
  EXPECT_THROW((void)ricci::removed_edges(mesh, tri), ricci::InvalidInputError);
}

TEST(SplitEdgesAtMidpoints, KeepsTheSurfaceAndTheEulerCharacteristic) {
  const ricci::Mesh mesh = ricci::make_genus_slab(4);
  ricci::Mesh split = mesh;
  const std::vector<int> edges{0, 5, 17};
  EXPECT_EQ(ricci::split_edges_at_midpoints(split, edges), 3);
  ASSERT_EQ(split.n_vertices(), mesh.n_vertices() + 3);
  EXPECT_EQ(split.n_faces(), mesh.n_faces() + 6);
  EXPECT_EQ(split.n_edges(), mesh.n_edges() + 9);
  for (auto v : mesh.vertices()) {
    EXPECT_EQ(split.point(split.vertex_handle(static_cast<unsigned>(v.idx()))), mesh.point(v));
  }
  for (size_t k = 0; k < edges.size(); ++k) {
    const auto h = mesh.halfedge_handle(mesh.edge_handle(static_cast<unsigned>(edges[k])), 0);
    const ricci::Mesh::Point mid =
        0.5 * (mesh.point(mesh.from_vertex_handle(h)) + mesh.point(mesh.to_vertex_handle(h)));
    const auto added = split.vertex_handle(static_cast<unsigned>(mesh.n_vertices() + k));
    EXPECT_LT((split.point(added) - mid).norm(), 1e-15);
    EXPECT_EQ(split.valence(added), 4u);
  }
  EXPECT_EQ(ricci::surface_topology(split).genus, 4);
  EXPECT_THROW((void)ricci::split_edges_at_midpoints(split, {-1}), ricci::InvalidInputError);
}

// The intrinsic route reports how many of its mesh's edges the final triangulation dropped.
TEST(RemovedEdges, ReportedByTheIntrinsicAtlas) {
  ricci::OneConeAtlasOptions options;
  options.singular_vertex = 0;
  options.route = ricci::FlowRoute::intrinsic_delaunay;
  const ricci::Mesh slab = ricci::make_genus_slab(4, 2, 4);
  const ricci::OneConeAtlasResult r = ricci::build_one_cone_atlas(slab, options);
  ASSERT_TRUE(r.intrinsic);
  EXPECT_GT(r.removed_edges, 0);  // a cone of -12 pi at a slab's corner needs flips
  EXPECT_LE(r.removed_edges, r.intrinsic_flips);
  // The count (made while the flow's input mesh waits as arrays) is the number of that mesh's
  // edges whose ends no edge of the flipped mesh joins.
  ricci::OneConeProblem input = ricci::prepare_one_cone(slab, 0, options.valence);
  (void)ricci::refine_around_cone(input, options.cone_refinement);
  ASSERT_EQ(input.mesh.n_vertices(), r.problem.mesh.n_vertices());
  int removed = 0;
  for (auto e : input.mesh.edges()) {
    const auto h = input.mesh.halfedge_handle(e, 0);
    const auto a = r.problem.mesh.vertex_handle(input.mesh.from_vertex_handle(h).idx());
    const auto b = r.problem.mesh.vertex_handle(input.mesh.to_vertex_handle(h).idx());
    if (!r.problem.mesh.find_halfedge(a, b).is_valid()) ++removed;
  }
  EXPECT_EQ(r.removed_edges, removed);
}

}  // namespace
