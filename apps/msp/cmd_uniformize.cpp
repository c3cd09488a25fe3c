// msp uniformize MESH: the uniformization metric by the Ricci flow and the geometric structure
// on it (issue 7): Fuchsian generators with their Klein (real projective) transitions for
// genus >= 2, translations and modulus for a torus, the unit-sphere embedding for genus 0; open
// surfaces through their double cover. Prints a summary or one JSON object; -o writes the
// Poincaré-disk picture of a few rings of the universal cover.
#include <iostream>

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

nlohmann::json complex_json(ricci::Complex z) { return {z.real(), z.imag()}; }

/// a1 b1 a2 b2 ... for the canonical generators.
std::string generator_name(size_t i) {
  return std::string(i % 2 == 0 ? "a" : "b") + std::to_string(i / 2 + 1);
}

nlohmann::json generators_json(const ricci::Uniformization& u) {
  nlohmann::json list = nlohmann::json::array();
  for (size_t i = 0; i < u.group.generators.size(); ++i) {
    const ricci::Mobius& g = u.group.generators[i];
    nlohmann::json j;
    j["name"] = generator_name(i);
    j["theta"] = g.theta();
    j["exp_i_theta"] = complex_json(std::polar(1.0, g.theta()));
    if (u.geometry == ricci::Geometry::hyperbolic) {
      // z -> e^{i theta} (z - z0) / (1 - conj(z0) z)
      j["z0"] = complex_json(g.z0());
      const Eigen::Matrix3d l = ricci::lorentz_matrix(g);
      j["klein"] = {{l(0, 0), l(0, 1), l(0, 2)}, {l(1, 0), l(1, 1), l(1, 2)}, {l(2, 0), l(2, 1), l(2, 2)}};
      j["translation_length"] = 2.0 * std::acosh(std::max(1.0, 0.5 * std::abs(g.m.trace().real())));
    } else {
      // z -> e^{i theta} z + t (a translation on the flat torus)
      j["translation"] = complex_json(g(0.0));
    }
    j["word"] = u.group.basis.generators[i].size();
    list.push_back(j);
  }
  return list;
}

nlohmann::json result_json(const std::string& path, const ricci::Mesh& mesh,
                           const ricci::Uniformization& u) {
  nlohmann::json j;
  j["mesh"] = path;
  j["vertices"] = mesh.n_vertices();
  j["faces"] = mesh.n_faces();
  j["geometry"] = ricci::to_string(u.geometry);
  j["genus"] = u.genus;
  j["double_cover"] = u.doubled;
  j["metric"] = ricci::to_string(u.flow.metric.scheme);
  j["iterations"] = u.flow.iterations;
  j["max_curvature_error"] = u.flow.max_error;
  j["generators"] = generators_json(u);
  j["relation_residual"] = u.group.relation_residual;
  j["seconds"] = u.timings.total;
  j["timings"] = {{"double_cover", u.timings.double_cover}, {"flow", u.timings.flow},
                  {"cut", u.timings.cut}, {"layout", u.timings.layout},
                  {"polish", u.timings.polish}, {"group", u.timings.group}};
  if (u.geometry == ricci::Geometry::spherical) {
    j["sphere"] = {{"max_radius_error", u.sphere.max_radius_error},
                   {"flipped_faces", u.sphere.flipped_faces},
                   {"centroid_norm", u.sphere.centroid_norm}};
  } else {
    j["polygon_residual"] = u.group.polygon_residual;
    j["relation_residual_direct"] = u.group.relation_residual_direct;
    j["side_spread"] = u.pairings.max_spread;
    if (u.geometry == ricci::Geometry::hyperbolic) {
      j["polish"] = {{"curvature_error_before", u.polish.error_before},
                     {"curvature_error_after", u.polish.error_after},
                     {"iterations", u.polish.iterations}};
    }
    j["sides"] = 2 * u.pairings.arcs.size();
    j["layout"] = {{"seed_face", u.layout.seed_face},
                   {"flipped_faces", u.layout.flipped_faces},
                   {"max_relative_length_error", u.layout.max_relative_length_error},
                   {"max_radius", u.layout.max_radius}};
  }
  if (u.geometry == ricci::Geometry::euclidean) {
    j["modulus"] = complex_json(u.modulus);
    j["reduced_modulus"] = complex_json(u.reduced_modulus);
  }
  return j;
}

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
       {"root", "V", "the vertex the cut graph's loops are based at (0)"},
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
  options.root_vertex = args.get_int("root", 0);
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
    std::cout << result_json(path, mesh, u).dump() << "\n";
  } else {
    print_summary(mesh, u);
  }
  return 0;
}

}  // namespace msp
