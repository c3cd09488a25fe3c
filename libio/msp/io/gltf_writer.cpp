// glTF 2.0 binary writer (Khronos glTF 2.0 specification, sections 3.6 buffers/accessors,
// 3.7 meshes, 3.9 materials, 4.4 GLB). tinygltf serialises; this file lays the data out.
#include "msp/io/gltf_writer.h"

#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>

#include <ricci/mesh/errors.h>
#include <tiny_gltf.h>

#include "msp/io/atomic_file.h"

namespace msp::gltf {
namespace {

constexpr int kArrayBuffer = 34962;         // GL ARRAY_BUFFER
constexpr int kElementArrayBuffer = 34963;  // GL ELEMENT_ARRAY_BUFFER

[[noreturn]] void fail(const Mesh& mesh, const std::string& what) {
  throw ricci::InvalidInputError("glTF mesh '" + mesh.name + "': " + what);
}

tinygltf::Value to_value(const nlohmann::json& j) {
  switch (j.type()) {
    case nlohmann::json::value_t::boolean:
      return tinygltf::Value(j.get<bool>());
    case nlohmann::json::value_t::number_integer:
    case nlohmann::json::value_t::number_unsigned: {
      // tinygltf holds int; larger integers keep their value as a double.
      const double d = j.get<double>();
      if (d >= std::numeric_limits<int>::min() && d <= std::numeric_limits<int>::max()) {
        return tinygltf::Value(j.get<int>());
      }
      return tinygltf::Value(d);
    }
    case nlohmann::json::value_t::number_float: {
      const double d = j.get<double>();
      // JSON has no NaN or infinity: write null rather than an invalid file.
      return std::isfinite(d) ? tinygltf::Value(d) : tinygltf::Value();
    }
    case nlohmann::json::value_t::string:
      return tinygltf::Value(j.get<std::string>());
    case nlohmann::json::value_t::array: {
      tinygltf::Value::Array array;
      for (const auto& item : j) array.push_back(to_value(item));
      return tinygltf::Value(std::move(array));
    }
    case nlohmann::json::value_t::object: {
      tinygltf::Value::Object object;
      for (const auto& [key, item] : j.items()) object[key] = to_value(item);
      return tinygltf::Value(std::move(object));
    }
    default:
      return tinygltf::Value();
  }
}

/// Appends views to the single buffer, each starting on a 4-byte boundary.
class BufferBuilder {
 public:
  explicit BufferBuilder(tinygltf::Model& model) : model_(model) { model_.buffers.resize(1); }

  int add_view(const void* data, size_t bytes, int target) {
    auto& buffer = model_.buffers[0].data;
    buffer.resize((buffer.size() + 3) / 4 * 4, 0);
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = buffer.size();
    view.byteLength = bytes;
    view.target = target;
    const auto* p = static_cast<const unsigned char*>(data);
    buffer.insert(buffer.end(), p, p + bytes);
    model_.bufferViews.push_back(view);
    return static_cast<int>(model_.bufferViews.size() - 1);
  }

  /// A float accessor of `columns` components per row (VEC2/VEC3), with min/max when asked.
  int add_floats(const std::vector<float>& values, int columns, bool with_bounds) {
    const int view = add_view(values.data(), values.size() * sizeof(float), kArrayBuffer);
    tinygltf::Accessor a;
    a.bufferView = view;
    a.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
    a.count = values.size() / static_cast<size_t>(columns);
    a.type = columns == 2 ? TINYGLTF_TYPE_VEC2 : TINYGLTF_TYPE_VEC3;
    if (with_bounds) {
      a.minValues.assign(static_cast<size_t>(columns), std::numeric_limits<double>::infinity());
      a.maxValues.assign(static_cast<size_t>(columns), -std::numeric_limits<double>::infinity());
      for (size_t i = 0; i < values.size(); ++i) {
        const size_t c = i % static_cast<size_t>(columns);
        a.minValues[c] = std::min(a.minValues[c], static_cast<double>(values[i]));
        a.maxValues[c] = std::max(a.maxValues[c], static_cast<double>(values[i]));
      }
    }
    model_.accessors.push_back(a);
    return static_cast<int>(model_.accessors.size() - 1);
  }

  int add_indices(const std::vector<std::uint32_t>& indices) {
    const int view =
        add_view(indices.data(), indices.size() * sizeof(std::uint32_t), kElementArrayBuffer);
    tinygltf::Accessor a;
    a.bufferView = view;
    a.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    a.count = indices.size();
    a.type = TINYGLTF_TYPE_SCALAR;
    model_.accessors.push_back(a);
    return static_cast<int>(model_.accessors.size() - 1);
  }

 private:
  tinygltf::Model& model_;
};

std::vector<float> to_floats(const Eigen::MatrixXd& m) {
  std::vector<float> out(static_cast<size_t>(m.size()));
  size_t k = 0;
  for (Eigen::Index r = 0; r < m.rows(); ++r) {
    for (Eigen::Index c = 0; c < m.cols(); ++c) out[k++] = static_cast<float>(m(r, c));
  }
  return out;
}

/// Unit normals in float (the validator checks unit length of the stored floats).
std::vector<float> unit_normals(const Eigen::MatrixX3d& normals) {
  std::vector<float> out(static_cast<size_t>(normals.size()));
  for (Eigen::Index r = 0; r < normals.rows(); ++r) {
    const Eigen::Vector3d n = normals.row(r).transpose().normalized();
    for (int c = 0; c < 3; ++c) out[static_cast<size_t>(3 * r + c)] = static_cast<float>(n[c]);
  }
  return out;
}

int add_texture(tinygltf::Model& model, BufferBuilder& buffer, const Texture& texture,
                const std::string& name) {
  tinygltf::Image image;
  image.name = name;
  image.mimeType = "image/png";
  // An image view has no target (glTF 2.0 section 3.6.2.3).
  image.bufferView = buffer.add_view(texture.png.data(), texture.png.size(), 0);
  model.images.push_back(image);

  tinygltf::Sampler sampler;
  const int wrap =
      texture.repeat ? TINYGLTF_TEXTURE_WRAP_REPEAT : TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
  sampler.wrapS = wrap;
  sampler.wrapT = wrap;
  sampler.magFilter =
      texture.nearest ? TINYGLTF_TEXTURE_FILTER_NEAREST : TINYGLTF_TEXTURE_FILTER_LINEAR;
  sampler.minFilter = TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR;
  model.samplers.push_back(sampler);

  tinygltf::Texture t;
  t.source = static_cast<int>(model.images.size() - 1);
  t.sampler = static_cast<int>(model.samplers.size() - 1);
  model.textures.push_back(t);
  return static_cast<int>(model.textures.size() - 1);
}

int add_material(tinygltf::Model& model, BufferBuilder& buffer, const Mesh& mesh) {
  const Material& m = mesh.material;
  tinygltf::Material material;
  material.name = m.name.empty() ? mesh.name : m.name;
  material.pbrMetallicRoughness.baseColorFactor.assign(m.base_color.begin(), m.base_color.end());
  material.pbrMetallicRoughness.metallicFactor = m.metallic;
  material.pbrMetallicRoughness.roughnessFactor = m.roughness;
  material.doubleSided = m.double_sided;
  if (m.base_color[3] < 1.0) material.alphaMode = "BLEND";
  if (m.texture) {
    material.pbrMetallicRoughness.baseColorTexture.index =
        add_texture(model, buffer, *m.texture, material.name);
  }
  model.materials.push_back(material);
  return static_cast<int>(model.materials.size() - 1);
}

int primitive_mode(Topology t) {
  switch (t) {
    case Topology::triangles:
      return TINYGLTF_MODE_TRIANGLES;
    case Topology::lines:
      return TINYGLTF_MODE_LINE;
    case Topology::points:
      return TINYGLTF_MODE_POINTS;
  }
  return TINYGLTF_MODE_TRIANGLES;
}

void add_mesh(tinygltf::Model& model, BufferBuilder& buffer, const Mesh& mesh) {
  tinygltf::Primitive primitive;
  primitive.mode = primitive_mode(mesh.topology);
  primitive.attributes["POSITION"] = buffer.add_floats(to_floats(mesh.positions), 3, true);
  if (mesh.normals.rows() > 0)
    primitive.attributes["NORMAL"] = buffer.add_floats(unit_normals(mesh.normals), 3, false);
  if (mesh.uvs.rows() > 0)
    primitive.attributes["TEXCOORD_0"] = buffer.add_floats(to_floats(mesh.uvs), 2, false);
  if (!mesh.indices.empty()) primitive.indices = buffer.add_indices(mesh.indices);
  primitive.material = add_material(model, buffer, mesh);

  tinygltf::Mesh m;
  m.name = mesh.name;
  m.primitives.push_back(primitive);
  if (!mesh.extras.is_null()) m.extras = to_value(mesh.extras);
  model.meshes.push_back(m);

  tinygltf::Node node;
  node.name = mesh.name;
  node.mesh = static_cast<int>(model.meshes.size() - 1);
  model.nodes.push_back(node);
}

tinygltf::Model build_model(const Scene& scene) {
  check_scene(scene);
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = scene.generator;
  if (!scene.extras.is_null()) model.asset.extras = to_value(scene.extras);
  BufferBuilder buffer(model);
  tinygltf::Scene s;
  s.name = scene.name;
  for (const Mesh& mesh : scene.meshes) {
    add_mesh(model, buffer, mesh);
    s.nodes.push_back(static_cast<int>(model.nodes.size() - 1));
  }
  if (!scene.extras.is_null()) s.extras = to_value(scene.extras);
  model.scenes.push_back(s);
  model.defaultScene = 0;
  // The BIN chunk holds the buffer; glTF asks its length to be what the views need.
  if (model.buffers[0].data.empty()) model.buffers.clear();
  return model;
}

void check_mesh(const Mesh& mesh) {
  const Eigen::Index n = mesh.positions.rows();
  if (n == 0) fail(mesh, "no vertices");
  if (!mesh.positions.allFinite()) fail(mesh, "a position is not finite");
  if (mesh.normals.rows() != 0 && mesh.normals.rows() != n)
    fail(mesh, "normals and positions differ in count");
  if (mesh.uvs.rows() != 0 && mesh.uvs.rows() != n) fail(mesh, "uvs and positions differ in count");
  if (!mesh.uvs.allFinite()) fail(mesh, "a texture coordinate is not finite");
  for (Eigen::Index r = 0; r < mesh.normals.rows(); ++r) {
    const double len = mesh.normals.row(r).norm();
    if (!std::isfinite(len) || len < 1e-12)
      fail(mesh, "normal " + std::to_string(r) + " is zero or not finite");
  }
  const size_t per = mesh.topology == Topology::triangles ? 3
                     : mesh.topology == Topology::lines   ? 2
                                                          : 1;
  if (mesh.indices.size() % per != 0) {
    fail(mesh, std::to_string(mesh.indices.size()) + " indices is not a multiple of " +
                   std::to_string(per));
  }
  if (mesh.topology != Topology::points && mesh.indices.empty()) fail(mesh, "no indices");
  for (size_t i = 0; i < mesh.indices.size(); ++i) {
    if (mesh.indices[i] >= static_cast<std::uint64_t>(n)) {
      fail(mesh, "index " + std::to_string(i) + " = " + std::to_string(mesh.indices[i]) +
                     " is out of range");
    }
  }
  if (mesh.material.texture) {
    if (mesh.uvs.rows() == 0) fail(mesh, "a texture needs uvs");
    if (mesh.material.texture->png.size() < 8 || mesh.material.texture->png[0] != 0x89 ||
        mesh.material.texture->png[1] != 'P') {
      fail(mesh, "the texture is not PNG data");
    }
  }
  for (double c : mesh.material.base_color) {
    if (!(c >= 0.0 && c <= 1.0)) fail(mesh, "base colour component outside [0, 1]");
  }
}

}  // namespace

void check_scene(const Scene& scene) {
  for (const Mesh& mesh : scene.meshes) check_mesh(mesh);
}

std::vector<std::uint8_t> glb_bytes(const Scene& scene) {
  const tinygltf::Model model = build_model(scene);
  std::ostringstream stream;
  tinygltf::TinyGLTF writer;
  if (!writer.WriteGltfSceneToStream(&model, stream, false, true)) {
    throw ricci::IOError("tinygltf could not serialise the scene '" + scene.name + "'");
  }
  const std::string bytes = stream.str();
  return {bytes.begin(), bytes.end()};
}

void write_glb(const Scene& scene, const std::string& path) {
  const std::vector<std::uint8_t> bytes = glb_bytes(scene);
  write_file_atomically(path, [&](const std::string& temp) {
    std::ofstream out(temp, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()),
              static_cast<std::streamsize>(bytes.size()));
    out.close();
    if (!out) throw ricci::IOError("cannot write " + path);
  });
}

std::array<double, 4> linear_colour(std::array<int, 3> srgb) {
  std::array<double, 4> out{0, 0, 0, 1};
  for (size_t c = 0; c < 3; ++c) {
    const double s = srgb[c] / 255.0;
    out[c] = s <= 0.04045 ? s / 12.92 : std::pow((s + 0.055) / 1.055, 2.4);
  }
  return out;
}

}  // namespace msp::gltf
