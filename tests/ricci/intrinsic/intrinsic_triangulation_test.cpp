// Intrinsic triangulations (ricci/intrinsic/intrinsic_triangulation.h): Ptolemy flips keep a
// valid Delta-complex, are involutions, reproduce Euclidean distances on cyclic quads, and
// flipping to Delaunay keeps Gauss-Bonnet and leaves every edge Delaunay.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "ricci/intrinsic/intrinsic_triangulation.h"
#include "ricci/mesh/errors.h"
#include "ricci/mesh/primitives.h"
#include "ricci/metric/mesh_tables.h"
#include "ricci/metric/polish_e2.h"
#include "ricci/mesh/arrays.h"

namespace {

using ricci::IntrinsicTriangulation;

// Twins are an involution between different slots of opposite direction, and every edge's
// two halfedges point back to it.
void expect_valid(const IntrinsicTriangulation& tri) {
  for (size_t h = 0; h < tri.tail.size(); ++h) {
    const int t = tri.twin[h];
    ASSERT_NE(t, static_cast<int>(h));
    ASSERT_EQ(tri.twin[static_cast<size_t>(t)], static_cast<int>(h));
    ASSERT_EQ(tri.edge[static_cast<size_t>(t)], tri.edge[h]);
    ASSERT_EQ(tri.tail[static_cast<size_t>(t)], tri.head(static_cast<int>(h)));
  }
  for (int e = 0; e < tri.edge_count(); ++e) {
    ASSERT_EQ(tri.edge[static_cast<size_t>(tri.edge_halfedge[static_cast<size_t>(e)])], e);
  }
}

TEST(IntrinsicTriangulation, FromMeshIsValidWithItsEulerCharacteristic) {
  const ricci::Mesh mesh = ricci::make_genus_slab(4);
  const IntrinsicTriangulation tri =
      ricci::make_intrinsic_triangulation(mesh, ricci::mesh_edge_lengths(mesh));
  expect_valid(tri);
  EXPECT_EQ(ricci::euler_characteristic(tri), -6);
  EXPECT_TRUE(ricci::is_simplicial(tri));
}

TEST(IntrinsicTriangulation, RefusesABoundary) {
  const ricci::Mesh mesh = ricci::make_disk(2, 6);
  EXPECT_THROW((void)ricci::make_intrinsic_triangulation(mesh, ricci::mesh_edge_lengths(mesh)),
               ricci::InvalidInputError);
}

TEST(IntrinsicTriangulation, FlipTwiceRestoresLengthsAndFlipIsPtolemy) {
  const ricci::Mesh mesh = ricci::make_random_perturbed(ricci::make_icosphere(2), 0.3, 7);
  IntrinsicTriangulation tri =
      ricci::make_intrinsic_triangulation(mesh, ricci::mesh_edge_lengths(mesh));
  const Eigen::VectorXd before = tri.log_length;
  for (int e = 0; e < tri.edge_count(); e += 7) {
    const int h = tri.edge_halfedge[static_cast<size_t>(e)];
    const int t = tri.twin[static_cast<size_t>(h)];
    const auto len = [&](int s) {
      return std::exp(tri.log_length[tri.edge[static_cast<size_t>(s)]]);
    };
    const double ptolemy =
        (len(IntrinsicTriangulation::prev(h)) * len(IntrinsicTriangulation::prev(t)) +
         len(IntrinsicTriangulation::next(h)) * len(IntrinsicTriangulation::next(t))) /
        len(h);
    const int k = tri.tail[static_cast<size_t>(IntrinsicTriangulation::prev(h))];
    const int l = tri.tail[static_cast<size_t>(IntrinsicTriangulation::prev(t))];
    ricci::flip_edge(tri, e);
    expect_valid(tri);
    const int g = tri.edge_halfedge[static_cast<size_t>(e)];
    EXPECT_EQ(std::min(tri.tail[static_cast<size_t>(g)], tri.head(g)), std::min(k, l));
    EXPECT_EQ(std::max(tri.tail[static_cast<size_t>(g)], tri.head(g)), std::max(k, l));
    EXPECT_NEAR(std::exp(tri.log_length[e]), ptolemy, 1e-12 * ptolemy);
    ricci::flip_edge(tri, e);
    expect_valid(tri);
  }
  EXPECT_LT((tri.log_length - before).cwiseAbs().maxCoeff(), 1e-12);
}

// Four points on a circle: the Ptolemy flip gives the Euclidean length of the other diagonal.
TEST(IntrinsicTriangulation, CyclicQuadFlipIsEuclidean) {
  const double angles[4] = {0.1, 1.9, 3.0, 4.4};  // counter-clockwise on the unit circle
  Eigen::Vector2d p[4];
  for (int n = 0; n < 4; ++n) p[n] = {std::cos(angles[n]), std::sin(angles[n])};
  // A closed surface holding the quad: the doubled quad (two copies glued along the rim), i.e.
  // the boundary of a tetrahedron with vertices 0..3 and lengths of the planar quad.
  ricci::Mesh mesh;
  std::vector<ricci::VertexHandle> v;
  for (int n = 0; n < 4; ++n) v.push_back(mesh.add_vertex({p[n].x(), p[n].y(), 0.0}));
  mesh.add_face(v[0], v[1], v[2]);
  mesh.add_face(v[0], v[2], v[3]);
  mesh.add_face(v[0], v[3], v[1]);  // these two faces hold the "back" copy of the quad
  mesh.add_face(v[1], v[3], v[2]);
  Eigen::VectorXd lengths(static_cast<Eigen::Index>(mesh.n_edges()));
  for (auto e : mesh.edges()) {
    const auto a = mesh.from_vertex_handle(mesh.halfedge_handle(e, 0)).idx();
    const auto b = mesh.to_vertex_handle(mesh.halfedge_handle(e, 0)).idx();
    lengths[e.idx()] = (p[a] - p[b]).norm();
  }
  IntrinsicTriangulation tri = ricci::make_intrinsic_triangulation(mesh, lengths);
  const ricci::EdgeHandle diagonal = mesh.edge_handle(mesh.find_halfedge(v[0], v[2]));
  ricci::flip_edge(tri, diagonal.idx());
  EXPECT_NEAR(std::exp(tri.log_length[diagonal.idx()]), (p[1] - p[3]).norm(), 1e-14);
}

TEST(IntrinsicTriangulation, DelaunayFlipsKeepGaussBonnetAndLeaveEveryEdgeDelaunay) {
  for (int genus : {0, 1, 4}) {
    ricci::Mesh mesh = genus == 0   ? ricci::make_icosphere(3)
                       : genus == 1 ? ricci::make_torus(30, 8, 2.0, 0.5)
                                    : ricci::make_genus_slab(genus, 2, 2);
    mesh = ricci::make_random_perturbed(mesh, 0.4, 11);
    IntrinsicTriangulation tri =
        ricci::make_intrinsic_triangulation(mesh, ricci::mesh_edge_lengths(mesh));
    const Eigen::VectorXd u = Eigen::VectorXd::Zero(tri.vertex_count);
    const ricci::DelaunayFlipResult flipped = ricci::flip_to_delaunay(tri, u);
    ASSERT_TRUE(flipped.delaunay);
    EXPECT_GT(flipped.flips, 0) << genus;
    expect_valid(tri);
    EXPECT_EQ(ricci::euler_characteristic(tri), 2 - 2 * genus);
    for (int e = 0; e < tri.edge_count(); ++e)
      EXPECT_GE(ricci::delaunay_measure(tri, e, u), -1e-12);
    Eigen::MatrixX3d angles;
    ASSERT_TRUE(ricci::intrinsic_corner_angles(tri, u, angles));
    const Eigen::VectorXd K = ricci::intrinsic_curvature(tri, angles);
    EXPECT_NEAR(K.sum(), 2 * M_PI * (2 - 2 * genus), 1e-9) << genus;
    // Every face's angles sum to pi.
    EXPECT_LT((angles.rowwise().sum().array() - M_PI).abs().maxCoeff(), 1e-13);
  }
}

// Lawson's algorithm as flip_to_delaunay ran it before its first pass went edge-parallel: a
// stack of every edge, each tested at its turn on the triangulation as it then is.
std::vector<int> serial_lawson_flips(IntrinsicTriangulation& tri, const Eigen::VectorXd& u) {
  const int edges = tri.edge_count();
  std::vector<int> stack(static_cast<size_t>(edges)), log;
  std::vector<char> queued(static_cast<size_t>(edges), 1);
  for (int e = 0; e < edges; ++e) stack[static_cast<size_t>(e)] = e;
  while (!stack.empty()) {
    const int e = stack.back();
    stack.pop_back();
    queued[static_cast<size_t>(e)] = 0;
    if (!ricci::is_flippable(tri, e) || !(ricci::delaunay_measure(tri, e, u) < -1e-12)) continue;
    ricci::flip_edge(tri, e);
    log.push_back(e);
    const int h = tri.edge_halfedge[static_cast<size_t>(e)];
    const int t = tri.twin[static_cast<size_t>(h)];
    for (int s : {IntrinsicTriangulation::next(h), IntrinsicTriangulation::prev(h),
                  IntrinsicTriangulation::next(t), IntrinsicTriangulation::prev(t)}) {
      const int f = tri.edge[static_cast<size_t>(s)];
      if (!queued[static_cast<size_t>(f)]) {
        queued[static_cast<size_t>(f)] = 1;
        stack.push_back(f);
      }
    }
  }
  return log;
}

// flip_to_delaunay tests every edge first in parallel and again only those whose faces a flip
// changed: the same flips in the same order as the serial algorithm, hence the same
// triangulation, under scale factors that cascade flips over the whole surface.
TEST(IntrinsicTriangulation, ParallelFirstPassKeepsLawsonsSequence) {
  const ricci::Mesh mesh =
      ricci::make_random_perturbed(ricci::make_genus_slab(3, 3, 3), 0.4, 7);
  const IntrinsicTriangulation initial =
      ricci::make_intrinsic_triangulation(mesh, ricci::mesh_edge_lengths(mesh));
  ASSERT_GT(initial.edge_count(), 1000);  // split over the threads
  for (double amplitude : {0.0, 0.5, 2.0}) {
    Eigen::VectorXd u(initial.vertex_count);
    for (int v = 0; v < initial.vertex_count; ++v) u[v] = amplitude * std::sin(0.37 * v);
    IntrinsicTriangulation parallel = initial, serial = initial;
    std::vector<int> log;
    ASSERT_TRUE(ricci::flip_to_delaunay(parallel, u, 1e-12, ricci::kMaxFlipsPerEdge, &log).delaunay);
    const std::vector<int> expected = serial_lawson_flips(serial, u);
    EXPECT_GT(log.size(), 100u) << amplitude;
    EXPECT_EQ(log, expected) << amplitude;
    EXPECT_EQ(parallel.tail, serial.tail);
    EXPECT_EQ(parallel.twin, serial.twin);
    EXPECT_EQ(parallel.edge, serial.edge);
    EXPECT_EQ(parallel.log_length, serial.log_length);
  }
}

// The polish at 1.6M faces runs on to_mesh_tables before the mesh exists: the tables must be
// the mesh's own (same faces, corner order and edge numbering), the mesh of the tables
// to_mesh's, and a polish on them the polish on the mesh, bit for bit.
TEST(IntrinsicTriangulation, MeshTablesAreToMeshsTablesAndPolishTheSame) {
  const ricci::Mesh mesh =
      ricci::make_random_perturbed(ricci::make_genus_slab(2, 2, 2), 0.4, 5);
  IntrinsicTriangulation tri =
      ricci::make_intrinsic_triangulation(mesh, ricci::mesh_edge_lengths(mesh));
  Eigen::VectorXd u = Eigen::VectorXd::Zero(tri.vertex_count);
  for (int v = 0; v < tri.vertex_count; ++v) u[v] = 0.3 * std::sin(1.7 * v);
  ASSERT_GT(ricci::flip_to_delaunay(tri, u).flips, 0);
  ASSERT_TRUE(ricci::is_simplicial(tri));
  const Eigen::MatrixX3d V = ricci::to_arrays(mesh).V;
  const ricci::IntrinsicMesh built = ricci::to_mesh(tri, u, V);
  const ricci::MeshTables expected = ricci::build_mesh_tables(built.mesh);
  const ricci::MeshTables tables = ricci::to_mesh_tables(tri);
  EXPECT_EQ(tables.face_vertices, expected.face_vertices);
  EXPECT_EQ(tables.face_edges, expected.face_edges);
  EXPECT_EQ(tables.edge_vertices, expected.edge_vertices);
  EXPECT_EQ(tables.valence, expected.valence);
  EXPECT_EQ(tables.is_boundary_vertex, expected.is_boundary_vertex);
  EXPECT_EQ(tables.euler_characteristic, -2);
  const Eigen::VectorXd lengths = ricci::table_edge_lengths(tri, tables, u);
  std::vector<int> edge_of;
  const ricci::Mesh again = ricci::mesh_of_tables(tables, V, edge_of);
  ASSERT_EQ(again.n_edges(), built.mesh.n_edges());
  EXPECT_EQ(ricci::to_arrays(again).F, ricci::to_arrays(built.mesh).F);
  for (size_t e = 0; e < edge_of.size(); ++e) {
    ASSERT_EQ(edge_of[e], static_cast<int>(e)) << "to_mesh_tables numbers edges as the mesh";
  }
  EXPECT_EQ(ricci::by_mesh_edge(lengths, edge_of), built.lengths);

  // A target 1e-9 from the curvature of these lengths: both polishes meet it alike.
  Eigen::MatrixX3d angles;
  ASSERT_TRUE(ricci::intrinsic_corner_angles(tri, u, angles));
  Eigen::VectorXd target = ricci::intrinsic_curvature(tri, angles);
  for (int v = 0; v < tri.vertex_count; ++v) target[v] += 1e-9 * std::cos(0.9 * v);
  target.array() -= (target.sum() - 2 * M_PI * -2) / tri.vertex_count;  // Gauss-Bonnet
  const ricci::PolishE2Result on_mesh = ricci::polish_e2_lengths(built.mesh, built.lengths, target);
  const ricci::PolishE2Result on_tables = ricci::polish_e2_lengths(tables, lengths, target);
  EXPECT_GT(on_mesh.error_before, 1e-10);
  EXPECT_LT(on_mesh.error_after, 1e-13);
  EXPECT_EQ(on_tables.error_after, on_mesh.error_after);
  EXPECT_EQ(ricci::by_mesh_edge(on_tables.lengths, edge_of), on_mesh.lengths);
  EXPECT_EQ(ricci::by_mesh_edge(on_tables.lengths_low, edge_of), on_mesh.lengths_low);
}

// mesh_of_tables on tables whose edges the new mesh numbers otherwise (a mesh after flips,
// which keep edge indices): edge_of maps each table edge to the new mesh's edge between the
// same two vertices, and by_mesh_edge moves values along it.
TEST(IntrinsicTriangulation, MeshOfTablesMapsEveryEdgeToItsEnds) {
  ricci::Mesh mesh = ricci::make_random_perturbed(ricci::make_genus_slab(2, 2, 2), 0.4, 5);
  int flips = 0;
  for (auto e : mesh.edges()) {
    if (e.idx() % 7 == 0 && mesh.is_flip_ok(e)) {
      mesh.flip(e);
      ++flips;
    }
  }
  ASSERT_GT(flips, 5);
  const ricci::MeshTables tables = ricci::build_mesh_tables(mesh);
  std::vector<int> edge_of;
  const ricci::Mesh again = ricci::mesh_of_tables(tables, ricci::to_arrays(mesh).V, edge_of);
  ASSERT_EQ(edge_of.size(), again.n_edges());
  Eigen::VectorXd numbers(tables.num_edges());
  bool identity = true;
  for (int e = 0; e < tables.num_edges(); ++e) {
    const int to = edge_of[static_cast<size_t>(e)];
    identity = identity && to == e;
    ASSERT_GE(to, 0);
    const auto h = again.halfedge_handle(again.edge_handle(static_cast<unsigned>(to)), 0);
    const int a = again.from_vertex_handle(h).idx(), b = again.to_vertex_handle(h).idx();
    EXPECT_EQ(std::minmax(a, b), std::minmax(tables.edge_vertices(e, 0), tables.edge_vertices(e, 1)));
    numbers[e] = e;
  }
  EXPECT_FALSE(identity);
  const Eigen::VectorXd moved = ricci::by_mesh_edge(numbers, edge_of);
  for (int e = 0; e < tables.num_edges(); ++e) EXPECT_EQ(moved[edge_of[static_cast<size_t>(e)]], e);
}

}  // namespace
