// msp fit MESH -o OUT.glb: the whole scan-to-glTF job of issue 6 (simplify, one-cone atlas,
// spline fit and fairing, hole filling, watertight tessellation, glTF export, JSON report).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>

#include <ricci/mesh/errors.h>
#include <ricci/mesh/io.h>
#include <ricci/util/memory.h>
#include <spline/basis/multi_index.h>
#include <spline/io/spline_file.h>
#include <spline/surface/fit_surface.h>
#include <nlohmann/json.hpp>

#include "msp/cli.h"
#include "msp/flow_options.h"
#include "msp/commands.h"
#include "msp/fit_export.h"
#include "msp/report/fit_report.h"

namespace msp {
namespace {

using Clock = std::chrono::steady_clock;

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// "msp fit: simplify... 0.52 s" lines: a stage's line is finished when the next one starts.
class Progress {
 public:
  explicit Progress(bool quiet) : quiet_(quiet) {}
  void start(const std::string& stage) {
    finish();
    if (quiet_ || stage.empty()) return;
    std::cerr << "msp fit: " << stage << "..." << std::flush;
    open_ = true;
    started_ = Clock::now();
  }
  /// Ends an open line without a time (the error message follows on its own line).
  void abort() {
    if (open_) std::cerr << " failed\n" << std::flush;
    open_ = false;
  }
  void finish() {
    if (!open_) return;
    char text[32];
    std::snprintf(text, sizeof text, " %.2f s\n",
                  std::chrono::duration<double>(Clock::now() - started_).count());
    std::cerr << text << std::flush;
    open_ = false;
  }

 private:
  bool quiet_;
  bool open_ = false;
  Clock::time_point started_;
};

spline::FitSurfaceOptions parse_options(const Args& args) {
  spline::FitSurfaceOptions o;
  o.domain_faces = args.get_int("domain-faces", o.domain_faces);
  o.degree = args.get_int("degree", o.degree);
  if (args.has("fairness")) o.fairness = args.get_int("fairness", 0);
  o.smoothing = args.get_double("smoothing", o.smoothing);
  o.singular_vertex = parse_singularity(args.get_or("singularity", "auto"));
  o.fill_boundaries = args.has("fill-boundaries");
  o.small_hole_diameter = args.get_double("small-holes", o.small_hole_diameter);
  o.density = args.get_int("density", 0);
  o.density_refine_levels = args.get_int("turn-refinement", o.density_refine_levels);
  o.cone_refinement.levels = args.get_int("cone-refinement", o.cone_refinement.levels);
  if (const int grading = args.get_int("cone-grading", 0); grading != 0) {
    o.cone_refinement.radial_from_genus = 2;
    o.cone_refinement.radial_levels = grading;
  }
  o.refinement_rounds = args.get_int("refine-rounds", o.refinement_rounds);
  o.fold_rounds = args.get_int("fold-rounds", o.fold_rounds);
  o.adaptive_domain = args.has("adaptive-domain");
  o.tracked_parameters = args.has("tracked-parameters");
  o.tolerance = args.get_double("tolerance", o.tolerance);
  o.rms_goal = args.get_double("rms-goal", o.rms_goal);
  o.max_surface_deviation = args.get_double("max-deviation", o.max_surface_deviation);
  try {
    spline::check_options(o, [](const std::string& field) {
      if (field == "refinement_rounds") return std::string("--refine-rounds");
      if (field == "max_surface_deviation") return std::string("--max-deviation");
      if (field == "small_hole_diameter") return std::string("--small-holes");
      if (field == "density_refine_levels") return std::string("--turn-refinement");
      std::string flag = "--" + field;
      std::replace(flag.begin(), flag.end(), '_', '-');
      return flag;
    });
  } catch (const ricci::InvalidInputError& e) {
    throw UsageError(e.what());
  }
  return o;
}

void check_outputs(const Args& args) {
  const auto glb = args.get("output");
  if (glb && !ends_with(*glb, ".glb"))
    throw UsageError("-o must name a .glb file, not '" + *glb + "'");
  if (auto obj = args.get("obj"); obj && !ends_with(*obj, ".obj"))
    throw UsageError("--obj must name an .obj file, not '" + *obj + "'");
  if (auto ply = args.get("ply"); ply && !ends_with(*ply, ".ply"))
    throw UsageError("--ply must name a .ply file, not '" + *ply + "'");
  if (auto msp = args.get("spline"); msp && !ends_with(*msp, ".msp"))
    throw UsageError("--spline must name an .msp file, not '" + *msp + "'");
  if (!glb && !args.has("obj") && !args.has("ply") && !args.has("json") && !args.has("spline"))
    throw UsageError("nothing to write: give -o OUT.glb (or --obj, --ply, --json, --spline)");
  // A missing folder is found before the work, not after the first file is written.
  for (const char* name : {"output", "obj", "ply", "json", "spline"}) {
    const auto path = args.get(name);
    if (!path) continue;
    const std::filesystem::path folder = std::filesystem::path(*path).parent_path();
    if (!folder.empty() && !std::filesystem::is_directory(folder))
      throw ricci::IOError("cannot write " + *path + ": folder " + folder.string() +
                           " does not exist");
  }
}

// Metadata of the glTF scene: the figures at the top, the whole report below.
nlohmann::json scene_extras(const nlohmann::json& report) {
  return {{"genus", report["genus"]},
          {"degree", report["degree"]},
          {"r", report["fairness"]},
          {"singularities", report["singularities"]},
          {"fit_error",
           {{"rms", report["fit_rms"]},
            {"max", report["fit_max"]},
            {"rms_relative", report["fit_rms_relative"]},
            {"max_relative", report["fit_max_relative"]},
            {"bbox_diagonal", report["bbox_diagonal"]}}},
          {"watertight", report["watertight"]},
          {"msp_fit", report}};
}

}  // namespace

const CommandSpec& fit_command() {
  static const CommandSpec spec{
      "fit",
      "fit a manifold spline to a mesh and export glTF",
      {{"MESH", "the input mesh: OBJ, OFF, PLY or STL, also gzipped"}},
      {{"output", "OUT.glb", "write the surface as binary glTF"},
       {"domain-faces", "N", "simplify the mesh to about N faces for the domain (2000)"},
       {"degree", "n", "degree of the DMS spline (3)"},
       {"fairness", "r",
        "fit inside the fairing constraints of order r; -1: none (1; 0 below degree 3)"},
       singularity_option(),
       {"fill-boundaries", "", "also cap the input's boundary loops with G1 patches"},
       {"small-holes", "F", "cap boundary loops narrower than F diagonals before the fit (0.002)"},
       {"json", "REPORT", "write the JSON report to the file REPORT"},
       {"density", "d", "tessellation samples per domain edge (chosen by domain size)"},
       {"turn-refinement", "LEVELS",
        "split the tessellation where it turns over 60 degrees, 0 to 6 levels (3)"},
       {"cone-refinement", "LEVELS", "1-to-4 splits of the domain around the cone, 0 to 4 (2)"},
       {"cone-grading", "LEVELS",
        "experimental: rounds of radial splits grading the domain log-polar around the cone, 0 to "
        "4 (0: off; 3 rounds multiply a genus-10 domain by 9 and its memory by 5)"},
       {"smoothing", "LAMBDA", "weight of the thin-plate energy (1e-4)"},
       {"tolerance", "F",
        "refine the domain where the input is farther than F diagonals from the surface (0)"},
       {"rms-goal", "F",
        "refine the domain where the fit misses most when its RMS exceeds F diagonals (0.0019)"},
       {"refine-rounds", "N", "domain refinements where the surface folds or misses (1)"},
       {"fold-rounds", "N", "refits with stronger fairing around folds left (4)"},
       {"adaptive-domain", "", "closed scans: a domain denser at detail and thin parts"},
       {"tracked-parameters", "",
        "experimental, genus >= 4: place the data through the flow's intrinsic flips (exact) "
        "rather than by closest point on the flipped faces"},
       {"max-deviation", "F",
        "fail when the surface strays farther than F diagonals from the input; 0: off (0.05)"},
       {"obj", "OUT.obj", "also write the tessellation as OBJ"},
       {"ply", "OUT.ply", "also write the tessellation as PLY"},
       {"spline", "OUT.msp", "also write the spline itself as a spline file (.msp)"},
       {"checkerboard", "", "texture the surface with the atlas' checkerboard"},
       {"checker-squares", "N", "checkerboard squares along each side, 1 to 256 (32)"},
       {"control-net", "", "add the control net (lines) to the glTF"},
       {"domain", "", "add the domain mesh's edges (lines) to the glTF"},
       {"cut-loops", "", "add the cut loops and the extraordinary point to the glTF"},
       quiet_option()}};
  return spec;
}

int run_fit(int argc, char** argv) {
  const Args args(argc, argv, fit_command());
  check_outputs(args);
  spline::FitSurfaceOptions options = parse_options(args);
  FitSceneOptions scene_options;
  scene_options.checkerboard = args.has("checkerboard");
  scene_options.texture.squares = args.get_int("checker-squares", scene_options.texture.squares);
  if (scene_options.texture.squares <= 0 || scene_options.texture.squares > 256)
    throw UsageError("--checker-squares must be in [1, 256]");
  scene_options.texture.size =
      scene_options.texture.squares * std::max(8, 1024 / scene_options.texture.squares);
  scene_options.control_net = args.has("control-net");
  scene_options.domain = args.has("domain");
  scene_options.cut_loops = args.has("cut-loops");

  const auto total = Clock::now();
  Progress progress(args.has("quiet"));
  options.progress = [&](const std::string& stage) { progress.start(stage); };
  const std::string path = args.positionals()[0];
  progress.start("read");
  auto t = Clock::now();
  spline::FittedSurface run;
  double read_seconds = 0.0;
  try {
    const ricci::Mesh mesh = ricci::read_mesh(path);
    read_seconds = std::chrono::duration<double>(Clock::now() - t).count();
    ricci::keep_freed_memory(mesh.n_vertices());
    run = spline::fit_surface(mesh, options);
  } catch (...) {
    progress.abort();
    throw;
  }

  // Every output is made in memory first, then written: a failure leaves no file behind.
  progress.start("export");
  t = Clock::now();
  std::vector<std::uint8_t> glb, ply, spline_file;
  std::string obj;
  nlohmann::json report = fit_report_json(path, run, options);
  if (args.has("output")) {
    scene_options.extras = scene_extras(report);
    glb = gltf::glb_bytes(fit_scene(run, scene_options));
  }
  if (args.has("obj")) obj = tessellation_obj(run.tessellation);
  if (args.has("ply")) ply = tessellation_ply(run.tessellation);
  if (args.has("spline")) {
    spline_file =
        spline::encode_spline_surface(run.surface, {{"tool", "msp fit"}, {"input", path}});
  }
  const double export_seconds = std::chrono::duration<double>(Clock::now() - t).count();
  auto& seconds = report["seconds"];
  seconds["read"] = read_seconds;
  seconds["export"] = export_seconds;
  seconds["total"] = std::chrono::duration<double>(Clock::now() - total).count();

  progress.start("write");
  if (args.has("output")) write_bytes_atomically(*args.get("output"), glb);
  if (args.has("obj")) write_text_atomically(*args.get("obj"), obj);
  if (args.has("ply")) write_bytes_atomically(*args.get("ply"), ply);
  if (args.has("spline")) write_bytes_atomically(*args.get("spline"), spline_file);
  if (args.has("json")) write_text_atomically(*args.get("json"), report.dump(2) + "\n");
  progress.finish();
  if (!args.has("quiet")) {
    char line[320];
    std::snprintf(line, sizeof line,
                  "msp fit: genus %d, %d domain faces, %d control points, fit rms %.3g%% max "
                  "%.3g%% of the diagonal, surface to scan max %.3g%%, %d folds, seam jump "
                  "%.3g deg, %s, %.2f s\n",
                  report["genus"].get<int>(), report["domain_faces"].get<int>(),
                  report["control_points"].get<int>(),
                  100 * report["fit_rms_relative"].get<double>(),
                  100 * report["fit_max_relative"].get<double>(),
                  100 * report["surface_to_scan"]["max_relative"].get<double>(),
                  report["folds"]["count"].get<int>(),
                  report["seam_normal_jump_max_deg"].get<double>(),
                  report["watertight"].get<bool>() ? "watertight" : "NOT watertight",
                  seconds["total"].get<double>());
    std::cerr << line;
  }
  // A surface of another genus than the input's is a failure, not a result (outputs are kept
  // for inspection).
  const std::string mismatch = report["topology_mismatch"].get<std::string>();
  if (!mismatch.empty() && mismatch.find("Euler characteristic") != std::string::npos) {
    std::cerr << "msp fit: error: " << mismatch << "\n";
    return 1;
  }
  return 0;
}

}  // namespace msp
