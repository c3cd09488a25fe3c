#pragma once
// Watertight tessellation of a manifold spline (issue 6): every domain face's spline piece is
// sampled on the regular barycentric grid of density d (d + 1 samples per domain edge, d^2
// triangles per face). Every domain vertex is evaluated once and every domain edge's d - 1
// interior samples once, so faces sharing a vertex or an edge share the very same sample:
// welded by construction (no cracks, no T-junctions). Normals come from the exact derivatives
// (du x dv in the evaluating chart, counter-clockwise like the domain faces); texture
// coordinates from the atlas' central chart, which has seams along the cut: the welded topology
// (position indices) is kept apart from the render vertices (position + uv), which split there.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

#include "ricci/mesh/mesh.h"
#include "spline/manifold/manifold_space.h"

namespace spline {

struct Tessellation;

struct TessellationOptions {
  int density = 8;  ///< d >= 1: samples per domain edge - 1; d^2 triangles per domain face.
  int threads = 0;  ///< Evaluation threads; 0 = std::thread::hardware_concurrency().
  /// tessellate_surface only (tessellate() keeps the uniform grid): refine_sharp_turns with
  /// these, after the fills are welded in. 0 levels: the uniform grid alone.
  int refine_levels = 3;
  double refine_turn_deg = 60.0;
  /// By face, nonzero: not tessellated (a fill patch covers it, fill/hole_fill.h's
  /// Rim::covered_faces). Empty: every domain face.
  std::vector<char> skip_faces;
  /// An earlier tessellation whose samples are copied instead of evaluated: a sample at the
  /// same domain point (face and barycentric coordinates, bit for bit) as one of reuse's, on a
  /// face flagged in reuse_faces (by face), takes its position and normal. Flag only faces the
  /// spline evaluates as it did for `reuse` (faces_evaluated_alike): the result is then the
  /// one a fresh evaluation gives, bit for bit. Null: every sample evaluated.
  const Tessellation* reuse = nullptr;
  std::vector<char> reuse_faces;
};

struct Tessellation {
  int density = 0;
  int turn_splits = 0;  ///< Triangles split 1-to-4 by refine_sharp_turns (0: the uniform grid).
  /// Welded topology: one row per surface sample.
  Eigen::MatrixX3d positions;
  Eigen::MatrixX3d normals;                   ///< Unit (du x dv); a zero row only if F is singular.
  std::vector<DomainPoint> parameters;        ///< The domain point each position was evaluated at.
  std::vector<std::array<int, 3>> triangles;  ///< Position indices, counter-clockwise.
  std::vector<int> triangle_face;  ///< Domain face of each triangle (-1 - r: fill patch r).

  /// Render vertices: a position with one central-chart uv (a cut vertex has several).
  std::vector<int> render_position;  ///< By render vertex: its position index.
  Eigen::MatrixX2d uvs;              ///< By render vertex, central-chart coordinates.
  std::vector<std::array<int, 3>> render_triangles;  ///< Same triangles, render indices.

  /// Position index of a domain vertex (-1 when no tessellated face touches it).
  [[nodiscard]] int vertex_sample(int vertex) const { return vertex_position_[vertex]; }
  /// True when `face` was tessellated (a domain face not skipped, e.g. not covered by a fill).
  [[nodiscard]] bool tessellated(int face) const { return face_corner_vertex_[face][0] >= 0; }
  /// Position index of sample i (0..d) of the edge opposite corner k of domain `face`, walking
  /// from corner k + 1 to corner k + 2 (the face's orientation) at barycentric t = i / d (the
  /// rim sample convention of fill/hole_fill.h). \pre face is a tessellated face.
  [[nodiscard]] int edge_sample(int face, int corner, int i) const;

  // Book-keeping for the lookups (filled by tessellate).
  std::vector<int> vertex_position_;  ///< By domain-mesh vertex.
  /// By face (3 per face): first interior sample of the edge opposite corner k, and whether the
  /// edge's canonical direction runs against the face (then sample i is d - i canonically).
  std::vector<std::array<int, 3>> face_edge_first_;
  std::vector<std::array<char, 3>> face_edge_reversed_;
  std::vector<std::array<int, 3>> face_corner_vertex_;  ///< By face: domain vertex of corner k.
};

/// Samples `spline` over every domain face at density d.
/// \pre `mesh` is the domain mesh the spline's space was built on.
/// \throw ricci::InvalidInputError for density < 1 or a mesh of another size;
///        as ManifoldSpline::evaluate.
[[nodiscard]] Tessellation tessellate(const ManifoldSpline& spline, const ricci::Mesh& mesh,
                                      const TessellationOptions& options = {});

/// By face of `a`'s domain mesh: 1 where `a` and `b` give the same bits at every point of the
/// face (the default chart's evaluation, as tessellate's): the functions reaching it
/// (ManifoldSplineSpace::reaching_faces) have the same control points in both. 0 outside the
/// domain.
/// \throw ricci::InvalidInputError when the two do not share one space or a control-point
///        count is not its function count.
[[nodiscard]] std::vector<char> faces_evaluated_alike(const ManifoldSpline& a,
                                                      const ManifoldSpline& b);

/// By face of the splines' shared domain mesh: 1 where a function reaching it
/// (ManifoldSplineSpace::reaching_faces) has control points farther than `distance` apart in
/// `a` and `b` (so the surfaces may differ there by about that much), 0 elsewhere and outside
/// the domain.
/// \throw ricci::InvalidInputError as faces_evaluated_alike.
[[nodiscard]] std::vector<char> faces_moved_farther(const ManifoldSpline& a,
                                                    const ManifoldSpline& b, double distance);

/// Local refinement where the sampled surface turns sharply, so that a smooth but tightly curved
/// part (an ear tip, a hoof) is not shown as a fold of the grid: every spline triangle on an edge
/// whose two triangles' normals differ by more than `turn_deg` degrees is split 1-to-4 at its
/// edges' domain midpoints (evaluated on `spline`), and its neighbours are closed by bisection
/// (red-green), so the result stays welded; repeated up to `levels` times while such edges
/// remain. The level kept is the deepest that shows no more fold edges (over 90 degrees) than
/// the grid and every level before it: more would be a fold of the spline within a triangle,
/// which the fit judged on the coarser grid. Fill-patch triangles (triangle_face < 0) and the
/// triangles next to them stay whole.
/// New samples are appended (earlier indices and the lookups above keep their meaning); render
/// vertices split where the central chart's uvs do. Returns the number of 1-to-4 splits.
/// \pre t = tessellate(spline, mesh, ...), fills appended or not.
/// \throw ricci::InvalidInputError for turn_deg outside (0, 180) or levels < 0.
int refine_sharp_turns(Tessellation& t, const ManifoldSpline& spline, double turn_deg, int levels,
                       int threads = 0);

/// What a triangle soup (by position index) is topologically.
struct WatertightReport {
  int vertices = 0, edges = 0, faces = 0;  ///< Used positions, undirected edges, triangles.
  int euler_characteristic = 0;            ///< V - E + F.
  int boundary_edges = 0;                  ///< In one triangle only.
  int boundary_loops = 0;        ///< Cycles of boundary edges (0 when they do not form cycles).
  int nonmanifold_edges = 0;     ///< In three or more triangles.
  int misoriented_edges = 0;     ///< Two triangles running the same way along it.
  int nonmanifold_vertices = 0;  ///< Triangles around the vertex not one fan.
  int degenerate_triangles = 0;  ///< Repeated index.
  int duplicate_positions = 0;   ///< Distinct used indices with bit-identical coordinates.
  int unused_positions = 0;      ///< Rows no triangle uses.
  int non_finite_positions = 0;

  /// An oriented 2-manifold (possibly with boundary) without duplicate or stray positions.
  [[nodiscard]] bool manifold() const {
    return nonmanifold_edges == 0 && misoriented_edges == 0 && nonmanifold_vertices == 0 &&
           degenerate_triangles == 0 && duplicate_positions == 0 && unused_positions == 0 &&
           non_finite_positions == 0 && faces > 0;
  }
  /// A closed oriented 2-manifold of genus g (Euler characteristic 2 - 2g).
  [[nodiscard]] bool closed(int genus) const {
    return manifold() && boundary_edges == 0 && euler_characteristic == 2 - 2 * genus;
  }
  /// A manifold surface of genus g with exactly `loops` boundary loops (chi = 2 - 2g - loops),
  /// i.e. the same topology as an input with those figures.
  [[nodiscard]] bool matches(int genus, int loops) const {
    return manifold() && boundary_loops == loops && euler_characteristic == 2 - 2 * genus - loops;
  }
};

/// Topology of the triangles over `positions` (one connected component assumed for the genus).
[[nodiscard]] WatertightReport check_watertight(const std::vector<std::array<int, 3>>& triangles,
                                                const Eigen::MatrixX3d& positions);

/// Largest angle (degrees) between the normals two adjacent domain faces give at the same
/// point, over `samples_per_edge` points of every interior domain edge (each face evaluated in
/// its own neighbourhood chart, derivatives carried to 3D: the frame does not matter). The
/// spline is C^(n-1), so this measures rounding and the atlas' transitions.
/// Faces flagged in `skip_faces` (by face, may be empty) are left out like non-domain faces;
/// `earlier` and `alike` reuse angles measured before, as edge_normal_jumps_deg says.
/// \throw ricci::InvalidInputError as edge_normal_jumps_deg does.
[[nodiscard]] double max_edge_normal_jump_deg(const ManifoldSpline& spline, const ricci::Mesh& mesh,
                                              int samples_per_edge = 4, int threads = 0,
                                              const std::vector<char>& skip_faces = {},
                                              const std::vector<double>& earlier = {},
                                              const std::vector<char>& alike = {});

/// The angles max_edge_normal_jump_deg takes the largest of, by domain edge (edge index): the
/// largest over the edge's samples, -1 for an edge not between two faces kept. An edge's angle
/// is taken from `earlier` (by edge; empty: none) when it is there (>= 0) and both its faces are
/// flagged in `alike` (by face: faces_evaluated_alike of the spline `earlier` was measured on
/// and this one, with the same samples_per_edge): the number it would measure again.
/// \throw ricci::InvalidInputError for earlier or alike of another size than the mesh's edges
///        or faces.
[[nodiscard]] std::vector<double> edge_normal_jumps_deg(const ManifoldSpline& spline,
                                                        const ricci::Mesh& mesh,
                                                        int samples_per_edge = 4, int threads = 0,
                                                        const std::vector<char>& skip_faces = {},
                                                        const std::vector<double>& earlier = {},
                                                        const std::vector<char>& alike = {});

}  // namespace spline
