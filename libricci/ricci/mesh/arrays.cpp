#include "ricci/mesh/arrays.h"

#include <string>

#include "ricci/mesh/build_mesh.h"
#include "ricci/mesh/errors.h"

namespace ricci {

Eigen::MatrixX3d vertex_positions(const Mesh& mesh) {
  Eigen::MatrixX3d x(static_cast<Eigen::Index>(mesh.n_vertices()), 3);
  for (const auto v : mesh.vertices()) x.row(v.idx()) = to_eigen(mesh.point(v)).transpose();
  return x;
}

VertexFaceArrays to_arrays(const Mesh& mesh) {
  VertexFaceArrays arrays;
  arrays.V = vertex_positions(mesh);
  arrays.F.resize(static_cast<Eigen::Index>(mesh.n_faces()), 3);
  for (const auto f : mesh.faces()) {
    int k = 0;
    for (const auto v : mesh.fv_range(f)) arrays.F(f.idx(), k++) = v.idx();
  }
  return arrays;
}

Mesh same_order_mesh(const VertexFaceArrays& arrays) {
  Mesh mesh;
  const auto vertices = static_cast<size_t>(arrays.V.rows());
  const auto faces = static_cast<size_t>(arrays.F.rows());
  mesh.reserve(vertices, vertices + faces, faces);
  for (Eigen::Index v = 0; v < arrays.V.rows(); ++v) mesh.add_vertex(to_openmesh(arrays.V.row(v)));
  for (Eigen::Index f = 0; f < arrays.F.rows(); ++f) {
    if (!mesh.add_face(mesh.vertex_handle(arrays.F(f, 0)), mesh.vertex_handle(arrays.F(f, 1)),
                       mesh.vertex_handle(arrays.F(f, 2)))
             .is_valid()) {
      throw TopologyError("same_order_mesh: face " + std::to_string(f) +
                          " would make the mesh non-manifold");
    }
  }
  return mesh;
}

Mesh from_arrays(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F) {
  PolygonSoup soup;
  soup.source = "(V, F) arrays";
  soup.positions.reserve(static_cast<size_t>(V.rows()));
  for (Eigen::Index v = 0; v < V.rows(); ++v) soup.positions.emplace_back(V.row(v).transpose());
  soup.faces.reserve(static_cast<size_t>(F.rows()));
  for (Eigen::Index f = 0; f < F.rows(); ++f) soup.faces.push_back({F(f, 0), F(f, 1), F(f, 2)});
  return build_mesh(soup);
}

}  // namespace ricci
