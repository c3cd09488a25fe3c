#include "ricci/singularity/valence.h"

#include <cmath>
#include <queue>
#include <string>

#include "ricci/mesh/errors.h"

namespace ricci {
namespace {

double edge_length(const Mesh& mesh, EdgeHandle e) {
  return (mesh.point(mesh.to_vertex_handle(mesh.halfedge_handle(e, 0))) -
          mesh.point(mesh.from_vertex_handle(mesh.halfedge_handle(e, 0))))
      .norm();
}

int valence(const Mesh& mesh, VertexHandle v) { return static_cast<int>(mesh.valence(v)); }

// The longest edge opposite `v` in one of its faces, skipping edges incident to `avoid`.
EdgeHandle longest_link_edge(const Mesh& mesh, VertexHandle v, VertexHandle avoid) {
  EdgeHandle best;
  double best_length = -1.0;
  for (auto h : mesh.voh_range(v)) {
    if (mesh.is_boundary(h)) continue;
    HalfedgeHandle opposite = mesh.next_halfedge_handle(h);  // the face's edge not touching v
    if (mesh.to_vertex_handle(opposite) == avoid || mesh.from_vertex_handle(opposite) == avoid) {
      continue;
    }
    EdgeHandle e = mesh.edge_handle(opposite);
    double length = edge_length(mesh, e);
    if (length > best_length) {
      best_length = length;
      best = e;
    }
  }
  return best;
}

void split_at_midpoint(Mesh& mesh, EdgeHandle e) {
  HalfedgeHandle h = mesh.halfedge_handle(e, 0);
  Mesh::Point mid = 0.5 * (mesh.point(mesh.from_vertex_handle(h)) + mesh.point(mesh.to_vertex_handle(h)));
  mesh.split_edge(e, mesh.add_vertex(mid));
}

void check_cone(const Mesh& mesh, VertexHandle cone) {
  if (!cone.is_valid() || cone.idx() >= static_cast<int>(mesh.n_vertices())) {
    throw InvalidInputError("cone vertex " + std::to_string(cone.idx()) + " is out of range (mesh has " +
                            std::to_string(mesh.n_vertices()) + " vertices)");
  }
  if (mesh.is_boundary(cone)) {
    throw InvalidInputError("cone vertex " + std::to_string(cone.idx()) +
                            " lies on the boundary; choose an interior vertex");
  }
}

}  // namespace

int required_cone_valence(double cone_curvature) {
  return static_cast<int>(std::ceil(4.0 - 2.0 * cone_curvature / M_PI - 1e-9));
}

std::vector<VertexHandle> ring_neighbourhood(const Mesh& mesh, VertexHandle center, int rings) {
  std::vector<int> depth(mesh.n_vertices(), -1);
  std::vector<VertexHandle> found;
  std::queue<VertexHandle> queue;
  depth[center.idx()] = 0;
  queue.push(center);
  while (!queue.empty()) {
    VertexHandle v = queue.front();
    queue.pop();
    if (depth[v.idx()] == rings) continue;
    for (VertexHandle w : mesh.vv_range(v)) {
      if (depth[w.idx()] >= 0) continue;
      depth[w.idx()] = depth[v.idx()] + 1;
      found.push_back(w);
      queue.push(w);
    }
  }
  return found;
}

ValenceResult modify_valence(const Mesh& input, VertexHandle cone, const ValenceOptions& options) {
  check_cone(input, cone);
  ValenceResult result;
  result.mesh = input;
  result.cone = cone;
  Mesh& mesh = result.mesh;
  result.cone_valence_before = valence(mesh, cone);
  result.required_cone_valence = required_cone_valence(options.cone_curvature) + options.cone_valence_margin;

  while (valence(mesh, cone) < result.required_cone_valence && result.splits < options.max_splits) {
    split_at_midpoint(mesh, longest_link_edge(mesh, cone, VertexHandle()));
    ++result.splits;
  }

  // The ring rule applies to the original vertices near the cone; split vertices are flat by
  // construction and asking valence 6 of them too would never terminate (each split makes one).
  const int original_vertices = static_cast<int>(input.n_vertices());
  for (VertexHandle q : ring_neighbourhood(mesh, cone, options.rings)) {
    if (q.idx() >= original_vertices || mesh.is_boundary(q)) continue;
    while (valence(mesh, q) < options.ring_valence && result.splits < options.max_splits) {
      EdgeHandle e = longest_link_edge(mesh, q, cone);
      if (!e.is_valid()) break;
      split_at_midpoint(mesh, e);
      ++result.splits;
    }
  }
  for (VertexHandle q : ring_neighbourhood(mesh, cone, options.rings)) {
    if (q.idx() < original_vertices && valence(mesh, q) < options.ring_valence) ++result.ring_vertices_below;
  }
  result.cone_valence_after = valence(mesh, cone);
  if (result.cone_valence_after < result.required_cone_valence) {
    throw SolverError("valence modification stopped after " + std::to_string(result.splits) +
                      " splits with cone valence " + std::to_string(result.cone_valence_after));
  }
  return result;
}

}  // namespace ricci
