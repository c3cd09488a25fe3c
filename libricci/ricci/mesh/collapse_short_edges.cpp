#include "ricci/mesh/collapse_short_edges.h"

#include <algorithm>

#include "ricci/mesh/edge_statistics.h"

namespace ricci {
namespace {

// The halfedge along e whose collapse removes its start vertex and keeps `keep` (if e has it),
// or an invalid handle when neither direction may be collapsed.
HalfedgeHandle collapsible_halfedge(Mesh& mesh, EdgeHandle e, VertexHandle keep) {
  for (int side = 0; side < 2; ++side) {
    const HalfedgeHandle h = mesh.halfedge_handle(e, side);
    if (mesh.from_vertex_handle(h) == keep) continue;
    // Keep the boundary where it is: a boundary vertex only merges into another one.
    if (mesh.is_boundary(mesh.from_vertex_handle(h)) && !mesh.is_boundary(mesh.to_vertex_handle(h))) continue;
    if (mesh.is_collapse_ok(h)) return h;
  }
  return HalfedgeHandle();
}

}  // namespace

ShortEdgeCollapse collapse_short_edges(const Mesh& input, const ShortEdgeOptions& options) {
  ShortEdgeCollapse result;
  result.mesh = input;
  Mesh& mesh = result.mesh;
  const double threshold = options.relative_length * median_edge_length(mesh);
  OpenMesh::VPropHandleT<int> original;
  mesh.add_property(original);
  for (auto v : mesh.vertices()) mesh.property(original, v) = v.idx();
  const VertexHandle keep = options.keep_vertex >= 0 ? mesh.vertex_handle(options.keep_vertex) : VertexHandle();
  bool collapsed = true;
  while (collapsed) {
    collapsed = false;
    for (auto e : mesh.edges()) {
      if (mesh.status(e).deleted() || !(mesh.calc_edge_length(e) < threshold)) continue;
      const HalfedgeHandle h = collapsible_halfedge(mesh, e, keep);
      if (!h.is_valid()) continue;
      mesh.collapse(h);
      ++result.collapses;
      collapsed = true;
    }
  }
  for (auto e : mesh.edges()) {
    if (!mesh.status(e).deleted() && mesh.calc_edge_length(e) < threshold) ++result.short_edges_left;
  }
  mesh.garbage_collection();
  result.input_vertex.resize(mesh.n_vertices());
  for (auto v : mesh.vertices()) result.input_vertex[static_cast<size_t>(v.idx())] = mesh.property(original, v);
  mesh.remove_property(original);
  return result;
}

}  // namespace ricci
