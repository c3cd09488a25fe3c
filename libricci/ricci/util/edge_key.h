#pragma once
// An undirected edge as one sortable integer, the one helper for it (edge sets and sorted edge
// lists over vertex indices).
#include <algorithm>
#include <cstdint>

namespace ricci {

/// The edge {a, b} as min(a, b) << 32 | max(a, b): the same key for (a, b) and (b, a); keys
/// order edges by their smaller end, then their larger one.
/// \pre a >= 0 and b >= 0 (vertex indices).
[[nodiscard]] constexpr std::uint64_t undirected_edge_key(int a, int b) {
  return static_cast<std::uint64_t>(static_cast<std::uint32_t>(std::min(a, b))) << 32 |
         static_cast<std::uint32_t>(std::max(a, b));
}

}  // namespace ricci
