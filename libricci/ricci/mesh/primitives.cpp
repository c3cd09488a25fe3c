// Procedural closed and planar meshes: tetrahedron, icosphere, tori, disk, annulus, grid.
#include "ricci/mesh/primitives.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "ricci/mesh/errors.h"
#include "ricci/mesh/primitives_detail.h"

namespace ricci {

namespace detail {

Mesh mesh_from_arrays(const std::vector<Eigen::Vector3d>& points,
                      const std::vector<std::array<int, 3>>& triangles, const char* what) {
  Mesh mesh;
  std::vector<VertexHandle> handles;
  handles.reserve(points.size());
  for (const auto& p : points) handles.push_back(mesh.add_vertex(to_openmesh(p)));
  for (size_t f = 0; f < triangles.size(); ++f) {
    const auto& t = triangles[f];
    FaceHandle fh = mesh.add_face(handles[t[0]], handles[t[1]], handles[t[2]]);
    // add_face refuses faces that would make an edge or vertex non-manifold: a bug here.
    if (!fh.is_valid()) {
      throw TopologyError(std::string(what) + ": face " + std::to_string(f) +
                          " would make the mesh non-manifold");
    }
  }
  return mesh;
}

}  // namespace detail

namespace {

using detail::mesh_from_arrays;
using Triangles = std::vector<std::array<int, 3>>;
using Points = std::vector<Eigen::Vector3d>;

// Orients every face of a star-shaped closed polyhedron (around the origin) outward.
void orient_outward(const Points& points, Triangles& triangles) {
  for (auto& t : triangles) {
    const Eigen::Vector3d& a = points[t[0]];
    const Eigen::Vector3d n = (points[t[1]] - a).cross(points[t[2]] - a);
    if (n.dot(a + points[t[1]] + points[t[2]]) < 0) std::swap(t[1], t[2]);
  }
}

void require(bool condition, const std::string& message) {
  if (!condition) throw InvalidInputError(message);
}

// Quad (i,j),(i+1,j),(i+1,j+1),(i,j+1) of an n x m periodic grid, split along (i,j)-(i+1,j+1).
Triangles periodic_grid_triangles(int n, int m) {
  Triangles triangles;
  triangles.reserve(2 * static_cast<size_t>(n) * m);
  auto id = [m, n](int i, int j) { return (i % n) * m + (j % m); };
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < m; ++j) {
      triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  return triangles;
}

Points torus_points(int n_major, int n_minor, double R, double r) {
  Points points;
  points.reserve(static_cast<size_t>(n_major) * n_minor);
  for (int i = 0; i < n_major; ++i) {
    const double u = 2 * M_PI * i / n_major;
    for (int j = 0; j < n_minor; ++j) {
      const double v = 2 * M_PI * j / n_minor;
      points.emplace_back((R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u),
                          r * std::sin(v));
    }
  }
  return points;
}

// A closed polygon of `count` vertices on the circle of `radius` in z = 0, starting at angle 0.
struct Circle {
  std::vector<int> ids;
  std::vector<double> angles;
};

Circle add_circle(Points& points, int count, double radius) {
  Circle c;
  for (int k = 0; k < count; ++k) {
    const double a = 2 * M_PI * k / count;
    c.ids.push_back(static_cast<int>(points.size()));
    c.angles.push_back(a);
    points.emplace_back(radius * std::cos(a), radius * std::sin(a), 0.0);
  }
  return c;
}

// Triangulates the strip between two concentric circles by merging their angle sequences, so
// every triangle spans the shorter angular step next; counter-clockwise seen from +z.
void stitch(const Circle& inner, const Circle& outer, Triangles& triangles) {
  const size_t ni = inner.ids.size();
  const size_t no = outer.ids.size();
  auto angle = [](const Circle& c, size_t k) {
    return k < c.angles.size() ? c.angles[k] : c.angles[k - c.angles.size()] + 2 * M_PI;
  };
  size_t a = 0;
  size_t b = 0;
  while (a < ni || b < no) {
    const bool advance_outer = a == ni || (b < no && angle(outer, b + 1) <= angle(inner, a + 1));
    const int ia = inner.ids[a % ni];
    const int ob = outer.ids[b % no];
    if (advance_outer) {
      triangles.push_back({ia, ob, outer.ids[(b + 1) % no]});
      ++b;
    } else {
      triangles.push_back({ia, ob, inner.ids[(a + 1) % ni]});
      ++a;
    }
  }
}

}  // namespace

Mesh make_tetrahedron() {
  const double s = 1.0 / std::sqrt(3.0);
  Points points = {{s, s, s}, {s, -s, -s}, {-s, s, -s}, {-s, -s, s}};
  Triangles triangles = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
  orient_outward(points, triangles);
  return mesh_from_arrays(points, triangles, "make_tetrahedron");
}

Mesh make_icosphere(int subdivisions, double radius) {
  require(subdivisions >= 0 && subdivisions <= 8,
          "make_icosphere: subdivisions must be in [0, 8], got " + std::to_string(subdivisions));
  require(radius > 0, "make_icosphere: radius must be positive");
  const double t = (1 + std::sqrt(5.0)) / 2;
  Points points = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                   {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  Triangles triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                         {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                         {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                         {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (auto& p : points) p.normalize();
  for (int s = 0; s < subdivisions; ++s) {
    std::map<std::pair<int, int>, int> midpoint;
    auto mid = [&](int a, int b) {
      auto key = std::minmax(a, b);
      auto it = midpoint.find(key);
      if (it != midpoint.end()) return it->second;
      const int id = static_cast<int>(points.size());
      points.push_back((points[a] + points[b]).normalized());
      midpoint.emplace(key, id);
      return id;
    };
    Triangles finer;
    finer.reserve(4 * triangles.size());
    for (const auto& f : triangles) {
      const int ab = mid(f[0], f[1]);
      const int bc = mid(f[1], f[2]);
      const int ca = mid(f[2], f[0]);
      finer.push_back({f[0], ab, ca});
      finer.push_back({f[1], bc, ab});
      finer.push_back({f[2], ca, bc});
      finer.push_back({ab, bc, ca});
    }
    triangles = std::move(finer);
  }
  for (auto& p : points) p *= radius;
  orient_outward(points, triangles);
  return mesh_from_arrays(points, triangles, "make_icosphere");
}

Mesh make_torus(int n_major, int n_minor, double R, double r) {
  require(n_major >= 3 && n_minor >= 3, "make_torus: n_major and n_minor must be >= 3, got " +
                                            std::to_string(n_major) + " x " +
                                            std::to_string(n_minor));
  require(r > 0 && R > r, "make_torus: radii must satisfy R > r > 0");
  return mesh_from_arrays(torus_points(n_major, n_minor, R, r),
                          periodic_grid_triangles(n_major, n_minor), "make_torus");
}

Mesh make_flat_torus_grid(int nx, int ny, double width, double height, double shear) {
  require(nx >= 3 && ny >= 3, "make_flat_torus_grid: nx and ny must be >= 3, got " +
                                  std::to_string(nx) + " x " + std::to_string(ny));
  require(width > 0 && height > 0 && std::isfinite(shear),
          "make_flat_torus_grid: width and height must be positive");
  // Any embedding will do; this one keeps the tube proportional to the periods.
  const double r = height / (2 * M_PI);
  const double R = r + width / (2 * M_PI);
  return mesh_from_arrays(torus_points(nx, ny, R, r), periodic_grid_triangles(nx, ny),
                          "make_flat_torus_grid");
}

Eigen::VectorXd flat_torus_edge_lengths(const Mesh& mesh, int nx, int ny, double width,
                                        double height, double shear) {
  require(nx >= 3 && ny >= 3 && static_cast<long>(mesh.n_vertices()) == long{nx} * ny,
          "flat_torus_edge_lengths: mesh has " + std::to_string(mesh.n_vertices()) +
              " vertices, not the " + std::to_string(long{nx} * ny) + " of the grid");
  // Grid steps of the lattice basis: one cell along i, one cell along j.
  const Eigen::Vector2d step_i(width / nx, 0.0);
  const Eigen::Vector2d step_j(shear / ny, height / ny);
  auto wrap = [](int d, int n) { return d == n - 1 ? -1 : (d == 1 - n ? 1 : d); };
  Eigen::VectorXd lengths(mesh.n_edges());
  for (auto e : mesh.edges()) {
    const int a = e.v0().idx();
    const int b = e.v1().idx();
    const int di = wrap(b / ny - a / ny, nx);
    const int dj = wrap(b % ny - a % ny, ny);
    const bool grid_edge = std::abs(di) + std::abs(dj) == 1 || (di == dj && di != 0);
    require(grid_edge, "flat_torus_edge_lengths: edge " + std::to_string(e.idx()) +
                           " is not an edge of the " + std::to_string(nx) + " x " +
                           std::to_string(ny) + " grid");
    lengths[e.idx()] = (di * step_i + dj * step_j).norm();
  }
  return lengths;
}

Mesh make_disk(int rings, int sectors) {
  require(rings >= 1 && sectors >= 3, "make_disk: need rings >= 1 and sectors >= 3");
  Points points = {{0.0, 0.0, 0.0}};
  Triangles triangles;
  Circle previous = add_circle(points, sectors, 1.0 / rings);
  for (int k = 0; k < sectors; ++k) {
    triangles.push_back({0, previous.ids[k], previous.ids[(k + 1) % sectors]});
  }
  for (int ring = 2; ring <= rings; ++ring) {
    Circle next = add_circle(points, sectors * ring, static_cast<double>(ring) / rings);
    stitch(previous, next, triangles);
    previous = std::move(next);
  }
  return mesh_from_arrays(points, triangles, "make_disk");
}

Mesh make_annulus(int rings, int sectors, double inner_radius, double outer_radius) {
  require(rings >= 1 && sectors >= 3, "make_annulus: need rings >= 1 and sectors >= 3");
  require(inner_radius > 0 && outer_radius > inner_radius,
          "make_annulus: need 0 < inner_radius < outer_radius");
  Points points;
  Triangles triangles;
  Circle previous;
  for (int ring = 0; ring <= rings; ++ring) {
    const double radius = inner_radius + (outer_radius - inner_radius) * ring / rings;
    const int count = std::max(3, static_cast<int>(std::lround(sectors * radius / outer_radius)));
    Circle next = add_circle(points, count, radius);
    if (ring > 0) stitch(previous, next, triangles);
    previous = std::move(next);
  }
  return mesh_from_arrays(points, triangles, "make_annulus");
}

Mesh make_planar_grid(int nx, int ny, double width, double height) {
  require(nx >= 1 && ny >= 1, "make_planar_grid: need nx, ny >= 1");
  require(width > 0 && height > 0, "make_planar_grid: width and height must be positive");
  Points points;
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i <= nx; ++i) points.emplace_back(width * i / nx, height * j / ny, 0.0);
  }
  Triangles triangles;
  auto id = [nx](int i, int j) { return j * (nx + 1) + i; };
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  return mesh_from_arrays(points, triangles, "make_planar_grid");
}

}  // namespace ricci
