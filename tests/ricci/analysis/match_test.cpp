// Surface matching (Algorithm 8): a planar strip and a plate with holes against their isometric
// bendings onto a cylinder come back as the identity (the vertex correspondence within 0.1% of
// the diagonal), one-to-one; two triangulations of one plate match with a small shape error;
// bad input is refused.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include <ricci/analysis/match.h>
#include <ricci/mesh/errors.h>
#include <ricci/mesh/primitives.h>
#include <ricci/metric/mesh_tables.h>

#include "ricci/analysis/analysis_meshes.h"
#include "ricci/analysis/match_internal.h"
#include "ricci/analysis/module_internal.h"
#include "ricci/test_meshes.h"

namespace ricci {
namespace {

using testing::TestCircle;

/// The plane z = 0 rolled onto the cylinder of radius `radius` about the line x = 0, z =
/// radius: an isometry of the plane onto the cylinder.
Mesh rolled(const Mesh& flat, double radius) {
  return testing::mapped(flat, [radius](const Eigen::Vector3d& p) {
    const double angle = p.x() / radius;
    return Eigen::Vector3d(radius * std::sin(angle), p.y(), radius * (1 - std::cos(angle)));
  });
}

/// The interior vertex closest to (x, y).
int vertex_near(const Mesh& mesh, double x, double y) {
  int best = -1;
  double best_d = 1e300;
  for (VertexHandle v : mesh.vertices()) {
    if (mesh.is_boundary(v)) continue;
    const double d = std::hypot(mesh.point(v)[0] - x, mesh.point(v)[1] - y);
    if (d < best_d) best_d = d, best = v.idx();
  }
  return best;
}

/// The map is one-to-one and sends each vertex to its own copy within `tolerance` of the
/// diagonal.
void expect_identity(const MatchResult& r, double tolerance) {
  EXPECT_EQ(r.flipped_faces, 0);
  EXPECT_EQ(r.flipped_faces_b, 0);
  EXPECT_LT(r.correspondence_error, tolerance);
  for (const MapPoint& p : r.map) {
    ASSERT_GE(p.face, 0);
    EXPECT_NEAR(p.weights.sum(), 1.0, 1e-12);
    EXPECT_GE(p.weights.minCoeff(), 0.0);
  }
}

const std::vector<TestCircle> kTwoHoles = {{-0.35, 0.1, 0.2}, {0.4, -0.1, 0.15}};
const std::vector<TestCircle> kThreeHoles = {
    {-0.4, 0.2, 0.18}, {0.4, 0.25, 0.15}, {0.0, -0.45, 0.2}};

TEST(Match, StripRolledOntoCylinderIsTheIdentity) {
  const Mesh flat = make_planar_grid(60, 20, 3.0, 1.0);
  const Mesh bent = rolled(flat, 1.0);  // 3 radians of the cylinder
  const MatchResult r = match_surfaces(flat, bent);
  EXPECT_EQ(r.domain, "rectangle");
  EXPECT_EQ(r.a.corners, (std::vector<int>{0, 60, 1280, 1220}));
  EXPECT_EQ(r.b.corners, r.a.corners);
  expect_identity(r, 1e-3);
  // The positions differ (the strip is bent): eq. (13) sees the bending, not the map.
  EXPECT_GT(r.shape_error, 0.05);
  // A strip against itself is matched exactly.
  const MatchResult self = match_surfaces(flat, flat);
  EXPECT_LT(self.shape_error, 1e-9);
}

TEST(Match, StripWithFeatureUsesTheUnitDisk) {
  const Mesh flat = make_planar_grid(60, 20, 3.0, 1.0);
  const Mesh bent = rolled(flat, 1.0);
  MatchOptions options;
  // Off the middle line: the shortest path to the boundary is unique.
  options.feature_a = options.feature_b = vertex_near(flat, 1.5, 0.3);
  const MatchResult r = match_surfaces(flat, bent, options);
  EXPECT_EQ(r.domain, "unit disk");
  EXPECT_EQ(r.a.feature, options.feature_a);
  expect_identity(r, 1e-3);
}

TEST(Match, DiskAgainstItsConformalImageIsTheIdentity) {
  // The unit disk and its stereographic image on the sphere (conformal, not isometric): the
  // disk maps with the same centre differ by nothing but discretisation.
  const Mesh flat = testing::circle_domain_mesh({}, 0.05);
  const Mesh cap =
      testing::mapped(flat, [](const Eigen::Vector3d& p) { return testing::onto_sphere(p, 1.5); });
  MatchOptions options;
  options.feature_a = options.feature_b = vertex_near(flat, 0.2, 0.1);
  const MatchResult r = match_surfaces(flat, cap, options);
  EXPECT_EQ(r.domain, "unit disk");
  expect_identity(r, 1e-3);
}

TEST(Match, PlateWithHolesRolledIsTheIdentity) {
  for (const auto& holes : {kTwoHoles, kThreeHoles}) {
    const Mesh flat = testing::circle_domain_mesh(holes, 0.05);
    const Mesh bent = rolled(flat, 0.8);
    const MatchResult r = match_surfaces(flat, bent);
    EXPECT_EQ(r.domain, "cone star");
    EXPECT_EQ(r.a.loop_order.size(), holes.size() + 1);
    EXPECT_EQ(r.a.loop_order, r.b.loop_order);
    // Algorithm 8's pieces: a quadrilateral round each hole and the central piece, glued
    // along the loops round the holes (a seam in the wrong place would move the vertices on it).
    EXPECT_EQ(r.pieces, static_cast<int>(holes.size()) + 1);
    expect_identity(r, 1e-3);
    // One convex piece per surface: the same map within the discretisation.
    MatchOptions one;
    one.decompose = false;
    const MatchResult single = match_surfaces(flat, bent, one);
    EXPECT_EQ(single.pieces, 1);
    expect_identity(single, 1e-3);
  }
}

TEST(Match, HyperbolicPlateWithHolesRolledIsTheIdentity) {
  MatchOptions options;
  options.method = MatchMethod::hyperbolic;
  for (const auto& holes : {kTwoHoles, kThreeHoles}) {
    const Mesh flat = testing::circle_domain_mesh(holes, 0.05);
    const Mesh bent = rolled(flat, 0.8);
    const MatchResult r = match_surfaces(flat, bent, options);
    EXPECT_EQ(r.domain, "klein polygon");
    EXPECT_EQ(r.a.metric, "inversive-distance");
    // Every loop is met by the cut tree: 2 n corners for n cuts, n + 1 loops.
    EXPECT_EQ(r.a.loop_order.size(), 2 * holes.size());
    EXPECT_EQ(r.a.loop_order, r.b.loop_order);
    expect_identity(r, 1e-3);
    // B's sides are bowed out: A's boundary vertices may fall just outside B's chords.
    EXPECT_LT(r.snap_distance, 1e-5);  // the flows agree to their tolerance
  }
}

TEST(Match, TextureErrorOfEquation14) {
  // Colours painted on the flat plate and carried by the vertex correspondence to its bending:
  // the identity map sees no texture error; a red shift of 0.1 everywhere on B is 0.1 over
  // B's mean colour norm.
  const Mesh flat = testing::circle_domain_mesh(kTwoHoles, 0.05);
  const Mesh bent = rolled(flat, 0.8);
  Eigen::MatrixX3d colours(flat.n_vertices(), 3);
  for (VertexHandle v : flat.vertices()) {
    const auto p = flat.point(v);
    colours.row(v.idx()) << 0.5 + 0.4 * p[0], 0.5 + 0.4 * p[1], 0.3;
  }
  const MatchResult r = match_surfaces(flat, bent);
  EXPECT_LT(texture_error(flat, bent, r, colours, colours), 1e-3);
  Eigen::MatrixX3d shifted = colours;
  shifted.col(0).array() += 0.1;
  const MatchResult self = match_surfaces(flat, flat);
  double norm = 0, area = 0;  // B's area-weighted mean colour norm
  for (FaceHandle f : flat.faces()) {
    double sum = 0;
    for (VertexHandle v : flat.fv_range(f)) sum += shifted.row(v.idx()).norm();
    norm += flat.calc_face_area(f) * sum / 3;
    area += flat.calc_face_area(f);
  }
  EXPECT_NEAR(texture_error(flat, flat, self, colours, shifted), 0.1 / (norm / area), 1e-9);
  EXPECT_THROW((void)texture_error(flat, bent, r, colours.topRows(3), colours), InvalidInputError);
  EXPECT_THROW(
      (void)texture_error(flat, bent, r, colours, Eigen::MatrixX3d::Zero(colours.rows(), 3)),
      InvalidInputError);
}

TEST(Match, HyperbolicTwoTriangulationsOfOnePlate) {
  const Mesh a = testing::circle_domain_mesh(kThreeHoles, 0.05, 1);
  const Mesh b = testing::circle_domain_mesh(kThreeHoles, 0.04, 2);
  MatchOptions options;
  options.method = MatchMethod::hyperbolic;
  const MatchResult r = match_surfaces(a, b, options);
  EXPECT_EQ(r.flipped_faces, 0);
  EXPECT_EQ(r.flipped_faces_b, 0);
  // The same plane, no feature to choose: each point lands near itself.
  EXPECT_LT(r.shape_error, 0.01);
}

TEST(Match, TwoTriangulationsOfOnePlate) {
  const Mesh a = testing::circle_domain_mesh(kTwoHoles, 0.05, 1);
  const Mesh b = testing::circle_domain_mesh(kTwoHoles, 0.04, 2);
  MatchOptions options;
  options.feature_a = vertex_near(a, 0.0, 0.5);
  options.feature_b = vertex_near(b, 0.0, 0.5);
  const MatchResult r = match_surfaces(a, b, options);
  EXPECT_EQ(r.flipped_faces, 0);
  EXPECT_EQ(r.flipped_faces_b, 0);
  EXPECT_TRUE(std::isnan(r.correspondence_error));
  // The same plane: each point should land near itself.
  EXPECT_LT(r.shape_error, 0.01);
}

/// A plate with five holes and its copy stretched by 1.2 along x and bent (z += 0.3 y^2): not
/// an isometry.
std::pair<Mesh, Mesh> five_hole_plate_and_deformed_copy() {
  const std::vector<TestCircle> holes = {
      {0, 0, 0.22}, {0.55, 0, 0.14}, {-0.4, 0.5, 0.12}, {-0.45, -0.45, 0.1}, {0.2, -0.7, 0.08}};
  Mesh a = testing::circle_domain_mesh(holes, 0.05);
  Mesh b = testing::mapped(a, [](const Eigen::Vector3d& p) {
    return Eigen::Vector3d(1.2 * p.x(), p.y(), p.z() + 0.3 * p.y() * p.y());
  });
  return {a, b};
}

/// One-to-one: no reversed face of A or B, no flattened ear (the plate has none), every point
/// inside B's domain.
void expect_one_to_one(const MatchResult& r) {
  EXPECT_EQ(r.flipped_faces, 0);
  EXPECT_EQ(r.flipped_faces_b, 0);
  EXPECT_EQ(r.flattened_ears, 0);
  EXPECT_LT(r.snap_distance, 1e-9);
  for (const MapPoint& p : r.map) {
    ASSERT_GE(p.face, 0);
    EXPECT_GE(p.weights.minCoeff(), 0.0);
  }
}

TEST(Match, HyperbolicFiveHolePlateAgainstItsStretchedAndBentCopyIsOneToOne) {
  const auto [a, b] = five_hole_plate_and_deformed_copy();
  MatchOptions options;
  options.method = MatchMethod::hyperbolic;
  expect_one_to_one(match_surfaces(a, b, options));
}

/// Three holes of radii 0.150, 0.151 and 0.152 round the centre, and a copy stretched by 1.1
/// along x whose smallest hole grows by about 3% (a bump about its centre): the loops' length
/// ranks differ on A and B (same connectivity: the vertex correspondence is the answer).
std::pair<Mesh, Mesh> three_holes_of_about_one_length() {
  std::vector<TestCircle> holes;
  for (int k = 0; k < 3; ++k) {
    const double angle = M_PI / 2 + 2 * M_PI * k / 3;
    holes.push_back({0.45 * std::cos(angle), 0.45 * std::sin(angle), 0.150 + 0.001 * k});
  }
  Mesh a = testing::circle_domain_mesh(holes, 0.05);
  const Eigen::Vector2d c(holes[0].x, holes[0].y);
  Mesh b = testing::mapped(a, [c](const Eigen::Vector3d& p) {
    const Eigen::Vector2d d = p.head<2>() - c;
    const Eigen::Vector2d q = c + d * (1 + 0.03 * std::exp(-d.squaredNorm() / 0.02));
    return Eigen::Vector3d(1.1 * q.x(), q.y(), p.z());
  });
  return {a, b};
}

/// The rays leave the feature in another order of ranks on the three holes of about one length;
/// the loops pair by their order round the feature (the centre) instead (lengths within 5%), and
/// the map is one-to-one and near the vertex correspondence.
TEST(Match, EuclideanPairsLoopsOfAboutTheSameLengthByTheirOrderRoundTheFeature) {
  const auto [a, b] = three_holes_of_about_one_length();
  MatchOptions options;  // the centre on both (the same vertex index)
  options.feature_a = options.feature_b = vertex_near(a, 0.0, 0.0);
  MatchOptions strict = options;
  strict.loop_length_tolerance = 0;  // ranks only: refused
  EXPECT_THROW((void)match_surfaces(a, b, strict), InvalidInputError);
  const MatchResult r = match_surfaces(a, b, options);
  EXPECT_NE(r.a.loop_order, r.b.loop_order);
  expect_one_to_one(r);
  // 5.3% (the stretch and the bump are not conformal); paired by rank order it was 39%.
  EXPECT_LT(r.correspondence_error, 0.1);
}

/// The hyperbolic method on the same pair: B's loops pair with A's by their hyperbolic lengths
/// and distances, not by 3D length rank (which sends each hole onto another), and the map is
/// one-to-one and near the vertex correspondence.
TEST(Match, HyperbolicPairsLoopsOfAboutTheSameLengthByTheirConformalInvariants) {
  const auto [a, b] = three_holes_of_about_one_length();
  MatchOptions options;
  options.method = MatchMethod::hyperbolic;
  const MatchResult r = match_surfaces(a, b, options);
  expect_one_to_one(r);
  EXPECT_LT(r.correspondence_error, 0.1);
}

/// The cone star on the same pair: A's boundary is placed on B's boundary polygon (fill_inside),
/// not on the circle between B's vertices, which reversed 40 thin faces of A by the circle (77
/// before the radial carry).
TEST(Match, EuclideanFiveHolePlateAgainstItsStretchedAndBentCopyIsOneToOne) {
  const auto [a, b] = five_hole_plate_and_deformed_copy();
  const MatchResult r = match_surfaces(a, b, {});
  // A piece for each hole but two (rays to other holes run one edge from them, leaving no
  // room for a loop round them) and the central one.
  EXPECT_EQ(r.pieces, 4);
  expect_one_to_one(r);
}

/// The cone star's rays forced into a given cyclic order round the feature (what the cone star
/// does when the two surfaces' free rays pass other sides of the holes): the order asked for,
/// the free one or two holes swapped, comes out, and the cut is a disk out along each ray,
/// round its loop and back (detail::star_from_rays checks the walk); an order of the wrong
/// length is refused.
TEST(Match, ConeStarRaysLeaveTheFeatureInTheOrderAskedFor) {
  const auto [a, b] = five_hole_plate_and_deformed_copy();
  (void)b;
  const MeshTables tables = build_mesh_tables(a);
  const EdgeLengths lengths = mesh_edge_lengths(a);  // a plane: a flat metric
  const int p = vertex_near(a, 0.3, 0.45);
  const detail::Star free = detail::cone_star(a, tables, p, lengths, "A", false);
  ASSERT_EQ(free.loop_order.size(), 6u);
  EXPECT_EQ(free.loop_order[0], 0);
  std::vector<int> swapped = free.loop_order;
  std::swap(swapped[2], swapped[4]);
  for (const std::vector<int>& order : {free.loop_order, swapped}) {
    const detail::Star star = detail::ordered_star(a, tables, p, lengths, order, "A");
    EXPECT_EQ(star.loop_order, order);
    EXPECT_EQ(star.corners.size(), 3 * order.size());
    check_disk(star.sliced, "forced star");
  }
  EXPECT_THROW((void)detail::ordered_star(a, tables, p, lengths, {0, 1, 2}, "A"), TopologyError);
}

/// The cut search shared by the annulus, the cone star and the loop tree, on the annulus
/// 0.3 < |z| < 1 with 3D edge lengths: the shortest path from the outer loop to the inner one is
/// a radius (length 0.7 within the mesh's zigzag); with the interior right of x = -0.2 blocked
/// it stays left of it; with the inner loop's neighbours blocked all round there is none.
TEST(Match, ShortestPathToLoopIsTheRadiusOfAnAnnulusAndGoesAroundBlockedVertices) {
  const Mesh annulus = testing::circle_domain_mesh({{0.0, 0.0, 0.3}}, 0.04);
  const MeshTables tables = build_mesh_tables(annulus);
  ASSERT_EQ(tables.boundary_loops.size(), 2u);
  const int outer =
      annulus.point(annulus.vertex_handle(tables.boundary_loops[0][0])).norm() > 0.5 ? 0 : 1;
  std::vector<int> loop_of(annulus.n_vertices(), -1);
  for (int k = 0; k < 2; ++k) {
    for (int v : tables.boundary_loops[k]) loop_of[v] = k;
  }
  EdgeLengths lengths(static_cast<Eigen::Index>(annulus.n_edges()));
  for (EdgeHandle e : annulus.edges()) lengths[e.idx()] = annulus.calc_edge_length(e);
  const auto inner = [outer](int loop) { return loop == 1 - outer; };
  const auto length_of = [&](const std::vector<HalfedgeHandle>& path) {
    double sum = 0;
    for (HalfedgeHandle h : path) sum += lengths[annulus.edge_handle(h).idx()];
    return sum;
  };
  std::vector<char> used(annulus.n_vertices(), 0);
  const auto path = detail::shortest_path_to_loop(annulus, loop_of, lengths,
                                                  tables.boundary_loops[outer], inner, used);
  ASSERT_FALSE(path.empty());
  EXPECT_EQ(loop_of[annulus.from_vertex_handle(path.front()).idx()], outer);
  EXPECT_EQ(loop_of[annulus.to_vertex_handle(path.back()).idx()], 1 - outer);
  for (size_t i = 0; i + 1 < path.size(); ++i) {
    EXPECT_EQ(loop_of[annulus.to_vertex_handle(path[i]).idx()], -1);
  }
  EXPECT_GT(length_of(path), 0.7 - 1e-9);
  EXPECT_LT(length_of(path), 0.7 * 1.08);
  // Interior vertices right of x = -0.2 blocked, the sources left of it: the path keeps left
  // of it and is still a radius (along the negative x axis).
  for (VertexHandle v : annulus.vertices()) {
    used[v.idx()] = loop_of[v.idx()] < 0 && annulus.point(v)[0] > -0.2;
  }
  std::vector<int> left;
  for (int v : tables.boundary_loops[outer]) {
    if (annulus.point(annulus.vertex_handle(v))[0] <= -0.2) left.push_back(v);
  }
  const auto detour = detail::shortest_path_to_loop(annulus, loop_of, lengths, left, inner, used);
  ASSERT_FALSE(detour.empty());
  for (HalfedgeHandle h : detour) EXPECT_LE(annulus.point(annulus.to_vertex_handle(h))[0], -0.2);
  EXPECT_GT(length_of(detour), 0.7 - 1e-9);
  EXPECT_LT(length_of(detour), 0.7 * 1.08);
  // The inner loop's ring of neighbours blocked: unreachable.
  std::fill(used.begin(), used.end(), 0);
  for (int v : tables.boundary_loops[1 - outer]) {
    for (VertexHandle w : annulus.vv_range(annulus.vertex_handle(v))) {
      if (loop_of[w.idx()] < 0) used[w.idx()] = 1;
    }
  }
  EXPECT_TRUE(detail::shortest_path_to_loop(annulus, loop_of, lengths, tables.boundary_loops[outer],
                                            inner, used)
                  .empty());
}

TEST(Match, BadInput) {
  const Mesh disk = make_planar_grid(10, 10, 1.0, 1.0);
  const Mesh plate = testing::circle_domain_mesh(kTwoHoles, 0.1);
  EXPECT_THROW((void)match_surfaces(disk, plate), InvalidInputError);
  EXPECT_THROW((void)match_surfaces(testing::torus(20, 10), testing::torus(20, 10)),
               InvalidInputError);
  MatchOptions options;
  options.feature_a = 5;  // only one side
  EXPECT_THROW((void)match_surfaces(plate, plate, options), InvalidInputError);
  options.feature_b = 100000;
  EXPECT_THROW((void)match_surfaces(plate, plate, options), InvalidInputError);
  options.feature_a = options.feature_b = 0;  // (0, 0): a corner, on the boundary
  EXPECT_THROW((void)match_surfaces(disk, disk, options), InvalidInputError);
  options = {};
  options.method = MatchMethod::hyperbolic;  // needs three or more loops
  EXPECT_THROW((void)match_surfaces(disk, disk, options), InvalidInputError);
  const Mesh annulus = testing::circle_domain_mesh({{0.0, 0.0, 0.3}}, 0.1);
  EXPECT_THROW((void)match_surfaces(annulus, annulus, options), InvalidInputError);
  options.feature_a = options.feature_b = vertex_near(plate, 0.0, 0.5);
  EXPECT_THROW((void)match_surfaces(plate, plate, options), InvalidInputError);
  EXPECT_THROW((void)parse_match_method("spherical"), InvalidInputError);
}

TEST(Match, MapText) {
  const Mesh flat = make_planar_grid(8, 4, 2.0, 1.0);
  const MatchResult r = match_surfaces(flat, rolled(flat, 1.0));
  std::istringstream in(surface_map_text(r, 45, 64));
  std::string magic;
  int version = 0, va = 0, vb = 0, fb = 0;
  in >> magic >> version >> va >> vb >> fb;
  EXPECT_EQ(magic, "msp-map");
  EXPECT_EQ(version, 1);
  EXPECT_EQ(va, 45);
  int lines = 0, face = 0, i = 0, j = 0, k = 0;
  double wi = 0, wj = 0, wk = 0;
  while (in >> face >> i >> j >> k >> wi >> wj >> wk) {
    EXPECT_TRUE(face >= 0 && face < fb);
    EXPECT_NEAR(wi + wj + wk, 1.0, 1e-12);
    ++lines;
  }
  EXPECT_EQ(lines, va);
}

}  // namespace
}  // namespace ricci
