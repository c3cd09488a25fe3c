#pragma once
// Shape indexing by conformal modules (ricci-flow-3d-shape-analysis §5.1, Fig. 14): surfaces of
// the same topology compared by the Euclidean distance between their module vectors.
#include <vector>

#include <Eigen/Core>

#include "ricci/analysis/conformal_module.h"

namespace ricci {

/// Surfaces of one topology (module kind, genus and boundary count) and their distances.
struct ModuleGroup {
  ModuleKind kind = ModuleKind::Sphere;
  int genus = 0;
  int boundary_loops = 0;
  std::vector<int> members;  ///< Indices into the input, in input order.
  /// distances(i, j) = module_distance between members i and j.
  Eigen::MatrixXd distances;
  /// For each member (by position in `members`): the other members' positions, nearest first
  /// (ties by input order).
  std::vector<std::vector<int>> nearest;
  /// False when a member's module is not a conformal invariant (fuchsian): the distances then
  /// depend on the bases chosen.
  bool invariant = true;
};

/// Groups the modules by topology (groups in order of their first member) and fills each group's
/// distance matrix and neighbour lists. Modules without values (the sphere) are at distance 0.
/// \throw InvalidInputError if two modules of one topology have different lengths.
[[nodiscard]] std::vector<ModuleGroup> index_modules(const std::vector<ModuleResult>& modules);

}  // namespace ricci
