// tools/render.mjs end to end: a .glb written by the writer, rendered by three.js in headless
// Chromium, comes back as a PNG of the asked size showing the model in the middle.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>

#include <tiny_gltf.h>

#include "msp/io/gltf_writer.h"
#include "msp/io/texture_image.h"

namespace {

namespace fs = std::filesystem;

TEST(GltfRender, RendersATexturedSquareInTheMiddle) {
  const fs::path tools = fs::path(MSP_SOURCE_DIR) / "tools";
  if (!fs::exists(tools / "node_modules" / "puppeteer-core") || !fs::exists("/usr/bin/chromium") ||
      std::system("command -v node >/dev/null 2>&1") != 0) {
    GTEST_SKIP() << "node, tools/node_modules or /usr/bin/chromium missing "
                    "(scripts/install-deps.sh installs them)";
  }
  // A unit square facing the camera (azimuth 0, elevation 0 looks down -z), red.
  msp::gltf::Mesh square;
  square.name = "square";
  square.positions.resize(4, 3);
  square.positions << -1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0;
  square.normals = Eigen::MatrixX3d::Zero(4, 3);
  square.normals.col(2).setOnes();
  square.indices = {0, 1, 2, 0, 2, 3};
  square.material.base_color = {1.0, 0.0, 0.0, 1.0};
  msp::gltf::Scene scene;
  scene.meshes.push_back(square);
  const fs::path dir = fs::temp_directory_path() / "msp_gltf_render_test";
  fs::create_directories(dir);
  const fs::path glb = dir / "square.glb", png = dir / "square.png";
  fs::remove(png);
  msp::gltf::write_glb(scene, glb.string());

  const std::string command =
      "node '" + (tools / "render.mjs").string() + "' '" + glb.string() + "' '" + png.string() +
      "' --width 200 --height 120 --azimuth 0 --elevation 0 >/dev/null 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << command;

  std::ifstream in(png, std::ios::binary);
  const std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)),
                                         std::istreambuf_iterator<char>());
  tinygltf::Image image;
  std::string err, warn;
  ASSERT_TRUE(tinygltf::LoadImageData(&image, 0, &err, &warn, 0, 0, bytes.data(),
                                      static_cast<int>(bytes.size()), nullptr))
      << err;
  ASSERT_EQ(image.width, 200);
  ASSERT_EQ(image.height, 120);
  auto pixel = [&](int x, int y, int c) {
    return image.image[static_cast<size_t>((y * image.width + x) * image.component + c)];
  };
  // Lit red in the middle; the white background in the corners.
  EXPECT_GT(pixel(100, 60, 0), 100);
  EXPECT_LT(pixel(100, 60, 1), 60);
  EXPECT_LT(pixel(100, 60, 2), 60);
  for (int c = 0; c < 3; ++c) EXPECT_EQ(pixel(2, 2, c), 255);
}

}  // namespace
