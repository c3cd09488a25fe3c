// Procedural genus-g slabs (closed and open), random perturbation, and topology counts.
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "ricci/mesh/errors.h"
#include "ricci/mesh/primitives.h"
#include "ricci/mesh/primitives_detail.h"

namespace ricci {

namespace {

// Voxel grid of a slab of (2g+1) x 3 x 1 cells, each cell res^3 voxels, with through-holes at
// cells (2k+1, 1). The holes are one cell apart and one cell from the rim, so no two empty
// regions touch along an edge or a corner only: the voxel boundary is a 2-manifold.
struct Slab {
  int genus;
  int res;
  int nx() const { return (2 * genus + 1) * res; }
  int ny() const { return 3 * res; }
  int nz() const { return res; }
  bool solid(int x, int y, int z) const {
    if (x < 0 || y < 0 || z < 0 || x >= nx() || y >= ny() || z >= nz()) return false;
    const int cx = x / res;
    const int cy = y / res;
    return !(cy == 1 && cx % 2 == 1);
  }
};

// One voxel face: the voxel, the axis of its normal (0, 1, 2) and the normal's sign.
struct VoxelFace {
  std::array<int, 3> voxel;
  int axis;
  int sign;
};

// Boundary of the slab's voxels, quads split into right isosceles triangles, minus the faces
// `skip` selects. Coordinates are in cell units.
Mesh slab_surface(const Slab& slab, const std::function<bool(const VoxelFace&)>& skip) {
  const int sx = slab.nx() + 1;
  const int sy = slab.ny() + 1;
  std::vector<int> lattice_id(static_cast<size_t>(sx) * sy * (slab.nz() + 1), -1);
  std::vector<Eigen::Vector3d> points;
  auto vertex = [&](const std::array<int, 3>& p) {
    int& id = lattice_id[(static_cast<size_t>(p[2]) * sy + p[1]) * sx + p[0]];
    if (id < 0) {
      id = static_cast<int>(points.size());
      points.push_back(Eigen::Vector3d(p[0], p[1], p[2]) / slab.res);
    }
    return id;
  };
  std::vector<std::array<int, 3>> triangles;
  for (int z = 0; z < slab.nz(); ++z) {
    for (int y = 0; y < slab.ny(); ++y) {
      for (int x = 0; x < slab.nx(); ++x) {
        if (!slab.solid(x, y, z)) continue;
        for (int axis = 0; axis < 3; ++axis) {
          for (int sign : {-1, 1}) {
            std::array<int, 3> n = {x, y, z};
            n[axis] += sign;
            if (slab.solid(n[0], n[1], n[2])) continue;
            if (skip && skip({{x, y, z}, axis, sign})) continue;
            // e1 x e2 = e_axis, so base, +e1, +e1+e2, +e2 turns counter-clockwise about +axis.
            const int e1 = (axis + 1) % 3;
            const int e2 = (axis + 2) % 3;
            std::array<int, 3> base = {x, y, z};
            if (sign > 0) base[axis] += 1;
            std::array<std::array<int, 3>, 4> c = {base, base, base, base};
            c[1][e1] += 1;
            c[2][e1] += 1;
            c[2][e2] += 1;
            c[3][e2] += 1;
            if (sign < 0) std::swap(c[1], c[3]);
            const int q0 = vertex(c[0]), q1 = vertex(c[1]), q2 = vertex(c[2]), q3 = vertex(c[3]);
            triangles.push_back({q0, q1, q2});
            triangles.push_back({q0, q2, q3});
          }
        }
      }
    }
  }
  return detail::mesh_from_arrays(points, triangles, "make_genus_slab");
}

// Taubin lambda|mu smoothing with uniform weights: rounds the slab without shrinking it.
void taubin_smooth(Mesh& mesh, int iterations) {
  std::vector<OpenMesh::Vec3d> moved(mesh.n_vertices());
  for (int it = 0; it < 2 * iterations; ++it) {
    const double factor = it % 2 == 0 ? 0.5 : -0.53;
    for (auto v : mesh.vertices()) {
      OpenMesh::Vec3d sum(0, 0, 0);
      int count = 0;
      for (auto w : v.vertices()) {
        sum += mesh.point(w);
        ++count;
      }
      const OpenMesh::Vec3d p = mesh.point(v);
      moved[v.idx()] = (v.is_boundary() || count == 0) ? p : p + factor * (sum / count - p);
    }
    for (auto v : mesh.vertices()) mesh.set_point(v, moved[v.idx()]);
  }
}

double min_corner_angle(const Mesh& mesh, FaceHandle f) {
  std::array<OpenMesh::Vec3d, 3> p;
  int k = 0;
  for (auto v : mesh.fv_range(f)) p[k++] = mesh.point(v);
  double smallest = M_PI;
  for (int i = 0; i < 3; ++i) {
    const OpenMesh::Vec3d a = p[(i + 1) % 3] - p[i];
    const OpenMesh::Vec3d b = p[(i + 2) % 3] - p[i];
    smallest = std::min(smallest, std::atan2(OpenMesh::cross(a, b).norm(), OpenMesh::dot(a, b)));
  }
  return smallest;
}

OpenMesh::Vec3d face_area_normal(const Mesh& mesh, FaceHandle f) {
  std::array<OpenMesh::Vec3d, 3> p;
  int k = 0;
  for (auto v : mesh.fv_range(f)) p[k++] = mesh.point(v);
  return OpenMesh::cross(p[1] - p[0], p[2] - p[0]);
}

}  // namespace

Mesh make_genus_slab(int genus, int resolution, int smoothing_iterations) {
  if (genus < 0 || genus > 64 || resolution < 1 || resolution > 64 || smoothing_iterations < 0) {
    throw InvalidInputError("make_genus_slab: need 0 <= genus <= 64, 1 <= resolution <= 64 and "
                            "smoothing_iterations >= 0");
  }
  Mesh mesh = slab_surface(Slab{genus, resolution}, nullptr);
  taubin_smooth(mesh, smoothing_iterations);
  return mesh;
}

Mesh make_open_genus(int genus, int holes, int resolution) {
  if (genus < 0 || genus > 64 || resolution < 1 || resolution > 64) {
    throw InvalidInputError("make_open_genus: need 0 <= genus <= 64 and 1 <= resolution <= 64");
  }
  const int sites = 4 * (genus + 1);
  if (holes < 0 || holes > sites) {
    throw InvalidInputError("make_open_genus: holes must be in [0, " + std::to_string(sites) +
                            "] for genus " + std::to_string(genus) + ", got " +
                            std::to_string(holes));
  }
  const Slab slab{genus, resolution};
  // Hole h: cell (2 (h mod (g+1)), 0 or 2), top then bottom face; sites never share a vertex.
  auto skip = [&](const VoxelFace& face) {
    if (face.axis != 2) return false;
    const int cx = face.voxel[0] / resolution;
    const int cy = face.voxel[1] / resolution;
    if (cx % 2 != 0 || cy == 1) return false;
    const int site = cx / 2 + (genus + 1) * ((face.sign > 0 ? 0 : 1) + (cy == 2 ? 2 : 0));
    return site < holes;
  };
  return slab_surface(slab, skip);
}

Mesh make_random_perturbed(Mesh mesh, double relative_amplitude, std::uint32_t seed) {
  if (!(relative_amplitude >= 0 && relative_amplitude < 0.5)) {
    throw InvalidInputError("make_random_perturbed: relative_amplitude must be in [0, 0.5)");
  }
  std::mt19937 rng(seed);
  // mt19937 output is fixed by the standard; the distributions are not, so map it by hand.
  auto uniform = [&rng]() { return static_cast<double>(rng()) / 4294967296.0; };
  const double min_angle = 5.0 * M_PI / 180.0;
  for (auto v : mesh.vertices()) {
    const double u1 = uniform();
    const double u2 = uniform();
    if (v.is_boundary() || mesh.is_isolated(v)) continue;
    OpenMesh::Vec3d normal(0, 0, 0);
    for (auto f : v.faces()) normal += face_area_normal(mesh, f);
    double shortest = std::numeric_limits<double>::infinity();
    for (auto h : v.outgoing_halfedges()) shortest = std::min(shortest, mesh.calc_edge_length(h));
    if (normal.norm() == 0 || !std::isfinite(shortest)) continue;
    normal.normalize();
    // Tangent basis: cross with the axis least aligned with the normal.
    int axis = 0;
    for (int k = 1; k < 3; ++k) {
      if (std::abs(normal[k]) < std::abs(normal[axis])) axis = k;
    }
    OpenMesh::Vec3d e(0, 0, 0);
    e[axis] = 1;
    const OpenMesh::Vec3d t1 = OpenMesh::cross(normal, e).normalized();
    const OpenMesh::Vec3d t2 = OpenMesh::cross(normal, t1);
    const double radius = relative_amplitude * shortest * std::sqrt(u1);
    const double phi = 2 * M_PI * u2;
    const OpenMesh::Vec3d old_point = mesh.point(v);
    std::vector<OpenMesh::Vec3d> old_normals;
    for (auto f : v.faces()) old_normals.push_back(face_area_normal(mesh, f));
    mesh.set_point(v, old_point + radius * (std::cos(phi) * t1 + std::sin(phi) * t2));
    size_t k = 0;
    bool ok = true;
    for (auto f : v.faces()) {
      ok = ok && OpenMesh::dot(face_area_normal(mesh, f), old_normals[k++]) > 0 &&
           min_corner_angle(mesh, f) > min_angle;
    }
    if (!ok) mesh.set_point(v, old_point);
  }
  return mesh;
}

SurfaceTopology surface_topology(const Mesh& mesh) {
  SurfaceTopology t;
  t.vertices = static_cast<int>(mesh.n_vertices());
  t.edges = static_cast<int>(mesh.n_edges());
  t.faces = static_cast<int>(mesh.n_faces());
  // Union-find over vertices joined by edges; isolated vertices are not surface components.
  std::vector<int> parent(mesh.n_vertices());
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&parent](int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (auto e : mesh.edges()) parent[find(e.v0().idx())] = find(e.v1().idx());
  int used_vertices = 0;
  for (auto v : mesh.vertices()) {
    if (mesh.is_isolated(v)) continue;
    ++used_vertices;
    if (find(v.idx()) == v.idx()) ++t.components;
    if (!mesh.is_manifold(v)) t.manifold = false;
  }
  std::vector<bool> seen(mesh.n_halfedges(), false);
  for (auto h : mesh.halfedges()) {
    if (!h.is_boundary() || seen[h.idx()]) continue;
    ++t.boundary_loops;
    for (auto g = h; !seen[g.idx()]; g = g.next()) seen[g.idx()] = true;
  }
  t.euler_characteristic = used_vertices - t.edges + t.faces;
  t.genus = (2 * t.components - t.euler_characteristic - t.boundary_loops) / 2;
  return t;
}

double signed_volume(const Mesh& mesh) {
  double six_volume = 0;
  for (auto f : mesh.faces()) {
    std::array<OpenMesh::Vec3d, 3> p;
    int k = 0;
    for (auto v : f.vertices()) p[k++] = mesh.point(v);
    six_volume += OpenMesh::dot(p[0], OpenMesh::cross(p[1], p[2]));
  }
  return six_volume / 6;
}

}  // namespace ricci
