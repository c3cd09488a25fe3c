#pragma once
// The one-extraordinary-point problem of the manifold-splines paper (section 4): which mesh the
// flow runs on and which curvature it aims for, by topology.
//   closed, genus 1   -> flat torus, no cone;
//   closed, genus >= 2 -> one cone of curvature 2*pi*chi at the chosen vertex, after valence
//                         modification;
//   closed, genus 0   -> the chosen vertex's star is removed (a cone of 4*pi has no flat
//                         realisation) and the new boundary carries the curvature 2*pi;
//   open               -> flat interior, all curvature (2*pi*chi) on the boundary, by default
//                         where the boundary keeps its lengths (open_target.h); spread by
//                         length or as a circle domain when that flow fails.
#include <string>
#include <vector>

#include "ricci/flow/continuation.h"
#include "ricci/flow/flow.h"
#include "ricci/flow/targets.h"
#include "ricci/mesh/mesh.h"
#include "ricci/mesh/primitives.h"
#include "ricci/singularity/valence.h"

namespace ricci {

enum class OneConeKind { FlatTorus, SingleCone, PuncturedSphere, OpenSurface };

std::string to_string(OneConeKind kind);

struct OneConeProblem {
  OneConeKind kind = OneConeKind::FlatTorus;
  Mesh mesh;            ///< The mesh the flow runs on (valence-modified or punctured).
  int cone = -1;        ///< Cone vertex in `mesh` (SingleCone only), else -1.
  int chosen_vertex = -1;  ///< The input vertex the problem was built around, -1 if unused.
  /// mesh vertex index -> input vertex index, or -1 for a vertex added by an edge split.
  std::vector<int> input_vertex;
  Targets targets;
  int valence_splits = 0;
  /// Rounds of local midpoint subdivision applied first because some face's neighbourhood
  /// wrapped around a thin handle or tube (mesh/neighbourhoods.h); 0 on most meshes.
  int subdivisions = 0;
  int genus = 0;
  int boundary_loops = 0;
};

/// At most this many rounds of local midpoint subdivision are spent on thin handles.
inline constexpr int kMaxHandleSubdivisions = 3;

/// Builds the problem around `vertex` (ignored for genus 1 and open surfaces). When some face's
/// neighbourhood is not a disk (a handle a few edges thick) those faces are first subdivided
/// (red-green), at most kMaxHandleSubdivisions rounds; input vertices keep their indices.
/// \pre a connected oriented 2-manifold triangle mesh.
/// \throw InvalidInputError for a vertex out of range or on the boundary when it is needed.
/// `refine_thin_handles` = false skips that (the flow alone does not need it: the singularity
/// choice's verifying flows run on the mesh as it is).
[[nodiscard]] OneConeProblem prepare_one_cone(const Mesh& mesh, int vertex,
                                              const ValenceOptions& valence = {},
                                              bool refine_thin_handles = true);

/// The same with thin handles refined, given `non_disk_faces` =
/// non_disk_face_neighbourhoods(mesh) (mesh/neighbourhoods.h), computed earlier (e.g. beside the
/// singularity choice: it needs no cone). \throw as above; InvalidInputError when its size is not
/// the mesh's face count.
[[nodiscard]] OneConeProblem prepare_one_cone(const Mesh& mesh, int vertex,
                                              const ValenceOptions& valence,
                                              const std::vector<char>& non_disk_faces);

/// Default flow settings for one-cone problems (scheme and radii are chosen per problem by
/// solve_one_cone_flow; tolerance 1e-10).
[[nodiscard]] FlowOptions one_cone_flow_options();

/// The metrics tried, in order, for a problem of this kind. Flat tori, open and punctured
/// surfaces start with the inversive distance (it reproduces the mesh, so the result is the most
/// conformal); a large cone (-4*pi for genus 2, -8*pi for genus 3) breaks inversive-distance
/// triangles on the shared scans, so single cones start with Thurston circle packing. The
/// combinatorial metric (tangent circles, Phi = 0) comes last: Thurston's theorem guarantees it
/// once the cone has valence >= 4 - 2K/pi, but it ignores the mesh's shape.
[[nodiscard]] std::vector<std::pair<Scheme, RadiusInit>> one_cone_metric_order(OneConeKind kind);

/// Runs the flow with the metrics of one_cone_metric_order until one converges (single cones
/// first try cone_tangent_metric with 3 rings, then that order; the options'
/// scheme and radii are overridden unless `keep_metric`). The result's failed_attempts lists the
/// runs that did not converge. Returns the last attempt when none converged. `first_metric`
/// skips that many metrics at the head of the order (the last one is always tried; the
/// singularity choice skips those that failed at every candidate it verified first).
[[nodiscard]] FlowResult solve_one_cone_flow(const OneConeProblem& problem, const FlowOptions& options,
                                             bool keep_metric = false, int first_metric = 0);

/// Position in one_cone_metric_order(kind) of the metric a solve_one_cone_flow result names
/// (FlowResult::metric_name); -1 for any other (the cone-tangent start, a continuation).
[[nodiscard]] int metric_order_position(OneConeKind kind, const std::string& metric_name);

/// A metric that differs near a single cone: `far` (the mesh's inversive distance or Thurston
/// circle packing, radii by `radii`) on the edges with both ends `rings` or more rings from the
/// cone, and `near` on the others: circle_packing (Thurston's angles, the inversive distance
/// clamped to [0, pi/2]) or combinatorial (tangent circles).
struct ConeRingMetric {
  Scheme far = Scheme::inversive_distance;
  Scheme near = Scheme::circle_packing;
  int rings = 4;
  RadiusInit radii = RadiusInit::mean;
  /// The edges of faces with a corner below this angle (radians, in the mesh) get `near` too,
  /// wherever they are: the inversive distance of a needle's short edge sits near -1, where its
  /// length is most sensitive to the radii (0 = none).
  double needle_angle = 0.0;
  /// Shrink the radii where two circles overlap by more than a right angle (I < 0) until every
  /// inversive distance is >= 0, the regime where the energy is locally convex (Guo 2011).
  bool nonnegative_inversive_distance = false;
};

/// The initial metric of `rule` on the mesh of `tables` with lengths `lengths`.
[[nodiscard]] CirclePackingMetric cone_ring_metric(const MeshTables& tables, const EdgeLengths& lengths, int cone,
                                                   const ConeRingMetric& rule);

/// Runs the flow of a single-cone problem from each metric of `rules` in turn until one
/// converges, each by continuation on the target (flow/continuation.h; one stage = the plain
/// flow). The result's failed_attempts lists the runs that did not (an initial metric that breaks
/// a triangle counts as a failed run); the last attempt is returned when none converged
/// (FlowStatus::stalled with an empty metric when `rules` is empty).
/// \throw InvalidInputError unless problem.kind == OneConeKind::SingleCone.
[[nodiscard]] FlowResult solve_cone_ring_flow(const OneConeProblem& problem, const std::vector<ConeRingMetric>& rules,
                                              const FlowOptions& options,
                                              const ContinuationOptions& continuation = {1});

/// "inversive-distance/mean, circle-packing within 4 rings of the cone".
[[nodiscard]] std::string to_string(const ConeRingMetric& rule);

/// Thurston circle packing of the mesh (radii by `radii`, angles from its lengths clamped to
/// [0, pi/2]) except on the edges within `rings` rings of `cone`, which get tangent circles
/// (Phi = 0, as the combinatorial metric): the combinatorial metric's existence condition near
/// the cone, the mesh's conformal structure elsewhere.
[[nodiscard]] CirclePackingMetric cone_tangent_metric(const MeshTables& tables, const EdgeLengths& lengths,
                                                      int cone, int rings, RadiusInit radii);

/// Denser sampling around a single cone (manifold-splines paper, section 4, step 2: "make the
/// sampling in the neighborhood of the singularity much denser"). Near a cone of angle
/// 2 pi alpha the flat metric scales like rho^(alpha - 1) (rho: distance to the cone), so across
/// a face of size h at distance rho the chart's scale changes by about (1 + h / rho)^(alpha - 1):
/// 16x from ring 1 to ring 2 of a uniform mesh at genus 3 (alpha = 5), where a spline over the
/// charts folds and no G1 patch can meet it. Each level splits the faces within `rings` rings
/// of the cone 1-to-4 (red-green, metric/subdivide.h), in the mesh the level before made: two
/// levels of 6 rings leave edges of 1/4 of the input's length within ~3 of its edges of the
/// cone, 1/2 within ~6, so h / rho stays below ~1/6 beyond the innermost rings (the cone's hole
/// covers those).
///
/// The 1-to-4 splits keep each face's radial extent over its distance (dr / rho), and at a cone
/// of 2 pi (2g - 1) the chart stretches a face radially by (1 + dr / rho)^(2g - 1) against
/// (2g - 1) dtheta around: at genus 10 the faces a few rings out are chart slivers (2-17 degree
/// angles) and the spline folds there. From genus radial_from_genus the refinement then grades
/// the mesh log-polar: radial_levels rounds split (at the 3D midpoint, joined to the opposite
/// corners) every edge within radial_rings rings of the cone, off the cone's faces, whose ends'
/// 3D distances rho_a, rho_b from the cone give a chart ratio (2g - 1) |ln(rho_b / rho_a)| above
/// radial_chart_log, so the faces' radial and angular chart extents become comparable. The
/// rounds do not always reach that bound (a split can join a vertex close to the cone again).
/// Off by default (msp fit --cone-grading turns it on); docs/design-notes.md has the figures.
struct ConeRefinementOptions {
  int levels = 0;  ///< rounds of refinement; 0: off
  int rings = 6;   ///< faces with a corner fewer than this many edges from the cone are split
  int radial_from_genus = 0;   ///< genus from which the radial grading runs; 0: never
  int radial_levels = 3;       ///< rounds of radial splits
  int radial_rings = 16;       ///< edges with both ends fewer than this many rings from the cone
  /// ... and at least this many (the cone hole's rings); 0: from the cone
  int radial_inner_rings = 0;
  double radial_chart_log = 1.0;  ///< largest (2g - 1) |ln(rho_b / rho_a)| left unsplit
};

/// What refine_around_cone did.
struct ConeRefinement {
  int levels = 0;       ///< rounds applied (0 when off or not a single cone)
  int added_faces = 0;
  int radial_splits = 0;  ///< edges split by the radial grading (0 below radial_from_genus)
};

/// Applies ConeRefinementOptions to a single-cone problem (a no-op for other kinds or levels 0):
/// the mesh is refined (the surface does not move: midpoints lie on the edges), the cone keeps
/// its vertex index and valence, the added vertices map to input vertex -1 and the targets are
/// recomputed (flat everywhere but the cone).
/// \throw InvalidInputError when levels < 0 or rings < 1, or radial_levels < 0, radial_rings < 1
/// or radial_chart_log <= 0.
ConeRefinement refine_around_cone(OneConeProblem& problem, const ConeRefinementOptions& options);

/// Whether the mesh's topology asks for a singular vertex at all (closed, genus != 1).
[[nodiscard]] bool needs_singular_vertex(const Mesh& mesh);
/// The same from the mesh's surface_topology (ricci/mesh/primitives.h), computed once.
[[nodiscard]] bool needs_singular_vertex(const SurfaceTopology& topology);

}  // namespace ricci
