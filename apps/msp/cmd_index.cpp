// msp index MESH...: shape indexing by conformal modules (issue 17): the module of each mesh,
// the meshes grouped by topology, and per group the matrix of Euclidean distances between the
// module vectors with each mesh's nearest neighbours. Prints tables or one JSON object.
#include <cstdio>
#include <iostream>

#include <ricci/analysis/module_index.h>

#include "msp/cli.h"
#include "msp/commands.h"
#include "msp/module_report.h"
#include "msp/svg_module.h"

namespace msp {

namespace {

std::string fixed(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%9.5f", value);
  return buffer;
}

std::string group_title(const ricci::ModuleGroup& g) {
  return ricci::to_string(g.kind) + ", genus " + std::to_string(g.genus) + ", " +
         std::to_string(g.boundary_loops) + " boundary loops";
}

void print_tables(const std::vector<std::string>& paths,
                  const std::vector<ricci::ModuleResult>& modules,
                  const std::vector<ricci::ModuleGroup>& groups) {
  for (size_t i = 0; i < paths.size(); ++i) {
    std::cout << "[" << i << "] " << paths[i] << ": " << ricci::to_string(modules[i].kind) << " "
              << module_values_text(modules[i]) << " (" << modules[i].seconds << " s)\n";
  }
  for (const ricci::ModuleGroup& g : groups) {
    std::cout << "\ngroup " << group_title(g) << ": " << g.members.size() << " mesh"
              << (g.members.size() == 1 ? "" : "es")
              << (g.invariant ? "" : " (not invariant: depends on the bases)") << "\n";
    std::cout << "     ";
    for (int m : g.members) std::cout << "  [" << m << "]" << std::string(4, ' ');
    std::cout << "\n";
    for (size_t a = 0; a < g.members.size(); ++a) {
      std::cout << "[" << g.members[a] << "]";
      for (size_t b = 0; b < g.members.size(); ++b) {
        std::cout << " " << fixed(g.distances(static_cast<Eigen::Index>(a),
                                              static_cast<Eigen::Index>(b)));
      }
      std::cout << "\n";
    }
    for (size_t a = 0; a < g.members.size(); ++a) {
      std::cout << "nearest to [" << g.members[a] << "]:";
      for (int b : g.nearest[a]) {
        std::cout << " [" << g.members[b] << "] "
                  << g.distances(static_cast<Eigen::Index>(a), b) << ";";
      }
      std::cout << "\n";
    }
  }
}

nlohmann::json groups_json(const std::vector<ricci::ModuleGroup>& groups) {
  nlohmann::json list = nlohmann::json::array();
  for (const ricci::ModuleGroup& g : groups) {
    nlohmann::json j;
    j["kind"] = ricci::to_string(g.kind);
    j["genus"] = g.genus;
    j["boundary_loops"] = g.boundary_loops;
    j["invariant"] = g.invariant;
    j["members"] = g.members;
    nlohmann::json rows = nlohmann::json::array(), nearest = nlohmann::json::array();
    for (size_t a = 0; a < g.members.size(); ++a) {
      std::vector<double> row;
      std::vector<int> order;
      for (size_t b = 0; b < g.members.size(); ++b) {
        row.push_back(g.distances(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b)));
      }
      for (int b : g.nearest[a]) order.push_back(g.members[b]);
      rows.push_back(row);
      nearest.push_back(order);
    }
    j["distances"] = rows;
    j["nearest"] = nearest;
    list.push_back(j);
  }
  return list;
}

}  // namespace

const CommandSpec& index_command() {
  static const CommandSpec spec{
      "index",
      "conformal modules of meshes grouped by topology, distances",
      {{"MESH...", "the input meshes (one or more): OBJ, OFF, PLY or STL, also gzipped"}},
      {json_option(),
       tolerance_option("1e-11"),
       solver_option(),
       metric_option("circle-packing, no fall-back"),
       radii_option(),
       quiet_option()}};
  return spec;
}

int run_index(int argc, char** argv) {
  const Args args(argc, argv, index_command());
  const ricci::ModuleOptions options = parse_module_options(args, false);
  const std::vector<std::string>& paths = args.positionals();
  std::vector<ricci::ModuleResult> modules;
  nlohmann::json meshes = nlohmann::json::array();
  for (const std::string& path : paths) {
    std::cerr << "msp index: " << path << "...\n";
    ricci::Mesh mesh;
    modules.push_back(module_of_file(path, options, mesh));
    meshes.push_back(module_json(path, mesh, modules.back()));
  }
  const std::vector<ricci::ModuleGroup> groups = ricci::index_modules(modules);
  if (args.has("json")) {
    std::cout << nlohmann::json{{"meshes", meshes}, {"groups", groups_json(groups)}}.dump()
              << "\n";
  } else {
    print_tables(paths, modules, groups);
  }
  return 0;
}

}  // namespace msp
