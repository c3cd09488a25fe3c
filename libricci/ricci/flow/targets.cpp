#include "ricci/flow/targets.h"

#include <cmath>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>

#include "ricci/mesh/errors.h"

namespace ricci {

namespace {

std::string format(double x) {
  std::ostringstream s;
  s.precision(12);
  s << x;
  return s.str();
}

double loop_length(const Mesh& mesh, const std::vector<int>& loop) {
  double length = 0;
  for (size_t i = 0; i < loop.size(); ++i) {
    length += (mesh.point(VertexHandle(loop[(i + 1) % loop.size()])) -
               mesh.point(VertexHandle(loop[i])))
                  .norm();
  }
  return length;
}

// Adds `total` to the vertices of `loops`, each weighted by half its two boundary edges.
void spread_by_length(const Mesh& mesh, const std::vector<std::vector<int>>& loops, double total,
                      Eigen::VectorXd& K) {
  double length = 0;
  for (const auto& loop : loops) length += loop_length(mesh, loop);
  for (const auto& loop : loops) {
    const size_t n = loop.size();
    for (size_t i = 0; i < n; ++i) {
      const auto p = mesh.point(VertexHandle(loop[i]));
      const double half = 0.5 * ((mesh.point(VertexHandle(loop[(i + 1) % n])) - p).norm() +
                                 (mesh.point(VertexHandle(loop[(i + n - 1) % n])) - p).norm());
      K[loop[i]] += total * half / length;
    }
  }
}

void check_vertex(const Mesh& mesh, int vertex) {
  if (vertex < 0 || vertex >= static_cast<int>(mesh.n_vertices())) {
    throw InvalidInputError("vertex " + std::to_string(vertex) + " is out of range (the mesh has " +
                            std::to_string(mesh.n_vertices()) + " vertices)");
  }
}

}  // namespace

Targets uniform_target(const Mesh& mesh, Geometry geometry) {
  const MeshTables t = build_mesh_tables(mesh);
  const int chi = t.euler_characteristic;
  const bool fits = (geometry == Geometry::euclidean && chi == 0) ||
                    (geometry == Geometry::hyperbolic && chi < 0) ||
                    (geometry == Geometry::spherical && chi > 0);
  if (!fits) {
    throw InfeasibleTargetError("uniform target K = 0 needs " +
                                std::string(chi == 0 ? "euclidean" : chi < 0 ? "hyperbolic" : "spherical") +
                                " geometry for Euler characteristic " + std::to_string(chi) +
                                ", not " + to_string(geometry));
  }
  return Targets{Eigen::VectorXd::Zero(t.num_vertices())};
}

Targets single_cone_target(const Mesh& mesh, int vertex) {
  check_vertex(mesh, vertex);
  const MeshTables t = build_mesh_tables(mesh);
  Targets targets{Eigen::VectorXd::Zero(t.num_vertices())};
  if (!t.boundary_loops.empty()) {
    spread_by_length(mesh, t.boundary_loops, 2.0 * M_PI * t.euler_characteristic, targets.curvature);
  } else {
    targets.curvature[vertex] = 2.0 * M_PI * t.euler_characteristic;
  }
  return targets;
}

Targets cones_target(const Mesh& mesh, const std::vector<std::pair<int, double>>& cones) {
  const MeshTables t = build_mesh_tables(mesh);
  Targets targets{Eigen::VectorXd::Zero(t.num_vertices())};
  std::set<int> seen;
  double sum = 0;
  for (const auto& [vertex, K] : cones) {
    check_vertex(mesh, vertex);
    if (!seen.insert(vertex).second) {
      throw InvalidInputError("cone vertex " + std::to_string(vertex) + " is listed twice");
    }
    targets.curvature[vertex] = K;
    sum += K;
  }
  if (!t.boundary_loops.empty()) {
    spread_by_length(mesh, t.boundary_loops, 2.0 * M_PI * t.euler_characteristic - sum,
                     targets.curvature);
  }
  return targets;
}

Targets boundary_target(const Mesh& mesh, BoundaryMode mode, int loop) {
  const MeshTables t = build_mesh_tables(mesh);
  if (t.boundary_loops.empty()) throw InvalidInputError("boundary target on a closed mesh");
  const int loops = static_cast<int>(t.boundary_loops.size());
  Targets targets{Eigen::VectorXd::Zero(t.num_vertices())};
  const double total = 2.0 * M_PI * t.euler_characteristic;
  if (mode == BoundaryMode::spread_by_length) {
    spread_by_length(mesh, t.boundary_loops, total, targets.curvature);
    return targets;
  }
  if (loop < 0) {
    loop = 0;
    for (int i = 1; i < loops; ++i) {
      if (loop_length(mesh, t.boundary_loops[i]) > loop_length(mesh, t.boundary_loops[loop])) loop = i;
    }
  }
  if (mode == BoundaryMode::circle_domain) {
    for (int i = 0; i < loops; ++i) {
      const double loop_total = i == loop ? total + 2.0 * M_PI * (loops - 1) : -2.0 * M_PI;
      spread_by_length(mesh, {t.boundary_loops[i]}, loop_total, targets.curvature);
    }
    return targets;
  }
  if (loop >= loops) {
    throw InvalidInputError("boundary loop " + std::to_string(loop) + " is out of range (the mesh has " +
                            std::to_string(loops) + ")");
  }
  spread_by_length(mesh, {t.boundary_loops[loop]}, total, targets.curvature);
  return targets;
}

void check_targets(const MeshTables& t, const Targets& targets, Geometry geometry, Scheme scheme) {
  const Eigen::VectorXd& K = targets.curvature;
  if (K.size() != t.num_vertices()) {
    throw InvalidInputError("target curvature has " + std::to_string(K.size()) + " entries for " +
                            std::to_string(t.num_vertices()) + " vertices");
  }
  for (int v = 0; v < t.num_vertices(); ++v) {
    const double limit = t.is_boundary_vertex[v] ? M_PI : 2.0 * M_PI;
    if (!std::isfinite(K[v]) || !(K[v] < limit)) {
      throw InfeasibleTargetError("target curvature " + format(K[v]) + " at " +
                                  (t.is_boundary_vertex[v] ? "boundary " : "") + "vertex " +
                                  std::to_string(v) + " is not below " +
                                  (t.is_boundary_vertex[v] ? "π" : "2π") +
                                  " (the angle sum there must stay positive)");
    }
  }
  const double sum = K.sum(), needed = 2.0 * M_PI * t.euler_characteristic;
  const std::string sums = "sum of target curvature " + format(sum) + ", 2πχ = " + format(needed) +
                           " (χ = " + std::to_string(t.euler_characteristic) + ")";
  const double slack = 1e-9 * (1.0 + K.cwiseAbs().sum());
  if (geometry == Geometry::euclidean && std::abs(sum - needed) > slack) {
    throw InfeasibleTargetError("target violates Gauss-Bonnet for euclidean geometry: " + sums +
                                "; they must be equal");
  }
  if (geometry == Geometry::hyperbolic && !(sum > needed + slack)) {
    throw InfeasibleTargetError("target violates Gauss-Bonnet for hyperbolic geometry: " + sums +
                                "; the sum must exceed 2πχ (faces carry negative curvature)");
  }
  if (geometry == Geometry::spherical && !(sum < needed - slack)) {
    throw InfeasibleTargetError("target violates Gauss-Bonnet for spherical geometry: " + sums +
                                "; the sum must be below 2πχ (faces carry positive curvature)");
  }
  if (scheme == Scheme::inversive_distance) return;
  for (int v = 0; v < t.num_vertices(); ++v) {
    if (t.is_boundary_vertex[v] || K[v] >= 0) continue;
    const double needed_valence = 4.0 - 2.0 * K[v] / M_PI;
    if (t.valence[v] < needed_valence - 1e-9) {
      throw InfeasibleTargetError(
          "vertex " + std::to_string(v) + " has valence " + std::to_string(t.valence[v]) +
          " but target curvature " + format(K[v]) + " needs valence >= " +
          std::to_string(static_cast<int>(std::ceil(needed_valence - 1e-9))) + " with " +
          to_string(scheme) +
          " (Φ in [0, π/2]): valence modification needed (split edges of its link), or use "
          "inversive-distance");
    }
  }
}

Targets parse_target(const std::string& spec, const Mesh& mesh, Geometry geometry) {
  if (spec == "uniform") return uniform_target(mesh, geometry);
  if (spec == "boundary") return boundary_target(mesh, BoundaryMode::spread_by_length);
  if (spec == "boundary-loop") return boundary_target(mesh, BoundaryMode::one_loop);
  if (spec.rfind("cone:", 0) == 0) {
    size_t used = 0;
    int vertex = -1;
    try {
      vertex = std::stoi(spec.substr(5), &used);
    } catch (const std::logic_error&) {
      used = 0;
    }
    if (used > 0 && used == spec.size() - 5) return single_cone_target(mesh, vertex);
    throw InvalidInputError("target cone:VERTEX needs a vertex index, got '" + spec + "'");
  }
  throw InvalidInputError("target must be uniform, cone:VERTEX, boundary or boundary-loop, not '" +
                          spec + "'");
}

}  // namespace ricci
