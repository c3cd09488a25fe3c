// read_glb_triangles: a .glb msp writes reads back as the surface it holds; bad files (missing,
// garbage, truncated, no such mesh) are refused with ricci::IOError, never a crash.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "info_subprocess.h"
#include "msp/io/gltf_reader.h"
#include "ricci/mesh/errors.h"

namespace {

namespace fs = std::filesystem;

fs::path scratch() {
  const fs::path dir = fs::temp_directory_path() / ("msp_glb_reader_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

TEST(GlbReader, ReadsWhatMspWritesAndRefusesBadFiles) {
  const fs::path dir = scratch();
  const std::string glb = (dir / "torus.glb").string();
  const auto fit = msp_test::run_msp({"fit", std::string(MSP_SOURCE_DIR) + "/models/genus1.off",
                                      "-o", glb, "--domain-faces", "300", "--quiet"});
  ASSERT_EQ(fit.exit_status, 0) << fit.err;
  const auto surface = msp::gltf::read_glb_triangles(glb);
  EXPECT_GT(surface.triangles.size(), 100u);
  EXPECT_GE(surface.render_vertices, surface.positions.rows());  // uv seams welded
  EXPECT_THROW((void)msp::gltf::read_glb_triangles(glb, "no such mesh"), ricci::IOError);
  EXPECT_THROW((void)msp::gltf::read_glb_triangles((dir / "missing.glb").string()),
               ricci::IOError);
  std::ifstream in(glb, std::ios::binary);
  const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), {});
  for (const std::size_t keep : {std::size_t{0}, std::size_t{11}, bytes.size() / 2}) {
    const std::string cut = (dir / ("cut" + std::to_string(keep) + ".glb")).string();
    std::ofstream(cut, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(keep));
    EXPECT_THROW((void)msp::gltf::read_glb_triangles(cut), ricci::IOError) << keep;
  }
}

}  // namespace
