#include "ricci/mesh/flat_flips.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "ricci/mesh/edge_statistics.h"

namespace ricci {
namespace {

double corner_angle(const Eigen::Vector3d& at, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return angle_between(a - at, b - at);
}

// The quad around an interior edge: its end points a -> b (along halfedge 0) and the vertices
// c (opposite in halfedge 0's face) and d (opposite in halfedge 1's face).
struct EdgeQuad {
  Eigen::Vector3d a, b, c, d;

  double opposite_angle_sum() const { return corner_angle(c, a, b) + corner_angle(d, b, a); }
  double flipped_opposite_angle_sum() const { return corner_angle(a, d, c) + corner_angle(b, c, d); }
  // Angle between the normals of faces (a, b, c) and (b, a, d).
  double normal_angle() const {
    return angle_between((b - a).cross(c - a), (a - b).cross(d - b));
  }
  // Distance between the lines of the two diagonals ab and cd: how far the flip moves the surface.
  double diagonal_distance() const {
    const Eigen::Vector3d n = (b - a).cross(d - c);
    const double norm = n.norm();
    return norm > 0 ? std::abs((c - a).dot(n)) / norm : 0.0;
  }
  // Whether the faces after the flip, (c, d, b) and (d, c, a), face the way the old ones do.
  bool flip_keeps_orientation() const {
    const Eigen::Vector3d n = (b - a).cross(c - a) + (a - b).cross(d - b);
    return (d - c).cross(b - c).dot(n) > 0 && (c - d).cross(a - d).dot(n) > 0;
  }
};

EdgeQuad edge_quad(const Mesh& mesh, EdgeHandle e) {
  const HalfedgeHandle h0 = mesh.halfedge_handle(e, 0), h1 = mesh.halfedge_handle(e, 1);
  auto p = [&](VertexHandle v) { return to_eigen(mesh.point(v)); };
  return {p(mesh.from_vertex_handle(h0)), p(mesh.to_vertex_handle(h0)),
          p(mesh.to_vertex_handle(mesh.next_halfedge_handle(h0))),
          p(mesh.to_vertex_handle(mesh.next_halfedge_handle(h1)))};
}

bool is_non_delaunay(const Mesh& mesh, EdgeHandle e, double margin) {
  return !mesh.is_boundary(e) && edge_quad(mesh, e).opposite_angle_sum() > M_PI + margin;
}

// Whether flipping e keeps a 2-manifold with every vertex of valence >= 3 and the surface in
// place, and makes the edge Delaunay.
bool can_flip(const Mesh& mesh, EdgeHandle e, const EdgeQuad& quad, const FlatFlipOptions& options,
              double max_deviation) {
  if (!mesh.is_flip_ok(e)) return false;
  const HalfedgeHandle h0 = mesh.halfedge_handle(e, 0);
  if (mesh.valence(mesh.from_vertex_handle(h0)) <= 3 || mesh.valence(mesh.to_vertex_handle(h0)) <= 3) return false;
  const bool flat = quad.normal_angle() <= options.max_normal_angle || quad.diagonal_distance() <= max_deviation;
  return flat && quad.flip_keeps_orientation() && quad.flipped_opposite_angle_sum() < M_PI;
}

// 1 for the vertices within `rings` rings of `center` (none when center < 0).
std::vector<char> protected_vertices(const Mesh& mesh, int center, int rings) {
  std::vector<char> inside(mesh.n_vertices(), 0);
  if (center < 0) return inside;
  std::vector<VertexHandle> front{mesh.vertex_handle(center)};
  inside[static_cast<size_t>(center)] = 1;
  for (int ring = 0; ring < rings; ++ring) {
    std::vector<VertexHandle> next;
    for (VertexHandle v : front) {
      for (VertexHandle w : mesh.vv_range(v)) {
        if (!inside[static_cast<size_t>(w.idx())]) {
          inside[static_cast<size_t>(w.idx())] = 1;
          next.push_back(w);
        }
      }
    }
    front = std::move(next);
  }
  return inside;
}

bool touches(const Mesh& mesh, EdgeHandle e, const std::vector<char>& inside) {
  const HalfedgeHandle h0 = mesh.halfedge_handle(e, 0), h1 = mesh.halfedge_handle(e, 1);
  for (HalfedgeHandle h : {h0, h1, mesh.next_halfedge_handle(h0), mesh.next_halfedge_handle(h1)}) {
    if (inside[static_cast<size_t>(mesh.to_vertex_handle(h).idx())]) return true;
  }
  return false;
}

}  // namespace

FlatFlipResult flip_flat_edges_to_delaunay(Mesh& mesh, const FlatFlipOptions& options) {
  FlatFlipResult result;
  const std::vector<char> frozen = protected_vertices(mesh, options.protected_vertex, options.protected_rings);
  std::vector<EdgeHandle> pending;
  std::vector<char> queued(mesh.n_edges(), 0);
  for (auto e : mesh.edges()) {
    if (is_non_delaunay(mesh, e, options.delaunay_margin)) {
      pending.push_back(e);
      queued[e.idx()] = 1;
    }
  }
  const double max_deviation = options.max_relative_deviation * median_edge_length(mesh);
  const double max_flips = options.max_flips_per_edge * static_cast<double>(mesh.n_edges());
  while (!pending.empty() && result.flips < max_flips) {
    const EdgeHandle e = pending.back();
    pending.pop_back();
    queued[e.idx()] = 0;
    if (!is_non_delaunay(mesh, e, options.delaunay_margin)) continue;
    const EdgeQuad quad = edge_quad(mesh, e);
    if (touches(mesh, e, frozen) || !can_flip(mesh, e, quad, options, max_deviation)) continue;
    result.max_normal_angle_flipped = std::max(result.max_normal_angle_flipped, quad.normal_angle());
    mesh.flip(e);
    ++result.flips;
    // The quad's four sides may have stopped being Delaunay.
    const HalfedgeHandle h = mesh.halfedge_handle(e, 0);
    for (HalfedgeHandle side : {mesh.next_halfedge_handle(h), mesh.prev_halfedge_handle(h),
                                mesh.next_halfedge_handle(mesh.opposite_halfedge_handle(h)),
                                mesh.prev_halfedge_handle(mesh.opposite_halfedge_handle(h))}) {
      const EdgeHandle s = mesh.edge_handle(side);
      if (!queued[s.idx()]) {
        queued[s.idx()] = 1;
        pending.push_back(s);
      }
    }
  }
  for (auto e : mesh.edges()) result.non_delaunay_left += is_non_delaunay(mesh, e, options.delaunay_margin);
  return result;
}

}  // namespace ricci
