#include "ricci/mesh/arrays.h"

#include "ricci/mesh/build_mesh.h"

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
