#include "ricci/metric/subdivide.h"

#include <string>
#include <vector>

#include "ricci/mesh/errors.h"
#include "ricci/metric/mesh_tables.h"

namespace ricci {

Mesh subdivide_midpoint(const Mesh& mesh) {
  const MeshTables t = build_mesh_tables(mesh);
  Mesh out;
  out.reserve(mesh.n_vertices() + mesh.n_edges(), 2 * (mesh.n_edges() + 2 * mesh.n_faces()),
              4 * mesh.n_faces());
  std::vector<VertexHandle> handles;
  handles.reserve(mesh.n_vertices() + mesh.n_edges());
  for (auto v : mesh.vertices()) handles.push_back(out.add_vertex(mesh.point(v)));
  for (int e = 0; e < t.num_edges(); ++e) {
    const auto a = mesh.point(VertexHandle(t.edge_vertices(e, 0)));
    const auto b = mesh.point(VertexHandle(t.edge_vertices(e, 1)));
    handles.push_back(out.add_vertex(0.5 * (a + b)));
  }
  const int nv = t.num_vertices();
  for (int f = 0; f < t.num_faces(); ++f) {
    VertexHandle v[3], m[3];
    for (int k = 0; k < 3; ++k) {
      v[k] = handles[t.face_vertices(f, k)];
      m[k] = handles[nv + t.face_edges(f, k)];  // midpoint of the edge opposite v[k]
    }
    out.add_face(v[0], m[2], m[1]);
    out.add_face(v[1], m[0], m[2]);
    out.add_face(v[2], m[1], m[0]);
    out.add_face(m[0], m[1], m[2]);
  }
  return out;
}

namespace {

// Edges to split (by edge index): those of the flagged faces, closed under "a face with two
// split edges splits all three".
std::vector<char> closed_split_edges(const MeshTables& t, const std::vector<char>& refine) {
  std::vector<char> split(static_cast<std::size_t>(t.num_edges()), 0);
  for (int f = 0; f < t.num_faces(); ++f) {
    if (!refine[f]) continue;
    for (int k = 0; k < 3; ++k) split[t.face_edges(f, k)] = 1;
  }
  for (bool changed = true; changed;) {
    changed = false;
    for (int f = 0; f < t.num_faces(); ++f) {
      int count = 0;
      for (int k = 0; k < 3; ++k) count += split[t.face_edges(f, k)];
      if (count != 2) continue;
      for (int k = 0; k < 3; ++k) split[t.face_edges(f, k)] = 1;
      changed = true;
    }
  }
  return split;
}

}  // namespace

Mesh subdivide_midpoint_locally(const Mesh& mesh, const std::vector<char>& refine) {
  if (refine.size() != mesh.n_faces()) {
    throw InvalidInputError("local subdivision: " + std::to_string(refine.size()) + " flags for " +
                            std::to_string(mesh.n_faces()) + " faces");
  }
  const MeshTables t = build_mesh_tables(mesh);
  const std::vector<char> split = closed_split_edges(t, refine);
  Mesh out;
  std::vector<VertexHandle> handles;
  for (auto v : mesh.vertices()) handles.push_back(out.add_vertex(mesh.point(v)));
  std::vector<int> midpoint(static_cast<std::size_t>(t.num_edges()), -1);
  for (int e = 0; e < t.num_edges(); ++e) {
    if (!split[e]) continue;
    const auto a = mesh.point(VertexHandle(t.edge_vertices(e, 0)));
    const auto b = mesh.point(VertexHandle(t.edge_vertices(e, 1)));
    midpoint[e] = static_cast<int>(handles.size());
    handles.push_back(out.add_vertex(0.5 * (a + b)));
  }
  for (int f = 0; f < t.num_faces(); ++f) {
    VertexHandle v[3];
    int m[3], count = 0;
    for (int k = 0; k < 3; ++k) {
      v[k] = handles[t.face_vertices(f, k)];
      m[k] = midpoint[t.face_edges(f, k)];  // midpoint of the edge opposite v[k], or -1
      count += m[k] >= 0;
    }
    if (count == 0) {
      out.add_face(v[0], v[1], v[2]);
    } else if (count == 3) {
      const VertexHandle a = handles[m[0]], b = handles[m[1]], c = handles[m[2]];
      out.add_face(v[0], c, b);
      out.add_face(v[1], a, c);
      out.add_face(v[2], b, a);
      out.add_face(a, b, c);
    } else {  // one split edge, opposite corner k: bisect from v[k]
      const int k = m[0] >= 0 ? 0 : (m[1] >= 0 ? 1 : 2);
      const VertexHandle mid = handles[m[k]];
      out.add_face(v[k], v[(k + 1) % 3], mid);
      out.add_face(v[k], mid, v[(k + 2) % 3]);
    }
  }
  return out;
}

}  // namespace ricci
