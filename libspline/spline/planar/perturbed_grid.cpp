#include "spline/planar/perturbed_grid.h"

#include <random>

namespace spline {

PlanarTriangulation perturbed_grid(int m, double jitter, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  PlanarTriangulation t;
  const double h = 1.0 / m;
  for (int j = 0; j <= m; ++j) {
    for (int i = 0; i <= m; ++i) {
      Eigen::Vector2d p(i * h, j * h);
      if (i > 0 && i < m && j > 0 && j < m) p += jitter * h * Eigen::Vector2d(unit(rng), unit(rng));
      t.positions.push_back(p);
    }
  }
  auto id = [m](int i, int j) { return j * (m + 1) + i; };
  for (int j = 0; j < m; ++j) {
    for (int i = 0; i < m; ++i) {
      const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if (unit(rng) > 0.0) {
        t.triangles.emplace_back(a, b, c);
        t.triangles.emplace_back(a, c, d);
      } else {
        t.triangles.emplace_back(a, b, d);
        t.triangles.emplace_back(b, c, d);
      }
    }
  }
  return t;
}

}  // namespace spline
