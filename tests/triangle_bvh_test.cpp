// Tests of edgefront/triangle_bvh.h: the nearest triangle and the overlapping boxes match a
// brute-force search, and an empty list and a non-finite corner are refused.

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "edgefront/error.h"
#include "edgefront/triangle_bvh.h"

namespace {

using edgefront::Triangle;
using edgefront::TriangleBvh;
using edgefront::Vec3;

std::vector<Triangle> random_triangles(std::size_t n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> centre(-10, 10), offset(-0.7, 0.7);
  std::vector<Triangle> t;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 c(centre(rng), centre(rng), centre(rng));
    t.emplace_back(std::array<Vec3, 3>{c + Vec3(offset(rng), offset(rng), offset(rng)),
                                       c + Vec3(offset(rng), offset(rng), offset(rng)),
                                       c + Vec3(offset(rng), offset(rng), offset(rng))});
  }
  return t;
}

double dist2(const Vec3& x, const Triangle& t) {
  return (edgefront::closest_point_on_triangle(x, t.p[0], t.p[1], t.p[2]) - x).sqrnorm();
}

TEST(TriangleBvh, NearestMatchesBruteForce) {
  const std::vector<Triangle> tris = random_triangles(500, 3);
  const TriangleBvh bvh(tris);
  EXPECT_EQ(bvh.size(), 500);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-12, 12);
  for (int q = 0; q < 200; ++q) {
    const Vec3 x(u(rng), u(rng), u(rng));
    int best = -1;
    double best_d2 = 0;
    for (std::size_t i = 0; i < tris.size(); ++i) {
      const double d2 = dist2(x, tris[i]);
      if (best < 0 || d2 < best_d2) {
        best = static_cast<int>(i);
        best_d2 = d2;
      }
    }
    const TriangleBvh::Hit h = bvh.nearest(x);
    EXPECT_EQ(h.tri, best) << q;
    EXPECT_DOUBLE_EQ(h.dist2, best_d2) << q;
  }
}

TEST(TriangleBvh, OverlappingPairsMatchBruteForceEachPairOnce) {
  const std::vector<Triangle> tris = random_triangles(400, 5);
  const TriangleBvh bvh(tris);
  std::set<std::pair<int, int>> expected, found;
  for (std::size_t i = 0; i < tris.size(); ++i) {
    for (std::size_t j = i + 1; j < tris.size(); ++j) {
      if (tris[i].contact_box().overlaps(tris[j].contact_box())) expected.emplace(static_cast<int>(i), static_cast<int>(j));
    }
  }
  std::size_t visits = 0;
  for (int k = 0; k < bvh.size(); ++k) {
    const int a = bvh.in_order(k);
    bvh.for_each_overlapping(bvh.box(a), k + 1, [&](int b) {
      ++visits;
      found.emplace(std::min(a, b), std::max(a, b));
    });
  }
  EXPECT_FALSE(expected.empty());
  EXPECT_EQ(found, expected);
  EXPECT_EQ(visits, expected.size());  // each pair once
}

TEST(TriangleBvh, NoTrianglesIsRefused) {
  EXPECT_THROW(TriangleBvh(std::vector<Triangle>{}), edgefront::InvalidInput);
  // A non-finite corner is named, not sorted into the hierarchy.
  std::vector<Triangle> bad(3, Triangle({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}));
  bad[2].p[1][2] = std::numeric_limits<double>::quiet_NaN();
  try {
    TriangleBvh b(bad);
    ADD_FAILURE() << "a NaN corner was accepted";
  } catch (const edgefront::InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("triangle 2"), std::string::npos) << e.what();
  }
}

}  // namespace
