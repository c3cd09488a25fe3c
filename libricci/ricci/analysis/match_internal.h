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

/// domain.faces and domain.to_original_vertex from the sliced mesh.
void fill_cut_domain(const SlicedMesh& sliced, ParameterDomain& domain);

/// Locates A's vertices in B's parameter domain (phi is the identity there) and fills
/// result.map, the reversed faces and ears, the snaps and the shape errors.
void evaluate_map(const Mesh& a, const Mesh& b, const MeshTables& tables_a,
                  const MeshTables& tables_b, MatchResult& result);

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
