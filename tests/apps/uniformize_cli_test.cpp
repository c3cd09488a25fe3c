// msp uniformize end to end (JSON keys, residuals, SVG, bad input) and the tiling property the
// Poincaré picture relies on.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>
#include <ricci/hyperbolic/uniformize.h>
#include <ricci/hyperbolic/universal_cover.h>
#include <ricci/mesh/io.h>
#include <ricci/topology/cut_graph.h>

#include "info_subprocess.h"
#include "msp/svg_cover.h"
#include "msp/svg_poincare.h"
#include "test_paths.h"

namespace {

namespace fs = std::filesystem;

std::string model(const std::string& name) { return msp_test::test_mesh(name); }

TEST(UniformizeCli, JsonOnGenus2HasTheContractKeysAndSmallResiduals) {
  const fs::path svg = fs::temp_directory_path() / "msp_uniformize_test_eight.svg";
  fs::remove(svg);
  const auto r = msp_test::run_msp({"uniformize", model("closed_g2/eight.off"), "-o", svg.string(), "--json"});
  ASSERT_EQ(r.exit_status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  for (const char* key : {"geometry", "genus", "max_curvature_error", "generators", "relation_residual", "seconds"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  EXPECT_EQ(j["geometry"], "hyperbolic");
  EXPECT_EQ(j["genus"], 2);
  EXPECT_LT(j["max_curvature_error"].get<double>(), 1e-10);
  EXPECT_LT(j["relation_residual"].get<double>(), 1e-9);
  ASSERT_EQ(j["generators"].size(), 4u);
  const char* names[] = {"a1", "b1", "a2", "b2"};
  for (size_t i = 0; i < 4; ++i) {
    const auto& g = j["generators"][i];
    EXPECT_EQ(g["name"], names[i]);
    const double c = g["exp_i_theta"][0], s = g["exp_i_theta"][1];
    EXPECT_NEAR(c * c + s * s, 1.0, 1e-12);
    const double x = g["z0"][0], y = g["z0"][1];
    EXPECT_LT(x * x + y * y, 1.0);
    ASSERT_EQ(g["klein"].size(), 3u);
    // Lorentz: the first column is a future-pointing unit timelike vector.
    const double l00 = g["klein"][0][0], l10 = g["klein"][1][0], l20 = g["klein"][2][0];
    EXPECT_NEAR((l00 * l00 - l10 * l10 - l20 * l20) / (l00 * l00), 1.0 / (l00 * l00), 1e-9);
  }
  std::ifstream in(svg);
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_NE(text.str().find("<circle"), std::string::npos);
  EXPECT_NE(text.str().find("id=\"copies\""), std::string::npos);
  fs::remove(svg);
}

TEST(UniformizeCli, TorusReportsTheModulus) {
  const auto r = msp_test::run_msp({"uniformize", model("closed_g1/knot1.off.gz"), "--json"});
  ASSERT_EQ(r.exit_status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["geometry"], "euclidean");
  EXPECT_EQ(j["generators"].size(), 2u);
  EXPECT_GT(j["reduced_modulus"][1].get<double>(), 0.86);
}

TEST(UniformizeCli, NonManifoldInputFailsWithOneLineAndNoFile) {
  const fs::path svg = fs::temp_directory_path() / "msp_uniformize_test_bad.svg";
  fs::remove(svg);
  const auto r = msp_test::run_msp({"uniformize", model("nonmanifold/cow_ajc.obj"), "-o", svg.string()});
  EXPECT_NE(r.exit_status, 0);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_TRUE(r.out.empty());
  EXPECT_FALSE(fs::exists(svg));
}

TEST(PoincareCover, ImagesOfTheDomainDoNotOverlapIt) {
  // Every nontrivial group element moves the domain's interior off itself: the centroids of
  // the domain's faces, mapped by the copies the picture draws, land outside the domain.
  const ricci::Uniformization u = ricci::uniformize(ricci::read_mesh(model("closed_g2/eight.off")));
  ASSERT_TRUE(u.converged());
  const auto loops = ricci::find_boundary_loops(u.sliced.mesh);
  ASSERT_EQ(loops.size(), 1u);
  Eigen::MatrixX2d outline(static_cast<Eigen::Index>(loops[0].size()), 2);
  for (size_t i = 0; i < loops[0].size(); ++i) {
    const auto z = u.positions[u.sliced.mesh.to_vertex_handle(loops[0][loops[0].size() - 1 - i]).idx()];
    outline.row(static_cast<Eigen::Index>(i)) << z.real(), z.imag();
  }
  std::vector<ricci::Mobius> pairings;
  for (const auto& a : u.pairings.arcs) pairings.push_back(a.pairing);
  const auto elements = ricci::group_elements(pairings, 2);
  EXPECT_GT(elements.size(), 2 * pairings.size());
  int inside = 0, tested = 0;
  for (auto f : u.sliced.mesh.faces()) {
    if (f.idx() % 7 != 0) continue;
    ricci::Complex c = 0.0;
    for (auto v : u.sliced.mesh.fv_range(f)) c += u.positions[v.idx()] / 3.0;
    EXPECT_EQ(msp::winding_number(outline, {c.real(), c.imag()}), 1);
    for (size_t k = 1; k < elements.size(); ++k) {
      const ricci::Complex z = elements[k].map(c);
      inside += msp::winding_number(outline, {z.real(), z.imag()}) != 0;
      ++tested;
    }
  }
  EXPECT_GT(tested, 1000);
  EXPECT_EQ(inside, 0);
  msp::PoincareSvgStats stats;
  (void)msp::uniformization_svg(u, {}, &stats);
  EXPECT_GT(stats.copies_drawn, 100);
}

}  // namespace
