#pragma once
// Pieces of match_surfaces shared between its source files (not a public header).
#include <vector>

#include <Eigen/Core>

#include "ricci/analysis/match.h"
#include "ricci/flow/flow.h"
#include "ricci/metric/mesh_tables.h"
#include "ricci/topology/slice.h"

namespace ricci::detail {

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
