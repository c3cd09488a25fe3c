// msp tessellate as the real binary: msp fit --spline then msp tessellate at the fit's density
// gives the same surface (the .glb's positions equal, welded as a reader sees them); another
// density re-tessellates watertight; bad spline files and command lines are refused.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "info_subprocess.h"
#include "msp/io/gltf_reader.h"
#include "spline/io/bad_splines.h"

namespace {

namespace fs = std::filesystem;
using msp_test::line_count;
using msp_test::run_msp;

fs::path scratch() {
  const fs::path dir =
      fs::temp_directory_path() / ("msp_tessellate_tests_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

TEST(TessellateCli, ReproducesTheFittedSurfaceAndRetessellates) {
  const fs::path dir = scratch();
  const std::string spline = (dir / "a.msp").string(), fitted = (dir / "a.glb").string(),
                    again = (dir / "b.glb").string(), fine = (dir / "c.ply").string();
  auto result = run_msp({"fit", std::string(MSP_SOURCE_DIR) + "/models/genus2.off", "-o", fitted,
                         "--spline", spline, "--domain-faces", "600", "--quiet"});
  ASSERT_EQ(result.exit_status, 0) << result.err;
  result = run_msp({"tessellate", spline, "-o", again, "--json"});
  ASSERT_EQ(result.exit_status, 0) << result.err;
  const auto report = nlohmann::json::parse(result.out);
  EXPECT_TRUE(report["manifold"].get<bool>());
  EXPECT_EQ(report["boundary_loops"].get<int>(), 0);
  const auto a = msp::gltf::read_glb_triangles(fitted);
  const auto b = msp::gltf::read_glb_triangles(again);
  ASSERT_EQ(a.positions.rows(), b.positions.rows());
  EXPECT_EQ(a.positions, b.positions);  // the same float32 values, vertex for vertex
  EXPECT_EQ(a.triangles, b.triangles);
  result = run_msp({"tessellate", spline, "-o", fine, "--density", "3", "--json"});
  ASSERT_EQ(result.exit_status, 0) << result.err;
  const auto coarse = nlohmann::json::parse(result.out);
  EXPECT_EQ(coarse["density"].get<int>(), 3);
  EXPECT_TRUE(coarse["manifold"].get<bool>());
  EXPECT_LT(coarse["triangles"].get<int>(), report["triangles"].get<int>());
}

TEST(TessellateCli, BadSplinesAndCommandLinesAreRefused) {
  const fs::path out = scratch() / "bad.glb";
  for (const auto& bad : spline::testing::kBadSplines) {
    SCOPED_TRACE(bad.name);
    const auto result = run_msp(
        {"tessellate", std::string(MSP_TEST_DATA) + "/bad/" + bad.name, "-o", out.string()});
    EXPECT_EQ(result.exit_status, 1);
    EXPECT_EQ(line_count(result.err), 1) << result.err;
    EXPECT_FALSE(fs::exists(out));
  }
  EXPECT_EQ(run_msp({"tessellate"}).exit_status, 2);
  EXPECT_EQ(run_msp({"tessellate", "x.msp", "-o", out.string(), "--density", "0"}).exit_status,
            2);
}

}  // namespace
