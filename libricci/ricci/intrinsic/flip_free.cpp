#include "ricci/intrinsic/flip_free.h"

#include <algorithm>
#include <set>
#include <string>
#include <utility>

#include "ricci/mesh/errors.h"

namespace ricci {

std::vector<int> removed_edges(const Mesh& mesh, const IntrinsicTriangulation& tri) {
  if (tri.vertex_count != static_cast<int>(mesh.n_vertices())) {
    throw InvalidInputError("removed_edges: the triangulation has " +
                            std::to_string(tri.vertex_count) + " vertices, the mesh " +
                            std::to_string(mesh.n_vertices()));
  }
  std::set<std::pair<int, int>> kept;
  for (int e = 0; e < tri.edge_count(); ++e) {
    const int h = tri.edge_halfedge[static_cast<size_t>(e)];
    const int a = tri.tail[static_cast<size_t>(h)], b = tri.head(h);
    kept.emplace(std::min(a, b), std::max(a, b));
  }
  std::vector<int> removed;
  for (auto e : mesh.edges()) {
    const HalfedgeHandle h = mesh.halfedge_handle(e, 0);
    const int a = mesh.from_vertex_handle(h).idx(), b = mesh.to_vertex_handle(h).idx();
    if (!kept.count({std::min(a, b), std::max(a, b)})) removed.push_back(e.idx());
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
