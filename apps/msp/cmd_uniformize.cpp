// msp uniformize MESH: the uniformization metric by the Ricci flow and the geometric structure
// on it (issue 7): Fuchsian generators with their Klein (real projective) transitions for
// genus >= 2, translations and modulus for a torus, the unit-sphere embedding for genus 0; open
// surfaces through their double cover. Prints a summary or one JSON object; -o writes the
// Poincaré-disk picture of a few rings of the universal cover.
#include <iostream>

#include <msp/report/ricci_reports.h>
#include <nlohmann/json.hpp>
#include <ricci/hyperbolic/klein.h>
#include <ricci/hyperbolic/uniformize.h>
#include <ricci/mesh/errors.h>
#include <ricci/mesh/io.h>

#include "msp/cli.h"
#include "msp/commands.h"
#include "msp/flow_options.h"
#include "msp/svg_poincare.h"

namespace msp {

namespace {

void print_summary(const ricci::Mesh& mesh, const ricci::Uniformization& u) {
  std::cout << "geometry " << ricci::to_string(u.geometry) << "\ngenus " << u.genus
            << (u.doubled ? " (double cover)" : "") << "\nvertices " << mesh.n_vertices()
            << "\nfaces " << mesh.n_faces() << "\nmax_curvature_error " << u.flow.max_error
            << "\n";
  if (u.geometry != ricci::Geometry::spherical) {
    std::cout << "side_spread " << u.pairings.max_spread << "\nrelation_residual "
              << u.group.relation_residual << "\n";
    for (size_t i = 0; i < u.group.generators.size(); ++i) {
      const ricci::Mobius& g = u.group.generators[i];
      std::cout << generator_name(i) << " theta " << g.theta();
      if (u.geometry == ricci::Geometry::hyperbolic) {
        std::cout << " z0 " << g.z0().real() << " " << g.z0().imag() << "\n";
      } else {
        std::cout << " translation " << g(0.0).real() << " " << g(0.0).imag() << "\n";
      }
    }
  }
  if (u.geometry == ricci::Geometry::euclidean) {
    std::cout << "modulus " << u.reduced_modulus.real() << " " << u.reduced_modulus.imag() << "\n";
  }
  std::cout << "seconds " << u.timings.total << "\n";
}

}  // namespace

const CommandSpec& uniformize_command() {
  static const CommandSpec spec{
      "uniformize",
      "hyperbolic / spherical / flat uniformization structures (Fuchsian group, modulus)",
      {{"MESH", "the input mesh: OBJ, OFF, PLY or STL, also gzipped"}},
      {{"output", "cover.svg", "write the Poincare-disk picture of a few rings of the cover"},
       json_option(),
       {"depth", "N", "rings of the universal cover in the picture, 0 to 6 (5)"},
       {"seed-face", "F", "the face the layout starts from (the most central one)"},
       {"root", "V", "the vertex the cut graph's loops are based at (central)"},
       solver_option(),
       tolerance_option("1e-12"),
       metric_option("inversive-distance, falling back to the others if it fails"),
       radii_option(),
       quiet_option()}};
  return spec;
}

int run_uniformize(int argc, char** argv) {
  const Args args(argc, argv, uniformize_command());
  ricci::UniformizeOptions options;
  options.seed_face = args.get_int("seed-face", -1);
  options.root_vertex = args.get_int("root", -1);
  if (args.has("root") && options.root_vertex < 0) {
    throw UsageError("--root must be a vertex index (0 or more)");
  }
  options.flow.solver = parse_solver(args.get_or("solver", "auto"));
  if (args.has("metric")) options.flow.scheme = parse_scheme(*args.get("metric"));
  if (args.has("radii")) options.flow.radii = parse_radii(*args.get("radii"));
  // As in msp flow and msp atlas: an explicit metric is used alone.
  options.flow.fall_back_to_other_metrics = !args.has("metric") && !args.has("radii");
  options.flow.tolerance = args.get_double("tolerance", options.flow.tolerance);
  const int depth = args.get_int("depth", 5);
  if (depth < 0 || depth > 6) throw UsageError("--depth must be between 0 and 6");
  const std::string path = args.positionals()[0];
  const ricci::Mesh mesh = ricci::read_mesh(path);
  const ricci::Uniformization u = ricci::uniformize(mesh, options);
  if (!u.converged()) throw ricci::SolverError("the flow did not converge: " + u.flow.message);
  if (auto out = args.get("output")) {
    PoincareSvgOptions svg;
    svg.title = path;
    svg.depth = depth;
    write_text_atomically(*out, uniformization_svg(u, svg));
  }
  if (args.has("json")) {
    std::cout << uniformize_report_json(path, mesh, u).dump() << "\n";
  } else {
    print_summary(mesh, u);
  }
  return 0;
}

}  // namespace msp
