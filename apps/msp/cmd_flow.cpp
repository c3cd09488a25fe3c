// msp flow MESH: discrete Ricci flow to a target curvature; prints iterations, error and time
// (one JSON object with --json), optionally writes the edge lengths.
#include <iomanip>
#include <iostream>
#include <sstream>

#include <msp/report/ricci_reports.h>
#include <nlohmann/json.hpp>
#include <ricci/flow/flow.h>
#include <ricci/intrinsic/routed_flow.h>
#include <ricci/mesh/errors.h>
#include <ricci/mesh/io.h>

#include "msp/cli.h"
#include "msp/commands.h"
#include "msp/flow_options.h"

namespace msp {

namespace {

std::string lengths_text(const ricci::Mesh& mesh, const ricci::EdgeLengths& lengths) {
  std::ostringstream out;
  out << std::setprecision(17);
  for (auto e : mesh.edges()) {
    auto h = mesh.halfedge_handle(e, 0);
    out << mesh.from_vertex_handle(h).idx() << " " << mesh.to_vertex_handle(h).idx() << " "
        << lengths[e.idx()] << "\n";
  }
  return out.str();
}

// One line 'from to length' per edge of the flipped triangulation (its own edges).
std::string lengths_text(const ricci::IntrinsicTriangulation& tri, const Eigen::VectorXd& u) {
  std::ostringstream out;
  out << std::setprecision(17);
  for (int e = 0; e < tri.edge_count(); ++e) {
    const int h = tri.edge_halfedge[static_cast<size_t>(e)];
    out << tri.tail[static_cast<size_t>(h)] << " " << tri.head(h) << " "
        << std::exp(tri.log_length_at(e, u)) << "\n";
  }
  return out.str();
}

}  // namespace

const CommandSpec& flow_command() {
  static const CommandSpec spec{
      "flow",
      "discrete Ricci flow to a target curvature (E2, H2, S2)",
      {{"MESH", "the input mesh: OBJ, OFF, PLY or STL, also gzipped"}},
      {{"geometry", "euclidean|hyperbolic|spherical", "the background geometry (euclidean)"},
       metric_option("inversive-distance, falling back to the others and then (closed, "
                     "euclidean) to intrinsic-delaunay if they fail",
                     true),
       radii_option(),
       {"target", "uniform|cone:VERTEX|boundary|boundary-loop",
        "the target curvature: uniform, one cone at VERTEX, flat with a curved boundary spread "
        "by length or on one loop (uniform)"},
       {"method", "newton|gradient", "Newton's method or gradient descent (newton)"},
       solver_option(),
       tolerance_option("1e-10"),
       {"max-iterations", "N", "at most N Newton or gradient steps"},
       {"lengths-out", "FILE",
        "write the flat metric: one line 'from to length' per edge (intrinsic-delaunay: per "
        "edge of the flipped triangulation)"},
       quiet_option(),
       json_option()}};
  return spec;
}

int run_flow(int argc, char** argv) {
  const Args args(argc, argv, flow_command());
  ricci::RoutedFlowOptions routed;
  ricci::FlowOptions& options = routed.flow;
  options.geometry = parse_geometry(args.get_or("geometry", "euclidean"));
  const bool intrinsic_only = args.get_or("metric", "") == "intrinsic-delaunay";
  options.scheme = intrinsic_only ? ricci::Scheme::inversive_distance
                                  : parse_scheme(args.get_or("metric", "inversive-distance"));
  // Without an explicit --metric, try the conformal metrics first and fall back (reported).
  options.fall_back_to_other_metrics = !args.has("metric") && !args.has("radii");
  routed.route = intrinsic_only ? ricci::FlowRoute::intrinsic_delaunay : ricci::FlowRoute::automatic;
  options.radii = parse_radii(args.get_or("radii", "min"));
  options.solver = parse_solver(args.get_or("solver", "auto"));
  options.tolerance = args.get_double("tolerance", 1e-10);
  const std::string method = args.get_or("method", "newton");
  if (method != "newton" && method != "gradient") {
    throw UsageError("--method must be newton or gradient, not '" + method + "'");
  }
  options.method =
      method == "newton" ? ricci::FlowMethod::newton : ricci::FlowMethod::gradient_descent;
  if (args.has("max-iterations")) {
    options.max_newton_iterations = options.max_gradient_iterations =
        routed.intrinsic_max_iterations = args.get_int("max-iterations", 0);
  }
  if (intrinsic_only && options.geometry != ricci::Geometry::euclidean) {
    throw UsageError("--metric intrinsic-delaunay needs --geometry euclidean");
  }
  if (!args.has("quiet")) {
    options.progress = [](const ricci::FlowProgress& p) {
      std::cerr << "iteration " << p.iteration << "  max|K - target| " << std::scientific
                << std::setprecision(3) << p.max_error << "  step " << std::defaultfloat << p.step
                << "  " << std::fixed << std::setprecision(3) << p.seconds << " s\n"
                << std::defaultfloat;
    };
  }
  const std::string path = args.positionals()[0];
  const ricci::Mesh mesh = ricci::read_mesh(path);
  ricci::Targets targets;
  try {
    targets = ricci::parse_target(args.get_or("target", "uniform"), mesh, options.geometry);
  } catch (const ricci::InfeasibleTargetError&) {
    throw;  // a well-formed target the mesh cannot take: an error, not a usage error
  } catch (const ricci::InvalidInputError& e) {
    throw UsageError(std::string("--") + e.what());
  }
  const ricci::RoutedFlowResult run = ricci::routed_flow(mesh, targets, routed);
  const ricci::FlowResult& result = run.flow;

  if (auto out = args.get("lengths-out"); out && result.converged()) {
    write_text_atomically(*out, run.intrinsic
                                    ? lengths_text(run.intrinsic->triangulation, run.intrinsic->u)
                                    : lengths_text(mesh, result.lengths));
  }
  if (args.has("json")) {
    std::cout << flow_report_json(path, mesh, options, run).dump() << "\n";
  } else {
    std::cout << "status " << ricci::to_string(result.status) << "\niterations "
              << result.iterations << "\nmax_curvature_error " << result.max_error
              << "\nseconds " << result.timings.total << "\nvertices " << mesh.n_vertices()
              << "\nfaces " << mesh.n_faces() << "\nmetric " << run.metric << "\n";
  }
  if (!result.converged()) throw ricci::SolverError(result.message);
  return 0;
}

}  // namespace msp
