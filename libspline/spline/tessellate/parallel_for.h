#pragma once
// A minimal parallel loop for independent spline evaluations (tessellation, projections): the
// evaluations are thread-safe (ManifoldSplineSpace caches its chart spaces under once_flags).
#include <algorithm>
#include <cstddef>
#include <exception>
#include <thread>
#include <vector>

namespace spline {

/// Threads for `work` items: `requested` (0 = hardware concurrency), fewer for small loops.
inline int parallel_thread_count(int requested, std::size_t work) {
  int n = requested > 0 ? requested : static_cast<int>(std::thread::hardware_concurrency());
  n = std::max(1, n);
  // Below a few hundred evaluations a thread costs more than it saves.
  return static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(n), 1 + work / 256));
}

/// Runs body(i) for i in [0, count) on up to `threads` threads, in interleaved blocks of 64
/// (neighbouring items share charts and cost about the same); rethrows the first exception of
/// any thread after all have joined.
template <class Body>
void parallel_for(std::size_t count, int threads, const Body& body) {
  const int n = parallel_thread_count(threads, count);
  if (n <= 1) {
    for (std::size_t i = 0; i < count; ++i) body(i);
    return;
  }
  constexpr std::size_t kBlock = 64;
  std::vector<std::exception_ptr> errors(static_cast<std::size_t>(n));
  std::vector<std::thread> pool;
  for (int t = 0; t < n; ++t) {
    pool.emplace_back([&, t] {
      try {
        for (std::size_t start = static_cast<std::size_t>(t) * kBlock; start < count;
             start += static_cast<std::size_t>(n) * kBlock) {
          for (std::size_t i = start; i < std::min(count, start + kBlock); ++i) body(i);
        }
      } catch (...) {
        errors[static_cast<std::size_t>(t)] = std::current_exception();
      }
    });
  }
  for (auto& th : pool) th.join();
  for (auto& e : errors)
    if (e) std::rethrow_exception(e);
}

}  // namespace spline
