// msp match A B -o MAP: deformable surface matching by the Ricci flow (issue 17, Algorithms 8, 9):
// ricci::match_surfaces, the map written as text (docs/match-map.md), the shape error of
// eq. (13), the flipped faces and the time printed; --glb draws the match as one checkerboard
// carried from A to B.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>

#include <ricci/analysis/match.h>
#include <ricci/mesh/errors.h>
#include <ricci/mesh/io.h>
#include <nlohmann/json.hpp>

#include "msp/cli.h"
#include "msp/commands.h"
#include "msp/flow_options.h"
#include "msp/io/gltf_writer.h"
#include "msp/io/texture_image.h"
#include "msp/module_report.h"

namespace msp {

namespace {

/// NaN as JSON null.
nlohmann::json number(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(); }

nlohmann::json match_json(const std::string& path_a, const std::string& path_b,
                          ricci::MatchMethod method, const ricci::MatchResult& r) {
  const auto side = [](const ricci::ParameterDomain& d) {
    nlohmann::json j;
    j["feature"] = d.feature;
    j["metric"] = d.metric;
    j["loop_order"] = d.loop_order;
    j["flow_iterations"] = d.flow_iterations;
    j["max_curvature_error"] = d.flow_error;
    j["seconds"] = d.seconds;
    return j;
  };
  nlohmann::json j;
  j["a"] = side(r.a);
  j["a"]["mesh"] = path_a;
  j["b"] = side(r.b);
  j["b"]["mesh"] = path_b;
  j["method"] = ricci::to_string(method);
  j["domain"] = r.domain;
  j["pieces"] = r.pieces;
  j["shape_error_percent"] = 100 * r.shape_error;
  j["correspondence_error_percent"] = number(100 * r.correspondence_error);
  j["flipped_faces"] = r.flipped_faces;
  j["flipped_faces_b"] = r.flipped_faces_b;
  j["flattened_ears"] = r.flattened_ears;
  j["snapped_vertices"] = r.snapped_vertices;
  j["snap_distance"] = r.snap_distance;
  j["seconds"] = r.seconds;
  return j;
}

void print_summary(ricci::MatchMethod method, const ricci::MatchResult& r) {
  std::cout << "method " << ricci::to_string(method) << "\ndomain " << r.domain << "\npieces "
            << r.pieces << "\n";
  if (r.a.feature >= 0) std::cout << "features " << r.a.feature << " " << r.b.feature << "\n";
  if (!r.a.loop_order.empty()) {
    std::cout << "loop_order";
    for (int k : r.a.loop_order) std::cout << " c" << k;
    std::cout << "\n";
  }
  std::cout << "shape_error_percent " << 100 * r.shape_error << "\n";
  if (std::isfinite(r.correspondence_error)) {
    std::cout << "correspondence_error_percent " << 100 * r.correspondence_error << "\n";
  }
  std::cout << "flipped_faces " << r.flipped_faces << "\nflipped_faces_b " << r.flipped_faces_b
            << "\nflattened_ears " << r.flattened_ears << "\nsnapped_vertices "
            << r.snapped_vertices << "\nmetrics " << r.a.metric << " " << r.b.metric
            << "\nflow_iterations " << r.a.flow_iterations << " " << r.b.flow_iterations
            << "\nseconds " << r.seconds << " (A " << r.a.seconds << ", B " << r.b.seconds << ")\n";
}

/// One textured glTF mesh of a parameter domain: the cut mesh in 3D, uv = the common domain.
gltf::Mesh textured(const ricci::Mesh& mesh, const ricci::ParameterDomain& d,
                    const std::string& name, const Eigen::Vector3d& offset,
                    const gltf::Texture& texture) {
  gltf::Mesh out;
  out.name = name;
  const Eigen::Index n = d.positions.rows();
  out.positions.resize(n, 3);
  out.uvs.resize(n, 2);
  const Eigen::Vector2d lo = d.positions.colwise().minCoeff().transpose();
  const Eigen::Vector2d hi = d.positions.colwise().maxCoeff().transpose();
  const double side = std::max(hi.x() - lo.x(), hi.y() - lo.y());
  for (Eigen::Index s = 0; s < n; ++s) {
    const int v = d.to_original_vertex[static_cast<size_t>(s)];
    out.positions.row(s) = (ricci::to_eigen(mesh.point(mesh.vertex_handle(v))) + offset);
    out.uvs.row(s) << (d.positions(s, 0) - lo.x()) / side, (hi.y() - d.positions(s, 1)) / side;
  }
  for (Eigen::Index f = 0; f < d.faces.rows(); ++f) {
    for (int k = 0; k < 3; ++k) out.indices.push_back(static_cast<std::uint32_t>(d.faces(f, k)));
  }
  out.material.name = name + " checkerboard";
  out.material.double_sided = true;
  out.material.texture = texture;
  return out;
}

/// A and B side by side (B to the right), both textured with the same checkerboard of the
/// common parameter domain: where the map sends a square of A, B shows the same square.
gltf::Scene match_scene(const ricci::Mesh& a, const ricci::Mesh& b, const ricci::MatchResult& r,
                        int squares, const nlohmann::json& extras) {
  const auto box = [](const ricci::Mesh& m) {
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
    Eigen::Vector3d hi = -lo;
    for (ricci::VertexHandle v : m.vertices()) {
      lo = lo.cwiseMin(ricci::to_eigen(m.point(v)));
      hi = hi.cwiseMax(ricci::to_eigen(m.point(v)));
    }
    return std::make_pair(lo, hi);
  };
  const auto [lo_a, hi_a] = box(a);
  const auto [lo_b, hi_b] = box(b);
  const double gap = 0.1 * std::max((hi_a - lo_a).norm(), (hi_b - lo_b).norm());
  const Eigen::Vector3d offset(hi_a.x() - lo_b.x() + gap, 0.0, 0.0);
  CheckerboardOptions board;
  board.squares = squares;
  board.size = squares * std::max(1, 1024 / squares);
  const gltf::Texture texture{encode_png(checkerboard(board)), true, false};
  gltf::Scene scene;
  scene.name = "msp match";
  scene.extras = extras;
  scene.meshes.push_back(textured(a, r.a, "A", Eigen::Vector3d::Zero(), texture));
  scene.meshes.push_back(textured(b, r.b, "B", offset, texture));
  return scene;
}

}  // namespace

const CommandSpec& match_command() {
  static const CommandSpec spec{
      "match",
      "deformable surface matching: map A onto B through canonical domains",
      {{"A", "the surface to map: OBJ, OFF, PLY or STL, also gzipped"},
       {"B", "the surface it lands on (same topology: genus 0 with boundary)"}},
      {{"output", "MAP", "write the map: each vertex of A as barycentric coordinates in B", true},
       {"feature-a", "V", "interior vertex of A matched to --feature-b (the cone)"},
       {"feature-b", "W", "interior vertex of B matched to --feature-a"},
       {"corners-a", "a,b,c,d", "a disk's rectangle corners on A (default: where it turns most)"},
       {"corners-b", "a,b,c,d", "the corners of B that match --corners-a, in the same order"},
       {"method", "euclidean|hyperbolic", "Algorithm 8 (default) or 9 (3+ boundary loops)"},
       {"one-piece", "",
        "cone star: one convex piece, not the pieces cut by loops round the holes"},
       {"glb", "OUT.glb", "draw the match: A and B with one checkerboard carried from A to B"},
       {"checker-squares", "N", "checkerboard squares along each side, 1 to 256 (16)"},
       json_option(),
       tolerance_option("1e-8"),
       solver_option(),
       quiet_option()}};
  return spec;
}

int run_match(int argc, char** argv) {
  const Args args(argc, argv, match_command());
  ricci::MatchOptions options;
  try {
    options.method = ricci::parse_match_method(args.get_or("method", "euclidean"));
  } catch (const ricci::InvalidInputError& e) {
    throw UsageError(e.what());
  }
  options.decompose = !args.has("one-piece");
  options.feature_a = args.get_int("feature-a", -1);
  options.feature_b = args.get_int("feature-b", -1);
  if (auto c = args.get("corners-a")) options.corners_a = parse_corners(*c, "corners-a");
  if (auto c = args.get("corners-b")) options.corners_b = parse_corners(*c, "corners-b");
  options.flow.tolerance = args.get_double("tolerance", options.flow.tolerance);
  if (!(options.flow.tolerance > 0)) throw UsageError("--tolerance must be positive");
  options.flow.solver = parse_solver(args.get_or("solver", "auto"));
  const int squares = args.get_int("checker-squares", 16);
  if (squares < 1 || squares > 256) throw UsageError("--checker-squares must be 1 to 256");
  const std::string path_a = args.positionals()[0], path_b = args.positionals()[1];
  const ricci::ColouredMesh coloured_a = ricci::read_mesh_with_colours(path_a);
  const ricci::ColouredMesh coloured_b = ricci::read_mesh_with_colours(path_b);
  const ricci::Mesh& a = coloured_a.mesh;
  const ricci::Mesh& b = coloured_b.mesh;
  const ricci::MatchResult result = ricci::match_surfaces(a, b, options);
  // Eq. (14) when both files colour their vertices.
  double texture = std::numeric_limits<double>::quiet_NaN();
  if (coloured_a.colours.rows() > 0 && coloured_b.colours.rows() > 0) {
    texture = ricci::texture_error(a, b, result, coloured_a.colours, coloured_b.colours);
  }
  write_text_atomically(*args.get("output"),
                        ricci::surface_map_text(result, static_cast<int>(b.n_vertices()),
                                                static_cast<int>(b.n_faces())));
  nlohmann::json report = match_json(path_a, path_b, options.method, result);
  report["texture_error"] = number(texture);
  if (auto glb = args.get("glb")) {
    gltf::write_glb(match_scene(a, b, result, squares, report), *glb);
  }
  if (args.has("json")) {
    std::cout << report.dump() << "\n";
  } else {
    print_summary(options.method, result);
    if (std::isfinite(texture)) std::cout << "texture_error " << texture << "\n";
  }
  return 0;
}

}  // namespace msp
