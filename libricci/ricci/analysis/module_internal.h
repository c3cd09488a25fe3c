#pragma once
// Pieces of conformal_module shared between its source files (not a public header).
#include "ricci/analysis/conformal_module.h"
#include "ricci/flow/flow.h"
#include "ricci/metric/mesh_tables.h"

namespace ricci::detail {

/// Copies the flow's status, iterations, error and message into the result.
void record_flow(const FlowResult& flow, ModuleResult& result);

/// domain.faces = the faces of `mesh` (vertex indices).
void copy_faces(const Mesh& mesh, CanonicalDomain& domain);

/// Closed genus 1 (flat torus) and genus >= 2 (Fuchsian) through uniformize().
void uniformized_module(const Mesh& mesh, const ModuleOptions& options, ModuleResult& result);

/// Open surface with χ < 0: hyperbolic metric with geodesic boundaries (Algorithm 6).
void hyperbolic_module(const Mesh& mesh, const MeshTables& tables, const ModuleOptions& options,
                       ModuleResult& result);

}  // namespace ricci::detail
