// The undirected-edge table: a counting sort of all polygon sides by their lower vertex, then a
// small sort inside each bucket; linear in practice, and several times faster than a hash map.
#include "ricci/mesh/topology_util.h"

#include <algorithm>

namespace ricci::detail {

EdgeTable build_edge_table(const std::vector<std::vector<int>>& faces,
                           const std::vector<char>& use_face) {
  auto used = [&](size_t f) { return use_face.empty() || use_face[f]; };
  int max_vertex = -1;
  for (size_t f = 0; f < faces.size(); ++f)
    if (used(f))
      for (int v : faces[f]) max_vertex = std::max(max_vertex, v);
  std::vector<size_t> bucket(static_cast<size_t>(max_vertex) + 2, 0);
  for (size_t f = 0; f < faces.size(); ++f) {
    if (!used(f)) continue;
    const auto& face = faces[f];
    for (size_t k = 0; k < face.size(); ++k)
      ++bucket[std::min(face[k], face[(k + 1) % face.size()]) + 1];
  }
  for (size_t b = 1; b < bucket.size(); ++b) bucket[b] += bucket[b - 1];
  std::vector<FaceSide> sides(bucket.back());
  std::vector<size_t> fill(bucket.begin(), bucket.end() - 1);
  for (size_t f = 0; f < faces.size(); ++f) {  // faces in order: buckets start sorted by face
    if (!used(f)) continue;
    const auto& face = faces[f];
    for (size_t k = 0; k < face.size(); ++k) {
      const int a = face[k], b = face[(k + 1) % face.size()];
      sides[fill[std::min(a, b)]++] = {static_cast<int>(f), a, b};
    }
  }
  EdgeTable table;
  auto high = [](const FaceSide& s) { return std::max(s.from, s.to); };
  for (size_t b = 0; b + 1 < bucket.size(); ++b) {
    const auto first = sides.begin() + static_cast<std::ptrdiff_t>(bucket[b]);
    const auto last = sides.begin() + static_cast<std::ptrdiff_t>(bucket[b + 1]);
    // Stable: sides of one edge stay in face order, so messages list faces in file order.
    std::stable_sort(first, last,
                     [&](const FaceSide& x, const FaceSide& y) { return high(x) < high(y); });
    for (auto it = first; it != last; ++it)
      if (it == first || high(*it) != high(*(it - 1)))
        table.edge_begin.push_back(static_cast<size_t>(it - sides.begin()));
  }
  if (!table.edge_begin.empty()) table.edge_begin.push_back(sides.size());
  table.sides = std::move(sides);
  return table;
}

OrientationColouring colour_orientation(const EdgeTable& table, size_t face_count,
                                        const std::vector<char>& use_face) {
  // Adjacency over 2-face edges in CSR form: (neighbour, edge, must it be flipped relative to us).
  struct Link {
    int face;
    int edge;
    bool flip;
  };
  std::vector<size_t> begin(face_count + 1, 0);
  for (size_t e = 0; e < table.edge_count(); ++e) {
    if (table.side_count(e) != 2) continue;
    ++begin[table.side(e, 0).face + 1];
    ++begin[table.side(e, 1).face + 1];
  }
  for (size_t f = 0; f < face_count; ++f) begin[f + 1] += begin[f];
  std::vector<Link> links(begin.back());
  std::vector<size_t> fill(begin.begin(), begin.end() - 1);
  for (size_t e = 0; e < table.edge_count(); ++e) {
    if (table.side_count(e) != 2) continue;
    const auto& s0 = table.side(e, 0);
    const auto& s1 = table.side(e, 1);
    const bool flip = s0.from == s1.from;  // same direction: one of the two must turn over
    links[fill[s0.face]++] = {s1.face, static_cast<int>(e), flip};
    links[fill[s1.face]++] = {s0.face, static_cast<int>(e), flip};
  }
  OrientationColouring result;
  result.flipped.assign(face_count, -1);
  std::vector<int> stack;
  for (size_t seed = 0; seed < face_count; ++seed) {
    if ((!use_face.empty() && !use_face[seed]) || result.flipped[seed] >= 0) continue;
    result.flipped[seed] = 0;
    stack.push_back(static_cast<int>(seed));
    while (!stack.empty()) {
      const int f = stack.back();
      stack.pop_back();
      for (size_t k = begin[f]; k < begin[f + 1]; ++k) {
        const Link& link = links[k];
        const auto want = static_cast<signed char>(result.flipped[f] ^ link.flip);
        if (result.flipped[link.face] < 0) {
          result.flipped[link.face] = want;
          stack.push_back(link.face);
        } else if (result.flipped[link.face] != want && result.conflict_edge < 0) {
          result.conflict_edge = link.edge;
        }
      }
    }
  }
  return result;
}

}  // namespace ricci::detail
