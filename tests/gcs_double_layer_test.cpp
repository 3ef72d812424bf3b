// Tests of the double-layer guards of the GCS loop (gcs/src/detail/double_layer.h): orienting
// fitted normals, the orientation-aware winner search, the signed support test, and end to end
// that planar and landscape clouds give one clean sheet.

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "../gcs/src/detail/double_layer.h"
#include "edgefront/mesh_stats.h"
#include "edgefront/shapes.h"
#include "gcs/evaluation.h"
#include "gcs/reconstructor.h"

namespace {

using edgefront::Mesh;
using edgefront::PointCloud;
using edgefront::Vec3;
using edgefront::VertexHandle;

PointCloud cloud_of(const std::string& shape, size_t n) {
  edgefront::shapes::SampleOptions o;
  o.points = n;
  return edgefront::shapes::sample(shape, o);
}

// The cloud's normals with seeded random signs.
std::vector<Vec3> scrambled_normals(const PointCloud& c) {
  std::mt19937_64 rng(7);
  std::vector<Vec3> n = c.normals;
  for (Vec3& m : n)
    if (rng() & 1) m = -m;
  return n;
}

TEST(GcsOrientNormals, PlanarCloudPointsAlongPositiveThinAxis) {
  const PointCloud c = cloud_of("grid", 5000);
  std::vector<Vec3> n = scrambled_normals(c);
  const edgefront::PointIndex index(c.points);
  ASSERT_TRUE(gcs::detail::orient_normals(c.points, index, n));
  for (const Vec3& m : n) ASSERT_GT(m[2], 0.99);
}

TEST(GcsOrientNormals, ClosedCloudPointsOutward) {
  for (const char* shape : {"icosphere", "torus"}) {
    const PointCloud c = cloud_of(shape, 3000);
    std::vector<Vec3> n = scrambled_normals(c);
    const edgefront::PointIndex index(c.points);
    ASSERT_TRUE(gcs::detail::orient_normals(c.points, index, n)) << shape;
    for (size_t i = 0; i < n.size(); ++i) ASSERT_GT(n[i] | c.normals[i], 0.99) << shape << " point " << i;
  }
}

TEST(GcsOrientNormals, DisconnectedCloudIsRefused) {
  PointCloud c = cloud_of("grid", 500);
  const size_t n0 = c.size();
  for (size_t i = 0; i < n0; ++i) {
    c.points.push_back(c.points[i] + Vec3(10, 0, 0));
    c.normals.push_back(c.normals[i]);
  }
  std::vector<Vec3> n = c.normals;
  const edgefront::PointIndex index(c.points);
  EXPECT_FALSE(gcs::detail::orient_normals(c.points, index, n));
}

}  // namespace
