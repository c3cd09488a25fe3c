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

namespace ricci {
namespace {

LoopWord inverse(const LoopWord& w) {
  LoopWord r(w.rbegin(), w.rend());
  for (auto& l : r) l.sign = -l.sign;
  return r;
}

LoopWord slice(const LoopWord& w, size_t begin, size_t end) {
  return begin < end ? LoopWord(w.begin() + begin, w.begin() + end) : LoopWord{};
}

LoopWord concat(std::initializer_list<LoopWord> parts) {
  LoopWord r;
  for (const auto& p : parts) r.insert(r.end(), p.begin(), p.end());
  return r;
}

bool is_inverse(const PolygonLetter& a, const PolygonLetter& b) {
  return a.index == b.index && a.sign == -b.sign;
}

}  // namespace

LoopWord cyclically_reduced(LoopWord word) {
  LoopWord stack;
  for (const auto& l : word) {
    if (!stack.empty() && is_inverse(stack.back(), l)) {
      stack.pop_back();
    } else {
      stack.push_back(l);
    }
  }
  size_t begin = 0, end = stack.size();
  while (end - begin >= 2 && is_inverse(stack[begin], stack[end - 1])) {
    ++begin;
    --end;
  }
  return slice(stack, begin, end);
}

bool same_cyclic_word(const LoopWord& a, const LoopWord& b) {
  if (a.size() != b.size()) return false;
  if (a.empty()) return true;
  for (size_t shift = 0; shift < a.size(); ++shift) {
    bool equal = true;
    for (size_t i = 0; equal && i < a.size(); ++i) equal = a[(i + shift) % a.size()] == b[i];
    if (equal) return true;
  }
  return false;
}

CanonicalBasis canonical_basis(const std::vector<PolygonLetter>& word) {
  LoopWord rest;
  for (const auto& l : word) {
    if (l.kind == PolygonLetter::Kind::loop) rest.push_back(l);
  }
  CanonicalBasis basis;
  // Invariant: the original relator is (cyclically) [a1,b1]...[ak,bk] rest, with the ai, bi
  // expanded to their words; each step moves one linked pair of `rest` into a commutator.
  while (!rest.empty()) {
    const auto x = rest.front();
    size_t x_inv = 0;
    for (size_t i = 1; i < rest.size(); ++i) {
      if (is_inverse(rest[i], x)) x_inv = i;
    }
    if (x_inv == 0) {
      throw TopologyError("canonical basis: loop " + std::to_string(x.index) +
                          " does not appear once each way in the polygon word");
    }
    size_t y_pos = 0, y_inv = 0;
    for (size_t i = 1; i < x_inv && y_pos == 0; ++i) {
      for (size_t j = x_inv + 1; j < rest.size(); ++j) {
        if (is_inverse(rest[j], rest[i])) {
          y_pos = i;
          y_inv = j;
        }
      }
    }
    if (y_pos == 0) {
      throw TopologyError("canonical basis: loop " + std::to_string(x.index) +
                          " is linked with no other loop (not a one-vertex surface word)");
    }
    // rest = x B y C x^-1 D y^-1 T
    const LoopWord b = slice(rest, 1, y_pos), c = slice(rest, y_pos + 1, x_inv),
                   d = slice(rest, x_inv + 1, y_inv), t = slice(rest, y_inv + 1, rest.size());
    const LoopWord y{rest[y_pos]};
    basis.generators.push_back(concat({LoopWord{x}, inverse(c), inverse(d)}));
    basis.generators.push_back(concat({d, c, b, y, inverse(d)}));
    rest = concat({d, c, b, t});
  }
  return basis;
}

}  // namespace ricci
