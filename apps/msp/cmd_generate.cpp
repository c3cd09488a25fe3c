// msp generate: not available in this build yet; its issue is open.
#include "msp/cli.h"
#include "msp/commands.h"

namespace msp {

int run_generate(int, char**) { throw UsageError("'generate' is not available in this build yet"); }

}  // namespace msp
