#pragma once
namespace spline {
/// Library version, "major.minor.patch".
const char* version();
}  // namespace spline
