#pragma once
// libricci's thread pool (ricci/util/parallel.h) under libspline's names, with libspline's
// parallel_for: blocks handed out as the threads ask for them (run_blocks_on_demand). Spline
// evaluations are thread-safe (ManifoldSplineSpace caches its chart spaces under once_flags).
#include <algorithm>
#include <cstddef>
#include <functional>

#include "ricci/util/parallel.h"

namespace spline {

using ricci::parallel_thread_count;
using ricci::run_workers;

/// Runs body(i) for i in [0, count) on up to `threads` threads (0: the hardware's; fewer for
/// small loops, parallel_thread_count), in blocks of `block` consecutive items that each thread
/// takes, in increasing order, when it has finished its previous block. A thread slowed down
/// (another of our stages beside it, another process) then takes fewer blocks instead of
/// holding the loop up. Each item must write its own outputs: results do not depend on which
/// thread ran an item. Rethrows the exception of the lowest-numbered thread that threw.
template <class Body>
void parallel_for(std::size_t count, int threads, const Body& body, std::size_t block = 64) {
  ricci::run_blocks_on_demand(parallel_thread_count(threads, count), count, block, body);
}

/// parallel_for over [0, count) in chunks of `chunk` items, asking `stop` before each chunk
/// (empty: never): once it returns true no further chunk begins. For work done while waiting
/// for something else, which may stop when that is there. Returns the items run: [0, returned).
template <class Body>
std::size_t parallel_for_until(std::size_t count, int threads, const std::function<bool()>& stop,
                               const Body& body, std::size_t chunk = 2048) {
  if (!stop) {
    parallel_for(count, threads, body);
    return count;
  }
  std::size_t done = 0;
  while (done < count && !stop()) {
    const std::size_t end = std::min(count, done + std::max<std::size_t>(chunk, 1));
    parallel_for(end - done, threads, [&](std::size_t i) { body(done + i); });
    done = end;
  }
  return done;
}

}  // namespace spline
