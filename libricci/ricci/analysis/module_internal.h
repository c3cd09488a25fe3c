#pragma once
// Pieces of conformal_module shared between its source files (not a public header).
#include "ricci/analysis/conformal_module.h"
#include "ricci/flow/flow.h"
#include "ricci/metric/mesh_tables.h"
#include "ricci/topology/slice.h"

namespace ricci::detail {

/// Copies the flow's status (converged, or stalled below options.accepted_error), iterations,
/// error and message into the result.
void record_flow(const FlowResult& flow, const ModuleOptions& options, ModuleResult& result);

/// domain.faces = the faces of `mesh` (vertex indices).
void copy_faces(const Mesh& mesh, CanonicalDomain& domain);

/// The conformal map of a doubly connected domain onto r < |z| < 1 (Algorithm 4).
struct AnnulusMap {
  FlowResult flow;  ///< When it failed (not converged nor stalled), nothing else is filled.
  std::vector<HalfedgeHandle> path;  ///< The cut, from loop 0 to loop 1 of the tables.
  SlicedMesh sliced;
  Eigen::VectorXcd w;  ///< By sliced vertex: log z (the outer loop at Re w = 0 on average).
  Eigen::VectorXcd z;  ///< By mesh vertex: exp(w) of any copy.
  std::vector<int> copy_of;  ///< By mesh vertex: one sliced copy.
  double module = 0;         ///< (1/2π) log(1/r).
  double roundness = 0;      ///< Max deviation of a boundary vertex's log|z| from its loop's.
};

/// \pre genus 0 with two boundary loops (tables.boundary_loops 0 and 1). `outer_vertex` (a
/// vertex of the loop sent to |z| = 1) or -1: the loop the orientation makes outer.
[[nodiscard]] AnnulusMap annulus_map(const Mesh& mesh, const MeshTables& tables,
                                     const FlowOptions& options, int outer_vertex);

/// Indices of tables.boundary_loops by 3D length, longest first (c0, c1, ...).
[[nodiscard]] std::vector<int> loops_by_length(const Mesh& mesh, const MeshTables& tables);

/// Genus 0, two boundaries: the annulus module.
void annulus_module(const Mesh& mesh, const MeshTables& tables, const ModuleOptions& options,
                    ModuleResult& result);

/// Genus 0, three or more boundaries: the circle domain (see module_circle_domain.cpp).
void circle_domain_module(const Mesh& mesh, const MeshTables& tables,
                          const ModuleOptions& options, ModuleResult& result);

/// Genus 0, one boundary: the conformal map onto the unit disk (see module_circle_domain.cpp).
/// \throw InvalidInputError for a bad options.centre.
void disk_module(const Mesh& mesh, const MeshTables& tables, const ModuleOptions& options,
                 ModuleResult& result);

/// The interior vertex farthest from the boundary along edge paths (3D lengths), preferring
/// those with at least `min_valence` neighbours. \throw InvalidInputError when there is none.
[[nodiscard]] int farthest_interior_vertex(const Mesh& mesh, const MeshTables& tables,
                                           int min_valence);

/// Closed genus 1 (flat torus) and genus >= 2 (Fuchsian) through uniformize().
void uniformized_module(const Mesh& mesh, const ModuleOptions& options, ModuleResult& result);

/// Open surface with χ < 0: hyperbolic metric with geodesic boundaries (Algorithm 6).
void hyperbolic_module(const Mesh& mesh, const MeshTables& tables, const ModuleOptions& options,
                       ModuleResult& result);

}  // namespace ricci::detail
