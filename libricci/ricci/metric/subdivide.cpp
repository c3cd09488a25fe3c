#include "ricci/metric/subdivide.h"

#include <vector>

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

}  // namespace ricci
