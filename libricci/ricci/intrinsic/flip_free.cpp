#include "ricci/intrinsic/flip_free.h"

#include <algorithm>
#include <cstdint>
#include <string>

#include "ricci/mesh/errors.h"
#include "ricci/util/edge_key.h"

namespace ricci {

std::vector<std::uint64_t> sorted_edge_keys(const IntrinsicTriangulation& tri) {
  std::vector<std::uint64_t> keys;
  keys.reserve(static_cast<size_t>(tri.edge_count()));
  for (int e = 0; e < tri.edge_count(); ++e) {
    const int h = tri.edge_halfedge[static_cast<size_t>(e)];
    keys.push_back(undirected_edge_key(tri.tail[static_cast<size_t>(h)], tri.head(h)));
  }
  std::sort(keys.begin(), keys.end());
  return keys;
}

std::vector<int> removed_edges(const Mesh& mesh, const IntrinsicTriangulation& tri) {
  if (tri.vertex_count != static_cast<int>(mesh.n_vertices())) {
    throw InvalidInputError("removed_edges: the triangulation has " +
                            std::to_string(tri.vertex_count) + " vertices, the mesh " +
                            std::to_string(mesh.n_vertices()));
  }
  const std::vector<std::uint64_t> kept = sorted_edge_keys(tri);
  std::vector<int> removed;
  for (auto e : mesh.edges()) {
    const HalfedgeHandle h = mesh.halfedge_handle(e, 0);
    const std::uint64_t k =
        undirected_edge_key(mesh.from_vertex_handle(h).idx(), mesh.to_vertex_handle(h).idx());
    if (!std::binary_search(kept.begin(), kept.end(), k)) removed.push_back(e.idx());
  }
  return removed;
}

int split_edges_at_midpoints(Mesh& mesh, const std::vector<int>& edges) {
  const auto count = static_cast<int>(mesh.n_edges());
  for (int e : edges) {
    if (e < 0 || e >= count) {
      throw InvalidInputError("split_edges_at_midpoints: edge " + std::to_string(e) +
                              " is out of range (the mesh has " + std::to_string(count) +
                              " edges)");
    }
  }
  // OpenMesh's split keeps the split edge's handle and appends the new ones: the listed
  // indices stay valid while splitting.
  for (int index : edges) {
    const EdgeHandle e = mesh.edge_handle(static_cast<unsigned>(index));
    const HalfedgeHandle h = mesh.halfedge_handle(e, 0);
    const Mesh::Point mid =
        0.5 * (mesh.point(mesh.from_vertex_handle(h)) + mesh.point(mesh.to_vertex_handle(h)));
    mesh.split_edge(e, mesh.add_vertex(mid));
  }
  return static_cast<int>(edges.size());
}

}  // namespace ricci
