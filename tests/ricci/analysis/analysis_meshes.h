#pragma once
// Planar annuli and their conformal images for the conformal-module tests (test code).
#include <cmath>
#include <complex>
#include <functional>

#include <ricci/mesh/arrays.h>
#include <ricci/mesh/mesh.h>

namespace ricci::testing {

/// The annulus r <= |z| <= R on a log-polar grid of `rings` x `sectors` cells (near-square in
/// log |z|, arg z), each cell split along a diagonal that alternates with the ring: 2 * rings *
/// sectors faces, genus 0, two boundary loops, counter-clockwise seen from +z.
inline Mesh log_polar_annulus(int rings, int sectors, double r, double R) {
  Eigen::MatrixX3d V((rings + 1) * sectors, 3);
  for (int i = 0; i <= rings; ++i) {
    const double radius = r * std::pow(R / r, double(i) / rings);
    for (int j = 0; j < sectors; ++j) {
      // Every other ring turned by half a sector: triangles closer to equilateral.
      const double angle = 2 * M_PI * (j + 0.5 * (i % 2)) / sectors;
      V.row(i * sectors + j) << radius * std::cos(angle), radius * std::sin(angle), 0.0;
    }
  }
  Eigen::MatrixX3i F(2 * rings * sectors, 3);
  int f = 0;
  for (int i = 0; i < rings; ++i) {
    for (int j = 0; j < sectors; ++j) {
      const int a = i * sectors + j, b = i * sectors + (j + 1) % sectors;
      const int c = (i + 1) * sectors + j, d = (i + 1) * sectors + (j + 1) % sectors;
      if (i % 2 == 0) {
        F.row(f++) << a, b, c;
        F.row(f++) << b, d, c;
      } else {
        F.row(f++) << a, d, c;
        F.row(f++) << a, b, d;
      }
    }
  }
  return from_arrays(V, F);
}

/// A copy of `mesh` whose vertex p goes to map(p).
inline Mesh mapped(const Mesh& mesh,
                   const std::function<Eigen::Vector3d(const Eigen::Vector3d&)>& map) {
  Mesh out = mesh;
  for (VertexHandle v : out.vertices()) out.set_point(v, to_openmesh(map(to_eigen(out.point(v)))));
  return out;
}

/// Inverse stereographic projection of the plane z = 0 (scaled by 1/scale) onto the unit
/// sphere: a conformal map.
inline Eigen::Vector3d onto_sphere(const Eigen::Vector3d& p, double scale) {
  const double x = p.x() / scale, y = p.y() / scale, q = x * x + y * y;
  return {2 * x / (1 + q), 2 * y / (1 + q), (q - 1) / (1 + q)};
}

/// The Möbius map z -> (z - a) / (1 - conj(a) z) of the plane z = 0 (a disk automorphism).
inline Eigen::Vector3d mobius(const Eigen::Vector3d& p, std::complex<double> a) {
  const std::complex<double> z(p.x(), p.y());
  const std::complex<double> w = (z - a) / (1.0 - std::conj(a) * z);
  return {w.real(), w.imag(), 0.0};
}

}  // namespace ricci::testing
