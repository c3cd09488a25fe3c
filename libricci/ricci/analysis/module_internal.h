#pragma once
// Pieces of conformal_module shared between its source files (not a public header).
#include <functional>
#include <memory>
#include <vector>

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
  Eigen::VectorXcd w;        ///< By sliced vertex: log z (the outer loop at Re w = 0 on average).
  Eigen::VectorXcd z;        ///< By mesh vertex: exp(w) of any copy.
  std::vector<int> copy_of;  ///< By mesh vertex: one sliced copy.
  double module = 0;         ///< (1/2π) log(1/r).
  double roundness = 0;      ///< Max deviation of a boundary vertex's log|z| from its loop's.
};

/// \pre genus 0 with two boundary loops (tables.boundary_loops 0 and 1). `outer_vertex` (a
/// vertex of the loop sent to |z| = 1) or -1: the loop the orientation makes outer.
[[nodiscard]] AnnulusMap annulus_map(const Mesh& mesh, const MeshTables& tables,
                                     const FlowOptions& options, int outer_vertex);

/// The shortest edge path (under `lengths`) from one of `sources` to a vertex of a boundary loop
/// `is_target` accepts (loop_of: by vertex, a loop label or -1 inside), through vertices neither
/// `used` nor on a loop it rejects; the search stops at the first target vertex it settles. The
/// cuts of the annulus (loop 0 to loop 1), the cone star (a ray from the feature vertex to one
/// loop) and the loop tree (from the loops reached so far to the next). Returns the halfedges from
/// the source to the loop, empty when no target is reachable; marks nothing.
[[nodiscard]] std::vector<HalfedgeHandle> shortest_path_to_loop(
    const Mesh& mesh, const std::vector<int>& loop_of, const EdgeLengths& lengths,
    const std::vector<int>& sources, const std::function<bool(int)>& is_target,
    const std::vector<char>& used);

/// Indices of tables.boundary_loops by 3D length, longest first (c0, c1, ...).
[[nodiscard]] std::vector<int> loops_by_length(const Mesh& mesh, const MeshTables& tables);

/// Genus 0, two boundaries: the annulus module.
void annulus_module(const Mesh& mesh, const MeshTables& tables, const ModuleOptions& options,
                    ModuleResult& result);

/// The flat metric the circle-domain iteration updates (module_circle_domain.cpp): flowed to new
/// curvature targets from the last solution, measured along the boundary, laid out.
class FlatMetric {
 public:
  virtual ~FlatMetric() = default;
  /// Flows to `targets` (by vertex of the tables) from the current metric, which it replaces;
  /// returns the run's figures (status, iterations, error, message).
  virtual FlowResult solve(const Targets& targets) = 0;
  /// Lengths of the boundary edges loop[i] -> loop[i + 1] (cyclically) in the current metric.
  [[nodiscard]] virtual std::vector<double> loop_lengths(const std::vector<int>& loop) const = 0;
  /// The current metric laid out: z by vertex of the drawn triangulation, whose first vertices
  /// are the tables' (the copies of a cut vertex may differ before the boundaries are round).
  virtual void layout(std::vector<Complex>& z) const = 0;
  /// The drawn triangulation's faces (indices into layout's z).
  [[nodiscard]] virtual Eigen::MatrixX3i faces() const = 0;
};

/// ricci::flow on the mesh's own connectivity (options.flow), warm-started from the last
/// metric. layout() cuts along tree paths from `cut_root` to the other loops (-1: no cut).
[[nodiscard]] std::unique_ptr<FlatMetric> fixed_flat_metric(const Mesh& mesh,
                                                            const MeshTables& tables,
                                                            const FlowOptions& options,
                                                            int cut_root);

/// The conformal flow with intrinsic Delaunay flips (intrinsic/conformal_flow.h) on the double
/// cover of `mesh`, each boundary vertex's target doubled; the metric of the half the mesh
/// covers, laid out through the flipped triangulation (module_intrinsic.cpp).
/// \pre the mesh has no interior edge between two boundary vertices (DoubleCover::original).
[[nodiscard]] std::unique_ptr<FlatMetric> intrinsic_flat_metric(const Mesh& mesh,
                                                                const MeshTables& tables,
                                                                const FlowOptions& options);

/// Genus 0, three or more boundaries: the circle domain (see module_circle_domain.cpp) of the
/// flat metric `metric` (nullptr: fixed_flat_metric of the mesh).
void circle_domain_module(const Mesh& mesh, const MeshTables& tables, const ModuleOptions& options,
                          ModuleResult& result, FlatMetric* metric = nullptr);

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
