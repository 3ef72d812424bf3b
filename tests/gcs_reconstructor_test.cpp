// Tests of the GCS reconstructor (gcs/reconstructor.h, gcs/operation.h): the loop's state checked
// against the mesh after every progress call, topology on analytic shapes, determinism, cancellation,
// operations registered through the hook API, and bad input. Small targets (<= 600 vertices).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "edgefront/error.h"
#include "edgefront/mesh_stats.h"
#include "shapes/shapes.h"
#include "gcs/reconstructor.h"

namespace {

using edgefront::Mesh;
using edgefront::PointCloud;
using edgefront::Vec3;

PointCloud cloud_of(const std::string& shape, size_t points = 3000, std::uint64_t seed = 1) {
  edgefront::shapes::SampleOptions o;
  o.points = points;
  o.seed = seed;
  return edgefront::shapes::sample(shape, o);
}

gcs::ReconstructOptions small(size_t target) {
  gcs::ReconstructOptions o;
  o.target_vertices = target;
  o.growth.batch_splits = 50;
  o.progress_interval = 25;
  return o;
}

void expect_manifold(const Mesh& mesh, const std::string& what) {
  const edgefront::MeshStats s = edgefront::compute_stats(mesh);
  EXPECT_EQ(s.nonmanifold_vertices, 0u) << what;
  EXPECT_EQ(s.isolated_vertices, 0u) << what;
  EXPECT_EQ(s.duplicate_faces, 0u) << what;
  EXPECT_GT(s.faces, 0u) << what;
}

std::vector<double> flat_points(const Mesh& mesh) {
  std::vector<double> out;
  for (auto v : mesh.vertices())
    for (int k = 0; k < 3; ++k) out.push_back(mesh.point(v)[k]);
  return out;
}
std::vector<int> flat_faces(const Mesh& mesh) {
  std::vector<int> out;
  for (auto f : mesh.faces())
    for (auto v : mesh.fv_range(f)) out.push_back(v.idx());
  return out;
}

class GcsState : public ::testing::TestWithParam<std::string> {};

TEST_P(GcsState, MatchesTheMeshAtEveryProgressCall) {
  {
    std::string shape = GetParam();
    std::replace(shape.begin(), shape.end(), '_', '-');
    gcs::Reconstructor r(cloud_of(shape, 2000), small(300));
    size_t checks = 0;
    const gcs::ReconstructResult res = r.run([&](const gcs::Progress& p) {
      EXPECT_NO_THROW(r.validate()) << shape << " at " << p.vertices << " vertices";
      ++checks;
      return true;
    });
    EXPECT_NO_THROW(r.validate()) << shape;
    EXPECT_GE(checks, 5u) << shape;
    EXPECT_EQ(res.stop_reason, gcs::StopReason::target_reached) << shape;
    EXPECT_GT(res.splits, 0u);
    expect_manifold(res.mesh, shape);
    // Every output vertex lies near the samples' surface (the bounding box grown by 10%).
    edgefront::MeshStats s = edgefront::compute_stats(res.mesh);
    EXPECT_LE(s.bbox_diagonal, 1.1 * 2 * std::sqrt(3.0) * 1.2) << shape;
  }
}

INSTANTIATE_TEST_SUITE_P(Shapes, GcsState,
                         ::testing::Values("icosphere", "torus", "hemisphere", "cylinder", "vault_sheet"),
                         [](const ::testing::TestParamInfo<std::string>& param_info) { return param_info.param; });

TEST(GcsReconstructor, SphereIsClosedWithEulerCharacteristicTwo) {
  const gcs::ReconstructResult res = gcs::reconstruct(cloud_of("icosphere"), small(400));
  const edgefront::MeshStats s = edgefront::compute_stats(res.mesh);
  EXPECT_EQ(s.vertices, 400u);
  EXPECT_EQ(s.components, 1u);
  EXPECT_EQ(s.border_loops, 0u);
  EXPECT_EQ(s.euler_characteristic, 2);
  // Vertices on the unit sphere, up to the discretization.
  for (auto v : res.mesh.vertices()) EXPECT_NEAR(res.mesh.point(v).norm(), 1.0, 0.05);
  // Outward orientation: positive signed volume.
  double vol = 0;
  for (auto f : res.mesh.faces()) {
    auto it = res.mesh.cfv_iter(f);
    const Vec3 a = res.mesh.point(*it), b = res.mesh.point(*++it), c = res.mesh.point(*++it);
    vol += (a | (b % c)) / 6.0;
  }
  EXPECT_NEAR(vol, 4.0 / 3.0 * M_PI, 0.3);
}

// Measured at 500 vertices with the default batch (200 splits); see the README for the targets at
// larger sizes. (With 50-split batches the torus stays at two unmerged loops at this size.)
struct TopologyCase {
  std::string shape;
  size_t loops;
  double genus;
};
class GcsTopology : public ::testing::TestWithParam<TopologyCase> {};

TEST_P(GcsTopology, BordersAndHandlesAsTheShapeHas) {
  const TopologyCase& c = GetParam();
  gcs::ReconstructOptions o;
  o.target_vertices = 500;
  const gcs::ReconstructResult res = gcs::reconstruct(cloud_of(c.shape, 20000), o);
  const edgefront::MeshStats s = edgefront::compute_stats(res.mesh);
  expect_manifold(res.mesh, c.shape);
  EXPECT_EQ(s.components, 1u) << c.shape;
  EXPECT_EQ(s.border_loops, c.loops) << c.shape;
  ASSERT_EQ(s.per_component.size(), 1u) << c.shape;
  EXPECT_EQ(s.per_component[0].genus, c.genus) << c.shape;
}

INSTANTIATE_TEST_SUITE_P(Shapes, GcsTopology,
                         ::testing::Values(TopologyCase{"hemisphere", 1, 0}, TopologyCase{"cylinder", 2, 0},
                                           TopologyCase{"vault-sheet", 1, 0}, TopologyCase{"torus", 0, 1}),
                         [](const ::testing::TestParamInfo<TopologyCase>& param_info) {
                           std::string n = param_info.param.shape;
                           std::replace(n.begin(), n.end(), '-', '_');
                           return n;
                         });

// A hollow ball: the outer sphere's samples face outward, the inner one's inward. The loop reaches
// the inner sphere through a tunnel whose faces the opposed-face test removes; the inner piece it
// cuts off lies on a part of the cloud of its own and stays (seeds 3 and 4 lost it, leaving 9-11
// border loops, before OpposedParams::sample_part).
TEST(GcsReconstructor, NestedSpheresEndAsTwoClosedSpheresOrientedAsTheirSamples) {
  const PointCloud cloud = cloud_of("nested-spheres", 8000);
  for (std::uint64_t seed : {1, 3, 4}) {
    gcs::ReconstructOptions o;
    o.target_vertices = 1000;
    o.seed = seed;
    const gcs::ReconstructResult res = gcs::reconstruct(cloud, o);
    const std::string what = "seed " + std::to_string(seed);
    expect_manifold(res.mesh, what);
    const edgefront::MeshStats s = edgefront::compute_stats(res.mesh);
    EXPECT_EQ(s.components, 2u) << what;
    EXPECT_EQ(s.border_loops, 0u) << what;
    // One sphere each: the components' mean radii; the volume signs say which way they face.
    const edgefront::ComponentLabels labels = edgefront::connected_components(res.mesh);
    ASSERT_EQ(labels.count, 2u) << what;
    std::vector<double> radius(2, 0), volume(2, 0), count(2, 0);
    for (auto v : res.mesh.vertices()) {
      const auto c = static_cast<size_t>(labels.vertex_component[static_cast<size_t>(v.idx())]);
      radius[c] += res.mesh.point(v).norm();
      count[c] += 1;
    }
    for (auto f : res.mesh.faces()) {
      auto it = res.mesh.cfv_iter(f);
      const auto c = static_cast<size_t>(labels.vertex_component[static_cast<size_t>(it->idx())]);
      const Vec3 a = res.mesh.point(*it), b = res.mesh.point(*++it), d = res.mesh.point(*++it);
      volume[c] += (a | (b % d)) / 6.0;
    }
    const size_t inner = radius[0] / count[0] < radius[1] / count[1] ? 0 : 1, outer = 1 - inner;
    EXPECT_NEAR(radius[inner] / count[inner], 0.5, 0.02) << what;
    EXPECT_NEAR(radius[outer] / count[outer], 1.0, 0.02) << what;
    EXPECT_NEAR(volume[outer], 4.0 / 3.0 * M_PI, 0.3) << what;              // outward
    EXPECT_NEAR(volume[inner], -4.0 / 3.0 * M_PI * 0.125, 0.05) << what;  // inward
  }
}

// A small sphere (radius 0.2) beside a large one: at 800 vertices it has a few dozen faces, far
// below 5% of the large sphere's, and the small-component rule deleted it (every seed). It lies
// on a part of the cloud of its own, so it is judged against the largest piece on that part.
TEST(GcsReconstructor, SmallSeparateSurfaceIsKept) {
  PointCloud cloud = cloud_of("icosphere", 10000);
  edgefront::shapes::SampleOptions o;
  o.points = 400;
  o.shape.radius = 0.2;
  o.seed = 2;
  const PointCloud small = edgefront::shapes::sample("icosphere", o);
  for (size_t i = 0; i < small.size(); ++i) {
    cloud.points.push_back(small.points[i] + Vec3(2.5, 0, 0));
    cloud.normals.push_back(small.normals[i]);
  }
  for (std::uint64_t seed : {1, 2, 3}) {
    gcs::ReconstructOptions options;
    options.target_vertices = 800;
    options.seed = seed;
    const gcs::ReconstructResult res = gcs::reconstruct(cloud, options);
    const std::string what = "seed " + std::to_string(seed);
    expect_manifold(res.mesh, what);
    const edgefront::MeshStats s = edgefront::compute_stats(res.mesh);
    EXPECT_EQ(s.components, 2u) << what;
    EXPECT_LE(s.border_loops, 1u) << what;
    // The small sphere's piece: a few dozen vertices, on average at its radius (a coarse mesh of
    // it strays by up to half the radius).
    size_t on_small = 0;
    double radius = 0;
    for (auto v : res.mesh.vertices()) {
      const Vec3& p = res.mesh.point(v);
      if (p[0] > 2.0) {
        ++on_small;
        radius += (p - Vec3(2.5, 0, 0)).norm();
      } else {
        EXPECT_NEAR(p.norm(), 1.0, 0.05) << what;
      }
    }
    ASSERT_GE(on_small, 8u) << what;
    EXPECT_NEAR(radius / static_cast<double>(on_small), 0.2, 0.03) << what;
  }
}

TEST(GcsReconstructor, SameSeedSameMeshOtherSeedOtherMesh) {
  const PointCloud cloud = cloud_of("torus", 2000);
  const gcs::ReconstructResult a = gcs::reconstruct(cloud, small(250));
  const gcs::ReconstructResult b = gcs::reconstruct(cloud, small(250));
  EXPECT_EQ(flat_points(a.mesh), flat_points(b.mesh));
  EXPECT_EQ(flat_faces(a.mesh), flat_faces(b.mesh));
  gcs::ReconstructOptions o = small(250);
  o.seed = 2;
  const gcs::ReconstructResult c = gcs::reconstruct(cloud, o);
  EXPECT_NE(flat_points(a.mesh), flat_points(c.mesh));
}

TEST(GcsReconstructor, CancelReturnsAValidMeshAndRunContinues) {
  gcs::Reconstructor r(cloud_of("icosphere", 2000), small(400));
  int calls = 0;
  const gcs::ReconstructResult first = r.run([&](const gcs::Progress&) { return ++calls < 3; });
  EXPECT_EQ(first.stop_reason, gcs::StopReason::cancelled);
  EXPECT_EQ(calls, 3);
  EXPECT_LT(first.mesh.n_vertices(), 400u);
  EXPECT_GT(first.mesh.n_vertices(), 8u);
  expect_manifold(first.mesh, "cancelled");
  EXPECT_EQ(edgefront::compute_stats(first.mesh).border_loops, 0u);
  EXPECT_NO_THROW(r.validate());
  const gcs::ReconstructResult second = r.run();
  EXPECT_EQ(second.stop_reason, gcs::StopReason::target_reached);
  EXPECT_EQ(second.mesh.n_vertices(), 400u);
}

// Deletes the lowest-index changed face (and so makes a border) in its first calls.
class DeleteOneFace : public gcs::Operation {
 public:
  std::string name() const override { return "delete-one-face"; }
  gcs::OperationResult apply(Mesh& mesh, const gcs::ChangeSet& changed, const gcs::OperationContext& ctx) override {
    check_change_set(mesh, changed);
    EXPECT_GT(ctx.mean_edge_length, 0);
    EXPECT_EQ(ctx.points.size(), 2000u);
    gcs::OperationResult r;
    if (++calls > 2 || changed.faces.empty()) return r;
    mesh.delete_face(changed.faces.front(), true);
    r.mesh_changed = true;
    r.summary = "deleted a face";
    return r;
  }
  static void check_change_set(const Mesh& mesh, const gcs::ChangeSet& cs) {
    EXPECT_TRUE(std::is_sorted(cs.vertices.begin(), cs.vertices.end()));
    EXPECT_TRUE(std::adjacent_find(cs.vertices.begin(), cs.vertices.end()) == cs.vertices.end());
    EXPECT_TRUE(std::is_sorted(cs.faces.begin(), cs.faces.end()));
    for (auto v : cs.vertices) EXPECT_TRUE(edgefront::is_live(mesh, v));
    for (auto f : cs.faces) EXPECT_TRUE(edgefront::is_live(mesh, f));
  }
  int calls = 0;
};

// Flips every flippable edge of up to 20 changed faces and moves a vertex (a "region flip").
class FlipRegion : public gcs::Operation {
 public:
  std::string name() const override { return "flip-region"; }
  gcs::OperationResult apply(Mesh& mesh, const gcs::ChangeSet& changed, const gcs::OperationContext&) override {
    DeleteOneFace::check_change_set(mesh, changed);
    gcs::OperationResult r;
    size_t n = 0;
    for (auto f : changed.faces) {
      if (n++ == 20) break;
      if (mesh.status(f).deleted()) continue;
      for (auto e : mesh.fe_range(f)) {
        if (mesh.is_flip_ok(e) && !mesh.is_boundary(e)) {
          mesh.flip(e);
          r.mesh_changed = true;
          break;
        }
      }
    }
    if (!changed.vertices.empty()) {
      mesh.point(changed.vertices.back()) *= 1.01;
      r.mesh_changed = true;
    }
    // And one new vertex inside a face.
    for (auto f : mesh.faces()) {
      Vec3 c(0, 0, 0);
      for (auto v : mesh.fv_range(f)) c += mesh.point(v) / 3.0;
      mesh.split(f, c);
      r.mesh_changed = true;
      break;
    }
    return r;
  }
};

TEST(GcsReconstructor, OperationsCanChangeTheMeshAndTheLoopResynchronizes) {
  gcs::Reconstructor r(cloud_of("icosphere", 2000), small(300));
  auto del = std::make_shared<DeleteOneFace>();
  r.add_operation(del);
  r.add_operation(std::make_shared<FlipRegion>());
  size_t checks = 0;
  const gcs::ReconstructResult res = r.run([&](const gcs::Progress&) {
    EXPECT_NO_THROW(r.validate());
    ++checks;
    return true;
  });
  EXPECT_NO_THROW(r.validate());
  EXPECT_GT(checks, 3u);
  EXPECT_EQ(res.stop_reason, gcs::StopReason::target_reached);
  ASSERT_EQ(res.operations.size(), 2u);
  EXPECT_EQ(res.operations[0].name, "delete-one-face");
  EXPECT_GE(res.operations[0].calls, 4u);
  EXPECT_EQ(res.operations[0].changes, 2u);
  EXPECT_EQ(res.operations[0].last_summary, "deleted a face");
  EXPECT_EQ(res.operations[1].changes, res.operations[1].calls);
  expect_manifold(res.mesh, "after operations");
  EXPECT_GE(res.mesh.n_vertices(), 290u);
}

TEST(GcsReconstructor, AnOperationSeesOnlyChangesSinceItsLastCall) {
  // An operation that changes nothing sees, in its second call, only elements the loop touched
  // in the batch between (fewer than all) and never a deleted one.
  class Recorder : public gcs::Operation {
   public:
    std::string name() const override { return "recorder"; }
    gcs::OperationResult apply(Mesh& mesh, const gcs::ChangeSet& cs, const gcs::OperationContext& ctx) override {
      DeleteOneFace::check_change_set(mesh, cs);
      sizes.push_back({cs.vertices.size(), ctx.live_vertices});
      return {};
    }
    std::vector<std::pair<size_t, size_t>> sizes;
  };
  auto rec = std::make_shared<Recorder>();
  gcs::ReconstructOptions o = small(400);
  o.growth.batch_splits = 1;
  gcs::Reconstructor r(cloud_of("icosphere", 2000), o);
  r.add_operation(rec);
  r.run();
  ASSERT_GT(rec->sizes.size(), 10u);
  EXPECT_EQ(rec->sizes[0].first, rec->sizes[0].second);  // first call: every vertex is new
  // In the second half (>= 200 vertices, 100 basic steps per call) most calls see a part.
  size_t partial = 0, calls = 0;
  for (size_t i = rec->sizes.size() / 2; i < rec->sizes.size(); ++i, ++calls)
    partial += rec->sizes[i].first < rec->sizes[i].second;
  EXPECT_GT(partial, calls / 2);
}

// GrowthOptions::batch_growth_vertices: from that many live vertices on, batches of
// ceil(batch_splits x live / batch_growth_vertices) splits. Below it the mesh is the same as with
// fixed batches; above it there are fewer, longer batches (each call still sees every change since
// the last), and the result is still a valid closed mesh.
TEST(GcsReconstructor, BatchesGrowWithTheMeshFromBatchGrowthVertices) {
  const PointCloud cloud = cloud_of("icosphere", 3000);
  gcs::ReconstructOptions fixed = small(400);
  fixed.growth.batch_growth_vertices = 0;
  gcs::ReconstructOptions above = small(400);
  above.growth.batch_growth_vertices = 400;  // the target: never grows
  const gcs::ReconstructResult a = gcs::reconstruct(cloud, fixed), b = gcs::reconstruct(cloud, above);
  EXPECT_EQ(flat_points(a.mesh), flat_points(b.mesh));
  EXPECT_EQ(flat_faces(a.mesh), flat_faces(b.mesh));
  EXPECT_EQ(a.batches, b.batches);

  fixed.growth.batch_splits = 1;
  gcs::ReconstructOptions grown = fixed;
  grown.growth.batch_growth_vertices = 10;  // from 10 vertices on: 10% growth per batch
  const gcs::ReconstructResult c = gcs::reconstruct(cloud, fixed), d = gcs::reconstruct(cloud, grown);
  EXPECT_GE(c.batches, c.splits);  // one split per batch (and the final call)
  // 10 vertices to 400 at >= 10% per batch: at most ln(40) / ln(1.1) ~ 39 batches, plus those
  // that collapses undo.
  EXPECT_LT(d.batches, 80u);
  EXPECT_GT(d.batches, 30u);
  EXPECT_EQ(edgefront::compute_stats(d.mesh).border_loops, 0u);
  expect_manifold(d.mesh, "grown batches");
}

// The presets differ from the defaults in the documented fields only; preset() maps the names; the
// header's designated-initializer example compiles and sets the nested field.
TEST(GcsReconstructor, PresetsChangeOnlyTheirDocumentedFields) {
  using gcs::ReconstructOptions;
  EXPECT_EQ(ReconstructOptions::scan(), ReconstructOptions{});
  ReconstructOptions shell = ReconstructOptions::thin_shell();
  EXPECT_TRUE(shell.experimental.skip_unfaced_samples);
  EXPECT_TRUE(shell.input.quadric_normals);
  shell.experimental.skip_unfaced_samples = false;
  shell.input.quadric_normals = false;
  EXPECT_EQ(shell, ReconstructOptions{});
  ReconstructOptions sheet = ReconstructOptions::open_sheet();
  EXPECT_TRUE(sheet.input.quadric_normals);
  EXPECT_FALSE(sheet.post.close_false_borders);
  sheet.input.quadric_normals = false;
  sheet.post.close_false_borders = true;
  EXPECT_EQ(sheet, ReconstructOptions{});
  EXPECT_NE(ReconstructOptions::thin_shell(), ReconstructOptions::open_sheet());

  const std::vector<std::string> names = ReconstructOptions::preset_names();
  ASSERT_EQ(names.size(), 3u);
  EXPECT_EQ(ReconstructOptions::preset("scan"), ReconstructOptions::scan());
  EXPECT_EQ(ReconstructOptions::preset("thin_shell"), ReconstructOptions::thin_shell());
  EXPECT_EQ(ReconstructOptions::preset("open_sheet"), ReconstructOptions::open_sheet());
  try {
    (void)ReconstructOptions::preset("thin-shell");
    ADD_FAILURE() << "an unknown preset was accepted";
  } catch (const edgefront::InvalidInput& e) {
    for (const std::string& n : names) EXPECT_NE(std::string(e.what()).find(n), std::string::npos) << e.what();
  }

  const ReconstructOptions o{.target_vertices = 2000, .post = {.fit_rounds = 5}};
  EXPECT_EQ(o.target_vertices, 2000u);
  EXPECT_EQ(o.post.fit_rounds, 5);
  EXPECT_TRUE(o.post.fit_surface);  // the group's other fields keep their defaults
}

TEST(GcsReconstructor, RejectsBadInputWithClearErrors) {
  using edgefront::InvalidInput;
  PointCloud three;
  three.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  EXPECT_THROW(gcs::Reconstructor(three, small(4)), InvalidInput);
  PointCloud nan = cloud_of("icosphere", 100);
  nan.points[7][1] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(gcs::Reconstructor(nan, small(50)), InvalidInput);
  PointCloud inf = cloud_of("icosphere", 100);
  inf.points[3][0] = std::numeric_limits<double>::infinity();
  EXPECT_THROW(gcs::Reconstructor(inf, small(50)), InvalidInput);
  PointCloud same;
  same.points.assign(100, Vec3(1, 2, 3));
  try {
    gcs::Reconstructor r(same, small(50));
    ADD_FAILURE() << "identical points accepted";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("coincide"), std::string::npos) << e.what();
  }
  PointCloud line;
  for (int i = 0; i < 100; ++i) line.points.push_back(Vec3(i, 2.0 * i, -i));
  try {
    gcs::Reconstructor r(line, small(50));
    ADD_FAILURE() << "collinear points accepted";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("line"), std::string::npos) << e.what();
  }
  const PointCloud ok = cloud_of("icosphere", 100);
  EXPECT_THROW(gcs::Reconstructor(ok, small(3)), InvalidInput);
  EXPECT_THROW(gcs::Reconstructor(ok, small(401)), InvalidInput);
  gcs::ReconstructOptions bad = small(50);
  bad.growth.winner_rate = 0;
  EXPECT_THROW(gcs::Reconstructor(ok, bad), InvalidInput);
  bad = small(50);
  bad.growth.steps_per_split = 0;
  EXPECT_THROW(gcs::Reconstructor(ok, bad), InvalidInput);
  bad = small(50);
  bad.topology.film_samples = 65;  // more nearest samples per face than the film test allows
  EXPECT_THROW(gcs::Reconstructor(ok, bad), InvalidInput);
  bad.topology.film_samples = 64;
  EXPECT_NO_THROW(gcs::Reconstructor(ok, bad));
  bad = small(50);
  bad.topology.border_trim_rings = 9;  // more rings trimmed along a refused loop than allowed
  EXPECT_THROW(gcs::Reconstructor(ok, bad), InvalidInput);
  bad.topology.border_trim_rings = 8;
  EXPECT_NO_THROW(gcs::Reconstructor(ok, bad));
  PointCloud wrong_normals = ok;
  wrong_normals.normals.resize(3);
  EXPECT_THROW(gcs::Reconstructor(wrong_normals, small(50)), InvalidInput);
  gcs::Reconstructor r(ok, small(50));
  EXPECT_THROW(r.add_operation(nullptr), InvalidInput);
}

// Repeated points are dropped: a cloud written three times gives the mesh of the cloud written
// once, byte for byte, with and without normals. (Before, a 1000-point plane without normals, each
// point written 3 times, came out at 900 vertices in 12 pieces with 28 holes.)
TEST(GcsReconstructor, RepeatedPointsAreDroppedAndChangeNothing) {
  for (const bool with_normals : {true, false}) {
    PointCloud once = cloud_of("icosphere", 1500);
    if (!with_normals) once.normals.clear();
    PointCloud thrice = once;
    for (int k = 0; k < 2; ++k) {
      thrice.points.insert(thrice.points.end(), once.points.begin(), once.points.end());
      thrice.normals.insert(thrice.normals.end(), once.normals.begin(), once.normals.end());
    }
    const gcs::ReconstructResult a = gcs::reconstruct(once, small(300));
    const gcs::ReconstructResult b = gcs::reconstruct(thrice, small(300));
    expect_manifold(b.mesh, "repeated points");
    EXPECT_EQ(edgefront::compute_stats(b.mesh).border_loops, 0u);
    EXPECT_EQ(flat_points(a.mesh), flat_points(b.mesh)) << "normals: " << with_normals;
    EXPECT_EQ(flat_faces(a.mesh), flat_faces(b.mesh)) << "normals: " << with_normals;
  }
}

TEST(GcsReconstructor, FourPointsGiveAValidMesh) {
  PointCloud c;
  c.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  const gcs::ReconstructResult res = gcs::reconstruct(c, small(4));
  expect_manifold(res.mesh, "four points");
  EXPECT_GE(res.mesh.n_vertices(), 4u);
  // One vertex per point at most: the loop cannot hold more (measured: a 3000-point plane asked
  // for 5000 vertices ran into the step limit after 10M steps with 15 holes).
  EXPECT_THROW(gcs::reconstruct(c, small(5)), edgefront::InvalidInput);
  // Repeated points do not count.
  PointCloud twice = c;
  twice.points.insert(twice.points.end(), c.points.begin(), c.points.end());
  try {
    gcs::reconstruct(twice, small(5));
    ADD_FAILURE() << "5 vertices from 4 distinct points were accepted";
  } catch (const edgefront::InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("distinct points (4; 4 repeat"), std::string::npos) << e.what();
  }
}

TEST(GcsReconstructor, CoplanarCloudGivesAValidSheetNearThePlane) {
  const PointCloud c = cloud_of("grid", 2000);
  for (const Vec3& p : c.points) ASSERT_EQ(p[2], 0.0);
  gcs::Reconstructor r(c, small(300));
  const gcs::ReconstructResult res = r.run([&](const gcs::Progress&) {
    r.validate();
    return true;
  });
  expect_manifold(res.mesh, "coplanar");
  // The padded start box collapses onto the plane: 90% of the vertices within 1% of the size.
  // Measured: half of the vertices within 0.011 of the plane, 90% within 0.067 (the slab's sides
  // fold in; the sheet is not a clean single layer, see the README).
  std::vector<double> z;
  for (auto v : res.mesh.vertices()) z.push_back(std::abs(res.mesh.point(v)[2]));
  std::sort(z.begin(), z.end());
  EXPECT_LT(z[z.size() / 2], 0.02);
  EXPECT_LT(z.back(), 0.5);
}

TEST(GcsReconstructor, LargeOffsetSmallExtent) {
  PointCloud c = cloud_of("icosphere", 2000);
  const Vec3 shift(1e6, -2e6, 1e6);
  for (Vec3& p : c.points) p = p * 0.01 + shift;
  const gcs::ReconstructResult res = gcs::reconstruct(c, small(300));
  expect_manifold(res.mesh, "offset");
  const edgefront::MeshStats s = edgefront::compute_stats(res.mesh);
  EXPECT_EQ(s.border_loops, 0u);
  for (auto v : res.mesh.vertices()) EXPECT_NEAR((res.mesh.point(v) - shift).norm(), 0.01, 0.001);
}

TEST(GcsReconstructor, TetrahedronStartAndStopReasons) {
  gcs::ReconstructOptions o = small(200);
  o.growth.start = gcs::StartShape::tetrahedron;
  const gcs::ReconstructResult res = gcs::reconstruct(cloud_of("icosphere", 2000), o);
  EXPECT_EQ(res.mesh.n_vertices(), 200u);
  EXPECT_EQ(edgefront::compute_stats(res.mesh).euler_characteristic, 2);
  EXPECT_EQ(gcs::to_string(res.stop_reason), "target reached");
  o.growth.max_steps_per_vertex = 1;  // 200 basic steps: two splits at most
  const gcs::ReconstructResult cut = gcs::reconstruct(cloud_of("icosphere", 2000), o);
  EXPECT_EQ(cut.stop_reason, gcs::StopReason::step_limit);
  expect_manifold(cut.mesh, "step limit");
}

}  // namespace
