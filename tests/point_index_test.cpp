#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "edgefront/error.h"
#include "edgefront/point_index.h"

using edgefront::PointIndex;
using edgefront::Vec3;

namespace {

std::vector<Vec3> random_points(size_t n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Vec3> p(n);
  for (Vec3& x : p) x = Vec3(u(rng), u(rng), 0.2 * u(rng));
  return p;
}

// Brute force: indices sorted by (distance, index).
std::vector<size_t> by_distance(const std::vector<Vec3>& pts, const Vec3& q) {
  std::vector<size_t> order(pts.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    const double da = (pts[a] - q).sqrnorm(), db = (pts[b] - q).sqrnorm();
    return da != db ? da < db : a < b;
  });
  return order;
}

}  // namespace

TEST(PointIndex, QueriesAgreeWithBruteForce) {
  const std::vector<Vec3> pts = random_points(2000, 7);
  const PointIndex index(pts);
  ASSERT_EQ(index.size(), pts.size());
  const std::vector<Vec3> queries = random_points(200, 8);
  std::vector<PointIndex::Neighbor> knn;
  std::vector<size_t> within;
  for (const Vec3& q : queries) {
    const std::vector<size_t> order = by_distance(pts, q);
    const PointIndex::Neighbor nn = index.nearest(q);
    EXPECT_DOUBLE_EQ(nn.distance2, (pts[order[0]] - q).sqrnorm());
    index.k_nearest(q, 12, knn);
    ASSERT_EQ(knn.size(), 12u);
    for (size_t k = 0; k < knn.size(); ++k) {
      EXPECT_DOUBLE_EQ(knn[k].distance2, (pts[order[k]] - q).sqrnorm()) << "rank " << k;
      EXPECT_DOUBLE_EQ(knn[k].distance2, (pts[knn[k].index] - q).sqrnorm());
    }
    const double r = 0.15;
    index.radius_search(q, r, within);
    std::vector<size_t> expected;
    for (size_t i = 0; i < pts.size(); ++i)
      if ((pts[i] - q).sqrnorm() < r * r) expected.push_back(i);
    EXPECT_EQ(within, expected);  // sorted by index, the same set
  }
}

TEST(PointIndex, EmptyAndSmallSets) {
  const PointIndex empty(std::vector<Vec3>{});
  EXPECT_TRUE(empty.empty());
  EXPECT_THROW(empty.nearest(Vec3(0, 0, 0)), edgefront::InvalidInput);
  std::vector<PointIndex::Neighbor> knn{{3, 1.0}};
  empty.k_nearest(Vec3(0, 0, 0), 5, knn);
  EXPECT_TRUE(knn.empty());
  std::vector<size_t> within{1};
  empty.radius_search(Vec3(0, 0, 0), 1.0, within);
  EXPECT_TRUE(within.empty());

  const PointIndex two(std::vector<Vec3>{Vec3(0, 0, 0), Vec3(1, 0, 0)});
  two.k_nearest(Vec3(0.9, 0, 0), 10, knn);  // asks for more than there are
  ASSERT_EQ(knn.size(), 2u);
  EXPECT_EQ(knn[0].index, 1u);
  EXPECT_EQ(knn[1].index, 0u);
  two.radius_search(Vec3(0, 0, 0), -1.0, within);  // negative radius: nothing
  EXPECT_TRUE(within.empty());
}

TEST(PointIndex, RejectsNonFinitePointsNamingThem) {
  std::vector<Vec3> pts{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, std::numeric_limits<double>::quiet_NaN(), 0)};
  try {
    const PointIndex index(pts);
    FAIL() << "a NaN coordinate was accepted";
  } catch (const edgefront::InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("point 2"), std::string::npos) << e.what();
  }
  pts[2] = Vec3(std::numeric_limits<double>::infinity(), 0, 0);
  EXPECT_THROW(PointIndex{pts}, edgefront::InvalidInput);
}

TEST(PointIndex, MovedIndexStillAnswers) {
  PointIndex a(random_points(100, 3));
  const PointIndex::Neighbor before = a.nearest(Vec3(0.1, 0.2, 0));
  PointIndex b(std::move(a));
  const PointIndex::Neighbor after = b.nearest(Vec3(0.1, 0.2, 0));
  EXPECT_EQ(before.index, after.index);
  EXPECT_EQ(b.points().size(), 100u);
}
