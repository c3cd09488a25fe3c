#pragma once
// The sides of a triangle list grouped by edge, in linear time (dihedral angles, the tessellation's
// refinement).
#include <array>
#include <cstdint>
#include <utility>
#include <vector>

namespace spline {

/// Every side (the edge from corner k to corner k + 1) of every triangle t not skipped, as
/// (min << 32 | max of its vertices, t), ordered by key and then by t: the order std::sort gives
/// the pairs, by counting sort on the smaller vertex. `skip`: by triangle, nonzero to leave it
/// out (empty: none).
/// \pre every vertex index of a triangle not skipped is in [0, vertex_count).
[[nodiscard]] std::vector<std::pair<std::uint64_t, int>> sorted_triangle_sides(
    const std::vector<std::array<int, 3>>& triangles, const std::vector<char>& skip,
    int vertex_count);

}  // namespace spline
