#include "detail/vertex_grid.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "edgefront/error.h"

namespace gcs::detail {

void VertexGrid::reset(double cell_size) {
  EF_CHECK(std::isfinite(cell_size) && cell_size > 0, "grid cell size must be positive");
  h_ = cell_size;
  inv_h_ = 1.0 / cell_size;
  count_ = 0;
  std::fill(key_.begin(), key_.end(), kAbsent);
  table_key_.assign(1024, kAbsent);
  table_head_.assign(1024, -1);
  table_used_ = 0;
}

void VertexGrid::resize(std::size_t n) {
  if (n <= key_.size()) return;
  key_.resize(n, kAbsent);
  pos_.resize(n, edgefront::Vec3(0, 0, 0));
  next_.resize(n, -1);
  prev_.resize(n, -1);
}

namespace {
// A 64-bit mix (the finalizer of MurmurHash3) so that neighbouring cells spread over the table.
std::uint64_t mix(std::uint64_t x) {
  x ^= x >> 33;
  x *= 0xff51afd7ed558ccdULL;
  x ^= x >> 33;
  x *= 0xc4ceb9fe1a85ec53ULL;
  x ^= x >> 33;
  return x;
}
}  // namespace

std::int64_t VertexGrid::find_slot(std::uint64_t key) const {
  if (table_key_.empty()) return -1;
  const std::size_t mask = table_key_.size() - 1;
  for (std::size_t s = mix(key) & mask;; s = (s + 1) & mask) {
    if (table_key_[s] == key) return static_cast<std::int64_t>(s);
    if (table_key_[s] == kAbsent) return -1;
  }
}

std::size_t VertexGrid::slot_for(std::uint64_t key) {
  if (table_key_.empty()) rehash(1024);
  const std::int64_t found = find_slot(key);
  if (found >= 0) return static_cast<std::size_t>(found);
  if (2 * (table_used_ + 1) > table_key_.size()) {
    // Full: drop the emptied cells, and double when at least a quarter of the slots hold ids.
    std::size_t nonempty = 0;
    for (const int head : table_head_) nonempty += head >= 0;
    rehash(4 * (nonempty + 1) > table_key_.size() ? 2 * table_key_.size() : table_key_.size());
  }
  const std::size_t mask = table_key_.size() - 1;
  std::size_t s = mix(key) & mask;
  while (table_key_[s] != kAbsent) s = (s + 1) & mask;
  table_key_[s] = key;
  table_head_[s] = -1;
  ++table_used_;
  return s;
}

void VertexGrid::rehash(std::size_t capacity) {
  std::vector<std::uint64_t> old_key;
  std::vector<int> old_head;
  old_key.swap(table_key_);
  old_head.swap(table_head_);
  table_key_.assign(capacity, kAbsent);
  table_head_.assign(capacity, -1);
  table_used_ = 0;
  const std::size_t mask = capacity - 1;
  for (std::size_t i = 0; i < old_key.size(); ++i) {
    if (old_key[i] == kAbsent || old_head[i] < 0) continue;
    std::size_t s = mix(old_key[i]) & mask;
    while (table_key_[s] != kAbsent) s = (s + 1) & mask;
    table_key_[s] = old_key[i];
    table_head_[s] = old_head[i];
    ++table_used_;
  }
}

void VertexGrid::insert(int id, const edgefront::Vec3& p) {
  EF_CHECK(id >= 0 && static_cast<std::size_t>(id) < key_.size(), "grid id out of range");
  EF_CHECK(key_[id] == kAbsent, "grid: id inserted twice");
  const std::uint64_t key = key_of(p);
  const std::size_t s = slot_for(key);
  const int head = table_head_[s];
  next_[id] = head;
  prev_[id] = -1;
  if (head >= 0) prev_[head] = id;
  table_head_[s] = id;
  key_[id] = key;
  pos_[id] = p;
  ++count_;
}

void VertexGrid::remove(int id) {
  EF_CHECK(contains(id), "grid: removing an absent id");
  const int nx = next_[id], pv = prev_[id];
  if (nx >= 0) prev_[nx] = pv;
  if (pv >= 0) {
    next_[pv] = nx;
  } else {
    const std::int64_t s = find_slot(key_[id]);
    EF_CHECK(s >= 0 && table_head_[static_cast<std::size_t>(s)] == id, "grid: cell of a stored id is missing");
    table_head_[static_cast<std::size_t>(s)] = nx;
  }
  key_[id] = kAbsent;
  --count_;
}

int VertexGrid::linear_nearest(const edgefront::Vec3& p) const {
  int best = -1;
  double best_d = std::numeric_limits<double>::infinity();
  for (std::size_t id = 0; id < key_.size(); ++id) {
    if (key_[id] == kAbsent) continue;
    const double d = (pos_[id] - p).sqrnorm();
    if (d < best_d) {
      best_d = d;
      best = static_cast<int>(id);
    }
  }
  return best;
}

int VertexGrid::nearest(const edgefront::Vec3& p) const {
  if (count_ == 0) return -1;
  const double px = p[0] * inv_h_, py = p[1] * inv_h_, pz = p[2] * inv_h_;
  const std::int64_t ci = cell_coord(p[0], inv_h_), cj = cell_coord(p[1], inv_h_), ck = cell_coord(p[2], inv_h_);
  // Position of p inside its cell, in [0, 1) per axis.
  const double fx = px - std::floor(px), fy = py - std::floor(py), fz = pz - std::floor(pz);
  int best = -1;
  double best_d = std::numeric_limits<double>::infinity();
  std::size_t visited = 0;
  // Squared distance (in cells) from p to cell (i, j, k); cells farther than the best are skipped.
  const auto gap = [](double x, std::int64_t c) {
    const double lo = static_cast<double>(c), hi = lo + 1;
    return x < lo ? lo - x : (x > hi ? x - hi : 0.0);
  };
  auto visit = [&](std::int64_t i, std::int64_t j, std::int64_t k) {
    ++visited;
    if (best >= 0) {
      const double gx = gap(px, i), gy = gap(py, j), gz = gap(pz, k);
      if ((gx * gx + gy * gy + gz * gz) * h_ * h_ > best_d) return;
    }
    const std::int64_t s = find_slot(pack(i, j, k));
    if (s < 0) return;
    for (int id = table_head_[static_cast<std::size_t>(s)]; id >= 0; id = next_[id]) {
      const double d = (pos_[id] - p).sqrnorm();
      if (d < best_d || (d == best_d && id < best)) {
        best_d = d;
        best = id;
      }
    }
  };
  // First the 2x2x2 block of cells nearest to p (its own cell and the neighbours on the side of p
  // along each axis): any cell outside the block is at least max(f, 1 - f) >= 1/2 cell away along
  // some axis, so a point found within that distance is the nearest (the usual case: the loop keeps
  // the cell size near the mean edge length, and samples lie within about half an edge of a
  // vertex). Otherwise the search continues in rings (which may revisit the block: the result,
  // the smallest (distance, id), does not depend on the visiting order).
  constexpr std::int64_t kInner = kBias - 4;  // away from the clamped border cells
  if (std::max({std::abs(ci), std::abs(cj), std::abs(ck)}) < kInner) {
    const std::int64_t si = fx < 0.5 ? -1 : 1, sj = fy < 0.5 ? -1 : 1, sk = fz < 0.5 ? -1 : 1;
    for (int c = 0; c < 8; ++c) visit(ci + ((c & 1) ? si : 0), cj + ((c & 2) ? sj : 0), ck + ((c & 4) ? sk : 0));
    if (best >= 0) {
      const double bound = std::min({std::max(fx, 1 - fx), std::max(fy, 1 - fy), std::max(fz, 1 - fz)}) * h_;
      if (best_d <= bound * bound) return best;
    }
  }
  // Lower bound of the distance from p to any cell of ring r + 1: distance to its own cell's
  // faces plus r whole cells.
  const double margin = std::min({fx, 1 - fx, fy, 1 - fy, fz, 1 - fz}) * h_;
  const std::size_t budget = 8 * count_ + 64;  // then a linear scan is cheaper
  for (std::int64_t r = 0;; ++r) {
    for (std::int64_t di = -r; di <= r; ++di) {
      for (std::int64_t dj = -r; dj <= r; ++dj) {
        const bool face = (di == -r || di == r || dj == -r || dj == r);
        if (face) {
          for (std::int64_t dk = -r; dk <= r; ++dk) visit(ci + di, cj + dj, ck + dk);
        } else {
          visit(ci + di, cj + dj, ck - r);
          if (r > 0) visit(ci + di, cj + dj, ck + r);
        }
      }
    }
    if (best >= 0) {
      const double bound = margin + static_cast<double>(r) * h_;
      if (best_d <= bound * bound) return best;
    }
    if (visited > budget || r > 2 * kBias) return linear_nearest(p);
  }
}

void VertexGrid::check(int id, const edgefront::Vec3& p) const {
  EF_CHECK(contains(id), "vertex " + std::to_string(id) + " is not in the spatial grid");
  EF_CHECK(pos_[id] == p, "vertex " + std::to_string(id) + " moved without a grid update");
  EF_CHECK(key_[id] == key_of(p), "vertex " + std::to_string(id) + " is stored in the wrong grid cell");
  const std::int64_t s = find_slot(key_[id]);
  bool found = false;
  for (int k = s >= 0 ? table_head_[static_cast<std::size_t>(s)] : -1; k >= 0 && !found; k = next_[k]) found = k == id;
  EF_CHECK(found, "grid cell of vertex " + std::to_string(id) + " does not hold it");
}

}  // namespace gcs::detail
