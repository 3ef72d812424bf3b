#pragma once
// Open-addressing hash map from a non-negative 32-bit key (a vertex or halfedge index) to a small
// value. Linear probing with backward-shift deletion (no tombstones). Its memory follows the
// number of entries it ever held at once, never the mesh size: the edge fronts keep their working
// sets here so that a query touches only what it visits.

#include <cstdint>
#include <vector>

#include "edgefront/error.h"

namespace edgefront::detail {

template <class Value>
class FlatMap {
 public:
  static constexpr uint32_t kEmpty = 0xffffffffu;

  FlatMap() { rehash(16); }

  size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  size_t capacity() const { return keys_.size(); }
  size_t memory_bytes() const { return keys_.capacity() * sizeof(uint32_t) + vals_.capacity() * sizeof(Value); }

  /// Removes every entry; keeps the capacity unless it is far above `keep`.
  void clear(size_t keep = 1024) {
    if (keys_.size() > 4 * keep && keys_.size() > 64) {
      // Shrink: a reused front that once held a large query must not pay for it in every small one.
      keys_.clear();
      vals_.clear();
      keys_.shrink_to_fit();
      vals_.shrink_to_fit();
      size_ = 0;
      rehash(16);
    } else {
      std::fill(keys_.begin(), keys_.end(), kEmpty);
    }
    size_ = 0;
  }

  Value* find(uint32_t key) {
    size_t i = slot(key);
    while (true) {
      const uint32_t k = keys_[i];
      if (k == key) return &vals_[i];
      if (k == kEmpty) return nullptr;
      i = (i + 1) & mask_;
    }
  }
  const Value* find(uint32_t key) const { return const_cast<FlatMap*>(this)->find(key); }
  bool contains(uint32_t key) const { return find(key) != nullptr; }

  /// Inserts `key` with `init` if absent. Returns the value and whether it was inserted.
  /// The pointer stays valid until the next insertion or erase.
  std::pair<Value*, bool> insert(uint32_t key, const Value& init) {
    EF_CHECK(key != kEmpty, "reserved key");
    if ((size_ + 1) * 4 > keys_.size() * 3) rehash(keys_.size() * 2);
    size_t i = slot(key);
    while (true) {
      const uint32_t k = keys_[i];
      if (k == key) return {&vals_[i], false};
      if (k == kEmpty) {
        keys_[i] = key;
        vals_[i] = init;
        ++size_;
        return {&vals_[i], true};
      }
      i = (i + 1) & mask_;
    }
  }

  bool erase(uint32_t key) {
    size_t i = slot(key);
    while (true) {
      const uint32_t k = keys_[i];
      if (k == kEmpty) return false;
      if (k == key) break;
      i = (i + 1) & mask_;
    }
    // Backward-shift deletion keeps every probe chain intact.
    size_t hole = i;
    size_t j = i;
    while (true) {
      j = (j + 1) & mask_;
      const uint32_t k = keys_[j];
      if (k == kEmpty) break;
      const size_t home = slot(k);
      // Move k into the hole if its home is not cyclically in (hole, j].
      const bool in_range = hole <= j ? (home > hole && home <= j) : (home > hole || home <= j);
      if (!in_range) {
        keys_[hole] = k;
        vals_[hole] = vals_[j];
        hole = j;
      }
    }
    keys_[hole] = kEmpty;
    --size_;
    return true;
  }

  template <class F>
  void for_each(F&& f) const {
    for (size_t i = 0; i < keys_.size(); ++i) {
      if (keys_[i] != kEmpty) f(keys_[i], vals_[i]);
    }
  }

 private:
  size_t slot(uint32_t key) const {
    return static_cast<size_t>((static_cast<uint64_t>(key) * 0x9E3779B97F4A7C15ull) >> shift_) & mask_;
  }
  void rehash(size_t cap) {
    std::vector<uint32_t> old_keys = std::move(keys_);
    std::vector<Value> old_vals = std::move(vals_);
    keys_.assign(cap, kEmpty);
    vals_.assign(cap, Value{});
    mask_ = cap - 1;
    int bits = 0;
    while ((size_t{1} << bits) < cap) ++bits;
    shift_ = 64 - bits;
    size_ = 0;
    for (size_t i = 0; i < old_keys.size(); ++i) {
      if (old_keys[i] != kEmpty) insert(old_keys[i], old_vals[i]);
    }
  }

  std::vector<uint32_t> keys_;
  std::vector<Value> vals_;
  size_t size_ = 0;
  size_t mask_ = 0;
  int shift_ = 60;
};

}  // namespace edgefront::detail
