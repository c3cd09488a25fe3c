// msp atlas: not available in this build yet; its issue is open.
#include "msp/cli.h"
#include "msp/commands.h"

namespace msp {

int run_atlas(int, char**) { throw UsageError("'atlas' is not available in this build yet"); }

}  // namespace msp
