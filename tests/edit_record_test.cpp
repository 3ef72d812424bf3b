// twist/edit_record.h: the reference replay (order, simultaneous corner replacements, refusals
// that leave the arrays untouched), compact_faces, and replays of one-shot repairs of twisted
// meshes on a separate plain copy, face for face against the repaired mesh.

#include "twist/edit_record.h"

#include <gtest/gtest.h>

#include <random>
#include <string>

#include "edgefront/error.h"
#include "shapes/shapes.h"
#include "edit_test_util.h"
#include "twist/arrays.h"
#include "shapes/twisted_shapes.h"

namespace {

using namespace edgefront;
using twist::EditRecord;

// Two triangles sharing the edge 1-2, and a spare vertex.
struct Square {
  std::vector<double> V = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 5, 5, 5};
  std::vector<int> F = {0, 1, 2, 2, 1, 3};
};

TEST(EditRecord, ReplayFollowsTheDocumentedOrder) {
  Square s;
  EditRecord r;
  r.vertices_before = 5;
  r.faces_before = 2;
  r.vertices_added = {{1, {1, 0, 0}}, {-1, {2, 2, 2}}};  // vertex 5 copies 1, vertex 6 is new
  r.vertices_moved = {{4, {6, 6, 6}}};
  r.faces_flipped = {0};                                 // 0 1 2 -> 0 2 1
  r.corners_replaced = {{0, 1, 5}, {1, 2, 3}, {1, 3, 2}};  // face 1's two replacements swap 2 and 3 together
  r.faces_removed = {};
  r.faces_added = {{5, 6, 3}};
  twist::apply(r, s.V, s.F);
  EXPECT_EQ(s.F, (std::vector<int>{0, 2, 5, 3, 1, 2, 5, 6, 3}));
  ASSERT_EQ(s.V.size(), 21u);
  EXPECT_EQ(s.V[12], 6.0);
  EXPECT_EQ(s.V[15], 1.0);
  EXPECT_EQ(s.V[18], 2.0);

  EditRecord remove;
  remove.vertices_before = 7;
  remove.faces_before = 3;
  remove.faces_removed = {1};
  remove.vertices_removed = {3};
  twist::apply(remove, s.V, s.F);
  EXPECT_EQ(s.F, (std::vector<int>{0, 2, 5, -1, -1, -1, 5, 6, 3}));
  EXPECT_EQ(twist::compact_faces(s.F), (std::vector<int>{0, -1, 1}));
  EXPECT_EQ(s.F, (std::vector<int>{0, 2, 5, 5, 6, 3}));
}

TEST(EditRecord, ABadRecordLeavesTheArraysUntouched) {
  auto refused = [](const EditRecord& r, const char* part) {
    Square s;
    const Square before;
    try {
      twist::apply(r, s.V, s.F);
      ADD_FAILURE() << "accepted a record that does not fit (" << part << ")";
    } catch (const InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("nothing applied"), std::string::npos) << e.what();
    }
    EXPECT_EQ(s.V, before.V);
    EXPECT_EQ(s.F, before.F);
  };
  EditRecord r;
  r.vertices_before = 5;
  r.faces_before = 2;
  EditRecord wrong_size = r;
  wrong_size.vertices_before = 6;
  refused(wrong_size, "expects 6 vertices");
  EditRecord no_corner = r;
  no_corner.vertices_moved = {{0, {1, 1, 1}}};  // valid, but the next part is not: nothing may happen
  no_corner.corners_replaced = {{0, 3, 4}};
  refused(no_corner, "face 0 has no corner 3");
  EditRecord gone = r;
  gone.faces_flipped = {2};
  refused(gone, "face 2 is not a face");
  EditRecord repeat = r;
  repeat.corners_replaced = {{0, 0, 1}};
  refused(repeat, "face 0 would repeat a vertex");
  EditRecord bad_add = r;
  bad_add.faces_added = {{0, 1, 7}};
  refused(bad_add, "uses vertex 7");
  EditRecord bad_copy = r;
  bad_copy.vertices_added = {{9, {0, 0, 0}}};
  refused(bad_copy, "copies vertex 9");
  EditRecord nan_move = r;
  nan_move.vertices_moved = {{1, {0, std::nan(""), 0}}};
  refused(nan_move, "non-finite");
}

/// Repairs the arrays of `mesh` in one shot, replays the record on a plain copy and compares it
/// face for face with the mesh the same repair leaves (the conversion and `repair` without
/// garbage collection, run here separately). Returns the report.
twist::RepairReport replay_one_shot(const Mesh& mesh, const twist::RepairOptions& options, bool with_gc = false) {
  const MeshArrays a = mesh_to_arrays(mesh);
  const twist::ArrayRepair r = twist::repair_arrays(a.vertices, a.faces, options);
  std::vector<double> V = a.vertices;
  std::vector<int> F = a.faces;
  twist::apply(r.record, V, F);

  ArrayMesh converted = mesh_from_arrays(a.vertices, a.faces);
  twist::RepairOptions o = options;
  o.garbage_collect = false;
  const twist::RepairReport direct = twist::repair(converted.mesh, o);
  EXPECT_EQ(direct.repairs, r.report.repairs);
  EXPECT_EQ(direct.faces_flipped, r.report.faces_flipped);
  edittest::expect_same_mesh(V, F, converted.mesh, edittest::appended_numbering(converted.mesh, a.n_vertices()));

  // The record's own account: its copies sit where their originals are (a cut does not move).
  for (size_t i = 0; i < r.record.vertices_added.size(); ++i) {
    const twist::VertexAdded& add = r.record.vertices_added[i];
    if (add.original < 0) continue;
    bool moved = false;
    for (const twist::VertexMoved& m : r.record.vertices_moved) moved |= m.vertex == add.original;
    if (!moved) {
      for (int k = 0; k < 3; ++k) EXPECT_EQ(add.position[k], a.vertices[3 * static_cast<size_t>(add.original) + k]);
    }
  }
  if (!with_gc) return r.report;
  // And with garbage collection (the default), the repair gives the same mesh, compacted.
  Mesh collected = mesh;
  const twist::RepairReport gc = twist::repair(collected, options);
  std::vector<int> compact = F;
  twist::compact_faces(compact);
  EXPECT_EQ(collected.n_faces(), compact.size() / 3);
  EXPECT_EQ(gc.repairs, r.report.repairs);
  return r.report;
}

TEST(EditRecord, OneShotRepairsOfTwistedTubesReplayFaceForFace) {
  for (int segment : {-1, 5}) {
    twist::TwistedTubeOptions o;
    o.along = 16;
    o.around = 12;
    o.twist_segment = segment;
    const twist::TwistedShape shape = twist::twisted_tube(o);
    EXPECT_GT(replay_one_shot(shape.mesh, {}, segment < 0).repairs, 0u) << "the tube is twisted: the record holds a repair";
  }
}

TEST(EditRecord, OneShotRepairsOfFlippedDisksReplayFaceForFace) {
  for (int disk_rings : {2, 3}) {
    twist::FlippedDiskOptions o;
    o.rings = 10;
    o.around = 24;
    o.disk_rings = disk_rings;
    const twist::TwistedShape shape = twist::flipped_disk_plate(o);
    const twist::ReferenceNormals ref(twist::truth_points(shape));
    twist::RepairOptions ro;
    ro.detect.reference = &ref;
    // The detector's regions (cut, flip the smaller side): the labelling does not flip disks this
    // small (radius about two mean edges, fold band included) at its default cut price.
    ro.label_by_reference = false;
    EXPECT_GT(replay_one_shot(shape.mesh, ro).repairs, 0u);
    EXPECT_GT(replay_one_shot(shape.mesh, {}).repairs, 0u);
  }
}

TEST(EditRecord, HandFlippedPatchesOnASphereReplayFaceForFace) {
  const Mesh sphere = shapes::icosphere(3);
  PointCloud truth;
  for (VertexHandle v : sphere.vertices()) {
    truth.points.push_back(sphere.point(v));
    truth.normals.push_back(sphere.point(v).normalized());
  }
  const twist::ReferenceNormals ref(truth);
  twist::RepairOptions o;
  o.detect.reference = &ref;
  o.label_by_reference = false;  // the detector's regions: patches of 2-3 rings are below the labelling's cut price
  o.experimental.peel_flaps = 2;           // the repair's later steps too: removals,
  o.experimental.drop_turned_patches = 4;  // collapses and straightening moves
  int repaired = 0;
  for (unsigned seed = 1; seed <= 8; ++seed) {
    std::mt19937 rng(seed);
    Mesh m = sphere;
    const int patches = 1 + static_cast<int>(seed % 3);
    for (int p = 0; p < patches; ++p) {
      const VertexHandle centre(std::uniform_int_distribution<int>(0, static_cast<int>(m.n_vertices()) - 1)(rng));
      edittest::flip_patch(m, centre, 2 + static_cast<int>((seed + static_cast<unsigned>(p)) % 2), rng);
    }
    SCOPED_TRACE("seed " + std::to_string(seed));
    repaired += replay_one_shot(m, o).repairs > 0;
  }
  EXPECT_GE(repaired, 7) << "most hand-flipped patches are found and repaired";
}

}  // namespace
