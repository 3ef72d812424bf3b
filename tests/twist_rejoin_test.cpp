// Tests of the border re-join after a twist repair (gcs/src/detail/border_rejoin.h): two pieces
// of a plate separated by a gap are joined when their borders run opposite (orientation-
// compatible), and left apart when one piece is flipped (both borders run the same way).

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "../gcs/src/detail/border_rejoin.h"
#include "edgefront/mesh_stats.h"
#include "edgefront/point_index.h"

namespace {

using edgefront::Mesh;
using edgefront::Vec3;

/// A 6 x 8 grid plate in z = 0 (edge 1, normals +z), split between columns 2 and 3: the right
/// part is moved by `gap` along x and, when `flip_right`, wound the other way.
Mesh split_plate(double gap, bool flip_right) {
  Mesh m;
  const int nx = 6, ny = 8;
  std::vector<std::vector<Mesh::VertexHandle>> left(nx), right(nx);
  for (int i = 0; i < nx; ++i) {
    for (int j = 0; j < ny; ++j) {
      left[i].push_back(i <= 2 ? m.add_vertex(Vec3(i, j, 0)) : Mesh::VertexHandle());
      right[i].push_back(i >= 2 ? m.add_vertex(Vec3(i + gap, j, 0)) : Mesh::VertexHandle());
    }
  }
  for (int i = 0; i + 1 < nx; ++i) {
    const bool r = i >= 2;
    const auto& g = r ? right : left;
    for (int j = 0; j + 1 < ny; ++j) {
      const auto a = g[i][j], b = g[i + 1][j], c = g[i + 1][j + 1], d = g[i][j + 1];
      if (r && flip_right) {
        m.add_face(a, c, b);
        m.add_face(a, d, c);
      } else {
        m.add_face(a, b, c);
        m.add_face(a, c, d);
      }
    }
  }
  return m;
}

/// The samples of the whole plate (with the gap filled) and their +z normals, as a cloud query.
struct PlateCloud {
  std::vector<Vec3> points;
  edgefront::PointIndex index;
  explicit PlateCloud(double gap) : points(make(gap)), index(points) {}
  static std::vector<Vec3> make(double gap) {
    std::vector<Vec3> p;
    for (double x = 0; x <= 5 + gap + 1e-9; x += 0.25) {
      for (double y = 0; y <= 7 + 1e-9; y += 0.25) p.emplace_back(x, y, 0);
    }
    return p;
  }
  gcs::detail::CloudQuery query() const {
    return [this](const Vec3& p) {
      return gcs::detail::CloudHit{std::sqrt(index.nearest(p).distance2), Vec3(0, 0, 1)};
    };
  }
};

TEST(TwistRejoin, CompatibleBordersAcrossAGapAreZipped) {
  Mesh m = split_plate(0.6, false);
  ASSERT_EQ(edgefront::compute_stats(m).components, 2u);
  const PlateCloud cloud(0.6);
  const gcs::detail::RejoinResult r = gcs::detail::rejoin_borders(m, cloud.query(), {1.0, 0.5, 1.0});
  EXPECT_GE(r.strips + r.loops_merged, 1u);
  m.garbage_collection();
  const edgefront::MeshStats st = edgefront::compute_stats(m);
  EXPECT_EQ(st.components, 1u);
  EXPECT_EQ(st.nonmanifold_vertices, 0u);
  for (auto f : m.faces()) EXPECT_GT(m.calc_face_normal(f)[2], 0.9) << "the strip agrees with both pieces";
}

TEST(TwistRejoin, IncompatibleBordersStayApart) {
  Mesh m = split_plate(0.6, true);  // the right piece faces -z: its border runs the same way as the left's
  const size_t faces = m.n_faces();
  const PlateCloud cloud(0.6);
  const gcs::detail::RejoinResult r = gcs::detail::rejoin_borders(m, cloud.query(), {1.0, 0.5, 1.0});
  EXPECT_EQ(r.strips + r.loops_merged, 0u);
  EXPECT_EQ(m.n_faces(), faces);
  EXPECT_EQ(edgefront::compute_stats(m).components, 2u);
}

TEST(TwistRejoin, FarBordersAndBadParametersDoNothing) {
  Mesh m = split_plate(2.5, false);  // the gap is wider than max_gap_edges
  const PlateCloud cloud(2.5);
  EXPECT_EQ(gcs::detail::rejoin_borders(m, cloud.query(), {1.0, 0.5, 1.0}).strips, 0u);
  EXPECT_EQ(edgefront::compute_stats(m).components, 2u);
  Mesh n = split_plate(0.6, false);
  const gcs::detail::RejoinResult r = gcs::detail::rejoin_borders(n, cloud.query(), {0.0, 0.5, 1.0});
  EXPECT_EQ(r.strips + r.loops_merged, 0u);
}

}  // namespace
