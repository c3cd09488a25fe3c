#include "msp/fit_export.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <sstream>

#include <ricci/mesh/errors.h>
#include <ricci/topology/slice.h>
#include <spline/basis/multi_index.h>

#include "msp/cli.h"
#include "msp/svg_cover.h"

namespace msp {
namespace {

gltf::Mesh surface_mesh(const spline::Tessellation& t, const FitSceneOptions& options,
                        bool double_sided) {
  gltf::Mesh surface = tessellation_gltf_mesh(t);
  surface.material.name = options.checkerboard ? "checkerboard" : "spline";
  if (options.checkerboard) surface.material.base_color = {1, 1, 1, 1};
  surface.material.double_sided = double_sided;
  if (options.checkerboard)
    surface.material.texture =
        gltf::Texture{encode_png(checkerboard(options.texture)), true, false};
  return surface;
}

// The control points of each domain face joined along the lattice of multi-indices.
gltf::Mesh control_net_mesh(const spline::ManifoldSpline& spline) {
  const auto& space = *spline.space;
  const int n = space.degree();
  gltf::Mesh net;
  net.name = "control net";
  net.topology = gltf::Topology::lines;
  net.positions = spline.control_points;
  const auto betas = spline::multi_indices(n);
  for (int f : space.domain_faces()) {
    for (const auto& beta : betas) {
      const int from = space.function_index(f, spline::multi_index_position(beta));
      // Steps e_j - e_i with i < j: each lattice edge once.
      for (int i = 0; i < 3; ++i) {
        if (beta[i] == 0) continue;
        for (int j = i + 1; j < 3; ++j) {
          Eigen::Vector3i other = beta;
          --other[i];
          ++other[j];
          net.indices.push_back(static_cast<std::uint32_t>(from));
          net.indices.push_back(static_cast<std::uint32_t>(
              space.function_index(f, spline::multi_index_position(other))));
        }
      }
    }
  }
  net.material.name = "control net";
  net.material.base_color = gltf::linear_colour({40, 90, 200});
  return net;
}

gltf::Mesh domain_mesh_lines(const ricci::Mesh& mesh, const spline::ManifoldSplineSpace& space) {
  gltf::Mesh lines;
  lines.name = "domain mesh";
  lines.topology = gltf::Topology::lines;
  lines.positions.resize(static_cast<Eigen::Index>(mesh.n_vertices()), 3);
  for (auto v : mesh.vertices())
    lines.positions.row(v.idx()) = ricci::to_eigen(mesh.point(v)).transpose();
  for (auto e : mesh.edges()) {
    const auto h0 = mesh.halfedge_handle(e, 0), h1 = mesh.halfedge_handle(e, 1);
    const auto f0 = mesh.face_handle(h0), f1 = mesh.face_handle(h1);
    const bool in = (f0.is_valid() && space.in_domain(f0.idx())) ||
                    (f1.is_valid() && space.in_domain(f1.idx()));
    if (!in) continue;
    lines.indices.push_back(static_cast<std::uint32_t>(mesh.from_vertex_handle(h0).idx()));
    lines.indices.push_back(static_cast<std::uint32_t>(mesh.to_vertex_handle(h0).idx()));
  }
  lines.material.name = "domain mesh";
  lines.material.base_color = gltf::linear_colour({30, 30, 30});
  return lines;
}

// The samples of a domain-mesh halfedge on the surface, from its from-vertex to its to-vertex
// (empty when neither of its faces is a tessellated domain face).
std::vector<int> halfedge_samples(const ricci::Mesh& mesh, const spline::ManifoldSplineSpace& space,
                                  const spline::Tessellation& t, ricci::HalfedgeHandle h) {
  const int d = t.density;
  for (bool reversed : {false, true}) {
    const auto g = reversed ? mesh.opposite_halfedge_handle(h) : h;
    const auto f = mesh.face_handle(g);
    // Faces covered by a fill patch were not tessellated: their samples do not exist.
    if (!f.is_valid() || !space.in_domain(f.idx()) || !t.tessellated(f.idx())) continue;
    const auto hs = ricci::face_halfedges(mesh, f);
    for (int k = 0; k < 3; ++k) {
      if (hs[(k + 2) % 3] != g) continue;  // h_{k+2} is the edge opposite corner k
      std::vector<int> samples;
      for (int i = 0; i <= d; ++i)
        samples.push_back(t.edge_sample(f.idx(), k, reversed ? d - i : i));
      return samples;
    }
  }
  return {};
}

void add_cut_loops(const spline::FittedSurface& fitted, gltf::Scene& scene) {
  const auto& atlas = fitted.atlas.atlas;
  const ricci::Mesh& mesh = fitted.surface.domain;
  const auto& space = *fitted.surface.spline.space;
  const auto& t = fitted.tessellation;
  const Eigen::MatrixX3d normals = tessellation_normals(t);
  const double lift = 2e-3 * fitted.bbox_diagonal;
  const auto names = loop_names(atlas);
  for (std::size_t loop = 0; loop < atlas.cut.loops.size(); ++loop) {
    gltf::Mesh lines;
    lines.name = "cut loop " + names[loop];
    lines.topology = gltf::Topology::lines;
    std::vector<Eigen::RowVector3d> points;
    for (const auto h : atlas.cut.loops[loop].halfedges) {
      const auto samples = halfedge_samples(mesh, space, t, h);
      for (std::size_t i = 0; i + 1 < samples.size(); ++i) {
        for (int p : {samples[i], samples[i + 1]}) {
          lines.indices.push_back(static_cast<std::uint32_t>(points.size()));
          points.push_back(t.positions.row(p) + lift * normals.row(p));
        }
      }
    }
    if (points.empty()) continue;
    lines.positions.resize(static_cast<Eigen::Index>(points.size()), 3);
    for (std::size_t i = 0; i < points.size(); ++i)
      lines.positions.row(static_cast<Eigen::Index>(i)) = points[i];
    lines.material.name = lines.name;
    lines.material.base_color = gltf::linear_colour(loop_colour_rgb(static_cast<int>(loop)));
    lines.extras = {{"loop", loop}, {"name", names[loop]}};
    scene.meshes.push_back(std::move(lines));
  }
  const int cone_vertex = fitted.surface.singular_vertex;
  if (cone_vertex >= 0) {
    gltf::Mesh cone;
    cone.name = "extraordinary point";
    cone.topology = gltf::Topology::points;
    cone.positions.resize(1, 3);
    cone.positions.row(0) =
        ricci::to_eigen(mesh.point(mesh.vertex_handle(cone_vertex))).transpose();
    cone.material.name = "extraordinary point";
    cone.material.base_color = gltf::linear_colour({220, 30, 30});
    cone.extras = {{"domain_vertex", cone_vertex},
                   {"note", "the cone's star lies outside the spline domain (filled hole)"}};
    scene.meshes.push_back(std::move(cone));
  }
}

}  // namespace

gltf::Scene fit_scene(const spline::FittedSurface& fitted, const FitSceneOptions& options) {
  const spline::SplineSurface& surface = fitted.surface;
  gltf::Scene scene;
  scene.name = "fit";
  scene.extras = options.extras;
  scene.meshes.push_back(surface_mesh(fitted.tessellation, options, !fitted.watertight));
  if (options.control_net) scene.meshes.push_back(control_net_mesh(surface.spline));
  if (options.domain)
    scene.meshes.push_back(domain_mesh_lines(surface.domain, *surface.spline.space));
  if (options.cut_loops) add_cut_loops(fitted, scene);
  return scene;
}

}  // namespace msp
