#pragma once
// A 4-ary min-heap of (key, index) pairs, for the Minimal Distance Front's queue. Internal.
//
// The order is the pairs' lexicographic order (key first, ties by index), a total order, so it
// pops exactly the sequence std::priority_queue<pair, vector, greater> pops: the same settle order
// and the same distances. Four children per node halve the depth of a binary heap, and the four
// children are adjacent (64 contiguous bytes), so a pop touches fewer cache lines.

#include <cstddef>
#include <utility>
#include <vector>

namespace edgefront::detail {

// `Index` is int, or a type with operator< (e.g. a vertex's index in two numberings, ordered by one).
template <class Key, class Index = int>
class MinHeap4 {
 public:
  using Entry = std::pair<Key, Index>;

  bool empty() const { return a_.empty(); }
  size_t size() const { return a_.size(); }
  const Entry& top() const { return a_.front(); }

  void push(Key key, Index index) {
    const Entry e{key, index};
    size_t i = a_.size();
    a_.push_back(e);
    while (i > 0) {
      const size_t p = (i - 1) / 4;
      if (!less(e, a_[p])) break;
      a_[i] = a_[p];
      i = p;
    }
    a_[i] = e;
  }

  void pop() {
    const Entry e = a_.back();
    a_.pop_back();
    const size_t n = a_.size();
    if (n == 0) return;
    size_t i = 0;
    while (true) {
      const size_t c0 = 4 * i + 1;
      if (c0 >= n) break;
      size_t best = c0;
      const size_t c_end = c0 + 4 < n ? c0 + 4 : n;
      for (size_t c = c0 + 1; c < c_end; ++c) {
        if (less(a_[c], a_[best])) best = c;
      }
      if (!less(a_[best], e)) break;
      a_[i] = a_[best];
      i = best;
    }
    a_[i] = e;
  }

  /// Empties the heap; gives the storage back when it is far above `keep` entries (a reused
  /// front that once ran a large query must not keep its memory for every small one).
  void clear(size_t keep = 4096) {
    if (a_.capacity() > keep) {
      std::vector<Entry>().swap(a_);
    } else {
      a_.clear();
    }
  }

 private:
  // The pairs' lexicographic order, spelled out: std::pair's operator< goes through a three-way
  // comparison of the doubles (a partial ordering), and a pop took 23% more instructions with it.
  // The same order for keys that are not NaN (the fronts push none).
  static bool less(const Entry& a, const Entry& b) {
    return a.first < b.first || (!(b.first < a.first) && a.second < b.second);
  }

  std::vector<Entry> a_;
};

}  // namespace edgefront::detail
