// Tests of the final projection of the GCS result onto the samples' tangent planes.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "../gcs/src/detail/sample_projection.h"
#include "edgefront/mesh.h"

namespace {

using edgefront::Mesh;
using edgefront::Vec3;
using edgefront::VertexHandle;

// A 5x5 vertex grid in z = 0 with unit spacing; interior vertices lifted by `lift`.
Mesh grid(double lift) {
  Mesh m;
  std::vector<VertexHandle> v;
  for (int j = 0; j < 5; ++j)
    for (int i = 0; i < 5; ++i) {
      const bool interior = i > 0 && i < 4 && j > 0 && j < 4;
      v.push_back(m.add_vertex(Vec3(i, j, interior ? lift : 0.0)));
    }
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      const VertexHandle a = v[j * 5 + i], b = v[j * 5 + i + 1], c = v[(j + 1) * 5 + i + 1], d = v[(j + 1) * 5 + i];
      m.add_face(a, b, c);
      m.add_face(a, c, d);
    }
  return m;
}

// Samples: the plane z = 0 with normal (0, 0, -1) (the sign must not matter); `nan_normal` gives none.
gcs::detail::CloudQuery plane(bool nan_normal = false) {
  return [nan_normal](const Vec3& p) {
    const Vec3 s(std::round(p[0]), std::round(p[1]), 0.0);
    const Vec3 n = nan_normal ? Vec3(std::numeric_limits<double>::quiet_NaN(), 0, 0) : Vec3(0, 0, -1);
    return gcs::detail::CloudHit{(p - s).norm(), n, s};
  };
}

TEST(GcsProjection, InteriorVerticesLandOnTheTangentPlaneBorderStays) {
  Mesh m = grid(0.2);
  EXPECT_EQ(gcs::detail::project_to_samples(m, plane(), 0.5), 9u);
  for (auto v : m.vertices()) EXPECT_NEAR(m.point(v)[2], 0.0, 1e-12);
}

TEST(GcsProjection, LongMovesAndUnknownNormalsAreRefused) {
  Mesh far = grid(0.2);
  EXPECT_EQ(gcs::detail::project_to_samples(far, plane(), 0.1), 0u);  // 0.2 > max_move
  Mesh nan = grid(0.2);
  EXPECT_EQ(gcs::detail::project_to_samples(nan, plane(true), 0.5), 0u);
  for (auto v : nan.vertices()) EXPECT_EQ(nan.point(v), grid(0.2).point(v));
}

TEST(GcsProjection, AFaceIsNotTurnedTooFar) {
  // Lifted by 3: the faces around the interior are steep; flattening them turns each by ~70-80 deg.
  Mesh m = grid(3.0);
  EXPECT_EQ(gcs::detail::project_to_samples(m, plane(), 10.0, 0.5), 0u);
  // Allowed to turn by up to 90 degrees, they move.
  Mesh n = grid(3.0);
  EXPECT_GT(gcs::detail::project_to_samples(n, plane(), 10.0, 0.0), 0u);
}

}  // namespace
