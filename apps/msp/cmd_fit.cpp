// msp fit: not available in this build yet; its issue is open.
#include "msp/cli.h"
#include "msp/commands.h"

namespace msp {

int run_fit(int, char**) { throw UsageError("'fit' is not available in this build yet"); }

}  // namespace msp
