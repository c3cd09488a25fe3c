#pragma once
// Pieces of match_surfaces shared between its source files (not a public header).
#include <vector>

#include <Eigen/Core>

#include "ricci/analysis/match.h"
#include "ricci/flow/flow.h"
#include "ricci/metric/mesh_tables.h"
#include "ricci/topology/slice.h"

namespace ricci::detail {

/// A disk's boundary walk cut into arcs at its corners.
struct ArcWalk {
  std::vector<int> walk;    ///< The disk's boundary vertices, counter-clockwise.
  std::vector<double> arc;  ///< Flat arc length along the walk (walk.size() + 1 entries).
  /// The length each arc is parametrised by (walk.size() + 1 entries): flat, but 3D along the
  /// cone's rays: the flat metric shrinks them towards the cone (as r^(theta / 2 pi - 1) for
  /// cone angle theta), where flat arc length would crowd the ray's vertices below the
  /// rounding of the unit circle.
  std::vector<double> param_arc;
  std::vector<int> corners;  ///< Walk positions of the arcs' first vertices, rising from 0.
};

/// A surface cut along its cone star (Algorithm 8, step 4): one disk, whose walk starts at a
/// copy of p and whose 3 (n + 1) arcs run out along a ray, around its loop and back.
struct Star : ArcWalk {
  SlicedMesh sliced;
  Eigen::VectorXd lengths;      ///< Flat lengths by sliced edge.
  std::vector<int> loop_order;  ///< Loop rank of each ray, in walk order.
};

/// Algorithm 8, step 4 and the cut (match_star.cpp): vertex-disjoint shortest rays (under the
/// flat metric `flat`) from interior vertex p to each boundary loop, taken in rank order, then
/// (if one is blocked) nearest loop first (`reach_first` swaps the two); the surface sliced
/// along them, its walk from the copy of p whose ray goes to c0.
/// \throw TopologyError when the rays cannot be made vertex-disjoint or the cut is not a disk.
[[nodiscard]] Star cone_star(const Mesh& mesh, const MeshTables& tables, int p,
                             const EdgeLengths& flat, const char* name, bool reach_first);

/// The cone star whose rays leave p towards the loops in the cyclic order `order` (loop ranks,
/// as Star::loop_order, from c0): each ray starts at its own neighbour of p, the neighbours
/// chosen in that order round p's fan as near as can be to the first steps of the free rays,
/// and is the shortest path from there avoiding p, the other starts and the earlier rays
/// (nearest loop first). Where the free rays pass other sides of the holes than on the other
/// surface, this gives both surfaces one cut pattern.
/// \throw TopologyError when no choice of starts gives such rays (p's valence too low, rays
///        fenced in) or the cut is not a disk.
[[nodiscard]] Star ordered_star(const Mesh& mesh, const MeshTables& tables, int p,
                                const EdgeLengths& flat, const std::vector<int>& order,
                                const char* name);

/// The relative flat length of each arc of `w`.
[[nodiscard]] std::vector<double> arc_fractions(const ArcWalk& w);

/// The turn's share of each arc, common to two walks with the same arcs: half by the arcs'
/// mean relative flat lengths, half evenly (a small hole's arcs keep room enough that the
/// harmonic map does not crowd its faces below the rounding).
[[nodiscard]] std::vector<double> common_extents(const ArcWalk& a, const ArcWalk& b);

/// Where each vertex of the walk goes on the turn (a fraction in [0, 1)): arc j spans
/// extents[j], parametrised by ArcWalk::param_arc.
[[nodiscard]] std::vector<double> arc_parameters(const ArcWalk& w,
                                                 const std::vector<double>& extents);

/// Fixes the walk's vertices on the unit circle about `centre` at 2 pi times their parameters.
void place_on_circle(const ArcWalk& w, const std::vector<double>& parameters,
                     const Eigen::Vector2d& centre, Eigen::MatrixX2d& x, std::vector<char>& fixed);

/// Copies the flow's metric, iterations and error into `domain`.
/// \throw SolverError when the flow neither converged nor stalled below options.accepted_error.
void record_match_flow(const FlowResult& flow, const MatchOptions& options, const char* name,
                       ParameterDomain& domain);

/// The mean-value harmonic map (Floater) of the planar metric `lengths` (by edge of `cut`): the
/// rows of `x` not `fixed` become the weighted means of their neighbours. One-to-one when the
/// fixed vertices are the boundary of a disk placed in order on a convex polygon.
/// \throw SolverError when the sparse solve fails.
void harmonic_fill(const Mesh& cut, const Eigen::VectorXd& lengths, const std::vector<char>& fixed,
                   Eigen::MatrixX2d& x);

/// Fixes A's boundary walk vertex i (a row of `x`) at parameter params_a[i] on B's boundary
/// polygon (B's walk at params_b, positions_b), between the vertices of B's walk whose
/// parameters bracket it, linearly in the parameter (see fill_inside).
void place_on_polygon(const std::vector<int>& walk_a, const std::vector<double>& params_a,
                      const std::vector<int>& walk_b, const std::vector<double>& params_b,
                      const Eigen::MatrixX2d& positions_b, double period, Eigen::MatrixX2d& x,
                      std::vector<char>& fixed);

/// A's cut disk placed inside B's convex parameter domain: A's boundary walk vertex i (a vertex
/// of `cut_a`) at parameter params_a[i] goes onto B's boundary polygon, between the vertices of
/// B's walk whose parameters bracket it, linearly in the parameter; the interior by the
/// mean-value harmonic map of `lengths_a`. Both parameter sequences rise from 0 along their
/// walks, below `period`, and A's corners share B's parameters (so land on B's corners). A's
/// boundary is then a weakly convex polygon inside B's and the map stays one-to-one (Floater)
/// with every vertex of A inside B's domain, where a common convex curve sampled at different
/// vertices would leave A's vertices between B's chords and the curve.
/// \throw SolverError when the sparse solve fails.
[[nodiscard]] Eigen::MatrixX2d fill_inside(const Mesh& cut_a, const Eigen::VectorXd& lengths_a,
                                           const std::vector<int>& walk_a,
                                           const std::vector<double>& params_a,
                                           const std::vector<int>& walk_b,
                                           const std::vector<double>& params_b,
                                           const Eigen::MatrixX2d& positions_b, double period);

/// domain.faces and domain.to_original_vertex from the sliced mesh.
void fill_cut_domain(const SlicedMesh& sliced, ParameterDomain& domain);

/// Locates A's vertices in B's parameter domain (phi is the identity there) and fills
/// result.map, the reversed faces and ears, the snaps and the shape errors. `carry_radially`:
/// A's domain is first carried onto B's by a radial map about B's boundary centroid (for two
/// convex domains whose boundaries sample one curve at different vertices); without it A's
/// vertices are taken where they are (fill_inside).
void evaluate_map(const Mesh& a, const Mesh& b, const MeshTables& tables_a,
                  const MeshTables& tables_b, MatchResult& result, bool carry_radially);

/// result.shape_error and result.correspondence_error of result.map (by vertex of A).
void map_errors(const Mesh& a, const Mesh& b, const MeshTables& tables_a,
                const MeshTables& tables_b, MatchResult& result);

/// Algorithm 8, steps 5-8 (match_pieces.cpp): each star's disk (`a` and `b`, B's turned so
/// that its rays pair with A's in walk order) is cut further along a shortest loop gamma_r round
/// each loop but the first (through a vertex x_r of its ray, near the ray's middle: the flat
/// collar of a geodesic boundary makes it parallel to the loop), which leaves a quadrilateral
/// x_r, ray, loop, ray back per such loop and one central piece with the cone's copies. Each
/// piece of B goes onto a polygon inscribed in its own unit circle (centres 3 apart on the x
/// axis) by the mean-value harmonic map, its arcs spanning common_extents of A's and B's; each
/// piece of A onto B's polygon (place_on_polygon) and its interior by its own harmonic map.
/// The gammas are parametrised by flat length on both sides, so the pieces glue. Loops whose
/// gamma is not found on both surfaces stay in the central piece. Fills the positions, faces
/// and vertex maps of result.a and result.b and result.pieces.
/// \throw TopologyError when no loop gets its gamma on both surfaces or the pieces of A and B
///        differ (the caller keeps one piece); SolverError when a sparse solve fails.
void cone_pieces(const Mesh& a, const Star& star_a, const EdgeLengths& flat_a, const Mesh& b,
                 const Star& star_b, const EdgeLengths& flat_b, MatchResult& result);

/// Algorithm 9: both surfaces (genus 0, three or more boundary loops) in the Klein model on
/// B's right-angled polygon (see match.h), B's loops paired with A's by their hyperbolic
/// lengths and distances (MatchOptions::loop_invariant_tolerance). Fills result.domain,
/// result.a, result.b and the map (evaluate_map).
/// \throw InvalidInputError when the cuts join the loops differently on A and B; TopologyError
///        when the loops cannot be joined by vertex-disjoint paths; SolverError when a flow does
///        not converge or B's polygon is not convex.
void klein_polygon_domains(const Mesh& a, const MeshTables& tables_a, const Mesh& b,
                           const MeshTables& tables_b, const MatchOptions& options,
                           MatchResult& result);

}  // namespace ricci::detail
