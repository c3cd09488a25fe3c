#include "spline/basis/simplex_spline.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <emmintrin.h>
#include <limits>
#include <string>

#include "ricci/mesh/errors.h"
#include "ricci/util/cross2d.h"

namespace spline {
namespace {

int popcount(std::uint32_t mask) { return __builtin_popcount(mask); }

void put_longest_opposite_first(const std::vector<Eigen::Vector2d>& knots, int& a, int& b, int& c) {
  // lambda_a's gradient is derived as -(g_b + g_c); it is the largest of the three (the one
  // opposite the longest edge), so the sum does not cancel. Deriving a small one would lose
  // digits in proportion to the triangle's aspect ratio (cloud radius / edge length).
  const double opposite_a = (knots[c] - knots[b]).squaredNorm();
  const double opposite_b = (knots[a] - knots[c]).squaredNorm();
  const double opposite_c = (knots[b] - knots[a]).squaredNorm();
  if (opposite_b > opposite_a && opposite_b >= opposite_c) {
    const int t = a;
    a = b, b = c, c = t;
  } else if (opposite_c > opposite_a && opposite_c > opposite_b) {
    const int t = c;
    c = b, b = a, a = t;
  }
}

// The largest float <= x (x finite): the box of a node only culls, so a float box rounded
// outwards is enough.
float float_below(double x) {
  const float f = static_cast<float>(x);
  if (static_cast<double>(f) <= x) return f;
  // One float step towards -infinity, as std::nextafter(f, -inf) but inline: the libm call was
  // 3% of building a triangle's DAG (msp-bench dms under callgrind). f > x is finite or +inf.
  std::uint32_t bits = 0;
  std::memcpy(&bits, &f, sizeof bits);
  if (f > 0.0f) {
    --bits;  // towards zero
  } else if (f < 0.0f) {
    ++bits;  // away from zero
  } else {
    bits = 0x80000001u;  // below +-0: the negative smallest subnormal
  }
  float below = 0.0f;
  std::memcpy(&below, &bits, sizeof below);
  return below;
}

// A recurrence node's barycentric gradients (g_a, g_b, g_c) of its triple from its data:
// g_b = data[0..1], g_c = data[2..3], g_a = -g_b - g_c (SimplexSplineDag::Node).
std::array<Eigen::Vector2d, 3> triple_gradients(const double (&data)[4]) {
  const Eigen::Vector2d g_b(data[0], data[1]), g_c(data[2], data[3]);
  return {Eigen::Vector2d(-g_b - g_c), g_b, g_c};
}

}  // namespace

SimplexSplineDag::SimplexSplineDag(std::vector<Eigen::Vector2d> knots) : knots_(std::move(knots)) {
  if (knots_.size() > 32) {
    throw ricci::InvalidInputError("simplex spline: " + std::to_string(knots_.size()) +
                                   " knots, at most 32 supported");
  }
  for (std::size_t i = 0; i < knots_.size(); ++i) {
    if (!knots_[i].allFinite()) {
      throw ricci::InvalidInputError("simplex spline: knot " + std::to_string(i) +
                                     " is not finite");
    }
  }
}

int SimplexSplineDag::add(std::uint32_t mask) {
  const int id = add_node(mask);
  Node& node = nodes_[static_cast<std::size_t>(id)];
  node.root = true;
  roots_.push_back(id);
  // evaluate_roots' gradient pass: the root's gradient and, for its Hessian, its children's.
  // Base and zero nodes have zero gradients and are left out.
  const auto mark = [this](int marked) {
    Node& n = nodes_[static_cast<std::size_t>(marked)];
    if (n.kind != Kind::recurrence || n.gradient) return;
    n.gradient = true;
    gradient_ids_.push_back(static_cast<std::uint16_t>(marked));
  };
  mark(id);
  for (const std::uint16_t child : node.child) {
    if (child != kNoChild) mark(child);
  }
  return id;
}

void SimplexSplineDag::prepare_build_caches() {
  if (!areas_.empty()) return;
  const std::size_t k = knots_.size();
  areas_.assign(k * k * k, 0.0);
  dets_.assign(k * k * k, std::numeric_limits<double>::quiet_NaN());
  for (std::size_t x = 0; x < k; ++x) {
    for (std::size_t y = x + 1; y < k; ++y) {
      const Eigen::Vector2d e1 = knots_[y] - knots_[x];
      for (std::size_t z = y + 1; z < k; ++z) {
        areas_[(x * k + y) * k + z] = std::abs(ricci::cross2d(e1, knots_[z] - knots_[x]));
      }
    }
  }
  if (k <= kDirectIndexKnots) direct_index_.assign(std::size_t{1} << k, 0);
  // Rounding outwards is monotonic, so a node's box is the min / max of its knots' rounded
  // coordinates: rounded once per knot here, not once per node (4 roundings per node were 40%
  // of the largest-triple search).
  knot_floor_.resize(k);
  knot_ceil_.resize(k);
  for (std::size_t i = 0; i < k; ++i) {
    knot_floor_[i] = {float_below(knots_[i].x()), float_below(knots_[i].y())};
    knot_ceil_[i] = {-float_below(-knots_[i].x()), -float_below(-knots_[i].y())};
  }
}

double SimplexSplineDag::determinant(int a, int b, int c) {
  const std::size_t k = knots_.size();
  double& det = dets_[(static_cast<std::size_t>(a) * k + static_cast<std::size_t>(b)) * k +
                      static_cast<std::size_t>(c)];
  if (std::isnan(det)) det = accurate_det2d(knots_[a], knots_[b], knots_[c]);
  return det;
}

int SimplexSplineDag::add_node(std::uint32_t mask) {
  prepare_build_caches();
  if (!direct_index_.empty()) {
    if (mask < direct_index_.size() && direct_index_[mask] != 0) return direct_index_[mask] - 1;
  } else if (const auto it = index_.find(mask); it != index_.end()) {
    return it->second;
  }
  const int count = popcount(mask);
  if (count < 3 || (knots_.size() < 32 && (mask >> knots_.size()) != 0)) {
    throw ricci::InvalidInputError("simplex spline: knot subset needs at least 3 valid knots");
  }
  if (nodes_.size() >= kNoChild) {
    throw ricci::InvalidInputError("simplex spline: too many knot subsets in one DAG");
  }
  Node node;
  node.degree = static_cast<std::uint8_t>(count - 3);
  float box[4];
  const Triple t = largest_triple(mask, box);
  // No affinely independent triple: M is a measure on a line, zero as a function.
  const int orientation = t.a < 0 ? 0 : orient2d(knots_[t.a], knots_[t.b], knots_[t.c]);
  if (orientation != 0 && count == 3) {
    node.kind = Kind::base;
    node.knot[0] = static_cast<std::uint8_t>(t.a);
    node.knot[1] = static_cast<std::uint8_t>(orientation > 0 ? t.b : t.c);
    node.knot[2] = static_cast<std::uint8_t>(orientation > 0 ? t.c : t.b);
    node.data[0] = 1.0 / std::abs(determinant(t.a, t.b, t.c));
  } else if (orientation != 0) {
    set_recurrence(mask, t, node);
  }
  const int id = push_node(node, box);
  if (!direct_index_.empty()) {
    direct_index_[mask] = static_cast<std::uint16_t>(id + 1);
  } else {
    index_.emplace(mask, id);
  }
  return id;
}

int SimplexSplineDag::push_node(const Node& node, const float box[4]) {
  const std::size_t id = nodes_.size();
  nodes_.push_back(node);
  if (id % 4 == 0) {
    // A new block of 4, all empty boxes until filled: a finite u is outside them.
    const float inf = std::numeric_limits<float>::infinity();
    boxes_.insert(boxes_.end(), 8, inf);
    boxes_.insert(boxes_.end(), 8, -inf);
  }
  float* block = &boxes_[(id / 4) * 16 + id % 4];
  for (int k = 0; k < 4; ++k) block[4 * k] = box[k];
  if (id % 64 == 0) {
    base_bits_.push_back(0);
    recurrence_bits_.push_back(0);
  }
  const std::uint64_t bit = std::uint64_t{1} << (id % 64);
  if (node.kind == Kind::base) base_bits_[id / 64] |= bit;
  if (node.kind == Kind::recurrence) recurrence_bits_[id / 64] |= bit;
  return static_cast<int>(id);
}

SimplexSplineDag::Triple SimplexSplineDag::largest_triple(std::uint32_t mask, float box[4]) const {
  int members[32];
  int size = 0;
  float lo_x = std::numeric_limits<float>::infinity(), lo_y = lo_x, hi_x = -lo_x, hi_y = -lo_x;
  for (std::uint32_t rest = mask; rest != 0; rest &= rest - 1) {  // set bits, ascending
    const int i = __builtin_ctz(rest);
    members[size++] = i;
    lo_x = std::min(lo_x, knot_floor_[i][0]);
    lo_y = std::min(lo_y, knot_floor_[i][1]);
    hi_x = std::max(hi_x, knot_ceil_[i][0]);
    hi_y = std::max(hi_y, knot_ceil_[i][1]);
  }
  box[0] = lo_x;
  box[1] = lo_y;
  box[2] = hi_x;
  box[3] = hi_y;
  // The triple of largest area keeps the barycentric coordinates bounded (|lambda| <= 3 on the
  // hull of the subset) and so the recurrence well conditioned.
  Triple best;
  double best_area = 0.0;
  const std::size_t k = knots_.size();
  for (int x = 0; x < size; ++x) {
    for (int y = x + 1; y < size; ++y) {
      const double* row = &areas_[(static_cast<std::size_t>(members[x]) * k +
                                   static_cast<std::size_t>(members[y])) * k];
      for (int z = y + 1; z < size; ++z) {
        const double area = row[members[z]];
        if (area > best_area) {
          best_area = area;
          best = Triple{members[x], members[y], members[z]};
        }
      }
    }
  }
  return best;
}

void SimplexSplineDag::set_recurrence(std::uint32_t mask, Triple t, Node& node) {
  put_longest_opposite_first(knots_, t.a, t.b, t.c);
  const int triple[3] = {t.a, t.b, t.c};
  for (int k = 0; k < 3; ++k) {
    const int child = add_node(mask & ~(1u << triple[k]));
    node.child[k] = nodes_[static_cast<std::size_t>(child)].kind == Kind::zero
                        ? kNoChild
                        : static_cast<std::uint16_t>(child);
    node.knot[k] = static_cast<std::uint8_t>(triple[k]);
  }
  // g_b, g_c from the edges opposite b and c, each without cancellation.
  const Eigen::Vector2d e1 = knots_[t.b] - knots_[t.a], e2 = knots_[t.c] - knots_[t.a];
  const double det = determinant(t.a, t.b, t.c);
  node.kind = Kind::recurrence;
  node.data[0] = e2.y() / det;
  node.data[1] = -e2.x() / det;
  node.data[2] = -e1.y() / det;
  node.data[3] = e1.x() / det;
}

void SimplexSplineDag::reserve(std::size_t nodes) {
  nodes_.reserve(nodes);
  boxes_.reserve((nodes + 3) / 4 * 16);
  base_bits_.reserve((nodes + 63) / 64);
  recurrence_bits_.reserve((nodes + 63) / 64);
}

void SimplexSplineDag::release_index() {
  std::unordered_map<std::uint32_t, int>().swap(index_);
  std::vector<std::uint16_t>().swap(direct_index_);
  std::vector<double>().swap(areas_);
  std::vector<double>().swap(dets_);
  std::vector<std::array<float, 2>>().swap(knot_floor_);
  std::vector<std::array<float, 2>>().swap(knot_ceil_);
  nodes_.shrink_to_fit();
  boxes_.shrink_to_fit();
  base_bits_.shrink_to_fit();
  recurrence_bits_.shrink_to_fit();
  roots_.shrink_to_fit();
  gradient_ids_.shrink_to_fit();
}

std::size_t SimplexSplineDag::memory_bytes() const {
  return nodes_.capacity() * sizeof(Node) + knots_.capacity() * sizeof(Eigen::Vector2d) +
         boxes_.capacity() * sizeof(float) +
         (base_bits_.capacity() + recurrence_bits_.capacity()) * sizeof(std::uint64_t) +
         roots_.capacity() * sizeof(int) + gradient_ids_.capacity() * sizeof(std::uint16_t);
}

// Everything an evaluation at u computes once per knot or knot pair instead of once per node.
// The numbers are the very ones a node would compute itself (same operations in the same order),
// so evaluation is bit for bit what the plain per-node recurrence gives.
struct SimplexSplineDag::PointState {
  PointState(const std::vector<Eigen::Vector2d>& knots, const Eigen::Vector2d& at,
             const TieBreak& tie_break)
      : knots_(knots), u(at), tie(tie_break), count(static_cast<int>(knots.size())) {
    for (int i = 0; i < count; ++i) {
      offset[i] = u - knots[static_cast<std::size_t>(i)];
      distance2[i] = offset[i].squaredNorm();
    }
    std::fill(side, side + count * count, std::int8_t{0});
  }

  // lambda_k(u) of a recurrence node: g_k . (u - s), s the end of the edge opposite x_k nearer
  // to u (see Node).
  double lambda(const Node& node, int k, const Eigen::Vector2d& g_k) const {
    const int p = node.knot[(k + 1) % 3], q = node.knot[(k + 2) % 3];
    return g_k.dot(distance2[p] <= distance2[q] ? offset[p] : offset[q]);
  }

  // left_of(x_p, x_q, u, tie), each directed knot line decided once (left_of is antisymmetric).
  bool left(int p, int q) {
    std::int8_t& s = side[p * count + q];
    if (s == 0) {
      const bool l = left_of(knots_[static_cast<std::size_t>(p)],
                             knots_[static_cast<std::size_t>(q)], u, tie);
      s = l ? 1 : -1;
      side[q * count + p] = static_cast<std::int8_t>(-s);
    }
    return s > 0;
  }

  // in_half_open_triangle of a base node's ccw triangle.
  bool in_base(const Node& node) {
    return left(node.knot[0], node.knot[1]) && left(node.knot[1], node.knot[2]) &&
           left(node.knot[2], node.knot[0]);
  }

  const std::vector<Eigen::Vector2d>& knots_;
  const Eigen::Vector2d u;
  const TieBreak& tie;
  const int count;
  Eigen::Vector2d offset[32];
  double distance2[32];
  std::int8_t side[32 * 32];
};

void SimplexSplineDag::evaluate(const Eigen::Vector2d& u, const TieBreak& tie,
                                std::vector<Jet>& jets) const {
  jets.resize(nodes_.size());
  PointState state(knots_, u, tie);
  const float ux = static_cast<float>(u.x()), uy = static_cast<float>(u.y());
  for (std::size_t id = 0; id < nodes_.size(); ++id) {
    const Node& node = nodes_[id];
    Jet& jet = jets[id];
    jet = Jet{};
    if (node.kind == Kind::zero || outside(id, ux, uy)) continue;
    if (node.kind == Kind::base) {
      if (state.in_base(node)) jet.value = node.data[0];
      continue;
    }
    const std::array<Eigen::Vector2d, 3> g = triple_gradients(node.data);
    double hxx = 0.0, hxy = 0.0, hyy = 0.0;
    for (int k = 0; k < 3; ++k) {
      if (node.child[k] == kNoChild) continue;
      const Jet& c = jets[node.child[k]];
      // A zero child adds only (signed) zeros: skipping it changes no bit. Many children vanish
      // at u (their box is larger than their support): -16% instructions (msp-bench dms).
      if (c.value == 0.0 && (!node.root || c.gradient.isZero(0.0))) continue;
      jet.value += state.lambda(node, k, g[k]) * c.value;
      jet.gradient += g[k] * c.value;
      if (!node.root) continue;
      hxx += g[k].x() * c.gradient.x();
      hxy += 0.5 * (g[k].x() * c.gradient.y() + g[k].y() * c.gradient.x());
      hyy += g[k].y() * c.gradient.y();
    }
    const double n = node.degree;
    jet.gradient *= n;
    if (node.root) jet.hessian = n * Eigen::Vector3d(hxx, hxy, hyy);
  }
}

void SimplexSplineDag::evaluate_all_values(const Eigen::Vector2d& u, const TieBreak& tie,
                                           std::vector<double>& values) const {
  // Culled nodes, zero nodes and base nodes outside their triangle stay at this zero.
  values.assign(nodes_.size(), 0.0);
  PointState state(knots_, u, tie);
  const float ux = static_cast<float>(u.x()), uy = static_cast<float>(u.y());
  const __m128 x = _mm_set1_ps(ux), y = _mm_set1_ps(uy);
  for (std::size_t word = 0; word < base_bits_.size(); ++word) {
    // The culling of 64 nodes as one bit mask: the test of outside() on 4 boxes at once (the
    // same float compares; NaN compares false and keeps a node, as there), instead of a branch
    // per node (the four compares and jumps were ~12% of a fit's samples).
    std::uint64_t live = 0;
    const std::size_t blocks = std::min<std::size_t>(16, (nodes_.size() - 64 * word + 3) / 4);
    for (std::size_t block = 0; block < blocks; ++block) {
      const float* b = &boxes_[(word * 16 + block) * 16];
      const __m128 out = _mm_or_ps(
          _mm_or_ps(_mm_cmplt_ps(x, _mm_loadu_ps(b)), _mm_cmplt_ps(y, _mm_loadu_ps(b + 4))),
          _mm_or_ps(_mm_cmpgt_ps(x, _mm_loadu_ps(b + 8)), _mm_cmpgt_ps(y, _mm_loadu_ps(b + 12))));
      live |= static_cast<std::uint64_t>(_mm_movemask_ps(out) ^ 0xF) << (4 * block);
    }
    // Base nodes first: a recurrence node's children have smaller ids, in this word or before.
    for (std::uint64_t bits = live & base_bits_[word]; bits != 0; bits &= bits - 1) {
      const std::size_t id = 64 * word + static_cast<std::size_t>(__builtin_ctzll(bits));
      const Node& node = nodes_[id];
      if (state.in_base(node)) values[id] = node.data[0];
    }
    for (std::uint64_t bits = live & recurrence_bits_[word]; bits != 0; bits &= bits - 1) {
      const std::size_t id = 64 * word + static_cast<std::size_t>(__builtin_ctzll(bits));
      const Node& node = nodes_[id];
      // The operations of evaluate()'s value, in its order: the same bits.
      const std::array<Eigen::Vector2d, 3> g = triple_gradients(node.data);
      double value = 0.0;
      for (int k = 0; k < 3; ++k) {
        if (node.child[k] == kNoChild) continue;
        const double child = values[node.child[k]];
        if (child != 0.0) value += state.lambda(node, k, g[k]) * child;
      }
      values[id] = value;
    }
  }
}

void SimplexSplineDag::evaluate_root_values(const Eigen::Vector2d& u, const TieBreak& tie,
                                            Scratch& scratch, std::vector<double>& roots) const {
  evaluate_all_values(u, tie, scratch.values);
  roots.resize(roots_.size());
  for (std::size_t i = 0; i < roots_.size(); ++i) {
    roots[i] = scratch.values[static_cast<std::size_t>(roots_[i])];
  }
}

Eigen::Vector2d SimplexSplineDag::gradient_from_values(const Node& node,
                                                       const std::vector<double>& values) const {
  const std::array<Eigen::Vector2d, 3> g = triple_gradients(node.data);
  Eigen::Vector2d gradient = Eigen::Vector2d::Zero();
  for (int k = 0; k < 3; ++k) {
    if (node.child[k] == kNoChild) continue;
    const double child = values[node.child[k]];
    if (child != 0.0) gradient += g[k] * child;
  }
  gradient *= static_cast<double>(node.degree);
  return gradient;
}

void SimplexSplineDag::evaluate_root_gradients(const Eigen::Vector2d& u, const TieBreak& tie,
                                               Scratch& scratch, std::vector<Jet>& roots) const {
  evaluate_root_jets(u, tie, scratch, roots, false);
}

void SimplexSplineDag::evaluate_roots(const Eigen::Vector2d& u, const TieBreak& tie,
                                      Scratch& scratch, std::vector<Jet>& roots) const {
  evaluate_root_jets(u, tie, scratch, roots, true);
}

void SimplexSplineDag::evaluate_root_jets(const Eigen::Vector2d& u, const TieBreak& tie,
                                          Scratch& scratch, std::vector<Jet>& roots,
                                          bool hessians) const {
  // The recurrence needs values below the roots' children: grad M is n sum_a grad(lambda_a)
  // M(. | X \ x_a), a sum of the children's values, and the Hessian the children's gradients.
  // Every sum is evaluate()'s, term for term: the terms it skips (zero children) add signed
  // zeros to sums that start at +0, which changes no bit. Without Hessians only the roots'
  // gradients are taken (the same sums).
  evaluate_all_values(u, tie, scratch.values);
  const std::vector<double>& values = scratch.values;
  if (hessians) {
    scratch.gradients.resize(nodes_.size());
    for (const std::uint16_t id : gradient_ids_) {
      scratch.gradients[id] = gradient_from_values(nodes_[id], values);
    }
  }
  roots.resize(roots_.size());
  for (std::size_t i = 0; i < roots_.size(); ++i) {
    const std::size_t id = static_cast<std::size_t>(roots_[i]);
    const Node& node = nodes_[id];
    Jet& jet = roots[i];
    jet = Jet{};
    jet.value = values[id];
    if (node.kind != Kind::recurrence) continue;
    if (!hessians) {
      jet.gradient = gradient_from_values(node, values);
      continue;
    }
    jet.gradient = scratch.gradients[id];
    const std::array<Eigen::Vector2d, 3> g = triple_gradients(node.data);
    double hxx = 0.0, hxy = 0.0, hyy = 0.0;
    for (int k = 0; k < 3; ++k) {
      if (node.child[k] == kNoChild) continue;
      const Node& child = nodes_[node.child[k]];
      if (child.kind != Kind::recurrence) continue;  // a base node's gradient is zero
      const Eigen::Vector2d& c = scratch.gradients[node.child[k]];
      if (c.isZero(0.0)) continue;
      hxx += g[k].x() * c.x();
      hxy += 0.5 * (g[k].x() * c.y() + g[k].y() * c.x());
      hyy += g[k].y() * c.y();
    }
    const double n = node.degree;
    jet.hessian = n * Eigen::Vector3d(hxx, hxy, hyy);
  }
}

void SimplexSplineDag::evaluate_directional(const Eigen::Vector2d& u,
                                            const Eigen::Vector2d& direction, int max_order,
                                            const TieBreak& tie,
                                            std::vector<double>& table) const {
  const std::size_t stride = static_cast<std::size_t>(max_order) + 1;
  table.assign(nodes_.size() * stride, 0.0);
  PointState state(knots_, u, tie);
  const float ux = static_cast<float>(u.x()), uy = static_cast<float>(u.y());
  for (std::size_t id = 0; id < nodes_.size(); ++id) {
    const Node& node = nodes_[id];
    if (node.kind == Kind::zero || outside(id, ux, uy)) continue;
    double* out = &table[id * stride];
    if (node.kind == Kind::base) {
      if (state.in_base(node)) out[0] = node.data[0];
      continue;
    }
    const std::array<Eigen::Vector2d, 3> g = triple_gradients(node.data);
    const double mb = g[1].dot(direction), mc = g[2].dot(direction);
    const double mu[3] = {-mb - mc, mb, mc};
    for (int k = 0; k < 3; ++k) {
      if (node.child[k] == kNoChild) continue;
      const double* c = &table[static_cast<std::size_t>(node.child[k]) * stride];
      out[0] += state.lambda(node, k, g[k]) * c[0];
      for (std::size_t order = 1; order < stride; ++order) out[order] += mu[k] * c[order - 1];
    }
    for (std::size_t order = 1; order < stride; ++order) out[order] *= node.degree;
  }
}

Jet simplex_spline(const std::vector<Eigen::Vector2d>& knots, const Eigen::Vector2d& u,
                   const TieBreak& tie) {
  if (knots.size() < 3) {
    throw ricci::InvalidInputError("simplex spline: needs at least 3 knots");
  }
  SimplexSplineDag dag(knots);
  const std::uint32_t all =
      knots.size() == 32 ? ~0u : ((1u << static_cast<std::uint32_t>(knots.size())) - 1u);
  const int root = dag.add(all);
  std::vector<Jet> jets;
  dag.evaluate(u, tie, jets);
  return jets[static_cast<std::size_t>(root)];
}

std::vector<double> simplex_spline_directional(const std::vector<Eigen::Vector2d>& knots,
                                               const Eigen::Vector2d& u,
                                               const Eigen::Vector2d& direction, int max_order,
                                               const TieBreak& tie) {
  if (knots.size() < 3 || max_order < 0) {
    throw ricci::InvalidInputError("simplex spline: needs at least 3 knots and max_order >= 0");
  }
  SimplexSplineDag dag(knots);
  const std::uint32_t all =
      knots.size() == 32 ? ~0u : ((1u << static_cast<std::uint32_t>(knots.size())) - 1u);
  const int root = dag.add(all);
  std::vector<double> table;
  dag.evaluate_directional(u, direction, max_order, tie, table);
  const auto begin = table.begin() + static_cast<std::ptrdiff_t>(root) * (max_order + 1);
  return std::vector<double>(begin, begin + max_order + 1);
}

}  // namespace spline
