// msp flow: not available in this build yet; its issue is open.
#include "msp/cli.h"
#include "msp/commands.h"

namespace msp {

int run_flow(int, char**) { throw UsageError("'flow' is not available in this build yet"); }

}  // namespace msp
