#pragma once
// Benchmarks that run each mesh in a child process (so peak memory is per mesh): starting the
// child, reading its one JSON object, and naming the row.
#include <memory>
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

/// The unit of the ratios: one CHOLMOD solve of a mesh's cotangent Laplacian (best of 3).
struct ReferenceSolve {
  double seconds = 0.0, cpu_seconds = 0.0;
  double peak_mb = 0.0;  ///< the process's peak RSS once it is done
};

/// The reference solve of `mesh`, measured before the run it is the unit of, its freed memory
/// given back (release_free_memory): the process's peak is then the larger of the two, not
/// the reference's factor on top of the run's freed heap.
[[nodiscard]] ReferenceSolve reference_solve(const ricci::Mesh& mesh);

/// The process's resident memory, sampled every `period_ms` by a thread while it lives: the
/// peak of a stage that runs after a larger one (the process's peak RSS then says nothing).
class RssSampler {
 public:
  explicit RssSampler(int period_ms = 20);
  ~RssSampler();
  RssSampler(const RssSampler&) = delete;
  RssSampler& operator=(const RssSampler&) = delete;
  /// The largest resident memory seen since the last call (or the start), MB.
  double window_peak_mb();
  /// Stops sampling; the largest resident memory seen, MB.
  double stop();

 private:
  struct State;
  std::unique_ptr<State> state_;
};

/// `row` finished with a reference measured before the run and printed (stdout, one line of
/// JSON): cholesky, cholesky_cpu, solves, cpu_solves as print_child_row, reference_peak_mb,
/// and peak_mb = peak_mb_with_cholesky, the process's peak RSS (reference included).
void print_row_after_reference(nlohmann::json& row, const ReferenceSolve& reference);

/// The row name of a mesh: its file name, with " /L" for L subdivision levels.
[[nodiscard]] std::string case_label(const std::string& path, int levels);

}  // namespace msp::bench
