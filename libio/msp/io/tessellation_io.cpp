#include "msp/io/tessellation_io.h"

#include <cmath>
#include <sstream>

#include <ricci/mesh/errors.h>

#include "msp/io/atomic_file.h"

namespace msp {
namespace {

void put(std::vector<std::uint8_t>& out, const void* data, std::size_t bytes) {
  const auto* p = static_cast<const std::uint8_t*>(data);
  out.insert(out.end(), p, p + bytes);
}

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

Eigen::MatrixX3d tessellation_normals(const spline::Tessellation& t) {
  Eigen::MatrixX3d n = t.normals;
  Eigen::MatrixX3d area = Eigen::MatrixX3d::Zero(n.rows(), 3);
  bool any_zero = false;
  for (Eigen::Index i = 0; i < n.rows(); ++i) any_zero = any_zero || !(n.row(i).norm() > 0.5);
  if (!any_zero) return n;
  for (const auto& tri : t.triangles) {
    const Eigen::RowVector3d a = t.positions.row(tri[0]), b = t.positions.row(tri[1]),
                             c = t.positions.row(tri[2]);
    const Eigen::RowVector3d cross = (b - a).cross(c - a);
    for (int v : tri) area.row(v) += cross;
  }
  for (Eigen::Index i = 0; i < n.rows(); ++i) {
    if (n.row(i).norm() > 0.5) continue;
    const double len = area.row(i).norm();
    n.row(i) = len > 0 ? Eigen::RowVector3d(area.row(i) / len) : Eigen::RowVector3d(0, 0, 1);
  }
  return n;
}

gltf::Mesh tessellation_gltf_mesh(const spline::Tessellation& t, const std::string& name) {
  const Eigen::MatrixX3d normals = tessellation_normals(t);
  gltf::Mesh surface;
  surface.name = name;
  const auto n = static_cast<Eigen::Index>(t.render_position.size());
  surface.positions.resize(n, 3);
  surface.normals.resize(n, 3);
  for (Eigen::Index i = 0; i < n; ++i) {
    surface.positions.row(i) = t.positions.row(t.render_position[static_cast<std::size_t>(i)]);
    surface.normals.row(i) = normals.row(t.render_position[static_cast<std::size_t>(i)]);
  }
  // The central chart scaled into the unit square, v pointing down the image (as msp atlas).
  double scale = 1.0;
  surface.uvs.resize(n, 2);
  if (n > 0) {
    const Eigen::RowVector2d lo = t.uvs.colwise().minCoeff(), hi = t.uvs.colwise().maxCoeff();
    const double side = (hi - lo).maxCoeff();
    scale = side > 0 && std::isfinite(side) ? 1.0 / side : 1.0;
    for (Eigen::Index i = 0; i < n; ++i) {
      surface.uvs(i, 0) = (t.uvs(i, 0) - lo.x()) * scale;
      surface.uvs(i, 1) = 1.0 - (t.uvs(i, 1) - lo.y()) * scale;
    }
  }
  surface.indices.reserve(3 * t.render_triangles.size());
  for (const auto& tri : t.render_triangles)
    for (int v : tri) surface.indices.push_back(static_cast<std::uint32_t>(v));
  surface.material.name = "spline";
  surface.material.base_color = gltf::linear_colour({196, 178, 150});
  surface.extras = {{"uv", "central chart of the affine atlas, scaled into the unit square"},
                    {"uv_per_metric_unit", scale},
                    {"density", t.density}};
  return surface;
}

std::string tessellation_obj(const spline::Tessellation& t) {
  const Eigen::MatrixX3d normals = tessellation_normals(t);
  std::ostringstream out;
  out.precision(17);
  out << "# manifold spline tessellation (Manifold Splines), density " << t.density << "\n";
  for (Eigen::Index i = 0; i < t.positions.rows(); ++i)
    out << "v " << t.positions(i, 0) << " " << t.positions(i, 1) << " " << t.positions(i, 2)
        << "\n";
  for (Eigen::Index i = 0; i < normals.rows(); ++i)
    out << "vn " << normals(i, 0) << " " << normals(i, 1) << " " << normals(i, 2) << "\n";
  for (Eigen::Index i = 0; i < t.uvs.rows(); ++i)
    out << "vt " << t.uvs(i, 0) << " " << t.uvs(i, 1) << "\n";
  for (std::size_t f = 0; f < t.triangles.size(); ++f) {
    out << "f";
    for (int k = 0; k < 3; ++k) {
      const int p = t.triangles[f][k] + 1, uv = t.render_triangles[f][k] + 1;
      out << " " << p << "/" << uv << "/" << p;
    }
    out << "\n";
  }
  return out.str();
}

std::vector<std::uint8_t> tessellation_ply(const spline::Tessellation& t) {
  static_assert(sizeof(float) == 4 && sizeof(double) == 8, "IEEE sizes");
  const Eigen::MatrixX3d normals = tessellation_normals(t);
  std::ostringstream header;
  header << "ply\nformat binary_little_endian 1.0\n"
         << "comment manifold spline tessellation (Manifold Splines)\n"
         << "element vertex " << t.positions.rows() << "\n"
         << "property double x\nproperty double y\nproperty double z\n"
         << "property float nx\nproperty float ny\nproperty float nz\n"
         << "element face " << t.triangles.size() << "\n"
         << "property list uchar int vertex_indices\nend_header\n";
  std::vector<std::uint8_t> out;
  const std::string h = header.str();
  put(out, h.data(), h.size());
  // Little-endian hosts only (x86-64, arm64): the bytes are written as they are in memory.
  for (Eigen::Index i = 0; i < t.positions.rows(); ++i) {
    for (int c = 0; c < 3; ++c) put(out, &t.positions(i, c), 8);
    for (int c = 0; c < 3; ++c) {
      const float n = static_cast<float>(normals(i, c));
      put(out, &n, 4);
    }
  }
  for (const auto& tri : t.triangles) {
    const std::uint8_t three = 3;
    put(out, &three, 1);
    for (int v : tri) {
      const std::int32_t index = v;
      put(out, &index, 4);
    }
  }
  return out;
}

void write_tessellation(const spline::Tessellation& t, const std::string& path) {
  if (t.triangles.empty())
    throw ricci::InvalidInputError("cannot write " + path + ": no triangles");
  if (ends_with(path, ".glb")) {
    gltf::Scene scene;
    scene.name = "tessellation";
    scene.meshes.push_back(tessellation_gltf_mesh(t));
    gltf::write_glb(scene, path);
  } else if (ends_with(path, ".obj")) {
    write_text_atomically(path, tessellation_obj(t));
  } else if (ends_with(path, ".ply")) {
    write_bytes_atomically(path, tessellation_ply(t));
  } else {
    throw ricci::InvalidInputError("cannot write " + path +
                                   ": the name must end in .glb, .obj or .ply");
  }
}

}  // namespace msp
