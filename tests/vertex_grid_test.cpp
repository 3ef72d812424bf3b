// Tests of the GCS loop's vertex grid (gcs/src/detail/vertex_grid.h): its nearest-point query
// (the 2x2x2 block first, then rings) answers exactly what a linear scan answers, smallest
// (distance, id), for queries on and off the points' surface and at any cell size, while points
// move and are removed.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include "../gcs/src/detail/vertex_grid.h"

namespace {

using edgefront::Vec3;

int brute_nearest(const std::vector<Vec3>& pos, const std::vector<bool>& present, const Vec3& p) {
  int best = -1;
  double best_d = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < pos.size(); ++i) {
    if (!present[i]) continue;
    const double d = (pos[i] - p).sqrnorm();
    if (d < best_d) {  // ascending ids: the first of equal distances is the smallest id
      best_d = d;
      best = static_cast<int>(i);
    }
  }
  return best;
}

Vec3 on_sphere(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  Vec3 v(g(rng), g(rng), g(rng));
  return v / v.norm();
}

TEST(VertexGrid, NearestAgreesWithALinearScanAtAnyCellSize) {
  std::mt19937_64 rng(7);
  const size_t n = 1500;  // mean spacing on the unit sphere about 0.09
  std::vector<Vec3> pos;
  for (size_t i = 0; i < n; ++i) pos.push_back(on_sphere(rng));
  std::vector<bool> present(n, true);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const double cell : {0.02, 0.05, 0.09, 0.2, 1.0}) {
    gcs::detail::VertexGrid grid;
    grid.reset(cell);
    grid.resize(n);
    for (size_t i = 0; i < n; ++i) grid.insert(static_cast<int>(i), pos[i]);
    size_t checked = 0;
    for (int q = 0; q < 400; ++q) {
      // On the surface (the loop's samples), near it, and far off (inside, outside).
      Vec3 p = on_sphere(rng) * (q % 4 == 0 ? 1.0 + 0.05 * u(rng) : 1.0);
      if (q % 10 == 5) p = Vec3(u(rng), u(rng), u(rng)) * 0.5;
      if (q % 10 == 7) p = Vec3(u(rng), u(rng), u(rng)) * 4.0;
      ASSERT_EQ(grid.nearest(p), brute_nearest(pos, present, p)) << "cell " << cell << " query " << q;
      ++checked;
    }
    EXPECT_EQ(checked, 400u);
  }
  // Moves (small, as in a basic step, and large) and removals, then queries again.
  gcs::detail::VertexGrid grid;
  grid.reset(0.09);
  grid.resize(n);
  for (size_t i = 0; i < n; ++i) grid.insert(static_cast<int>(i), pos[i]);
  for (int round = 0; round < 2000; ++round) {
    const size_t i = static_cast<size_t>(rng() % n);
    if (!present[i]) continue;
    if (round % 7 == 0) {
      grid.remove(static_cast<int>(i));
      present[i] = false;
      continue;
    }
    pos[i] = round % 5 == 0 ? on_sphere(rng) : pos[i] + Vec3(u(rng), u(rng), u(rng)) * 0.01;
    grid.move(static_cast<int>(i), pos[i]);
  }
  for (int q = 0; q < 400; ++q) {
    const Vec3 p = on_sphere(rng);
    ASSERT_EQ(grid.nearest(p), brute_nearest(pos, present, p)) << "query " << q;
  }
}

TEST(VertexGrid, TiesGoToTheSmallerIdAndAnEmptyGridHasNoNearest) {
  gcs::detail::VertexGrid grid;
  grid.reset(0.5);
  grid.resize(4);
  EXPECT_EQ(grid.nearest(Vec3(0, 0, 0)), -1);
  // Two points at exactly the same distance (0.25) from the query, in two cells.
  const Vec3 q(0.25, 0.75, 0.75);
  grid.insert(3, Vec3(0.5, 0.75, 0.75));
  grid.insert(1, Vec3(0.0, 0.75, 0.75));
  grid.insert(2, Vec3(5, 5, 5));
  EXPECT_EQ(grid.nearest(q), 1);
  grid.remove(1);
  EXPECT_EQ(grid.nearest(q), 3);
  grid.insert(0, Vec3(0.5, 0.75, 0.75));  // same position as 3: the smaller id wins
  EXPECT_EQ(grid.nearest(q), 0);
  grid.remove(0);
  grid.remove(3);
  EXPECT_EQ(grid.nearest(q), 2);  // far away: found by the rings
}

}  // namespace
