#include "ricci/topology/double_cover.h"

#include <string>

#include "ricci/mesh/errors.h"

namespace ricci {

namespace {

/// Splits every interior edge whose two ends lie on the boundary (a chord), at its midpoint.
int split_chords(Mesh& mesh) {
  std::vector<EdgeHandle> chords;
  for (auto e : mesh.edges()) {
    const auto h = mesh.halfedge_handle(e, 0);
    if (!mesh.is_boundary(e) && mesh.is_boundary(mesh.from_vertex_handle(h)) &&
        mesh.is_boundary(mesh.to_vertex_handle(h))) {
      chords.push_back(e);
    }
  }
  for (EdgeHandle e : chords) {
    const auto h = mesh.halfedge_handle(e, 0);
    const auto mid = 0.5 * (mesh.point(mesh.from_vertex_handle(h)) + mesh.point(mesh.to_vertex_handle(h)));
    mesh.split(e, mid);
  }
  return static_cast<int>(chords.size());
}

}  // namespace

DoubleCover double_cover(const Mesh& input) {
  bool open = false;
  for (auto v : input.vertices()) open = open || input.is_boundary(v);
  if (!open) throw TopologyError("double_cover: the mesh is closed (nothing to double)");
  DoubleCover result;
  result.original = input;
  result.split_edges = split_chords(result.original);
  const Mesh& mesh = result.original;
  result.original_faces = static_cast<int>(mesh.n_faces());
  result.mirror_vertex.resize(mesh.n_vertices());
  for (auto v : mesh.vertices()) {
    result.mesh.add_vertex(mesh.point(v));
    result.to_original_vertex.push_back(v.idx());
  }
  for (auto v : mesh.vertices()) {
    if (mesh.is_boundary(v)) {
      result.mirror_vertex[v.idx()] = v.idx();
    } else {
      result.mirror_vertex[v.idx()] = result.mesh.add_vertex(mesh.point(v)).idx();
      result.to_original_vertex.push_back(v.idx());
    }
  }
  for (auto f : mesh.faces()) {
    std::vector<VertexHandle> corners;
    for (auto v : mesh.fv_range(f)) corners.push_back(VertexHandle(v.idx()));
    if (!result.mesh.add_face(corners).is_valid()) {
      throw TopologyError("double_cover: face " + std::to_string(f.idx()) + " is not manifold");
    }
  }
  for (auto f : mesh.faces()) {
    std::vector<VertexHandle> corners;
    for (auto v : mesh.fv_range(f)) corners.insert(corners.begin(), VertexHandle(result.mirror_vertex[v.idx()]));
    if (!result.mesh.add_face(corners).is_valid()) {
      throw TopologyError("double_cover: mirror of face " + std::to_string(f.idx()) +
                          " cannot be glued (non-manifold boundary)");
    }
  }
  return result;
}

}  // namespace ricci
