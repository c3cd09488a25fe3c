#include "ricci/mesh/edge_statistics.h"

#include <algorithm>
#include <vector>

namespace ricci {

double median_edge_length(const Mesh& mesh) {
  std::vector<double> lengths;
  lengths.reserve(mesh.n_edges());
  for (auto e : mesh.edges()) lengths.push_back(mesh.calc_edge_length(e));
  if (lengths.empty()) return 0.0;
  auto middle = lengths.begin() + static_cast<std::ptrdiff_t>(lengths.size() / 2);
  std::nth_element(lengths.begin(), middle, lengths.end());
  return *middle;
}

}  // namespace ricci
