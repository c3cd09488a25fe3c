// msp info MESH [--json] [--strict]: describes a mesh file (counts, topology, defects).
// Exit 0 when the file was read and described; with --strict, exit 1 and print the first
// problem as the one-line error when the mesh is not a clean single-component orientable
// 2-manifold (what the pipeline commands require). Unreadable files always fail (main()).
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>

#include <ricci/mesh/diagnose.h>
#include <ricci/mesh/errors.h>
#include <ricci/mesh/soup_io.h>
#include <msp/report/ricci_reports.h>
#include <nlohmann/json.hpp>

#include "msp/cli.h"
#include "msp/commands.h"

namespace msp {
namespace {

std::string genus_text(double genus) {
  std::ostringstream out;
  out << genus;
  return out.str();
}

bool has_triangles(const ricci::MeshDiagnosis& d) { return d.non_triangle_faces < d.faces; }

const char* yes_no(bool value) { return value ? "yes" : "no"; }

void print_text(std::ostream& out, const std::string& path, const ricci::MeshDiagnosis& d) {
  char line[256];
  out << "file                  " << path << "\n";
  out << "vertices              " << d.vertices << " (" << d.unreferenced_vertices
      << " unreferenced)\n";
  out << "edges                 " << d.edges << " (" << d.boundary_edges << " on the boundary)\n";
  out << "faces                 " << d.faces;
  if (d.non_triangle_faces > 0) out << " (" << d.non_triangle_faces << " not triangles)";
  out << "\n";
  out << "components            " << d.components << "\n";
  out << "boundary loops        " << d.boundary_loops << "\n";
  out << "euler characteristic  " << d.euler_characteristic << "\n";
  out << "genus                 " << genus_text(d.genus)
      << (d.genus == std::floor(d.genus) ? "" : " (not a 2-manifold: chi = 2c - 2g - b fails)")
      << "\n";
  out << "manifold              " << yes_no(d.edge_manifold && d.vertex_manifold) << " (edges "
      << yes_no(d.edge_manifold) << ", vertices " << yes_no(d.vertex_manifold) << ")\n";
  out << "orientable            " << yes_no(d.orientable) << " (consistently oriented "
      << yes_no(d.consistently_oriented) << ")\n";
  out << "degenerate faces      " << d.degenerate_faces << "\n";
  out << "duplicate vertices    " << d.duplicate_vertices << "\n";
  out << "duplicate faces       " << d.duplicate_faces << "\n";
  std::snprintf(line, sizeof line, "bbox diagonal         %.9g\n", d.bbox_diagonal);
  out << line;
  std::snprintf(line, sizeof line, "min angle             %.4g deg\n", d.min_angle_deg);
  out << (has_triangles(d) ? line : "min angle             n/a (no triangles)\n");
  if (d.problems.empty()) {
    out << "problems              none: a clean single-component orientable 2-manifold\n";
    return;
  }
  out << "problems              " << d.problems.size() << "\n";
  for (const auto& problem : d.problems) out << "  - " << problem.message << "\n";
}

}  // namespace

const CommandSpec& info_command() {
  static const CommandSpec spec{
      "info",
      "describe a mesh: counts, topology, defects",
      {{"MESH", "the input mesh: OBJ, OFF, PLY or STL, also gzipped"}},
      {json_option(),
       {"strict", "", "exit 1 unless the mesh is a clean single-component orientable 2-manifold"},
       quiet_option()}};
  return spec;
}

int run_info(int argc, char** argv) {
  const Args args(argc, argv, info_command());
  const std::string& path = args.positionals()[0];
  const ricci::PolygonSoup soup = ricci::read_soup(path);  // throws IOError: main() reports it
  const ricci::MeshDiagnosis diagnosis = ricci::diagnose(soup);
  if (args.has("json"))
    std::cout << mesh_info_json(path, diagnosis).dump(2) << "\n";
  else
    print_text(std::cout, path, diagnosis);
  std::cout.flush();
  if (args.has("strict") && !diagnosis.problems.empty()) {
    std::cerr << "msp info: error: " << path << ": " << diagnosis.problems.front().message << "\n";
    return 1;
  }
  return 0;
}

}  // namespace msp
