// msp index MESH...: shape indexing by conformal modules (issue 17): the module of each mesh,
// the meshes grouped by topology, and per group the matrix of Euclidean distances between the
// module vectors with each mesh's nearest neighbours. Prints tables or one JSON object. A mesh
// whose module fails (unreadable, refused, flow not converged) is reported and left out; the
// others are still indexed.
#include <algorithm>
#include <cstdio>
#include <iostream>

#include <ricci/analysis/module_index.h>
#include <ricci/mesh/errors.h>

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

/// The indexed meshes: modules[i] is of paths[source[i]]; failures[k] is the reason the mesh
/// paths[failed[k]] has no module.
struct Indexed {
  std::vector<ricci::ModuleResult> modules;
  std::vector<int> source;
  std::vector<int> failed;
  std::vector<std::string> failures;
};

void print_tables(const std::vector<std::string>& paths, const Indexed& indexed,
                  const std::vector<ricci::ModuleGroup>& groups) {
  size_t next_failure = 0;
  for (size_t i = 0; i < paths.size(); ++i) {
    std::cout << "[" << i << "] " << paths[i] << ": ";
    const auto at = std::find(indexed.source.begin(), indexed.source.end(), static_cast<int>(i));
    if (at == indexed.source.end()) {
      std::cout << "failed: " << indexed.failures[next_failure++] << "\n";
      continue;
    }
    const ricci::ModuleResult& m = indexed.modules[at - indexed.source.begin()];
    std::cout << ricci::to_string(m.kind) << " " << module_values_text(m) << " (" << m.seconds
              << " s)\n";
  }
  for (const ricci::ModuleGroup& g : groups) {
    std::cout << "\ngroup " << group_title(g) << ": " << g.members.size() << " mesh"
              << (g.members.size() == 1 ? "" : "es")
              << (g.invariant ? "" : " (not invariant: depends on the bases)") << "\n";
    std::cout << "     ";
    for (int m : g.members) std::cout << "  [" << indexed.source[m] << "]" << std::string(4, ' ');
    std::cout << "\n";
    for (size_t a = 0; a < g.members.size(); ++a) {
      std::cout << "[" << indexed.source[g.members[a]] << "]";
      for (size_t b = 0; b < g.members.size(); ++b) {
        std::cout << " " << fixed(g.distances(static_cast<Eigen::Index>(a),
                                              static_cast<Eigen::Index>(b)));
      }
      std::cout << "\n";
    }
    for (size_t a = 0; a < g.members.size(); ++a) {
      std::cout << "nearest to [" << indexed.source[g.members[a]] << "]:";
      for (int b : g.nearest[a]) {
        std::cout << " [" << indexed.source[g.members[b]] << "] "
                  << g.distances(static_cast<Eigen::Index>(a), b) << ";";
      }
      std::cout << "\n";
    }
  }
}

nlohmann::json groups_json(const std::vector<ricci::ModuleGroup>& groups,
                           const std::vector<int>& source) {
  nlohmann::json list = nlohmann::json::array();
  for (const ricci::ModuleGroup& g : groups) {
    nlohmann::json j;
    j["kind"] = ricci::to_string(g.kind);
    j["genus"] = g.genus;
    j["boundary_loops"] = g.boundary_loops;
    j["invariant"] = g.invariant;
    std::vector<int> members;
    for (int m : g.members) members.push_back(source[m]);
    j["members"] = members;
    nlohmann::json rows = nlohmann::json::array(), nearest = nlohmann::json::array();
    for (size_t a = 0; a < g.members.size(); ++a) {
      std::vector<double> row;
      std::vector<int> order;
      for (size_t b = 0; b < g.members.size(); ++b) {
        row.push_back(g.distances(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b)));
      }
      for (int b : g.nearest[a]) order.push_back(source[g.members[b]]);
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
  Indexed indexed;
  nlohmann::json meshes = nlohmann::json::array();
  for (size_t i = 0; i < paths.size(); ++i) {
    const std::string& path = paths[i];
    std::cerr << "msp index: " << path << "...\n";
    ricci::Mesh mesh;
    try {
      indexed.modules.push_back(module_of_file(path, options, mesh));
    } catch (const ricci::Error& e) {
      // One mesh's failure leaves the others to index (the message names the mesh).
      const std::string what = e.what();
      std::cerr << "msp index: failed: " << what << "\n";
      indexed.failed.push_back(static_cast<int>(i));
      indexed.failures.push_back(what);
      meshes.push_back({{"mesh", path}, {"failed", what}});
      continue;
    }
    indexed.source.push_back(static_cast<int>(i));
    meshes.push_back(module_json(path, mesh, indexed.modules.back()));
  }
  if (indexed.modules.empty()) {
    throw ricci::SolverError("no mesh has a module (" + indexed.failures.front() + ")");
  }
  const std::vector<ricci::ModuleGroup> groups = ricci::index_modules(indexed.modules);
  if (args.has("json")) {
    std::cout << nlohmann::json{{"meshes", meshes},
                                {"groups", groups_json(groups, indexed.source)},
                                {"failed", indexed.failed}}
                     .dump()
              << "\n";
  } else {
    print_tables(paths, indexed, groups);
  }
  return 0;
}

}  // namespace msp
