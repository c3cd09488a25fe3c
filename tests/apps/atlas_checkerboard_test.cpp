// `msp atlas --checkerboard`: the mesh split along the cut with the central chart as uvs.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <tiny_gltf.h>

#include "apps/atlas_test_util.h"
#include "apps/gltf_test_util.h"
#include "msp/gltf_atlas.h"
#include "test_paths.h"

namespace {

namespace fs = std::filesystem;
using msp_test::genus2_atlas;
using msp_test::torus_atlas;

fs::path temp_dir() {
  fs::path dir = fs::temp_directory_path() / "msp_atlas_checkerboard_tests";
  fs::create_directories(dir);
  return dir;
}

TEST(AtlasCheckerboard, UvsAreTheFlatMetricUpToOneScale) {
  for (const auto* r : {&torus_atlas(), &genus2_atlas()}) {
    const msp::AtlasTexturedMesh m = msp::atlas_textured_mesh(*r);
    const auto& sliced = r->atlas.sliced;
    ASSERT_EQ(m.positions.rows(), static_cast<Eigen::Index>(sliced.mesh.n_vertices()));
    ASSERT_EQ(m.triangles.size(), 3 * r->problem.mesh.n_faces());
    // Every edge of every face: uv length = scale * flat-metric length (conformal to the surface
    // where the metric is, exactly the Ricci-flow lengths here).
    double worst = 0.0;
    for (auto e : sliced.mesh.edges()) {
      const auto h = sliced.mesh.halfedge_handle(e, 0);
      const int a = sliced.mesh.from_vertex_handle(h).idx(),
                b = sliced.mesh.to_vertex_handle(h).idx();
      const double uv = (m.uvs.row(a) - m.uvs.row(b)).norm();
      const double metric = r->flow.lengths[sliced.to_original_edge[static_cast<size_t>(e.idx())]];
      worst = std::max(worst, std::abs(uv / (m.uv_scale * metric) - 1.0));
    }
    EXPECT_LT(worst, 1e-9);
    // Inside the unit square, touching both ends of the longer side.
    EXPECT_GE(m.uvs.minCoeff(), -1e-12);
    EXPECT_LE(m.uvs.maxCoeff(), 1 + 1e-12);
    EXPECT_NEAR(std::max(m.uvs.col(0).maxCoeff() - m.uvs.col(0).minCoeff(),
                         m.uvs.col(1).maxCoeff() - m.uvs.col(1).minCoeff()),
                1.0, 1e-12);
    // Positions are those of the problem mesh; normals are unit and shared across the seam.
    for (Eigen::Index v = 0; v < m.positions.rows(); ++v) {
      const int p = m.problem_vertex[static_cast<size_t>(v)];
      EXPECT_EQ(
          m.positions.row(v),
          ricci::to_eigen(r->problem.mesh.point(r->problem.mesh.vertex_handle(p))).transpose());
      EXPECT_NEAR(m.normals.row(v).norm(), 1.0, 1e-12);
    }
    // The split adds exactly the seam copies: more vertices than the closed mesh.
    EXPECT_GT(m.positions.rows(), static_cast<Eigen::Index>(r->problem.mesh.n_vertices()));
  }
}

TEST(AtlasCheckerboard, GlbHasSurfaceLoopsAndConeAndValidates) {
  const auto& r = genus2_atlas();
  msp::CheckerboardExportOptions options;
  options.texture.size = 256;
  options.texture.squares = 16;
  options.extras = {{"genus", 2}};
  const auto scene = msp::checkerboard_scene(r, options);
  ASSERT_EQ(scene.meshes.size(), 1 + r.atlas.cut.loops.size() + 1);
  EXPECT_EQ(scene.meshes.front().name, "surface");
  EXPECT_EQ(scene.meshes.back().name, "cone");
  const fs::path path = temp_dir() / "eight.glb";
  msp::gltf::write_glb(scene, path.string());

  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &err, &warn, path.string())) << err;
  EXPECT_EQ(model.meshes.size(), scene.meshes.size());
  EXPECT_EQ(model.images.size(), 1u);
  EXPECT_EQ(model.images[0].width, 256);
  EXPECT_EQ(model.asset.extras.Get("genus").GetNumberAsInt(), 2);
  const auto& surface = model.meshes[0].primitives[0];
  EXPECT_EQ(model.accessors[static_cast<size_t>(surface.indices)].count,
            3 * r.problem.mesh.n_faces());

  const auto report = msp_test::run_gltf_validator(path.string());
  if (!report)
    GTEST_SKIP() << "node or tools/node_modules missing (scripts/install-deps.sh installs them)";
  EXPECT_EQ(report->value("errors", -1), 0) << report->dump(1);
  EXPECT_EQ(report->value("warnings", -1), 0) << report->dump(1);
}

TEST(AtlasCheckerboard, ObjWritesMeshMaterialAndTexture) {
  const auto& r = torus_atlas();
  const fs::path obj = temp_dir() / "elk.obj";
  msp::CheckerboardOptions texture;
  texture.size = 128;
  texture.squares = 8;
  msp::write_checkerboard_obj(r, obj.string(), texture);
  ASSERT_TRUE(fs::exists(temp_dir() / "elk.mtl"));
  ASSERT_TRUE(fs::exists(temp_dir() / "elk_checker.png"));
  std::ifstream in(obj);
  std::string line;
  size_t v = 0, vt = 0, vn = 0, f = 0;
  bool mtllib = false;
  while (std::getline(in, line)) {
    if (line.rfind("v ", 0) == 0) ++v;
    if (line.rfind("vt ", 0) == 0) ++vt;
    if (line.rfind("vn ", 0) == 0) ++vn;
    if (line.rfind("f ", 0) == 0) ++f;
    if (line == "mtllib elk.mtl") mtllib = true;
  }
  EXPECT_TRUE(mtllib);
  EXPECT_EQ(v, r.atlas.sliced.mesh.n_vertices());
  EXPECT_EQ(vt, v);
  EXPECT_EQ(vn, v);
  EXPECT_EQ(f, r.problem.mesh.n_faces());
  std::ifstream mtl(temp_dir() / "elk.mtl");
  std::stringstream text;
  text << mtl.rdbuf();
  EXPECT_NE(text.str().find("map_Kd elk_checker.png"), std::string::npos);
}

TEST(AtlasCheckerboard, CommandLineWritesPicturesAndKeepsTheReport) {
  const fs::path dir = temp_dir();
  const std::string model = msp_test::test_mesh("closed_g2/eight.off");
  const std::string out = (dir / "cli.json").string();
  const std::string command = std::string(MSP_BINARY) + " atlas '" + model +
                              "' --singularity 570 --quiet --json -o '" +
                              (dir / "cli.svg").string() + "' --checkerboard '" +
                              (dir / "cli.glb").string() + "' > '" + out + "'";
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  std::ifstream in(out);
  const auto report = nlohmann::json::parse(in);
  for (const char* key :
       {"genus", "transition_residual", "polygon_word", "singularities", "stage_seconds"}) {
    EXPECT_TRUE(report.contains(key)) << key;
  }
  EXPECT_GT(fs::file_size(dir / "cli.svg"), 10000u);
  EXPECT_GT(fs::file_size(dir / "cli.glb"), 10000u);
  // Bad output names are usage errors (status 2) and write nothing.
  const std::string bad = std::string(MSP_BINARY) + " atlas '" + model + "' --quiet -o '" +
                          (dir / "x.png").string() + "' 2>/dev/null >/dev/null";
  const int status = std::system(bad.c_str());
  EXPECT_EQ(WEXITSTATUS(status), 2);
  EXPECT_FALSE(fs::exists(dir / "x.png"));
}

}  // namespace
