// msp tessellate SPLINE.msp -o OUT.glb|obj|ply [--density d] [--json]: a spline file's surface
// tessellated again, without refitting (spline::tessellate_surface: the spline over the domain
// faces it shows, the fill patches welded in, watertight as msp fit writes it). The same
// density as msp fit gives the same vertex positions.
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

#include <msp/io/tessellation_io.h>
#include <spline/io/spline_file.h>
#include <spline/surface/tessellate_surface.h>

#include "msp/cli.h"
#include "msp/commands.h"

namespace msp {

const CommandSpec& tessellate_command() {
  static const CommandSpec spec{
      "tessellate",
      "tessellate a spline file (.msp) again at any density, without refitting",
      {{"SPLINE.msp", "the spline file (msp fit --spline)"}},
      {{"output", "OUT.glb", "the tessellation: .glb, .obj or .ply by extension", true},
       {"density", "d",
        "samples per domain edge - 1 (d^2 triangles per domain face); default: msp fit's "
        "choice for the domain's size"},
       json_option(),
       quiet_option()}};
  return spec;
}

int run_tessellate(int argc, char** argv) {
  const Args args(argc, argv, tessellate_command());
  const std::string& input = args.positionals()[0];
  const std::string output = *args.get("output");
  const int density = args.get_int("density", 0);
  if (args.has("density") && density < 1) throw UsageError("--density must be at least 1");
  const spline::SplineSurface surface = spline::load_spline_surface(input);
  spline::TessellationOptions options;
  options.density =
      density > 0 ? density : spline::default_density(surface.spline.space->domain_face_count());
  const spline::Tessellation t = spline::tessellate_surface(surface, options);
  write_tessellation(t, output);
  const spline::WatertightReport topology = spline::check_watertight(t.triangles, t.positions);
  const nlohmann::json report = {{"spline", input},
                                 {"output", output},
                                 {"density", t.density},
                                 {"vertices", t.positions.rows()},
                                 {"triangles", t.triangles.size()},
                                 {"fills", surface.fills.size()},
                                 {"boundary_loops", topology.boundary_loops},
                                 {"manifold", topology.manifold()}};
  if (args.has("json")) {
    std::cout << report.dump(2) << "\n";
  } else if (!args.has("quiet")) {
    std::cerr << "msp tessellate: " << output << ": " << t.triangles.size() << " triangles, "
              << t.positions.rows() << " vertices (density " << t.density << ")\n";
  }
  return 0;
}

}  // namespace msp
