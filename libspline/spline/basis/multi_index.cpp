#include "spline/basis/multi_index.h"

namespace spline {

std::vector<Eigen::Vector3i> multi_indices(int degree) {
  std::vector<Eigen::Vector3i> result;
  result.reserve(static_cast<std::size_t>(multi_index_count(degree)));
  for (int b0 = degree; b0 >= 0; --b0) {
    for (int b1 = degree - b0; b1 >= 0; --b1) result.emplace_back(b0, b1, degree - b0 - b1);
  }
  return result;
}

int multi_index_position(const Eigen::Vector3i& beta) {
  // Rows with beta0 > b0 come first: sum_{k=b0+1}^{n} (n - k + 1) = m (m + 1) / 2, m = n - b0.
  const int n = beta.sum();
  const int m = n - beta[0];
  return m * (m + 1) / 2 + (m - beta[1]);
}

}  // namespace spline
