// msp uniformize: not available in this build yet; its issue is open.
#include "msp/cli.h"
#include "msp/commands.h"

namespace msp {

int run_uniformize(int, char**) { throw UsageError("'uniformize' is not available in this build yet"); }

}  // namespace msp
