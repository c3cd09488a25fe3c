#include "ricci/mesh/collar.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include <Eigen/Geometry>

#include "ricci/mesh/errors.h"

namespace ricci {
namespace {

// The boundary loops as cycles of boundary halfedges (no face), each following the next.
std::vector<std::vector<HalfedgeHandle>> boundary_cycles(const Mesh& mesh) {
  std::vector<std::vector<HalfedgeHandle>> cycles;
  std::vector<char> seen(mesh.n_halfedges(), 0);
  for (auto h : mesh.halfedges()) {
    if (!mesh.is_boundary(h) || seen[static_cast<std::size_t>(h.idx())]) continue;
    std::vector<HalfedgeHandle> cycle;
    for (auto g = h; !seen[static_cast<std::size_t>(g.idx())]; g = mesh.next_halfedge_handle(g)) {
      seen[static_cast<std::size_t>(g.idx())] = 1;
      cycle.push_back(g);
    }
    cycles.push_back(std::move(cycle));
  }
  return cycles;
}

// Area-weighted normal of the faces around v.
Eigen::Vector3d vertex_normal(const Mesh& mesh, VertexHandle v) {
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  for (auto f : mesh.vf_range(v)) {
    std::array<Eigen::Vector3d, 3> p;
    int k = 0;
    for (auto w : mesh.fv_range(f)) p[static_cast<std::size_t>(k++)] = to_eigen(mesh.point(w));
    n += (p[1] - p[0]).cross(p[2] - p[0]);
  }
  return n.normalized();
}

// One ring outside the boundary cycles of `mesh` (modified in place); returns the new cycles'
// vertex normals carried over from their parents (the collar continues the tangent plane).
void add_ring(Mesh& mesh, std::vector<Eigen::Vector3d>& normal, const CollarOptions& options) {
  const auto cycles = boundary_cycles(mesh);
  for (const auto& cycle : cycles) {
    const std::size_t n = cycle.size();
    std::vector<VertexHandle> v(n);
    std::vector<Eigen::Vector3d> outward(n);
    std::vector<double> length(n);
    for (std::size_t i = 0; i < n; ++i) v[i] = mesh.from_vertex_handle(cycle[i]);
    for (std::size_t i = 0; i < n; ++i) {
      // Boundary halfedges run with the surface on their right: n x direction points out.
      const Eigen::Vector3d prev = to_eigen(mesh.point(v[(i + n - 1) % n]));
      const Eigen::Vector3d here = to_eigen(mesh.point(v[i]));
      const Eigen::Vector3d next = to_eigen(mesh.point(v[(i + 1) % n]));
      const Eigen::Vector3d& nv = normal[static_cast<std::size_t>(v[i].idx())];
      outward[i] = nv.cross(next - prev).normalized();
      length[i] = 0.5 * ((here - prev).norm() + (next - here).norm());
    }
    double perimeter = 0.0;
    for (std::size_t i = 0; i < n; ++i) perimeter += length[i];
    const double cap =
        options.max_loop_fraction * perimeter / (2.0 * M_PI) / static_cast<double>(options.rings);
    std::vector<VertexHandle> copy(n);
    for (std::size_t i = 0; i < n; ++i) {
      Eigen::Vector3d o = outward[(i + n - 1) % n] + 2.0 * outward[i] + outward[(i + 1) % n];
      if (!(o.norm() > 0.0)) o = outward[i];
      const double w = std::min(options.width * length[i], cap);
      const Eigen::Vector3d p = to_eigen(mesh.point(v[i])) + w * o.normalized();
      copy[i] = mesh.add_vertex(to_openmesh(p));
      normal.push_back(normal[static_cast<std::size_t>(v[i].idx())]);
    }
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t j = (i + 1) % n;  // boundary halfedge i runs v[i] -> v[j]
      if (!mesh.add_face(v[i], v[j], copy[j]).is_valid() ||
          !mesh.add_face(v[i], copy[j], copy[i]).is_valid()) {
        throw TopologyError("collar: the ring along boundary vertex " +
                            std::to_string(v[i].idx()) + " is not a manifold");
      }
    }
  }
}

}  // namespace

CollarResult add_boundary_collar(const Mesh& mesh, const CollarOptions& options) {
  if (options.rings < 1) throw InvalidInputError("collar: rings must be at least 1");
  if (!(options.width > 0.0) || !(options.max_loop_fraction > 0.0)) {
    throw InvalidInputError("collar: width and max_loop_fraction must be positive");
  }
  CollarResult result;
  result.mesh = mesh;
  result.original_vertices = static_cast<int>(mesh.n_vertices());
  result.original_faces = static_cast<int>(mesh.n_faces());
  for (auto v : mesh.vertices()) {
    int out = 0;
    for (auto h : mesh.voh_range(v)) out += mesh.is_boundary(h);
    if (out > 1) {
      throw InvalidInputError("collar: boundary vertex " + std::to_string(v.idx()) +
                              " is on two boundary stretches (a pinched boundary)");
    }
  }
  std::vector<Eigen::Vector3d> normal(mesh.n_vertices());
  for (auto v : mesh.vertices()) {
    if (mesh.is_boundary(v)) normal[static_cast<std::size_t>(v.idx())] = vertex_normal(mesh, v);
  }
  result.ring.assign(mesh.n_faces(), 0);
  for (int r = 1; r <= options.rings; ++r) {
    const std::size_t before = result.mesh.n_faces();
    add_ring(result.mesh, normal, options);
    if (result.mesh.n_faces() == before) break;  // closed: nothing to add
    result.ring.resize(result.mesh.n_faces(), r);
  }
  return result;
}

}  // namespace ricci
