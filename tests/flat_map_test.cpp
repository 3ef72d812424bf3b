// The open-addressing table behind every front's working set (internal header).
#include "detail/flat_map.h"

#include <gtest/gtest.h>

#include <random>
#include <unordered_map>

namespace {

using edgefront::detail::FlatMap;

TEST(FlatMap, AgreesWithStdUnorderedMapUnderRandomInsertEraseAndClear) {
  FlatMap<int> map;
  std::unordered_map<uint32_t, int> ref;
  std::mt19937_64 rng(3);
  for (int round = 0; round < 4; ++round) {
    const uint32_t range = round % 2 == 0 ? 200000 : 300;  // large tables, then small ones
    for (int i = 0; i < 60000; ++i) {
      const uint32_t k = static_cast<uint32_t>(rng() % range);
      if (rng() % 3 == 0) {
        EXPECT_EQ(map.erase(k), ref.erase(k) == 1);
      } else {
        const int v = static_cast<int>(rng() % 1000);
        auto [p, inserted] = map.insert(k, v);
        auto [it, ref_inserted] = ref.emplace(k, v);
        ASSERT_EQ(inserted, ref_inserted);
        ASSERT_EQ(*p, it->second);
      }
      ASSERT_EQ(map.size(), ref.size());
    }
    for (const auto& [k, v] : ref) ASSERT_TRUE(map.find(k) && *map.find(k) == v);
    size_t seen = 0;
    map.for_each([&](uint32_t k, int v) {
      ++seen;
      EXPECT_EQ(ref.at(k), v);
    });
    EXPECT_EQ(seen, ref.size());
    // Clearing a large table gives back its memory and leaves a working, empty map.
    map.clear();
    ref.clear();
    EXPECT_TRUE(map.empty());
    EXPECT_LE(map.capacity(), 4096u);
    EXPECT_FALSE(map.contains(5));
  }
}

}  // namespace
