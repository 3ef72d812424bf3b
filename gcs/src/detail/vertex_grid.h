#pragma once
// A hashed uniform grid over moving points (the mesh vertices of the GCS loop): insert, remove and
// move in O(1), nearest-point queries that visit the cells in rings of growing radius around the
// query (O(1) cells when the points are spread at about one per cell, which the loop keeps by
// rebuilding with a cell size near the mean edge length).
//
// Why not nanoflann: its dynamic index (KDTreeSingleIndexDynamicAdaptor) can add points and mark
// them removed, but cannot move one; a GCS basic step moves the winner and its 1-ring (about 7
// points, 5 smoothing passes), so a move would be a removal plus an insertion into a logarithmic
// forest of static trees whose removed entries stay in place until the sub-tree is rebuilt: the
// forest grows by ~7 entries per step (10^7 steps for 100K vertices). This reasoning was not
// measured against nanoflann; bench/bench_gcs.cpp measures the whole loop (time per basic step).
//
// Deterministic: a query returns the nearest point, ties broken by the smaller id; the hash table
// is only looked up, never iterated for results.
//
// Storage without allocations per move: an open-addressing hash table (linear probing, power-of-
// two capacity) from cell keys to the head of an intrusive doubly linked list of the ids in the
// cell. Emptied cells keep their table entry until the table is compacted (when it fills up).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "edgefront/mesh.h"

namespace gcs::detail {

class VertexGrid {
 public:
  static constexpr std::uint64_t kAbsent = std::numeric_limits<std::uint64_t>::max();

  /// Empties the grid and sets the cell size (> 0).
  void reset(double cell_size);
  double cell_size() const { return h_; }

  /// Makes room for ids < n (new ids absent).
  void resize(std::size_t n);
  std::size_t capacity() const { return key_.size(); }

  bool contains(int id) const { return static_cast<std::size_t>(id) < key_.size() && key_[id] != kAbsent; }
  const edgefront::Vec3& position(int id) const { return pos_[id]; }
  std::size_t size() const { return count_; }

  void insert(int id, const edgefront::Vec3& p);
  void remove(int id);
  /// Updates the stored position; moves the id to another cell only when its cell changed.
  void move(int id, const edgefront::Vec3& p) {
    const std::uint64_t key = key_of(p);
    if (key == key_[id]) {
      pos_[id] = p;
      return;
    }
    remove(id);
    insert(id, p);
  }

  /// The id nearest to p (ties: smaller id), -1 when the grid is empty.
  int nearest(const edgefront::Vec3& p) const;

  /// Throws InternalError when id's stored cell is not the cell of `p` or the cell lacks it.
  void check(int id, const edgefront::Vec3& p) const;

 private:
  static constexpr std::int64_t kBias = std::int64_t(1) << 20;  // cell coordinates in [-2^20, 2^20)
  static std::int64_t cell_coord(double x, double inv_h) {
    const double c = std::floor(x * inv_h);
    return static_cast<std::int64_t>(std::clamp(c, -double(kBias), double(kBias - 1)));
  }
  static std::uint64_t pack(std::int64_t i, std::int64_t j, std::int64_t k) {
    return (static_cast<std::uint64_t>(i + kBias) << 42) | (static_cast<std::uint64_t>(j + kBias) << 21) |
           static_cast<std::uint64_t>(k + kBias);
  }
  std::uint64_t key_of(const edgefront::Vec3& p) const {
    return pack(cell_coord(p[0], inv_h_), cell_coord(p[1], inv_h_), cell_coord(p[2], inv_h_));
  }
  int linear_nearest(const edgefront::Vec3& p) const;
  /// Table slot of `key`, or -1 when the key has no entry.
  std::int64_t find_slot(std::uint64_t key) const;
  /// Table slot of `key`, creating an (empty) entry when missing.
  std::size_t slot_for(std::uint64_t key);
  void rehash(std::size_t capacity);

  double h_ = 1.0;
  double inv_h_ = 1.0;
  std::size_t count_ = 0;
  std::vector<std::uint64_t> key_;      // per id: its cell key, kAbsent when not stored
  std::vector<edgefront::Vec3> pos_;    // per id: stored position
  std::vector<int> next_, prev_;        // per id: neighbours in its cell's list (-1: none)
  std::vector<std::uint64_t> table_key_;  // per table slot: cell key, kAbsent when free
  std::vector<int> table_head_;           // per table slot: first id in the cell, -1 when empty
  std::size_t table_used_ = 0;            // slots with a key
};

}  // namespace gcs::detail
