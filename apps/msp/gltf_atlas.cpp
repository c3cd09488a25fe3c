#include "msp/gltf_atlas.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include <ricci/mesh/errors.h>

#include "msp/cli.h"
#include "msp/svg_cover.h"

namespace msp {
namespace {

Eigen::MatrixX3d vertex_normals(const ricci::Mesh& mesh) {
  Eigen::MatrixX3d n = Eigen::MatrixX3d::Zero(static_cast<Eigen::Index>(mesh.n_vertices()), 3);
  for (auto f : mesh.faces()) {
    Eigen::Vector3d p[3];
    int k = 0;
    for (auto v : mesh.fv_range(f)) p[k++] = ricci::to_eigen(mesh.point(v));
    // The cross product's length is twice the area: area weighting for free.
    const Eigen::Vector3d cross = (p[1] - p[0]).cross(p[2] - p[0]);
    for (auto v : mesh.fv_range(f)) n.row(v.idx()) += cross.transpose();
  }
  for (Eigen::Index i = 0; i < n.rows(); ++i) {
    const double len = n.row(i).norm();
    if (len > 0 && std::isfinite(len)) {
      n.row(i) /= len;
    } else {
      n.row(i) << 0, 0, 1;
    }
  }
  return n;
}

double bounding_diagonal(const Eigen::MatrixX3d& p) {
  return (p.colwise().maxCoeff() - p.colwise().minCoeff()).norm();
}

gltf::Mesh loop_lines(const ricci::OneConeAtlasResult& result, size_t loop, const std::string& name,
                      const Eigen::MatrixX3d& normals, double lift) {
  const ricci::Mesh& mesh = result.problem.mesh;
  gltf::Mesh lines;
  lines.name = "cut loop " + name;
  lines.topology = gltf::Topology::lines;
  const auto& halfedges = result.atlas.cut.loops[loop].halfedges;
  lines.positions.resize(static_cast<Eigen::Index>(2 * halfedges.size()), 3);
  for (size_t i = 0; i < halfedges.size(); ++i) {
    const auto h = halfedges[i];
    const int a = mesh.from_vertex_handle(h).idx(), b = mesh.to_vertex_handle(h).idx();
    // Lifted off the surface along the normal so the lines are not buried in it.
    lines.positions.row(static_cast<Eigen::Index>(2 * i)) =
        ricci::to_eigen(mesh.point(mesh.vertex_handle(a))).transpose() + lift * normals.row(a);
    lines.positions.row(static_cast<Eigen::Index>(2 * i + 1)) =
        ricci::to_eigen(mesh.point(mesh.vertex_handle(b))).transpose() + lift * normals.row(b);
    lines.indices.push_back(static_cast<std::uint32_t>(2 * i));
    lines.indices.push_back(static_cast<std::uint32_t>(2 * i + 1));
  }
  lines.material.name = lines.name;
  lines.material.base_color = gltf::linear_colour(loop_colour_rgb(static_cast<int>(loop)));
  lines.extras = {{"loop", loop}, {"name", name}};
  return lines;
}

}  // namespace

AtlasTexturedMesh atlas_textured_mesh(const ricci::OneConeAtlasResult& result) {
  const ricci::AffineAtlas& atlas = result.atlas;
  const ricci::Mesh& sliced = atlas.sliced.mesh;
  const Eigen::MatrixX2d& x = atlas.layout.positions;
  if (x.rows() == 0 || x.rows() != static_cast<Eigen::Index>(sliced.n_vertices())) {
    throw ricci::InvalidInputError("atlas texture: the result has no layout of the sliced mesh");
  }
  const Eigen::MatrixX3d problem_normals = vertex_normals(result.problem.mesh);
  AtlasTexturedMesh out;
  const auto n = static_cast<Eigen::Index>(sliced.n_vertices());
  out.positions.resize(n, 3);
  out.normals.resize(n, 3);
  out.problem_vertex.resize(static_cast<size_t>(n));
  for (Eigen::Index v = 0; v < n; ++v) {
    const int original = atlas.sliced.to_original_vertex[static_cast<size_t>(v)];
    out.problem_vertex[static_cast<size_t>(v)] = original;
    out.positions.row(v) =
        ricci::to_eigen(sliced.point(sliced.vertex_handle(static_cast<int>(v)))).transpose();
    out.normals.row(v) = problem_normals.row(original);
  }
  const Eigen::RowVector2d lo = x.colwise().minCoeff(), hi = x.colwise().maxCoeff();
  const double side = (hi - lo).maxCoeff();
  if (!(side > 0) || !std::isfinite(side))
    throw ricci::InvalidInputError("atlas texture: the layout is degenerate");
  out.uv_scale = 1.0 / side;
  out.uvs.resize(n, 2);
  for (Eigen::Index v = 0; v < n; ++v) {
    out.uvs(v, 0) = (x(v, 0) - lo.x()) * out.uv_scale;
    out.uvs(v, 1) = 1.0 - (x(v, 1) - lo.y()) * out.uv_scale;
  }
  out.triangles.reserve(3 * sliced.n_faces());
  for (auto f : sliced.faces()) {
    for (auto v : sliced.fv_range(f)) out.triangles.push_back(static_cast<std::uint32_t>(v.idx()));
  }
  return out;
}

gltf::Scene checkerboard_scene(const ricci::OneConeAtlasResult& result,
                               const CheckerboardExportOptions& options) {
  const AtlasTexturedMesh textured = atlas_textured_mesh(result);
  gltf::Scene scene;
  scene.name = "atlas checkerboard";
  scene.extras = options.extras;

  gltf::Mesh surface;
  surface.name = "surface";
  surface.positions = textured.positions;
  surface.normals = textured.normals;
  surface.uvs = textured.uvs;
  surface.indices = textured.triangles;
  surface.material.name = "checkerboard";
  surface.material.double_sided = true;
  surface.material.texture = gltf::Texture{encode_png(checkerboard(options.texture)), true, false};
  surface.extras = {{"uv", "central chart of the affine atlas, scaled into the unit square"},
                    {"uv_per_metric_unit", textured.uv_scale}};
  scene.meshes.push_back(std::move(surface));

  const ricci::Mesh& mesh = result.problem.mesh;
  const Eigen::MatrixX3d normals = vertex_normals(mesh);
  const double lift = 2e-3 * bounding_diagonal(textured.positions);
  if (options.cut_loops) {
    const auto names = loop_names(result.atlas);
    for (size_t i = 0; i < result.atlas.cut.loops.size(); ++i) {
      if (!result.atlas.cut.loops[i].halfedges.empty())
        scene.meshes.push_back(loop_lines(result, i, names[i], normals, lift));
    }
  }
  if (options.cone_point && result.problem.cone >= 0) {
    gltf::Mesh cone;
    cone.name = "cone";
    cone.topology = gltf::Topology::points;
    const int c = result.problem.cone;
    cone.positions =
        (ricci::to_eigen(mesh.point(mesh.vertex_handle(c))) + lift * normals.row(c).transpose())
            .transpose();
    cone.material.base_color = {0.0, 0.0, 0.0, 1.0};
    const double angle = 2 * M_PI - result.flow.curvature[c];
    cone.extras = {{"vertex", c}, {"input_vertex", result.chosen_vertex}, {"cone_angle", angle}};
    scene.meshes.push_back(std::move(cone));
  }
  return scene;
}

void write_checkerboard_obj(const ricci::OneConeAtlasResult& result, const std::string& obj_path,
                            const CheckerboardOptions& texture) {
  namespace fs = std::filesystem;
  const AtlasTexturedMesh m = atlas_textured_mesh(result);
  const fs::path obj(obj_path);
  const std::string stem = obj.stem().string();
  const fs::path folder = obj.has_parent_path() ? obj.parent_path() : fs::path(".");
  const std::string mtl_name = stem + ".mtl", png_name = stem + "_checker.png";

  write_bytes_atomically((folder / png_name).string(), encode_png(checkerboard(texture)));
  write_text_atomically((folder / mtl_name).string(),
                        "# msp atlas checkerboard\nnewmtl checkerboard\nKa 0 0 0\nKd 1 1 1\nKs 0 0 "
                        "0\nillum 1\nmap_Kd " +
                            png_name + "\n");
  std::ostringstream out;
  out.precision(9);
  out << "# msp atlas: the mesh split along the cut, texture coordinates = central chart of the "
         "atlas\n";
  out << "mtllib " << mtl_name << "\no surface\n";
  for (Eigen::Index v = 0; v < m.positions.rows(); ++v) {
    out << "v " << m.positions(v, 0) << ' ' << m.positions(v, 1) << ' ' << m.positions(v, 2)
        << '\n';
  }
  // OBJ's v axis points up the image: undo the glTF flip.
  for (Eigen::Index v = 0; v < m.uvs.rows(); ++v)
    out << "vt " << m.uvs(v, 0) << ' ' << 1.0 - m.uvs(v, 1) << '\n';
  for (Eigen::Index v = 0; v < m.normals.rows(); ++v) {
    out << "vn " << m.normals(v, 0) << ' ' << m.normals(v, 1) << ' ' << m.normals(v, 2) << '\n';
  }
  out << "usemtl checkerboard\n";
  for (size_t i = 0; i < m.triangles.size(); i += 3) {
    out << 'f';
    for (size_t k = 0; k < 3; ++k) {
      const auto v = m.triangles[i + k] + 1;
      out << ' ' << v << '/' << v << '/' << v;
    }
    out << '\n';
  }
  write_text_atomically(obj_path, out.str());
}

}  // namespace msp
