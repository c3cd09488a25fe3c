// Procedural meshes: topology (Euler characteristic, genus, boundary loops), manifoldness,
// orientation, exact areas and volumes, and the exactly flat metric of the flat torus.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <set>

#include "ricci/mesh/errors.h"
#include "ricci/mesh/primitives.h"

namespace ricci {
namespace {

std::array<OpenMesh::Vec3d, 3> corners(const Mesh& mesh, FaceHandle f) {
  std::array<OpenMesh::Vec3d, 3> p;
  int k = 0;
  for (auto v : mesh.fv_range(f)) p[k++] = mesh.point(v);
  return p;
}

OpenMesh::Vec3d area_normal(const Mesh& mesh, FaceHandle f) {
  auto p = corners(mesh, f);
  return OpenMesh::cross(p[1] - p[0], p[2] - p[0]) / 2;
}

// Every face has three distinct vertices and no two faces share their vertex set.
void expect_simplicial(const Mesh& mesh) {
  std::set<std::array<int, 3>> seen;
  for (auto f : mesh.faces()) {
    std::array<int, 3> ids;
    int k = 0;
    for (auto v : f.vertices()) ids[k++] = v.idx();
    std::sort(ids.begin(), ids.end());
    EXPECT_TRUE(ids[0] != ids[1] && ids[1] != ids[2]);
    EXPECT_TRUE(seen.insert(ids).second) << "face " << f.idx() << " repeats a vertex triple";
  }
}

void expect_surface(const Mesh& mesh, int genus, int loops) {
  const SurfaceTopology t = surface_topology(mesh);
  EXPECT_TRUE(t.manifold);
  EXPECT_EQ(t.components, 1);
  EXPECT_EQ(t.boundary_loops, loops);
  EXPECT_EQ(t.genus, genus);
  EXPECT_EQ(t.euler_characteristic, 2 - 2 * genus - loops);
  EXPECT_EQ(t.vertices - t.edges + t.faces, t.euler_characteristic);
  for (auto v : mesh.vertices()) EXPECT_TRUE(mesh.is_manifold(v));
  expect_simplicial(mesh);
  for (auto f : mesh.faces()) EXPECT_GT(area_normal(mesh, f).norm(), 1e-12);
}

void expect_closed(const Mesh& mesh, int genus) {
  expect_surface(mesh, genus, 0);
  for (auto h : mesh.halfedges()) EXPECT_FALSE(h.is_boundary());
  EXPECT_GT(signed_volume(mesh), 0);
}

// Planar meshes: z = 0 everywhere and every face counter-clockwise seen from +z; returns the area.
double planar_area(const Mesh& mesh) {
  double area = 0;
  for (auto v : mesh.vertices()) EXPECT_EQ(mesh.point(v)[2], 0.0);
  for (auto f : mesh.faces()) {
    const double a = area_normal(mesh, f)[2];
    EXPECT_GT(a, 0) << "face " << f.idx();
    area += a;
  }
  return area;
}

double polygon_area(int n, double radius) { return n / 2.0 * radius * radius * std::sin(2 * M_PI / n); }

TEST(Primitives, Tetrahedron) {
  const Mesh mesh = make_tetrahedron();
  EXPECT_EQ(mesh.n_vertices(), 4u);
  EXPECT_EQ(mesh.n_faces(), 4u);
  expect_closed(mesh, 0);
  for (auto v : mesh.vertices()) EXPECT_NEAR(mesh.point(v).norm(), 1.0, 1e-15);
  // Regular tetrahedron inscribed in the unit sphere: volume 8 / (9 sqrt 3).
  EXPECT_NEAR(signed_volume(mesh), 8 / (9 * std::sqrt(3.0)), 1e-14);
}

TEST(Primitives, Icosphere) {
  for (int s = 0; s <= 3; ++s) {
    const Mesh mesh = make_icosphere(s, 2.0);
    const int power = 1 << (2 * s);
    EXPECT_EQ(static_cast<int>(mesh.n_vertices()), 10 * power + 2);
    EXPECT_EQ(static_cast<int>(mesh.n_faces()), 20 * power);
    expect_closed(mesh, 0);
    for (auto v : mesh.vertices()) EXPECT_NEAR(mesh.point(v).norm(), 2.0, 1e-14);
    EXPECT_LT(signed_volume(mesh), 4 * M_PI / 3 * 8);
  }
  EXPECT_NEAR(signed_volume(make_icosphere(4)), 4 * M_PI / 3, 0.01);
  EXPECT_THROW((void)make_icosphere(-1), InvalidInputError);
  EXPECT_THROW((void)make_icosphere(1, 0.0), InvalidInputError);
}

TEST(Primitives, TorusTopologyAndVolume) {
  for (auto [n, m] : {std::pair{3, 3}, std::pair{3, 4}, std::pair{7, 5}, std::pair{48, 24}}) {
    const Mesh mesh = make_torus(n, m, 2.0, 0.5);
    EXPECT_EQ(static_cast<int>(mesh.n_vertices()), n * m);
    EXPECT_EQ(static_cast<int>(mesh.n_faces()), 2 * n * m);
    expect_closed(mesh, 1);
    for (auto v : mesh.vertices()) EXPECT_EQ(v.valence(), 6u);
  }
  // The inscribed polyhedron converges to 2 pi^2 R r^2 from below.
  const double exact = 2 * M_PI * M_PI * 2.0 * 0.25;
  const double volume = signed_volume(make_torus(96, 48, 2.0, 0.5));
  EXPECT_LT(volume, exact);
  EXPECT_GT(volume, 0.995 * exact);
  EXPECT_THROW((void)make_torus(2, 5, 2, 1), InvalidInputError);
  EXPECT_THROW((void)make_torus(5, 5, 1, 2), InvalidInputError);
}

// Law of cosines corner angle opposite nothing: the angle at the vertex between sides b and c.
double corner_angle(double a, double b, double c) {
  return std::acos(std::clamp((b * b + c * c - a * a) / (2 * b * c), -1.0, 1.0));
}

void expect_flat(const Mesh& mesh, const Eigen::VectorXd& lengths, double expected_area) {
  ASSERT_EQ(lengths.size(), static_cast<Eigen::Index>(mesh.n_edges()));
  Eigen::VectorXd angle_sum = Eigen::VectorXd::Zero(mesh.n_vertices());
  double area = 0;
  for (auto f : mesh.faces()) {
    std::array<double, 3> l;  // l[k]: length of the edge opposite corner k
    std::array<int, 3> v;
    int k = 0;
    for (auto h : f.halfedges()) {
      v[k] = h.from().idx();
      l[(k + 2) % 3] = lengths[h.edge().idx()];  // halfedge k joins corners k and k+1
      ++k;
    }
    for (int i = 0; i < 3; ++i) {
      EXPECT_LT(l[i], l[(i + 1) % 3] + l[(i + 2) % 3] - 1e-9) << "face " << f.idx();
      angle_sum[v[i]] += corner_angle(l[i], l[(i + 1) % 3], l[(i + 2) % 3]);
    }
    const double s = (l[0] + l[1] + l[2]) / 2;
    area += std::sqrt(s * (s - l[0]) * (s - l[1]) * (s - l[2]));
  }
  for (auto vh : mesh.vertices()) {
    EXPECT_NEAR(2 * M_PI - angle_sum[vh.idx()], 0.0, 1e-12) << "vertex " << vh.idx();
  }
  EXPECT_NEAR(area, expected_area, 1e-12 * expected_area);
}

TEST(Primitives, FlatTorusMetricIsExactlyFlat) {
  for (auto [nx, ny] : {std::pair{3, 3}, std::pair{4, 7}, std::pair{16, 9}}) {
    const Mesh mesh = make_flat_torus_grid(nx, ny, 3.0, 2.0);
    expect_closed(mesh, 1);
    expect_flat(mesh, flat_torus_edge_lengths(mesh, nx, ny, 3.0, 2.0), 6.0);
  }
  // A sheared lattice (non-rectangular periods) is flat too, with area width * height.
  const Mesh sheared = make_flat_torus_grid(10, 6, 2.0, 1.5, 0.7);
  expect_flat(sheared, flat_torus_edge_lengths(sheared, 10, 6, 2.0, 1.5, 0.7), 3.0);
}

TEST(Primitives, FlatTorusLengthsRejectAForeignMesh) {
  const Mesh mesh = make_flat_torus_grid(5, 4, 1, 1);
  EXPECT_THROW((void)flat_torus_edge_lengths(mesh, 4, 5, 1, 1), InvalidInputError);
  EXPECT_THROW((void)flat_torus_edge_lengths(make_icosphere(0), 3, 4, 1, 1), InvalidInputError);
  EXPECT_THROW((void)make_flat_torus_grid(2, 5, 1, 1), InvalidInputError);
}

TEST(Primitives, DiskIsAnInscribedPolygon) {
  for (auto [rings, sectors] : {std::pair{1, 3}, std::pair{2, 5}, std::pair{8, 6}}) {
    const Mesh mesh = make_disk(rings, sectors);
    expect_surface(mesh, 0, 1);
    int boundary_vertices = 0;
    for (auto v : mesh.vertices()) {
      if (!v.is_boundary()) continue;
      ++boundary_vertices;
      EXPECT_NEAR(mesh.point(v).norm(), 1.0, 1e-15);
    }
    EXPECT_EQ(boundary_vertices, rings * sectors);
    EXPECT_NEAR(planar_area(mesh), polygon_area(rings * sectors, 1.0), 1e-13);
  }
  EXPECT_THROW((void)make_disk(0, 6), InvalidInputError);
  EXPECT_THROW((void)make_disk(3, 2), InvalidInputError);
}

TEST(Primitives, AnnulusHasTwoBoundaryLoops) {
  for (auto [rings, sectors] : {std::pair{1, 6}, std::pair{4, 32}, std::pair{3, 7}}) {
    const Mesh mesh = make_annulus(rings, sectors, 0.4, 1.0);
    expect_surface(mesh, 0, 2);
    const int inner_count = std::max(3, static_cast<int>(std::lround(sectors * 0.4)));
    EXPECT_NEAR(planar_area(mesh), polygon_area(sectors, 1.0) - polygon_area(inner_count, 0.4),
                1e-13);
  }
  EXPECT_THROW((void)make_annulus(2, 8, 1.0, 0.5), InvalidInputError);
}

TEST(Primitives, PlanarGrid) {
  const Mesh mesh = make_planar_grid(7, 3, 2.0, 0.5);
  EXPECT_EQ(mesh.n_vertices(), 32u);
  EXPECT_EQ(mesh.n_faces(), 42u);
  expect_surface(mesh, 0, 1);
  EXPECT_NEAR(planar_area(mesh), 1.0, 1e-14);
  expect_surface(make_planar_grid(1, 1, 1, 1), 0, 1);
}

TEST(Primitives, GenusSlabs) {
  for (int genus = 0; genus <= 4; ++genus) {
    for (int resolution : {1, 2, 3}) {
      const Mesh mesh = make_genus_slab(genus, resolution);
      expect_closed(mesh, genus);
      // (2g+1) x 3 x 1 cells minus g holes, exactly.
      EXPECT_NEAR(signed_volume(mesh), 3.0 * (2 * genus + 1) - genus, 1e-12);
    }
  }
  const Mesh smooth = make_genus_slab(3, 3, 10);
  expect_closed(smooth, 3);
  EXPECT_THROW((void)make_genus_slab(-1), InvalidInputError);
  EXPECT_THROW((void)make_genus_slab(2, 0), InvalidInputError);
}

TEST(Primitives, OpenGenusSurfaces) {
  for (int genus = 0; genus <= 3; ++genus) {
    for (int holes = 0; holes <= 4 * (genus + 1); holes += genus + 1) {
      for (int resolution : {1, 2}) {
        expect_surface(make_open_genus(genus, holes, resolution), genus, holes);
      }
    }
    expect_surface(make_open_genus(genus, 1), genus, 1);
    expect_surface(make_open_genus(genus, 2), genus, 2);
  }
  EXPECT_THROW((void)make_open_genus(1, 9), InvalidInputError);
  EXPECT_THROW((void)make_open_genus(1, -1), InvalidInputError);
}

TEST(Primitives, RandomPerturbationIsSeededAndKeepsTheSurface) {
  const Mesh disk = make_disk(6, 6);
  const Mesh a = make_random_perturbed(disk, 0.3, 7);
  const Mesh b = make_random_perturbed(disk, 0.3, 7);
  const Mesh c = make_random_perturbed(disk, 0.3, 8);
  double moved = 0;
  double differ = 0;
  for (auto v : disk.vertices()) {
    EXPECT_EQ(a.point(v), b.point(v));
    const double d = (a.point(v) - disk.point(v)).norm();
    if (v.is_boundary()) {
      EXPECT_EQ(d, 0.0);
    }
    moved = std::max(moved, d);
    differ = std::max(differ, (a.point(v) - c.point(v)).norm());
  }
  EXPECT_GT(moved, 0.01);
  EXPECT_GT(differ, 0.01);
  expect_surface(a, 0, 1);
  EXPECT_NEAR(planar_area(a), planar_area(disk), 1e-13);  // the outline is fixed

  const Mesh torus = make_random_perturbed(make_torus(12, 8, 2, 0.7), 0.3, 1);
  expect_closed(torus, 1);
  EXPECT_THROW((void)make_random_perturbed(disk, 0.6, 1), InvalidInputError);
}

TEST(Primitives, TopologyCountsSeveralComponents) {
  Mesh two = make_tetrahedron();
  const Mesh torus = make_torus(4, 3, 2, 1);
  std::vector<VertexHandle> handles;
  for (auto v : torus.vertices()) handles.push_back(two.add_vertex(torus.point(v)));
  for (auto f : torus.faces()) {
    std::vector<VertexHandle> face;
    for (auto v : f.vertices()) face.push_back(handles[v.idx()]);
    two.add_face(face);
  }
  const SurfaceTopology t = surface_topology(two);
  EXPECT_EQ(t.components, 2);
  EXPECT_EQ(t.genus, 1);
  EXPECT_EQ(t.euler_characteristic, 2);
}

}  // namespace
}  // namespace ricci
