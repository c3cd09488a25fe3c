#pragma once
// The DMS triangular B-spline basis functions of one domain triangle (Dahmen-Micchelli-Seidel
// 1992; manifold-splines paper eq. 13):
//     N_{I,beta}(u) = |d(t_{0,beta0}, t_{1,beta1}, t_{2,beta2})| M(u | V_beta^I),
//     V_beta^I = {t_{0,0..beta0}, t_{1,0..beta1}, t_{2,0..beta2}},  |beta| = n,
// with M the DMS-normalised simplex spline (simplex_spline.h). With this factor the N of all
// triangles sum to one wherever every triangle whose functions reach the point is present, and
// as the clouds shrink to their vertices N_{I,beta} tends to the Bernstein polynomial
// B_beta on I: both integrate to |d| / ((n + 1)(n + 2)).
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "spline/basis/simplex_spline.h"
#include "spline/knots/knot_cloud.h"

namespace spline {

/// What an evaluation of basis functions computes: values only (e.g. the rows of a least-squares
/// fit), values and gradients (positions and tangents), or values, gradients and Hessians. What
/// is computed has the same bits at every order; what is not is left zero.
enum class BasisDerivatives : std::uint8_t { none, first, second };

/// The (n + 1)(n + 2)/2 basis functions of one triangle from the clouds of its three vertices,
/// given in one planar frame (a chart), all evaluated together through one shared DAG.
class TriangleBasis {
 public:
  /// \pre clouds of equal degree n in 1..kMaxDmsDegree, listed in the triangle's vertex order.
  /// \throw ricci::InvalidInputError on unequal or unsupported degrees, non-finite knots, or a
  ///        shifted triangle [t_{0,beta0}, t_{1,beta1}, t_{2,beta2}] that is degenerate.
  TriangleBasis(const KnotCloud& cloud0, const KnotCloud& cloud1, const KnotCloud& cloud2);

  [[nodiscard]] int degree() const { return degree_; }
  [[nodiscard]] int size() const { return static_cast<int>(dag_.roots().size()); }
  [[nodiscard]] int node_count() const { return dag_.node_count(); }
  /// Bytes of evaluation state (about 70 per DAG node: ~10 KB at degree 3, ~45 KB at degree 5).
  [[nodiscard]] std::size_t memory_bytes() const;

  /// Knot set V_beta^I of the function at position i of multi_indices(n).
  [[nodiscard]] std::vector<Eigen::Vector2d> knot_set(int i) const;
  /// |d(t_{0,beta0}, t_{1,beta1}, t_{2,beta2})| of the function at position i.
  [[nodiscard]] double scale(int i) const { return scales_[static_cast<std::size_t>(i)]; }

  /// Axis-aligned box of all knots of the three clouds: every N_{I,beta} vanishes outside it.
  [[nodiscard]] const Eigen::Vector2d& box_min() const { return box_min_; }
  [[nodiscard]] const Eigen::Vector2d& box_max() const { return box_max_; }

  /// True when u lies in the closed convex hull of V_beta^I (the support of function i).
  [[nodiscard]] bool in_support(int i, const Eigen::Vector2d& u) const;

  /// True when u lies in the closed convex hull of all knots of the three clouds: outside it,
  /// every function of the triangle and all its derivatives vanish.
  [[nodiscard]] bool in_hull(const Eigen::Vector2d& u) const;

  /// Jets of all functions at u, in multi_indices(n) order, up to `derivatives` (the rest of
  /// each jet zero). scratch is reused storage.
  void evaluate(const Eigen::Vector2d& u, const TieBreak& tie, std::vector<Jet>& out,
                SimplexSplineDag::Scratch& scratch,
                BasisDerivatives derivatives = BasisDerivatives::second) const;

  /// Values only of all functions at u (the same numbers as evaluate()'s values).
  void evaluate_values(const Eigen::Vector2d& u, const TieBreak& tie, std::vector<double>& out,
                       SimplexSplineDag::Scratch& scratch) const;

  /// D_d^k N for k = 0..max_order of all functions: out[i * (max_order + 1) + k].
  void evaluate_directional(const Eigen::Vector2d& u, const Eigen::Vector2d& direction,
                            int max_order, const TieBreak& tie, std::vector<double>& out,
                            std::vector<double>& scratch) const;

 private:
  int degree_;
  SimplexSplineDag dag_;
  std::vector<std::uint32_t> masks_;
  std::vector<double> scales_;
  Eigen::Vector2d box_min_, box_max_;
  std::vector<Eigen::Vector2d> hull_;  // counter-clockwise hull of all knots
};

}  // namespace spline
