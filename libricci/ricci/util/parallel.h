#pragma once
// The project's one thread pool: run_workers (a fixed number of workers, each told its index),
// and on top of it run_blocks_on_demand (blocks taken as the workers ask: libspline's
// spline::parallel_for, the atlas' chart pairs) and parallel_for (interleaved blocks: per-face
// angles, the choice's scores). Each item writes its own outputs, so results do not depend on
// the number of threads.
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <functional>
#include <thread>
#include <vector>

namespace ricci {

/// Runs work(t) for t = 0..workers-1: worker 0 on the calling thread, each other on a thread of
/// its own (the calling thread alone when workers <= 1), and rethrows the exception of the
/// lowest-numbered worker that threw, after all have joined.
inline void run_workers(int workers, const std::function<void(int)>& work) {
  if (workers <= 1) {
    work(0);
    return;
  }
  // The calling thread would only wait in join(): it takes worker 0's share, one thread start
  // fewer per call (an atlas at 100k faces makes ~60 such calls).
  std::vector<std::exception_ptr> errors(static_cast<std::size_t>(workers));
  const auto run = [&](int t) {
    try {
      work(t);
    } catch (...) {
      errors[static_cast<std::size_t>(t)] = std::current_exception();
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(static_cast<std::size_t>(workers - 1));
  for (int t = 1; t < workers; ++t) pool.emplace_back(run, t);
  run(0);
  for (auto& th : pool) th.join();
  for (const auto& e : errors) {
    if (e) std::rethrow_exception(e);
  }
}

/// Threads asked for: `requested`, or the hardware's concurrency when 0; at least 1.
inline int requested_threads(int requested) {
  if (requested > 0) return requested;
  return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

/// Threads for `work` items: `requested` (0 = hardware concurrency), fewer for small loops.
inline int parallel_thread_count(int requested, std::size_t work) {
  const int n = requested_threads(requested);
  // Below a few hundred evaluations a thread costs more than it saves.
  return static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(n), 1 + work / 256));
}

/// Runs body(i) for i in [0, count) on `workers` threads (run_workers; the calling thread alone
/// when workers <= 1), in blocks of `block` consecutive items that each thread takes, in
/// increasing order, when it has finished its previous one: a thread slowed down takes fewer
/// blocks instead of holding the loop up. Each item must write its own outputs. Rethrows as
/// run_workers.
template <class Body>
void run_blocks_on_demand(int workers, std::size_t count, std::size_t block, const Body& body) {
  if (workers <= 1) {
    for (std::size_t i = 0; i < count; ++i) body(i);
    return;
  }
  block = std::max<std::size_t>(1, block);
  std::atomic<std::size_t> next{0};
  run_workers(workers, [&](int) {
    for (;;) {
      const std::size_t start = next.fetch_add(block, std::memory_order_relaxed);
      if (start >= count) return;
      const std::size_t end = std::min(count, start + block);
      for (std::size_t i = start; i < end; ++i) body(i);
    }
  });
}

/// Runs body(i) for i in [0, count) on up to `threads` threads (run_workers), in interleaved
/// blocks of 64 (neighbouring items share charts and cost about the same); rethrows the first
/// exception of any thread after all have joined.
template <class Body>
void parallel_for(std::size_t count, int threads, const Body& body) {
  const int n = parallel_thread_count(threads, count);
  if (n <= 1) {
    for (std::size_t i = 0; i < count; ++i) body(i);
    return;
  }
  constexpr std::size_t kBlock = 64;
  run_workers(n, [&](int t) {
    for (std::size_t start = static_cast<std::size_t>(t) * kBlock; start < count;
         start += static_cast<std::size_t>(n) * kBlock) {
      for (std::size_t i = start; i < std::min(count, start + kBlock); ++i) body(i);
    }
  });
}

}  // namespace ricci
