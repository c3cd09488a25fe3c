#pragma once
// Benchmarks that run each mesh in a child process (so peak memory is per mesh): starting the
// child, reading its one JSON object, and naming the row.
#include <string>

#include <nlohmann/json.hpp>

namespace msp::bench {

/// This executable's path (popen runs a shell, whose /proc/self/exe is the shell: resolve ours
/// first).
[[nodiscard]] std::string self_executable();

struct ChildResult {
  bool parsed = false;   ///< stdout was one JSON object
  nlohmann::json json;   ///< when parsed
  std::string output;    ///< stdout as read
};

/// Runs `command` in a shell and parses its stdout. \throw std::runtime_error when it cannot start.
[[nodiscard]] ChildResult run_child(const std::string& command);

/// The row name of a mesh: its file name, with " /L" for L subdivision levels.
[[nodiscard]] std::string case_label(const std::string& path, int levels);

}  // namespace msp::bench
