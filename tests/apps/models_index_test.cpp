// Regression over every mesh listed in tests/data/meshes/INDEX.md (the real test meshes) and
// models/INDEX.md (the bundled models): `msp info --json` must report the vertex and face counts,
// boundary loops, genus, manifoldness and orientation the index lists, and read_mesh() must
// build exactly the clean ones into an OpenMesh surface with the same topology.
#include <gtest/gtest.h>

#include <ricci/mesh/boundary_loops.h>
#include <ricci/mesh/errors.h>
#include <ricci/mesh/io.h>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "info_subprocess.h"

namespace {

namespace fs = std::filesystem;

using Row = std::map<std::string, std::string>;  // column header -> cell

std::vector<std::string> split_cells(const std::string& line) {
  std::vector<std::string> cells;
  std::string cell;
  for (size_t i = 1; i < line.size(); ++i) {  // skip the leading '|'
    if (line[i] != '|') {
      cell += line[i];
      continue;
    }
    const size_t a = cell.find_first_not_of(" \t"), b = cell.find_last_not_of(" \t");
    cells.push_back(a == std::string::npos ? "" : cell.substr(a, b - a + 1));
    cell.clear();
  }
  return cells;
}

/// Every row of every markdown table whose header has a "file" column, keyed by header name.
std::vector<Row> read_index_tables(const fs::path& index) {
  std::ifstream in(index);
  std::vector<Row> rows;
  std::vector<std::string> header;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] != '|') {
      header.clear();
      continue;
    }
    const auto cells = split_cells(line);
    if (header.empty()) {
      header = cells;
      continue;
    }
    if (cells.empty() || cells[0].rfind("---", 0) == 0) continue;  // the |---|---| rule
    Row row;
    for (size_t k = 0; k < cells.size() && k < header.size(); ++k) row[header[k]] = cells[k];
    if (row.count("file")) rows.push_back(row);
  }
  return rows;
}

struct Expected {
  fs::path path;
  Row row;
};

std::vector<Expected> expectations(const fs::path& folder) {
  std::vector<Expected> all;
  for (const auto& row : read_index_tables(folder / "INDEX.md"))
    all.push_back({folder / row.at("file"), row});
  return all;
}

bool yes(const std::string& cell) { return cell == "yes" || cell == "YES" || cell == "Yes"; }

/// Runs msp info --json on each listed mesh and compares every column the table has.
void check_against_index(const fs::path& folder) {
  const auto all = expectations(folder);
  ASSERT_FALSE(all.empty()) << "no table rows in " << folder / "INDEX.md";
  for (const auto& [path, row] : all) {
    SCOPED_TRACE(path.string());
    const auto result = msp_test::run_msp({"info", "--json", path.string()});
    ASSERT_EQ(result.exit_status, 0) << result.err;
    const auto info = nlohmann::json::parse(result.out);
    ASSERT_TRUE(row.count("bdry loops") && row.count("genus") && row.count("clean manifold"));
    EXPECT_EQ(info["boundary_loops"].get<int>(), std::stoi(row.at("bdry loops")));
    EXPECT_EQ(info["genus"].get<double>(), std::stod(row.at("genus")));
    EXPECT_EQ(info["clean_manifold"].get<bool>(), yes(row.at("clean manifold")));
    if (row.count("V")) {
      EXPECT_EQ(info["vertices"].get<int>(), std::stoi(row.at("V")));
    }
    if (row.count("F")) {
      EXPECT_EQ(info["faces"].get<int>(), std::stoi(row.at("F")));
    }
    if (row.count("oriented")) {
      EXPECT_EQ(info["consistently_oriented"].get<bool>(), yes(row.at("oriented")));
    }
    if (row.count("min angle") && row.at("min angle") != "n/a") {
      const double listed = std::stod(row.at("min angle"));  // rounded to 3 significant digits
      EXPECT_NEAR(info["min_angle_deg"].get<double>(), listed, 0.006 * listed + 1e-4);
    }
    if (yes(row.at("clean manifold"))) {
      EXPECT_TRUE(info["problems"].empty()) << info["problems"];
    }
  }
}

/// read_mesh() builds the clean rows (same chi and boundary loops after triangulation) and
/// refuses the others with a TopologyError.
void check_build(const fs::path& folder) {
  for (const auto& [path, row] : expectations(folder)) {
    SCOPED_TRACE(path.string());
    if (!yes(row.at("clean manifold"))) {
      EXPECT_THROW((void)ricci::read_mesh(path.string()), ricci::TopologyError);
      continue;
    }
    const ricci::Mesh mesh = ricci::read_mesh(path.string());
    const int chi = static_cast<int>(mesh.n_vertices()) - static_cast<int>(mesh.n_edges()) +
                    static_cast<int>(mesh.n_faces());
    const int loops = static_cast<int>(ricci::find_boundary_loops(mesh).size());
    EXPECT_EQ(loops, std::stoi(row.at("bdry loops")));
    EXPECT_EQ(2 - loops - chi, 2 * std::stoi(row.at("genus")));
    if (row.count("V")) {
      EXPECT_LE(static_cast<int>(mesh.n_vertices()), std::stoi(row.at("V")));
    }
  }
}

fs::path test_meshes() { return fs::path(MSP_TEST_DATA) / "meshes"; }

TEST(TestMeshes, InfoMatchesIndex) { check_against_index(test_meshes()); }

TEST(TestMeshes, ReadMeshBuildsExactlyTheCleanOnes) { check_build(test_meshes()); }

TEST(BundledModels, InfoMatchesIndex) {
  const fs::path folder = fs::path(MSP_SOURCE_DIR) / "models";
  check_against_index(folder);
  check_build(folder);
}

TEST(TestMeshes, EveryMeshFileIsIndexed) {
  std::set<fs::path> listed;
  for (const auto& e : expectations(test_meshes())) listed.insert(fs::weakly_canonical(e.path));
  int meshes = 0;
  for (const auto& entry : fs::recursive_directory_iterator(test_meshes())) {
    const std::string ext = entry.path().extension().string();
    const bool mesh =
        ext == ".off" || ext == ".obj" || ext == ".ply" || ext == ".stl" || ext == ".gz";
    if (!mesh) continue;
    ++meshes;
    EXPECT_TRUE(listed.count(fs::weakly_canonical(entry.path())))
        << entry.path() << " is not in INDEX.md";
  }
  EXPECT_EQ(meshes, static_cast<int>(listed.size()));
}

}  // namespace
