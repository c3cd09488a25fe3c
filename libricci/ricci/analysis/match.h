#pragma once
// Deformable surface matching through canonical domains (ricci-flow-3d-shape-analysis §5.2,
// Algorithms 8 and 9): each surface is carried by the Ricci flow to a planar parameter domain,
// the two domains are made to coincide on a common convex domain, and the map A -> B is
// tau_B^-1 o phi o tau_A, written as barycentric coordinates of each vertex of A in a face of B.
// The euclidean method (Algorithm 8):
//   rectangle   genus 0, one boundary, no feature vertices: both surfaces conformally onto
//               rectangles (Ricci flow, geodesic curvature pi/2 at four corners: given, or
//               where the boundary turns most), each scaled to the unit square; phi is the
//               affine map between the rectangles.
//   unit disk   genus 0, one boundary, feature vertices given: both surfaces conformally onto
//               the unit disk (ModuleKind::Disk), the feature at 0 and the boundary vertex
//               nearest it (edge paths, 3D lengths) at 1; phi is the identity of the disk.
//   cone star   genus 0, n + 1 >= 2 boundaries: the flat metric with geodesic boundaries and
//               the whole curvature 2 pi chi at a cone on the feature vertex p (steps 1-3), cut
//               along vertex-disjoint shortest paths (flat metric) from p to each boundary
//               (step 4), which leaves one disk whose boundary is 3 (n + 1) arcs: out along a
//               cut, around a boundary loop, back along the cut. Step 5: the disk is cut
//               further along a shortest loop gamma round each loop but c0, through a vertex
//               of its ray (the flat collar of a geodesic boundary makes it about parallel to
//               the loop): a quadrilateral per such loop (ray, loop, ray back, gamma) and one
//               central piece holding the cone's copies. Steps 6-8: each piece of B is carried
//               onto a convex polygon inscribed in its own unit circle, each arc spanning the
//               mean of its two relative flat lengths and parametrised by flat arc length (3D
//               along the rays), by the harmonic map with mean-value weights of the flat metric
//               (one-to-one onto a convex polygon: Rado, Kneser-Choquet, Floater); each piece of
//               A's boundary goes onto B's polygon at the same parameters and its interior by
//               its own harmonic map, so that A's vertices all lie in B's pieces; the pieces
//               glue along the gammas and rays (the same parameters on both sides); phi is the
//               identity there. A loop without a gamma on both surfaces (a ray to another loop
//               runs one edge from it) stays in the central piece (MatchOptions::decompose).
// The hyperbolic method (Algorithm 9):
//   klein       genus 0, n + 1 >= 3 boundaries: the hyperbolic metric with geodesic boundaries;
//   polygon     the loops joined into a tree by n shortest paths (Prim's order from c0,
//               vertex-disjoint), which leaves one disk: a right-angled hyperbolic polygon of
//               4n sides (the paper cuts pants into right-angled hexagons instead), laid out in
//               the Poincaré disk and carried to the Klein model, where its sides are chords and
//               it is convex. B is mapped onto its polygon (the sides bowed out by a parabola
//               so that no face lies flat on a side), A onto B's boundary polygon: the boundary
//               by hyperbolic arc length along each side, the interior by the mean-value
//               harmonic map of each surface's own Klein layout (which it reproduces when the
//               sides are straight).
// Boundary loops are ranked by 3D length (c0 the longest, as for the circle-domain module).
// Cone star: the loops correspond by rank; the cuts must leave the feature vertex in the same
// cyclic order of loops on both surfaces, else the loops pair by that order where their
// lengths agree (MatchOptions::loop_length_tolerance), else by length alone, one surface's
// rays forced to leave p in the other's cyclic order (each from its own neighbour of p: the
// feature needs a neighbour per loop, and a forced ray may detour). Klein polygon: B's loops pair
// with A's by their conformal invariants, the hyperbolic lengths of the loops and the hyperbolic
// distances between them (MatchOptions::loop_invariant_tolerance), not by rank, which a
// deformation permutes among loops of about one length; the cuts must join the paired loops in
// the same order on both surfaces.
#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "ricci/flow/flow.h"
#include "ricci/mesh/mesh.h"

namespace ricci {

enum class MatchMethod { euclidean, hyperbolic };

/// "euclidean", "hyperbolic".
std::string to_string(MatchMethod method);
/// \throw InvalidInputError for another name.
[[nodiscard]] MatchMethod parse_match_method(const std::string& name);

struct MatchOptions {
  /// euclidean (Algorithm 8) or hyperbolic (Algorithm 9, three or more boundary loops).
  MatchMethod method = MatchMethod::euclidean;
  /// Interior vertices of A and B that correspond (the cone of the cone star, the centre of
  /// the unit disk); both -1 = the interior vertex farthest (3D edge paths) from the boundary
  /// of each surface among those with a neighbour per boundary loop. A disk with both -1 is
  /// matched through the rectangle. Not for the hyperbolic method.
  int feature_a = -1;
  int feature_b = -1;
  /// Flow settings; a flow that stops short of the tolerance but below accepted_error (max
  /// |K - K̄|, radians) counts as converged. The map is a harmonic map onto a convex polygon,
  /// one-to-one whatever the metric, which only places the cuts and weighs the edges: when the
  /// inversive-distance metric fails (slivers, a large cone), the flow falls back to the other
  /// metrics, down to the combinatorial one (not conformal; ParameterDomain::metric says).
  FlowOptions flow = [] {
    FlowOptions o;
    o.tolerance = 1e-8;
    o.fall_back_to_other_metrics = true;
    return o;
  }();
  double accepted_error = 1e-4;
  /// The cone's curvature 2 pi chi is spread evenly over the feature vertex and the interior
  /// vertices within this many rings of it (0: the vertex alone).
  int cone_rings = 2;
  /// Cone star: decompose each surface into convex pieces (Algorithm 8, steps 5-8): a
  /// quadrilateral between each loop but c0 and a shortest loop round it through its ray
  /// (gamma, near the ray's middle), and one central piece with the cone; corresponding pieces
  /// are mapped harmonically onto common convex polygons and glued along the gammas. Loops
  /// without a gamma on both surfaces stay in the central piece. false: one convex piece.
  bool decompose = true;
  /// Cone star: when the rays leave the feature towards the loops in another cyclic order on
  /// A and B (loops of about the same length swap ranks under a deformation), the loops pair by
  /// that cyclic order instead, at each turn whose pairs have relative 3D lengths (over the
  /// whole boundary's) within this fraction of each other; of those, the turn with the
  /// smallest shape error. No such turn: the loops pair by these lengths alone (up to 4
  /// pairings, the closest first) and one surface's rays are forced into the other's cyclic
  /// order round p; none of those either: InvalidInputError.
  double loop_length_tolerance = 0.05;
  /// Klein polygon: the pairings of B's loops with A's (permutations; up to 8 loops, more pair
  /// by rank) are ordered by the relative difference of their invariants, sqrt(sum (x_A -
  /// x_B)^2 / sum x_A^2) over the loops' hyperbolic lengths and the hyperbolic distances
  /// between loops; those within this of the closest (at most loop_pairings of them) are each
  /// mapped, and the map with the smallest shape error is kept.
  double loop_invariant_tolerance = 0.05;
  int loop_pairings = 8;
  /// Rectangle: four boundary vertices of A and the four of B they correspond to, in the
  /// boundary's counter-clockwise order (ModuleOptions::corners). Empty = the four vertices
  /// where the boundary turns most in 3D, at least 1/20 of its length apart, the lowest index
  /// first.
  std::vector<int> corners_a;
  std::vector<int> corners_b;
};

/// Where a vertex of A lands on B: inside face `face` of B (index in B), the point
/// sum_k weights[k] * B.point(vertices[k]) (weights >= 0, summing to 1).
struct MapPoint {
  int face = -1;
  std::array<int, 3> vertices = {-1, -1, -1};
  Eigen::Vector3d weights = Eigen::Vector3d::Zero();
};

/// One surface in the common parameter domain: the mesh cut open (the rectangle: not cut).
struct ParameterDomain {
  Eigen::MatrixX3i faces;  ///< By face of the mesh (same index), into positions.
  /// By cut vertex, in the unit square or unit disk; cone pieces: piece k in the unit disk
  /// about (3 k, 0).
  Eigen::MatrixX2d positions;
  std::vector<int> to_original_vertex;  ///< By cut vertex: the mesh vertex.
  int feature = -1;                     ///< The cone vertex or disk centre, else -1.
  std::vector<int> corners;             ///< Rectangle: the corner vertices, ccw from corner 0.
  /// Cone star: loops (by 3D length rank) around p, ccw. Klein polygon: the loop of each
  /// boundary side, ccw, by the rank of A's loop it is paired with.
  std::vector<int> loop_order;
  std::string metric;  ///< The metric of the flow that converged (FlowResult::metric.scheme).
  int flow_iterations = 0;
  double flow_error = 0;  ///< max |K - K̄| of the flow.
  double seconds = 0;     ///< Flow, cut and parametrisation of this surface.
};

struct MatchResult {
  std::string domain;         ///< "rectangle", "unit disk", "cone star" or "klein polygon".
  std::vector<MapPoint> map;  ///< By vertex of A.
  ParameterDomain a, b;
  /// Shape error d_g of eq. (13): the area-weighted mean of |r_A(p) - r_B(phi(p))| over A,
  /// divided by B's bounding-box diagonal (a fraction; x100 for %).
  double shape_error = 0;
  /// When A and B have the same vertex count and faces: d_g of the map against the vertex
  /// correspondence (r_A replaced by r_B of the same vertex index): 0 for the identity. NaN
  /// otherwise.
  double correspondence_error = 0;
  /// Convex pieces of the common domain: 1 + the loops with a gamma for the cone star
  /// (MatchOptions::decompose), else 1.
  int pieces = 1;
  /// Faces of A whose image in B's parameter domain has signed area <= 0, and faces of B
  /// reversed or degenerate in the parameter domain. The map is one-to-one when both are 0.
  int flipped_faces = 0;
  int flipped_faces_b = 0;
  /// Faces of A with their three corners on its (cut) boundary (ears, and faces across a
  /// corner of the cut) that land on one side of B's boundary, so that their image is a segment
  /// (within the rounding of the positions): any map given by vertices that covers B's domain
  /// flattens such a face (its corners go to B's boundary, and B has no vertex between them).
  /// Not counted in flipped_faces: the rest of the map stays one-to-one.
  int flattened_ears = 0;
  /// Vertices of A that fell outside B's parameter domain (on its boundary, within rounding
  /// or the boundary's chords) and were moved to the nearest point of it.
  int snapped_vertices = 0;
  double snap_distance = 0;  ///< Largest such move, in parameter units.
  double seconds = 0;        ///< Wall clock of the whole call.
};

/// Matches A to B (see the file comment).
/// \pre connected oriented triangle 2-manifolds without degenerate faces.
/// \throw InvalidInputError for different topologies, closed surfaces, genus above 0, the
///        hyperbolic method with fewer than three loops or with features or corners, a feature
///        vertex out of range, on the boundary or with fewer neighbours than boundary loops,
///        only one feature or corner set given, bad corners (see conformal_module), or cuts
///        that differ between A and B (see the file comment); TopologyError for a non-manifold
///        or disconnected mesh, or when no vertex-disjoint shortest paths make the cuts;
///        SolverError when a flow does not converge (or B's Klein polygon is not convex).
[[nodiscard]] MatchResult match_surfaces(const Mesh& a, const Mesh& b,
                                         const MatchOptions& options = {});

/// Texture error d_t of eq. (14): the area-weighted mean over A of |c_A(p) - c_B(phi(p))|
/// over the area-weighted mean of |c_B| over B (colours linear over faces, |.| the RGB norm).
/// \pre `result` maps A to B; colours by vertex (#V by 3), e.g. ColouredMesh::colours.
/// \throw InvalidInputError when a colour matrix does not match its mesh, or B is all black.
[[nodiscard]] double texture_error(const Mesh& a, const Mesh& b, const MatchResult& result,
                                   const Eigen::MatrixX3d& colours_a,
                                   const Eigen::MatrixX3d& colours_b);

/// The map as text (docs/match-map.md): a header line "msp-map 1 <vertices of A> <vertices of
/// B> <faces of B>", then one line per vertex of A: "face i j k wi wj wk".
[[nodiscard]] std::string surface_map_text(const MatchResult& result, int vertices_b, int faces_b);

}  // namespace ricci
