#pragma once
// Planar annuli and their conformal images for the conformal-module tests (test code).
#include <cmath>
#include <complex>
#include <array>
#include <functional>
#include <map>
#include <random>
#include <utility>
#include <vector>

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

/// A circle: centre (x, y) and radius.
struct TestCircle {
  double x = 0, y = 0, r = 1;
};

/// Delaunay triangulation (Bowyer-Watson, quadratic: test sizes only) of planar points,
/// counter-clockwise faces.
inline std::vector<std::array<int, 3>> delaunay(const std::vector<Eigen::Vector2d>& input) {
  std::vector<Eigen::Vector2d> p = input;
  const int n = static_cast<int>(p.size());
  p.push_back({-1e3, -1e3});
  p.push_back({1e3, -1e3});
  p.push_back({0, 1e3});
  struct Tri {
    std::array<int, 3> v;
    Eigen::Vector2d centre;
    double radius2;
  };
  const auto make = [&](int a, int b, int c) {
    const Eigen::Vector2d A = p[a], B = p[b], C = p[c];
    const double d =
        2 * (A.x() * (B.y() - C.y()) + B.x() * (C.y() - A.y()) + C.x() * (A.y() - B.y()));
    const double a2 = A.squaredNorm(), b2 = B.squaredNorm(), c2 = C.squaredNorm();
    const Eigen::Vector2d centre(
        (a2 * (B.y() - C.y()) + b2 * (C.y() - A.y()) + c2 * (A.y() - B.y())) / d,
        (a2 * (C.x() - B.x()) + b2 * (A.x() - C.x()) + c2 * (B.x() - A.x())) / d);
    return Tri{{a, b, c}, centre, (A - centre).squaredNorm()};
  };
  std::vector<Tri> tris = {make(n, n + 1, n + 2)};
  for (int i = 0; i < n; ++i) {
    std::map<std::pair<int, int>, int> edges;  // directed edge of a removed triangle -> count
    std::vector<Tri> kept;
    for (const Tri& t : tris) {
      if ((p[i] - t.centre).squaredNorm() < t.radius2) {
        for (int k = 0; k < 3; ++k) edges[{t.v[k], t.v[(k + 1) % 3]}] += 1;
      } else {
        kept.push_back(t);
      }
    }
    for (const auto& [e, count] : edges) {
      if (!edges.count({e.second, e.first})) kept.push_back(make(e.first, e.second, i));
    }
    tris = std::move(kept);
  }
  std::vector<std::array<int, 3>> faces;
  for (const Tri& t : tris) {
    if (t.v[0] < n && t.v[1] < n && t.v[2] < n) faces.push_back(t.v);
  }
  return faces;
}

/// The unit disk minus the closed disks `holes` (inside it, disjoint), triangulated at edge
/// length about h: a jittered triangular lattice kept 0.5 h away from the circles, the circles
/// sampled at spacing about 0.8 h, Delaunay, faces outside the domain removed. Boundary vertices
/// lie on the circles within 1e-10. z = 0, counter-clockwise.
inline Mesh circle_domain_mesh(const std::vector<TestCircle>& holes, double h, unsigned seed = 1) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> jitter(-0.05 * h, 0.05 * h);
  std::vector<Eigen::Vector2d> points;
  std::vector<TestCircle> circles = {{0, 0, 1}};
  circles.insert(circles.end(), holes.begin(), holes.end());
  for (const TestCircle& c : circles) {
    const int m = std::max(12, static_cast<int>(std::ceil(2 * M_PI * c.r / (0.8 * h))));
    for (int i = 0; i < m; ++i) {
      // Off the circle by 1e-9 at random: co-circular points would make the Delaunay
      // predicate's rounding decide, and break the cavities.
      const double a = 2 * M_PI * i / m, radius = c.r * (1 + 1e-9 * jitter(random) / h);
      points.push_back({c.x + radius * std::cos(a), c.y + radius * std::sin(a)});
    }
  }
  const auto inside = [&](const Eigen::Vector2d& q, double margin) {
    if (q.norm() > 1 - margin) return false;
    for (const TestCircle& c : holes) {
      if ((q - Eigen::Vector2d(c.x, c.y)).norm() < c.r + margin) return false;
    }
    return true;
  };
  const double dy = h * std::sqrt(3.0) / 2;
  for (int j = -static_cast<int>(1 / dy) - 1; j * dy <= 1; ++j) {
    for (int i = -static_cast<int>(1 / h) - 2; i * h <= 1 + h; ++i) {
      const Eigen::Vector2d q((i + 0.5 * (j & 1)) * h + jitter(random), j * dy + jitter(random));
      if (inside(q, 0.5 * h)) points.push_back(q);
    }
  }
  std::vector<std::array<int, 3>> faces;
  for (const auto& f : delaunay(points)) {
    if (inside((points[f[0]] + points[f[1]] + points[f[2]]) / 3, 0)) faces.push_back(f);
  }
  Eigen::MatrixX3d V(static_cast<Eigen::Index>(points.size()), 3);
  for (size_t i = 0; i < points.size(); ++i) V.row(i) << points[i].x(), points[i].y(), 0.0;
  Eigen::MatrixX3i F(static_cast<Eigen::Index>(faces.size()), 3);
  for (size_t i = 0; i < faces.size(); ++i) F.row(i) << faces[i][0], faces[i][1], faces[i][2];
  return from_arrays(V, F);
}

}  // namespace ricci::testing
