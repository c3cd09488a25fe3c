#pragma once
// Bivariate simplex splines M(u | X) for a knot multiset X of n + 3 points (degree n), by the
// Micchelli recurrence, memoised over knot subsets (bit masks), with exact derivative formulas.
//
// Normalisation (the DMS one, manifold-splines paper section 5): for 3 knots M = 1/|d(a,b,c)|
// inside the triangle (d = det[1 1 1; a b c] = twice the signed area), and for more knots
//     M(u | X) = sum_a lambda_a(u) M(u | X \ x_a),   u = sum_a lambda_a x_a, sum_a lambda_a = 1,
// over any affinely independent triple {x_a} of X (we take the one of largest area: choosing the
// first found one loses partition of unity at small cloud radii). The standard simplex spline
// (volume of a slice of an (n+2)-simplex over its volume, integral 1) satisfies the same
// recurrence with the factor (n+2)/n, and equals 2/|d| for 3 knots; so
//     M_DMS = M_standard / ((n + 1)(n + 2)),   integral of M_DMS over R^2 = 1 / ((n + 1)(n + 2)),
// which is also the integral of a degree-n Bernstein polynomial over a triangle divided by |d|:
// the factor that makes N = |d| M a partition of unity. Derivatives (Micchelli; DMS 1992): for
// d = sum_a mu_a x_a with sum_a mu_a = 0,
//     D_d M(u | X) = n sum_a mu_a M(u | X \ x_a)    (degree-n M, this normalisation),
// applied with the same triple (mu_a = d . grad lambda_a) and recursively for higher orders.
// Points on knot lines take the value of the polynomial piece on the side given by a TieBreak.
//
// Numerics (measured with msp-bench dms and the tests): the triples' determinants use error-free
// products (orientation.h); each lambda_a is anchored at the end of its opposite edge nearer to
// u; and the one gradient derived from the other two (sum of gradients = 0) is the largest, so the
// subtraction does not cancel. Without the last point thin triples (two knots of a cloud and a
// far knot) lost digits in proportion to edge length / cloud radius; with it partition of unity
// holds to ~1e-15 for cloud radii from 0.45 of the inradius down to 1e-7 of the edge length, also
// at points inside the clouds. Evaluation is const and thread-safe.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "spline/basis/orientation.h"

namespace spline {

/// Value, gradient and Hessian (xx, xy, yy) of a function of the plane at a point.
struct Jet {
  double value = 0.0;
  Eigen::Vector2d gradient = Eigen::Vector2d::Zero();
  Eigen::Vector3d hessian = Eigen::Vector3d::Zero();  ///< (d2/dx2, d2/dxdy, d2/dy2)
};

/// Factor from the DMS normalisation to the standard one (integral 1): (n + 1)(n + 2).
[[nodiscard]] constexpr double standard_simplex_spline_factor(int degree) {
  return (degree + 1.0) * (degree + 2.0);
}

/// A set of simplex splines over subsets of one knot list, sharing the sub-results of their
/// recurrences: a DAG of knot subsets, each node with its affinely independent triple chosen once
/// (largest |det|) so that evaluating at a point is one pass over the nodes.
class SimplexSplineDag {
 public:
  /// \throw ricci::InvalidInputError with more than 32 knots or a non-finite knot.
  /// (A DAG holds at most 65535 nodes: far more than 32 knots of degree <= 7 need.)
  explicit SimplexSplineDag(std::vector<Eigen::Vector2d> knots);

  /// Adds M(. | {knots[i] : bit i of mask}) (at least 3 bits) and returns its node id. The node
  /// is a root, the next one of evaluate_roots(); evaluate() gives its Hessian (the Hessians of
  /// the other nodes are not needed by the recurrence, and are skipped).
  /// \throw ricci::InvalidInputError with fewer than 3 bits, bits past the knots, or too many
  ///        nodes.
  int add(std::uint32_t mask);

  [[nodiscard]] int node_count() const { return static_cast<int>(nodes_.size()); }
  /// Node ids returned by add(), in call order (the roots of evaluate_roots()).
  [[nodiscard]] const std::vector<int>& roots() const { return roots_; }

  /// Room for `nodes` nodes before the evaluation arrays grow again (no effect on results).
  void reserve(std::size_t nodes);

  /// Drops the subset -> node map once all roots are added (it is as large as the nodes). Later
  /// add() calls stay correct but no longer share the nodes built before.
  void release_index();

  /// Bytes held by the nodes and knots (the evaluation state).
  [[nodiscard]] std::size_t memory_bytes() const;
  [[nodiscard]] const std::vector<Eigen::Vector2d>& knots() const { return knots_; }

  /// Reusable storage of evaluate_roots / evaluate_root_values (one per thread).
  struct Scratch {
    std::vector<double> values;             // M of every node
    std::vector<Eigen::Vector2d> gradients;  // grad M, written for the roots and their children
    std::vector<double> roots;              // for callers of evaluate_root_values
  };

  /// Jets of the roots at u: roots[i] is M, grad M and its Hessian for the i-th add() call. The
  /// same numbers, bit for bit, as evaluate() gives for those nodes, computed in three passes:
  /// values of all nodes not culled by their box, gradients of the roots and their children
  /// only, Hessians of the roots only.
  void evaluate_roots(const Eigen::Vector2d& u, const TieBreak& tie, Scratch& scratch,
                      std::vector<Jet>& roots) const;

  /// Values and gradients of the roots (Hessians left zero): the numbers of evaluate_roots,
  /// without its Hessian pass and the gradients of the roots' children that pass needs.
  void evaluate_root_gradients(const Eigen::Vector2d& u, const TieBreak& tie, Scratch& scratch,
                               std::vector<Jet>& roots) const;

  /// Values only of the roots: roots[i] = M(u | X) for the i-th add() call (the numbers of
  /// evaluate_roots).
  void evaluate_root_values(const Eigen::Vector2d& u, const TieBreak& tie, Scratch& scratch,
                            std::vector<double>& roots) const;

  /// Reference evaluation, one pass with a jet per node: jets[id] is then M and grad M for every
  /// node id, and the Hessian of M for the roots (zero for the other nodes).
  void evaluate(const Eigen::Vector2d& u, const TieBreak& tie, std::vector<Jet>& jets) const;

  /// Directional derivatives D_d^k M for k = 0..max_order of every node at u:
  /// table[id * (max_order + 1) + k].
  void evaluate_directional(const Eigen::Vector2d& u, const Eigen::Vector2d& direction,
                            int max_order, const TieBreak& tie, std::vector<double>& table) const;

 private:
  enum class Kind : std::uint8_t { zero, base, recurrence };
  static constexpr std::uint16_t kNoChild = 0xFFFF;
  // 48 bytes (the boxes live apart, in boxes_): a degree-5 triangle has ~700 nodes, and a domain
  // thousands of triangles.
  struct Node {
    // base: 1/|d| in data[0]. recurrence: lambda_k(u) = g_k.(u - s) for the triple k = a, b, c
    // with g_b = data[0..1], g_c = data[2..3], g_a = -g_b - g_c, and s either end of the edge
    // opposite x_k (knot[(k+1)%3], knot[(k+2)%3]; lambda_k vanishes at both): the one nearer to
    // u, since the rounding error is eps |g_k| |u - s| and thin triples (two knots of one cloud
    // and a far knot) have large |g_k|.
    double data[4] = {0.0, 0.0, 0.0, 0.0};
    std::uint16_t child[3] = {kNoChild, kNoChild, kNoChild};  // X \ x_a, X \ x_b, X \ x_c
    std::uint8_t knot[3] = {0, 0, 0};  // base: ccw triangle; recurrence: the triple (a, b, c)
    Kind kind = Kind::zero;
    std::uint8_t degree = 0;
    bool root = false;      // added by add(): its Hessian is wanted
    bool gradient = false;  // a recurrence root or a recurrence child of a root: in gradient_ids_
  };
  struct Triple {
    int a = -1, b = -1, c = -1;
  };
  // The subset's largest-area knot triple (a < 0: all collinear); also fills box (lo x, lo y,
  // hi x, hi y: the knots' bounding box rounded outwards).
  Triple largest_triple(std::uint32_t mask, float box[4]) const;
  // Appends node and its box to the evaluation arrays.
  int push_node(const Node& node, const float box[4]);
  // Adds the children X \ x_k and the barycentric gradients of the triple to node.
  void set_recurrence(std::uint32_t mask, Triple triple, Node& node);
  // add() without marking the node a root.
  int add_node(std::uint32_t mask);
  // Per-point scratch of one evaluation (simplex_spline.cpp): u - x_i for every knot, and the
  // sides of u of the directed knot lines already decided by base triangles.
  struct PointState;
  // Strictly outside the closed box: u and its perturbation lie outside the knots' hull. u is
  // compared rounded to float (once per pass, not per node): rounding is monotonic and the box
  // corners are floats, so a culled node is outside in double too; a node the float test keeps
  // but the double test would cull evaluates to exact zeros, as culled ones read. A node's
  // descendants have boxes inside its own, so they are culled with it.
  bool outside(std::size_t id, float x, float y) const {
    const float* b = &boxes_[(id / 4) * 16 + id % 4];
    return x < b[0] || y < b[4] || x > b[8] || y > b[12];
  }
  // The values pass of evaluate_roots / evaluate_root_values.
  void evaluate_all_values(const Eigen::Vector2d& u, const TieBreak& tie,
                           std::vector<double>& values) const;
  // grad M of recurrence node `node` from its children's values (zero children skipped: their
  // terms are signed zeros added to a sum that starts at +0).
  Eigen::Vector2d gradient_from_values(const Node& node, const std::vector<double>& values) const;
  // evaluate_roots (hessians) and evaluate_root_gradients (not): one routine, the same sums.
  void evaluate_root_jets(const Eigen::Vector2d& u, const TieBreak& tie, Scratch& scratch,
                          std::vector<Jet>& roots, bool hessians) const;

  // Build-time caches, dropped by release_index(): subset -> node (a direct table up to
  // kDirectIndexKnots knots, a hash map above), |det| of every ascending knot triple (the
  // largest-triple search) and the accurate determinant of every ordered triple used.
  static constexpr std::size_t kDirectIndexKnots = 15;
  void prepare_build_caches();
  double determinant(int a, int b, int c);

  std::vector<Eigen::Vector2d> knots_;
  std::vector<Node> nodes_;
  // Node boxes by blocks of 4 nodes: lo x[4], lo y[4], hi x[4], hi y[4] (SSE2 compares 4 nodes at
  // once); the padding of the last block is an empty box (+inf lo, -inf hi).
  std::vector<float> boxes_;
  // One bit per node id: base nodes, recurrence nodes (zero nodes are in neither).
  std::vector<std::uint64_t> base_bits_, recurrence_bits_;
  std::vector<int> roots_;                   // add() results in call order
  std::vector<std::uint16_t> gradient_ids_;  // nodes with Node::gradient, in order of marking
  std::unordered_map<std::uint32_t, int> index_;
  std::vector<std::uint16_t> direct_index_;  // mask -> id + 1, 0 when absent
  std::vector<double> areas_, dets_;         // by (x * knots + y) * knots + z
  // Each knot's coordinates rounded to float downwards / upwards (node boxes).
  std::vector<std::array<float, 2>> knot_floor_, knot_ceil_;
};

/// M_DMS(u | knots) with gradient and Hessian (3 to 32 knots).
[[nodiscard]] Jet simplex_spline(const std::vector<Eigen::Vector2d>& knots,
                                 const Eigen::Vector2d& u, const TieBreak& tie = {});

/// D_d^k M_DMS(u | knots) for k = 0..max_order.
[[nodiscard]] std::vector<double> simplex_spline_directional(
    const std::vector<Eigen::Vector2d>& knots, const Eigen::Vector2d& u,
    const Eigen::Vector2d& direction, int max_order, const TieBreak& tie = {});

}  // namespace spline
