#include "spline/version.h"
namespace spline {
const char* version() { return "0.1.0"; }
}  // namespace spline
