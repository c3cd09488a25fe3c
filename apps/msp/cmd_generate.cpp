// msp generate: meshes one of the project's test surfaces (closed genus 0-10, or opened by cutting
// end caps) at a chosen size and writes it as OFF, OBJ or PLY.
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include <ricci/mesh/errors.h>
#include <ricci/mesh/generate.h>
#include <ricci/mesh/io.h>
#include <ricci/mesh/primitives.h>
#include <ricci/util/stopwatch.h>

#include "msp/cli.h"
#include "msp/commands.h"

namespace msp {

namespace {

ricci::GenerateOptions parse_options(const Args& args) {
  ricci::GenerateOptions o;
  o.genus = args.get_int("genus", o.genus);
  o.holes = args.get_int("holes", o.holes);
  o.hole_depth = args.get_double("hole-depth", o.hole_depth);
  o.target_faces = args.get_int("faces", o.target_faces);
  const int seed = args.get_int("seed", static_cast<int>(o.seed));
  if (seed < 0) throw UsageError("option --seed must be >= 0, got " + std::to_string(seed));
  o.seed = static_cast<std::uint32_t>(seed);
  if (o.genus < 0 || o.genus > ricci::kMaxGeneratedGenus) {
    throw UsageError("option --genus must be 0 to " + std::to_string(ricci::kMaxGeneratedGenus) +
                     ", got " + std::to_string(o.genus));
  }
  if (o.holes < 0 || o.holes > 2) {
    throw UsageError("option --holes must be 0, 1 or 2, got " + std::to_string(o.holes));
  }
  if (o.target_faces < 200) {
    throw UsageError("option --faces must be at least 200, got " + std::to_string(o.target_faces));
  }
  return o;
}

}  // namespace

const CommandSpec& generate_command() {
  static const CommandSpec spec{
      "generate",
      "mesh a closed or open test surface of a given genus (CGAL)",
      {},
      {{"genus", "G", "genus of the surface: 0 to 10", true},
       {"holes", "H", "boundary loops cut at the ends: 0, 1 or 2 (0)"},
       {"hole-depth", "D", "how deep the end caps are cut, relative to the size (0.25)"},
       {"faces", "N", "wanted face count, at least 200; the result lands within ~15% (3000)"},
       {"seed", "S", "seed of the random generators: same seed, same mesh (1)"},
       {"output", "OUT.off|obj|ply", "the mesh file to write", true},
       json_option(),
       quiet_option()}};
  return spec;
}

int run_generate(int argc, char** argv) {
  const Args args(argc, argv, generate_command());
  const auto output = args.get("output");
  const ricci::GenerateOptions options = parse_options(args);

  const ricci::Stopwatch watch;
  const ricci::Mesh mesh = ricci::generate_surface(options);
  const double seconds = watch.seconds();
  ricci::write_mesh(mesh, *output);

  const ricci::SurfaceTopology t = ricci::surface_topology(mesh);
  const double min_angle = ricci::min_corner_angle_degrees(mesh);
  if (args.has("json")) {
    nlohmann::json j = {{"file", *output},
                        {"surface", ricci::describe_surface(options)},
                        {"vertices", t.vertices},
                        {"faces", t.faces},
                        {"genus", t.genus},
                        {"boundary_loops", t.boundary_loops},
                        {"manifold", t.manifold},
                        {"min_angle_deg", min_angle},
                        {"seed", options.seed},
                        {"seconds", seconds}};
    std::cout << j.dump(2) << "\n";
  } else {
    std::ostringstream line;
    line << std::fixed << std::setprecision(2) << *output << ": " << ricci::describe_surface(options)
         << ", V=" << t.vertices << " F=" << t.faces << " genus=" << t.genus
         << " boundary_loops=" << t.boundary_loops << " min_angle=" << min_angle << " deg, "
         << seconds << " s\n";
    std::cout << line.str();
  }
  return 0;
}

}  // namespace msp
