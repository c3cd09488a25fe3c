#include "msp/io/gltf_reader.h"

#include <cstring>
#include <map>

#include <ricci/mesh/errors.h>
#include <tiny_gltf.h>

namespace msp::gltf {
namespace {

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw ricci::IOError(path + ": " + what);
}

// The bytes of element i of an accessor, checked against its buffer.
const unsigned char* element(const tinygltf::Model& model, const tinygltf::Accessor& accessor,
                             std::size_t i, std::size_t size, const std::string& path) {
  if (accessor.bufferView < 0 ||
      accessor.bufferView >= static_cast<int>(model.bufferViews.size())) {
    fail(path, "accessor without a valid buffer view");
  }
  const auto& view = model.bufferViews[static_cast<std::size_t>(accessor.bufferView)];
  if (view.buffer < 0 || view.buffer >= static_cast<int>(model.buffers.size())) {
    fail(path, "buffer view without a valid buffer");
  }
  const auto& buffer = model.buffers[static_cast<std::size_t>(view.buffer)].data;
  const std::size_t stride = view.byteStride ? view.byteStride : size;
  const std::size_t offset = view.byteOffset + accessor.byteOffset + i * stride;
  if (offset + size > buffer.size() || accessor.byteOffset + i * stride + size > view.byteLength) {
    fail(path, "accessor reads past its buffer");
  }
  return buffer.data() + offset;
}

std::vector<Eigen::Vector3f> read_positions(const tinygltf::Model& model, int index,
                                            const std::string& path) {
  if (index < 0 || index >= static_cast<int>(model.accessors.size())) {
    fail(path, "POSITION accessor out of range");
  }
  const auto& accessor = model.accessors[static_cast<std::size_t>(index)];
  if (accessor.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT ||
      accessor.type != TINYGLTF_TYPE_VEC3) {
    fail(path, "POSITION is not a float VEC3 accessor");
  }
  std::vector<Eigen::Vector3f> out(accessor.count);
  for (std::size_t i = 0; i < accessor.count; ++i) {
    std::memcpy(out[i].data(), element(model, accessor, i, 12, path), 12);
  }
  return out;
}

std::vector<int> read_indices(const tinygltf::Model& model, int index, std::size_t vertices,
                              const std::string& path) {
  std::vector<int> out;
  if (index < 0) {  // non-indexed: consecutive vertices
    for (std::size_t i = 0; i < vertices; ++i) out.push_back(static_cast<int>(i));
    return out;
  }
  if (index >= static_cast<int>(model.accessors.size())) fail(path, "index accessor out of range");
  const auto& accessor = model.accessors[static_cast<std::size_t>(index)];
  std::size_t size = 0;
  switch (accessor.componentType) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: size = 1; break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: size = 2; break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: size = 4; break;
    default: fail(path, "indices of an unsupported component type");
  }
  for (std::size_t i = 0; i < accessor.count; ++i) {
    std::uint32_t value = 0;
    std::memcpy(&value, element(model, accessor, i, size, path), size);  // little endian
    if (value >= vertices) fail(path, "vertex index out of range");
    out.push_back(static_cast<int>(value));
  }
  return out;
}

}  // namespace

TriangleSurface read_glb_triangles(const std::string& path, const std::string& mesh_name) {
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string error, warning;
  if (!loader.LoadBinaryFromFile(&model, &error, &warning, path)) {
    fail(path, "not a readable glTF binary" + (error.empty() ? "" : " (" + error + ")"));
  }
  TriangleSurface surface;
  std::map<std::array<float, 3>, int> welded;
  std::vector<Eigen::Vector3d> positions;
  bool found = false;
  for (const auto& mesh : model.meshes) {
    if (!mesh_name.empty() && mesh.name != mesh_name) continue;
    for (const auto& primitive : mesh.primitives) {
      if (primitive.mode != TINYGLTF_MODE_TRIANGLES && primitive.mode != -1) continue;
      const auto position = primitive.attributes.find("POSITION");
      if (position == primitive.attributes.end()) fail(path, "primitive without POSITION");
      const auto vertices = read_positions(model, position->second, path);
      const auto indices = read_indices(model, primitive.indices, vertices.size(), path);
      if (indices.size() % 3 != 0) fail(path, "index count is not a multiple of 3");
      std::vector<int> weld(vertices.size());
      for (std::size_t v = 0; v < vertices.size(); ++v) {
        const std::array<float, 3> key{vertices[v].x(), vertices[v].y(), vertices[v].z()};
        const auto [it, inserted] = welded.emplace(key, static_cast<int>(positions.size()));
        if (inserted) positions.push_back(vertices[v].cast<double>());
        weld[v] = it->second;
      }
      for (std::size_t i = 0; i < indices.size(); i += 3) {
        surface.triangles.push_back({weld[static_cast<std::size_t>(indices[i])],
                                     weld[static_cast<std::size_t>(indices[i + 1])],
                                     weld[static_cast<std::size_t>(indices[i + 2])]});
      }
      surface.render_vertices += static_cast<int>(vertices.size());
      found = true;
    }
  }
  if (!found) {
    fail(path, mesh_name.empty() ? "no triangle mesh" : "no triangle mesh '" + mesh_name + "'");
  }
  surface.positions.resize(static_cast<Eigen::Index>(positions.size()), 3);
  for (std::size_t i = 0; i < positions.size(); ++i) {
    surface.positions.row(static_cast<Eigen::Index>(i)) = positions[i].transpose();
  }
  return surface;
}

}  // namespace msp::gltf
