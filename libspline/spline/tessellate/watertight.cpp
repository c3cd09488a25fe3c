#include <algorithm>
#include <array>
#include <cmath>
#include <tuple>
#include <vector>

#include "spline/tessellate/tessellate.h"

namespace spline {
namespace {

// Number of positions whose used coordinates repeat another used position's bit for bit.
int count_duplicates(const Eigen::MatrixX3d& positions, const std::vector<char>& used) {
  std::vector<std::tuple<double, double, double>> xyz;
  for (Eigen::Index i = 0; i < positions.rows(); ++i) {
    if (used[static_cast<std::size_t>(i)])
      xyz.emplace_back(positions(i, 0), positions(i, 1), positions(i, 2));
  }
  std::sort(xyz.begin(), xyz.end());
  int duplicates = 0;
  for (std::size_t i = 1; i < xyz.size(); ++i) duplicates += xyz[i] == xyz[i - 1];
  return duplicates;
}

// Triangles around each vertex must form one fan: the link map a -> b of corners (v, a, b) is
// one chain or one cycle covering every corner.
int count_nonmanifold_vertices(const std::vector<std::array<int, 3>>& triangles, int n) {
  std::vector<int> start(static_cast<std::size_t>(n) + 1, 0);
  for (const auto& t : triangles)
    for (int v : t) ++start[static_cast<std::size_t>(v) + 1];
  for (int v = 0; v < n; ++v) start[v + 1] += start[v];
  std::vector<std::pair<int, int>> link(static_cast<std::size_t>(start[n]));
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (const auto& t : triangles) {
    for (int k = 0; k < 3; ++k) link[fill[t[k]]++] = {t[(k + 1) % 3], t[(k + 2) % 3]};
  }
  int bad = 0;
  for (int v = 0; v < n; ++v) {
    const auto first = link.begin() + start[v], last = link.begin() + start[v + 1];
    const int count = static_cast<int>(last - first);
    if (count == 0) continue;
    // A chain starts at an `a` that is no corner's `b`.
    int starts = 0;
    auto begin = first;
    for (auto c = first; c != last; ++c) {
      const bool is_target =
          std::any_of(first, last, [&](const auto& o) { return o.second == c->first; });
      if (!is_target) {
        ++starts;
        begin = c;
      }
    }
    if (starts > 1) {
      ++bad;
      continue;
    }
    int steps = 1;
    for (auto c = begin; steps <= count; ++steps) {
      auto next = std::find_if(first, last, [&](const auto& o) { return o.first == c->second; });
      if (next == last || next == begin) break;
      c = next;
    }
    if (steps != count) ++bad;
  }
  return bad;
}

}  // namespace

WatertightReport check_watertight(const std::vector<std::array<int, 3>>& triangles,
                                  const Eigen::MatrixX3d& positions) {
  WatertightReport r;
  const int n = static_cast<int>(positions.rows());
  std::vector<char> used(static_cast<std::size_t>(n), 0);
  std::vector<std::array<int, 3>> valid;
  for (const auto& t : triangles) {
    bool in_range = true;
    for (int v : t) in_range = in_range && v >= 0 && v < n;
    if (!in_range || t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) {
      ++r.degenerate_triangles;
      continue;
    }
    for (int v : t) used[static_cast<std::size_t>(v)] = 1;
    valid.push_back(t);
  }
  r.faces = static_cast<int>(triangles.size());
  for (int i = 0; i < n; ++i) {
    if (!used[static_cast<std::size_t>(i)]) {
      ++r.unused_positions;
      continue;
    }
    ++r.vertices;
    if (!positions.row(i).allFinite()) ++r.non_finite_positions;
  }
  r.duplicate_positions = count_duplicates(positions, used);

  // Directed edges sorted by undirected key: groups of one are boundary, of two must oppose.
  struct Directed {
    int lo, hi;
    bool forward;  // runs lo -> hi
  };
  std::vector<Directed> directed;
  directed.reserve(3 * valid.size());
  for (const auto& t : valid) {
    for (int k = 0; k < 3; ++k) {
      const int a = t[k], b = t[(k + 1) % 3];
      directed.push_back({std::min(a, b), std::max(a, b), a < b});
    }
  }
  std::sort(directed.begin(), directed.end(), [](const Directed& x, const Directed& y) {
    return std::tie(x.lo, x.hi, x.forward) < std::tie(y.lo, y.hi, y.forward);
  });
  std::vector<int> boundary_next(static_cast<std::size_t>(n), -1);
  std::vector<int> boundary_out(static_cast<std::size_t>(n), 0);
  for (std::size_t i = 0; i < directed.size();) {
    std::size_t j = i;
    while (j < directed.size() && directed[j].lo == directed[i].lo &&
           directed[j].hi == directed[i].hi)
      ++j;
    ++r.edges;
    const std::size_t group = j - i;
    if (group == 1) {
      ++r.boundary_edges;
      const int a = directed[i].forward ? directed[i].lo : directed[i].hi;
      const int b = directed[i].forward ? directed[i].hi : directed[i].lo;
      boundary_next[static_cast<std::size_t>(a)] = b;
      ++boundary_out[static_cast<std::size_t>(a)];
    } else if (group == 2) {
      if (directed[i].forward == directed[i + 1].forward) ++r.misoriented_edges;
    } else {
      ++r.nonmanifold_edges;
    }
    i = j;
  }
  r.euler_characteristic = r.vertices - r.edges + r.faces;
  r.nonmanifold_vertices = count_nonmanifold_vertices(valid, n);

  // Boundary loops: follow boundary_next where every boundary vertex has one way out.
  const bool simple =
      std::all_of(boundary_out.begin(), boundary_out.end(), [](int c) { return c <= 1; });
  if (simple) {
    std::vector<char> seen(static_cast<std::size_t>(n), 0);
    for (int v = 0; v < n; ++v) {
      if (boundary_next[v] < 0 || seen[v]) continue;
      int w = v;
      while (w >= 0 && !seen[w]) {
        seen[w] = 1;
        w = boundary_next[w];
      }
      if (w == v) ++r.boundary_loops;
    }
  }
  return r;
}

}  // namespace spline
