#include "spline/basis/triangle_basis.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "ricci/mesh/errors.h"
#include "ricci/util/cross2d.h"
#include "spline/basis/multi_index.h"

namespace spline {
namespace {

std::vector<Eigen::Vector2d> concatenate(const KnotCloud& c0, const KnotCloud& c1,
                                         const KnotCloud& c2) {
  const int n = c0.degree();
  if (n < 1 || n > kMaxDmsDegree || c1.degree() != n || c2.degree() != n) {
    throw ricci::InvalidInputError("triangle basis: clouds of degrees " +
                                   std::to_string(c0.degree()) + ", " +
                                   std::to_string(c1.degree()) + ", " +
                                   std::to_string(c2.degree()) + " (need equal, 1.." +
                                   std::to_string(kMaxDmsDegree) + ")");
  }
  std::vector<Eigen::Vector2d> knots;
  for (const KnotCloud* c : {&c0, &c1, &c2}) {
    knots.insert(knots.end(), c->knots.begin(), c->knots.end());
  }
  return knots;
}

// Counter-clockwise convex hull (Andrew's monotone chain, exact orientations, collinear points
// dropped); fewer than 3 points when all are collinear.
std::vector<Eigen::Vector2d> convex_hull(std::vector<Eigen::Vector2d> points) {
  std::sort(points.begin(), points.end(), [](const Eigen::Vector2d& p, const Eigen::Vector2d& q) {
    return p.x() < q.x() || (p.x() == q.x() && p.y() < q.y());
  });
  std::vector<Eigen::Vector2d> hull(2 * points.size() + 1);
  std::size_t k = 0;
  for (std::size_t pass = 0; pass < 2; ++pass) {
    const std::size_t start = k;
    for (std::size_t j = 0; j < points.size(); ++j) {
      const Eigen::Vector2d& p = pass == 0 ? points[j] : points[points.size() - 1 - j];
      while (k >= start + 2 && orient2d(hull[k - 2], hull[k - 1], p) <= 0) --k;
      hull[k++] = p;
    }
    --k;  // the last point starts the other chain
  }
  hull.resize(k);
  return hull;
}

bool in_closed_polygon(const std::vector<Eigen::Vector2d>& hull, const Eigen::Vector2d& u) {
  if (hull.size() < 3) return false;  // collinear knots: the functions vanish
  for (std::size_t j = 0; j < hull.size(); ++j) {
    if (orient2d(hull[j], hull[(j + 1) % hull.size()], u) < 0) return false;
  }
  return true;
}


}  // namespace

TriangleBasis::TriangleBasis(const KnotCloud& cloud0, const KnotCloud& cloud1,
                             const KnotCloud& cloud2)
    : degree_(cloud0.degree()), dag_(concatenate(cloud0, cloud1, cloud2)) {
  const int n = degree_;
  const auto& knots = dag_.knots();
  box_min_ = box_max_ = knots[0];
  for (const Eigen::Vector2d& t : knots) {
    box_min_ = box_min_.cwiseMin(t);
    box_max_ = box_max_.cwiseMax(t);
  }
  // The triangles of a space have DAGs of about one size: room for the last one built on this
  // thread (and an eighth more) spares the node arrays' regrowth (docs/design-notes.md, "Node
  // arrays of the DAGs reserved"); release_index trims the rest.
  thread_local std::size_t last_nodes = 0;
  dag_.reserve(last_nodes + last_nodes / 8);
  for (const Eigen::Vector3i& beta : multi_indices(n)) {
    std::uint32_t mask = 0;
    for (int v = 0; v < 3; ++v) {
      for (int j = 0; j <= beta[v]; ++j) mask |= 1u << (v * (n + 1) + j);
    }
    const Eigen::Vector2d& a = knots[static_cast<std::size_t>(beta[0])];
    const Eigen::Vector2d& b = knots[static_cast<std::size_t>(n + 1 + beta[1])];
    const Eigen::Vector2d& c = knots[static_cast<std::size_t>(2 * (n + 1) + beta[2])];
    const double d = std::abs(ricci::cross2d(b - a, c - a));
    if (!(d > 0.0)) {
      throw ricci::InvalidInputError("triangle basis: shifted triangle of beta (" +
                                     std::to_string(beta[0]) + "," + std::to_string(beta[1]) +
                                     "," + std::to_string(beta[2]) + ") is degenerate");
    }
    masks_.push_back(mask);
    scales_.push_back(d);
    (void)dag_.add(mask);  // root i of the DAG: function i
  }
  last_nodes = static_cast<std::size_t>(dag_.node_count());
  dag_.release_index();
  hull_ = convex_hull(knots);
}

std::size_t TriangleBasis::memory_bytes() const {
  return sizeof(*this) + dag_.memory_bytes() + masks_.capacity() * sizeof(std::uint32_t) +
         scales_.capacity() * sizeof(double);
}

std::vector<Eigen::Vector2d> TriangleBasis::knot_set(int i) const {
  std::vector<Eigen::Vector2d> result;
  const std::uint32_t mask = masks_[static_cast<std::size_t>(i)];
  for (std::size_t k = 0; k < dag_.knots().size(); ++k) {
    if (mask & (1u << k)) result.push_back(dag_.knots()[k]);
  }
  return result;
}

bool TriangleBasis::in_support(int i, const Eigen::Vector2d& u) const {
  return in_closed_polygon(convex_hull(knot_set(i)), u);
}

bool TriangleBasis::in_hull(const Eigen::Vector2d& u) const {
  if ((u.array() < box_min_.array()).any() || (u.array() > box_max_.array()).any()) return false;
  return in_closed_polygon(hull_, u);
}

void TriangleBasis::evaluate(const Eigen::Vector2d& u, const TieBreak& tie, std::vector<Jet>& out,
                             SimplexSplineDag::Scratch& scratch,
                             BasisDerivatives derivatives) const {
  // Roots in multi_indices(n) order.
  if (derivatives == BasisDerivatives::none) {
    evaluate_values(u, tie, scratch.roots, scratch);
    out.assign(scratch.roots.size(), Jet{});
    for (std::size_t i = 0; i < out.size(); ++i) out[i].value = scratch.roots[i];
    return;
  }
  const bool hessians = derivatives == BasisDerivatives::second;
  if (hessians) {
    dag_.evaluate_roots(u, tie, scratch, out);
  } else {
    dag_.evaluate_root_gradients(u, tie, scratch, out);
  }
  for (std::size_t i = 0; i < out.size(); ++i) {
    out[i].value = scales_[i] * out[i].value;
    out[i].gradient = scales_[i] * out[i].gradient;
    if (hessians) out[i].hessian = scales_[i] * out[i].hessian;
  }
}

void TriangleBasis::evaluate_values(const Eigen::Vector2d& u, const TieBreak& tie,
                                    std::vector<double>& out,
                                    SimplexSplineDag::Scratch& scratch) const {
  dag_.evaluate_root_values(u, tie, scratch, out);
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = scales_[i] * out[i];
}

void TriangleBasis::evaluate_directional(const Eigen::Vector2d& u,
                                         const Eigen::Vector2d& direction, int max_order,
                                         const TieBreak& tie, std::vector<double>& out,
                                         std::vector<double>& scratch) const {
  dag_.evaluate_directional(u, direction, max_order, tie, scratch);
  const std::size_t stride = static_cast<std::size_t>(max_order) + 1;
  const std::vector<int>& roots = dag_.roots();
  out.resize(roots.size() * stride);
  for (std::size_t i = 0; i < roots.size(); ++i) {
    for (std::size_t k = 0; k < stride; ++k) {
      out[i * stride + k] = scales_[i] * scratch[static_cast<std::size_t>(roots[i]) * stride + k];
    }
  }
}

}  // namespace spline
