// msp module MESH: the conformal module of a surface by the Ricci flow (issue 17): annulus,
// rectangle (with --corners), flat torus, hyperbolic boundary lengths or Fuchsian translation
// lengths, chosen from the topology or by --kind. Prints a summary or one JSON object; -o
// writes the SVG of the canonical domain.
#include <iostream>

#include <ricci/analysis/conformal_module.h>

#include "msp/cli.h"
#include "msp/commands.h"
#include "msp/module_report.h"
#include "msp/svg_module.h"

namespace msp {

namespace {

void print_summary(const ricci::Mesh& mesh, const ricci::ModuleResult& r) {
  std::cout << "kind " << ricci::to_string(r.kind) << "\ngenus " << r.genus
            << "\nboundary_loops " << r.boundary_loops << "\nvertices " << mesh.n_vertices()
            << "\nfaces " << mesh.n_faces() << "\n";
  for (size_t i = 0; i < r.values.size(); ++i) {
    std::cout << r.names[i] << " " << r.values[i] << "\n";
  }
  if (!r.invariant) std::cout << "invariant no (depends on the cut graph's basis)\n";
  if (r.kind == ricci::ModuleKind::Annulus || r.kind == ricci::ModuleKind::Rectangle ||
      r.kind == ricci::ModuleKind::CircleDomain || r.kind == ricci::ModuleKind::Disk) {
    std::cout << "roundness " << r.roundness << "\n";
  }
  if (r.kind == ricci::ModuleKind::CircleDomain || r.kind == ricci::ModuleKind::Disk) {
    std::cout << "circle_iterations " << r.circle_iterations << "\n";
  }
  if (r.preparation != "as given") {
    std::cout << "preparation " << r.preparation << " (" << r.faces_used << " faces)\n";
  }
  if (!r.corners.empty()) {
    std::cout << "corners";
    for (int c : r.corners) std::cout << " " << c;
    std::cout << "\n";
  }
  std::cout << "flow_iterations " << r.flow_iterations << "\nmax_curvature_error "
            << r.flow_error << "\nseconds " << r.seconds << "\n";
}

}  // namespace

const CommandSpec& module_command() {
  static const CommandSpec spec{
      "module",
      "conformal module: annulus, rectangle, disk, flat torus, hyperbolic",
      {{"MESH", "the input mesh: OBJ, OFF, PLY or STL, also gzipped"}},
      {json_option(),
       {"output", "domain.svg", "draw the canonical domain as SVG"},
       {"corners", "a,b,c,d", "four boundary vertices: the module of the rectangle they make"},
       {"kind", "auto|annulus|rectangle|disk|flat-torus|circle-domain|hyperbolic|fuchsian",
        "the module to compute (auto: chosen from the topology)"},
       {"centre", "V", "--kind disk: the interior vertex sent to 0 (default: the deepest)"},
       tolerance_option("1e-11"),
       solver_option(),
       metric_option("circle-packing, no fall-back"),
       radii_option(),
       quiet_option()}};
  return spec;
}

int run_module(int argc, char** argv) {
  const Args args(argc, argv, module_command());
  const ricci::ModuleOptions options = parse_module_options(args, true);
  const std::string path = args.positionals()[0];
  ricci::Mesh mesh;
  const ricci::ModuleResult result = module_of_file(path, options, mesh);
  if (auto out = args.get("output")) {
    ModuleSvgOptions svg;
    svg.title = path;
    write_text_atomically(*out, module_svg(result, svg));
  }
  if (args.has("json")) {
    std::cout << module_json(path, mesh, result).dump() << "\n";
  } else {
    print_summary(mesh, result);
  }
  return 0;
}

}  // namespace msp
