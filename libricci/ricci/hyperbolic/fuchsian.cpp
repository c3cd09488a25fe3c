#include "ricci/hyperbolic/fuchsian.h"

#include <string>

#include "ricci/mesh/errors.h"

namespace ricci {
namespace {

/// P_e from the two copies of e's ends: right copy (x1, y1) onto left copy (x0, y0).
MobiusL pair_segments(ComplexL x0, ComplexL y0, ComplexL x1, ComplexL y1, Geometry geometry) {
  if (geometry == Geometry::hyperbolic)
    return disk_to_centre(x0, y0).inverse() * disk_to_centre(x1, y1);
  return plane_to_centre(x0, y0).inverse() * plane_to_centre(x1, y1);
}

/// Walks every arc of the cut graph from a branch vertex (or anywhere on a cycle).
std::vector<CutArc> trace_arcs(const Mesh& mesh, const std::vector<char>& is_cut) {
  std::vector<int> valence(mesh.n_vertices(), 0);
  for (auto e : mesh.edges()) {
    if (!is_cut[e.idx()]) continue;
    ++valence[mesh.from_vertex_handle(mesh.halfedge_handle(e, 0)).idx()];
    ++valence[mesh.to_vertex_handle(mesh.halfedge_handle(e, 0)).idx()];
  }
  std::vector<char> done(mesh.n_edges(), 0);
  std::vector<CutArc> arcs;
  auto walk = [&](HalfedgeHandle h) {
    CutArc arc;
    while (true) {
      arc.halfedges.push_back(h);
      done[mesh.edge_handle(h).idx()] = 1;
      const VertexHandle v = mesh.to_vertex_handle(h);
      if (valence[v.idx()] != 2) break;
      HalfedgeHandle next;
      for (auto g : mesh.voh_range(v)) {
        if (is_cut[mesh.edge_handle(g).idx()] && !done[mesh.edge_handle(g).idx()]) next = g;
      }
      if (!next.is_valid()) break;  // closed cycle
      h = next;
    }
    arcs.push_back(std::move(arc));
  };
  for (auto v : mesh.vertices()) {
    if (valence[v.idx()] == 2 || valence[v.idx()] == 0) continue;
    for (auto g : mesh.voh_range(v)) {
      if (is_cut[mesh.edge_handle(g).idx()] && !done[mesh.edge_handle(g).idx()]) walk(g);
    }
  }
  for (auto e : mesh.edges()) {
    if (is_cut[e.idx()] && !done[e.idx()]) walk(mesh.halfedge_handle(e, 0));
  }
  return arcs;
}

/// For every cut edge: its arc and the sign of P_e in that arc's letter.
struct EdgeLetters {
  std::vector<ArcLetter> letter;  // by edge index; arc -1 for uncut edges
  EdgeLetters(const Mesh& mesh, const DomainPairings& p) : letter(mesh.n_edges(), {-1, 0}) {
    for (size_t a = 0; a < p.arcs.size(); ++a) {
      for (auto h : p.arcs[a].halfedges) {
        const EdgeHandle e = mesh.edge_handle(h);
        letter[e.idx()] = {static_cast<int>(a), h == mesh.halfedge_handle(e, 0) ? 1 : -1};
      }
    }
  }
};

/// Appends the arc crossed (if any) when developing from face(g) across g's edge.
void cross(const Mesh& mesh, const EdgeLetters& letters, HalfedgeHandle g, ArcWord& word) {
  const EdgeHandle e = mesh.edge_handle(g);
  ArcLetter l = letters.letter[e.idx()];
  if (l.arc >= 0) {
    // Leaving face(halfedge(e, 0)) multiplies by P_e on the right, the other way by P_e^-1.
    if (g != mesh.halfedge_handle(e, 0)) l.sign = -l.sign;
    word.push_back(l);
  }
}

/// Develops clockwise around from_vertex(start) from face(start) to face(stop), appending the
/// arcs crossed to `word`.
void turn_clockwise(const Mesh& mesh, const EdgeLetters& letters, HalfedgeHandle start,
                    HalfedgeHandle stop, ArcWord& word) {
  for (auto g = start; g != stop;) {
    cross(mesh, letters, g, word);
    g = mesh.next_halfedge_handle(mesh.opposite_halfedge_handle(g));
  }
}

}  // namespace

DomainPairings domain_pairings(const Mesh& mesh, const CutGraph& cut, const SlicedMesh& sliced,
                               const Eigen::VectorXcd& positions, Geometry geometry,
                               const std::vector<ComplexL>& precise_positions,
                               const std::vector<ComplexQ>& quad_positions) {
  if (geometry == Geometry::spherical) {
    throw InvalidInputError("domain_pairings: the sphere has no side pairings");
  }
  if (positions.size() != static_cast<Eigen::Index>(sliced.mesh.n_vertices()) ||
      cut.is_cut_edge.size() != mesh.n_edges() ||
      (!precise_positions.empty() && precise_positions.size() != sliced.mesh.n_vertices()) ||
      (!quad_positions.empty() &&
       (quad_positions.size() != sliced.mesh.n_vertices() || geometry != Geometry::hyperbolic))) {
    throw InvalidInputError("domain_pairings: positions or cut do not match the meshes");
  }
  DomainPairings result;
  result.is_cut_edge = cut.is_cut_edge;
  result.edge_pairing.assign(mesh.n_edges(), Mobius::identity());
  std::vector<MobiusL> precise_edge_pairing(mesh.n_edges());
  std::vector<MobiusQ> quad_edge_pairing(mesh.n_edges());
  auto position = [&](VertexHandle v) {
    return precise_positions.empty() ? ComplexL(positions[v.idx()])
                                     : precise_positions[static_cast<size_t>(v.idx())];
  };
  for (const CutEdgeSides& s : sliced.cut_sides) {
    const auto& sm = sliced.mesh;
    const ComplexL x0 = position(sm.from_vertex_handle(s.side[0]));
    const ComplexL y0 = position(sm.to_vertex_handle(s.side[0]));
    // side[1] runs the other way (to -> from of the original halfedge 0).
    const ComplexL y1 = position(sm.from_vertex_handle(s.side[1]));
    const ComplexL x1 = position(sm.to_vertex_handle(s.side[1]));
    MobiusQ& quad = quad_edge_pairing[s.edge.idx()];
    if (quad_positions.empty()) {
      quad = MobiusQ(pair_segments(x0, y0, x1, y1, geometry));
    } else {
      const auto q = [&](HalfedgeHandle h, bool from) {
        const VertexHandle v = from ? sm.from_vertex_handle(h) : sm.to_vertex_handle(h);
        return quad_positions[static_cast<size_t>(v.idx())];
      };
      quad = disk_to_centre_q(q(s.side[0], true), q(s.side[0], false)).inverse() *
             disk_to_centre_q(q(s.side[1], false), q(s.side[1], true));
    }
    precise_edge_pairing[s.edge.idx()] = quad.to_long();
    result.edge_pairing[s.edge.idx()] = precise_edge_pairing[s.edge.idx()].to_double();
  }
  result.arcs = trace_arcs(mesh, cut.is_cut_edge);
  std::vector<int> loop_of_edge(mesh.n_edges(), -1);
  for (size_t i = 0; i < cut.loops.size(); ++i) {
    loop_of_edge[mesh.edge_handle(cut.loops[i].generator).idx()] = static_cast<int>(i);
  }
  for (CutArc& arc : result.arcs) {
    std::vector<MobiusQ> maps;
    for (auto h : arc.halfedges) {
      const EdgeHandle e = mesh.edge_handle(h);
      if (loop_of_edge[e.idx()] >= 0) arc.loop = loop_of_edge[e.idx()];
      const MobiusQ& m = quad_edge_pairing[e.idx()];
      maps.push_back(h == mesh.halfedge_handle(e, 0) ? m : m.inverse());
    }
    const Mobius first = maps[0].to_long().to_double();
    for (const MobiusQ& m : maps) {
      arc.spread = std::max(arc.spread, mobius_distance(m.to_long().to_double(), first));
    }
    arc.quad_pairing = mobius_mean_q(maps.data(), static_cast<int>(maps.size()));
    arc.precise_pairing = arc.quad_pairing.to_long();
    arc.pairing = arc.precise_pairing.to_double();
    result.max_spread = std::max(result.max_spread, arc.spread);
  }
  return result;
}

namespace {

/// A double-quad number hi + lo (|lo| <= half an ulp of hi, ~226 bits) with error-free sums
/// and products (Knuth's two-sum, Dekker's split): the relators are multiplied in it. Their
/// partial products reach norm ~1e11 (casting, genus 9), and the rounding of a product in quad
/// precision, amplified by the square of that norm and by the frame, left 7e-9 where the
/// product of the same quad pairings is 3e-14 (long double left 2e-8 on elephant_cgal).
struct ProductReal {
  RealQ hi = 0, lo = 0;

  ProductReal() = default;
  ProductReal(RealQ x) : hi(x) {}  // NOLINT(google-explicit-constructor): exact
  ProductReal(int x) : hi(x) {}    // NOLINT(google-explicit-constructor): exact
  static ProductReal renormalised(RealQ a, RealQ b) {
    ProductReal r;
    r.hi = a + b;
    r.lo = b - (r.hi - a);
    return r;
  }
  static ProductReal two_sum(RealQ a, RealQ b) {
    ProductReal r;
    r.hi = a + b;
    const RealQ bb = r.hi - a;
    r.lo = (a - (r.hi - bb)) + (b - bb);
    return r;
  }
  static void split(RealQ a, RealQ& high, RealQ& low) {
#ifdef __SIZEOF_FLOAT128__
    const RealQ splitter = RealQ(144115188075855873.0L);  // 2^57 + 1 (113-bit mantissa)
#else
    const RealQ splitter = RealQ(4294967297.0L);  // 2^32 + 1 (64-bit mantissa)
#endif
    const RealQ t = splitter * a;
    high = t - (t - a);
    low = a - high;
  }
  static ProductReal two_product(RealQ a, RealQ b) {
    RealQ ah, al, bh, bl;
    split(a, ah, al);
    split(b, bh, bl);
    ProductReal r;
    r.hi = a * b;
    r.lo = ((ah * bh - r.hi) + ah * bl + al * bh) + al * bl;
    return r;
  }
  ProductReal operator+(const ProductReal& b) const {
    const ProductReal s = two_sum(hi, b.hi);
    return renormalised(s.hi, s.lo + lo + b.lo);
  }
  ProductReal operator-() const {
    ProductReal r;
    r.hi = -hi;
    r.lo = -lo;
    return r;
  }
  ProductReal operator-(const ProductReal& b) const { return *this + (-b); }
  ProductReal operator*(const ProductReal& b) const {
    const ProductReal p = two_product(hi, b.hi);
    return renormalised(p.hi, p.lo + (hi * b.lo + lo * b.hi));
  }
  explicit operator long double() const {
    return static_cast<long double>(hi) + static_cast<long double>(lo);
  }
};

/// A 2x2 complex matrix in ProductReal: the relators are multiplied in it.
struct ProductMatrix {
  ProductReal re[2][2] = {{1, 0}, {0, 1}}, im[2][2] = {{0, 0}, {0, 0}};

  ProductMatrix() = default;
  explicit ProductMatrix(const MobiusL& a) {
    for (int i = 0; i < 2; ++i) {
      for (int j = 0; j < 2; ++j) {
        re[i][j] = RealQ(a.m(i, j).real());
        im[i][j] = RealQ(a.m(i, j).imag());
      }
    }
  }
  explicit ProductMatrix(const MobiusQ& a) {
    const ComplexQ* entries[2][2] = {{&a.a, &a.b}, {&a.c, &a.d}};
    for (int i = 0; i < 2; ++i) {
      for (int j = 0; j < 2; ++j) {
        re[i][j] = entries[i][j]->re;
        im[i][j] = entries[i][j]->im;
      }
    }
  }
  ProductMatrix operator*(const ProductMatrix& b) const {
    ProductMatrix c;
    for (int i = 0; i < 2; ++i) {
      for (int j = 0; j < 2; ++j) {
        c.re[i][j] = re[i][0] * b.re[0][j] - im[i][0] * b.im[0][j] + re[i][1] * b.re[1][j] -
                     im[i][1] * b.im[1][j];
        c.im[i][j] = re[i][0] * b.im[0][j] + im[i][0] * b.re[0][j] + re[i][1] * b.im[1][j] +
                     im[i][1] * b.re[1][j];
      }
    }
    return c;
  }
  /// min over the sign of ||M -+ I||_F.
  [[nodiscard]] double distance_to_identity() const {
    long double minus = 0, plus = 0;
    for (int i = 0; i < 2; ++i) {
      for (int j = 0; j < 2; ++j) {
        const ProductReal id = i == j ? 1 : 0;
        const long double dm = static_cast<long double>(re[i][j] - id);
        const long double dp = static_cast<long double>(re[i][j] + id);
        const long double di = static_cast<long double>(im[i][j]);
        minus += dm * dm + di * di;
        plus += dp * dp + di * di;
      }
    }
    return static_cast<double>(std::sqrt(std::min(minus, plus)));
  }
};

/// The point c among `candidates` whose images under the prefixes of `word` stay closest to it
/// (smallest max over prefixes g of |g|_c, the norm of g in the frame centred at c).
Complex best_frame_centre(const DomainPairings& pairings, const ArcWord& word,
                          const std::vector<Complex>& candidates) {
  Complex best = 0.0;
  double best_size = INFINITY;
  for (const Complex& c : candidates) {
    const Mobius to_c = Mobius::from_rotation_point(0.0, c);
    Mobius prefix;
    double size = 0.0;
    for (const ArcLetter& l : word) {
      const Mobius& m = pairings.arcs[static_cast<size_t>(l.arc)].pairing;
      prefix = prefix * (l.sign > 0 ? m : m.inverse());
      size = std::max(size, (to_c * prefix * to_c.inverse()).m.norm());
      if (size >= best_size) break;
    }
    if (size < best_size) {
      best_size = size;
      best = c;
    }
  }
  return best;
}

/// distance_to_identity of the word's product (not reduced) in the frame centred at c,
/// multiplied in ProductReal. The product is taken first and conjugated once: conjugating each
/// factor multiplies the frame's own rounding (its determinant is 1 only to eps ||to_c||^2,
/// 1e-29 near the rim) by every factor's norm, which left 1e-14 on corners of casting whose
/// cycles close to 2e-19; double-quad carries the prefixes' norms (e^{d/2}) without that.
double residual_in_frame(const DomainPairings& pairings, const ArcWord& w, Complex c) {
  const MobiusQ to_c = MobiusQ(MobiusL::from_rotation_point(0.0L, ComplexL(c))).normalised();
  ProductMatrix product;
  for (const ArcLetter& l : w) {
    const MobiusQ& m = pairings.arcs[static_cast<size_t>(l.arc)].quad_pairing;
    product = product * ProductMatrix(l.sign > 0 ? m : m.inverse());
  }
  return (ProductMatrix(to_c) * product * ProductMatrix(to_c.inverse())).distance_to_identity();
}

}  // namespace

double conditioned_residual(const DomainPairings& pairings, const ArcWord& word,
                            const std::vector<Complex>& candidates) {
  const ArcWord w = cyclically_reduced(word);
  return residual_in_frame(pairings, w, best_frame_centre(pairings, w, candidates));
}

std::vector<VertexCycle> vertex_cycles(const Mesh& mesh, const CutGraph& cut,
                                       const SlicedMesh& sliced, const DomainPairings& pairings,
                                       const Eigen::VectorXcd& positions) {
  if (positions.size() != static_cast<Eigen::Index>(sliced.mesh.n_vertices()) ||
      cut.is_cut_edge.size() != mesh.n_edges()) {
    throw InvalidInputError("vertex_cycles: positions or cut do not match the meshes");
  }
  const EdgeLetters letters(mesh, pairings);
  std::vector<VertexCycle> cycles;
  for (auto v : mesh.vertices()) {
    int valence = 0;
    for (auto e : mesh.ve_range(v)) valence += cut.is_cut_edge[e.idx()] ? 1 : 0;
    if (valence < 3 || mesh.is_boundary(v)) continue;
    const HalfedgeHandle start = *mesh.voh_range(v).begin();
    VertexCycle cycle;
    cycle.vertex = v.idx();
    cross(mesh, letters, start, cycle.word);
    turn_clockwise(mesh, letters, mesh.next_halfedge_handle(mesh.opposite_halfedge_handle(start)),
                   start, cycle.word);
    // v's copy in face(start): the corner that prev(start) enters.
    const int copy =
        sliced.corner_vertex[static_cast<size_t>(mesh.prev_halfedge_handle(start).idx())];
    cycle.centre = positions[copy];
    cycles.push_back(std::move(cycle));
  }
  return cycles;
}

double vertex_cycle_residual(const DomainPairings& pairings,
                             const std::vector<VertexCycle>& cycles) {
  double worst = 0.0;
  for (const VertexCycle& c : cycles) {
    worst = std::max(worst, residual_in_frame(pairings, c.word, c.centre));
  }
  return worst;
}

ArcWord freely_reduced(const ArcWord& word) {
  ArcWord out;
  for (const ArcLetter& l : word) {
    if (!out.empty() && out.back().arc == l.arc && out.back().sign == -l.sign) {
      out.pop_back();
    } else {
      out.push_back(l);
    }
  }
  return out;
}

ArcWord cyclically_reduced(const ArcWord& word) {
  ArcWord w = freely_reduced(word);
  size_t begin = 0, end = w.size();
  while (end - begin >= 2 && w[begin].arc == w[end - 1].arc && w[begin].sign == -w[end - 1].sign) {
    ++begin;
    --end;
  }
  return ArcWord(w.begin() + static_cast<std::ptrdiff_t>(begin),
                 w.begin() + static_cast<std::ptrdiff_t>(end));
}

Mobius evaluate(const DomainPairings& pairings, const ArcWord& word) {
  MobiusQ product;
  for (const ArcLetter& l : word) {
    const MobiusQ& m = pairings.arcs.at(static_cast<size_t>(l.arc)).quad_pairing;
    product = product * (l.sign > 0 ? m : m.inverse());
  }
  return product.to_long().to_double();
}

std::vector<ArcWord> loop_arc_words(const Mesh& mesh, const CutGraph& cut,
                                    const DomainPairings& pairings) {
  if (cut.boundary_loop_count > 0) {
    throw InvalidInputError("loop_arc_words: the surface has boundary (take its double cover)");
  }
  const EdgeLetters letters(mesh, pairings);
  std::vector<ArcWord> result;
  const HalfedgeHandle reference = *mesh.voh_range(cut.root).begin();
  for (const CutPath& loop : cut.loops) {
    const auto& hs = loop.halfedges;
    ArcWord word;
    turn_clockwise(mesh, letters, reference, hs.front(), word);
    for (size_t k = 0; k + 1 < hs.size(); ++k) {
      turn_clockwise(mesh, letters, mesh.next_halfedge_handle(hs[k]), hs[k + 1], word);
    }
    turn_clockwise(mesh, letters, mesh.next_halfedge_handle(hs.back()), reference, word);
    result.push_back(freely_reduced(word));
  }
  return result;
}

ArcWord arc_word(const std::vector<ArcWord>& loop_words, const LoopWord& word) {
  ArcWord out;
  for (const PolygonLetter& l : word) {
    if (l.kind != PolygonLetter::Kind::loop) continue;
    const ArcWord& w = loop_words.at(static_cast<size_t>(l.index));
    if (l.sign > 0) {
      out.insert(out.end(), w.begin(), w.end());
    } else {
      for (auto it = w.rbegin(); it != w.rend(); ++it) out.push_back({it->arc, -it->sign});
    }
  }
  return freely_reduced(out);
}

double relation_residual(const std::vector<Mobius>& generators) {
  if (generators.size() % 2 != 0) {
    throw InvalidInputError("relation_residual: an odd number of generators");
  }
  Mobius product;
  for (size_t i = 0; i + 1 < generators.size(); i += 2) {
    const Mobius& a = generators[i];
    const Mobius& b = generators[i + 1];
    product = product * a * b * a.inverse() * b.inverse();
  }
  return distance_to_identity(product);
}

HolonomyGroup holonomy_group(const Mesh& mesh, const CutGraph& cut, const SlicedMesh& sliced,
                             const DomainPairings& pairings, const Eigen::VectorXcd& positions) {
  HolonomyGroup group;
  group.polygon = fundamental_polygon_word(mesh, cut, sliced);
  group.loop_words = loop_arc_words(mesh, cut, pairings);
  for (const ArcWord& w : group.loop_words) group.loop_holonomy.push_back(evaluate(pairings, w));
  std::vector<Complex> candidates{0.0};
  const Eigen::Index stride = std::max<Eigen::Index>(1, positions.size() / 64);
  for (Eigen::Index i = 0; i < positions.size(); i += stride) candidates.push_back(positions[i]);
  group.polygon_residual =
      conditioned_residual(pairings, arc_word(group.loop_words, group.polygon.word), candidates);
  group.basis = canonical_basis(group.polygon.word);
  for (size_t i = 0; i < group.basis.generators.size(); ++i) {
    group.generator_words.push_back(arc_word(group.loop_words, group.basis.generators[i]));
    group.generators.push_back(evaluate(pairings, group.generator_words.back()));
  }
  ArcWord relation;
  for (size_t i = 0; i + 1 < group.generator_words.size(); i += 2) {
    const ArcWord& a = group.generator_words[i];
    const ArcWord& b = group.generator_words[i + 1];
    for (const ArcWord* w : {&a, &b}) relation.insert(relation.end(), w->begin(), w->end());
    for (const ArcWord* w : {&a, &b}) {
      for (auto it = w->rbegin(); it != w->rend(); ++it) relation.push_back({it->arc, -it->sign});
    }
  }
  group.relation_residual = conditioned_residual(pairings, relation, candidates);
  group.relation_residual_direct = relation_residual(group.generators);
  if (positions.size() > 0) {
    group.cycle_residual =
        vertex_cycle_residual(pairings, vertex_cycles(mesh, cut, sliced, pairings, positions));
  }
  return group;
}

}  // namespace ricci
