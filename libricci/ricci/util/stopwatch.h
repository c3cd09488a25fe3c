#pragma once
// Wall-clock stopwatch for the stage timings the libraries and tools report (seconds in their
// result structs). The one timer of the project: use it rather than std::chrono directly.
#include <chrono>

namespace ricci {

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

}  // namespace ricci
