// Tests of the film test of the border creation and of the final projection of the GCS result
// onto the samples' tangent planes.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "../gcs/src/detail/border_topology.h"
#include "../gcs/src/detail/sample_projection.h"
#include "edgefront/mesh.h"

namespace {

using edgefront::Mesh;
using edgefront::Vec3;
using edgefront::VertexHandle;

// An n x n vertex grid in z = 0 with the given spacing, starting at `origin`; interior vertices
// lifted by `lift`.
Mesh grid(double lift, int n = 5, double spacing = 1.0, Vec3 origin = Vec3(0, 0, 0)) {
  Mesh m;
  std::vector<VertexHandle> v;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const bool interior = i > 0 && i < n - 1 && j > 0 && j < n - 1;
      v.push_back(m.add_vertex(origin + Vec3(i * spacing, j * spacing, interior ? lift : 0.0)));
    }
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const VertexHandle a = v[j * n + i], b = v[j * n + i + 1], c = v[(j + 1) * n + i + 1], d = v[(j + 1) * n + i];
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

// A film spanning a tunnel: a flat sheet (z = 0, x and y in [-0.5, 0.5]) inside a cylinder of
// radius 0.8 around the z axis sampled with normals pointing at the axis (the object lies outside
// the tunnel), plus samples on the sheet's plane (normal +z) for x < -0.3 only. Brute-force
// neighbour queries.
struct Tunnel {
  std::vector<gcs::detail::CloudHit> samples;
  explicit Tunnel(double wall_normal_sign) {
    for (int a = 0; a < 120; ++a)
      for (int k = -6; k <= 6; ++k) {
        const double t = 2 * M_PI * a / 120;
        const Vec3 p(0.8 * std::cos(t), 0.8 * std::sin(t), 0.05 * k);
        samples.push_back({0, wall_normal_sign * Vec3(-std::cos(t), -std::sin(t), 0), p});
      }
    for (int i = 0; i < 5; ++i)
      for (int j = 0; j <= 20; ++j) samples.push_back({0, Vec3(0, 0, 1), Vec3(-0.5 + 0.04 * i, -0.5 + 0.05 * j, 0)});
  }
  gcs::detail::CloudHit nearest(const Vec3& p) const {
    gcs::detail::CloudHit best{std::numeric_limits<double>::infinity(), {}, {}};
    for (const auto& s : samples)
      if ((s.point - p).norm() < best.distance) best = {(s.point - p).norm(), s.normal, s.point};
    return best;
  }
  void neighbors(const Vec3& p, std::size_t k, std::vector<gcs::detail::CloudHit>& out) const {
    out = samples;
    for (auto& s : out) s.distance = (s.point - p).norm();
    std::sort(out.begin(), out.end(), [](const auto& x, const auto& y) { return x.distance < y.distance; });
    out.resize(std::min(k, out.size()));
  }
};

// Faces with centroid x beyond `x` (sign > 0: x > limit; sign < 0: x < limit).
std::size_t faces_beyond(const Mesh& m, double limit, double sign) {
  std::size_t n = 0;
  for (auto f : m.faces()) {
    Vec3 c(0, 0, 0);
    for (auto v : m.fv_range(f)) c += m.point(v);
    if (sign * (c[0] / 3.0 - limit) > 0) ++n;
  }
  return n;
}

TEST(GcsFilm, AFilmAcrossATunnelIsRemovedTheSupportedSheetStays) {
  const Tunnel tunnel(+1.0);
  gcs::detail::BorderParams bp;
  bp.max_support_distance = 1.0;
  bp.max_edge_length = 1.0;
  bp.normal_check_distance = 1.0;  // the nearest-sample normal test stays out of the way
  bp.min_component_faces = 1;
  bp.min_component_fraction = 0;
  const auto query = [&](const Vec3& p) { return tunnel.nearest(p); };
  const auto near = [&](const Vec3& p, std::size_t k, std::vector<gcs::detail::CloudHit>& out) {
    tunnel.neighbors(p, k, out);
  };
  Mesh off = grid(0.0, 11, 0.1, Vec3(-0.5, -0.5, 0));
  EXPECT_EQ(gcs::detail::remove_unsupported_faces(off, query, bp, near), 0u);  // film_samples = 0: off
  bp.film_samples = 8;
  Mesh m = grid(0.0, 11, 0.1, Vec3(-0.5, -0.5, 0));
  const std::size_t left = faces_beyond(m, -0.35, -1), right = faces_beyond(m, 0.3, +1);
  EXPECT_GT(gcs::detail::remove_unsupported_faces(m, query, bp, near), 0u);
  m.garbage_collection();
  EXPECT_EQ(faces_beyond(m, 0.3, +1), 0u) << "of " << right;
  EXPECT_EQ(faces_beyond(m, -0.35, -1), left);
}

TEST(GcsFilm, AFaceBehindTheSamplesStays) {
  // Wall normals pointing away from the axis: the sheet lies inside the object (a sparsely sampled
  // stretch of a solid, not a film in front of its walls) and is kept.
  const Tunnel solid(-1.0);
  gcs::detail::BorderParams bp;
  bp.max_support_distance = 1.0;
  bp.max_edge_length = 1.0;
  bp.normal_check_distance = 1.0;
  bp.film_samples = 8;
  Mesh m = grid(0.0, 11, 0.1, Vec3(-0.5, -0.5, 0));
  EXPECT_EQ(gcs::detail::remove_unsupported_faces(
                m, [&](const Vec3& p) { return solid.nearest(p); }, bp,
                [&](const Vec3& p, std::size_t k, std::vector<gcs::detail::CloudHit>& out) { solid.neighbors(p, k, out); }),
            0u);
}

}  // namespace
