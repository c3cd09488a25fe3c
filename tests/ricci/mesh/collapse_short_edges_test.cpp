#include <gtest/gtest.h>

#include <algorithm>

#include "ricci/mesh/collapse_short_edges.h"
#include "ricci/mesh/primitives.h"
#include "ricci/test_meshes.h"

namespace {

// A torus with one vertex moved to within 1e-7 of a neighbour, as marching cubes leaves them.
ricci::Mesh torus_with_close_pair(int& moved, int& neighbour) {
  ricci::Mesh mesh = ricci::testing::torus(24, 16);
  const ricci::VertexHandle v = mesh.vertex_handle(37);
  const ricci::VertexHandle w = *mesh.vv_range(v).begin();
  mesh.point(v) = mesh.point(w) + OpenMesh::Vec3d(1e-7, 0, 0);
  moved = v.idx();
  neighbour = w.idx();
  return mesh;
}

TEST(CollapseShortEdges, MergesCloseVerticesAndKeepsTheTopology) {
  int moved = 0, neighbour = 0;
  const ricci::Mesh mesh = torus_with_close_pair(moved, neighbour);
  const ricci::ShortEdgeCollapse r = ricci::collapse_short_edges(mesh);
  EXPECT_EQ(r.collapses, 1);
  EXPECT_EQ(r.short_edges_left, 0);
  EXPECT_EQ(r.mesh.n_vertices(), mesh.n_vertices() - 1);
  EXPECT_EQ(r.mesh.n_faces(), mesh.n_faces() - 2);
  const ricci::SurfaceTopology before = ricci::surface_topology(mesh), after = ricci::surface_topology(r.mesh);
  EXPECT_EQ(after.genus, before.genus);
  EXPECT_EQ(after.boundary_loops, 0);
  // Every surviving vertex is an input vertex at its input position; one of the pair is gone.
  ASSERT_EQ(r.input_vertex.size(), r.mesh.n_vertices());
  int pair_left = 0;
  for (auto v : r.mesh.vertices()) {
    const int input = r.input_vertex[static_cast<size_t>(v.idx())];
    EXPECT_EQ(r.mesh.point(v), mesh.point(mesh.vertex_handle(input)));
    pair_left += input == moved || input == neighbour;
  }
  EXPECT_EQ(pair_left, 1);
}

TEST(CollapseShortEdges, KeepsTheVertexAskedFor) {
  int moved = 0, neighbour = 0;
  const ricci::Mesh mesh = torus_with_close_pair(moved, neighbour);
  for (int keep : {moved, neighbour}) {
    ricci::ShortEdgeOptions options;
    options.keep_vertex = keep;
    const ricci::ShortEdgeCollapse r = ricci::collapse_short_edges(mesh, options);
    EXPECT_NE(std::find(r.input_vertex.begin(), r.input_vertex.end(), keep), r.input_vertex.end());
  }
}

TEST(CollapseShortEdges, RegularMeshIsUnchanged) {
  const ricci::Mesh mesh = ricci::testing::torus(24, 16);
  const ricci::ShortEdgeCollapse r = ricci::collapse_short_edges(mesh);
  EXPECT_EQ(r.collapses, 0);
  EXPECT_EQ(r.mesh.n_vertices(), mesh.n_vertices());
  for (size_t i = 0; i < r.input_vertex.size(); ++i) EXPECT_EQ(r.input_vertex[i], static_cast<int>(i));
}

}  // namespace
