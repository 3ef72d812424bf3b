// twist/repair_session.h, SessionOptions::heal: the border heal after a repair. A host cuts an
// icosphere (a small hole, a band between two loops); the session's records are replayed on
// plain arrays and compared with the mirror face for face, and the heal must close only what
// runs opposite (a band whose two sides face the same way stays open).

#include "twist/repair_session.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <utility>

#include "edgefront/error.h"
#include "edit_test_util.h"
#include "shapes/shapes.h"

namespace {

using namespace edgefront;
using twist::EditRecord;
using twist::RepairSession;

/// The host: plain arrays that replay every record, and tell the session what they change.
struct Host {
  Host(std::vector<double> v, std::vector<int> f) : V(std::move(v)), F(std::move(f)), orphan_(V.size() / 3, 0) {}
  std::vector<double> V;
  std::vector<int> F;
  std::array<int, 3> face(size_t f) const { return {F[3 * f], F[3 * f + 1], F[3 * f + 2]}; }
  Vec3 point(int v) const { return Vec3(V[3 * size_t(v)], V[3 * size_t(v) + 1], V[3 * size_t(v) + 2]); }
  Vec3 centroid(size_t f) const {
    const std::array<int, 3> t = face(f);
    return (point(t[0]) + point(t[1]) + point(t[2])) / 3.0;
  }
  /// Removes the faces `pick` selects, and the vertices left without faces, in the session too.
  template <class Pick>
  size_t remove_faces(RepairSession& s, Pick pick) {
    size_t removed = 0;
    for (size_t f = 0; 3 * f < F.size(); ++f) {
      if (F[3 * f] < 0 || !pick(f)) continue;
      s.remove_face(static_cast<int>(f));
      std::fill_n(F.begin() + 3 * std::ptrdiff_t(f), 3, -1);
      ++removed;
    }
    std::vector<int> uses(V.size() / 3, 0);
    for (int v : F)
      if (v >= 0) ++uses[size_t(v)];
    for (size_t v = 0; v < uses.size(); ++v)
      if (uses[v] == 0 && !orphan_[v]) {
        s.remove_vertex(static_cast<int>(v));
        orphan_[v] = 1;
      }
    return removed;
  }
  size_t border_edges() const { return edittest::border_edges(F); }
  void replay(const EditRecord& r) {
    twist::apply(r, V, F);
    orphan_.resize(V.size() / 3, 0);
  }
  std::vector<char> orphan_;  // vertices this host removed
};

void expect_host_matches(const RepairSession& s, const Host& host) {
  edittest::expect_session_matches(s, host.V, host.F);
}

/// An icosphere (radius 1) and a reference cloud on it (its vertices and its edges' midpoints
/// pushed onto the sphere): outward normals, or inward where `inward(point)`.
struct Sphere {
  Mesh mesh = shapes::icosphere(3);
  MeshArrays arrays = mesh_to_arrays(mesh);
  double mean_edge = 0;
  template <class Inward>
  PointCloud cloud(Inward inward) const {
    PointCloud c;
    auto add = [&](const Vec3& p) {
      c.points.push_back(p);
      c.normals.push_back(p * (inward(p) ? -1.0 : 1.0));
    };
    for (VertexHandle v : mesh.vertices()) add(mesh.point(v).normalized());
    for (EdgeHandle e : mesh.edges()) {
      const HalfedgeHandle h = mesh.halfedge_handle(e, 0);
      add((mesh.point(mesh.from_vertex_handle(h)) + mesh.point(mesh.to_vertex_handle(h))).normalized());
    }
    return c;
  }
  Sphere() { mean_edge = edittest::mean_edge_length(mesh); }
};

TEST(RepairSessionHeal, ASmallHoleIsClosedByAFanAndReplays) {
  const Sphere sphere;
  const twist::ReferenceNormals ref(sphere.cloud([](const Vec3&) { return false; }));
  for (bool heal : {false, true}) {
    SCOPED_TRACE(heal ? "heal" : "no heal");
    twist::SessionOptions so;
    so.repair.detect.reference = &ref;
    so.heal.enabled = heal;
    RepairSession s(sphere.arrays.vertices, sphere.arrays.faces, so);
    Host host{sphere.arrays.vertices, sphere.arrays.faces};
    const Vec3 top = host.point(7);
    // The star of vertex 7 goes (5 or 6 faces): one hole, 5 or 6 border vertices.
    const size_t removed = host.remove_faces(s, [&](size_t f) {
      const std::array<int, 3> t = host.face(f);
      return t[0] == 7 || t[1] == 7 || t[2] == 7;
    });
    ASSERT_GE(removed, 5u);
    ASSERT_EQ(host.border_edges(), removed);
    const EditRecord r = s.repair(sphere.mean_edge);
    host.replay(r);
    expect_host_matches(s, host);
    if (!heal) {
      EXPECT_TRUE(r.faces_added.empty());
      EXPECT_EQ(host.border_edges(), removed);
      continue;
    }
    EXPECT_EQ(s.stats().heal.holes, 1u);
    EXPECT_EQ(s.stats().heal.faces_added, removed);
    ASSERT_EQ(r.faces_added.size(), removed);
    ASSERT_EQ(r.vertices_added.size(), 1u);  // the fan's centre: a new point
    EXPECT_EQ(r.vertices_added[0].original, -1);
    const std::array<double, 3>& c = r.vertices_added[0].position;
    EXPECT_LT((Vec3(c[0], c[1], c[2]) - top).norm(), 0.5 * sphere.mean_edge);
    EXPECT_EQ(host.border_edges(), 0u) << "closed again";
    // The next answer has nothing to heal; the finish keeps the mesh closed and replays.
    host.replay(s.repair(sphere.mean_edge));
    EXPECT_EQ(s.stats().heal.faces_added, 0u);
    host.replay(s.finish());
    expect_host_matches(s, host);
    EXPECT_EQ(host.border_edges(), 0u);
  }
}

/// The row of faces crossing the plane z = 0.1 removed: two loops about one edge apart. Zipped
/// when they run opposite; when the upper cap is turned (and the reference agrees with it, so
/// nothing is repaired), both loops run the same way and the heal must leave them open.
TEST(RepairSessionHeal, ABandIsZippedOnlyWhenItsSidesRunOpposite) {
  const Sphere sphere;
  const double plane = 0.1;
  auto crosses = [&](const Host& host, size_t f) {
    double lo = 2, hi = -2;
    for (int v : host.face(f)) {
      lo = std::min(lo, host.point(v)[2]);
      hi = std::max(hi, host.point(v)[2]);
    }
    return lo < plane && hi > plane;
  };
  for (bool turned : {false, true}) {
    SCOPED_TRACE(turned ? "upper cap turned" : "as made");
    const twist::ReferenceNormals ref(sphere.cloud([&](const Vec3& p) { return turned && p[2] > plane; }));
    twist::SessionOptions so;
    so.repair.detect.reference = &ref;
    so.heal.enabled = true;
    so.heal.max_gap_edges = 1.6;
    RepairSession s(sphere.arrays.vertices, sphere.arrays.faces, so);
    Host host{sphere.arrays.vertices, sphere.arrays.faces};
    ASSERT_GT(host.remove_faces(s, [&](size_t f) { return crosses(host, f); }), 40u);
    if (turned) {
      for (size_t f = 0; 3 * f < host.F.size(); ++f) {
        if (host.F[3 * f] < 0 || host.centroid(f)[2] <= plane) continue;
        std::swap(host.F[3 * f + 1], host.F[3 * f + 2]);
        s.set_face(static_cast<int>(f), host.face(f));
      }
    }
    const size_t border_before = host.border_edges();
    ASSERT_GT(border_before, 80u);
    const EditRecord r = s.repair(sphere.mean_edge);
    host.replay(r);
    expect_host_matches(s, host);
    EXPECT_EQ(s.stats().report.repairs, 0u) << "the reference agrees with every face";
    if (turned) {
      EXPECT_EQ(s.stats().heal.strips, 0u);
      EXPECT_EQ(s.stats().heal.holes, 0u);
      EXPECT_TRUE(r.faces_added.empty());
      EXPECT_EQ(host.border_edges(), border_before);
    } else {
      EXPECT_GE(s.stats().heal.strips, 1u);
      EXPECT_EQ(r.faces_added.size(), s.stats().heal.faces_added);
      EXPECT_LE(r.vertices_added.size(), s.stats().heal.holes);  // strips add no vertex, a fan at most one
      for (const twist::VertexAdded& a : r.vertices_added) EXPECT_EQ(a.original, -1);
      EXPECT_LT(host.border_edges(), border_before / 8) << "the band is zipped";
    }
  }
}

TEST(RepairSessionHeal, BadOptionsAreRefused) {
  const Sphere sphere;
  twist::SessionOptions so;
  so.heal.enabled = true;  // no reference cloud
  EXPECT_THROW(RepairSession(sphere.arrays.vertices, sphere.arrays.faces, so), InvalidInput);
  const twist::ReferenceNormals ref(sphere.cloud([](const Vec3&) { return false; }));
  so.repair.detect.reference = &ref;
  so.heal.max_gap_edges = -1;
  EXPECT_THROW(RepairSession(sphere.arrays.vertices, sphere.arrays.faces, so), InvalidInput);
  so.heal.max_gap_edges = 1;
  so.heal.max_support_edges = std::nan("");
  EXPECT_THROW(RepairSession(sphere.arrays.vertices, sphere.arrays.faces, so), InvalidInput);
  so.heal.enabled = false;  // off: the heal's values are not looked at
  EXPECT_NO_THROW(RepairSession(sphere.arrays.vertices, sphere.arrays.faces, so));
}

}  // namespace
