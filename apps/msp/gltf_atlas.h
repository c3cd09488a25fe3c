#pragma once
// The atlas as texture coordinates (issue 4): the (valence-modified) mesh split along the cut,
// each corner carrying its position in the central chart, with a checkerboard texture: where
// the flat metric is conformal to the surface the squares stay square. Written as .glb (with the
// cut loops as coloured lines and the cone as a point) or as .obj + .mtl + .png.
#include <cstdint>
#include <string>
#include <vector>

#include <ricci/pipeline/one_cone_atlas.h>
#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "msp/io/gltf_writer.h"
#include "msp/io/texture_image.h"

namespace msp {

/// One vertex per vertex of the sliced mesh (a seam vertex has one copy per wedge of faces).
struct AtlasTexturedMesh {
  Eigen::MatrixX3d positions;  ///< 3D positions of the problem mesh.
  Eigen::MatrixX3d normals;    ///< Area-weighted normals of the problem mesh (no shading seam).
  /// Central-chart positions scaled by 1/side of their bounding square into [0, 1]^2, v pointing
  /// down the image (glTF convention).
  Eigen::MatrixX2d uvs;
  std::vector<std::uint32_t> triangles;  ///< 3 per face, face order of the problem mesh.
  std::vector<int> problem_vertex;       ///< By vertex: the vertex of the problem mesh.
  double uv_scale = 1.0;                 ///< uv length per unit of the flat metric.
};

/// \throw ricci::InvalidInputError if the result holds no layout.
[[nodiscard]] AtlasTexturedMesh atlas_textured_mesh(const ricci::OneConeAtlasResult& result);

struct CheckerboardExportOptions {
  CheckerboardOptions texture;
  bool cut_loops = true;   ///< Add each cut loop as a line mesh in its picture colour.
  bool cone_point = true;  ///< Add the cone as a point.
  nlohmann::json extras;   ///< Scene metadata (e.g. the atlas report).
};

/// The glTF scene: "surface" (textured, double sided), "cut loop <name>" lines, "cone" point.
[[nodiscard]] gltf::Scene checkerboard_scene(const ricci::OneConeAtlasResult& result,
                                             const CheckerboardExportOptions& options = {});

/// Writes FILE.obj with FILE.mtl and FILE_checker.png next to it (each atomically).
/// \throw ricci::IOError if a file cannot be written.
void write_checkerboard_obj(const ricci::OneConeAtlasResult& result, const std::string& obj_path,
                            const CheckerboardOptions& texture = {});

}  // namespace msp
