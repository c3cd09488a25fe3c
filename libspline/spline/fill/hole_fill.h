#pragma once
// Hole filling (manifold-splines paper, section 5: "we use planar triangular B-splines to fill
// these holes with G1 continuity along the boundaries").
//
// A rim (find_rims) is a closed loop of domain edges with exactly one kept face: the cone's
// one-ring hole, an open surface's boundary loop, or the hole left by excluded faces, each grown
// by FindRimsOptions. fill_rim fills a rim with a planar DMS spline patch P that meets the
// surface with G1 continuity: a height field P(u) = origin + u_x e1 + u_y e2 + h(u) n over a
// plane (FillMethod::height_field; needs every rim normal within ~87 degrees of n and a simple,
// projected rim), or a parametric patch over the rim developed into the plane
// (FillMethod::parametric). Both are one sparse least-squares problem: positions and tangent
// planes at samples of every rim edge plus a thin-plate energy. Only the positions-only fallback
// is not G1 (HoleFill::g1 false). The construction of both patches and the measurements behind
// the defaults: docs/design-notes.md, "Hole filling".
//
// Rim sample convention (the weld shared with the tessellator): rim edge j is sampled at d + 1
// points t_i = i / d, i = 0..d, linear in the barycentric coordinates of its domain face from the
// start vertex (t = 0) to the end vertex (t = 1): rim_edge_barycentric(edge, t). Sample (j, d) is
// the same surface point as sample (j + 1, 0).
#include <Eigen/Core>
#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include "ricci/mesh/mesh.h"
#include "spline/basis/planar_space.h"
#include "spline/knots/knot_cloud.h"
#include "spline/manifold/manifold_space.h"

namespace spline {

/// One rim edge: a domain face and its corner k opposite the edge (corner numbering of
/// manifold_space.h: corner k = to_vertex of the k-th halfedge of ricci::face_halfedges). The
/// edge runs from corner (k + 1) % 3 (start) to corner (k + 2) % 3 (end): the face's own
/// counter-clockwise direction, so the face is on the left and the hole on the right.
struct RimEdge {
  int face = -1;
  int corner = 0;
};

[[nodiscard]] inline int rim_edge_start_corner(const RimEdge& edge) {
  return (edge.corner + 1) % 3;
}
[[nodiscard]] inline int rim_edge_end_corner(const RimEdge& edge) { return (edge.corner + 2) % 3; }

/// Barycentric coordinates (face corner order) of the point at t in [0, 1] of the rim edge:
/// (1 - t) at the start corner, t at the end corner, 0 at the opposite corner.
[[nodiscard]] Eigen::Vector3d rim_edge_barycentric(const RimEdge& edge, double t);

/// A closed loop of rim edges, chained: edges[j]'s end vertex is edges[j + 1]'s start vertex
/// (cyclically). Each edge has a kept domain face on its left and, on its right, a face the
/// patch replaces (covered_faces), a face outside the domain, or the mesh boundary.
struct Rim {
  enum class Kind {
    cone_hole,  ///< around the cone's one-ring (faces with atlas.in_domain == 0)
    boundary,   ///< along an open surface's boundary loop
    excluded,   ///< around faces the spline space excluded (excluded_faces()) only
  };
  std::vector<RimEdge> edges;
  Kind kind = Kind::cone_hole;
  /// Domain faces inside the rim that the patch replaces (ascending): the faces FindRimsOptions::
  /// grow added to the hole. A tessellation of the spline must skip them (and the faces outside
  /// the domain); the patch covers them.
  std::vector<int> covered_faces;
};

/// The rim kind's identifier in reports and tables: "cone_hole", "boundary", "excluded" (the
/// fit report's JSON key `fill_patches[].kind`; stable).
[[nodiscard]] const char* rim_kind_id(Rim::Kind kind);
/// The rim kind in words for messages: "cone hole", "boundary loop", "excluded-face hole".
[[nodiscard]] const char* rim_kind_description(Rim::Kind kind);

struct FindRimsOptions {
  /// Layers of domain faces added to every hole (all domain faces touching a rim vertex, per
  /// layer) before the rims are taken, so that the basis is a partition of unity on the seam;
  /// kept faces left as islands inside a grown hole are covered too. 0: the rims are the
  /// domain's own (the cone's one-ring link, the boundary loops).
  int grow = 1;
  /// Cone hole only, after the `grow` layers: more layers (the cone hole alone, face by face as
  /// in rims.h, so it stays a disk apart from the other holes) while a face on its rim has a
  /// chart scale (chart_scale_by_face) that differs from an edge neighbour's by more than this
  /// factor (the first rings around a large cone, where the fitted spline folds). <= 1: off.
  double max_cone_rim_scale_ratio = 5.0;
  /// ... or while the fitted spline folds on a face of its rim: its normal turns by more than
  /// this (degrees) between points 1/100 of an edge apart along one of the face's edges
  /// (max_normal_step_deg; given to find_rims as a function). A smooth fit turns by ~1 degree.
  double max_cone_rim_normal_step_deg = 20.0;
  int max_cone_layers = 3;  ///< cap on those extra layers
  /// Layers taken after the last layer whose rim had such a face (within the caps): the spline
  /// on the faces a ring past a fold or a scale jump still carries it (the basis functions'
  /// supports reach a ring), so the rim is moved one ring away from them. 0: none.
  int cone_margin_layers = 0;
  /// The first this many of those layers are taken whatever the rim's faces (still within the
  /// caps): for a retry on a bigger hole when a patch cannot meet the rim (msp fit does when a
  /// cone patch flips).
  int extra_cone_layers = 0;
  /// ... and on the domain faces the cone hole may cover (a coarse domain, e.g. joint.off's 540
  /// faces, distorted everywhere, would otherwise lose a large part of its spline to the patch).
  double max_cone_cover_fraction = 0.08;
  /// Further reach of those layers: while its rim stays poor at the caps above, the cone hole
  /// goes on growing up to this many layers and this fraction of the domain's faces, and keeps
  /// that growth only when its rim comes clear of poor faces (then with its margin layers)
  /// within them; otherwise the hole is the one the caps above give. For a sliver band around
  /// a large cone that ends a little past the caps. 0 layers: no further reach.
  int cone_reach_layers = 0;
  double cone_reach_cover_fraction = 0.0;  ///< see cone_reach_layers
  /// Cone hole only, after its layers: the kept faces around these domain vertices (vertices
  /// of its rim) join it face by face, keeping it a disk (the cover fraction does not apply):
  /// where its patch cannot meet the surface (cap_holes passes the ends of the rim edges whose
  /// seam is worst). Empty: none.
  std::vector<int> cone_rim_vertices_to_cover{};
  /// By face, nonzero: a face beyond the surface's own boundary (the scan fit's boundary collar,
  /// fitted but not part of the surface): not kept, and its hole is a boundary hole. Empty: none.
  std::vector<char> boundary_faces{};
};

/// By face: the chart's length scale over the surface's, sqrt(chart area / 3D area) of the
/// domain mesh's triangle in its chart (the conformal factor e^-u of the flat metric, face by
/// face); 0 for faces outside the space's domain or degenerate ones.
/// \pre `mesh` is the mesh the space was built on.
[[nodiscard]] std::vector<double> chart_scale_by_face(const ManifoldSplineSpace& space,
                                                      const ricci::Mesh& mesh);

/// The largest angle (degrees) between the spline's normals at consecutive points 1/steps of an
/// edge apart along the three edges of domain face `face` (just inside it, 1e-3 of the way to
/// its centre): a crease or fold shows as tens of degrees, a smooth fit as about one.
/// \throw ricci::InvalidInputError when steps < 1 or the face is outside the domain.
[[nodiscard]] double max_normal_step_deg(const ManifoldSpline& spline, int face, int steps = 100);
/// Mesh vertex index of each rim edge's start vertex (so vertex j is shared by edges j - 1, j).
/// \pre `mesh` is the space's domain mesh.
[[nodiscard]] std::vector<int> rim_vertices(const Rim& rim, const ricci::Mesh& mesh);

/// Every rim: closed loops of edges with exactly one kept face (a domain face not covered, see
/// FindRimsOptions::grow). Cone holes first, then boundary loops, then excluded-face holes;
/// within a kind by smallest face index. A vertex where the kept region touches itself is passed
/// through by turning to the first rim edge around it, so loops never reuse an edge.
/// \pre `mesh` is the mesh the space was built on.
/// \throw ricci::InvalidInputError when the mesh has another face count than the space or
///        grow < 0.
[[nodiscard]] std::vector<Rim> find_rims(const ManifoldSplineSpace& space, const ricci::Mesh& mesh,
                                         const FindRimsOptions& options = {});

/// Which patch fill_rim makes.
enum class FillMethod {
  /// The height field when it exists and meets the surface within FillOptions::target_jump_deg;
  /// otherwise the parametric patch too, keeping the one with the smaller seam jump.
  automatic,
  height_field,  ///< the height field only (with the positions-only fallback)
  parametric,    ///< the parametric G1 patch only
};

struct FillOptions {
  FillMethod method = FillMethod::automatic;
  /// FillMethod::automatic: a height field whose seam jump exceeds this also tries the
  /// parametric patch.
  double target_jump_deg = 1.0;
  int degree = 3;  ///< degree of the patch's DMS spline, 1..kMaxDmsDegree
  /// Patch triangulation edges per rim edge along D's boundary: the patch's triangles (a
  /// regular grid over D) have sides of about (rim length in the plane) / (refinement * edges).
  int refinement = 3;
  /// The patch's triangles near D's corners (the rim's vertices) are this many times smaller
  /// than elsewhere (patch_space), so the patch can turn as fast as the surface next to a rim
  /// vertex. A refined patch missing target_jump_deg is compared with the uniform one and the
  /// smaller seam kept. 1: a uniform grid.
  int corner_refinement = 8;
  /// ... except, in the height-field and parametric patches, at rim vertices where the
  /// surface's normal turns by at most this (degrees) between consecutive rim samples
  /// (fit_samples_per_edge) next to the vertex: there it is refined mild_corner_refinement times
  /// (at most corner_refinement), a smaller patch. The positions-only patch refines every rim
  /// vertex corner_refinement times.
  double mild_corner_step_deg = 0.04;
  int mild_corner_refinement = 2;
  /// Height-field patch: outside D, where the patch is not evaluated, the corner refinement's
  /// triangles grow this many times faster with the distance from the rim vertex (>= 1; 1: as
  /// inside). Fewer triangles, but the patch inside D moves too (fewer small triangles across
  /// D's boundary).
  double outside_corner_grading = 1.0;
  /// Height-field patch: the thin plate of triangles outside D farther than this many grid
  /// sides (rim length in the plane / boundary vertices) from it takes Dunavant's 6-point rule
  /// instead of the 42 points with the corner sub-triangles, which catch spikes inside knot
  /// clouds; no function reaching D is nonzero there. Negative: the 42 points everywhere.
  double plain_quadrature_distance = 1.0;
  /// Height-field and parametric patches: the patch's grid keeps the triangles whose centroid
  /// lies in D or within this many grid sides of it (>= 1: every function reaching D stays, so
  /// the partition of unity holds on D), not the whole box of D plus two sides. Fewer
  /// unknowns; the thin plate then ends there. Negative: the whole box.
  double grid_margin = 2.0;
  /// ... but a rim where the surface's normal turns by more than this (degrees) between samples
  /// 1/100 of an edge apart (a fold or crease) gets the uniform patch only: the refined one
  /// would follow the fold into the hole.
  double max_refined_rim_step_deg = 20.0;
  /// Cap on rim edges * refinement: long rims (past 21 edges at refinement 3, e.g. the cone
  /// holes of genus 2 and 3) get a coarser patch (cost grows with the square of it).
  int max_boundary_vertices = 64;
  /// Samples per rim edge of the seam measurement stored in HoleFill.
  int samples_per_edge = 100;
  /// Samples per rim edge in the least-squares objective (and of D's Hermite boundary curve).
  /// Dense on purpose: between sparser samples the patch's slope wanders.
  int fit_samples_per_edge = 96;
  double position_weight = 1e6;  ///< weight of the height rows (dimensionless, see hole_fill.cpp)
  double tangent_weight = 1e6;   ///< weight of the slope (G1) rows
  /// Parametric patch only: weight of the soft in-plane derivative rows (the rim's derivative
  /// along D's boundary, a tangent-plane vector into the hole across it). Low on purpose: they
  /// only keep P from folding; G1 comes from the tangent rows.
  double cross_weight = 1e5;
  /// Parametric patch: samples per rim edge in its least-squares objective (denser than the
  /// height field's; a finer patch needs still more).
  int parametric_samples_per_edge = 200;
  /// Weight of the thin-plate energy of the patch (dimensionless): lower lets the slope wander
  /// between samples, higher fights the seam.
  double smoothing = 1e-2;
  /// Smallest accepted cosine between the plane's normal and the surface's normals on the rim.
  double min_normal_cosine = 0.05;
  /// FillMethod::height_field: cone and excluded-face holes that are no height field are filled
  /// anyway by a patch fitted to the rim's positions only over the rim laid out on a circle
  /// (watertight, consistently oriented, NOT G1: HoleFill::g1 false, its fallback_reason says
  /// why). Boundary loops throw. (FillMethod::automatic makes the parametric patch instead.)
  bool fallback = true;
  /// Apply the fallback (automatic: the parametric patch, even when it folds over a loop around
  /// the surface's outside) to boundary loops too (e.g. the puncture the one-cone pipeline cuts
  /// into a closed genus-0 scan, which the caller must close); off: they throw.
  bool fallback_boundary = false;
  /// Boundary loops only: refuse (throw) when the loop's projection is not simple. Cone and
  /// excluded holes are always checked (a fold cannot be filled by a height field).
  bool require_simple_projection = true;
  KnotCloudOptions knots;
  /// When not null and set, fill_rim stops at its next check (between its patches and their
  /// stages) and throws ricci::Cancelled: a caller that no longer needs the patch gets its
  /// thread back (fit_surface's early capping of a round that folds).
  const std::atomic<bool>* cancel = nullptr;
};

/// Position, first derivatives in D's coordinates and unit normal (Pu x Pv) of the patch.
struct PatchPoint {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Vector3d du = Eigen::Vector3d::Zero(), dv = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  ///< zero where degenerate
};

/// A filled rim: the planar patch, its domain D and the seam figures.
struct HoleFill {
  Rim rim;
  /// The patch's planar DMS space: a regular triangle grid covering D with a margin of two
  /// triangles (so every function reaching D is present: partition of unity on D).
  std::shared_ptr<const PlanarDmsSpace> space;
  Eigen::MatrixX3d control_points;  ///< space->function_count() rows: P = sum c_f N_f
  /// The plane: P(u) = origin + u_x axes.col(0) + u_y axes.col(1) + h(u) normal.
  Eigen::Vector3d origin = Eigen::Vector3d::Zero(), normal = Eigen::Vector3d::UnitZ();
  Eigen::Matrix<double, 3, 2> axes = Eigen::Matrix<double, 3, 2>::Identity();
  /// D's boundary: per rim edge, the projected rim at t = i / q (i = 0..q) and d/dt there; the
  /// boundary runs clockwise around D in rim order (viewed from `normal`).
  std::vector<std::vector<Eigen::Vector2d>> boundary_points, boundary_tangents;
  std::vector<Eigen::Vector2d> corners;              ///< corners[j] = parameter(j, 0)
  /// A point D is star-shaped from, when it is (the mean of D's boundary points otherwise).
  Eigen::Vector2d center = Eigen::Vector2d::Zero();
  double diagonal = 1.0;  ///< bounding-box diagonal of the domain mesh: unit of the gaps
  /// False for the positions-only fallback (FillOptions::fallback); then `normal`/`axes` are
  /// informative only (P is not a height field) and fallback_reason holds the height-field
  /// failure.
  bool g1 = true;
  std::string fallback_reason;

  // Seam figures (measure_seam at FillOptions::samples_per_edge).
  double max_normal_jump_deg = 0.0;  ///< max angle between the surface's and patch's normals
  /// By rim edge: its largest normal jump (degrees).
  std::vector<double> edge_normal_jump_deg;
  double max_position_gap = 0.0;     ///< max |P - S| / diagonal
  double rms_position_gap = 0.0;     ///< RMS |P - S| / diagonal
  int seam_samples = 0;

  /// Parameter point in D of rim sample (edge j, t in [0, 1]): the cubic Hermite interpolant
  /// of boundary_points/boundary_tangents (exact at t = i / q).
  [[nodiscard]] Eigen::Vector2d parameter(int edge, double t) const;
  /// The patch at a parameter point (D, or its margin).
  [[nodiscard]] PatchPoint evaluate(const Eigen::Vector2d& u) const;
  /// Value, gradient and Hessian (3 components) of the patch at a parameter point.
  [[nodiscard]] SplineJet jet(const Eigen::Vector2d& u) const;
};

/// Fills one rim of `spline` with a G1 patch (FillOptions::method; the header comment).
/// \pre `domain_mesh` is the spline space's mesh; `rim` came from find_rims on them.
/// \throw ricci::InvalidInputError on bad options, a rim of fewer than 3 edges, or a rim that
///        is no height field over any tried plane (a normal too steep, a projection that is
///        not simple; the message names the rim and the reason);
///        ricci::SolverError when the least-squares system cannot be solved;
///        ricci::Cancelled when options.cancel is set while it runs.
[[nodiscard]] HoleFill fill_rim(const ManifoldSpline& spline, const ricci::Mesh& domain_mesh,
                                const Rim& rim, const FillOptions& options = {});

struct SeamReport {
  double max_normal_jump_deg = 0.0;
  /// By rim edge: the largest normal jump (degrees) at its samples.
  std::vector<double> edge_normal_jump_deg;
  double max_position_gap = 0.0;  ///< relative to fill.diagonal
  double rms_position_gap = 0.0;  ///< relative to fill.diagonal
  int samples = 0;
};

/// Normal-angle jump (degrees) and position gap between the surrounding spline (evaluated on
/// the rim edge inside its domain face, one-sided) and the patch, at the rim parameters of
/// fill_detail::rim_edge_parameters (t = i / samples_per_edge, graded towards the rim's
/// vertices) and at 64 steps within 1.5 knot-cloud radii of each rim vertex, refined by
/// bisection wherever either normal turns by more than 0.1 degrees between neighbouring samples
/// (down to 1e-7 of a rim edge, at most 16384 samples an edge), so that a surface turning fast
/// inside a vertex's knot cloud is not stepped over; the RMS gap and
/// `samples` count the uniform ones. Normals are compared with their orientation (a flipped
/// patch reports ~180 degrees).
/// \throw ricci::InvalidInputError when samples_per_edge < 1.
[[nodiscard]] SeamReport measure_seam(const ManifoldSpline& spline, const HoleFill& fill,
                                      int samples_per_edge = 100);

/// The patch triangulated at density d (d segments per rim edge): nested copies of D's boundary
/// shrunk towards `center`, or, where D is not star-shaped from it, ricci::triangulate_region.
/// Vertex indices: i >= 0 is the interior vertex i (rows of positions/normals/parameters);
/// i < 0 is rim sample -(1 + (j * d + s)) for rim edge j, sample s in 0..d-1 (sample (j, d) is
/// (j + 1, 0)). The rim samples are not in `positions`: the caller welds them to the surface's
/// own vertices at rim_edge_barycentric(edge j, s / d). Triangles are oriented like the
/// surrounding surface (counter-clockwise in the atlas charts), so surface + patches form a
/// consistently oriented closed surface.
struct PatchTessellation {
  Eigen::MatrixX3d positions, normals;  ///< interior vertices
  Eigen::MatrixX2d parameters;          ///< interior vertices, in D
  Eigen::MatrixX3i triangles;
};

/// \throw ricci::InvalidInputError when d < 1 or D's boundary at density d is not simple.
[[nodiscard]] PatchTessellation tessellate_fill(const HoleFill& fill, int d);

}  // namespace spline
