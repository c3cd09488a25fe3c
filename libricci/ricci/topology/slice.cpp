#include "ricci/topology/slice.h"

#include <string>

#include "ricci/mesh/errors.h"
#include "ricci/topology/cut_graph.h"

namespace ricci {
namespace {

/// Gives every face corner its vertex copy: around each vertex, a new copy starts at every cut
/// or boundary edge (walking counter-clockwise); a vertex with neither keeps a single copy.
/// Returns the number of copies.
int assign_corner_copies(const Mesh& mesh, const std::vector<char>& is_cut_edge,
                         std::vector<int>& corner_vertex, std::vector<int>& copy_original) {
  corner_vertex.assign(mesh.n_halfedges(), -1);
  auto separates = [&](HalfedgeHandle h) {
    return mesh.is_boundary(mesh.opposite_halfedge_handle(h)) ||
           is_cut_edge[mesh.edge_handle(h).idx()];
  };
  for (auto v : mesh.vertices()) {
    bool has_start = false;
    for (auto s : mesh.voh_range(v)) {
      if (mesh.is_boundary(s) || !separates(s)) continue;
      has_start = true;
      const int copy = static_cast<int>(copy_original.size());
      copy_original.push_back(v.idx());
      for (auto h = s;;) {
        corner_vertex[mesh.prev_halfedge_handle(h).idx()] = copy;
        h = mesh.opposite_halfedge_handle(mesh.prev_halfedge_handle(h));
        if (h == s || mesh.is_boundary(h) || separates(h)) break;
      }
    }
    if (!has_start) {
      const int copy = static_cast<int>(copy_original.size());
      copy_original.push_back(v.idx());
      for (auto h : mesh.voh_range(v)) {
        if (!mesh.is_boundary(h)) corner_vertex[mesh.prev_halfedge_handle(h).idx()] = copy;
      }
    }
  }
  for (auto h : mesh.halfedges()) {
    if (!mesh.is_boundary(h) && corner_vertex[h.idx()] < 0) {
      throw TopologyError("slice: corner of face " + std::to_string(mesh.face_handle(h).idx()) +
                          " at vertex " + std::to_string(mesh.to_vertex_handle(h).idx()) +
                          " is in no wedge (non-manifold vertex)");
    }
  }
  return static_cast<int>(copy_original.size());
}

int count_components(const Mesh& mesh) {
  std::vector<char> seen(mesh.n_vertices(), 0);
  std::vector<VertexHandle> stack;
  int components = 0;
  for (auto v : mesh.vertices()) {
    if (seen[v.idx()]) continue;
    ++components;
    seen[v.idx()] = 1;
    stack.push_back(v);
    while (!stack.empty()) {
      const auto w = stack.back();
      stack.pop_back();
      for (auto u : mesh.vv_range(w)) {
        if (!seen[u.idx()]) {
          seen[u.idx()] = 1;
          stack.push_back(u);
        }
      }
    }
  }
  return components;
}

}  // namespace

std::array<HalfedgeHandle, 3> face_halfedges(const Mesh& mesh, FaceHandle f) {
  const auto h0 = mesh.halfedge_handle(f);
  const auto h1 = mesh.next_halfedge_handle(h0);
  return {h0, h1, mesh.next_halfedge_handle(h1)};
}

SlicedMesh slice_along(const Mesh& mesh, const std::vector<char>& is_cut_edge) {
  if (is_cut_edge.size() != mesh.n_edges()) {
    throw InvalidInputError("slice: " + std::to_string(is_cut_edge.size()) + " cut flags for " +
                            std::to_string(mesh.n_edges()) + " edges");
  }
  for (auto e : mesh.edges()) {
    if (is_cut_edge[e.idx()] && mesh.is_boundary(e)) {
      throw InvalidInputError("slice: boundary edge " + std::to_string(e.idx()) +
                              " is flagged as a cut");
    }
  }
  SlicedMesh s;
  const int copies = assign_corner_copies(mesh, is_cut_edge, s.corner_vertex, s.to_original_vertex);
  s.mesh.reserve(copies, mesh.n_edges(), mesh.n_faces());
  for (int c = 0; c < copies; ++c)
    s.mesh.add_vertex(mesh.point(VertexHandle(s.to_original_vertex[c])));

  s.from_original_halfedge.assign(mesh.n_halfedges(), -1);
  for (auto f : mesh.faces()) {
    const auto hs = face_halfedges(mesh, f);
    int c[3];
    for (int k = 0; k < 3; ++k) c[k] = s.corner_vertex[hs[k].idx()];
    const auto g = s.mesh.add_face(VertexHandle(c[2]), VertexHandle(c[0]), VertexHandle(c[1]));
    if (!g.is_valid() || g.idx() != f.idx()) {
      throw TopologyError("slice: face " + std::to_string(f.idx()) +
                          " cannot be added to the sliced mesh (non-manifold cut)");
    }
    for (auto sh : s.mesh.fh_range(g)) {
      const int to = s.mesh.to_vertex_handle(sh).idx();
      for (int k = 0; k < 3; ++k) {
        if (c[k] == to) s.from_original_halfedge[hs[k].idx()] = sh.idx();
      }
    }
  }

  s.to_original_halfedge.assign(s.mesh.n_halfedges(), -1);
  for (auto h : mesh.halfedges()) {
    const int sh = s.from_original_halfedge[h.idx()];
    if (sh < 0) continue;
    s.to_original_halfedge[sh] = h.idx();
    const auto outer = s.mesh.opposite_halfedge_handle(HalfedgeHandle(sh));
    if (s.mesh.is_boundary(outer)) {
      s.to_original_halfedge[outer.idx()] = mesh.opposite_halfedge_handle(h).idx();
    }
  }
  s.to_original_edge.assign(s.mesh.n_edges(), -1);
  for (auto e : s.mesh.edges()) {
    const int h = s.to_original_halfedge[s.mesh.halfedge_handle(e, 0).idx()];
    s.to_original_edge[e.idx()] = mesh.edge_handle(HalfedgeHandle(h)).idx();
  }
  for (auto e : mesh.edges()) {
    if (!is_cut_edge[e.idx()]) continue;
    CutEdgeSides sides;
    sides.edge = e;
    for (int k = 0; k < 2; ++k) {
      sides.side[k] = HalfedgeHandle(s.from_original_halfedge[mesh.halfedge_handle(e, k).idx()]);
    }
    s.cut_sides.push_back(sides);
  }
  s.boundary_loop_count = static_cast<int>(find_boundary_loops(s.mesh).size());
  s.euler_characteristic = euler_characteristic(s.mesh);
  s.component_count = count_components(s.mesh);
  return s;
}

void check_disk(const SlicedMesh& sliced, const char* what) {
  if (sliced.component_count != 1 || sliced.boundary_loop_count != 1 ||
      sliced.euler_characteristic != 1) {
    throw TopologyError(std::string(what) + ": sliced mesh is not a disk (" +
                        std::to_string(sliced.component_count) + " components, " +
                        std::to_string(sliced.boundary_loop_count) +
                        " boundary loops, Euler characteristic " +
                        std::to_string(sliced.euler_characteristic) + ")");
  }
}

Eigen::VectorXd sliced_edge_lengths(const SlicedMesh& sliced,
                                    const Eigen::VectorXd& original_lengths) {
  Eigen::VectorXd lengths(sliced.mesh.n_edges());
  for (size_t e = 0; e < sliced.to_original_edge.size(); ++e) {
    const int o = sliced.to_original_edge[e];
    if (o < 0 || o >= original_lengths.size()) {
      throw InvalidInputError("sliced edge lengths: no original length for sliced edge " +
                              std::to_string(e));
    }
    lengths[static_cast<Eigen::Index>(e)] = original_lengths[o];
  }
  return lengths;
}

}  // namespace ricci
