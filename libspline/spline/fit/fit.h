#pragma once
// Control points of a manifold spline: the paper's initial choice (the piecewise-linear surface
// reproduced face by face) and a least-squares fit to points with a thin-plate smoothness term;
// closest-point projection onto the spline; and the whole scan pipeline (simplify, atlas, fit,
// fair) of manifold-splines section 5.
#include <Eigen/Core>
#include <functional>
#include <optional>
#include <memory>
#include <string>
#include <vector>

#include "ricci/mesh/mesh.h"
#include "ricci/mesh/boundary_follow.h"
#include "ricci/mesh/collar.h"
#include "ricci/pipeline/one_cone_atlas.h"
#include "spline/fair/fair.h"
#include "spline/fill/puncture.h"
#include "spline/fit/boundary_curve.h"
#include "spline/manifold/manifold_space.h"

namespace spline {

/// Per domain face, the degree-1 polynomial L_I mapping I's corners (in its neighbourhood chart)
/// to the mesh's 3D vertex positions, seen as degree n: c_{I,beta} = L_I(mean of beta's blossom
/// arguments) (the "domain points"). F then equals the mesh up to the knot clouds' spread.
/// \pre space was built on `mesh`.
[[nodiscard]] Eigen::MatrixX3d piecewise_linear_control_points(const ManifoldSplineSpace& space,
                                                               const ricci::Mesh& mesh);

struct FitOptions {
  /// lambda: weight of the thin-plate energy. The objective is
  ///   sum_k |F(u_k) - p_k|^2 + lambda (N / A) h^4 E(F) + anchor (N / #functions) |c - c_0|^2,
  /// N the number of points, E the thin-plate energy int (|F_uu|^2 + 2 |F_uv|^2 + |F_vv|^2),
  /// A the domain's area and h its mean edge length, so lambda compares a point residual with a
  /// second difference over one edge (dimensionless). Lower lambda lowers the RMS at the points
  /// and lets the surface fold between them.
  double smoothing = 1e-4;
  /// true: E, A and h are those of the surface, not of the charts: face I's part of E is
  /// weighted by s_I^2 = 1 / J_I, J_I = |F0_u x F0_v| at I's centre for the initial surface F0
  /// (the area ratio 3D / chart), which is the thin-plate energy in a locally isometric
  /// parameterisation (the one-cone atlas shrinks parts of the surface by large factors in the
  /// chart, where a chart-measured energy over-smooths them). false: chart measure.
  bool isometric_smoothing = true;
  /// Faces within `rim_rings` (edge-adjacency) rings of the domain's rim (the cone's hole, open
  /// boundaries) use at least this smoothing: their functions lack neighbours (no partition of
  /// unity) and few points reach them, so with light smoothing the surface there swings its
  /// normal more than a G1 hole filling can meet.
  double rim_smoothing = 1e-3;
  int rim_rings = 3;
  /// Faces reached by fewer points than they carry functions ((n + 1)(n + 2) / 2) use at least
  /// this smoothing: the points cannot determine them, and with lambda alone the surface folds
  /// there.
  double sparse_smoothing = 1e-3;
  /// Optional, by face of the space's mesh: the smoothing each face uses at least (locally
  /// stronger fairing where a surface folded, fit_surface's fold rounds); empty: none.
  std::vector<double> face_smoothing;
  /// Keeps the normal matrix SPD where no point reaches a function (dimensionless, tiny).
  double anchor = 1e-8;
  /// >= 0: fit subject to the fairing constraints of this r (fair.h, eq. 14's constraints): the
  /// best constrained surface for the points, where fitting first and projecting the control
  /// points afterwards (eq. 14) loses the fit. Solved by solve_constrained (constrained_solve.h).
  /// -1: unconstrained.
  int constraint_r = -1;
  /// w relative to the mean diagonal of the (reduced) normal matrix; lowered automatically when
  /// the factorisation fails.
  double constraint_penalty = 1e6;
  /// By face of the space's mesh, nonzero: the fairing constraints of constraint_r tie this face
  /// (FairOptions::active_faces); empty: every face.
  std::vector<char> constraint_faces;
  int constraint_iterations = 100;
  /// Worker threads of the assembly and of the residuals (the result does not depend on it
  /// beyond rounding of the sum order).
  int threads = 2;
};

struct FitResult {
  Eigen::MatrixX3d control_points;
  int points = 0;                  ///< points used (those with a domain face)
  double rms_at_parameters = 0.0;  ///< of |F(u_k) - p_k| (no projection)
  double max_at_parameters = 0.0;
  double seconds_assemble = 0.0, seconds_solve = 0.0;
  double max_constraint_residual = 0.0;  ///< max |C c| when constrained
  int constraint_rows = 0;               ///< rows of C when constrained
  int constraint_iterations = 0;         ///< multiplier updates when constrained
  int reduced_unknowns = 0;  ///< unknowns after merging shared control points (constrained)
  bool anchor_raised = false;  ///< the factorisation needed a larger anchor (rounding)
};

/// Least-squares fit (normal equations, CHOLMOD supernodal). Points whose face is -1 or outside
/// the domain are skipped. `initial` (function_count() x 3) anchors unreached functions.
/// \throw ricci::InvalidInputError on size mismatches; ricci::SolverError if the solve fails.
[[nodiscard]] FitResult fit_control_points(const ManifoldSplineSpace& space,
                                           const std::vector<DomainPoint>& parameters,
                                           const Eigen::MatrixX3d& points,
                                           const Eigen::MatrixX3d& initial,
                                           const FitOptions& options = {});

/// fit_control_points with the thin-plate and anchor weights set up from `setup_parameters`
/// rather than `parameters`: their scale (the count of points in the domain) and the faces
/// FitOptions::sparse_smoothing raises (those reached by few points) follow setup_parameters.
/// fit_scan sets them up once, before its parameter corrections
/// (ScanFitResult::setup_parameters); a refit of its data with the corrected parameters passes
/// them here and smooths every face as the fit it repeats did. The two may differ in size
/// (fit_scan appends missed boundary samples after the setup).
/// \throw as fit_control_points.
[[nodiscard]] FitResult fit_control_points(const ManifoldSplineSpace& space,
                                           const std::vector<DomainPoint>& setup_parameters,
                                           const std::vector<DomainPoint>& parameters,
                                           const Eigen::MatrixX3d& points,
                                           const Eigen::MatrixX3d& initial,
                                           const FitOptions& options);

/// The closest point of the spline to `target`, by Gauss-Newton steps on |F(u) - target|^2 from
/// `start`, moving between faces through the neighbourhood charts (stops at the hole's rim).
struct Projection {
  DomainPoint point;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  double distance = 0.0;
};
[[nodiscard]] Projection project_to_spline(const ManifoldSpline& spline, const DomainPoint& start,
                                           const Eigen::Vector3d& target, int iterations = 6);

struct FitErrors {
  int points = 0;
  double rms = 0.0, max = 0.0;  ///< distances to the spline (after projection)
};
/// Distances of points (with parameters; face -1 skipped) to the spline after projection, on
/// `threads` workers.
[[nodiscard]] FitErrors fit_errors(const ManifoldSpline& spline,
                                   const std::vector<DomainPoint>& parameters,
                                   const Eigen::MatrixX3d& points, int iterations = 6,
                                   int threads = 2);

/// By domain index: rings (across edges) from the domain's rim, 0 for a face with a missing or
/// non-domain neighbour, -1 everywhere when there is no rim (closed surface without a hole).
[[nodiscard]] std::vector<int> domain_rim_rings(const ManifoldSplineSpace& space);

/// Parameter correction (Hoschek's remedy for poor foot points): each point's parameter moved to
/// its closest point on `spline` (project_to_spline from the current parameter). A projection
/// that ends on the domain's rim (clamped there: the point lies over the hole or beyond an open
/// boundary) keeps the old parameter, so the set of fitted points never changes. Points with
/// face -1 stay -1. Runs on `threads` workers.
struct CorrectedParameters {
  std::vector<DomainPoint> parameters;
  int moved = 0;  ///< points whose parameter changed
};
[[nodiscard]] CorrectedParameters correct_parameters(const ManifoldSpline& spline,
                                                     const std::vector<DomainPoint>& parameters,
                                                     const Eigen::MatrixX3d& points,
                                                     int iterations = 6, int threads = 2);

struct ScanFitOptions {
  int domain_faces = 2000;  ///< target size of the simplified domain mesh
  int degree = 3;
  int fair_r = 1;  ///< fairing after the fit; -1 = none
  /// Fit subject to the fairing constraints of fair_r (then fairing changes nothing and is
  /// skipped); false: fit freely, then fair by eq. 14 (projection of the control points), which
  /// loses most of the fit.
  bool constrained_fit = true;  // (when true, fairing afterwards is skipped: it changes nothing)
  /// Rounds of parameter correction (correct_parameters, then refit) after the first fit: the
  /// first parameters are closest points on the piecewise-linear domain mesh, whose tangential
  /// foot-point error would otherwise be fitted as if it were shape. Each round costs one
  /// projection of every point and one refit.
  int parameter_corrections = 1;
  /// Gauss-Newton steps of each correction's projection (project_to_spline).
  int correction_iterations = 2;
  FitOptions fit;
  /// From this genus on (a single cone of angle 2 pi (2g - 1)), the faces with a corner within
  /// free_cone_rings edges of the cone are fitted free of the fairing constraints
  /// (FitOptions::constraint_faces): there the one-cone chart is z^(2g - 1) of the surface, its
  /// faces are slivers whose neighbours' polynomials, blossomed across an edge, predict the face
  /// badly, and the constrained fit folds the spline there (docs/design-notes.md has the
  /// figures). The spline stays C^(n-1) (its basis is); only eq. 14's fairing is dropped there.
  /// 0: never.
  int free_cone_faces_from_genus = 10;
  /// Vertex rings of the domain (after the cone refinement) around the cone whose faces are
  /// freed: the rings that hold the chart's slivers at genus 10 (more rings let the spline fold
  /// farther out).
  int free_cone_rings = 8;
  FairOptions fair;  ///< its r is replaced by fair_r
  KnotCloudOptions knots;
  /// The atlas, with the cone's neighbourhood sampled densely (cone_refinement, 2 levels of 6
  /// rings: ricci/singularity/one_cone.h), so the spline does not fold next to a large cone.
  /// The circle packing's metric route (not the intrinsic flow or the inversive-distance route
  /// msp atlas takes first by default): with it the bundled genus-3 model's Bezier export meets
  /// the spline to 1e-12 of the diagonal (3.7e-11 with the route). The intrinsic flow still
  /// runs where the circle packings fail (genus >= 4 directly).
  ricci::OneConeAtlasOptions atlas = [] {
    ricci::OneConeAtlasOptions o;
    o.cone_refinement.levels = 2;
    o.inversive_distance_route = false;
    o.intrinsic_first = false;
    return o;
  }();
  /// Closed genus-0 surfaces with the automatic singularity: the puncture (the removed star
  /// the fill patch covers) goes to the flattest of the vertices verified within a tolerance
  /// of the least area distortion (spline/fill/puncture.h). distortion_tolerance 0: the
  /// distortion's choice, as the atlas makes it.
  PunctureChoiceOptions puncture;
  /// Open surfaces: ghost rings added outside the simplified domain's boundary loops
  /// (ricci/mesh/collar.h) before the atlas, so the spline has its full basis on every face of
  /// the surface up to the boundary; ScanFitResult::collar_faces says which faces to drop.
  /// rings = 0: none (the band along the boundary then lacks the partition of unity).
  ricci::CollarOptions collar;
  /// Open surfaces: the simplified domain's boundary edges split until its boundary follows the
  /// scan's within boundary_follow.tolerance of the diagonal (ricci/mesh/boundary_follow.h), so
  /// the surface's boundary reaches the scan's. max_rounds = 0: off.
  ricci::BoundaryFollowOptions boundary_follow;
  /// Open surfaces with a collar: the surface's boundary fitted to the scan's boundary curve
  /// (spline/fit/boundary_curve.h); weight 0: off.
  BoundaryCurveOptions boundary_curve;
  /// An input of at most domain_faces faces (a coarse CAD mesh, often with slivers) is
  /// isotropically remeshed to domain_faces for the domain, like a simplified scan; false: the
  /// input itself is the domain.
  bool remesh_coarse_inputs = true;
  /// Data points: the input's vertices and face centroids, plus points on a barycentric grid of
  /// each input face until there are at least this many per control point (a coarse input
  /// gives too few points for the spline's control points otherwise).
  double data_points_per_control_point = 1.0;
  /// Dense inputs: when the input's vertices alone are at least this many per control point,
  /// they are the only data points (no face centroids), which divides the cost of the
  /// parameters, the fit and the corrections by about 3 on a 1M-face scan. The measures of the
  /// delivered surface still take every input vertex.
  double vertices_only_per_control_point = 16.0;
  /// Each data point's parameter is the closest point of the domain on a face facing the same
  /// way as the input there (ricci::closest_points with normals), not merely the closest point
  /// (on thin parts the closest point can lie on the other side). Off by default: on the
  /// shared scans it changed no fold count and raised femur's largest error.
  bool oriented_parameters = false;
  /// On the intrinsic route (genus >= 4): each data point is placed on the faces the flow
  /// started from and carried through its flips (ricci::place_on_problem_mesh, exact), not by
  /// closest point onto the flipped triangulation's faces, which are chords of the surface.
  /// Off by default: the parameter correction that follows leaves the surfaces of the generated
  /// genus 4-10 meshes, anchor and fertility within 0.4 degrees of seam of the chords' (docs/
  /// design-notes.md, "Tracked parameters").
  bool tracked_parameters = false;
  /// The domain mesh to build the spline on instead of simplifying the input (a domain refined
  /// after an earlier fit); it must have the input's topology. Empty: simplify the input.
  std::optional<ricci::Mesh> domain;
  /// Optional progress: called with a stage name when that stage starts.
  std::function<void(const std::string& stage)> progress;
};

struct ScanFitTimings {
  double simplify = 0, atlas = 0, space = 0, parameters = 0, fit = 0, fair = 0, total = 0;
  double correction = 0;  ///< parameter correction: projections and refits after the first fit
};

struct ScanFitResult {
  ricci::OneConeAtlasResult atlas;  ///< atlas.problem.mesh is the spline's domain mesh
  /// The puncture's choice (ScanFitOptions::puncture) when it was made; vertex -1 otherwise.
  PunctureChoice puncture;
  ManifoldSpline spline;
  /// By input vertex, after the parameter corrections; face -1: not covered by the spline
  /// (closest point of the domain mesh in a hole face, or on the rim of the domain, an edge or a
  /// vertex of it: over a punctured sphere's hole or beyond an open boundary; or so close to the
  /// rim that the basis is no partition of unity there, a band the fill patches cover). Those
  /// points are neither fitted nor measured.
  std::vector<DomainPoint> vertex_parameters;
  int uncovered_points = 0;  ///< vertices and face centroids of the input left out that way
  /// Data points taken from the input: its vertices, then its face centroids and grid points
  /// unless the vertices alone were enough (ScanFitOptions::vertices_only_per_control_point).
  int scan_data_points = 0;
  FitResult fit;
  FairResult fairing;
  ScanFitTimings timings;
  int corrections = 0;  ///< parameter-correction rounds run
  /// Faces fitted free of the fairing constraints (ScanFitOptions::free_cone_faces_from_genus).
  int unconstrained_faces = 0;
  int boundary_refits = 0;  ///< refits after raising missed boundary samples' weight
  /// By face of the domain mesh (atlas.problem.mesh): nonzero on the ghost faces of the
  /// boundary collar (ScanFitOptions::collar), which are fitted but are not the surface; empty
  /// when no collar was added (closed surfaces, collar.rings = 0, or refused).
  std::vector<char> collar_faces;
  /// Why the collar was dropped (the atlas failed on the collared mesh), empty otherwise.
  std::string collar_refused;
  /// What follow_boundary did to the simplified domain (zeros when nothing was simplified).
  ricci::BoundaryFollowResult boundary_follow;
  /// The domain before the collar and the atlas (simplified, boundary followed, or the given
  /// ScanFitOptions::domain): what a refinement of the domain starts from.
  ricci::Mesh domain;
  /// What a refit on the same space starts from: every data point fitted (the input's
  /// vertices, face centroids and grid points, boundary samples), its parameter after the
  /// corrections, and the fit options the fit used (constraint_r set).
  Eigen::MatrixX3d data_points;
  std::vector<DomainPoint> data_parameters;
  FitOptions fit_options;
  /// The parameters the fit's thin-plate weights were set up from (those of the first fit,
  /// before the corrections; fit_control_points' setup_parameters for a refit).
  std::vector<DomainPoint> setup_parameters;
  /// The input vertices (data points) whose parameter is pinned on the boundary curve; with
  /// every data point from scan_data_points on (boundary samples), a refit keeps their
  /// parameters as fit_scan's corrections do.
  std::vector<int> pinned_scan_vertices;
};

/// Simplify the scan (ricci::simplify_mesh, same topology), build the one-cone atlas on it, the
/// space, parameters of the scan's vertices and face centroids by closest point on the domain
/// mesh (points not covered by the spline left out, see vertex_parameters), fit, correct the
/// parameters and refit (parameter_corrections rounds), then fair.
/// \throw as simplify_mesh, build_one_cone_atlas, fit_control_points, fair.
[[nodiscard]] ScanFitResult fit_scan(const ricci::Mesh& dense, const ScanFitOptions& options = {});

}  // namespace spline
