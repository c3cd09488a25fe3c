#include "ricci/analysis/module_index.h"

#include <algorithm>

namespace ricci {

std::vector<ModuleGroup> index_modules(const std::vector<ModuleResult>& modules) {
  std::vector<ModuleGroup> groups;
  for (size_t i = 0; i < modules.size(); ++i) {
    const ModuleResult& m = modules[i];
    auto group = std::find_if(groups.begin(), groups.end(), [&](const ModuleGroup& g) {
      return g.kind == m.kind && g.genus == m.genus && g.boundary_loops == m.boundary_loops;
    });
    if (group == groups.end()) {
      groups.push_back({m.kind, m.genus, m.boundary_loops, {}, {}, {}, true});
      group = groups.end() - 1;
    }
    group->members.push_back(static_cast<int>(i));
    group->invariant = group->invariant && m.invariant;
  }
  for (ModuleGroup& g : groups) {
    const int n = static_cast<int>(g.members.size());
    g.distances = Eigen::MatrixXd::Zero(n, n);
    for (int a = 0; a < n; ++a) {
      for (int b = a + 1; b < n; ++b) {
        g.distances(a, b) = g.distances(b, a) =
            module_distance(modules[g.members[a]], modules[g.members[b]]);
      }
    }
    for (int a = 0; a < n; ++a) {
      std::vector<int> order;
      for (int b = 0; b < n; ++b) {
        if (b != a) order.push_back(b);
      }
      std::stable_sort(order.begin(), order.end(),
                       [&](int x, int y) { return g.distances(a, x) < g.distances(a, y); });
      g.nearest.push_back(order);
    }
  }
  return groups;
}

}  // namespace ricci
