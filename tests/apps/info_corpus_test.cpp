// msp info on the bad-input corpus (tests/data/bad): every file gives exactly one line on stderr
// naming the problem, a non-zero exit and nothing on stdout, run as the real binary (no crash or
// hang, also under ASan/UBSan). Files that can be read but are not clean surfaces are described
// by plain `msp info` (exit 0) and refused by `msp info --strict`.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>

#include "info_subprocess.h"

namespace {

namespace fs = std::filesystem;
using msp_test::line_count;
using msp_test::run_msp;

struct BadFile {
  const char* name;
  const char* keyword;  ///< must appear in the error line
  bool unreadable;      ///< refused even without --strict (parse-level error)
};

const BadFile kBadFiles[] = {
    {"empty.off", "file is empty", true},
    {"truncated_vertices.off", ":7: file ends after 5 of 8 vertices", true},
    {"truncated_faces.off", ":8: file ends after 2 of 4 faces", true},
    {"garbage.off", ":1: not an OFF file", true},
    {"garbage.ply", ":1: not a PLY file", true},
    {"garbage.obj", "binary data", true},
    {"unknown_extension.xyz", "unknown mesh format '.xyz'", true},
    {"index_out_of_range.off", ":11: face 3 has vertex index 99 but the file has 4 vertices", true},
    {"index_out_of_range.ply", ":12: face 0 has vertex index 7", true},
    {"index_zero.obj", ":8: face 3 has vertex index 0", true},
    {"bad_number.obj", ":3: vertex 2: expected a number, found '1.5e'", true},
    {"two_vertex_face.obj", ":4: face 0 has 2 vertices", true},
    {"no_faces.obj", "no faces", true},
    {"negative_count.off", ":2: bad vertex count '-4'", true},
    {"huge_count.off", "cannot fit in a file of 24 bytes", true},
    {"missing_z.ply", "lacks an x, y or z", true},
    {"truncated_binary.ply", "file ends inside element 'vertex' (record 58 of 100)", true},
    {"truncated_ascii.stl", "file ends inside a facet", true},
    {"truncated_binary.stl", "binary STL says 10 triangles", true},
    {"corrupt.off.gz", "corrupt or truncated gzip", true},
    {"nan_coordinate.obj", "vertex 2 (line 3) has a non-finite coordinate (nan", false},
    {"inf_coordinate.off", "vertex 2 (line 5) has a non-finite coordinate (0, 1, inf)", false},
    {"fin_edge.off", "edge (0, 1) is shared by 3 faces (faces 0, 1, 2)", false},
    {"bowtie.off", "vertex 0 is pinched: its faces form 2 fans", false},
    {"mobius.obj", "non-orientable: orientation conflict at edge", false},
    {"two_components.off", "2 connected components", false},
    {"zero_area_face.off", "face 3 (line 12) has zero area", false},
    {"repeated_index.off", "face 3 (line 10) is degenerate: it repeats a vertex index", false},
};

std::string bad_path(const char* name) { return std::string(MSP_TEST_DATA) + "/bad/" + name; }

TEST(InfoCorpus, EveryBadFileIsInTheTableAndViceVersa) {
  std::set<std::string> listed, present;
  for (const auto& bad : kBadFiles) listed.insert(bad.name);
  for (const auto& entry : fs::directory_iterator(std::string(MSP_TEST_DATA) + "/bad")) {
    // Spline files (.msp) have their own table (tests/spline/io/bad_splines.h).
    if (entry.path().extension() != ".msp") present.insert(entry.path().filename().string());
  }
  EXPECT_EQ(listed, present);
}

TEST(InfoCorpus, StrictGivesOneLineNamingTheProblemAndFails) {
  for (const auto& bad : kBadFiles) {
    SCOPED_TRACE(bad.name);
    const auto result = run_msp({"info", "--strict", bad_path(bad.name)});
    EXPECT_EQ(result.exit_status, 1);  // 1 = refused on purpose; -1 or 3 would be a crash
    EXPECT_EQ(line_count(result.err), 1) << result.err;
    EXPECT_EQ(result.err.rfind("msp info: error: ", 0), 0u) << result.err;
    EXPECT_NE(result.err.find(bad.name), std::string::npos) << result.err;
    EXPECT_NE(result.err.find(bad.keyword), std::string::npos) << result.err;
    if (bad.unreadable) {
      EXPECT_TRUE(result.out.empty()) << result.out;
    }
  }
}

TEST(InfoCorpus, UnreadableFilesFailWithoutStrictReadableOnesAreDescribed) {
  for (const auto& bad : kBadFiles) {
    SCOPED_TRACE(bad.name);
    const auto result = run_msp({"info", "--json", bad_path(bad.name)});
    if (bad.unreadable) {
      EXPECT_EQ(result.exit_status, 1);
      EXPECT_EQ(line_count(result.err), 1) << result.err;
      EXPECT_TRUE(result.out.empty());
      continue;
    }
    EXPECT_EQ(result.exit_status, 0) << result.err;
    EXPECT_TRUE(result.err.empty()) << result.err;
    const auto info = nlohmann::json::parse(result.out);
    ASSERT_FALSE(info["problems"].empty());
    EXPECT_NE(info["problems"][0].get<std::string>().find(bad.keyword), std::string::npos);
  }
}

// The pipeline commands read through ricci::read_mesh(), which refuses every bad file with the
// same one-line message (here `msp flow`, the first command that needs a clean surface).
TEST(InfoCorpus, PipelineCommandsRefuseEveryBadFileInOneLine) {
  for (const auto& bad : kBadFiles) {
    SCOPED_TRACE(bad.name);
    const auto result = run_msp({"flow", bad_path(bad.name)});
    EXPECT_EQ(result.exit_status, 1);
    EXPECT_EQ(line_count(result.err), 1) << result.err;
    EXPECT_EQ(result.err.rfind("msp flow: error: ", 0), 0u) << result.err;
    EXPECT_NE(result.err.find(bad.keyword), std::string::npos) << result.err;
  }
}

TEST(InfoCorpus, DescribesTheDefectsItFinds) {
  auto info = [](const char* name) {
    return nlohmann::json::parse(run_msp({"info", "--json", bad_path(name)}).out);
  };
  const auto fin = info("fin_edge.off");
  EXPECT_FALSE(fin["manifold"].get<bool>());
  EXPECT_EQ(fin["non_manifold_edges"], 1);
  const auto bowtie = info("bowtie.off");
  EXPECT_FALSE(bowtie["manifold"].get<bool>());
  EXPECT_EQ(bowtie["components"], 1);
  EXPECT_EQ(bowtie["boundary_loops"], 1);  // the two triangle boundaries meet at the pinch
  const auto mobius = info("mobius.obj");
  EXPECT_FALSE(mobius["orientable"].get<bool>());
  EXPECT_TRUE(mobius["manifold"].get<bool>());
  EXPECT_EQ(mobius["boundary_loops"], 1);
  EXPECT_EQ(mobius["euler_characteristic"], 0);
  const auto two = info("two_components.off");
  EXPECT_EQ(two["components"], 2);
  EXPECT_EQ(two["genus"], 0);
  EXPECT_EQ(two["euler_characteristic"], 4);
  EXPECT_EQ(info("zero_area_face.off")["degenerate_faces"], 1);
  EXPECT_EQ(info("repeated_index.off")["degenerate_faces"], 1);
}

TEST(InfoCommand, UsageErrorsExitTwo) {
  EXPECT_EQ(run_msp({"info"}).exit_status, 2);
  EXPECT_EQ(run_msp({"info", "--frobnicate", bad_path("bowtie.off")}).exit_status, 2);
  const auto missing = run_msp({"info", "/nonexistent/mesh.off"});
  EXPECT_EQ(missing.exit_status, 1);
  EXPECT_NE(missing.err.find("cannot open"), std::string::npos);
}

}  // namespace
