#pragma once
// A small glTF 2.0 binary (.glb) writer over tinygltf: a scene of named meshes (triangles, lines
// or points), each with one material and an optional PNG texture, plus JSON metadata (`extras`).
// The file passes the Khronos glTF-Validator with no errors and no warnings: one buffer (the
// GLB BIN chunk), 4-byte-aligned buffer views, POSITION min/max, unit normals, PNG bytes in the
// buffer referenced by image.bufferView.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

namespace msp::gltf {

enum class Topology {
  triangles,  ///< indices: 3 per triangle, counter-clockwise seen from the front.
  lines,      ///< indices: 2 per segment (cut loops, control nets).
  points,     ///< indices: optional; empty draws every vertex (extraordinary points).
};

struct Texture {
  std::vector<std::uint8_t> png;  ///< The encoded PNG file (e.g. msp::encode_png).
  bool repeat = true;             ///< Wrap mode REPEAT (else CLAMP_TO_EDGE) on both axes.
  bool nearest = false;           ///< NEAREST magnification (crisp checker squares when near).
};

struct Material {
  std::string name;
  std::array<double, 4> base_color = {1.0, 1.0, 1.0, 1.0};  ///< Linear RGBA factors in [0, 1].
  double metallic = 0.0;
  double roughness = 0.9;
  bool double_sided = false;
  std::optional<Texture> texture;  ///< baseColorTexture; needs the mesh's uvs.
};

/// One glTF mesh with one primitive, instanced by one node of the same name.
struct Mesh {
  std::string name;
  Topology topology = Topology::triangles;
  Eigen::MatrixX3d positions;  ///< #V by 3 (stored as float).
  Eigen::MatrixX3d normals;    ///< Empty, or #V by 3 (normalised on output; zero rows refused).
  Eigen::MatrixX2d uvs;        ///< Empty, or #V by 2 texture coordinates (TEXCOORD_0).
  std::vector<std::uint32_t> indices;
  Material material;
  nlohmann::json extras;  ///< Copied to the mesh's `extras` when not null.
};

struct Scene {
  std::string name = "scene";
  std::vector<Mesh> meshes;
  nlohmann::json extras;  ///< Copied to the scene's and the asset's `extras` when not null.
  std::string generator = "msp (Manifold Splines)";
};

/// Checks `scene`: positions finite and non-empty, attribute row counts equal, index counts a
/// multiple of 3 (triangles) or 2 (lines), indices in range, normals non-zero, a texture only
/// with uvs and non-empty PNG bytes.
/// \throw ricci::InvalidInputError naming the mesh and the problem.
void check_scene(const Scene& scene);

/// Writes `scene` as a binary glTF, atomically (temporary file renamed into place).
/// \throw ricci::InvalidInputError (see check_scene); ricci::IOError if the file cannot be written.
void write_glb(const Scene& scene, const std::string& path);

/// The same file as bytes (for tests and streaming).
[[nodiscard]] std::vector<std::uint8_t> glb_bytes(const Scene& scene);

/// An opaque colour given as 8-bit sRGB, as linear RGBA factors (what base_color holds).
[[nodiscard]] std::array<double, 4> linear_colour(std::array<int, 3> srgb);

}  // namespace msp::gltf
