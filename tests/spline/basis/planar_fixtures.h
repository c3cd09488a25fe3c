#pragma once
// Seeded irregular planar triangulations for the DMS tests.
#include <Eigen/Core>
#include <cmath>
#include <random>
#include <vector>

#include "spline/planar/perturbed_grid.h"
#include "spline/planar/triangulation.h"

namespace spline::testing {

using spline::perturbed_grid;  // spline/planar/perturbed_grid.h

/// Concentric rings around a centre vertex with 5, 11, 17, ... vertices (irregular valences),
/// radii jittered; rings stitched by an angular merge.
inline PlanarTriangulation ring_disk(int rings, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const double pi = 3.14159265358979323846;
  PlanarTriangulation t;
  t.positions.emplace_back(0.03 * unit(rng), 0.03 * unit(rng));
  std::vector<int> previous = {0};
  std::vector<double> previous_angle = {0.0};
  for (int r = 1; r <= rings; ++r) {
    const int count = 6 * r - 1;
    const double phase = 0.3 * unit(rng);
    std::vector<int> ring;
    std::vector<double> angles;
    for (int k = 0; k < count; ++k) {
      const double angle = phase + 2.0 * pi * (k + 0.2 * unit(rng)) / count;
      const double radius = r * (1.0 + 0.1 * unit(rng));
      ring.push_back(static_cast<int>(t.positions.size()));
      angles.push_back(angle);
      t.positions.emplace_back(radius * std::cos(angle), radius * std::sin(angle));
    }
    if (r == 1) {
      for (int k = 0; k < count; ++k) t.triangles.emplace_back(0, ring[k], ring[(k + 1) % count]);
    } else {
      // Walk both rings by angle from the inner ring's first vertex, always advancing the ring
      // whose next vertex comes first.
      const int pc = static_cast<int>(previous.size());
      const double base = previous_angle[0];
      auto unwrap = [&](double x) {
        while (x < base) x += 2.0 * pi;
        while (x >= base + 2.0 * pi) x -= 2.0 * pi;
        return x;
      };
      std::vector<double> inner(pc + 1), outer(count + 1);
      for (int q = 0; q < pc; ++q) inner[q] = unwrap(previous_angle[q]);
      inner[pc] = base + 2.0 * pi;
      int start = 0;
      for (int q = 0; q < count; ++q) {
        if (unwrap(angles[q]) < unwrap(angles[start])) start = q;
      }
      for (int q = 0; q <= count; ++q) outer[q] = unwrap(angles[(start + q) % count]) + (q == count ? 2.0 * pi : 0.0);
      int i = 0, k = 0;
      while (i < pc || k < count) {
        const int a = previous[i % pc], b = ring[(start + k) % count];
        if (k == count || (i < pc && inner[i + 1] < outer[k + 1])) {
          t.triangles.emplace_back(a, b, previous[(i + 1) % pc]);
          ++i;
        } else {
          t.triangles.emplace_back(a, b, ring[(start + k + 1) % count]);
          ++k;
        }
      }
    }
    previous = ring;
    previous_angle = angles;
  }
  return t;
}

/// Vertices with a closed one-ring (interior vertices).
inline std::vector<bool> interior_vertices(const PlanarTriangulation& t) {
  std::vector<bool> interior(t.positions.size(), false);
  const std::vector<VertexRing> rings = vertex_rings(t);
  for (std::size_t v = 0; v < rings.size(); ++v) interior[v] = rings[v].closed;
  return interior;
}

/// Triangles whose three vertices are interior: there, every function reaching a point exists.
inline std::vector<int> inner_triangles(const PlanarTriangulation& t) {
  const std::vector<bool> interior = interior_vertices(t);
  std::vector<int> result;
  for (std::size_t i = 0; i < t.triangles.size(); ++i) {
    const Eigen::Vector3i& tri = t.triangles[i];
    if (interior[tri[0]] && interior[tri[1]] && interior[tri[2]]) result.push_back(static_cast<int>(i));
  }
  return result;
}

/// A uniformly random point of triangle i.
inline Eigen::Vector2d random_point_in(const PlanarTriangulation& t, int i, std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  double a = unit(rng), b = unit(rng);
  if (a + b > 1.0) a = 1.0 - a, b = 1.0 - b;
  const Eigen::Vector3i& tri = t.triangles[static_cast<std::size_t>(i)];
  const Eigen::Vector2d& p0 = t.positions[tri[0]];
  return p0 + a * (t.positions[tri[1]] - p0) + b * (t.positions[tri[2]] - p0);
}

}  // namespace spline::testing
