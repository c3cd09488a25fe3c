// msp: the manifold-spline command-line tool. Dispatches to one subcommand per file.
#include <exception>
#include <iostream>
#include <string>

#include <ricci/mesh/errors.h>

#include "msp/cli.h"
#include "msp/commands.h"

int main(int argc, char** argv) {
  const std::string first = argc < 2 ? "" : argv[1];
  if (argc < 2 || first == "--help" || first == "-h") {
    (argc < 2 ? std::cerr : std::cout) << msp::overview_text();
    return argc < 2 ? 2 : 0;
  }
  for (const auto& c : msp::subcommands()) {
    const std::string name = c.spec().name;
    if (first != name) continue;
    try {
      return c.run(argc - 2, argv + 2);
    } catch (const msp::HelpRequested& help) {
      std::cout << msp::help_text(*help.spec);
      return 0;
    } catch (const msp::UsageError& e) {
      std::cerr << "msp " << name << ": " << e.what() << "\n";
      return 2;
    } catch (const ricci::Error& e) {
      std::cerr << "msp " << name << ": error: " << e.what() << "\n";
      return 1;
    } catch (const std::bad_alloc&) {
      std::cerr << "msp " << name << ": error: out of memory\n";
      return 1;
    } catch (const std::exception& e) {
      std::cerr << "msp " << name << ": internal error: " << e.what() << "\n";
      return 3;
    }
  }
  std::cerr << "msp: unknown command '" << first << "' (msp --help lists them)\n";
  return 2;
}
