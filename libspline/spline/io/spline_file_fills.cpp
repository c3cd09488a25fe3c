// The spline file's rims and fills (spline_file_detail.h).
#include <cmath>
#include <limits>
#include <memory>
#include <string>

#include "spline/io/spline_file_detail.h"

namespace spline::io_detail {
namespace {

std::string str(std::size_t value) { return std::to_string(value); }

Eigen::Vector2d read_vec2(ByteReader& in, const std::string& what) {
  const Eigen::Vector2d v = in.vec2();
  if (!v.allFinite()) in.invalid(what + " is not finite");
  return v;
}

Eigen::Vector3d read_vec3(ByteReader& in, const std::string& what) {
  const Eigen::Vector3d v = in.vec3();
  if (!v.allFinite()) in.invalid(what + " is not finite");
  return v;
}

void write_curve(ByteWriter& out, const std::vector<std::vector<Eigen::Vector2d>>& curve) {
  out.count(curve.size());
  for (const auto& points : curve) {
    out.count(points.size());
    for (const Eigen::Vector2d& p : points) out.vec2(p);
  }
}

// One list of at least two finite points per rim edge.
std::vector<std::vector<Eigen::Vector2d>> read_curve(ByteReader& in, std::size_t edges,
                                                     const std::string& what) {
  std::vector<std::vector<Eigen::Vector2d>> curve(in.count(8, what + " lists"));
  if (curve.size() != edges) {
    in.fail("inconsistent counts: " + str(curve.size()) + " " + what + " lists for " + str(edges) +
            " rim edges");
  }
  for (std::size_t j = 0; j < curve.size(); ++j) {
    curve[j].resize(in.count(16, what));
    if (curve[j].size() < 2) in.invalid(what + " of rim edge " + str(j) + " has fewer than 2");
    for (Eigen::Vector2d& p : curve[j]) p = read_vec2(in, what + " of rim edge " + str(j));
  }
  return curve;
}

// The patch's clouds must keep the bound that guarantees the DMS conditions (knot_cloud.h):
// every knot closer to its vertex than half the smallest inradius of the vertex's triangles.
void check_cloud_radii(ByteReader& in, const PlanarTriangulation& triangulation,
                       const std::vector<KnotCloud>& clouds, const std::string& what) {
  std::vector<double> smallest(triangulation.positions.size(),
                               std::numeric_limits<double>::infinity());
  for (const Eigen::Vector3i& t : triangulation.triangles) {
    const double r = inradius(triangulation.positions[t[0]], triangulation.positions[t[1]],
                              triangulation.positions[t[2]]);
    for (int k = 0; k < 3; ++k) smallest[t[k]] = std::min(smallest[t[k]], r);
  }
  for (std::size_t v = 0; v < clouds.size(); ++v) {
    if (!std::isfinite(smallest[v])) continue;  // in no triangle: carries no function
    for (const Eigen::Vector2d& knot : clouds[v].knots) {
      if (!((knot - triangulation.positions[v]).norm() < 0.5 * smallest[v])) {
        in.invalid(what + " knot cloud " + str(v) +
                   " has a knot farther than half the smallest inradius");
      }
    }
  }
}

std::shared_ptr<const PlanarDmsSpace> read_patch_space(ByteReader& in, const std::string& what) {
  PlanarTriangulation triangulation;
  triangulation.positions.resize(in.count(16, what + " vertices"));
  for (Eigen::Vector2d& p : triangulation.positions) p = read_vec2(in, what + " vertex");
  triangulation.triangles.resize(in.count(12, what + " triangles"));
  for (Eigen::Vector3i& t : triangulation.triangles) {
    for (int k = 0; k < 3; ++k) t[k] = in.i32();
  }
  std::vector<KnotCloud> clouds = read_clouds(in);
  if (clouds.size() != triangulation.positions.size()) {
    in.fail("inconsistent counts: " + str(clouds.size()) + " " + what + " knot clouds for " +
            str(triangulation.positions.size()) + " vertices");
  }
  try {
    validate(triangulation);
  } catch (const ricci::InvalidInputError& e) {
    in.invalid(what + ": " + e.what());
  }
  check_cloud_radii(in, triangulation, clouds, what);
  try {
    return std::make_shared<const PlanarDmsSpace>(std::move(triangulation), std::move(clouds));
  } catch (const ricci::InvalidInputError& e) {
    in.invalid(what + ": " + e.what());
  }
}

}  // namespace

void write_rim(ByteWriter& out, const Rim& rim) {
  out.u8(static_cast<std::uint8_t>(rim.kind));
  out.count(rim.edges.size());
  for (const RimEdge& e : rim.edges) {
    out.i32(e.face);
    out.i32(e.corner);
  }
  out.count(rim.covered_faces.size());
  for (int f : rim.covered_faces) out.i32(f);
}

Rim read_rim(ByteReader& in, const FaceCorners& corners, const ManifoldSplineSpace& space,
             const std::string& what) {
  Rim rim;
  const std::uint8_t kind = in.u8();
  if (kind > static_cast<std::uint8_t>(Rim::Kind::excluded)) {
    in.invalid(what + " has an unknown kind " + std::to_string(kind));
  }
  rim.kind = static_cast<Rim::Kind>(kind);
  rim.edges.resize(in.count(8, what + " edges"));
  if (rim.edges.size() < 3) in.invalid(what + " has fewer than 3 edges");
  const int faces = static_cast<int>(corners.size());
  for (std::size_t j = 0; j < rim.edges.size(); ++j) {
    RimEdge& e = rim.edges[j];
    e.face = in.i32();
    e.corner = in.i32();
    if (e.face < 0 || e.face >= faces || !space.in_domain(e.face) || e.corner < 0 || e.corner > 2) {
      in.invalid(what + " edge " + str(j) + " (face " + std::to_string(e.face) + ", corner " +
                 std::to_string(e.corner) + ") is not a corner of a spline domain face");
    }
  }
  for (std::size_t j = 0; j < rim.edges.size(); ++j) {
    const RimEdge& a = rim.edges[j];
    const RimEdge& b = rim.edges[(j + 1) % rim.edges.size()];
    if (corners[a.face][rim_edge_end_corner(a)] != corners[b.face][rim_edge_start_corner(b)]) {
      in.invalid(what + " edge " + str(j) + " does not end where the next one starts");
    }
  }
  rim.covered_faces.resize(in.count(4, what + " covered faces"));
  for (std::size_t i = 0; i < rim.covered_faces.size(); ++i) {
    const int f = in.i32();
    if (f < 0 || f >= faces || (i > 0 && f <= rim.covered_faces[i - 1])) {
      in.invalid(what + " covered face " + std::to_string(f) + " is out of range or out of order");
    }
    rim.covered_faces[i] = f;
  }
  return rim;
}

void write_fill(ByteWriter& out, const HoleFill& fill) {
  if (!fill.space) throw ricci::InvalidInputError("spline file: a fill has no patch space");
  write_rim(out, fill.rim);
  const PlanarTriangulation& triangulation = fill.space->triangulation();
  out.count(triangulation.positions.size());
  for (const Eigen::Vector2d& p : triangulation.positions) out.vec2(p);
  out.count(triangulation.triangles.size());
  for (const Eigen::Vector3i& t : triangulation.triangles) {
    for (int k = 0; k < 3; ++k) out.i32(t[k]);
  }
  write_clouds(out, fill.space->clouds());
  write_points(out, fill.control_points);
  out.vec3(fill.origin);
  out.vec3(fill.normal);
  out.vec3(fill.axes.col(0));
  out.vec3(fill.axes.col(1));
  write_curve(out, fill.boundary_points);
  write_curve(out, fill.boundary_tangents);
  out.count(fill.corners.size());
  for (const Eigen::Vector2d& c : fill.corners) out.vec2(c);
  out.vec2(fill.center);
  out.f64(fill.diagonal);
  out.u8(fill.g1 ? 1 : 0);
  out.text(fill.fallback_reason);
  out.f64(fill.max_normal_jump_deg);
  out.f64(fill.max_position_gap);
  out.f64(fill.rms_position_gap);
  out.i32(fill.seam_samples);
}

HoleFill read_fill(ByteReader& in, const FaceCorners& corners, const ManifoldSplineSpace& space,
                   const std::string& what) {
  HoleFill fill;
  fill.rim = read_rim(in, corners, space, what + " rim");
  fill.space = read_patch_space(in, what + " patch");
  fill.control_points = read_points(in, fill.space->function_count(), what + " control point");
  fill.origin = read_vec3(in, what + " origin");
  fill.normal = read_vec3(in, what + " normal");
  fill.axes.col(0) = read_vec3(in, what + " axis");
  fill.axes.col(1) = read_vec3(in, what + " axis");
  const std::size_t edges = fill.rim.edges.size();
  fill.boundary_points = read_curve(in, edges, what + " boundary points");
  fill.boundary_tangents = read_curve(in, edges, what + " boundary tangents");
  for (std::size_t j = 0; j < edges; ++j) {
    if (fill.boundary_points[j].size() != fill.boundary_tangents[j].size()) {
      in.fail("inconsistent counts: " + what + " rim edge " + str(j) +
              " has unequal numbers of boundary points and tangents");
    }
  }
  fill.corners.resize(in.count(16, what + " corners"));
  if (fill.corners.size() != edges) {
    in.fail("inconsistent counts: " + str(fill.corners.size()) + " " + what + " corners for " +
            str(edges) + " rim edges");
  }
  for (Eigen::Vector2d& c : fill.corners) c = read_vec2(in, what + " corner");
  fill.center = read_vec2(in, what + " centre");
  fill.diagonal = in.f64();
  if (!(std::isfinite(fill.diagonal) && fill.diagonal > 0.0)) {
    in.invalid(what + " diagonal is not a positive number");
  }
  const std::uint8_t g1 = in.u8();
  if (g1 > 1) in.invalid(what + " g1 flag is " + std::to_string(g1));
  fill.g1 = g1 != 0;
  fill.fallback_reason = in.text(what + " fallback reason bytes");
  fill.max_normal_jump_deg = in.f64();
  fill.max_position_gap = in.f64();
  fill.rms_position_gap = in.f64();
  fill.seam_samples = in.i32();
  return fill;
}

}  // namespace spline::io_detail
