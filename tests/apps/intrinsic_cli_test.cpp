// msp flow and msp atlas with --metric intrinsic-delaunay on a genus-4 surface made here: the
// flow converges with flips and reports its metric; the atlas on the flipped triangulation has
// rigid transitions and no flipped face; --geometry other than euclidean is refused.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include <ricci/mesh/io.h>
#include <ricci/mesh/primitives.h>
#include <nlohmann/json.hpp>

#include "info_subprocess.h"
#include "scratch_folder.h"
#include "test_paths.h"

namespace {

class IntrinsicCli : public msp_test::ScratchFolderTest {
 protected:
  IntrinsicCli() : ScratchFolderTest("msp_intrinsic_cli_") {}
  void SetUp() override {
    ScratchFolderTest::SetUp();
    mesh_ = file("genus4.off", ricci::make_genus_slab(4, 2, 4));
  }
  std::string mesh_;
};

TEST_F(IntrinsicCli, FlowConvergesWithFlips) {
  const auto r = msp_test::run_msp(
      {"flow", mesh_, "--metric", "intrinsic-delaunay", "--target", "cone:0", "--json", "--quiet"});
  ASSERT_EQ(r.exit_status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["metric"], "intrinsic-delaunay");
  EXPECT_EQ(j["status"], "converged");
  EXPECT_GT(j["intrinsic_flips"].get<int>(), 0);
  EXPECT_LT(j["max_curvature_error"].get<double>(), 1e-10);
}

TEST_F(IntrinsicCli, AtlasOnTheFlippedTriangulation) {
  const auto r = msp_test::run_msp({"atlas", mesh_, "--json", "--quiet"});
  ASSERT_EQ(r.exit_status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["metric"], "intrinsic-delaunay");  // genus 4: the automatic route's choice
  EXPECT_EQ(j["genus"], 4);
  EXPECT_EQ(j["flipped_faces"], 0);
  EXPECT_GE(j["removed_edges"].get<int>(), 0);  // the intrinsic flow ran and converged
  EXPECT_LE(j["removed_edges"].get<int>(), j["intrinsic_flips"].get<int>());
  EXPECT_LT(j["transition_residual"].get<double>(), 1e-9);
  EXPECT_NEAR(j["singularities"][0]["cone_angle"].get<double>(), 14 * M_PI, 1e-8);
}

TEST_F(IntrinsicCli, RefusesANonEuclideanGeometry) {
  const auto r = msp_test::run_msp(
      {"flow", mesh_, "--metric", "intrinsic-delaunay", "--geometry", "hyperbolic", "--quiet"});
  EXPECT_EQ(r.exit_status, 2);
  EXPECT_NE(r.err.find("euclidean"), std::string::npos) << r.err;
}

// `msp atlas` hands the mesh it read over to the pipeline (build_one_cone_atlas(Mesh&&)); what
// the pipeline refuses after that is still one line, exit 1 and nothing on stdout.
TEST(AtlasCli, RefusesWhatThePipelineRefusesInOneLine) {
  const std::string genus0 = msp_test::bundled_model("genus0.off");
  const std::string genus2 = msp_test::bundled_model("genus2.off");
  const struct {
    std::vector<std::string> args;
    const char* keyword;
  } cases[] = {
      {{"atlas", genus2, "--singularity", "999999", "--json", "--quiet"}, "out of range"},
      {{"atlas", genus0, "--metric", "intrinsic-delaunay", "--json", "--quiet"}, "genus >= 1"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.keyword);
    const auto r = msp_test::run_msp(c.args);
    EXPECT_EQ(r.exit_status, 1);
    EXPECT_EQ(msp_test::line_count(r.err), 1) << r.err;
    EXPECT_EQ(r.err.rfind("msp atlas: error: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(c.keyword), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
}

}  // namespace
