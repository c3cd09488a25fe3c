#pragma once
// Small procedural meshes for the topology, layout and atlas tests: a flat torus grid with its
// exact flat edge lengths and a planar grid (open disk). Kept here so these tests do not depend
// on the mesh generator's branch.
#include <cmath>
#include <string>

#include <Eigen/Core>

#include "ricci/mesh/mesh.h"

namespace ricci::test {

/// nx by ny periodic grid, each cell split along its (i,j)-(i+1,j+1) diagonal. Vertex (i, j)
/// has index j * nx + i. The 3D embedding is a round torus (R = 3, r = 1); the flat metric is
/// the one of the width x height rectangle with opposite sides identified.
inline Mesh flat_torus_grid(int nx, int ny) {
  Mesh mesh;
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const double u = 2.0 * M_PI * i / nx, v = 2.0 * M_PI * j / ny;
      mesh.add_vertex(Mesh::Point((3.0 + std::cos(v)) * std::cos(u),
                                  (3.0 + std::cos(v)) * std::sin(u), std::sin(v)));
    }
  }
  auto id = [&](int i, int j) { return VertexHandle(((j + ny) % ny) * nx + (i + nx) % nx); };
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      mesh.add_face(id(i, j), id(i + 1, j), id(i + 1, j + 1));
      mesh.add_face(id(i, j), id(i + 1, j + 1), id(i, j + 1));
    }
  }
  return mesh;
}

/// Exact flat lengths of flat_torus_grid(nx, ny) for a width x height period rectangle.
inline Eigen::VectorXd flat_torus_lengths(const Mesh& mesh, int nx, int ny, double width,
                                          double height) {
  Eigen::VectorXd lengths(mesh.n_edges());
  for (auto e : mesh.edges()) {
    const auto h = mesh.halfedge_handle(e, 0);
    const int a = mesh.from_vertex_handle(h).idx(), b = mesh.to_vertex_handle(h).idx();
    int di = b % nx - a % nx, dj = b / nx - a / nx;
    if (di > 1) di -= nx;
    if (di < -1) di += nx;
    if (dj > 1) dj -= ny;
    if (dj < -1) dj += ny;
    lengths[e.idx()] = std::hypot(di * width / nx, dj * height / ny);
  }
  return lengths;
}

/// Planar (z = 0) nx by ny cell grid over [0, width] x [0, height], cells split by a diagonal
/// whose direction alternates, with a small deterministic jitter of the interior vertices.
inline Mesh planar_grid(int nx, int ny, double width, double height) {
  Mesh mesh;
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i <= nx; ++i) {
      double x = width * i / nx, y = height * j / ny;
      if (i > 0 && i < nx && j > 0 && j < ny) {
        x += 0.2 * width / nx * std::sin(1.7 * i + 2.3 * j);
        y += 0.2 * height / ny * std::cos(2.9 * i - 1.1 * j);
      }
      mesh.add_vertex(Mesh::Point(x, y, 0.0));
    }
  }
  auto id = [&](int i, int j) { return VertexHandle(j * (nx + 1) + i); };
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      if ((i + j) % 2 == 0) {
        mesh.add_face(id(i, j), id(i + 1, j), id(i + 1, j + 1));
        mesh.add_face(id(i, j), id(i + 1, j + 1), id(i, j + 1));
      } else {
        mesh.add_face(id(i, j), id(i + 1, j), id(i, j + 1));
        mesh.add_face(id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
      }
    }
  }
  return mesh;
}

inline std::string shared_model(const std::string& relative) {
  return std::string(MSP_SHARED_MODELS) + "/" + relative;
}

}  // namespace ricci::test
