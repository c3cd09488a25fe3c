// The undirected-edge table: a sort of all polygon sides, cheaper than a hash map at 100k faces.
#include "ricci/mesh/topology_util.h"

#include <algorithm>

namespace ricci::detail {

EdgeTable build_edge_table(const std::vector<std::vector<int>>& faces,
                           const std::vector<char>& use_face) {
  struct Keyed {
    uint64_t key;
    FaceSide side;
  };
  std::vector<Keyed> keyed;
  size_t total = 0;
  for (const auto& face : faces) total += face.size();
  keyed.reserve(total);
  for (size_t f = 0; f < faces.size(); ++f) {
    if (!use_face.empty() && !use_face[f]) continue;
    const auto& face = faces[f];
    for (size_t k = 0; k < face.size(); ++k) {
      const int a = face[k], b = face[(k + 1) % face.size()];
      const auto lo = static_cast<uint64_t>(static_cast<uint32_t>(std::min(a, b)));
      const auto hi = static_cast<uint64_t>(static_cast<uint32_t>(std::max(a, b)));
      keyed.push_back({(lo << 32) | hi, {static_cast<int>(f), a, b}});
    }
  }
  // Stable on (key, face) so messages list faces in file order.
  std::sort(keyed.begin(), keyed.end(), [](const Keyed& x, const Keyed& y) {
    return x.key != y.key ? x.key < y.key : x.side.face < y.side.face;
  });
  EdgeTable table;
  table.sides.reserve(keyed.size());
  for (size_t i = 0; i < keyed.size(); ++i) {
    if (i == 0 || keyed[i].key != keyed[i - 1].key) table.edge_begin.push_back(i);
    table.sides.push_back(keyed[i].side);
  }
  table.edge_begin.push_back(keyed.size());
  if (keyed.empty()) table.edge_begin.clear();
  return table;
}

}  // namespace ricci::detail
