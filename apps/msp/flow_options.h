#pragma once
// Parsing of the flow-related option values shared by msp subcommands.
#include <string>

#include <ricci/flow/flow.h>

namespace msp {

ricci::Geometry parse_geometry(const std::string& s);
ricci::Scheme parse_scheme(const std::string& s);
ricci::RadiusInit parse_radii(const std::string& s);
ricci::LinearSolver parse_solver(const std::string& s);
/// --singularity: "auto" (-1) or a non-negative vertex index. \throw UsageError otherwise.
int parse_singularity(const std::string& s);

}  // namespace msp
