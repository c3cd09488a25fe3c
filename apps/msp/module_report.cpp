#include "msp/module_report.h"

#include <sstream>

#include <ricci/mesh/errors.h>
#include <ricci/mesh/io.h>

#include "msp/flow_options.h"

namespace msp {

std::vector<int> parse_corners(const std::string& text, const std::string& option) {
  std::vector<int> corners;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ',')) {
    try {
      size_t used = 0;
      const int v = std::stoi(item, &used);
      if (used != item.size() || v < 0) throw std::invalid_argument("not a vertex");
      corners.push_back(v);
    } catch (const std::exception&) {
      throw UsageError("--" + option + " expects four vertex indices a,b,c,d, got '" + text + "'");
    }
  }
  if (corners.size() != 4) {
    throw UsageError("--" + option + " expects four vertex indices a,b,c,d, got '" + text + "'");
  }
  return corners;
}

ricci::ModuleOptions parse_module_options(const Args& args, bool shape) {
  ricci::ModuleOptions options;
  if (shape) {
    try {
      options.force_kind = ricci::parse_module_kind(args.get_or("kind", "auto"), options.kind);
    } catch (const ricci::InvalidInputError& e) {
      throw UsageError(e.what());
    }
    if (auto corners = args.get("corners")) options.corners = parse_corners(*corners, "corners");
    options.centre = args.get_int("centre", -1);
  }
  options.flow.tolerance = args.get_double("tolerance", options.flow.tolerance);
  if (!(options.flow.tolerance > 0)) throw UsageError("--tolerance must be positive");
  options.flow.solver = parse_solver(args.get_or("solver", "auto"));
  if (args.has("metric")) options.flow.scheme = parse_scheme(*args.get("metric"));
  if (args.has("radii")) options.flow.radii = parse_radii(*args.get("radii"));
  return options;
}

nlohmann::json module_json(const std::string& path, const ricci::Mesh& mesh,
                           const ricci::ModuleResult& result) {
  nlohmann::json j;
  j["mesh"] = path;
  j["vertices"] = mesh.n_vertices();
  j["faces"] = mesh.n_faces();
  j["genus"] = result.genus;
  j["boundary_loops"] = result.boundary_loops;
  j["kind"] = ricci::to_string(result.kind);
  nlohmann::json values = nlohmann::json::object();
  for (size_t i = 0; i < result.values.size(); ++i) values[result.names[i]] = result.values[i];
  j["module"] = values;
  j["vector"] = result.values;
  j["names"] = result.names;
  j["invariant"] = result.invariant;
  j["roundness"] = result.roundness;
  j["circle_iterations"] = result.circle_iterations;
  j["preparation"] = result.preparation;
  j["faces_used"] = result.faces_used;
  j["corners"] = result.corners;
  j["flow"] = {{"converged", result.converged},
               {"iterations", result.flow_iterations},
               {"max_curvature_error", result.flow_error}};
  j["seconds"] = result.seconds;
  return j;
}

ricci::ModuleResult module_of_file(const std::string& path, const ricci::ModuleOptions& options,
                                   ricci::Mesh& mesh) {
  mesh = ricci::read_mesh(path);
  ricci::ModuleResult result;
  try {
    result = ricci::conformal_module(mesh, options);
  } catch (const ricci::InvalidInputError& e) {
    throw ricci::InvalidInputError(path + ": " + e.what());
  }
  if (!result.converged) {
    throw ricci::SolverError(path + ": " + result.message);
  }
  return result;
}

}  // namespace msp
