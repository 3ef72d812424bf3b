// Tests of the "mesh renumbered" notice of the GCS hook API (gcs/operation.h): the loop renumbers
// its mesh in spatial order on larger meshes only when every registered operation can follow,
// and an operation that keeps handles between calls gets maps that send each of them to the same
// element; the loop's own state stays valid and the result deterministic.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <functional>
#include <memory>
#include <utility>
#include <vector>

#include "../gcs/src/detail/spatial_order.h"
#include "shapes/shapes.h"
#include "gcs/operation.h"
#include "gcs/reconstructor.h"
#include "gcs/twist_operation.h"
#include "shapes/twisted_shapes.h"

namespace {

using edgefront::EdgeHandle;
using edgefront::FaceHandle;
using edgefront::HalfedgeHandle;
using edgefront::Mesh;
using edgefront::Vec3;
using edgefront::VertexHandle;

// Keeps every live handle from its last call (the worst case of an operation keeping handles).
// Right before a renumbering (can_follow_renumbering) it notes what each kept handle stands for
// in the mesh as it is then; after it (on_renumbered) it checks that the map sends each to the
// same element of the renumbered mesh, and that exactly the deleted ones are gone.
class RecordingOperation : public gcs::Operation {
 public:
  explicit RecordingOperation(bool follow) : follow_(follow) {}
  std::string name() const override { return "recording"; }
  gcs::OperationResult apply(Mesh& mesh, const gcs::ChangeSet& changed, const gcs::OperationContext&) override {
    mesh_ = &mesh;
    ++calls;
    // The change set is in the current numbering: every handle is live.
    for (auto v : changed.vertices) ok = ok && v.idx() < static_cast<int>(mesh.n_vertices()) && !mesh.status(v).deleted();
    for (auto f : changed.faces) ok = ok && f.idx() < static_cast<int>(mesh.n_faces()) && !mesh.status(f).deleted();
    vertices_.clear();
    faces_.clear();
    halfedges_.clear();
    edges_.clear();
    for (auto v : mesh.vertices()) vertices_.push_back(v);
    for (auto f : mesh.faces()) faces_.push_back(f);
    for (auto h : mesh.halfedges()) halfedges_.push_back(h);
    for (auto e : mesh.edges()) edges_.push_back(e);
    return {};
  }
  bool can_follow_renumbering() const override {
    ++asked;
    if (!follow_ || mesh_ == nullptr) return follow_;
    const Mesh& m = *mesh_;
    before_.clear();
    for (auto v : vertices_) before_.push_back(m.status(v).deleted() ? dead() : vertex_print(m, v));
    for (auto f : faces_) before_.push_back(m.status(f).deleted() ? dead() : face_print(m, f));
    for (auto h : halfedges_) before_.push_back(m.status(m.edge_handle(h)).deleted() ? dead() : halfedge_print(m, h));
    for (auto e : edges_) before_.push_back(m.status(e).deleted() ? dead() : halfedge_print(m, m.halfedge_handle(e, 0)));
    return true;
  }
  void on_renumbered(const Mesh& mesh, const gcs::MeshRenumbering& map) override {
    ++renumberings;
    if (when_renumbered) when_renumbered();
    size_t k = 0;
    auto check = [&](bool gone, bool mapped_gone, const Print& now) {
      const Print& was = before_[k++];
      if (was == dead()) {
        ok = ok && mapped_gone;
        ++gone_checked;
        return;
      }
      ok = ok && !gone && !mapped_gone && now == was;
      ++kept_checked;
    };
    for (auto v : vertices_) {
      const VertexHandle n = map(v);
      check(!n.is_valid(), !n.is_valid(), n.is_valid() ? vertex_print(mesh, n) : dead());
    }
    for (auto f : faces_) {
      const FaceHandle n = map(f);
      check(!n.is_valid(), !n.is_valid(), n.is_valid() ? face_print(mesh, n) : dead());
    }
    for (auto h : halfedges_) {
      const HalfedgeHandle n = map(h);
      check(!n.is_valid(), !n.is_valid(), n.is_valid() ? halfedge_print(mesh, n) : dead());
    }
    for (auto e : edges_) {
      const EdgeHandle n = map(e);
      check(!n.is_valid(), !n.is_valid(), n.is_valid() ? halfedge_print(mesh, mesh.halfedge_handle(n, 0)) : dead());
    }
    ok = ok && k == before_.size();
    // The renumbered mesh has no deleted elements left.
    ok = ok && mesh.n_vertices() == static_cast<size_t>(std::count_if(map.vertex.begin(), map.vertex.end(), [](int i) { return i >= 0; }));
  }

  size_t calls = 0, renumberings = 0, kept_checked = 0, gone_checked = 0;
  std::function<void()> when_renumbered;  ///< called at each renumbering, after the checks' set-up
  mutable size_t asked = 0;
  bool ok = true;

 private:
  // What a handle stands for, by positions: a vertex its position, a face its corners from its
  // halfedge on, a halfedge its two ends and the third corner of its face.
  using Print = std::array<double, 9>;
  static Print dead() { return Print{-1e300, -1e300, -1e300, 0, 0, 0, 0, 0, 0}; }
  static void put(Print& p, int slot, const Vec3& x) {
    for (int a = 0; a < 3; ++a) p[static_cast<size_t>(3 * slot + a)] = x[a];
  }
  static Print vertex_print(const Mesh& m, VertexHandle v) {
    Print p{};
    put(p, 0, m.point(v));
    // and its first neighbour (the circulation start is kept too)
    if (m.halfedge_handle(v).is_valid()) put(p, 1, m.point(m.to_vertex_handle(m.halfedge_handle(v))));
    return p;
  }
  static Print face_print(const Mesh& m, FaceHandle f) {
    Print p{};
    int s = 0;
    for (auto v : m.fv_range(f)) put(p, s++, m.point(v));
    return p;
  }
  static Print halfedge_print(const Mesh& m, HalfedgeHandle h) {
    Print p{};
    put(p, 0, m.point(m.from_vertex_handle(h)));
    put(p, 1, m.point(m.to_vertex_handle(h)));
    if (m.face_handle(h).is_valid()) put(p, 2, m.point(m.to_vertex_handle(m.next_halfedge_handle(h))));
    return p;
  }

  bool follow_;
  const Mesh* mesh_ = nullptr;
  std::vector<VertexHandle> vertices_;
  std::vector<FaceHandle> faces_;
  std::vector<HalfedgeHandle> halfedges_;
  std::vector<EdgeHandle> edges_;
  mutable std::vector<Print> before_;
};

// Renumbered at 2048 live vertices (and then at every 1.5x growth); 10 basic steps per split keep
// the runs short.
gcs::ReconstructOptions options() {
  gcs::ReconstructOptions o;
  o.target_vertices = 2100;
  o.growth.steps_per_split = 10;
  o.growth.batch_splits = 50;
  o.progress_interval = 100;
  return o;
}

edgefront::PointCloud torus_cloud() {
  edgefront::shapes::SampleOptions so;
  so.points = 2500;  // at least one point per target vertex (options(): 2100)
  return edgefront::shapes::sample("torus", so);
}

edgefront::PointCloud vault_shell_cloud(size_t points, double thickness) {
  edgefront::shapes::SampleOptions so;
  so.points = points;
  so.shape.thickness = thickness;
  return edgefront::shapes::sample("vault-shell", so);
}

std::vector<Vec3> positions(const Mesh& mesh) {
  std::vector<Vec3> out;
  for (auto v : mesh.vertices()) out.push_back(mesh.point(v));
  return out;
}

TEST(GcsOperationRenumber, MapsSendKeptHandlesToTheSameElementsAndTheLoopStaysValid) {
  const edgefront::PointCloud cloud = torus_cloud();
  gcs::Reconstructor r(cloud, options());
  auto op = std::make_shared<RecordingOperation>(true);
  r.add_operation(op);
  size_t validated = 0;
  const gcs::ReconstructResult a = r.run([&](const gcs::Progress&) {
    r.validate();  // throws on any disagreement between the loop's state and the mesh
    ++validated;
    return true;
  });
  r.validate();
  EXPECT_EQ(a.stop_reason, gcs::StopReason::target_reached);
  EXPECT_GE(validated, 20u);  // every 100 splits
  EXPECT_EQ(op->renumberings, 1u);  // at 2048 live vertices
  EXPECT_TRUE(op->ok);
  EXPECT_GT(op->kept_checked, 20000u);  // ~2000 vertices, ~4000 faces, ~12000 halfedges, ~6000 edges
  EXPECT_GT(op->calls, 40u);

  // Same seed, same result, with the operation registered.
  gcs::Reconstructor r2(cloud, options());
  r2.add_operation(std::make_shared<RecordingOperation>(true));
  const gcs::ReconstructResult b = r2.run();
  EXPECT_EQ(positions(a.mesh), positions(b.mesh));
  EXPECT_EQ(a.mesh.n_faces(), b.mesh.n_faces());
}

// Registering an operation that changes nothing (and follows renumbering) leaves the run as it
// is without operations, byte for byte: the loop's own state does not depend on the hook.
TEST(GcsOperationRenumber, AnOperationThatChangesNothingLeavesTheRunAsItIs) {
  const edgefront::PointCloud cloud = vault_shell_cloud(5000, 0.02);
  gcs::ReconstructOptions o = options();
  o.target_vertices = 600;
  o.growth.steps_per_split = 50;  // with these settings the grid was once checked only with operations registered
  gcs::Reconstructor plain(cloud, o);
  const gcs::ReconstructResult a = plain.run();
  gcs::Reconstructor hooked(cloud, o);
  auto op = std::make_shared<RecordingOperation>(true);
  hooked.add_operation(op);
  const gcs::ReconstructResult b = hooked.run();
  EXPECT_GT(op->calls, 5u);
  EXPECT_GT(a.faces_removed, 0u) << "the topology pass removed faces (the case this guards)";
  EXPECT_EQ(positions(a.mesh), positions(b.mesh));
}

TEST(GcsOperationRenumber, AnOperationThatDoesNotOptInKeepsTheNumbering) {
  const edgefront::PointCloud cloud = torus_cloud();
  // Median index distance between the two ends of an edge: small after a spatial renumbering.
  auto median_gap = [](const Mesh& mesh) {
    std::vector<int> gaps;
    for (auto e : mesh.edges()) {
      const HalfedgeHandle h = mesh.halfedge_handle(e, 0);
      gaps.push_back(std::abs(mesh.from_vertex_handle(h).idx() - mesh.to_vertex_handle(h).idx()));
    }
    std::nth_element(gaps.begin(), gaps.begin() + static_cast<long>(gaps.size() / 2), gaps.end());
    return gaps[gaps.size() / 2];
  };
  gcs::Reconstructor r(cloud, options());
  auto declining = std::make_shared<RecordingOperation>(false);
  auto following = std::make_shared<RecordingOperation>(true);
  r.add_operation(following);
  r.add_operation(declining);
  r.run();
  r.validate();
  EXPECT_GT(declining->asked, 40u);  // asked at every split from 2048 live vertices on
  EXPECT_EQ(declining->renumberings, 0u);
  EXPECT_EQ(following->renumberings, 0u);  // one operation declining is enough
  gcs::Reconstructor renumbered(cloud, options());
  renumbered.add_operation(std::make_shared<RecordingOperation>(true));
  renumbered.run();
  EXPECT_GT(median_gap(r.mesh()), 5 * median_gap(renumbered.mesh()))
      << "not renumbered: splits append their vertices at the end, far from their neighbours";

  // The default of the interface declines.
  class Plain : public gcs::Operation {
   public:
    std::string name() const override { return "plain"; }
    gcs::OperationResult apply(Mesh&, const gcs::ChangeSet&, const gcs::OperationContext&) override { return {}; }
  } plain;
  EXPECT_FALSE(plain.can_follow_renumbering());
}

TEST(GcsOperationRenumber, MapOfHandlesOutOfRangeOrGoneIsInvalid) {
  gcs::MeshRenumbering map;
  map.vertex = {2, -1, 0};
  map.edge = {1, 0};
  map.face = {-1, 0};
  EXPECT_EQ(map(VertexHandle(0)), VertexHandle(2));
  EXPECT_FALSE(map(VertexHandle(1)).is_valid());
  EXPECT_FALSE(map(VertexHandle(3)).is_valid());
  EXPECT_FALSE(map(VertexHandle()).is_valid());
  EXPECT_EQ(map(FaceHandle(1)), FaceHandle(0));
  EXPECT_FALSE(map(FaceHandle(0)).is_valid());
  EXPECT_EQ(map(EdgeHandle(0)), EdgeHandle(1));
  EXPECT_EQ(map(HalfedgeHandle(1)), HalfedgeHandle(3));  // edge 0 -> 1, same direction
  EXPECT_EQ(map(HalfedgeHandle(2)), HalfedgeHandle(0));
  EXPECT_FALSE(map(HalfedgeHandle(4)).is_valid());
  EXPECT_FALSE(map(HalfedgeHandle()).is_valid());
}

// The twist repair follows a renumbering while it has found nothing (its state is then only
// caches), and declines once it found a region (its repairer keeps handles it cannot translate).
// A twist repair leaves index-keyed state (cut pairs, face snapshots, face grid) that the
// repairer translates itself (twist::TwistRepairer::renumber), so the operation keeps following.
TEST(GcsOperationRenumber, TwistOperationFollowsAfterItFoundARegion) {
  gcs::TwistOperation op;
  EXPECT_TRUE(op.can_follow_renumbering());
  twist::TwistedShape s = twist::flipped_disk_plate();
  const edgefront::PointCloud no_points;
  gcs::OperationContext ctx{no_points};
  ctx.live_vertices = s.mesh.n_vertices();
  gcs::ChangeSet all;
  for (auto f : s.mesh.faces()) all.faces.push_back(f);
  ASSERT_TRUE(op.apply(s.mesh, all, ctx).mesh_changed);
  EXPECT_GT(op.stats().regions_found, 0u);
  EXPECT_TRUE(op.can_follow_renumbering());
}

// Runs the loop with the twist operation and a recording operation (both following renumbering),
// validating the loop's state at every progress report.
struct TwistRun {
  gcs::ReconstructResult result;
  std::shared_ptr<gcs::TwistOperation> twist = std::make_shared<gcs::TwistOperation>();
  std::shared_ptr<RecordingOperation> recorder = std::make_shared<RecordingOperation>(true);
  size_t regions_at_first_renumbering = 0;
};
TwistRun run_with_twist(const edgefront::PointCloud& cloud, const gcs::ReconstructOptions& o) {
  TwistRun t;
  t.recorder->when_renumbered = [&t] {
    if (t.recorder->renumberings == 1) t.regions_at_first_renumbering = t.twist->stats().regions_found;
  };
  gcs::Reconstructor r(cloud, o);
  r.add_operation(t.twist);
  r.add_operation(t.recorder);
  t.result = r.run([&](const gcs::Progress&) {
    r.validate();
    return true;
  });
  r.validate();
  return t;
}

edgefront::PointCloud bumpy_sphere_cloud() {
  edgefront::shapes::SampleOptions so;
  so.points = 3000;
  return edgefront::shapes::sample("bumpy-sphere", so);
}

TEST(GcsOperationRenumber, ReconstructionWithTheTwistOperationRenumbersAndStaysValid) {
  const edgefront::PointCloud cloud = bumpy_sphere_cloud();
  gcs::ReconstructOptions o = options();
  o.growth.steps_per_split = 20;
  const TwistRun a = run_with_twist(cloud, o);
  EXPECT_EQ(a.result.stop_reason, gcs::StopReason::target_reached);
  EXPECT_GT(a.twist->stats().calls, 10u);
  EXPECT_EQ(a.twist->stats().regions_found, 0u);  // a clean bumpy sphere: nothing twisted
  EXPECT_EQ(a.recorder->renumberings, 1u);        // so the loop renumbered with the twist operation registered
  EXPECT_TRUE(a.recorder->ok);
  const TwistRun b = run_with_twist(cloud, o);
  EXPECT_EQ(positions(a.result.mesh), positions(b.result.mesh));
}

// A vault shell from a box with plain winners twists early (see twist_operation_test.cpp): the
// repair finds regions before the loop reaches the size where it renumbers; the loop still
// renumbers and stays valid, and the repairs never empty the mesh (a re-twist guard once cut out
// a region that was nearly all of it).
TEST(GcsOperationRenumber, ReconstructionRenumbersAfterTwistRepairs) {
  const edgefront::PointCloud cloud = vault_shell_cloud(3000, 0.2);
  gcs::ReconstructOptions o = options();
  o.input.orient_winners = false;
  o.growth.steps_per_split = 5;
  const TwistRun a = run_with_twist(cloud, o);
  EXPECT_GT(a.regions_at_first_renumbering, 0u);
  EXPECT_GE(a.recorder->renumberings, 1u);
  EXPECT_TRUE(a.recorder->ok);
  EXPECT_GT(a.result.mesh.n_vertices(), o.target_vertices / 2);
}

}  // namespace
