// Tests of the fitted normals of clouds without normals (gcs/cloud_normals.h) and of their
// orientation (gcs::detail::orient_normals, gcs/src/detail/double_layer.h).

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "../gcs/src/detail/double_layer.h"
#include "edgefront/error.h"
#include "edgefront/point_index.h"
#include "shapes/shapes.h"
#include "gcs/cloud_normals.h"

namespace {

using edgefront::PointCloud;
using edgefront::PointIndex;
using edgefront::Vec3;

PointCloud sample(const std::string& shape, size_t n, double noise = 0) {
  edgefront::shapes::SampleOptions o;
  o.points = n;
  o.noise_sigma = noise;
  return edgefront::shapes::sample(shape, o);
}

struct Shares {
  double within30 = 0, undefined = 0;
};

// Shares of the points whose fitted normal lies within 30 degrees of the exact normal's line, and
// of the points without a normal.
Shares shares(const PointCloud& c, const std::vector<Vec3>& n) {
  Shares s;
  for (size_t i = 0; i < n.size(); ++i) {
    if (!std::isfinite(n[i][0])) {
      s.undefined += 1.0 / static_cast<double>(n.size());
      continue;
    }
    EXPECT_NEAR(n[i].norm(), 1.0, 1e-9);
    if (std::abs(n[i] | c.normals[i]) >= std::cos(M_PI / 6)) s.within30 += 1.0 / static_cast<double>(n.size());
  }
  return s;
}

// Mean distance from a point to its nearest other point.
double spacing(const PointCloud& c) {
  const PointIndex index(c.points);
  std::vector<PointIndex::Neighbor> knn;
  double sum = 0;
  for (const Vec3& p : c.points) {
    index.k_nearest(p, 2, knn);
    sum += std::sqrt(knn.back().distance2);
  }
  return sum / static_cast<double>(c.size());
}

// A coarse torus (400 points: 12 neighbours span a third of the tube's circumference): the plane
// through 20 neighbours failed its flatness test on 99.5% of them; the quadric's normal at the
// point is defined and right everywhere.
TEST(GcsFitNormals, CoarseCurvedCloudGetsItsNormalsEverywhere) {
  const PointCloud c = sample("torus", 400);
  const PointIndex index(c.points);
  const Shares s = shares(c, gcs::fit_normals(c.points, index));
  EXPECT_EQ(s.undefined, 0.0);
  EXPECT_GE(s.within30, 0.99);
}

// A thin closed box whose walls are closer than the point spacing (400 points, walls 0.1 apart,
// spacing about 0.14): most neighbourhoods hold both walls, which no one normal describes.
TEST(GcsFitNormals, TwoSheetsInOneNeighbourhoodHaveNoNormal) {
  const PointCloud c = sample("thin-plate", 400);
  const PointIndex index(c.points);
  EXPECT_GE(shares(c, gcs::fit_normals(c.points, index)).undefined, 0.8);
}

// Noise of one point spacing along the normal: no normal at the sampling scale; a twentieth of it:
// every normal defined and right.
TEST(GcsFitNormals, NoiseComparableToTheSpacingLeavesTheNormalsUndefined) {
  const double s = spacing(sample("grid", 3000));
  const PointCloud noisy = sample("grid", 3000, s), quiet = sample("grid", 3000, 0.05 * s);
  const PointIndex a(noisy.points), b(quiet.points);
  EXPECT_GE(shares(noisy, gcs::fit_normals(noisy.points, a)).undefined, 0.8);
  const Shares q = shares(quiet, gcs::fit_normals(quiet.points, b));
  EXPECT_EQ(q.undefined, 0.0);
  EXPECT_GE(q.within30, 1.0 - 1e-9);
}

// The thin box resolved (walls 3-4 spacings apart), its edges 90-degree creases: a point whose
// own neighbourhood straddles a crease takes a neighbour's neighbourhood on its own side.
TEST(GcsFitNormals, PointsNearACreaseTakeTheNormalOfTheirSide) {
  const PointCloud c = sample("thin-plate", 10000);
  const PointIndex index(c.points);
  gcs::NormalFitOptions own;
  own.best_neighbourhood = false;
  std::vector<double> residuals;
  const std::vector<Vec3> n = gcs::fit_normals(c.points, index, {}, &residuals);
  const Shares best = shares(c, n), alone = shares(c, gcs::fit_normals(c.points, index, own));
  EXPECT_GE(alone.undefined, 0.03);
  EXPECT_LE(best.undefined, 0.005);
  EXPECT_GE(best.within30, 0.96);
  ASSERT_EQ(residuals.size(), c.size());
  for (size_t i = 0; i < c.size(); ++i) EXPECT_EQ(std::isfinite(n[i][0]), std::isfinite(residuals[i])) << i;
}

TEST(GcsFitNormals, BadOptionsAreRefusedAndTinyCloudsHaveNoNormals) {
  const PointCloud c = sample("grid", 100);
  const PointIndex index(c.points);
  gcs::NormalFitOptions o;
  o.neighbours = 7;
  EXPECT_THROW(gcs::fit_normals(c.points, index, o), edgefront::InvalidInput);
  o = {};
  o.max_residual = 0;
  EXPECT_THROW(gcs::fit_normals(c.points, index, o), edgefront::InvalidInput);
  const std::vector<Vec3> few(c.points.begin(), c.points.begin() + 5);
  EXPECT_THROW(gcs::fit_normals(few, index), edgefront::InvalidInput);  // index of other points
  const PointIndex few_index(few);
  for (const Vec3& m : gcs::fit_normals(few, few_index)) EXPECT_TRUE(std::isnan(m[0]));
}

// The exact normals with seeded random signs.
std::vector<Vec3> scrambled(const PointCloud& c) {
  std::mt19937_64 rng(11);
  std::vector<Vec3> n = c.normals;
  for (Vec3& m : n)
    if (rng() & 1) m = -m;
  return n;
}

// Creases and two walls close together: Hoppe's n_i . n_j carried the sign across the thin box's
// 90-degree edges and between the hairpin's arms at random (0.6-0.8 of the box flipped); the
// reflection agreement orients every point outward.
TEST(GcsOrientNormals, CreasesAndCloseWallsAreOrientedOutward) {
  for (const char* shape : {"thin-plate", "hairpin", "vault-shell"}) {
    const PointCloud c = sample(shape, 10000);
    std::vector<Vec3> n = scrambled(c);
    const PointIndex index(c.points);
    ASSERT_TRUE(gcs::detail::orient_normals(c.points, index, n)) << shape;
    size_t wrong = 0;
    for (size_t i = 0; i < n.size(); ++i) wrong += (n[i] | c.normals[i]) < 0;
    EXPECT_EQ(wrong, 0u) << shape;
  }
}

// Noise along the normal: two points close together, one above the other, look like the two
// walls of a shell to the reflection; the fits' residuals given as the noise, a noisy plane's
// normals all end up.
TEST(GcsOrientNormals, NoiseAlongTheNormalIsNotReadAsTwoWalls) {
  const double s = spacing(sample("grid", 5000));
  const PointCloud c = sample("grid", 5000, 0.5 * s);
  std::vector<Vec3> n = scrambled(c);  // exact normals: (0, 0, +-1)
  std::vector<double> noise(c.size(), 0.5 * s);
  const PointIndex index(c.points);
  std::vector<Vec3> undamped = n;
  ASSERT_TRUE(gcs::detail::orient_normals(c.points, index, n, 8, &noise));
  for (const Vec3& m : n) ASSERT_GT(m[2], 0.99);
  ASSERT_TRUE(gcs::detail::orient_normals(c.points, index, undamped));
  size_t down = 0;
  for (const Vec3& m : undamped) down += m[2] < 0;
  EXPECT_GT(down, 0u);  // why the noise is needed
}

// A cluster of points denser than its surroundings whose 8 nearest are all its own, and an island
// of usable normals in undefined ones, are reached by the wider searches; a part lying far apart
// is not.
TEST(GcsOrientNormals, IslandsAreReachedPartsLyingApartAreNot) {
  PointCloud c = sample("grid", 2000);
  std::vector<Vec3> n = scrambled(c);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // Undefined normals on a ring around the point nearest the middle: its neighbours are an island.
  size_t mid = 0;
  for (size_t i = 0; i < c.size(); ++i)
    if (c.points[i].sqrnorm() < c.points[mid].sqrnorm()) mid = i;
  const double s = spacing(c);
  for (size_t i = 0; i < c.size(); ++i) {
    const double r = (c.points[i] - c.points[mid]).norm();
    if (r > 3 * s && r < 7 * s) n[i] = Vec3(nan, nan, nan);
  }
  {
    const PointIndex index(c.points);
    std::vector<Vec3> m = n;
    ASSERT_TRUE(gcs::detail::orient_normals(c.points, index, m));
    for (const Vec3& v : m) {
      if (std::isfinite(v[0])) {
        ASSERT_GT(v[2], 0.99);
      }
    }
  }
  // The same grid twice, far apart: refused.
  const size_t n0 = c.size();
  for (size_t i = 0; i < n0; ++i) {
    c.points.push_back(c.points[i] + Vec3(0, 0, 5));
    n.push_back(n[i]);
  }
  const PointIndex index(c.points);
  EXPECT_FALSE(gcs::detail::orient_normals(c.points, index, n));
}

}  // namespace
