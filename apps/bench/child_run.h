#pragma once
// Benchmarks that run each mesh in a child process (so peak memory is per mesh): starting the
// child, reading its one JSON object, and naming the row.
#include <string>

#include <nlohmann/json.hpp>

#include "ricci/mesh/mesh.h"

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

/// The process's resident memory now and, with glibc, the bytes its allocations hold (the
/// difference is freed memory the allocator kept): "RSS R MB, allocated A MB (mmapped M)".
[[nodiscard]] std::string memory_note();

/// A child's row finished and printed: "cholesky" (seconds of one CHOLMOD solve of `mesh`'s
/// cotangent Laplacian, the unit of the ratios) and "peak_mb" (the process's peak RSS) added to
/// `row`, which goes to stdout as the child's one line of JSON.
void print_child_row(nlohmann::json& row, const ricci::Mesh& mesh);

/// The row name of a mesh: its file name, with " /L" for L subdivision levels.
[[nodiscard]] std::string case_label(const std::string& path, int levels);

}  // namespace msp::bench
