#include "msp/flow_options.h"

#include <stdexcept>

#include "msp/cli.h"

namespace msp {

ricci::Geometry parse_geometry(const std::string& s) {
  if (s == "euclidean" || s == "e2") return ricci::Geometry::Euclidean;
  if (s == "hyperbolic" || s == "h2") return ricci::Geometry::Hyperbolic;
  if (s == "spherical" || s == "s2") return ricci::Geometry::Spherical;
  throw UsageError("--geometry must be euclidean, hyperbolic or spherical, not '" + s + "'");
}

ricci::Scheme parse_scheme(const std::string& s) {
  if (s == "circle-packing") return ricci::Scheme::CirclePacking;
  if (s == "inversive-distance") return ricci::Scheme::InversiveDistance;
  if (s == "combinatorial") return ricci::Scheme::Combinatorial;
  throw UsageError("--metric must be circle-packing, inversive-distance or combinatorial, not '" + s + "'");
}

ricci::RadiusInit parse_radii(const std::string& s) {
  if (s == "mean") return ricci::RadiusInit::Mean;
  if (s == "min") return ricci::RadiusInit::Min;
  if (s == "least-squares") return ricci::RadiusInit::LeastSquares;
  throw UsageError("--radii must be mean, min or least-squares, not '" + s + "'");
}

ricci::LinearSolver parse_solver(const std::string& s) {
  for (auto k : {ricci::LinearSolver::Auto, ricci::LinearSolver::EigenLDLT, ricci::LinearSolver::EigenLLT,
                 ricci::LinearSolver::CholmodSupernodal, ricci::LinearSolver::CholmodSimplicial}) {
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
