#pragma once
// A spline's tessellation (spline/tessellate/tessellate.h) as files: a glTF mesh for the .glb
// writer (gltf_writer.h), Wavefront OBJ text and binary PLY, or any of them by file name.
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <spline/tessellate/tessellate.h>

#include "msp/io/gltf_writer.h"

namespace msp {

/// #positions by 3 unit normals: the tessellation's own, and where one is zero (a singular
/// parametrisation) the area-weighted normal of its triangles instead.
[[nodiscard]] Eigen::MatrixX3d tessellation_normals(const spline::Tessellation& t);

/// The tessellation as a triangle mesh of render vertices: positions, unit normals, uvs (the
/// central chart scaled into the unit square, v pointing down the image), a single-sided
/// material of a neutral colour, and extras {uv, uv_per_metric_unit, density}.
[[nodiscard]] gltf::Mesh tessellation_gltf_mesh(const spline::Tessellation& t,
                                                const std::string& name = "surface");

/// Wavefront OBJ text: v/vn by position index (welded), vt by render vertex, faces v/vt/vn.
[[nodiscard]] std::string tessellation_obj(const spline::Tessellation& t);

/// Binary little-endian PLY: welded vertices (double x y z, float nx ny nz), triangles.
[[nodiscard]] std::vector<std::uint8_t> tessellation_ply(const spline::Tessellation& t);

/// Writes the tessellation atomically as .glb (a scene of one mesh "surface"), .obj or .ply,
/// chosen by the extension of `path`.
/// \throw ricci::InvalidInputError for another extension or an empty tessellation;
///        ricci::IOError if the file cannot be written.
void write_tessellation(const spline::Tessellation& t, const std::string& path);

}  // namespace msp
