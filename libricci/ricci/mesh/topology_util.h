#pragma once
// Internal: the undirected-edge table and union-find shared by diagnose() and build_mesh().
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <vector>

namespace ricci::detail {

/// Union-find with path halving; elements are 0..n-1.
class DisjointSets {
 public:
  explicit DisjointSets(size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }
  int find(int x) {
    while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
    return x;
  }
  bool unite(int a, int b) {
    a = find(a);
    b = find(b);
    if (a == b) return false;
    parent_[a] = b;
    return true;
  }

 private:
  std::vector<int> parent_;
};

/// One side of a polygon edge: face `face` walks from `from` to `to`.
struct FaceSide {
  int face;
  int from;
  int to;
};

/// Every polygon side grouped by undirected edge (sorted by (min, max) vertex index).
struct EdgeTable {
  std::vector<FaceSide> sides;     // grouped by edge
  std::vector<size_t> edge_begin;  // edge e owns sides[edge_begin[e] .. edge_begin[e + 1])
  size_t edge_count() const { return edge_begin.empty() ? 0 : edge_begin.size() - 1; }
  size_t side_count(size_t e) const { return edge_begin[e + 1] - edge_begin[e]; }
  const FaceSide& side(size_t e, size_t k) const { return sides[edge_begin[e] + k]; }
  int low(size_t e) const {
    const auto& s = sides[edge_begin[e]];
    return s.from < s.to ? s.from : s.to;
  }
  int high(size_t e) const {
    const auto& s = sides[edge_begin[e]];
    return s.from < s.to ? s.to : s.from;
  }
};

/// Builds the table over the faces with `use_face[f]` true (all when `use_face` is empty).
EdgeTable build_edge_table(const std::vector<std::vector<int>>& faces,
                           const std::vector<char>& use_face);

/// Consistent orientation by 2-colouring faces across every 2-face edge: `flipped[f]` = 1 when
/// face f must be reversed to agree with the first face of its component (-1 for faces not
/// used); `conflict_edge` is the first edge where the colouring clashes (non-orientable), or -1.
struct OrientationColouring {
  std::vector<signed char> flipped;
  int conflict_edge = -1;
};
[[nodiscard]] OrientationColouring colour_orientation(const EdgeTable& table, size_t face_count,
                                                      const std::vector<char>& use_face);

}  // namespace ricci::detail
