// Tests of edgefront/union_find.h: sets merge, the root is the smallest element whatever the
// order of the unions, and the narrow index type behaves the same.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <random>
#include <vector>

#include "edgefront/union_find.h"

namespace {

TEST(UnionFind, StartsAsSingletons) {
  edgefront::UnionFind u(5);
  EXPECT_EQ(u.size(), 5u);
  for (std::size_t i = 0; i < 5; ++i) EXPECT_EQ(u.find(i), i);
  EXPECT_FALSE(u.same(0, 1));
}

TEST(UnionFind, UniteMergesAndReportsWhetherItDid) {
  edgefront::UnionFind u(6);
  EXPECT_TRUE(u.unite(4, 2));
  EXPECT_TRUE(u.unite(2, 5));
  EXPECT_FALSE(u.unite(5, 4));  // already one set
  EXPECT_TRUE(u.same(4, 5));
  EXPECT_FALSE(u.same(0, 4));
  EXPECT_EQ(u.find(5), 2u);  // the smallest element is the root
}

// Against a brute-force labelling: random unions in random order; every root is the smallest
// element of its set, for both index types.
template <class UF>
void check_against_labels(unsigned seed) {
  constexpr std::size_t n = 300;
  std::mt19937 rng(seed);
  UF u(n);
  std::vector<std::size_t> label(n);
  std::iota(label.begin(), label.end(), std::size_t{0});
  for (int k = 0; k < 200; ++k) {
    const std::size_t a = rng() % n, b = rng() % n;
    u.unite(a, b);
    const std::size_t la = label[a], lb = label[b];
    const std::size_t lo = std::min(la, lb);
    for (std::size_t& l : label) {
      if (l == la || l == lb) l = lo;  // labels are the smallest member of each set
    }
  }
  for (std::size_t i = 0; i < n; ++i) EXPECT_EQ(u.find(i), label[i]) << i;
}

TEST(UnionFind, RootsAreTheSmallestElementsWhateverTheOrder) {
  for (unsigned seed = 1; seed <= 5; ++seed) {
    check_against_labels<edgefront::UnionFind>(seed);
    check_against_labels<edgefront::BasicUnionFind<std::uint32_t>>(seed);
  }
}

}  // namespace
