#include "ricci/flow/flow.h"

#include <algorithm>
#include <numeric>
#include <sstream>

#include "ricci/flow/flow_internal.h"
#include "ricci/mesh/errors.h"
#include "ricci/metric/curvature.h"

namespace ricci {

std::string to_string(FlowStatus status) {
  switch (status) {
    case FlowStatus::converged:
      return "converged";
    case FlowStatus::max_iterations:
      return "max-iterations";
    case FlowStatus::stalled:
      return "stalled";
    default: return "triangle-inequality";
  }
}

std::string to_string(FlowMethod method) {
  return method == FlowMethod::newton ? "newton" : "gradient";
}

namespace detail {

std::string failure_message(const FlowRun& run, const FlowState& state, FlowStatus status,
                            const std::string& reason) {
  const Eigen::VectorXd error = (state.curvature - run.target).cwiseAbs();
  std::vector<int> order(error.size());
  std::iota(order.begin(), order.end(), 0);
  const size_t shown = std::min<size_t>(5, order.size());
  std::partial_sort(order.begin(), order.begin() + shown, order.end(),
                    [&](int a, int b) { return error[a] > error[b]; });
  std::ostringstream out;
  out.precision(6);
  out << "Ricci flow did not converge (" << to_string(status) << "): " << reason
      << "; max |K - target| = " << error.maxCoeff() << "; worst vertices:";
  for (size_t i = 0; i < shown; ++i) {
    const int v = order[i];
    out << (i ? "," : "") << " " << v << " (K " << state.curvature[v] << ", target "
        << run.target[v] << ")";
  }
  out << ". Try: ";
  if (status == FlowStatus::max_iterations) {
    out << "more iterations or a looser tolerance; ";
  }
  if (run.geometry == Geometry::spherical) {
    out << "(S2: the spherical energy is not convex and circle packings on the sphere are only "
           "unique up to Möbius maps, so Newton from the mesh's metric can drift to degenerate "
           "triangles; start from a flat metric laid out and mapped by inverse stereographic "
           "projection) ";
  }
  out << "valence modification around large cones (split edges of the cone vertex's link), "
         "another metric (inversive-distance or circle-packing, min radii), or a target "
         "with smaller cones.";
  return out.str();
}

}  // namespace detail

namespace {

// H2/S2 lengths are absolute: scale the mesh so its area is the one Gauss-Bonnet gives the
// target, λ Σ A = 2πχ - Σ K̄, so that the initial metric is near the answer's size.
double geometry_length_scale(const MeshTables& t, const EdgeLengths& lengths, Geometry g,
                             const Eigen::VectorXd& target) {
  if (g == Geometry::euclidean) return 1.0;
  const double area_needed =
      curvature_sign(g) * (2.0 * M_PI * t.euler_characteristic - target.sum());
  const double area = face_areas(t, lengths, Geometry::euclidean).sum();
  return std::sqrt(area_needed / area);
}

}  // namespace

FlowResult flow(const MeshTables& tables, const CirclePackingMetric& initial,
                const Targets& targets, const FlowOptions& options) {
  const Stopwatch start;
  check_targets(tables, targets, initial.geometry, initial.scheme);
  if (initial.gamma.size() != tables.num_vertices() || initial.eta.size() != tables.num_edges()) {
    throw InvalidInputError("initial metric does not match the mesh's element counts");
  }
  if (!(options.tolerance > 0)) throw InvalidInputError("flow tolerance must be positive");
  FlowResult result;
  result.metric = initial;
  result.target = targets.curvature;
  result.solver = options.solver;
  const detail::FlowRun run{tables, initial.geometry, initial.eta, targets.curvature, options, start};
  FlowState state;
  Stopwatch t0;
  if (!evaluate_flow_state(tables, initial.geometry, initial.eta,
                           u_from_radii(initial.geometry, initial.gamma), state)) {
    throw InvalidInputError("the initial metric is not valid: " +
                            (state.bad_face >= 0 ? "face " + std::to_string(state.bad_face) +
                                                       " violates the triangle inequality"
                                                 : state.bad_edge >= 0
                                                       ? "edge " + std::to_string(state.bad_edge) + " has no length"
                                                       : "vertex " + std::to_string(state.bad_vertex) +
                                                             " has a radius out of range"));
  }
  result.timings.evaluation += t0.seconds();
  if (options.method == FlowMethod::newton) {
    detail::run_newton(run, state, result);
  } else {
    detail::run_gradient_descent(run, state, result);
  }
  result.u = state.u;
  result.metric.gamma = state.gamma;
  result.lengths = state.lengths;
  result.curvature = state.curvature;
  result.max_error = detail::max_error(state, run.target);
  result.timings.total = start.seconds();
  return result;
}

FlowResult flow(const Mesh& mesh, const Targets& targets, const FlowOptions& options) {
  const Stopwatch start;
  const MeshTables tables = build_mesh_tables(mesh);
  // Gauss-Bonnet first, before any work; the valence test belongs to each attempt's metric.
  check_targets(tables, targets, options.geometry,
                options.fall_back_to_other_metrics ? Scheme::inversive_distance : options.scheme);
  EdgeLengths lengths = mesh_edge_lengths(mesh);
  const double scale = geometry_length_scale(tables, lengths, options.geometry, targets.curvature);
  lengths *= scale;
  std::vector<std::pair<Scheme, RadiusInit>> attempts = {{options.scheme, options.radii}};
  if (options.fall_back_to_other_metrics) {
    for (auto next : {std::pair{Scheme::inversive_distance, RadiusInit::min},
                      std::pair{Scheme::inversive_distance, RadiusInit::mean},
                      std::pair{Scheme::circle_packing, RadiusInit::mean},
                      std::pair{Scheme::combinatorial, RadiusInit::mean}}) {
      if (next != attempts.front()) attempts.push_back(next);
    }
  }
  FlowResult result, best;
  std::vector<std::string> failures;
  for (const auto& [scheme, radii] : attempts) {
    const Stopwatch attempt_start;
    const CirclePackingMetric initial =
        initial_metric(tables, lengths, options.geometry, scheme, radii);
    const double setup = attempt_start.seconds();
    try {
      result = flow(tables, initial, targets, options);
    } catch (const InfeasibleTargetError&) {
      if (attempts.size() == 1) throw;
      failures.push_back(to_string(scheme) + ": target infeasible for this metric");
      continue;
    }
    result.timings.setup += setup;
    if (result.converged()) break;
    // If nothing converges, report the attempt that came closest.
    if (best.error_history.empty() || result.max_error < best.max_error) best = result;
    failures.push_back(to_string(scheme) + (radii == RadiusInit::min ? "/min" : "/mean") + ": " +
                       result.message);
  }
  if (!result.converged() && !best.error_history.empty()) result = std::move(best);
  result.failed_attempts = std::move(failures);
  result.length_scale = scale;
  result.timings.total = start.seconds();
  return result;
}

}  // namespace ricci
