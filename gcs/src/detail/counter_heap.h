#pragma once
// An indexed binary max-heap of (value, id) pairs: the GCS loop's signal counters, ordered so that
// the most active vertex is found in O(1) and a counter changes in O(log n) without allocating.
// Order: by value, ties by the larger id (the same order as the largest element of a
// std::set<std::pair<double, int>>), so the result does not depend on the insertion history.

#include <cstddef>
#include <utility>
#include <vector>

#include "edgefront/error.h"

namespace gcs::detail {

class CounterHeap {
 public:
  bool contains(int id) const { return static_cast<std::size_t>(id) < where_.size() && where_[id] >= 0; }
  std::size_t size() const { return heap_.size(); }
  bool empty() const { return heap_.empty(); }
  double value(int id) const { return value_[id]; }
  /// The id with the largest (value, id). Requires a non-empty heap.
  int top() const { return heap_.front(); }

  /// Inserts id or changes its value.
  void set(int id, double v) {
    if (static_cast<std::size_t>(id) >= where_.size()) {
      where_.resize(static_cast<std::size_t>(id) + 1, -1);
      value_.resize(static_cast<std::size_t>(id) + 1, 0.0);
    }
    if (where_[id] < 0) {
      value_[id] = v;
      where_[id] = static_cast<int>(heap_.size());
      heap_.push_back(id);
      up(heap_.size() - 1);
      return;
    }
    const double old = value_[id];
    value_[id] = v;
    if (v > old) up(static_cast<std::size_t>(where_[id]));
    else down(static_cast<std::size_t>(where_[id]));
  }

  void erase(int id) {
    if (!contains(id)) return;
    const std::size_t i = static_cast<std::size_t>(where_[id]);
    const int last = heap_.back();
    heap_.pop_back();
    where_[id] = -1;
    if (last == id) return;
    heap_[i] = last;
    where_[last] = static_cast<int>(i);
    up(i);
    down(static_cast<std::size_t>(where_[last]));
  }

  void clear() {
    for (const int id : heap_) where_[id] = -1;
    heap_.clear();
  }

  /// Multiplies every value by f > 0 and restores the heap order (rounding may create ties).
  void scale_all(double f) {
    for (const int id : heap_) value_[id] *= f;
    for (std::size_t i = heap_.size() / 2; i-- > 0;) down(i);
  }

  /// Throws InternalError when the heap order or the index is broken.
  void check() const {
    for (std::size_t i = 0; i < heap_.size(); ++i) {
      EF_CHECK(where_[heap_[i]] == static_cast<int>(i), "counter heap index is broken");
      if (i > 0) EF_CHECK(!above(heap_[i], heap_[(i - 1) / 2]), "counter heap order is broken");
    }
  }

 private:
  bool above(int a, int b) const {
    return value_[a] > value_[b] || (value_[a] == value_[b] && a > b);
  }
  void place(std::size_t i, int id) {
    heap_[i] = id;
    where_[id] = static_cast<int>(i);
  }
  void up(std::size_t i) {
    const int id = heap_[i];
    while (i > 0) {
      const std::size_t p = (i - 1) / 2;
      if (!above(id, heap_[p])) break;
      place(i, heap_[p]);
      i = p;
    }
    place(i, id);
  }
  void down(std::size_t i) {
    const int id = heap_[i];
    const std::size_t n = heap_.size();
    for (;;) {
      std::size_t c = 2 * i + 1;
      if (c >= n) break;
      if (c + 1 < n && above(heap_[c + 1], heap_[c])) ++c;
      if (!above(heap_[c], id)) break;
      place(i, heap_[c]);
      i = c;
    }
    place(i, id);
  }

  std::vector<int> heap_;
  std::vector<int> where_;    // per id: position in heap_, -1 when absent
  std::vector<double> value_;  // per id
};

}  // namespace gcs::detail
