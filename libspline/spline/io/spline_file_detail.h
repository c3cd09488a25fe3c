#pragma once
// Internal to the spline file: the codecs of its sections (docs/spline-file.md).
#include <array>
#include <string>
#include <vector>

#include "ricci/atlas/atlas.h"
#include "ricci/mesh/mesh.h"
#include "spline/basis/planar_space.h"
#include "spline/fill/hole_fill.h"
#include "spline/io/byte_stream.h"
#include "spline/manifold/manifold_space.h"

namespace spline::io_detail {

/// By face, the vertex of each corner (corner order of ricci::face_halfedges).
using FaceCorners = std::vector<std::array<int, 3>>;
[[nodiscard]] FaceCorners face_corners(const ricci::Mesh& mesh);

/// Section ATLS: the atlas fields the spline space reads. Decoding checks them against the mesh
/// (indices in range, charts' corners on the faces' vertices, finite positions and motions).
void write_atlas(ByteWriter& out, const ricci::AffineAtlas& atlas);
[[nodiscard]] ricci::AffineAtlas read_atlas(ByteReader& in, const FaceCorners& corners,
                                            int vertex_count);

/// Knot clouds: a knot count then the knots.
void write_clouds(ByteWriter& out, const std::vector<KnotCloud>& clouds);
[[nodiscard]] std::vector<KnotCloud> read_clouds(ByteReader& in);

/// A control-point matrix (rows, then x y z per row).
void write_points(ByteWriter& out, const Eigen::MatrixX3d& points);
/// Refused unless every coordinate is finite and there are `expected_rows` rows; `what` is the
/// singular noun of messages ("control point").
[[nodiscard]] Eigen::MatrixX3d read_points(ByteReader& in, Eigen::Index expected_rows,
                                           const std::string& what);

/// A rim; decoding checks its faces are the space's domain faces and its edges chained.
void write_rim(ByteWriter& out, const Rim& rim);
[[nodiscard]] Rim read_rim(ByteReader& in, const FaceCorners& corners,
                           const ManifoldSplineSpace& space, const std::string& what);

/// A fill with its patch space; decoding rebuilds the PlanarDmsSpace from the stored
/// triangulation and clouds and checks every size and number.
void write_fill(ByteWriter& out, const HoleFill& fill);
[[nodiscard]] HoleFill read_fill(ByteReader& in, const FaceCorners& corners,
                                 const ManifoldSplineSpace& space, const std::string& what);

}  // namespace spline::io_detail
