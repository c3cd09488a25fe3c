#include <gtest/gtest.h>

#include <random>
#include <set>
#include <utility>
#include <vector>

#include "ricci/mesh/indexed_min_queue.h"

namespace {

// A reference queue: the ordered set of (cost, item) pairs.
struct ReferenceQueue {
  std::set<std::pair<double, int>> entries;
  std::vector<double> cost;
  std::vector<bool> queued;
  explicit ReferenceQueue(int items) : cost(items, 0.0), queued(items, false) {}
  void set(int item, double c) {
    if (queued[item]) entries.erase({cost[item], item});
    cost[item] = c;
    queued[item] = true;
    entries.insert({c, item});
  }
  int pop() {
    const int item = entries.begin()->second;
    entries.erase(entries.begin());
    queued[item] = false;
    return item;
  }
};

// Costs drawn from a few values, so most comparisons are ties broken by the item.
double draw_cost(std::mt19937& random) { return static_cast<double>(random() % 8) * 0.25; }

TEST(IndexedMinQueue, AssignThenPopGivesTheItemsByCostThenIndex) {
  std::mt19937 random(7);
  const int items = 1000;
  std::vector<double> costs(items);
  for (double& c : costs) c = draw_cost(random);
  ricci::IndexedMinQueue queue(items);
  queue.assign(costs);
  ASSERT_EQ(queue.size(), static_cast<size_t>(items));
  std::pair<double, int> previous{-1.0, -1};
  for (int k = 0; k < items; ++k) {
    const int item = queue.pop();
    const std::pair<double, int> now{costs[item], item};
    EXPECT_LT(previous, now) << "pop " << k;
    previous = now;
  }
  EXPECT_TRUE(queue.empty());
}

// Updates up and down, inserts of popped items and pops interleaved as the decimation does them:
// every pop is the reference's.
TEST(IndexedMinQueue, UpdatesAndPopsAgreeWithAnOrderedSet) {
  std::mt19937 random(11);
  const int items = 500;
  ricci::IndexedMinQueue queue(items);
  ReferenceQueue reference(items);
  std::vector<double> costs(items);
  for (double& c : costs) c = draw_cost(random);
  queue.assign(costs);
  for (int i = 0; i < items; ++i) reference.set(i, costs[i]);
  for (int step = 0; step < 20000 && !reference.entries.empty(); ++step) {
    if (random() % 3 == 0) {
      ASSERT_FALSE(queue.empty());
      ASSERT_EQ(queue.pop(), reference.pop()) << "step " << step;
    } else {
      const int item = static_cast<int>(random() % items);
      const double c = draw_cost(random);
      queue.set(item, c);
      reference.set(item, c);
    }
    ASSERT_EQ(queue.size(), reference.entries.size());
  }
  while (!reference.entries.empty()) ASSERT_EQ(queue.pop(), reference.pop());
  EXPECT_TRUE(queue.empty());
}

}  // namespace
