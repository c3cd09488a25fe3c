#pragma once
// Conversions between ricci::Mesh and CGAL::Surface_mesh. Include only from *_cgal.cpp files.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include "ricci/mesh/mesh.h"

namespace ricci::cgal {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point3 = Kernel::Point_3;
using SurfaceMesh = CGAL::Surface_mesh<Point3>;

inline SurfaceMesh to_surface_mesh(const Mesh& mesh) {
  SurfaceMesh out;
  out.reserve(static_cast<SurfaceMesh::size_type>(mesh.n_vertices()),
              static_cast<SurfaceMesh::size_type>(mesh.n_edges()),
              static_cast<SurfaceMesh::size_type>(mesh.n_faces()));
  std::vector<SurfaceMesh::Vertex_index> index(mesh.n_vertices());
  for (auto v : mesh.vertices()) {
    const auto& p = mesh.point(v);
    index[v.idx()] = out.add_vertex(Point3(p[0], p[1], p[2]));
  }
  for (auto f : mesh.faces()) {
    std::array<SurfaceMesh::Vertex_index, 3> corners;
    int k = 0;
    for (auto v : mesh.fv_range(f)) corners[k++] = index[v.idx()];
    out.add_face(corners[0], corners[1], corners[2]);
  }
  return out;
}

inline Mesh from_surface_mesh(const SurfaceMesh& in) {
  Mesh out;
  // num_vertices() counts removed vertices too, so indices stay valid before collect_garbage().
  std::vector<int> compact(in.num_vertices(), -1);
  for (auto v : in.vertices()) {
    const auto& p = in.point(v);
    VertexHandle h = out.add_vertex(Mesh::Point(p.x(), p.y(), p.z()));
    compact[v.idx()] = h.idx();
  }
  for (auto f : in.faces()) {
    std::vector<VertexHandle> corners;
    for (auto v : CGAL::vertices_around_face(in.halfedge(f), in)) {
      corners.push_back(out.vertex_handle(compact[v.idx()]));
    }
    out.add_face(corners);
  }
  return out;
}

}  // namespace ricci::cgal
