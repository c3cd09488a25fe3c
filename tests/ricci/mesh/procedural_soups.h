#pragma once
// Small procedural soups with known topology, shared by the mesh tests.
#include <cmath>

#include "ricci/mesh/soup.h"

namespace ricci_test {

inline ricci::PolygonSoup tetrahedron() {
  ricci::PolygonSoup soup;
  soup.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  soup.faces = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};  // outward
  return soup;
}

/// An n by m grid on a torus (R = 2, r = 1); quads when `quads`, else two triangles per quad.
/// `twist` glues the last column to the first upside down: a Klein bottle (non-orientable).
inline ricci::PolygonSoup torus(int n, int m, bool quads = false, bool twist = false) {
  ricci::PolygonSoup soup;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      const double u = 2 * M_PI * i / n, v = 2 * M_PI * j / m;
      soup.positions.emplace_back((2 + std::cos(v)) * std::cos(u), (2 + std::cos(v)) * std::sin(u),
                                  std::sin(v) + 0.01 * i);
    }
  auto id = [&](int i, int j) {
    if (twist && i == n) j = (m - j) % m;
    return (i % n) * m + (j % m);
  };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if (quads) {
        soup.faces.push_back({a, b, c, d});
      } else {
        soup.faces.push_back({a, b, c});
        soup.faces.push_back({a, c, d});
      }
    }
  return soup;
}

/// An open n by m grid of the unit square (one boundary loop) in the plane z = 0.
inline ricci::PolygonSoup disk(int n, int m) {
  ricci::PolygonSoup soup;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= m; ++j) soup.positions.emplace_back(double(i) / n, double(j) / m, 0.0);
  auto id = [&](int i, int j) { return i * (m + 1) + j; };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      soup.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      soup.faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return soup;
}

/// A Mobius strip of n quads (split into triangles), glued with a half twist.
inline ricci::PolygonSoup mobius(int n) {
  ricci::PolygonSoup soup;
  for (int i = 0; i < n; ++i) {
    const double u = 2 * M_PI * i / n;
    for (double v : {-0.3, 0.3})
      soup.positions.emplace_back((1 + v * std::cos(u / 2)) * std::cos(u),
                                  (1 + v * std::cos(u / 2)) * std::sin(u), v * std::sin(u / 2));
  }
  for (int i = 0; i < n; ++i) {
    int a0 = 2 * i, b0 = 2 * i + 1, a1 = 2 * (i + 1), b1 = 2 * (i + 1) + 1;
    if (i == n - 1) {
      a1 = 1;  // the twist: the bottom edge comes back as the top edge
      b1 = 0;
    }
    soup.faces.push_back({a0, a1, b1});
    soup.faces.push_back({a0, b1, b0});
  }
  return soup;
}

/// Appends `other` with its indices shifted (a disjoint union).
inline void append(ricci::PolygonSoup& soup, const ricci::PolygonSoup& other,
                   const Eigen::Vector3d& shift) {
  const int offset = static_cast<int>(soup.positions.size());
  for (const auto& p : other.positions) soup.positions.push_back(p + shift);
  for (auto face : other.faces) {
    for (int& v : face) v += offset;
    soup.faces.push_back(face);
  }
}

}  // namespace ricci_test
