#pragma once
// The priority queue of quadric_decimate (simplify_quadric.h): items 0..n-1 ordered by (cost,
// index), a total order, so the order in which items leave it does not depend on how the queue
// is built, and two correct queues give the same collapse sequence.
#include <cstddef>
#include <vector>

namespace ricci {

/// Min-queue of the items 0..items-1 keyed by (cost, item): a 4-ary heap that records where each
/// item sits, so that a new cost moves the item's one entry (no stale entries pile up, and a
/// level of the heap is one cache line of four children).
class IndexedMinQueue {
 public:
  /// An empty queue for the items 0..items-1. \pre items >= 0
  explicit IndexedMinQueue(int items = 0);

  [[nodiscard]] bool empty() const { return heap_.empty(); }
  [[nodiscard]] std::size_t size() const { return heap_.size(); }
  [[nodiscard]] bool contains(int item) const { return position_[static_cast<std::size_t>(item)] >= 0; }

  /// Queues every item i with cost costs[i] at once (linear time), replacing what was queued.
  /// \pre costs.size() == items; no cost is NaN.
  void assign(const std::vector<double>& costs);

  /// Queues `item` with `cost`, or gives the queued item that cost.
  /// \pre 0 <= item < items; cost is not NaN.
  void set(int item, double cost);

  /// Removes and returns the item of least (cost, item). \pre !empty()
  int pop();

 private:
  struct Entry {
    double cost;
    int item;
  };
  static bool before(const Entry& a, const Entry& b) {
    return a.cost < b.cost || (a.cost == b.cost && a.item < b.item);
  }
  void put(std::size_t at, const Entry& entry) {
    heap_[at] = entry;
    position_[static_cast<std::size_t>(entry.item)] = static_cast<int>(at);
  }
  // Moves `entry`, meant for `hole`, up or down to its place (by value: it may be a copy of the
  // hole's own entry, which the moves overwrite).
  void sift_up(std::size_t hole, Entry entry);
  void sift_down(std::size_t hole, Entry entry);

  std::vector<Entry> heap_;
  std::vector<int> position_;  // -1: not queued
};

}  // namespace ricci
