// msp: the manifold-spline command-line tool. Dispatches to one subcommand per file.
#include <cstring>
#include <exception>
#include <iostream>
#include <string>

#include <ricci/mesh/errors.h>

#include "msp/cli.h"
#include "msp/commands.h"

namespace {

struct Subcommand {
  const char* name;
  int (*run)(int, char**);
  const char* summary;
};

const Subcommand kSubcommands[] = {
    {"info", msp::run_info, "describe a mesh: counts, topology, defects (--json)"},
    {"generate", msp::run_generate, "mesh a closed or open test surface of a given genus"},
    {"flow", msp::run_flow, "discrete Ricci flow to a target curvature (E2, H2, S2)"},
    {"atlas", msp::run_atlas, "one-cone flat metric, cut graph, layout and affine atlas"},
    {"uniformize", msp::run_uniformize, "hyperbolic / spherical / flat uniformization structures"},
    {"fit", msp::run_fit, "fit a manifold spline to a mesh and export glTF"},
    {"edit", msp::run_edit, "move control points of a spline file (.msp): by index or a region"},
    {"eval", msp::run_eval,
     "evaluate a spline file: position, derivatives, normal, curvatures (points, closest points)"},
    {"bezier", msp::run_bezier,
     "export a spline file's exact polynomial pieces as Bezier patches (JSON)"},
    {"module", msp::run_module, "conformal module: annulus, rectangle, flat torus, hyperbolic"},
    {"index", msp::run_index, "conformal modules of meshes grouped by topology, distances"},
};

void print_usage() {
  std::cerr << "usage: msp <command> [options]\n\ncommands:\n";
  for (const auto& c : kSubcommands) std::cerr << "  " << c.name << "\t" << c.summary << "\n";
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h")) {
    print_usage();
    return argc < 2 ? 2 : 0;
  }
  const std::string name = argv[1];
  for (const auto& c : kSubcommands) {
    if (name != c.name) continue;
    try {
      return c.run(argc - 2, argv + 2);
    } catch (const msp::UsageError& e) {
      std::cerr << "msp " << name << ": " << e.what() << "\n";
      return 2;
    } catch (const ricci::Error& e) {
      std::cerr << "msp " << name << ": error: " << e.what() << "\n";
      return 1;
    } catch (const std::bad_alloc&) {
      std::cerr << "msp " << name << ": error: out of memory\n";
      return 1;
    } catch (const std::exception& e) {
      std::cerr << "msp " << name << ": internal error: " << e.what() << "\n";
      return 3;
    }
  }
  std::cerr << "msp: unknown command '" << name << "' (msp --help lists them)\n";
  return 2;
}
