#pragma once
// Outputs of `msp fit`: the tessellated spline as a glTF scene (surface with atlas texture
// coordinates, optional checkerboard, control net, domain mesh, cut loops, extraordinary point,
// metadata in extras); OBJ and PLY come from msp/io/tessellation_io.h.
#include <cstdint>
#include <string>
#include <vector>

#include <spline/surface/fit_surface.h>
#include <spline/tessellate/tessellate.h>
#include <nlohmann/json.hpp>

#include "msp/io/gltf_writer.h"
#include "msp/io/tessellation_io.h"
#include "msp/io/texture_image.h"

namespace msp {

struct FitSceneOptions {
  bool checkerboard = false;  ///< Texture the surface with a checkerboard over the atlas.
  CheckerboardOptions texture;
  bool control_net = false;  ///< Lines of each domain face's control-point net.
  bool domain = false;       ///< Lines of the domain mesh's edges.
  bool cut_loops = false;    ///< The cut loops on the surface and the extraordinary point.
  nlohmann::json extras;     ///< Scene metadata.
};

/// The scene "fit": mesh "surface" (render vertices: positions, unit normals, uvs = central
/// chart scaled into [0, 1]^2), and the optional line/point meshes.
[[nodiscard]] gltf::Scene fit_scene(const spline::FittedSurface& fitted,
                                    const FitSceneOptions& options = {});

}  // namespace msp
