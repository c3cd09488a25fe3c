#pragma once
// Shared by msp module and msp index: the module options from the command line and a module's
// JSON report.
#include <string>
#include <vector>

#include <ricci/analysis/conformal_module.h>
#include <ricci/mesh/mesh.h>
#include <nlohmann/json.hpp>

#include "msp/cli.h"

namespace msp {

/// Four vertex indices "a,b,c,d" given to --`option`. \throw UsageError otherwise.
[[nodiscard]] std::vector<int> parse_corners(const std::string& text, const std::string& option);

/// --tolerance, --solver, --metric, --radii, and with `shape` (msp module, not msp index) --kind,
/// --corners a,b,c,d and --centre V.
/// \throw UsageError for malformed values.
[[nodiscard]] ricci::ModuleOptions parse_module_options(const Args& args, bool shape);

/// The module as one JSON object: mesh, counts, kind, values by name, vector, invariant,
/// roundness, corners, the flow's figures and the seconds.
[[nodiscard]] nlohmann::json module_json(const std::string& path, const ricci::Mesh& mesh,
                                         const ricci::ModuleResult& result);

/// Computes the module of `path`, refusing a flow that did not converge.
/// \throw ricci::SolverError when the flow did not converge, and what read_mesh and
///        conformal_module throw.
[[nodiscard]] ricci::ModuleResult module_of_file(const std::string& path,
                                                 const ricci::ModuleOptions& options,
                                                 ricci::Mesh& mesh);

}  // namespace msp
