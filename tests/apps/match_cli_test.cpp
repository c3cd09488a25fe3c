// msp match end to end on meshes made here: a plate with two holes against its isometric
// bending, the map file read back against the vertex correspondence, the .glb written; bad
// input gives one line, a non-zero status and no map.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <ricci/mesh/io.h>
#include <ricci/mesh/primitives.h>
#include <nlohmann/json.hpp>

#include "info_subprocess.h"
#include "scratch_folder.h"
#include "ricci/analysis/analysis_meshes.h"
#include "ricci/test_meshes.h"

namespace {

namespace fs = std::filesystem;

class MatchCli : public msp_test::ScratchFolderTest {
 protected:
  MatchCli() : ScratchFolderTest("msp_match_cli_") {}
};

ricci::Mesh plate() {
  return ricci::testing::circle_domain_mesh({{-0.35, 0.1, 0.2}, {0.4, -0.1, 0.15}}, 0.08);
}

ricci::Mesh rolled(const ricci::Mesh& flat) {
  return ricci::testing::mapped(flat, [](const Eigen::Vector3d& p) {
    return Eigen::Vector3d(std::sin(p.x()), p.y(), 1 - std::cos(p.x()));
  });
}

TEST_F(MatchCli, PlateAgainstItsBendingIsTheIdentity) {
  const ricci::Mesh flat = plate(), bent = rolled(flat);
  const std::string a = file("flat.off", flat), b = file("bent.off", bent);
  const auto r = msp_test::run_msp(
      {"match", a, b, "-o", path("map.txt"), "--glb", path("match.glb"), "--json"});
  ASSERT_EQ(r.exit_status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["domain"], "cone star");
  EXPECT_EQ(j["pieces"], 3);  // a quadrilateral round each hole and the central piece
  EXPECT_EQ(j["flipped_faces"], 0);
  EXPECT_EQ(j["flipped_faces_b"], 0);
  EXPECT_LT(j["correspondence_error_percent"].get<double>(), 0.1);
  EXPECT_TRUE(fs::file_size(path("match.glb")) > 1000);
  // --one-piece: the cut disk whole, the same identity.
  const auto one =
      msp_test::run_msp({"match", a, b, "-o", path("one.txt"), "--one-piece", "--json"});
  ASSERT_EQ(one.exit_status, 0) << one.err;
  const auto k = nlohmann::json::parse(one.out);
  EXPECT_EQ(k["pieces"], 1);
  EXPECT_EQ(k["flipped_faces"], 0);
  EXPECT_LT(k["correspondence_error_percent"].get<double>(), 0.1);
  // The map file: each vertex of A lands next to the same vertex of B.
  std::ifstream in(path("map.txt"));
  std::string magic;
  int version = 0, va = 0, vb = 0, fb = 0;
  in >> magic >> version >> va >> vb >> fb;
  ASSERT_EQ(magic, "msp-map");
  ASSERT_EQ(va, static_cast<int>(flat.n_vertices()));
  double worst = 0;
  for (int v = 0; v < va; ++v) {
    int face = 0, idx[3];
    double w[3];
    ASSERT_TRUE(in >> face >> idx[0] >> idx[1] >> idx[2] >> w[0] >> w[1] >> w[2]);
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) p += w[k] * ricci::to_eigen(bent.point(bent.vertex_handle(idx[k])));
    worst = std::max(worst, (p - ricci::to_eigen(bent.point(bent.vertex_handle(v)))).norm());
  }
  EXPECT_LT(worst, 0.01);  // of a diagonal ~2.3
}

TEST_F(MatchCli, HyperbolicMethod) {
  const ricci::Mesh flat = plate(), bent = rolled(flat);
  const std::string a = file("flat.off", flat), b = file("bent.off", bent);
  const auto r =
      msp_test::run_msp({"match", a, b, "-o", path("map.txt"), "--method", "hyperbolic", "--json"});
  ASSERT_EQ(r.exit_status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["method"], "hyperbolic");
  EXPECT_EQ(j["domain"], "klein polygon");
  EXPECT_EQ(j["flipped_faces"], 0);
  EXPECT_EQ(j["flipped_faces_b"], 0);
  EXPECT_LT(j["correspondence_error_percent"].get<double>(), 0.1);
  EXPECT_TRUE(fs::exists(path("map.txt")));
}

TEST_F(MatchCli, TextureErrorFromVertexColours) {
  const ricci::Mesh flat = plate(), bent = rolled(flat);
  // The same colours on both (COFF, 0-255): the map is the identity, so d_t is ~0.
  const auto coloured = [&](const std::string& name, const ricci::Mesh& mesh) {
    const std::string at = path(name);
    std::ofstream out(at);
    out << "COFF\n" << mesh.n_vertices() << " " << mesh.n_faces() << " 0\n";
    for (ricci::VertexHandle v : mesh.vertices()) {
      const auto p = mesh.point(v);
      const auto q = flat.point(v);
      out << p[0] << " " << p[1] << " " << p[2] << " " << static_cast<int>(120 + 100 * q[0]) << " "
          << static_cast<int>(120 + 100 * q[1]) << " 60 255\n";
    }
    for (ricci::FaceHandle f : mesh.faces()) {
      out << "3";
      for (ricci::VertexHandle v : mesh.fv_range(f)) out << " " << v.idx();
      out << "\n";
    }
    return at;
  };
  const std::string a = coloured("flat.off", flat), b = coloured("bent.off", bent);
  const auto r = msp_test::run_msp({"match", a, b, "-o", path("map.txt"), "--json"});
  ASSERT_EQ(r.exit_status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_TRUE(j["texture_error"].is_number()) << r.out;
  EXPECT_LT(j["texture_error"].get<double>(), 1e-2);
  // Without colours the key is null.
  const auto plain = msp_test::run_msp(
      {"match", file("p.off", flat), file("q.off", bent), "-o", path("m.txt"), "--json"});
  ASSERT_EQ(plain.exit_status, 0) << plain.err;
  EXPECT_TRUE(nlohmann::json::parse(plain.out)["texture_error"].is_null());
}

TEST_F(MatchCli, BadInputOneLineNoMap) {
  const std::string disk = file("disk.off", ricci::make_planar_grid(6, 6, 1, 1));
  const std::string holes = file("holes.off", plate());
  const std::string map = path("bad.map");
  const std::vector<std::vector<std::string>> cases = {
      {"match", disk, holes, "-o", map},  // topologies differ
      {"match", holes, holes, "-o", map, "--feature-a", "99999", "--feature-b", "3"},
      {"match", disk, disk, "-o", map, "--feature-a", "0", "--feature-b", "0"},  // on boundary
      {"match", disk, disk, "-o", map, "--method", "hyperbolic"},                // chi = 1
      {"match", holes, path("missing.off"), "-o", map},
  };
  for (const auto& args : cases) {
    const auto r = msp_test::run_msp(args);
    EXPECT_EQ(r.exit_status, 1) << args[2] << " " << r.err;
    EXPECT_EQ(msp_test::line_count(r.err), 1) << r.err;
    EXPECT_FALSE(fs::exists(map));
  }
  const auto usage = msp_test::run_msp({"match", disk, disk, "-o", map, "--method", "spherical"});
  EXPECT_EQ(usage.exit_status, 2) << usage.err;
}

}  // namespace
