// Watertight tessellation of manifold splines: welded samples, exact normals, atlas uvs, and the
// topology check itself on hand-made soups.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "ricci/mesh/errors.h"
#include "ricci/topology/slice.h"
#include "spline/fit/fit.h"
#include "spline/manifold/manifold_fixtures.h"
#include "spline/tessellate/dihedral.h"
#include "spline/tessellate/tessellate.h"
#include "spline/tessellate/tessellate_fill.h"

namespace spline {
namespace {

using testing::small_atlas;
using testing::small_space;

TessellationOptions options(int density, int threads) {
  TessellationOptions o;
  o.density = density;
  o.threads = threads;
  return o;
}

struct Case {
  const ricci::Mesh* mesh;
  ManifoldSpline spline;
};

Case make_case(const std::string& model, int degree = 3, int faces = 300) {
  const auto space = small_space(model, degree, faces);
  const ricci::Mesh& mesh = small_atlas(model, faces).problem.mesh;
  return {&mesh, {space, piecewise_linear_control_points(*space, mesh)}};
}

// Density d, 2 threads, every face outside the domain or covered by `rim` skipped.
TessellationOptions without_rim_faces(const Case& c, const Rim& rim, int d) {
  TessellationOptions o = options(d, 2);
  o.skip_faces.assign(c.mesh->n_faces(), 0);
  for (int f = 0; f < static_cast<int>(c.mesh->n_faces()); ++f)
    o.skip_faces[f] = !c.spline.space->in_domain(f);
  for (int f : rim.covered_faces) o.skip_faces[f] = 1;
  return o;
}

int interior_edges(const ricci::Mesh& mesh, const ManifoldSplineSpace& space) {
  int count = 0;
  for (auto e : mesh.edges()) {
    const auto f0 = mesh.face_handle(mesh.halfedge_handle(e, 0));
    const auto f1 = mesh.face_handle(mesh.halfedge_handle(e, 1));
    count +=
        f0.is_valid() && f1.is_valid() && space.in_domain(f0.idx()) && space.in_domain(f1.idx());
  }
  return count;
}

// The counts of a welded grid: V + E (d - 1) + F (d - 1)(d - 2) / 2 samples, F d^2 triangles.
TEST(Tessellate, SamplesEveryVertexAndEdgeOnce) {
  const Case c = make_case("genus1.off");
  const auto& space = *c.spline.space;
  for (int d : {1, 2, 5}) {
    const Tessellation t = tessellate(c.spline, *c.mesh, options(d, 2));
    const int F = space.domain_face_count();
    const long V = static_cast<long>(c.mesh->n_vertices()),
               E = static_cast<long>(c.mesh->n_edges());
    EXPECT_EQ(t.positions.rows(), V + E * (d - 1) + F * (d - 1) * (d - 2) / 2) << d;
    EXPECT_EQ(static_cast<long>(t.triangles.size()), static_cast<long>(F) * d * d);
  }
}

// A torus has no cone: the tessellation is a closed surface of genus 1, with no duplicates.
TEST(Tessellate, GenusOneIsClosed) {
  const Case c = make_case("genus1.off");
  const Tessellation t = tessellate(c.spline, *c.mesh, options(4, 2));
  const WatertightReport r = check_watertight(t.triangles, t.positions);
  EXPECT_TRUE(r.closed(1)) << r.boundary_edges << " " << r.euler_characteristic;
  EXPECT_EQ(r.duplicate_positions, 0);
  EXPECT_FALSE(r.closed(0));
}

// Genus 2 without filling: one rim (the cone's one-ring) of rim_edges * d boundary edges.
TEST(Tessellate, GenusTwoLeavesTheConeHoleOpen) {
  const Case c = make_case("genus2.off");
  const int d = 3;
  const Tessellation t = tessellate(c.spline, *c.mesh, options(d, 2));
  const WatertightReport r = check_watertight(t.triangles, t.positions);
  EXPECT_TRUE(r.matches(2, 1));
  EXPECT_FALSE(r.closed(2));
  int rim_edges = 0;
  for (auto e : c.mesh->edges()) {
    const auto f0 = c.mesh->face_handle(c.mesh->halfedge_handle(e, 0));
    const auto f1 = c.mesh->face_handle(c.mesh->halfedge_handle(e, 1));
    rim_edges += c.spline.space->in_domain(f0.idx()) != c.spline.space->in_domain(f1.idx());
  }
  EXPECT_EQ(r.boundary_edges, rim_edges * d);
}

// An open model keeps its boundary loops (plus the cone hole when it has one).
TEST(Tessellate, OpenModelKeepsItsBoundary) {
  const Case c = make_case("genus1_hole.off");
  const auto& problem = small_atlas("genus1_hole.off", 300).problem;
  const Tessellation t = tessellate(c.spline, *c.mesh, options(3, 2));
  const WatertightReport r = check_watertight(t.triangles, t.positions);
  const int cone_hole = problem.cone >= 0 ? 1 : 0;
  EXPECT_TRUE(r.matches(problem.genus, problem.boundary_loops + cone_hole))
      << r.boundary_loops << " loops, chi " << r.euler_characteristic;
}

// The weld hides no crack: an edge sample evaluated from the face across the edge (its own
// neighbourhood chart) lands on the same point, and edge_sample indexes it from both sides.
TEST(Tessellate, EdgeSamplesAgreeFromBothFaces) {
  const Case c = make_case("genus2.off");
  const int d = 4;
  const Tessellation t = tessellate(c.spline, *c.mesh, options(d, 2));
  const auto& space = *c.spline.space;
  const double diag = (t.positions.colwise().maxCoeff() - t.positions.colwise().minCoeff()).norm();
  int checked = 0;
  double worst = 0.0;
  for (int f : space.domain_faces()) {
    for (int k = 0; k < 3; ++k) {
      const int g = space.neighbour(f, k);
      if (g < 0 || !space.in_domain(g)) continue;
      // The corner of g opposite the shared edge.
      int kg = -1;
      for (int m = 0; m < 3; ++m)
        if (space.neighbour(g, m) == f) kg = m;
      ASSERT_GE(kg, 0);
      for (int i = 0; i <= d; ++i) {
        const int p = t.edge_sample(f, k, i);
        ASSERT_EQ(p, t.edge_sample(g, kg, d - i));  // g walks the edge the other way
        Eigen::Vector3d b = Eigen::Vector3d::Zero();
        b[(kg + 1) % 3] = 1.0 - double(d - i) / d;
        b[(kg + 2) % 3] = double(d - i) / d;
        const Eigen::Vector3d other = c.spline.evaluate({g, b}).position;
        worst = std::max(worst, (other - t.positions.row(p).transpose()).norm());
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 100);
  EXPECT_LT(worst, 1e-10 * diag);
}

// Normals are du x dv: orthogonal to central differences of F across the face, unit length,
// and facing like the triangles (the input's orientation) but for a crease's fold or two.
TEST(Tessellate, NormalsComeFromTheDerivatives) {
  const Case c = make_case("genus2.off");
  const Tessellation t = tessellate(c.spline, *c.mesh, options(3, 2));
  const double h = 1e-5;
  double worst = 0.0;
  for (Eigen::Index i = 0; i < t.positions.rows(); i += 7) {
    const DomainPoint p = t.parameters[static_cast<std::size_t>(i)];
    const Eigen::Vector3d n = t.normals.row(i).transpose();
    ASSERT_NEAR(n.norm(), 1.0, 1e-12);
    // Directions inside the face from p (one-sided at corners and edges).
    const Eigen::Vector3d centre = Eigen::Vector3d::Constant(1.0 / 3.0);
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d dir =
          (centre - p.barycentric + 0.2 * (Eigen::Vector3d::Unit(k) - centre)).normalized();
      const Eigen::Vector3d a = c.spline.evaluate({p.face, p.barycentric + h * dir}).position;
      const Eigen::Vector3d b = c.spline.evaluate({p.face, p.barycentric + 2 * h * dir}).position;
      const Eigen::Vector3d x = t.positions.row(i).transpose();
      // Second-order one-sided difference: F'(0) ~ (-3 F0 + 4 F1 - F2) / 2h.
      const Eigen::Vector3d tangent = (-3 * x + 4 * a - b) / (2 * h);
      if (tangent.norm() > 0) worst = std::max(worst, std::abs(n.dot(tangent.normalized())));
    }
  }
  EXPECT_LT(worst, 1e-5);
  int facing = 0;
  for (const auto& tri : t.triangles) {
    const Eigen::Vector3d a = t.positions.row(tri[0]), b = t.positions.row(tri[1]),
                          q = t.positions.row(tri[2]);
    const Eigen::Vector3d fn = (b - a).cross(q - a);
    facing += fn.dot(t.normals.row(tri[0]).transpose() + t.normals.row(tri[1]).transpose() +
                     t.normals.row(tri[2]).transpose()) > 0;
  }
  // Orientation, not smoothness: a coarse spline may fold a few triangles at sharp creases.
  EXPECT_GT(facing, 0.99 * static_cast<double>(t.triangles.size()));
}

// The spline is C^2: normals of both faces agree along every interior edge up to rounding.
TEST(Tessellate, NoNormalJumpAcrossDomainEdges) {
  const Case c = make_case("genus2.off");
  EXPECT_LT(max_edge_normal_jump_deg(c.spline, *c.mesh, 3, 2), 1e-5);
  EXPECT_GT(interior_edges(*c.mesh, *c.spline.space), 100);
}

// Texture coordinates: the central chart itself. Every uv triangle is counter-clockwise and
// they tile the domain faces' chart triangles exactly; render vertices split only at the cut.
TEST(Tessellate, UvsTileTheCentralChart) {
  const Case c = make_case("genus2.off");
  const Tessellation t = tessellate(c.spline, *c.mesh, options(3, 2));
  const auto& space = *c.spline.space;
  const ricci::Chart& central = space.atlas().charts[0];
  auto area = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& q) {
    const Eigen::Vector2d u = b - a, v = q - a;
    return 0.5 * (u.x() * v.y() - u.y() * v.x());
  };
  double chart_area = 0.0, uv_area = 0.0, smallest = 1e300;
  for (int f : space.domain_faces()) {
    const auto x = space.atlas().face_positions(0, f);
    chart_area += area(x.row(0), x.row(1), x.row(2));
  }
  for (const auto& tri : t.render_triangles) {
    const double a = area(t.uvs.row(tri[0]), t.uvs.row(tri[1]), t.uvs.row(tri[2]));
    uv_area += a;
    smallest = std::min(smallest, a);
  }
  EXPECT_GT(smallest, 0.0);
  EXPECT_NEAR(uv_area, chart_area, 1e-12 * chart_area);
  ASSERT_EQ(t.render_position.size(), static_cast<std::size_t>(t.uvs.rows()));
  for (std::size_t i = 0; i < t.triangles.size(); ++i)
    for (int k = 0; k < 3; ++k)
      ASSERT_EQ(t.render_position[t.render_triangles[i][k]], t.triangles[i][k]);
  // Copies = extra chart copies of cut vertices plus d - 1 per extra side of each cut edge.
  std::vector<char> seen_vertex(central.positions.rows(), 0);
  long chart_vertices = 0;
  for (int f : space.domain_faces())
    for (int k = 0; k < 3; ++k) {
      const int v = central.corners(central.slot(f), k);
      chart_vertices += !seen_vertex[v];
      seen_vertex[v] = 1;
    }
  long domain_vertices = 0;
  for (int v = 0; v < static_cast<int>(c.mesh->n_vertices()); ++v)
    domain_vertices += t.vertex_sample(v) >= 0;
  long cut_edges = 0;
  for (auto e : c.mesh->edges()) {
    const auto f0 = c.mesh->face_handle(c.mesh->halfedge_handle(e, 0));
    const auto f1 = c.mesh->face_handle(c.mesh->halfedge_handle(e, 1));
    if (!f0.is_valid() || !f1.is_valid() || !space.in_domain(f0.idx()) ||
        !space.in_domain(f1.idx()))
      continue;
    cut_edges += space.atlas().cut.is_cut_edge[static_cast<std::size_t>(e.idx())] != 0;
  }
  EXPECT_GT(cut_edges, 0);
  EXPECT_EQ(t.uvs.rows() - t.positions.rows(),
            (chart_vertices - domain_vertices) + cut_edges * (t.density - 1));
}

// Scaling the control points scales the positions and leaves the normals.
TEST(Tessellate, ScalingInvariance) {
  Case c = make_case("genus1.off", 2);
  const Tessellation a = tessellate(c.spline, *c.mesh, options(2, 1));
  c.spline.control_points *= 1e6;
  const Tessellation b = tessellate(c.spline, *c.mesh, options(2, 1));
  EXPECT_LT((b.positions - 1e6 * a.positions).cwiseAbs().maxCoeff(),
            1e-9 * b.positions.cwiseAbs().maxCoeff());
  EXPECT_LT((b.normals - a.normals).cwiseAbs().maxCoeff(), 1e-9);
}

// Skipped faces (a fill patch's covered faces) leave a hole of their own: one more loop of
// 3 d edges around one skipped interior face, and no samples of their own interior.
TEST(Tessellate, SkippedFacesLeaveAHole) {
  const Case c = make_case("genus1.off");
  const int d = 3;
  TessellationOptions opts = options(d, 2);
  opts.skip_faces.assign(c.mesh->n_faces(), 0);
  opts.skip_faces[17] = 1;
  const Tessellation t = tessellate(c.spline, *c.mesh, opts);
  const WatertightReport r = check_watertight(t.triangles, t.positions);
  EXPECT_TRUE(r.matches(1, 1));
  EXPECT_EQ(r.boundary_edges, 3 * d);
  EXPECT_EQ(static_cast<int>(t.triangles.size()),
            (c.spline.space->domain_face_count() - 1) * d * d);
  // A skipped face has no samples of its own (callers must ask before edge_sample).
  EXPECT_FALSE(t.tessellated(17));
  EXPECT_TRUE(t.tessellated(c.spline.space->domain_faces().front() == 17
                                ? c.spline.space->domain_faces()[1]
                                : c.spline.space->domain_faces().front()));
  opts.skip_faces.pop_back();
  EXPECT_THROW((void)tessellate(c.spline, *c.mesh, opts), ricci::InvalidInputError);
}

// The cone's hole capped: the patch's rim samples are the surface's own edge samples, so the
// welded surface is closed of genus 2 whatever the patch's shape; patch vertices get render
// vertices of their own along the rim (a uv seam), never new positions there.
TEST(Tessellate, FillPatchWeldsIntoAClosedSurface) {
  const Case c = make_case("genus2.off");
  const auto& space = *c.spline.space;
  const auto rims = find_rims(space, *c.mesh);
  ASSERT_EQ(rims.size(), 1u);
  ASSERT_EQ(rims[0].kind, Rim::Kind::cone_hole);
  const int d = 3;
  const TessellationOptions opts = without_rim_faces(c, rims[0], d);
  Tessellation t = tessellate(c.spline, *c.mesh, opts);
  const WatertightReport open = check_watertight(t.triangles, t.positions);
  EXPECT_TRUE(open.matches(2, 1));
  EXPECT_EQ(open.boundary_edges, static_cast<int>(rims[0].edges.size()) * d);
  const HoleFill fill = fill_rim(c.spline, *c.mesh, rims[0]);
  const PatchTessellation patch = tessellate_fill(fill, d);
  const auto positions_before = t.positions.rows();
  const auto triangles_before = t.triangles.size();
  append_fill(t, fill, patch, 0);
  EXPECT_EQ(t.positions.rows(), positions_before + patch.positions.rows());
  EXPECT_EQ(t.triangles.size(),
            triangles_before + static_cast<std::size_t>(patch.triangles.rows()));
  const WatertightReport closed = check_watertight(t.triangles, t.positions);
  EXPECT_TRUE(closed.closed(2)) << closed.boundary_edges << " " << closed.misoriented_edges;
  ASSERT_EQ(t.render_position.size(), static_cast<std::size_t>(t.uvs.rows()));
  for (std::size_t i = triangles_before; i < t.triangles.size(); ++i) {
    EXPECT_EQ(t.triangle_face[i], -1);
    for (int k = 0; k < 3; ++k)
      ASSERT_EQ(t.render_position[t.render_triangles[i][k]], t.triangles[i][k]);
  }
  // A patch made at another density is refused.
  Tessellation other = tessellate(c.spline, *c.mesh, opts);
  EXPECT_THROW(append_fill(other, fill, tessellate_fill(fill, d + 2), 0), ricci::InvalidInputError);
}

// Refinement where the grid turns sharply: the refined soup stays closed and welded, every new
// sample lies on the spline at its parameter, uvs stay counter-clockwise in the central chart,
// the patch is left whole, and the sharpest turn drops.
TEST(Tessellate, SharpTurnsAreRefinedOnTheSurface) {
  const Case c = make_case("genus2.off");
  const auto& space = *c.spline.space;
  const auto rims = find_rims(space, *c.mesh);
  ASSERT_EQ(rims.size(), 1u);
  const int d = 2;
  const TessellationOptions opts = without_rim_faces(c, rims[0], d);
  Tessellation t = tessellate(c.spline, *c.mesh, opts);
  const HoleFill fill = fill_rim(c.spline, *c.mesh, rims[0]);
  append_fill(t, fill, tessellate_fill(fill, d), 0);
  auto patch_triangles = [](const Tessellation& s) {
    return std::count_if(s.triangle_face.begin(), s.triangle_face.end(),
                         [](int f) { return f < 0; });
  };
  const auto patch_before = patch_triangles(t);
  const auto triangles_before = t.triangles.size();
  const auto positions_before = t.positions.rows();
  const DihedralReport before = dihedral_angles(t.triangles, t.positions);
  const double turn = 0.5 * before.max_deg;

  Tessellation same = t;
  EXPECT_EQ(refine_sharp_turns(same, c.spline, turn, 0), 0);
  EXPECT_EQ(same.triangles, t.triangles);
  const int splits = refine_sharp_turns(t, c.spline, turn, 2, 2);
  ASSERT_GT(splits, 0);
  EXPECT_GE(t.triangles.size(), triangles_before + 3 * static_cast<std::size_t>(splits));
  EXPECT_EQ(patch_triangles(t), patch_before);

  const WatertightReport closed = check_watertight(t.triangles, t.positions);
  EXPECT_TRUE(closed.closed(2)) << closed.boundary_edges << " " << closed.misoriented_edges;
  EXPECT_EQ(closed.duplicate_positions, 0);
  const DihedralReport after = dihedral_angles(t.triangles, t.positions);
  EXPECT_LT(after.max_deg, before.max_deg);

  ASSERT_EQ(t.parameters.size(), static_cast<std::size_t>(t.positions.rows()));
  ASSERT_EQ(t.normals.rows(), t.positions.rows());
  for (Eigen::Index i = positions_before; i < t.positions.rows(); ++i) {
    const DomainPoint& p = t.parameters[static_cast<std::size_t>(i)];
    ASSERT_GE(p.face, 0);
    EXPECT_NEAR(p.barycentric.sum(), 1.0, 1e-15);
    const SurfaceJet jet = c.spline.evaluate(p);
    EXPECT_LT((jet.position - t.positions.row(i).transpose()).norm(), 1e-12) << i;
    EXPECT_GT(jet.normal.dot(t.normals.row(i).transpose()), 1.0 - 1e-12) << i;
  }
  ASSERT_EQ(t.render_triangles.size(), t.triangles.size());
  ASSERT_EQ(t.render_position.size(), static_cast<std::size_t>(t.uvs.rows()));
  for (std::size_t i = 0; i < t.triangles.size(); ++i) {
    for (int k = 0; k < 3; ++k)
      ASSERT_EQ(t.render_position[t.render_triangles[i][k]], t.triangles[i][k]) << i;
    if (t.triangle_face[i] < 0) continue;
    const auto& r = t.render_triangles[i];
    const Eigen::Vector2d a = t.uvs.row(r[1]) - t.uvs.row(r[0]),
                          b = t.uvs.row(r[2]) - t.uvs.row(r[0]);
    EXPECT_GT(a.x() * b.y() - a.y() * b.x(), 0.0) << i;
    // Orientation kept: the triangle faces the way the exact normals at its corners do.
    const Eigen::Vector3d e = t.positions.row(t.triangles[i][1]) - t.positions.row(t.triangles[i][0]),
                          f = t.positions.row(t.triangles[i][2]) - t.positions.row(t.triangles[i][0]);
    EXPECT_GT(e.cross(f).dot(t.normals.row(t.triangles[i][0])), 0.0) << i;
  }
  EXPECT_THROW(refine_sharp_turns(t, c.spline, 0.0, 1), ricci::InvalidInputError);
  EXPECT_THROW(refine_sharp_turns(t, c.spline, 180.0, 1), ricci::InvalidInputError);
  EXPECT_THROW(refine_sharp_turns(t, c.spline, 60.0, -1), ricci::InvalidInputError);
}

// `spline` with the control point of function `k` of domain face `face` moved by `delta`.
ManifoldSpline with_moved_point(const ManifoldSpline& spline, int face, int k,
                                const Eigen::RowVector3d& delta) {
  ManifoldSpline moved = spline;
  moved.control_points.row(spline.space->function_index(face, k)) += delta;
  return moved;
}

// One control point moved: the faces its function reaches evaluate differently, the others
// alike; a tessellation taking the earlier samples on the alike faces (and on faces skipped
// before, evaluated now) has the bits of a fresh one.
TEST(Tessellate, ReusesSamplesOfFacesEvaluatedAlike) {
  const Case c = make_case("genus2.off");
  const ManifoldSplineSpace& space = *c.spline.space;
  const int face = space.domain_faces()[space.domain_faces().size() / 2];
  const ManifoldSpline moved = with_moved_point(c.spline, face, 0, {0.01, 0, 0});
  const std::vector<char> alike = faces_evaluated_alike(c.spline, moved);
  ASSERT_EQ(alike.size(), c.mesh->n_faces());
  int differ = 0;
  for (int f : space.domain_faces()) {
    const auto reaching = space.reaching_faces(f);
    const bool reached = std::binary_search(reaching.begin(), reaching.end(), face);
    EXPECT_EQ(alike[static_cast<std::size_t>(f)], !reached) << f;
    differ += reached;
  }
  EXPECT_GT(differ, 3);
  EXPECT_EQ(faces_evaluated_alike(c.spline, c.spline),
            [&] {
              std::vector<char> all(c.mesh->n_faces(), 0);
              for (int f : space.domain_faces()) all[static_cast<std::size_t>(f)] = 1;
              return all;
            }());

  TessellationOptions before = options(3, 2);
  before.skip_faces.assign(c.mesh->n_faces(), 0);
  before.skip_faces[static_cast<std::size_t>(space.domain_faces().front())] = 1;
  const Tessellation earlier = tessellate(c.spline, *c.mesh, before);
  const Tessellation fresh = tessellate(moved, *c.mesh, options(3, 2));
  TessellationOptions reuse = options(3, 2);
  reuse.reuse = &earlier;
  reuse.reuse_faces = alike;
  const Tessellation reused = tessellate(moved, *c.mesh, reuse);
  EXPECT_EQ(reused.triangles, fresh.triangles);
  EXPECT_TRUE((reused.positions.array() == fresh.positions.array()).all());
  EXPECT_TRUE((reused.normals.array() == fresh.normals.array()).all());
  EXPECT_FALSE((fresh.positions.array() == tessellate(c.spline, *c.mesh, options(3, 2))
                                               .positions.array())
                   .all());
  // The samples are copied, not evaluated: every face flagged takes the earlier spline's.
  reuse.reuse_faces.assign(c.mesh->n_faces(), 1);
  const Tessellation copied = tessellate(moved, *c.mesh, reuse);
  const Tessellation unmoved = tessellate(c.spline, *c.mesh, options(3, 2));
  EXPECT_TRUE((copied.positions.array() == unmoved.positions.array()).all());
  reuse.reuse_faces.pop_back();
  EXPECT_THROW((void)tessellate(moved, *c.mesh, reuse), ricci::InvalidInputError);
  ManifoldSpline other = moved;
  other.space = small_space("genus2.off", 2, 300);
  other.control_points = piecewise_linear_control_points(*other.space, *c.mesh);
  EXPECT_THROW((void)faces_evaluated_alike(c.spline, other), ricci::InvalidInputError);
}

// Two control points moved by 0.01 and 0.03: at a distance below both, the faces either
// function reaches are flagged (the complement of faces_evaluated_alike on the domain); between
// the two, only the farther one's; above both, none.
TEST(Tessellate, FacesMovedFartherThanADistance) {
  const Case c = make_case("genus2.off");
  const ManifoldSplineSpace& space = *c.spline.space;
  const std::vector<int>& domain = space.domain_faces();
  const int near = domain[domain.size() / 4], far = domain[3 * domain.size() / 4];
  const ManifoldSpline moved =
      with_moved_point(with_moved_point(c.spline, near, 0, {0.01, 0, 0}), far, 1, {0, 0, 0.03});
  const std::vector<char> alike = faces_evaluated_alike(c.spline, moved);
  const std::vector<char> both = faces_moved_farther(c.spline, moved, 0.005);
  const std::vector<char> farther = faces_moved_farther(c.spline, moved, 0.02);
  ASSERT_EQ(both.size(), c.mesh->n_faces());
  int flagged = 0;
  for (int f : domain) {
    const auto reaching = space.reaching_faces(f);
    const auto reached = [&](int g) {
      return std::binary_search(reaching.begin(), reaching.end(), g);
    };
    EXPECT_EQ(both[static_cast<std::size_t>(f)], !alike[static_cast<std::size_t>(f)]) << f;
    EXPECT_EQ(farther[static_cast<std::size_t>(f)], reached(far)) << f;
    flagged += farther[static_cast<std::size_t>(f)];
  }
  EXPECT_GT(flagged, 3);
  const std::vector<char> none(c.mesh->n_faces(), 0);
  EXPECT_EQ(faces_moved_farther(c.spline, moved, 0.04), none);
  ManifoldSpline other = moved;
  other.space = small_space("genus2.off", 2, 300);
  EXPECT_THROW((void)faces_moved_farther(c.spline, other, 0.0), ricci::InvalidInputError);
}

// The seams' jumps by edge: their largest is max_edge_normal_jump_deg; measured again after a
// control point moved, those of edges between faces evaluated alike are taken from before and
// the result is the fresh one.
TEST(Tessellate, EdgeJumpsOfFacesEvaluatedAlikeAreTakenFromBefore) {
  const Case c = make_case("genus2.off");
  const ManifoldSplineSpace& space = *c.spline.space;
  const int face = space.domain_faces()[space.domain_faces().size() / 3];
  const ManifoldSpline moved = with_moved_point(c.spline, face, 1, {0, 0.02, 0.01});
  const std::vector<double> before = edge_normal_jumps_deg(c.spline, *c.mesh, 2, 2);
  ASSERT_EQ(before.size(), c.mesh->n_edges());
  EXPECT_EQ(*std::max_element(before.begin(), before.end()),
            max_edge_normal_jump_deg(c.spline, *c.mesh, 2, 2));
  EXPECT_EQ(static_cast<int>(std::count_if(before.begin(), before.end(),
                                           [](double a) { return a >= 0.0; })),
            interior_edges(*c.mesh, space));
  const std::vector<char> alike = faces_evaluated_alike(c.spline, moved);
  const std::vector<double> fresh = edge_normal_jumps_deg(moved, *c.mesh, 2, 2);
  EXPECT_EQ(edge_normal_jumps_deg(moved, *c.mesh, 2, 2, {}, before, alike), fresh);
  // Taken, not measured: earlier angles (made up) come back on the edges between alike faces.
  std::vector<double> made_up = before;
  for (double& a : made_up) a = a >= 0.0 ? 7.0 : a;
  const std::vector<double> taken = edge_normal_jumps_deg(moved, *c.mesh, 2, 2, {}, made_up, alike);
  int from_before = 0, measured = 0;
  for (auto e : c.mesh->edges()) {
    const auto i = static_cast<std::size_t>(e.idx());
    if (before[i] < 0.0) continue;
    const bool both = alike[c.mesh->face_handle(c.mesh->halfedge_handle(e, 0)).idx()] &&
                      alike[c.mesh->face_handle(c.mesh->halfedge_handle(e, 1)).idx()];
    EXPECT_EQ(taken[i], both ? 7.0 : fresh[i]) << i;
    (both ? from_before : measured) += 1;
  }
  EXPECT_GT(from_before, 0);
  EXPECT_GT(measured, 0);
  EXPECT_THROW((void)edge_normal_jumps_deg(moved, *c.mesh, 2, 2, {}, before, {}),
               ricci::InvalidInputError);
}

TEST(Tessellate, RefusesBadDensity) {
  const Case c = make_case("genus1.off", 2);
  EXPECT_THROW((void)tessellate(c.spline, *c.mesh, options(0, 1)), ricci::InvalidInputError);
}

// The check itself: a tetrahedron, then the ways a soup fails to be watertight.
Eigen::MatrixX3d tetra_points() {
  Eigen::MatrixX3d p(4, 3);
  p << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  return p;
}
const std::vector<std::array<int, 3>> kTetra = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};

TEST(Watertight, TetrahedronIsClosedGenusZero) {
  const auto r = check_watertight(kTetra, tetra_points());
  EXPECT_TRUE(r.closed(0));
  EXPECT_EQ(r.euler_characteristic, 2);
  EXPECT_EQ(r.edges, 6);
}

TEST(Watertight, MissingTriangleLeavesOneLoop) {
  auto tris = kTetra;
  tris.pop_back();
  const auto r = check_watertight(tris, tetra_points());
  EXPECT_FALSE(r.closed(0));
  EXPECT_TRUE(r.matches(0, 1));
  EXPECT_EQ(r.boundary_edges, 3);
}

TEST(Watertight, FlippedTriangleIsMisoriented) {
  auto tris = kTetra;
  std::swap(tris[3][1], tris[3][2]);
  const auto r = check_watertight(tris, tetra_points());
  EXPECT_EQ(r.misoriented_edges, 3);
  EXPECT_FALSE(r.manifold());
}

TEST(Watertight, CrackWithDuplicateVertexIsCaught) {
  // Vertex 3 doubled (4 has the same coordinates): the cracked soup has boundary and duplicates.
  Eigen::MatrixX3d p(5, 3);
  p << tetra_points(), 0, 0, 1;
  auto tris = kTetra;
  tris[3] = {1, 2, 4};
  const auto r = check_watertight(tris, p);
  EXPECT_EQ(r.duplicate_positions, 1);
  EXPECT_GT(r.boundary_edges, 0);
  EXPECT_FALSE(r.closed(0));
}

TEST(Watertight, PinchedVertexIsNotManifold) {
  // Two tetrahedra sharing vertex 0 only.
  Eigen::MatrixX3d p(7, 3);
  p << tetra_points(), -1, 0, 0, 0, -1, 0, 0, 0, -1;
  auto tris = kTetra;
  for (auto t : kTetra) {
    std::array<int, 3> u;
    for (int k = 0; k < 3; ++k) u[k] = t[k] == 0 ? 0 : t[k] + 3;
    std::swap(u[1], u[2]);  // mirrored copy: keep it outward
    tris.push_back(u);
  }
  const auto r = check_watertight(tris, p);
  EXPECT_EQ(r.nonmanifold_vertices, 1);
  EXPECT_EQ(r.boundary_edges, 0);
  EXPECT_EQ(r.misoriented_edges, 0);
  EXPECT_FALSE(r.manifold());
}

}  // namespace
}  // namespace spline
