// msp flow MESH: discrete Ricci flow to a target curvature; prints iterations, error and time
// (one JSON object with --json), optionally writes the edge lengths.
#include <iomanip>
#include <iostream>
#include <sstream>

#include <msp/report/ricci_reports.h>
#include <nlohmann/json.hpp>
#include <ricci/flow/flow.h>
#include <ricci/mesh/errors.h>
#include <ricci/mesh/io.h>
#include <ricci/metric/mesh_tables.h>

#include "msp/cli.h"
#include "msp/commands.h"
#include "msp/flow_options.h"

namespace msp {

namespace {

ricci::Targets parse_target(const std::string& s, const ricci::Mesh& mesh, ricci::Geometry g) {
  if (s == "uniform") return ricci::uniform_target(mesh, g);
  if (s == "boundary") return ricci::boundary_target(mesh, ricci::BoundaryMode::spread_by_length);
  if (s == "boundary-loop") return ricci::boundary_target(mesh, ricci::BoundaryMode::one_loop);
  if (s.rfind("cone:", 0) == 0) {
    try {
      size_t used = 0;
      const int v = std::stoi(s.substr(5), &used);
      if (used == s.size() - 5) return ricci::single_cone_target(mesh, v);
    } catch (const std::logic_error&) {
    }
    throw UsageError("--target cone:VERTEX needs a vertex index, got '" + s + "'");
  }
  throw UsageError("--target must be uniform, cone:VERTEX, boundary or boundary-loop, not '" + s + "'");
}

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

}  // namespace

const CommandSpec& flow_command() {
  static const CommandSpec spec{
      "flow",
      "discrete Ricci flow to a target curvature (E2, H2, S2)",
      {{"MESH", "the input mesh: OBJ, OFF, PLY or STL, also gzipped"}},
      {{"geometry", "euclidean|hyperbolic|spherical", "the background geometry (euclidean)"},
       metric_option("inversive-distance, falling back to the others if it fails"),
       radii_option(),
       {"target", "uniform|cone:VERTEX|boundary|boundary-loop",
        "the target curvature: uniform, one cone at VERTEX, flat with a curved boundary spread "
        "by length or on one loop (uniform)"},
       {"method", "newton|gradient", "Newton's method or gradient descent (newton)"},
       solver_option(),
       tolerance_option("1e-10"),
       {"max-iterations", "N", "at most N Newton or gradient steps"},
       {"lengths-out", "FILE", "write the flat metric: one line 'from to length' per edge"},
       quiet_option(),
       json_option()}};
  return spec;
}

int run_flow(int argc, char** argv) {
  const Args args(argc, argv, flow_command());
  ricci::FlowOptions options;
  options.geometry = parse_geometry(args.get_or("geometry", "euclidean"));
  options.scheme = parse_scheme(args.get_or("metric", "inversive-distance"));
  // Without an explicit --metric, try the conformal metrics first and fall back (reported).
  options.fall_back_to_other_metrics = !args.has("metric") && !args.has("radii");
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
    options.max_newton_iterations = options.max_gradient_iterations = args.get_int("max-iterations", 0);
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
  const ricci::Targets targets =
      parse_target(args.get_or("target", "uniform"), mesh, options.geometry);
  const ricci::FlowResult result = ricci::flow(mesh, targets, options);

  if (auto out = args.get("lengths-out"); out && result.converged()) {
    write_text_atomically(*out, lengths_text(mesh, result.lengths));
  }
  if (args.has("json")) {
    const nlohmann::json j = flow_report_json(path, mesh, options, result);
    std::cout << j.dump() << "\n";
  } else {
    std::cout << "status " << ricci::to_string(result.status) << "\niterations "
              << result.iterations << "\nmax_curvature_error " << result.max_error
              << "\nseconds " << result.timings.total << "\nvertices " << mesh.n_vertices()
              << "\nfaces " << mesh.n_faces() << "\nmetric "
              << ricci::to_string(result.metric.scheme) << "\n";
  }
  if (!result.converged()) throw ricci::SolverError(result.message);
  return 0;
}

}  // namespace msp
