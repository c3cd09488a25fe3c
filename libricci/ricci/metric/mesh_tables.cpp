#include "ricci/metric/mesh_tables.h"

#include <string>

#include "ricci/mesh/boundary_loops.h"
#include "ricci/mesh/errors.h"

namespace ricci {

namespace {

// Boundary loops as the vertex indices their halfedges start from.
std::vector<std::vector<int>> collect_boundary_loops(const Mesh& mesh) {
  std::vector<std::vector<int>> loops;
  for (const auto& halfedges : find_boundary_loops(mesh)) {
    std::vector<int> loop;
    loop.reserve(halfedges.size());
    for (const auto h : halfedges) loop.push_back(mesh.from_vertex_handle(h).idx());
    loops.push_back(std::move(loop));
  }
  return loops;
}

}  // namespace

MeshTables build_mesh_tables(const Mesh& mesh) {
  if (mesh.n_faces() == 0) throw InvalidInputError("mesh has no faces");
  MeshTables t;
  const int nv = static_cast<int>(mesh.n_vertices());
  t.face_vertices.resize(mesh.n_faces(), 3);
  t.face_edges.resize(mesh.n_faces(), 3);
  t.edge_vertices.resize(mesh.n_edges(), 2);
  t.valence = Eigen::VectorXi::Zero(nv);
  for (auto f : mesh.faces()) {
    int k = 0;
    for (auto h : mesh.fh_range(f)) {
      if (k == 3) {
        throw InvalidInputError("face " + std::to_string(f.idx()) + " is not a triangle");
      }
      // The halfedge from v_{k} to v_{k+1} is opposite v_{k+2}.
      const int v = mesh.from_vertex_handle(h).idx();
      t.face_vertices(f.idx(), k) = v;
      t.face_edges(f.idx(), (k + 2) % 3) = mesh.edge_handle(h).idx();
      ++t.valence[v];
      ++k;
    }
    if (k != 3) throw InvalidInputError("face " + std::to_string(f.idx()) + " is not a triangle");
  }
  for (auto e : mesh.edges()) {
    auto h = mesh.halfedge_handle(e, 0);
    t.edge_vertices(e.idx(), 0) = mesh.from_vertex_handle(h).idx();
    t.edge_vertices(e.idx(), 1) = mesh.to_vertex_handle(h).idx();
  }
  t.is_boundary_vertex.assign(nv, 0);
  for (auto v : mesh.vertices()) {
    if (t.valence[v.idx()] == 0) {
      throw TopologyError("vertex " + std::to_string(v.idx()) + " is isolated (in no face)");
    }
    t.is_boundary_vertex[v.idx()] = mesh.is_boundary(v) ? 1 : 0;
  }
  t.boundary_loops = collect_boundary_loops(mesh);
  t.euler_characteristic = euler_characteristic(mesh);
  return t;
}

EdgeLengths mesh_edge_lengths(const Mesh& mesh) {
  EdgeLengths l(mesh.n_edges());
  for (auto e : mesh.edges()) {
    auto h = mesh.halfedge_handle(e, 0);
    l[e.idx()] = (mesh.point(mesh.to_vertex_handle(h)) - mesh.point(mesh.from_vertex_handle(h))).norm();
  }
  return l;
}

}  // namespace ricci
