#include "ricci/mesh/indexed_min_queue.h"

namespace ricci {
namespace {

constexpr std::size_t kArity = 4;

std::size_t parent(std::size_t i) { return (i - 1) / kArity; }
std::size_t first_child(std::size_t i) { return kArity * i + 1; }

}  // namespace

IndexedMinQueue::IndexedMinQueue(int items) : position_(static_cast<std::size_t>(items), -1) {}

void IndexedMinQueue::assign(const std::vector<double>& costs) {
  for (const Entry& entry : heap_) position_[static_cast<std::size_t>(entry.item)] = -1;
  heap_.resize(costs.size());
  for (std::size_t i = 0; i < costs.size(); ++i) put(i, {costs[i], static_cast<int>(i)});
  if (heap_.size() < 2) return;
  for (std::size_t i = parent(heap_.size() - 1) + 1; i-- > 0;) sift_down(i, heap_[i]);
}

void IndexedMinQueue::set(int item, double cost) {
  const int at = position_[static_cast<std::size_t>(item)];
  if (at < 0) {
    heap_.push_back({cost, item});
    sift_up(heap_.size() - 1, heap_.back());
    return;
  }
  const Entry entry{cost, item};
  const auto hole = static_cast<std::size_t>(at);
  if (hole > 0 && before(entry, heap_[parent(hole)])) {
    sift_up(hole, entry);
  } else {
    sift_down(hole, entry);
  }
}

int IndexedMinQueue::pop() {
  const int item = heap_.front().item;
  position_[static_cast<std::size_t>(item)] = -1;
  const Entry last = heap_.back();
  heap_.pop_back();
  if (!heap_.empty()) sift_down(0, last);
  return item;
}

void IndexedMinQueue::sift_up(std::size_t hole, Entry entry) {
  while (hole > 0 && before(entry, heap_[parent(hole)])) {
    put(hole, heap_[parent(hole)]);
    hole = parent(hole);
  }
  put(hole, entry);
}

void IndexedMinQueue::sift_down(std::size_t hole, Entry entry) {
  const std::size_t size = heap_.size();
  for (;;) {
    const std::size_t first = first_child(hole);
    if (first >= size) break;
    const std::size_t end = first + kArity < size ? first + kArity : size;
    std::size_t least = first;
    for (std::size_t c = first + 1; c < end; ++c) {
      if (before(heap_[c], heap_[least])) least = c;
    }
    if (!before(heap_[least], entry)) break;
    put(hole, heap_[least]);
    hole = least;
  }
  put(hole, entry);
}

}  // namespace ricci
