// msp atlas MESH: one-cone flat metric, cut graph, layout and affine atlas, with the figures
// that say whether it worked (curvature error, transition residual, flipped faces, distortion).
#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <utility>

#include <ricci/mesh/errors.h>
#include <ricci/mesh/io.h>
#include <ricci/pipeline/one_cone_atlas.h>
#include <ricci/util/memory.h>
#include <msp/report/ricci_reports.h>
#include <nlohmann/json.hpp>

#include "msp/cli.h"
#include "msp/commands.h"
#include "msp/flow_options.h"
#include "msp/gltf_atlas.h"
#include "msp/svg_atlas.h"

namespace msp {
namespace {

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// The pictures of issue 4: the SVG of the domain and its copies, the checkerboard mesh.
void write_pictures(const Args& args, const std::string& path,
                    const ricci::OneConeAtlasResult& result, const nlohmann::json& report) {
  auto note = [&](const std::string& file) {
    if (!args.has("quiet")) std::cerr << "msp atlas: wrote " << file << "\n";
  };
  if (auto svg = args.get("output")) {
    AtlasSvgOptions options;
    options.title = path;
    options.cover_depth = args.get_int("cover-depth", -1);
    write_text_atomically(*svg, atlas_svg(result, options));
    note(*svg);
  }
  if (auto out = args.get("checkerboard")) {
    CheckerboardOptions texture;
    texture.squares = args.get_int("checker-squares", texture.squares);
    if (texture.squares <= 0 || texture.squares > 256)
      throw UsageError("--checker-squares must be in [1, 256]");
    texture.size = texture.squares * std::max(8, 1024 / texture.squares);
    if (ends_with(*out, ".glb")) {
      CheckerboardExportOptions options;
      options.texture = texture;
      options.extras = {{"msp_atlas", report}};
      gltf::write_glb(checkerboard_scene(result, options), *out);
    } else {
      write_checkerboard_obj(result, *out, texture);
    }
    note(*out);
  }
}

}  // namespace

const CommandSpec& atlas_command() {
  static const CommandSpec spec{
      "atlas",
      "one-cone flat metric, cut graph, layout and affine atlas",
      {{"MESH", "the input mesh: OBJ, OFF, PLY or STL, also gzipped"}},
      {singularity_option(),
       metric_option("chosen per surface: the most conformal that converges (on genus >= 2 "
                     "intrinsic-delaunay, then the inversive-distance route, then the circle "
                     "packings; combinatorial only where intrinsic-delaunay fails too)",
                     true),
       radii_option(),
       tolerance_option("1e-10"),
       {"output", "PICTURE.svg", "write the fundamental domain and its neighbouring copies"},
       {"cover-depth", "N", "copies in the picture: products of up to N side pairings"},
       {"checkerboard", "OUT.glb|OUT.obj", "write the mesh textured with the atlas' checkerboard"},
       {"checker-squares", "N", "checkerboard squares along each side, 1 to 256 (32)"},
       quiet_option(),
       json_option()}};
  return spec;
}

int run_atlas(int argc, char** argv) {
  const Args args(argc, argv, atlas_command());
  if (auto svg = args.get("output"); svg && !ends_with(*svg, ".svg"))
    throw UsageError("-o must name an .svg file, not '" + *svg + "'");
  if (auto out = args.get("checkerboard");
      out && !ends_with(*out, ".glb") && !ends_with(*out, ".obj")) {
    throw UsageError("--checkerboard must name a .glb or .obj file, not '" + *out + "'");
  }
  ricci::OneConeAtlasOptions options;
  options.singular_vertex = parse_singularity(args.get_or("singularity", "auto"));
  const bool intrinsic = args.get_or("metric", "") == "intrinsic-delaunay";
  if (intrinsic) {
    options.route = ricci::FlowRoute::intrinsic_delaunay;
  } else if (args.has("metric")) {
    options.flow.scheme = parse_scheme(*args.get("metric"));
  }
  if (args.has("radii")) options.flow.radii = parse_radii(*args.get("radii"));
  options.keep_metric = (args.has("metric") && !intrinsic) || args.has("radii");
  options.flow.tolerance = args.get_double("tolerance", 1e-10);
  if (!args.has("quiet")) {
    options.progress = [](const std::string& stage) {
      std::cerr << "msp atlas: " << stage << "\n";
    };
  }
  const std::string path = args.positionals()[0];
  ricci::Mesh mesh = ricci::read_mesh(path);
  const size_t vertices = mesh.n_vertices(), faces = mesh.n_faces();
  ricci::use_one_malloc_arena(vertices);  // before the pipeline's threads allocate
  // Handed over: the pipeline keeps it as arrays while the flow runs (its memory peak).
  const ricci::OneConeAtlasResult result = ricci::build_one_cone_atlas(std::move(mesh), options);
  nlohmann::json report = atlas_report_json(path, vertices, faces, result);
  write_pictures(args, path, result, report);
  if (args.has("json")) {
    std::cout << report.dump() << "\n";
  } else {
    for (auto& [key, value] : report.items()) std::cout << key << " " << value.dump() << "\n";
  }

  return 0;
}

}  // namespace msp
