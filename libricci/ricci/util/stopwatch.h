#pragma once
// Wall-clock stopwatch for the stage timings the libraries and tools report (seconds in their
// result structs), and the process' CPU seconds beside it. The one timer of the project: use it
// rather than std::chrono or clock_gettime directly.
#include <time.h>

#include <chrono>

namespace ricci {

/// CPU seconds the process has used so far, all its threads together (CLOCK_PROCESS_CPUTIME_ID):
/// on a loaded machine a stage's CPU time moves far less than its wall time.
inline double process_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

/// Wall seconds (steady clock) since construction or the last restart.
class Stopwatch {
 public:
  Stopwatch() : start_(Clock::now()) {}

  /// Seconds since construction or the last restart.
  [[nodiscard]] double seconds() const {
    return std::chrono::duration<double>(Clock::now() - start_).count();
  }

  /// Starts again from now.
  void restart() { start_ = Clock::now(); }

  /// seconds(), then restart(): the time of one stage of a sequence.
  double lap() {
    const Clock::time_point now = Clock::now();
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    start_ = now;
    return elapsed;
  }

 private:
  using Clock = std::chrono::steady_clock;
  Clock::time_point start_;
};

/// Process CPU seconds (process_cpu_seconds) since construction or the last restart.
class CpuStopwatch {
 public:
  CpuStopwatch() : start_(process_cpu_seconds()) {}
  [[nodiscard]] double seconds() const { return process_cpu_seconds() - start_; }
  void restart() { start_ = process_cpu_seconds(); }

 private:
  double start_;
};

/// A stage's wall and CPU seconds together.
struct StageTimer {
  Stopwatch wall;
  CpuStopwatch cpu;
  void restart() {
    wall.restart();
    cpu.restart();
  }
};

}  // namespace ricci
