#pragma once
/// \file union_find.h
/// Disjoint sets over the integers 0..n-1 (union-find), the one the libraries share: connected
/// components of a mesh, corner classes of a triangle soup, cloud parts, vertex groups of a repair.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <type_traits>
#include <vector>

namespace edgefront {

/// Union-find with path halving. Every set is represented by its smallest element: `find(x)` is
/// the smallest element of x's set, whatever the order of the `unite` calls, so labels derived
/// from roots are deterministic (a set's root is also its first element in index order).
/// `Index` is the stored element type (`std::uint32_t` halves the memory when n < 2^32).
/// Elements are not range-checked: callers pass x < size() (an internal invariant, not input).
template <class Index = std::size_t>
class BasicUnionFind {
  static_assert(std::is_unsigned_v<Index>, "BasicUnionFind: Index must be an unsigned integer type");

 public:
  /// `n` singleton sets {0}, ..., {n-1}.
  explicit BasicUnionFind(std::size_t n = 0) : parent_(n) { std::iota(parent_.begin(), parent_.end(), Index{0}); }

  /// Number of elements.
  std::size_t size() const { return parent_.size(); }

  /// The smallest element of the set holding `x` (halves the path on the way).
  std::size_t find(std::size_t x) {
    while (parent_[x] != x) {
      parent_[x] = parent_[parent_[x]];
      x = parent_[x];
    }
    return x;
  }

  /// Merges the sets of `a` and `b`; returns true when they were different sets.
  bool unite(std::size_t a, std::size_t b) {
    a = find(a);
    b = find(b);
    if (a == b) return false;
    parent_[std::max(a, b)] = static_cast<Index>(std::min(a, b));
    return true;
  }

  /// Whether `a` and `b` are in the same set.
  bool same(std::size_t a, std::size_t b) { return find(a) == find(b); }

 private:
  std::vector<Index> parent_;
};

/// The usual union-find (std::size_t elements).
using UnionFind = BasicUnionFind<std::size_t>;

}  // namespace edgefront
