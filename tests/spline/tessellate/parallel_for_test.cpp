// parallel_for and run_workers (the library's one thread pool): every item once, the result
// of the serial loop whatever the thread count, exceptions carried to the caller.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <thread>
#include <vector>

#include "spline/tessellate/parallel_for.h"

namespace spline {
namespace {

// A value of i that costs a little and depends on nothing else.
double item(std::size_t i) {
  double x = static_cast<double>(i) + 0.5;
  for (int k = 0; k < 20; ++k) x = std::sin(x) + std::sqrt(x * x + 1.0);
  return x;
}

TEST(ParallelFor, GivesTheSerialLoopsResultOnEveryThreadCount) {
  // Sizes around the block of 64 and the 256 items a thread needs to be worth starting.
  for (std::size_t count : {0u, 1u, 63u, 64u, 65u, 257u, 1000u, 4099u}) {
    std::vector<double> serial(count);
    for (std::size_t i = 0; i < count; ++i) serial[i] = item(i);
    for (int threads : {1, 2, 3, 0}) {
      std::vector<double> parallel(count, -1.0);
      std::vector<int> visits(count, 0);
      parallel_for(count, threads, [&](std::size_t i) {
        parallel[i] = item(i);
        ++visits[i];  // each index belongs to one thread: no race when it is visited once
      });
      for (std::size_t i = 0; i < count; ++i) {
        ASSERT_EQ(visits[i], 1) << "item " << i << " of " << count << ", " << threads;
        ASSERT_EQ(parallel[i], serial[i]) << "item " << i << " of " << count;  // bit for bit
      }
    }
  }
}

TEST(ParallelFor, AThreadHeldUpLeavesTheRemainingBlocksToTheOthers) {
  // Item 0 waits until every item outside its own block (0..63) has run: the blocks are handed
  // out as threads ask for them, so the other thread runs them all. (With blocks dealt out in
  // advance, half of them would wait behind item 0; the wait gives up after 20 s.)
  constexpr std::size_t kCount = 1000, kBlock = 64;
  std::atomic<std::size_t> others{0};
  bool waited_for_all = false;
  parallel_for(kCount, 2, [&](std::size_t i) {
    if (i == 0) {
      const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(20);
      while (others.load() < kCount - kBlock && std::chrono::steady_clock::now() < give_up)
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
      waited_for_all = others.load() == kCount - kBlock;
    } else if (i >= kBlock) {
      ++others;
    }
  });
  EXPECT_TRUE(waited_for_all);
  EXPECT_EQ(others.load(), kCount - kBlock);
}

TEST(ParallelFor, UsesFewerThreadsOnSmallLoops) {
  EXPECT_EQ(parallel_thread_count(2, 10), 1);
  EXPECT_EQ(parallel_thread_count(2, 100000), 2);
  EXPECT_EQ(parallel_thread_count(-3, 0), 1);
}

TEST(RunWorkers, EveryWorkerRunsOnceAndTheLowestExceptionIsRethrown) {
  std::vector<int> ran(4, 0);
  run_workers(4, [&](int t) { ++ran[static_cast<std::size_t>(t)]; });
  EXPECT_EQ(ran, std::vector<int>(4, 1));
  EXPECT_THROW(run_workers(3,
                           [](int t) {
                             if (t == 1) throw std::invalid_argument("one");
                             if (t == 2) throw std::runtime_error("two");
                           }),
               std::invalid_argument);
  EXPECT_THROW(parallel_for(5000, 2,
                            [](std::size_t i) {
                              if (i == 4321) throw std::runtime_error("item");
                            }),
               std::runtime_error);
}

}  // namespace
// Chunks run until the stop is asked for; the items run are a prefix, each once.
TEST(ParallelForUntil, StopsBetweenChunksAfterAPrefix) {
  for (int threads : {1, 2}) {
    std::vector<std::atomic<int>> runs(10000);
    int asked = 0;
    const std::size_t done = parallel_for_until(
        runs.size(), threads, [&asked] { return ++asked > 3; },
        [&](std::size_t i) { runs[i].fetch_add(1); }, 1000);
    EXPECT_EQ(done, 3000u);
    for (std::size_t i = 0; i < runs.size(); ++i) EXPECT_EQ(runs[i].load(), i < done ? 1 : 0) << i;
    std::vector<std::atomic<int>> all(2500);
    EXPECT_EQ(
        parallel_for_until(all.size(), threads, {}, [&](std::size_t i) { all[i] += 1; }, 1000),
        all.size());
    EXPECT_EQ(parallel_for_until(all.size(), threads, [] { return false; },
                                 [&](std::size_t i) { all[i] += 1; }, 1000),
              all.size());
    for (const auto& a : all) EXPECT_EQ(a.load(), 2);
  }
}

}  // namespace spline
