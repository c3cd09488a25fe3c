#include "bench/child_run.h"

#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>

namespace msp::bench {

std::string self_executable() { return std::filesystem::read_symlink("/proc/self/exe").string(); }

ChildResult run_child(const std::string& command) {
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
  if (!pipe) throw std::runtime_error("cannot start " + command);
  ChildResult result;
  char buffer[4096];
  while (fgets(buffer, sizeof buffer, pipe.get())) result.output += buffer;
  try {
    result.json = nlohmann::json::parse(result.output);
    result.parsed = true;
  } catch (const std::exception&) {
    result.parsed = false;
  }
  return result;
}

std::string case_label(const std::string& path, int levels) {
  std::string name = path.substr(path.find_last_of('/') + 1);
  if (levels) name += " /" + std::to_string(levels);
  return name;
}

}  // namespace msp::bench
