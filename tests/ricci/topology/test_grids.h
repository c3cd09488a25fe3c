#pragma once
// Small procedural meshes for the topology, layout and atlas tests: a jittered planar grid
// (open disk, non-uniform lengths). Flat tori come from ricci/mesh/primitives.h.
#include <cmath>
#include <string>

#include <Eigen/Core>

#include "ricci/mesh/mesh.h"

namespace ricci::test {

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


}  // namespace ricci::test
