#include "spline/tessellate/triangle_sides.h"

#include <algorithm>

#include "ricci/util/edge_key.h"

namespace spline {

std::vector<std::pair<std::uint64_t, int>> sorted_triangle_sides(
    const std::vector<std::array<int, 3>>& triangles, const std::vector<char>& skip,
    int vertex_count) {
  const auto skipped = [&](std::size_t t) { return !skip.empty() && skip[t]; };
  std::vector<int> start(static_cast<std::size_t>(vertex_count) + 1, 0);
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    if (skipped(t)) continue;
    const auto& tri = triangles[t];
    for (int k = 0; k < 3; ++k)
      ++start[static_cast<std::size_t>(std::min(tri[k], tri[(k + 1) % 3])) + 1];
  }
  for (std::size_t v = 1; v < start.size(); ++v) start[v] += start[v - 1];
  std::vector<std::pair<std::uint64_t, int>> sides(static_cast<std::size_t>(start.back()));
  std::vector<int> next(start.begin(), start.end() - 1);
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    if (skipped(t)) continue;
    const auto& tri = triangles[t];
    for (int k = 0; k < 3; ++k) {
      const auto u = static_cast<std::size_t>(std::min(tri[k], tri[(k + 1) % 3]));
      sides[static_cast<std::size_t>(next[u]++)] = {
          ricci::undirected_edge_key(tri[k], tri[(k + 1) % 3]), static_cast<int>(t)};
    }
  }
  // Each vertex's few sides by their larger vertex (and triangle).
  for (std::size_t v = 0; v + 1 < start.size(); ++v)
    std::sort(sides.begin() + start[v], sides.begin() + start[v + 1]);
  return sides;
}

}  // namespace spline
