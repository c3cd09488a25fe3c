#include "ricci/topology/polygon_word.h"

#include <algorithm>
#include <string>

#include "ricci/mesh/errors.h"

namespace ricci {

bool is_canonical_word(const std::vector<PolygonLetter>& w, std::vector<int>* order) {
  const size_t n = w.size();
  if (n % 4 != 0) return false;
  if (n == 0) {
    if (order) order->clear();
    return true;
  }
  auto inverse = [](PolygonLetter a, PolygonLetter b) { return a.index == b.index && a.sign == -b.sign; };
  for (size_t shift = 0; shift < 4; ++shift) {
    bool ok = true;
    std::vector<int> found;
    for (size_t k = 0; ok && k < n; k += 4) {
      const auto& x = w[(shift + k) % n];
      const auto& y = w[(shift + k + 1) % n];
      ok = x.index != y.index && inverse(x, w[(shift + k + 2) % n]) &&
           inverse(y, w[(shift + k + 3) % n]);
      found.push_back(x.index);
      found.push_back(y.index);
    }
    if (ok) {
      if (order) *order = found;
      return true;
    }
  }
  return false;
}

FundamentalPolygon fundamental_polygon_word(const Mesh& mesh, const CutGraph& cut,
                                            const SlicedMesh& sliced) {
  const Mesh& disk = sliced.mesh;
  std::vector<int> loop_of_edge(mesh.n_edges(), -1);
  for (size_t i = 0; i < cut.loops.size(); ++i) {
    loop_of_edge[mesh.edge_handle(cut.loops[i].generator).idx()] = static_cast<int>(i);
  }
  HalfedgeHandle start;
  for (auto h : disk.halfedges()) {
    if (disk.is_boundary(h)) {
      start = h;
      break;
    }
  }
  if (!start.is_valid()) throw TopologyError("polygon word: the sliced mesh has no boundary");
  // Boundary halfedges run clockwise around the disk; reversed and flipped to their inner
  // twins they run counter-clockwise with the interior on the left.
  std::vector<HalfedgeHandle> ccw;
  for (auto h = start;;) {
    ccw.push_back(disk.opposite_halfedge_handle(h));
    h = disk.next_halfedge_handle(h);
    if (h == start) break;
  }
  std::reverse(ccw.begin(), ccw.end());

  FundamentalPolygon polygon;
  std::vector<PolygonLetter> loop_letters;
  for (auto inner : ccw) {
    const HalfedgeHandle h(sliced.to_original_halfedge[inner.idx()]);
    const auto e = mesh.edge_handle(h);
    PolygonLetter letter;
    if (mesh.is_boundary(e)) {
      letter.kind = PolygonLetter::Kind::boundary;
      const auto outer = mesh.opposite_halfedge_handle(h);
      letter.index = cut.boundary_loop_of_vertex[mesh.to_vertex_handle(outer).idx()];
      if (!polygon.word.empty() && polygon.word.back() == letter) continue;
    } else if (loop_of_edge[e.idx()] >= 0) {
      letter.index = loop_of_edge[e.idx()];
      letter.sign = h == cut.loops[letter.index].generator ? 1 : -1;
      loop_letters.push_back(letter);
    } else {
      continue;
    }
    polygon.word.push_back(letter);
  }
  // A boundary run split by the starting point appears at both ends: merge it.
  if (polygon.word.size() > 1 && polygon.word.front() == polygon.word.back() &&
      polygon.word.front().kind == PolygonLetter::Kind::boundary) {
    polygon.word.pop_back();
  }
  std::vector<int> plus(cut.loops.size(), 0), minus(cut.loops.size(), 0);
  for (const auto& l : loop_letters) ++(l.sign > 0 ? plus : minus)[l.index];
  for (size_t i = 0; i < cut.loops.size(); ++i) {
    if (plus[i] != 1 || minus[i] != 1) {
      throw TopologyError("polygon word: loop " + std::to_string(i) + " appears " +
                          std::to_string(plus[i]) + "+" + std::to_string(minus[i]) +
                          " times on the disk boundary (expected once each way)");
    }
  }
  polygon.canonical = is_canonical_word(loop_letters, &polygon.canonical_order);
  return polygon;
}

}  // namespace ricci
