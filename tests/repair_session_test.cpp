// twist/repair_session.h: a session mirroring a host's plain mesh. Every record is replayed on a
// separate plain copy (the host) and compared face for face with the mirror; the incremental
// repair through the session is compared with the same TwistRepairer calls on an edgefront::Mesh.

#include "twist/repair_session.h"

#include <gtest/gtest.h>

#include <random>
#include <set>
#include <string>

#include "edgefront/error.h"
#include "shapes/shapes.h"
#include "edgefront/vertex_twins.h"
#include "edit_test_util.h"

namespace {

using namespace edgefront;
using twist::EditRecord;
using twist::RepairSession;

/// The host: plain arrays that replay every record.
struct Host {
  std::vector<double> V;
  std::vector<int> F;
  void replay(const EditRecord& r) { twist::apply(r, V, F); }
  std::array<int, 3> face(int f) const { return {F[3 * f], F[3 * f + 1], F[3 * f + 2]}; }
};

void expect_host_matches(const RepairSession& s, const Host& host) {
  edittest::expect_session_matches(s, host.V, host.F);
}

MeshArrays sphere_arrays(int subdivisions = 3) { return mesh_to_arrays(shapes::icosphere(subdivisions)); }

TEST(RepairSession, InitialRecordSplitsPinchedVertices) {
  // Two tetrahedra sharing one vertex (0).
  const std::vector<double> V = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, -1, 0, 0, 0, -1, 0, 0, 0, -1};
  const std::vector<int> F = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3, 0, 5, 4, 0, 4, 6, 0, 6, 5, 4, 5, 6};
  RepairSession s(V, F);
  EXPECT_EQ(s.conversion().pinched_vertices, 1u);
  const EditRecord& r = s.initial_record();
  ASSERT_EQ(r.vertices_added.size(), 1u);
  EXPECT_EQ(r.vertices_added[0].original, 0);
  EXPECT_EQ(r.corners_replaced.size(), 3u);  // the second tetrahedron's faces at vertex 0
  for (const twist::CornerReplaced& c : r.corners_replaced) {
    EXPECT_GE(c.face, 4);
    EXPECT_EQ(c.from, 0);
    EXPECT_EQ(c.to, 7);
  }
  Host host{V, F};
  host.replay(r);
  expect_host_matches(s, host);
}

TEST(RepairSession, RefusedBatchChangesNothing) {
  const MeshArrays a = sphere_arrays(2);
  RepairSession s(a.vertices, a.faces);
  Host host{a.vertices, a.faces};
  host.replay(s.initial_record());
  const std::array<int, 3> f0 = host.face(0);
  // Valid edits, then a face wound against face 0 (the same edge direction): all refused.
  s.set_vertex(5, {9, 9, 9});
  s.remove_face(7);
  s.set_face(static_cast<int>(host.F.size() / 3), {f0[0], f0[1], static_cast<int>(host.V.size() / 3)});
  s.set_vertex(static_cast<int>(host.V.size() / 3), {2, 2, 2});
  try {
    s.sync();
    FAIL() << "a face running along another face's edge in the same direction was accepted";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("nothing of the batch was applied"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(s.pending());
  expect_host_matches(s, host);
  EXPECT_TRUE(s.sync().empty());
  // Refused before anything is touched: a vertex no face may lose, gaps, dead vertices.
  s.remove_vertex(0);
  EXPECT_THROW(s.sync(), InvalidInput);
  s.set_vertex(static_cast<int>(host.V.size() / 3) + 3, {1, 1, 1});
  EXPECT_THROW(s.sync(), InvalidInput);
  s.set_face(0, {0, 1, 100000});
  EXPECT_THROW(s.sync(), InvalidInput);
  s.set_vertex(3, {std::nan(""), 0, 0});
  EXPECT_THROW(s.sync(), InvalidInput);
  EXPECT_THROW(s.set_face(-1, {0, 1, 2}), InvalidInput);
  expect_host_matches(s, host);
}

TEST(RepairSession, HostSplitsAndCollapsesAreMirrored) {
  // An edge split as a GCS loop does it: a new vertex on edge (a, b), the two faces re-connected
  // and two faces added; then collapsing it again.
  const MeshArrays a = sphere_arrays(2);
  RepairSession s(a.vertices, a.faces);
  Host host{a.vertices, a.faces};
  const std::array<int, 3> f = host.face(10);
  const int va = f[0], vb = f[1], vc = f[2];
  int g = -1, vd = -1;  // the face across (a, b): it runs b -> a
  for (size_t i = 0; 3 * i < host.F.size(); ++i) {
    const std::array<int, 3> t = host.face(static_cast<int>(i));
    for (int k = 0; k < 3; ++k)
      if (t[k] == vb && t[(k + 1) % 3] == va) {
        g = static_cast<int>(i);
        vd = t[(k + 2) % 3];
      }
  }
  ASSERT_GE(g, 0);
  const int x = static_cast<int>(host.V.size() / 3);
  const int nf = static_cast<int>(host.F.size() / 3);
  std::array<double, 3> mid{};
  for (int k = 0; k < 3; ++k) mid[k] = 0.5 * (host.V[3 * va + k] + host.V[3 * vb + k]);
  s.set_vertex(x, mid);
  s.set_face(10, {va, x, vc});
  s.set_face(nf, {x, vb, vc});
  s.set_face(g, {vb, x, vd});
  s.set_face(nf + 1, {x, va, vd});
  // The host does the same on its side.
  host.V.insert(host.V.end(), mid.begin(), mid.end());
  for (auto [slot, t] : std::vector<std::pair<int, std::array<int, 3>>>{{10, {va, x, vc}}, {g, {vb, x, vd}}})
    std::copy(t.begin(), t.end(), host.F.begin() + 3 * slot);
  for (std::array<int, 3> t : {std::array<int, 3>{x, vb, vc}, {x, va, vd}}) host.F.insert(host.F.end(), t.begin(), t.end());
  const EditRecord split = s.repair();
  EXPECT_TRUE(split.empty());
  expect_host_matches(s, host);
  // Collapse x back into a: remove the two new faces, re-connect, remove x.
  s.remove_face(nf);
  s.remove_face(nf + 1);
  s.set_face(10, {va, vb, vc});
  s.set_face(g, {vb, va, vd});
  s.remove_vertex(x);
  for (int slot : {nf, nf + 1}) std::fill_n(host.F.begin() + 3 * slot, 3, -1);
  for (auto [slot, t] : std::vector<std::pair<int, std::array<int, 3>>>{{10, {va, vb, vc}}, {g, {vb, va, vd}}})
    std::copy(t.begin(), t.end(), host.F.begin() + 3 * slot);
  EXPECT_TRUE(s.repair().empty());
  expect_host_matches(s, host);
  EXPECT_FALSE(s.mirror_vertex(x).is_valid());
  // The slots the host freed are free again.
  s.set_face(nf, {va, vb, vc});
  EXPECT_THROW(s.sync(), InvalidInput);  // (but face 10 already runs a -> b)
}

TEST(RepairSession, RemovalsThatPinchAVertexAreSplitInTheRecord) {
  // A strip of the sphere's faces around a vertex removed but two opposite faces: the vertex
  // joins two fans; the session splits it and the record says so.
  const MeshArrays a = sphere_arrays(2);
  RepairSession s(a.vertices, a.faces);
  Host host{a.vertices, a.faces};
  const int v = 0;
  std::vector<int> around;
  for (size_t i = 0; 3 * i < host.F.size(); ++i) {
    const std::array<int, 3> t = host.face(static_cast<int>(i));
    if (t[0] == v || t[1] == v || t[2] == v) around.push_back(static_cast<int>(i));
  }
  ASSERT_GE(around.size(), 5u);
  // Remove two non-adjacent faces of the ring: two fans remain at v.
  const Mesh& mirror = s.mirror();
  std::vector<int> ring;  // faces around v in circulation order
  for (FaceHandle f : mirror.vf_range(s.mirror_vertex(v))) ring.push_back(s.host_face(f));
  s.remove_face(ring[0]);
  s.remove_face(ring[2]);
  for (int f : {ring[0], ring[2]}) std::fill_n(host.F.begin() + 3 * f, 3, -1);
  const EditRecord r = s.sync();
  EXPECT_EQ(s.stats().pinched_split, 1u);
  ASSERT_EQ(r.vertices_added.size(), 1u);
  EXPECT_EQ(r.vertices_added[0].original, v);
  EXPECT_FALSE(r.corners_replaced.empty());
  host.replay(r);
  expect_host_matches(s, host);
  EXPECT_EQ(twins_of(s.mirror(), s.mirror_vertex(v)).size(), 1u);
}

// The incremental repair through the session and its records, against the same calls on a mesh.
TEST(RepairSession, IncrementalRepairsMatchTheRepairerOnAMeshAndReplay) {
  const Mesh sphere = shapes::icosphere(3);
  PointCloud truth;
  for (VertexHandle v : sphere.vertices()) {
    truth.points.push_back(sphere.point(v));
    truth.normals.push_back(sphere.point(v).normalized());
  }
  const twist::ReferenceNormals ref(truth);
  twist::SessionOptions so;
  so.repair.detect.reference = &ref;
  int repaired_calls = 0;
  for (unsigned seed = 1; seed <= 6; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const MeshArrays a = mesh_to_arrays(sphere);
    RepairSession s(a.vertices, a.faces, so);
    Host host{a.vertices, a.faces};
    twist::RepairOptions direct_options = so.repair;
    direct_options.garbage_collect = false;
    twist::TwistRepairer direct(direct_options, so.max_retwists);
    ArrayMesh mesh = mesh_from_arrays(a.vertices, a.faces);
    std::mt19937 rng(seed);
    const double mel = 0.1;
    for (int step = 0; step < 3; ++step) {
      // The host turns a patch over: on a copy of its own positions, then tells the session.
      Mesh turned = mesh.mesh;  // the same positions as the host (mirror indices = host's here)
      const VertexHandle centre(std::uniform_int_distribution<int>(0, static_cast<int>(sphere.n_vertices()) - 1)(rng));
      const std::vector<VertexHandle> moved = edittest::flip_patch(turned, centre, 2, rng);
      std::vector<FaceHandle> changed;
      for (VertexHandle v : moved) {
        const Vec3 p = turned.point(v);
        const int hv = s.host_vertex(v);
        ASSERT_GE(hv, 0);
        s.set_vertex(hv, {p[0], p[1], p[2]});
        for (int k = 0; k < 3; ++k) host.V[3 * static_cast<size_t>(hv) + k] = p[k];
        mesh.mesh.set_point(v, p);
        for (FaceHandle f : mesh.mesh.vf_range(v)) changed.push_back(f);
      }
      std::sort(changed.begin(), changed.end());
      changed.erase(std::unique(changed.begin(), changed.end()), changed.end());
      const EditRecord r = s.repair(mel);
      const twist::RepairReport d = direct.repair_changed(mesh.mesh, changed, mel);
      EXPECT_EQ(s.stats().report.repairs, d.repairs);
      repaired_calls += d.repairs > 0;
      host.replay(r);
      expect_host_matches(s, host);
      // The mirror is the directly repaired mesh, element for element.
      ASSERT_EQ(s.mirror().n_faces(), mesh.mesh.n_faces());
      ASSERT_EQ(s.mirror().n_vertices(), mesh.mesh.n_vertices());
      EXPECT_EQ(mesh_to_arrays(s.mirror()).faces, mesh_to_arrays(mesh.mesh).faces);
      EXPECT_EQ(mesh_to_arrays(s.mirror()).vertices, mesh_to_arrays(mesh.mesh).vertices);
      if (::testing::Test::HasFailure()) return;
    }
    const EditRecord last = s.finish();
    direct.finish(mesh.mesh);
    host.replay(last);
    expect_host_matches(s, host);
    EXPECT_EQ(mesh_to_arrays(s.mirror()).faces.size(), mesh_to_arrays(mesh.mesh).faces.size());
  }
  EXPECT_GE(repaired_calls, 6) << "the turned patches are found";
}

TEST(RepairSession, BoundedQueriesOnTheMirror) {
  const MeshArrays a = sphere_arrays(3);
  RepairSession s(a.vertices, a.faces);
  GeodesicSolver solver(a.vertices, a.faces);
  const DistanceArrays full = solver.distance_from_vertices(std::vector<int>{4});
  const SparseDistances near = s.distances_within(std::vector<int>{4}, 0.3);
  ASSERT_FALSE(near.vertex.empty());
  for (size_t i = 0; i < near.vertex.size(); ++i) EXPECT_EQ(near.distance[i], full.distance[static_cast<size_t>(near.vertex[i])]);
  const int w = near.vertex.back();
  ASSERT_TRUE(s.distance_between(4, w, 0.3).has_value());
  EXPECT_EQ(*s.distance_between(4, w, 0.3), full.distance[static_cast<size_t>(w)]);
  EXPECT_FALSE(s.distance_between(4, w, 0.5 * full.distance[static_cast<size_t>(w)]).has_value());
  s.set_vertex(4, {1.01 * a.vertices[12], 1.01 * a.vertices[13], 1.01 * a.vertices[14]});
  EXPECT_THROW(s.distance_between(4, w, 0.3), InvalidInput);  // edits pending
  s.sync();
  EXPECT_TRUE(s.distance_between(4, w, 0.3).has_value());
  EXPECT_THROW(s.distance_between(4, 100000, 0.3), InvalidInput);
}

}  // namespace
