#include "ricci/mesh/small_holes.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "ricci/mesh/boundary_loops.h"
#include "ricci/mesh/errors.h"
#include "ricci/mesh/triangulate_polygon.h"

namespace ricci {
namespace {

double bbox_diagonal(const Mesh& mesh) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
  for (auto v : mesh.vertices()) {
    const Eigen::Vector3d p = to_eigen(mesh.point(v));
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return mesh.n_vertices() > 0 ? (hi - lo).norm() : 0.0;
}

double loop_diameter(const std::vector<Eigen::Vector3d>& corners) {
  double d = 0.0;
  for (std::size_t i = 0; i < corners.size(); ++i)
    for (std::size_t j = i + 1; j < corners.size(); ++j)
      d = std::max(d, (corners[i] - corners[j]).norm());
  return d;
}

// Adds the cap of one loop (its from-vertices in walk order, which is the surface's orientation
// for faces inside the hole). Returns the faces added; none when a face cannot be added.
int cap_loop(Mesh& mesh, const std::vector<VertexHandle>& loop,
             const std::vector<Eigen::Vector3d>& corners) {
  auto allowed = [&](int i, int j) {
    return !mesh.find_halfedge(loop[static_cast<std::size_t>(i)], loop[static_cast<std::size_t>(j)])
                .is_valid();
  };
  const std::vector<std::array<int, 3>> triangles = triangulate_polygon(corners, allowed);
  // Every diagonal must be new: a cap through an existing edge would make it non-manifold.
  for (const auto& t : triangles) {
    for (int k = 0; k < 3; ++k) {
      const int a = t[static_cast<std::size_t>(k)], b = t[static_cast<std::size_t>((k + 1) % 3)];
      const int n = static_cast<int>(loop.size());
      const bool side = (b - a + n) % n == 1 || (a - b + n) % n == 1;
      if (!side && !allowed(a, b)) return 0;
    }
  }
  int added = 0;
  for (const auto& t : triangles) {
    const FaceHandle f =
        mesh.add_face(loop[static_cast<std::size_t>(t[0])], loop[static_cast<std::size_t>(t[1])],
                      loop[static_cast<std::size_t>(t[2])]);
    if (!f.is_valid()) break;  // OpenMesh refused it (complex vertex): the rest stays open
    ++added;
  }
  return added;
}

}  // namespace

SmallHoleCaps cap_small_holes(const Mesh& mesh, const SmallHoleOptions& options) {
  if (!(options.max_diameter >= 0.0) || !std::isfinite(options.max_diameter)) {
    throw InvalidInputError("cap_small_holes: max_diameter must be finite and >= 0");
  }
  SmallHoleCaps out;
  out.mesh = mesh;
  out.capped_vertex.assign(mesh.n_vertices(), 0);
  const double limit = options.max_diameter * bbox_diagonal(mesh);
  for (const auto& halfedges : find_boundary_loops(mesh)) {
    std::vector<VertexHandle> loop;
    std::vector<Eigen::Vector3d> corners;
    for (auto h : halfedges) {
      loop.push_back(mesh.from_vertex_handle(h));
      corners.push_back(to_eigen(mesh.point(loop.back())));
    }
    const double diameter = loop_diameter(corners);
    if (!(diameter < limit) || loop.size() < 3) continue;
    const int faces = cap_loop(out.mesh, loop, corners);
    if (faces == 0) continue;
    out.cap_faces += faces;
    ++out.capped_loops;
    out.largest_diameter = std::max(out.largest_diameter, diameter);
    for (auto v : loop) out.capped_vertex[static_cast<std::size_t>(v.idx())] = 1;
  }
  if (out.capped_loops > 0) out.largest_diameter /= bbox_diagonal(mesh);
  return out;
}

}  // namespace ricci
