#include "spline/tessellate/tessellate_fill.h"

#include <cmath>
#include <string>

#include "ricci/mesh/errors.h"
#include "ricci/util/cross2d.h"

namespace spline {
namespace {

// Mean uv length per unit of surface length over the tessellation (sqrt of the area ratio).
double uv_per_length(const Tessellation& t) {
  double uv_area = 0.0, area = 0.0;
  for (std::size_t i = 0; i < t.render_triangles.size(); ++i) {
    const auto& r = t.render_triangles[i];
    const Eigen::Vector2d a = t.uvs.row(r[1]) - t.uvs.row(r[0]),
                          b = t.uvs.row(r[2]) - t.uvs.row(r[0]);
    uv_area += 0.5 * std::abs(ricci::cross2d(a, b));
    const auto& p = t.triangles[i];
    const Eigen::Vector3d e = t.positions.row(p[1]) - t.positions.row(p[0]),
                          f = t.positions.row(p[2]) - t.positions.row(p[0]);
    area += 0.5 * e.cross(f).norm();
  }
  return area > 0 && uv_area > 0 ? std::sqrt(uv_area / area) : 1.0;
}

}  // namespace

void append_fill(Tessellation& t, const HoleFill& fill, const PatchTessellation& patch,
                 int patch_index) {
  const int d = t.density;
  const int rim_samples = static_cast<int>(fill.rim.edges.size()) * d;
  const auto interior = static_cast<int>(patch.positions.rows());
  // Rim sample -> position index of the surface's own sample.
  auto rim_position = [&](int m) {
    const RimEdge& e = fill.rim.edges[static_cast<std::size_t>(m / d)];
    return t.edge_sample(e.face, e.corner, m % d);
  };

  // D's length per 3D length along the rim fixes the patch's uv scale.
  double rim_length = 0.0, d_length = 0.0;
  const int edges = static_cast<int>(fill.rim.edges.size());
  for (int j = 0; j < edges; ++j) {
    const Eigen::Vector3d a = t.positions.row(rim_position(j * d)),
                          b = t.positions.row(rim_position(((j + 1) % edges) * d));
    rim_length += (b - a).norm();
    d_length += (fill.corners[static_cast<std::size_t>((j + 1) % edges)] -
                 fill.corners[static_cast<std::size_t>(j)])
                    .norm();
  }
  const double scale = uv_per_length(t) * (d_length > 0 ? rim_length / d_length : 1.0);
  auto uv_of = [&](const Eigen::Vector2d& u) -> Eigen::Vector2d {
    return (u - fill.center) * scale;
  };

  const auto base = static_cast<int>(t.positions.rows());
  const auto render_base = static_cast<int>(t.uvs.rows());
  t.positions.conservativeResize(base + interior, 3);
  t.normals.conservativeResize(base + interior, 3);
  t.uvs.conservativeResize(render_base + interior + rim_samples, 2);
  for (int i = 0; i < interior; ++i) {
    t.positions.row(base + i) = patch.positions.row(i);
    t.normals.row(base + i) = patch.normals.row(i);
    t.parameters.push_back({-1 - patch_index, Eigen::Vector3d::Zero()});
    t.render_position.push_back(base + i);
    t.uvs.row(render_base + i) = uv_of(patch.parameters.row(i).transpose()).transpose();
  }
  for (int m = 0; m < rim_samples; ++m) {
    t.render_position.push_back(rim_position(m));
    t.uvs.row(render_base + interior + m) =
        uv_of(fill.parameter(m / d, double(m % d) / d)).transpose();
  }
  for (Eigen::Index r = 0; r < patch.triangles.rows(); ++r) {
    std::array<int, 3> position{}, render{};
    for (int k = 0; k < 3; ++k) {
      const int i = patch.triangles(r, k);
      if (i >= interior || -(1 + i) >= rim_samples) {
        throw ricci::InvalidInputError("append_fill: patch vertex " + std::to_string(i) +
                                       " is out of range (density " + std::to_string(d) + "?)");
      }
      position[k] = i >= 0 ? base + i : rim_position(-(1 + i));
      render[k] = i >= 0 ? render_base + i : render_base + interior - (1 + i);
    }
    t.triangles.push_back(position);
    t.render_triangles.push_back(render);
    t.triangle_face.push_back(-1 - patch_index);
  }
}

}  // namespace spline
