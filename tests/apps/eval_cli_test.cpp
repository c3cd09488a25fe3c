// msp eval and msp bezier as the real binary: the figures printed equal the library's evaluation
// of the same spline file (evaluate_surface, ClosestPointIndex, bezier_patches); bad input gives
// one line on stderr and a non-zero status (1: refused input, 2: bad command line), no output.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "info_subprocess.h"
#include "spline/io/spline_file.h"
#include "spline/surface/bezier.h"
#include "spline/surface/closest_point.h"
#include "spline/surface/evaluate.h"
#include "spline/surface/surface_fixtures.h"

namespace {

namespace fs = std::filesystem;
using msp_test::line_count;
using msp_test::run_msp;

fs::path scratch() {
  const fs::path dir = fs::temp_directory_path() / ("msp_eval_tests_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

// The torus at 100 faces saved as a spline file (once), and that file read back.
const std::string& torus_file() {
  static const std::string path = [] {
    const std::string p = (scratch() / "torus.msp").string();
    spline::save_spline_surface(spline::testing::small_surface("genus1.off", 100), p);
    return p;
  }();
  return path;
}

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream(path) << text;
}

Eigen::Vector3d vec(const nlohmann::json& j) {
  return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()};
}

TEST(EvalCli, PointsMatchTheLibrary) {
  const spline::SplineSurface surface = spline::load_spline_surface(torus_file());
  const std::vector<int>& faces = surface.spline.space->domain_faces();
  std::vector<spline::DomainPoint> points;
  std::string csv = "# face, b0, b1, b2\n";
  for (std::size_t i = 0; i < faces.size(); i += 9) {
    points.push_back({faces[i], Eigen::Vector3d(0.2, 0.3, 0.5)});
    csv += std::to_string(faces[i]) + ", 0.2, 0.3, 0.5\n";
  }
  const fs::path p = scratch() / "points.csv";
  write_text(p, csv);
  const auto result = run_msp({"eval", torus_file(), "--points", p.string(), "--json"});
  ASSERT_EQ(result.exit_status, 0) << result.err;
  const nlohmann::json json = nlohmann::json::parse(result.out);
  ASSERT_EQ(json["points"].size(), points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const spline::SurfaceDifferential d = spline::evaluate_surface(surface, points[i]);
    const nlohmann::json& e = json["points"][i];
    EXPECT_EQ(e["location"]["face"].get<int>(), points[i].face);
    EXPECT_EQ(vec(e["position"]), d.position);
    EXPECT_EQ(vec(e["du"]), d.du);
    EXPECT_EQ(vec(e["dvv"]), d.dvv);
    EXPECT_EQ(vec(e["normal"]), d.normal);
    EXPECT_EQ(e["gaussian_curvature"].get<double>(), d.curvature.gaussian);
    EXPECT_EQ(e["mean_curvature"].get<double>(), d.curvature.mean);
    EXPECT_EQ(e["chart"].get<int>(), d.chart);
  }
  const auto text = run_msp({"eval", torus_file(), "--points", p.string()});
  ASSERT_EQ(text.exit_status, 0) << text.err;
  EXPECT_EQ(line_count(text.out), static_cast<int>(points.size()));
}

TEST(EvalCli, ClosestPointsMatchTheLibrary) {
  const spline::SplineSurface surface = spline::load_spline_surface(torus_file());
  Eigen::MatrixX3d targets(3, 3);
  targets << 0.1, 0.2, 0.3, 1.5, -0.2, 0.1, -0.4, 0.9, -0.3;
  std::string xyz;
  for (int i = 0; i < 3; ++i) {
    xyz += std::to_string(targets(i, 0)) + " " + std::to_string(targets(i, 1)) + " " +
           std::to_string(targets(i, 2)) + "\n";
  }
  const fs::path q = scratch() / "targets.xyz";
  write_text(q, xyz);
  const auto result = run_msp({"eval", torus_file(), "--closest", q.string(), "--json"});
  ASSERT_EQ(result.exit_status, 0) << result.err;
  const nlohmann::json json = nlohmann::json::parse(result.out);
  const spline::ClosestPointIndex index(surface);
  ASSERT_EQ(json["points"].size(), 3u);
  for (int i = 0; i < 3; ++i) {
    const spline::ClosestPoint c = index.find(Eigen::Vector3d(targets.row(i).transpose()));
    const nlohmann::json& e = json["points"][static_cast<std::size_t>(i)];
    EXPECT_EQ(e["distance"].get<double>(), c.distance);
    // The point printed is the surface evaluated at the closest point's location.
    EXPECT_EQ(vec(e["position"]), spline::evaluate_surface(surface, c.location).position);
    EXPECT_NEAR((vec(e["target"]) - vec(e["position"])).norm(), c.distance, 1e-12);
  }
}

TEST(EvalCli, BadInputGivesOneLine) {
  const fs::path dir = scratch();
  write_text(dir / "letters.csv", "3, 0.2, x, 0.5\n");
  write_text(dir / "short.csv", "3, 0.2, 0.5\n");
  write_text(dir / "far.csv", "999999, 0.2, 0.3, 0.5\n");
  write_text(dir / "nan.csv", "3, nan, 0.3, 0.5\n");
  write_text(dir / "empty.xyz", "# nothing\n");
  const std::string bad_msp = std::string(MSP_TEST_DATA) + "/bad/truncated.msp";
  for (const std::vector<std::string>& call :
       {std::vector<std::string>{"eval", torus_file(), "--points", (dir / "letters.csv").string()},
        {"eval", torus_file(), "--points", (dir / "short.csv").string()},
        {"eval", torus_file(), "--points", (dir / "far.csv").string()},
        {"eval", torus_file(), "--points", (dir / "nan.csv").string()},
        {"eval", torus_file(), "--points", (dir / "missing.csv").string()},
        {"eval", torus_file(), "--closest", (dir / "empty.xyz").string()},
        {"eval", bad_msp, "--points", (dir / "short.csv").string()},
        {"bezier", bad_msp, "-o", (dir / "patches.json").string()}}) {
    SCOPED_TRACE(call[3]);
    const auto result = run_msp(call);
    EXPECT_EQ(result.exit_status, 1);
    EXPECT_EQ(line_count(result.err), 1) << result.err;
    EXPECT_TRUE(result.out.empty()) << result.out;
  }
  EXPECT_FALSE(fs::exists(dir / "patches.json"));
  // Bad command lines: status 2.
  for (const std::vector<std::string>& call :
       {std::vector<std::string>{"eval", torus_file()},
        {"eval", torus_file(), "--points", "a.csv", "--closest", "b.xyz"},
        {"bezier", torus_file()}}) {
    const auto result = run_msp(call);
    EXPECT_EQ(result.exit_status, 2);
    EXPECT_EQ(line_count(result.err), 1) << result.err;
  }
}

TEST(BezierCli, WritesTheLibrarysPatches) {
  const fs::path out = scratch() / "patches.json";
  const auto result = run_msp({"bezier", torus_file(), "-o", out.string(), "--json"});
  ASSERT_EQ(result.exit_status, 0) << result.err;
  const spline::BezierExport e = spline::bezier_patches(spline::load_spline_surface(torus_file()));
  const nlohmann::json summary = nlohmann::json::parse(result.out);
  EXPECT_EQ(summary["patches"].get<std::size_t>(), e.patches.size());
  std::ifstream in(out);
  const nlohmann::json file = nlohmann::json::parse(in);
  EXPECT_EQ(file["format"], "msp-bezier");
  EXPECT_EQ(file["degree"].get<int>(), e.degree);
  EXPECT_EQ(file["faces"].get<int>(), e.faces);
  ASSERT_EQ(file["patches"].size(), e.patches.size());
  ASSERT_EQ(file["multi_indices"].size(),
            static_cast<std::size_t>(e.patches[0].control_points.rows()));
  for (std::size_t i = 0; i < e.patches.size(); i += 97) {
    const nlohmann::json& p = file["patches"][i];
    EXPECT_EQ(p["face"].get<int>(), e.patches[i].face);
    EXPECT_EQ(p["vertices"][2].get<int>(), e.patches[i].vertices[2]);
    EXPECT_EQ(vec(p["corners"][1]), Eigen::Vector3d(e.patches[i].corners.col(1)));
    for (Eigen::Index r = 0; r < e.patches[i].control_points.rows(); ++r) {
      EXPECT_EQ(vec(p["control_points"][static_cast<std::size_t>(r)]),
                Eigen::Vector3d(e.patches[i].control_points.row(r).transpose()));
    }
  }
}

}  // namespace
