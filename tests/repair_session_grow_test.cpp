// twist/repair_session.h, HealOptions::grow_rows: border growth on the reference points. A host
// removes a cap of an icosphere (a hole too large for the heal's fan); with growth the session
// grows rows of faces across the hole on the points, each answer replayed on plain arrays and
// compared with the mirror face for face, until the hole is closed; where the points face the
// other way (the cap turned in the reference) nothing grows.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <string>
#include <utility>

#include "edgefront/error.h"
#include "gcs/twist_operation.h"
#include "edit_test_util.h"
#include "shapes/shapes.h"
#include "twist/repair_session.h"

namespace {

using namespace edgefront;
using twist::EditRecord;
using twist::RepairSession;

/// Border edges of plain arrays: directed edges whose opposite no face holds.
Vec3 point_of(const std::vector<double>& V, int v) { return Vec3(V[3 * size_t(v)], V[3 * size_t(v) + 1], V[3 * size_t(v) + 2]); }

/// The unit sphere as a mesh (icosphere, 3 subdivisions) and as a denser reference cloud (the
/// vertices of a 5-times subdivided one), normals outward, or inward above z = `turned_above`.
struct CappedSphere {
  Mesh mesh = shapes::icosphere(3);
  MeshArrays arrays = mesh_to_arrays(mesh);
  double mean_edge = 0;
  PointCloud cloud(double turned_above) const {
    const Mesh dense = shapes::icosphere(5);
    PointCloud c;
    for (VertexHandle v : dense.vertices()) {
      const Vec3 p = dense.point(v).normalized();
      c.points.push_back(p);
      c.normals.push_back(p * (p[2] > turned_above ? -1.0 : 1.0));
    }
    return c;
  }
  CappedSphere() { mean_edge = edittest::mean_edge_length(mesh); }
  /// Removes the faces with a corner above z = 0.4 from the host's arrays and the session, and
  /// the vertices left without faces. Returns the faces removed.
  size_t remove_cap(RepairSession& s, std::vector<double>& V, std::vector<int>& F) const {
    size_t removed = 0;
    std::vector<int> uses(V.size() / 3, 0);
    for (size_t f = 0; 3 * f < F.size(); ++f) {
      bool above = false;
      for (size_t k = 0; k < 3; ++k) above = above || point_of(V, F[3 * f + k])[2] > 0.4;
      if (above) {
        s.remove_face(static_cast<int>(f));
        std::fill_n(F.begin() + 3 * std::ptrdiff_t(f), 3, -1);
        ++removed;
        continue;
      }
      for (size_t k = 0; k < 3; ++k) ++uses[size_t(F[3 * f + k])];
    }
    for (size_t v = 0; v < uses.size(); ++v)
      if (uses[v] == 0) s.remove_vertex(static_cast<int>(v));
    return removed;
  }
};

TEST(RepairSessionGrow, ACapGrowsBackClosedOnThePointsAndReplays) {
  const CappedSphere sphere;
  const twist::ReferenceNormals ref(sphere.cloud(2.0));  // every normal outward
  twist::SessionOptions so;
  so.repair.detect.reference = &ref;
  so.heal.enabled = true;
  so.heal.grow_rows = 2;
  RepairSession s(sphere.arrays.vertices, sphere.arrays.faces, so);
  std::vector<double> V = sphere.arrays.vertices;
  std::vector<int> F = sphere.arrays.faces;
  ASSERT_GT(sphere.remove_cap(s, V, F), 100u);
  const size_t border_before = edittest::border_edges(F);
  ASSERT_GT(border_before, 20u) << "a hole far larger than the heal's fans";
  size_t grown = 0, calls = 0;
  for (; calls < 40 && edittest::border_edges(F) > 0; ++calls) {
    const size_t vertices_before = V.size() / 3;
    const EditRecord r = s.repair(sphere.mean_edge);
    twist::apply(r, V, F);
    edittest::expect_session_matches(s, V, F);
    grown += s.stats().heal.grown;
    EXPECT_EQ(s.stats().report.repairs, 0u) << "nothing is twisted";
    // Every new vertex is a new point on the sphere, in the hole; every face faces outward.
    for (const twist::VertexAdded& a : r.vertices_added) {
      EXPECT_EQ(a.original, -1);
      const Vec3 p(a.position[0], a.position[1], a.position[2]);
      EXPECT_NEAR(p.norm(), 1.0, 0.1 * sphere.mean_edge);  // a mean of points on the sphere: slightly inside
      EXPECT_GT(p[2], 0.4 - sphere.mean_edge);
    }
    for (size_t f = 0; 3 * f < F.size(); ++f) {
      if (F[3 * f] < 0) continue;
      const Vec3 a = point_of(V, F[3 * f]), b = point_of(V, F[3 * f + 1]), c = point_of(V, F[3 * f + 2]);
      EXPECT_GT(((b - a) % (c - a)) | (a + b + c), 0.0) << "face " << f << " faces inward";
    }
    EXPECT_GE(V.size() / 3, vertices_before);
  }
  EXPECT_GT(grown, 50u);
  EXPECT_EQ(edittest::border_edges(F), 0u) << "closed after " << calls << " answers";
  // The finish keeps it closed and replays.
  twist::apply(s.finish(), V, F);
  edittest::expect_session_matches(s, V, F);
  EXPECT_EQ(edittest::border_edges(F), 0u);
}

TEST(RepairSessionGrow, NothingGrowsWhereThePointsFaceTheOtherWay) {
  const CappedSphere sphere;
  // The reference turned above z = 0.35: the hole's points face inward, against the faces around.
  const twist::ReferenceNormals ref(sphere.cloud(0.35));
  twist::SessionOptions so;
  so.repair.detect.reference = &ref;
  so.heal.enabled = true;
  so.heal.grow_rows = 2;
  RepairSession s(sphere.arrays.vertices, sphere.arrays.faces, so);
  std::vector<double> V = sphere.arrays.vertices;
  std::vector<int> F = sphere.arrays.faces;
  sphere.remove_cap(s, V, F);
  const size_t border_before = edittest::border_edges(F);
  const EditRecord r = s.repair(sphere.mean_edge);
  twist::apply(r, V, F);
  edittest::expect_session_matches(s, V, F);
  EXPECT_EQ(s.stats().heal.grown, 0u);
  EXPECT_TRUE(r.faces_added.empty());
  EXPECT_TRUE(r.vertices_added.empty());
  EXPECT_EQ(edittest::border_edges(F), border_before);
}

TEST(RepairSessionGrow, BadGrowthOptionsAreRefused) {
  const CappedSphere sphere;
  const twist::ReferenceNormals ref(sphere.cloud(2.0));
  twist::SessionOptions so;
  so.repair.detect.reference = &ref;
  so.heal.enabled = true;
  so.heal.grow_rows = 9;
  EXPECT_THROW(RepairSession(sphere.arrays.vertices, sphere.arrays.faces, so), InvalidInput);
  so.heal.grow_rows = 1;
  so.heal.grow_min_support = 0;
  EXPECT_THROW(RepairSession(sphere.arrays.vertices, sphere.arrays.faces, so), InvalidInput);
  so.heal.grow_min_support = 3;
  for (double share : {-0.1, 1.0, std::nan("")}) {
    so.heal.min_piece_share = share;
    EXPECT_THROW(RepairSession(sphere.arrays.vertices, sphere.arrays.faces, so), InvalidInput) << share;
  }
  so.heal.min_piece_share = 0.01;
  EXPECT_NO_THROW(RepairSession(sphere.arrays.vertices, sphere.arrays.faces, so));
  // The same growth in EdgeFront's own loop (gcs::TwistOperationOptions::grow_rows).
  gcs::TwistOperationOptions to;
  to.grow_rows = 9;
  EXPECT_THROW(gcs::TwistOperation{to}, InvalidInput);
  to.grow_rows = 2;
  EXPECT_NO_THROW(gcs::TwistOperation{to});
}

/// Small pieces go at the finish (HealOptions::min_piece_share): a sphere and a far smaller
/// separate sphere, the small one removed with a share above its size, kept below; replayed.
TEST(RepairSessionGrow, TheFinishDropsPiecesUnderTheShare) {
  const CappedSphere sphere;
  // The big sphere (1280 faces) and a small one (icosphere(1), 80 faces) beside it, both with
  // their own points (outward normals).
  Mesh both = sphere.mesh;
  const Mesh small = shapes::icosphere(1, 0.2);
  PointCloud cloud = sphere.cloud(2.0);
  const Mesh small_dense = shapes::icosphere(3, 0.2);
  for (VertexHandle v : small_dense.vertices()) {
    cloud.points.push_back(small_dense.point(v) + Vec3(3, 0, 0));
    cloud.normals.push_back(small_dense.point(v).normalized());
  }
  const twist::ReferenceNormals ref(cloud);
  std::vector<VertexHandle> map;
  for (VertexHandle v : small.vertices()) map.push_back(both.add_vertex(small.point(v) + Vec3(3, 0, 0)));
  for (FaceHandle f : small.faces()) {
    std::vector<VertexHandle> t;
    for (VertexHandle v : small.fv_range(f)) t.push_back(map[static_cast<size_t>(v.idx())]);
    both.add_face(t);
  }
  const MeshArrays arrays = mesh_to_arrays(both);
  for (double share : {0.05, 0.1}) {
    SCOPED_TRACE(share);
    twist::SessionOptions so;
    so.repair.detect.reference = &ref;
    so.heal.enabled = true;
    so.heal.min_piece_share = share;
    RepairSession s(arrays.vertices, arrays.faces, so);
    std::vector<double> V = arrays.vertices;
    std::vector<int> F = arrays.faces;
    const EditRecord r = s.finish();
    twist::apply(r, V, F);
    edittest::expect_session_matches(s, V, F);
    const size_t live = static_cast<size_t>(std::count_if(F.begin(), F.end(), [](int v) { return v >= 0; })) / 3;
    if (share < 80.0 / 1280.0) {
      EXPECT_EQ(s.stats().heal.piece_faces_removed, 0u);
      EXPECT_EQ(live, 1360u);
    } else {
      EXPECT_EQ(s.stats().heal.piece_faces_removed, 80u);
      EXPECT_EQ(live, 1280u);
    }
  }
}

}  // namespace
