#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <ricci/mesh/errors.h>
#include <tiny_gltf.h>

#include "apps/gltf_test_util.h"
#include "msp/io/gltf_writer.h"
#include "msp/io/texture_image.h"

namespace {

namespace fs = std::filesystem;
using msp::gltf::Mesh;
using msp::gltf::Scene;
using msp::gltf::Topology;

// An octahedron with per-vertex normals (the positions themselves) and spherical uvs.
Mesh octahedron() {
  Mesh m;
  m.name = "octahedron";
  m.positions.resize(6, 3);
  m.positions << 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1;
  m.normals = m.positions * 3.0;  // not unit: the writer normalises
  m.uvs.resize(6, 2);
  for (int i = 0; i < 6; ++i)
    m.uvs.row(i) << 0.5 + 0.5 * m.positions(i, 0), 0.5 + 0.5 * m.positions(i, 1);
  m.indices = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
  return m;
}

Scene sample_scene() {
  Scene scene;
  scene.name = "test scene";
  Mesh surface = octahedron();
  msp::CheckerboardOptions checker;
  checker.size = 64;
  checker.squares = 8;
  surface.material.texture =
      msp::gltf::Texture{msp::encode_png(msp::checkerboard(checker)), true, true};
  surface.material.double_sided = true;
  surface.extras = {{"kind", "surface"}};
  scene.meshes.push_back(surface);

  Mesh loop;
  loop.name = "cut loop";
  loop.topology = Topology::lines;
  loop.positions = surface.positions.topRows(4);
  loop.indices = {0, 2, 2, 1, 1, 3, 3, 0};
  loop.material.base_color = {0.9, 0.1, 0.1, 1.0};
  scene.meshes.push_back(loop);

  Mesh point;
  point.name = "extraordinary point";
  point.topology = Topology::points;
  point.positions = Eigen::RowVector3d(0.25, -0.5, 2.0);
  point.material.base_color = {0.1, 0.1, 0.9, 1.0};
  scene.meshes.push_back(point);

  scene.extras = {{"genus", 2},
                  {"cone_angle", 6 * M_PI},
                  {"word", "a1 b1 a1^-1 b1^-1"},
                  {"list", {1, 2.5, false}},
                  {"big", 10000000000LL}};
  return scene;
}

fs::path temp_file(const std::string& name) {
  fs::path dir = fs::temp_directory_path() / "msp_gltf_tests";
  fs::create_directories(dir);
  return dir / name;
}

tinygltf::Model load(const fs::path& path) {
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string err, warn;
  const bool ok = loader.LoadBinaryFromFile(&model, &err, &warn, path.string());
  EXPECT_TRUE(ok) << err;
  EXPECT_EQ(warn, "");
  return model;
}

template <typename T>
std::vector<T> read_accessor(const tinygltf::Model& model, int index) {
  const auto& a = model.accessors[static_cast<size_t>(index)];
  const auto& view = model.bufferViews[static_cast<size_t>(a.bufferView)];
  const auto& data = model.buffers[static_cast<size_t>(view.buffer)].data;
  const size_t components = a.type == TINYGLTF_TYPE_SCALAR ? 1
                            : a.type == TINYGLTF_TYPE_VEC2 ? 2
                                                           : 3;
  std::vector<T> out(a.count * components);
  std::memcpy(out.data(), data.data() + view.byteOffset + a.byteOffset, out.size() * sizeof(T));
  return out;
}

TEST(GltfWriter, RoundTripsMeshesTextureAndExtras) {
  const Scene scene = sample_scene();
  const fs::path path = temp_file("roundtrip.glb");
  msp::gltf::write_glb(scene, path.string());
  const tinygltf::Model model = load(path);

  ASSERT_EQ(model.meshes.size(), 3u);
  ASSERT_EQ(model.nodes.size(), 3u);
  ASSERT_EQ(model.scenes.size(), 1u);
  EXPECT_EQ(model.scenes[0].nodes.size(), 3u);
  EXPECT_EQ(model.buffers.size(), 1u);
  EXPECT_EQ(model.images.size(), 1u);
  EXPECT_EQ(model.meshes[0].name, "octahedron");
  EXPECT_EQ(model.meshes[1].primitives[0].mode, TINYGLTF_MODE_LINE);
  EXPECT_EQ(model.meshes[2].primitives[0].mode, TINYGLTF_MODE_POINTS);

  // Positions and indices come back exactly (floats of the input), with min/max bounds.
  const auto& surface = model.meshes[0].primitives[0];
  const int pos = surface.attributes.at("POSITION");
  const auto positions = read_accessor<float>(model, pos);
  ASSERT_EQ(positions.size(), 18u);
  for (int i = 0; i < 18; ++i)
    EXPECT_EQ(positions[static_cast<size_t>(i)],
              static_cast<float>(scene.meshes[0].positions(i / 3, i % 3)));
  EXPECT_EQ(model.accessors[static_cast<size_t>(pos)].minValues, (std::vector<double>{-1, -1, -1}));
  EXPECT_EQ(model.accessors[static_cast<size_t>(pos)].maxValues, (std::vector<double>{1, 1, 1}));
  EXPECT_EQ(read_accessor<std::uint32_t>(model, surface.indices), scene.meshes[0].indices);

  const auto normals = read_accessor<float>(model, surface.attributes.at("NORMAL"));
  for (size_t v = 0; v < 6; ++v) {
    EXPECT_NEAR(std::hypot(normals[3 * v], normals[3 * v + 1], normals[3 * v + 2]), 1.0, 1e-7);
    EXPECT_NEAR(normals[3 * v + 2], scene.meshes[0].positions(static_cast<int>(v), 2), 1e-7);
  }
  const auto uvs = read_accessor<float>(model, surface.attributes.at("TEXCOORD_0"));
  EXPECT_EQ(uvs.size(), 12u);
  EXPECT_FLOAT_EQ(uvs[0], 1.0f);

  // Every buffer view starts on a 4-byte boundary.
  for (const auto& view : model.bufferViews) EXPECT_EQ(view.byteOffset % 4, 0u);

  // The texture decodes to the checkerboard we encoded.
  const auto& material = model.materials[static_cast<size_t>(surface.material)];
  EXPECT_TRUE(material.doubleSided);
  const int texture = material.pbrMetallicRoughness.baseColorTexture.index;
  ASSERT_GE(texture, 0);
  const auto& image =
      model.images[static_cast<size_t>(model.textures[static_cast<size_t>(texture)].source)];
  EXPECT_EQ(image.mimeType, "image/png");
  EXPECT_GE(image.bufferView, 0);
  ASSERT_EQ(image.width, 64);
  ASSERT_EQ(image.height, 64);
  EXPECT_EQ(image.image[(9 * 64 + 9) * 4], 40);    // square (1, 1): dark
  EXPECT_EQ(image.image[(9 * 64 + 17) * 4], 236);  // square (2, 1): light

  const auto& line_material =
      model.materials[static_cast<size_t>(model.meshes[1].primitives[0].material)];
  EXPECT_DOUBLE_EQ(line_material.pbrMetallicRoughness.baseColorFactor[0], 0.9);

  // Metadata: on the asset and the scene, numbers keep their values.
  EXPECT_EQ(model.asset.extras.Get("genus").GetNumberAsInt(), 2);
  EXPECT_DOUBLE_EQ(model.scenes[0].extras.Get("cone_angle").GetNumberAsDouble(), 6 * M_PI);
  EXPECT_EQ(model.asset.extras.Get("word").Get<std::string>(), "a1 b1 a1^-1 b1^-1");
  EXPECT_EQ(model.asset.extras.Get("list").ArrayLen(), 3u);
  EXPECT_DOUBLE_EQ(model.asset.extras.Get("big").GetNumberAsDouble(), 1e10);
  EXPECT_EQ(model.meshes[0].extras.Get("kind").Get<std::string>(), "surface");
}

TEST(GltfWriter, GlbHeaderAndChunksAreConsistent) {
  const std::vector<std::uint8_t> bytes = msp::gltf::glb_bytes(sample_scene());
  auto u32 = [&](size_t at) {
    return static_cast<std::uint32_t>(bytes[at]) | static_cast<std::uint32_t>(bytes[at + 1]) << 8 |
           static_cast<std::uint32_t>(bytes[at + 2]) << 16 |
           static_cast<std::uint32_t>(bytes[at + 3]) << 24;
  };
  ASSERT_GE(bytes.size(), 28u);
  EXPECT_EQ(std::string(bytes.begin(), bytes.begin() + 4), "glTF");
  EXPECT_EQ(u32(4), 2u);
  EXPECT_EQ(u32(8), bytes.size());
  const std::uint32_t json_length = u32(12);
  EXPECT_EQ(u32(16), 0x4E4F534Au);  // "JSON"
  EXPECT_EQ(json_length % 4, 0u);
  const size_t bin = 20 + json_length;
  EXPECT_EQ(u32(bin + 4), 0x004E4942u);  // "BIN\0"
  EXPECT_EQ(u32(bin) % 4, 0u);
  EXPECT_EQ(bin + 8 + u32(bin), bytes.size());
}

TEST(GltfWriter, PassesTheKhronosValidatorWithoutWarnings) {
  const fs::path path = temp_file("validate.glb");
  msp::gltf::write_glb(sample_scene(), path.string());
  const auto report = msp_test::run_gltf_validator(path.string());
  if (!report)
    GTEST_SKIP() << "node or tools/node_modules missing (scripts/install-deps.sh installs them)";
  ASSERT_TRUE(report->is_object()) << "validator output is not JSON";
  EXPECT_EQ(report->value("errors", -1), 0) << report->dump(1);
  EXPECT_EQ(report->value("warnings", -1), 0) << report->dump(1);
  EXPECT_EQ((*report)["info"].value("totalTriangleCount", -1), 8);
}

TEST(GltfWriter, RejectsBadMeshesNamingThem) {
  auto expect_rejected = [](const Mesh& mesh, const std::string& fragment) {
    Scene scene;
    scene.meshes.push_back(mesh);
    try {
      msp::gltf::check_scene(scene);
      ADD_FAILURE() << "accepted a mesh with " << fragment;
    } catch (const ricci::InvalidInputError& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("octahedron"), std::string::npos) << e.what();
    }
  };
  Mesh m = octahedron();
  m.indices.push_back(0);
  expect_rejected(m, "multiple of 3");
  m = octahedron();
  m.indices[4] = 6;
  expect_rejected(m, "out of range");
  m = octahedron();
  m.positions(2, 1) = std::nan("");
  expect_rejected(m, "not finite");
  m = octahedron();
  m.normals.row(3).setZero();
  expect_rejected(m, "normal 3");
  m = octahedron();
  m.uvs.resize(0, 2);
  m.material.texture = msp::gltf::Texture{{1, 2, 3}, true, false};
  expect_rejected(m, "needs uvs");
  m = octahedron();
  m.uvs.conservativeResize(5, 2);
  expect_rejected(m, "differ in count");

  const fs::path path = temp_file("never.glb");
  fs::remove(path);
  Scene bad;
  bad.meshes.push_back(m);
  EXPECT_THROW(msp::gltf::write_glb(bad, path.string()), ricci::InvalidInputError);
  EXPECT_FALSE(fs::exists(path));
}

TEST(TexturePng, EncodesPixelsExactly) {
  msp::RgbaImage image(5, 3, {0, 0, 0, 255});
  for (int y = 0; y < 3; ++y) {
    for (int x = 0; x < 5; ++x) {
      image.set(x, y,
                {static_cast<std::uint8_t>(50 * x), static_cast<std::uint8_t>(100 * y), 7,
                 static_cast<std::uint8_t>(255 - x)});
    }
  }
  const auto png = msp::encode_png(image);
  tinygltf::Image decoded;
  std::string err, warn;
  ASSERT_TRUE(tinygltf::LoadImageData(&decoded, 0, &err, &warn, 0, 0, png.data(),
                                      static_cast<int>(png.size()), nullptr))
      << err;
  ASSERT_EQ(decoded.width, 5);
  ASSERT_EQ(decoded.height, 3);
  ASSERT_EQ(decoded.component, 4);
  EXPECT_EQ(decoded.image, image.pixels);
  EXPECT_THROW((void)msp::encode_png(msp::RgbaImage{}), ricci::InvalidInputError);
}

TEST(TexturePng, CheckerboardSquaresAlternateAndTile) {
  msp::CheckerboardOptions o;
  o.size = 256;
  o.squares = 16;
  o.major = 0;
  const msp::RgbaImage c = msp::checkerboard(o);
  for (int j = 0; j < 16; ++j) {
    for (int i = 0; i < 16; ++i) {
      const msp::Rgba expected = (i + j) % 2 == 0 ? o.dark : o.light;
      EXPECT_EQ(c.at(16 * i + 8, 16 * j + 8), expected) << i << " " << j;
    }
  }
  // Opposite edges match up to the parity of the square count: the texture tiles seamlessly.
  for (int y = 0; y < 256; ++y) EXPECT_NE(c.at(0, y), c.at(255, y));
  EXPECT_THROW((void)msp::checkerboard({100, 16}), ricci::InvalidInputError);
}

}  // namespace
