#include "ricci/version.h"
namespace ricci {
const char* version() { return "0.1.0"; }
}  // namespace ricci
