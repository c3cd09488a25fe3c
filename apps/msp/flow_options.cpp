#include "msp/flow_options.h"

#include <stdexcept>

#include "msp/cli.h"

namespace msp {

ricci::Geometry parse_geometry(const std::string& s) {
  if (s == "euclidean" || s == "e2") return ricci::Geometry::euclidean;
  if (s == "hyperbolic" || s == "h2") return ricci::Geometry::hyperbolic;
  if (s == "spherical" || s == "s2") return ricci::Geometry::spherical;
  throw UsageError("--geometry must be euclidean, hyperbolic or spherical, not '" + s + "'");
}

ricci::Scheme parse_scheme(const std::string& s) {
  if (s == "circle-packing") return ricci::Scheme::circle_packing;
  if (s == "inversive-distance") return ricci::Scheme::inversive_distance;
  if (s == "combinatorial") return ricci::Scheme::combinatorial;
  throw UsageError("--metric must be circle-packing, inversive-distance or combinatorial, not '" + s + "'");
}

ricci::RadiusInit parse_radii(const std::string& s) {
  if (s == "mean") return ricci::RadiusInit::mean;
  if (s == "min") return ricci::RadiusInit::min;
  if (s == "least-squares") return ricci::RadiusInit::least_squares;
  throw UsageError("--radii must be mean, min or least-squares, not '" + s + "'");
}

ricci::LinearSolver parse_solver(const std::string& s) {
  for (auto k : {ricci::LinearSolver::automatic, ricci::LinearSolver::eigen_ldlt,
                 ricci::LinearSolver::eigen_llt, ricci::LinearSolver::cholmod_supernodal,
                 ricci::LinearSolver::cholmod_simplicial}) {
    if (s == ricci::to_string(k)) return k;
  }
  throw UsageError("unknown --solver '" + s + "'");
}


int parse_singularity(const std::string& s) {
  if (s == "auto") return -1;
  try {
    size_t used = 0;
    int v = std::stoi(s, &used);
    if (used == s.size() && v >= 0) return v;
  } catch (const std::logic_error&) {
  }
  throw UsageError("--singularity must be auto or a vertex index, not '" + s + "'");
}

}  // namespace msp
