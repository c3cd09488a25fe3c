// msp bezier SPLINE.msp -o PATCHES.json [--json]: the spline's exact polynomial pieces as
// triangular Bezier patches (spline/surface/bezier.h; file format: docs/bezier.md). Prints the
// figures (domain faces, patches, seconds), or one JSON object with --json.
#include <chrono>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

#include <ricci/mesh/errors.h>
#include <spline/io/spline_file.h>
#include <spline/surface/bezier.h>

#include "msp/cli.h"
#include "msp/commands.h"
#include "msp/surface_json.h"

namespace msp {

const CommandSpec& bezier_command() {
  static const CommandSpec spec{
      "bezier",
      "export a spline file's exact polynomial pieces as Bezier patches (JSON)",
      {{"SPLINE.msp", "the spline file to export"}},
      {{"output", "PATCHES.json", "write the Bezier patches (docs/bezier.md)", true},
       json_option(),
       quiet_option()}};
  return spec;
}

int run_bezier(int argc, char** argv) {
  const Args args(argc, argv, bezier_command());
  const auto output = args.get("output");  // required: Args has checked it
  const std::string& input = args.positionals()[0];
  const auto start = std::chrono::steady_clock::now();
  const spline::SplineSurface surface = spline::load_spline_surface(input);
  const spline::BezierExport patches = spline::bezier_patches(surface);
  write_file_atomically(*output, [&](const std::string& temp) {
    std::ofstream out(temp, std::ios::binary);
    write_bezier_json(patches, out);
    out.flush();
    if (!out) throw ricci::IOError(*output + ": cannot be written");
  });
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (args.has("json")) {
    nlohmann::ordered_json json = {{"input", input},        {"output", *output},
                                   {"degree", patches.degree}, {"faces", patches.faces},
                                   {"patches", patches.patches.size()}, {"seconds", seconds}};
    std::cout << json.dump(2) << "\n";
  } else {
    std::cout << "wrote " << patches.patches.size() << " Bezier patches of degree "
              << patches.degree << " over " << patches.faces << " domain faces to " << *output
              << " (" << seconds << " s)\n";
  }
  return 0;
}

}  // namespace msp
