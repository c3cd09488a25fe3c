// The good corpus (tests/data/good): one unit cube in every format and variant the readers
// accept. msp info --strict passes on each, and read_mesh() gives the same closed outward cube.
#include <gtest/gtest.h>

#include <ricci/mesh/io.h>
#include <Eigen/Geometry>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "info_subprocess.h"
#include "test_paths.h"

namespace {

namespace fs = std::filesystem;

std::vector<fs::path> good_files() {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(std::string(MSP_TEST_DATA) + "/good"))
    files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

TEST(InfoGood, EveryFormatDescribesTheSameCube) {
  const auto files = good_files();
  ASSERT_GE(files.size(), 7u);
  for (const auto& path : files) {
    SCOPED_TRACE(path.string());
    const auto result = msp_test::run_msp({"info", "--json", "--strict", path.string()});
    ASSERT_EQ(result.exit_status, 0) << result.err;
    EXPECT_TRUE(result.err.empty());
    const auto info = nlohmann::json::parse(result.out);
    EXPECT_EQ(info["vertices"], 8);
    EXPECT_EQ(info["euler_characteristic"], 2);
    EXPECT_EQ(info["genus"], 0);
    EXPECT_EQ(info["boundary_loops"], 0);
    EXPECT_TRUE(info["manifold"].get<bool>());
    EXPECT_TRUE(info["orientable"].get<bool>());
    EXPECT_EQ(info["degenerate_faces"], 0);
    EXPECT_EQ(info["duplicate_vertices"], 0);
    EXPECT_DOUBLE_EQ(info["bbox_diagonal"].get<double>(), std::sqrt(3.0));
    EXPECT_TRUE(info["problems"].empty());
  }
}

TEST(InfoGood, ReadMeshGivesAClosedOutwardUnitCube) {
  for (const auto& path : good_files()) {
    SCOPED_TRACE(path.string());
    const ricci::Mesh mesh = ricci::read_mesh(path.string());
    EXPECT_EQ(mesh.n_vertices(), 8u);
    EXPECT_EQ(mesh.n_faces(), 12u);
    double volume = 0;
    for (const auto f : mesh.faces()) {
      std::vector<Eigen::Vector3d> p;
      for (const auto v : mesh.fv_range(f)) p.push_back(ricci::to_eigen(mesh.point(v)));
      volume += p[0].dot(p[1].cross(p[2])) / 6;
    }
    EXPECT_NEAR(volume, 1.0, 1e-15);
  }
}

TEST(InfoGood, TextSummaryNamesEveryField) {
  const std::string eight = msp_test::test_mesh("closed_g2/eight.off");
  const auto result = msp_test::run_msp({"info", eight});
  ASSERT_EQ(result.exit_status, 0) << result.err;
  for (const char* line :
       {"vertices              766 (0 unreferenced)\n", "faces                 1536\n",
        "components            1\n", "boundary loops        0\n", "euler characteristic  -2\n",
        "genus                 2\n", "manifold              yes", "orientable            yes",
        "degenerate faces      0\n", "duplicate vertices    0\n", "bbox diagonal ",
        "problems              none"})
    EXPECT_NE(result.out.find(line), std::string::npos) << line << " missing from\n" << result.out;
  const auto quads = msp_test::run_msp(
      {"info", "--json", msp_test::test_mesh("open/double-torus-3-holes_quad.off")});
  const auto info = nlohmann::json::parse(quads.out);
  EXPECT_TRUE(info["min_angle_deg"].is_null());  // no triangles to measure
  EXPECT_EQ(info["non_triangle_faces"], 201);
}

}  // namespace
