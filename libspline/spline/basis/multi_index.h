#pragma once
// Multi-indices beta = (beta0, beta1, beta2), |beta| = n, labelling the basis functions and control
// points of one domain triangle (manifold-splines eq. 13; DMS 1992).
#include <Eigen/Core>
#include <vector>

namespace spline {

/// Highest degree the DMS machinery accepts: a knot set has n + 3 points and a triangle's three
/// clouds 3 (n + 1) <= 32 points (bit masks), and the cost grows like 2^(n+3).
constexpr int kMaxDmsDegree = 7;

/// Number of beta with |beta| = n: (n + 1)(n + 2) / 2.
[[nodiscard]] constexpr int multi_index_count(int degree) {
  return (degree + 1) * (degree + 2) / 2;
}

/// All beta with |beta| = n, in the library's fixed order: beta0 descending, then beta1
/// descending (so (n,0,0) first, (0,0,n) last).
[[nodiscard]] std::vector<Eigen::Vector3i> multi_indices(int degree);

/// Position of beta in multi_indices(|beta|).
[[nodiscard]] int multi_index_position(const Eigen::Vector3i& beta);

}  // namespace spline
