#include "spline/planar/triangulation.h"

#include <cmath>
#include <map>
#include <string>

#include "ricci/mesh/errors.h"
#include "ricci/util/cross2d.h"
#include "spline/basis/orientation.h"

namespace spline {

void validate(const PlanarTriangulation& triangulation) {
  const auto& p = triangulation.positions;
  for (std::size_t v = 0; v < p.size(); ++v) {
    if (!p[v].allFinite()) {
      throw ricci::InvalidInputError("planar triangulation: vertex " + std::to_string(v) +
                                     " has a non-finite position");
    }
  }
  const int count = static_cast<int>(p.size());
  for (std::size_t t = 0; t < triangulation.triangles.size(); ++t) {
    const Eigen::Vector3i& tri = triangulation.triangles[t];
    for (int k = 0; k < 3; ++k) {
      if (tri[k] < 0 || tri[k] >= count) {
        throw ricci::InvalidInputError("planar triangulation: triangle " + std::to_string(t) +
                                       " has a vertex index out of range");
      }
    }
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0]) {
      throw ricci::InvalidInputError("planar triangulation: triangle " + std::to_string(t) +
                                     " repeats a vertex");
    }
    if (orient2d(p[tri[0]], p[tri[1]], p[tri[2]]) <= 0) {
      throw ricci::InvalidInputError("planar triangulation: triangle " + std::to_string(t) +
                                     " is not counter-clockwise (or is degenerate)");
    }
  }
}

std::vector<VertexRing> vertex_rings(const PlanarTriangulation& triangulation) {
  const std::size_t n = triangulation.positions.size();
  // Around vertex v, each counter-clockwise triangle (v, a, b) is an arc a -> b of v's fan.
  std::vector<std::map<int, int>> next(n);
  std::vector<std::map<int, int>> previous(n);
  for (const Eigen::Vector3i& tri : triangulation.triangles) {
    for (int k = 0; k < 3; ++k) {
      const int v = tri[k], a = tri[(k + 1) % 3], b = tri[(k + 2) % 3];
      if (!next[v].emplace(a, b).second || !previous[v].emplace(b, a).second) {
        throw ricci::TopologyError("planar triangulation: edge (" + std::to_string(v) + ", " +
                                   std::to_string(a) + ") is used twice in the same direction");
      }
    }
  }
  std::vector<VertexRing> rings(n);
  for (std::size_t v = 0; v < n; ++v) {
    if (next[v].empty()) continue;
    // Start at a neighbour with no predecessor (boundary fan) or anywhere (closed ring).
    int start = next[v].begin()->first;
    bool closed = true;
    for (const auto& arc : next[v]) {
      if (previous[v].count(arc.first) == 0) {
        start = arc.first;
        closed = false;
        break;
      }
    }
    VertexRing& ring = rings[v];
    ring.closed = closed;
    int current = start;
    ring.neighbours.push_back(current);
    while (true) {
      const auto it = next[v].find(current);
      if (it == next[v].end()) break;
      current = it->second;
      if (current == start) break;
      ring.neighbours.push_back(current);
    }
    const std::size_t expected = next[v].size() + (closed ? 0 : 1);
    if (ring.neighbours.size() != expected) {
      throw ricci::TopologyError("planar triangulation: the triangles around vertex " +
                                 std::to_string(v) + " do not form a single fan");
    }
  }
  return rings;
}

double inradius(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  const double ab = (b - a).norm(), bc = (c - b).norm(), ca = (a - c).norm();
  const Eigen::Vector2d e1 = b - a, e2 = c - a;
  const double area = 0.5 * std::abs(ricci::cross2d(e1, e2));
  return 2.0 * area / (ab + bc + ca);
}

}  // namespace spline
