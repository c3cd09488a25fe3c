// msp info MESH [--json]: placeholder until the mesh reader and diagnosis land (issue 2).
#include <iostream>

#include "msp/cli.h"
#include "msp/commands.h"

namespace msp {

int run_info(int argc, char** argv) {
  Args args(argc, argv, {"json"});
  args.require_known({"json"});
  args.require_positionals(1, "msp info MESH [--json]");
  std::cout << "info: " << args.positionals()[0] << "\n";
  return 0;
}

}  // namespace msp
