#pragma once
// Small procedural meshes for the metric and flow tests (header-only, test code).
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <ricci/mesh/generate.h>
#include <ricci/mesh/io.h>
#include <ricci/mesh/mesh.h>
#include <ricci/metric/subdivide.h>
#include <ricci/pipeline/one_cone_atlas.h>

namespace ricci::testing {

/// Torus of revolution (radii R > r) on an n × m grid, each quad split in two.
inline Mesh torus(int n, int m, double R = 2.0, double r = 0.7) {
  Mesh mesh;
  std::vector<VertexHandle> v(n * m);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < m; ++j) {
      const double a = 2 * M_PI * i / n, b = 2 * M_PI * j / m;
      v[i * m + j] = mesh.add_vertex({(R + r * std::cos(b)) * std::cos(a),
                                      (R + r * std::cos(b)) * std::sin(a), r * std::sin(b)});
    }
  }
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < m; ++j) {
      auto p = v[i * m + j], q = v[((i + 1) % n) * m + j], s = v[((i + 1) % n) * m + (j + 1) % m],
           t = v[i * m + (j + 1) % m];
      mesh.add_face(p, q, s);
      mesh.add_face(p, s, t);
    }
  }
  return mesh;
}

/// Unit sphere from an octahedron refined `levels` times (midpoint + projection).
inline Mesh sphere(int levels) {
  Mesh mesh;
  const OpenMesh::Vec3d p[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  VertexHandle v[6];
  for (int i = 0; i < 6; ++i) v[i] = mesh.add_vertex(p[i]);
  const int f[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                       {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  for (auto& t : f) mesh.add_face(v[t[0]], v[t[1]], v[t[2]]);
  for (int l = 0; l < levels; ++l) {
    mesh = subdivide_midpoint(mesh);
    for (auto vh : mesh.vertices()) mesh.set_point(vh, mesh.point(vh).normalized());
  }
  return mesh;
}

/// Planar square [0,1]² on an n × n grid (a disk: one boundary loop, χ = 1).
inline Mesh square(int n) {
  Mesh mesh;
  std::vector<VertexHandle> v((n + 1) * (n + 1));
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= n; ++j) v[i * (n + 1) + j] = mesh.add_vertex({1.0 * i / n, 1.0 * j / n, 0});
  }
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      auto a = v[i * (n + 1) + j], b = v[(i + 1) * (n + 1) + j], c = v[(i + 1) * (n + 1) + j + 1],
           d = v[i * (n + 1) + j + 1];
      mesh.add_face(a, b, c);
      mesh.add_face(a, c, d);
    }
  }
  return mesh;
}

/// Moves every vertex by a uniform random offset of at most `amount` per coordinate.
inline void jitter(Mesh& mesh, double amount, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> d(-amount, amount);
  for (auto v : mesh.vertices()) mesh.set_point(v, mesh.point(v) + OpenMesh::Vec3d(d(rng), d(rng), d(rng)));
}


/// The one-cone atlas msp fit builds (cone refinement 2) on a generated surface of `genus`
/// with about `faces` faces: one cone of curvature 2 pi (2 - 2g).
inline OneConeAtlasResult generated_fit_atlas(int genus, int faces) {
  GenerateOptions generate;
  generate.genus = genus;
  generate.target_faces = faces;
  OneConeAtlasOptions options;
  options.cone_refinement.levels = 2;
  return build_one_cone_atlas(generate_surface(generate), options);
}

/// generated_fit_atlas at genus 8, about 2400 faces: one cone of curvature -28 pi.
inline OneConeAtlasResult genus8_fit_atlas() { return generated_fit_atlas(8, 2400); }

}  // namespace ricci::testing
