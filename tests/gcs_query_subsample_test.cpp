// Tests of the reconstructor's query subsample (InputOptions::max_query_points): a cloud
// with normals larger than the limit is queried through a spatially even subsample in the
// topology passes and the projection; the results keep the shape's topology, are deterministic,
// and clouds within the limit (or without normals) give the same bytes as without a limit.
// Small limits (a few thousand points) stand in for the automatic one (>= 100,000).

#include <gtest/gtest.h>

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

PointCloud cloud_of(const std::string& shape, size_t points) { return edgefront::shapes::sample(shape, {.points = points, .shape = {}}); }

gcs::ReconstructOptions options(size_t target, size_t max_query_points) {
  gcs::ReconstructOptions o;
  o.target_vertices = target;
  o.input.max_query_points = max_query_points;
  return o;
}

// The same positions and faces in the same order (what byte-identical output files need).
::testing::AssertionResult same_mesh(const Mesh& a, const Mesh& b) {
  if (a.n_vertices() != b.n_vertices() || a.n_faces() != b.n_faces())
    return ::testing::AssertionFailure() << a.n_vertices() << "/" << a.n_faces() << " vs " << b.n_vertices() << "/"
                                         << b.n_faces() << " vertices/faces";
  for (auto v : a.vertices())
    if (a.point(v) != b.point(v)) return ::testing::AssertionFailure() << "vertex " << v.idx() << " moved";
  for (auto f : a.faces()) {
    auto ia = a.cfv_iter(f), ib = b.cfv_iter(f);
    for (int k = 0; k < 3; ++k, ++ia, ++ib)
      if (ia->idx() != ib->idx()) return ::testing::AssertionFailure() << "face " << f.idx() << " differs";
  }
  return ::testing::AssertionSuccess();
}

struct Topology {
  size_t components, loops, nonmanifold;
  double genus;
};
Topology topology_of(const Mesh& mesh) {
  const edgefront::MeshStats s = edgefront::compute_stats(mesh);
  return {s.components, s.border_loops, s.nonmanifold_vertices, s.per_component.empty() ? -1.0 : s.per_component[0].genus};
}

// The GcsTopology cases (20K points, 500 vertices): an open surface (border creation through the
// subsample's support queries) and a handle (loop merging), each with the whole cloud and with a
// 2,500-point subsample (5 per target vertex, as the automatic limit).
class QuerySubsampleTopology : public ::testing::TestWithParam<const char*> {};

TEST_P(QuerySubsampleTopology, SameTopologyAsTheWholeCloud) {
  const PointCloud cloud = cloud_of(GetParam(), 20000);
  const gcs::ReconstructResult whole = gcs::reconstruct(cloud, options(500, 0));
  const gcs::ReconstructResult sub = gcs::reconstruct(cloud, options(500, 2500));
  const Topology a = topology_of(whole.mesh), b = topology_of(sub.mesh);
  EXPECT_EQ(b.components, 1u);
  EXPECT_EQ(b.nonmanifold, 0u);
  EXPECT_EQ(b.components, a.components);
  EXPECT_EQ(b.loops, a.loops);
  EXPECT_EQ(b.genus, a.genus);
  // The subsample did change what the queries saw (otherwise this test would test nothing).
  EXPECT_FALSE(same_mesh(whole.mesh, sub.mesh));
}

INSTANTIATE_TEST_SUITE_P(Shapes, QuerySubsampleTopology, ::testing::Values("hemisphere", "torus"));

TEST(QuerySubsample, DeterministicForASeed) {
  const PointCloud cloud = cloud_of("torus", 8000);
  EXPECT_TRUE(same_mesh(gcs::reconstruct(cloud, options(300, 1500)).mesh, gcs::reconstruct(cloud, options(300, 1500)).mesh));
}

TEST(QuerySubsample, CloudWithinTheLimitOrWithoutNormalsIsUsedWhole) {
  const PointCloud cloud = cloud_of("torus", 2500);
  EXPECT_TRUE(same_mesh(gcs::reconstruct(cloud, options(200, 0)).mesh, gcs::reconstruct(cloud, options(200, 2500)).mesh));

  PointCloud bare = cloud;
  bare.normals.clear();
  EXPECT_TRUE(same_mesh(gcs::reconstruct(bare, options(200, 0)).mesh, gcs::reconstruct(bare, options(200, 1000)).mesh));
}

// OperationContext::query_points: the subsample (points with their normals, a part of the cloud in
// the operation's coordinates) when the loop queries one, nullptr when it uses the whole cloud.
class QueryPointsRecorder : public gcs::Operation {
 public:
  std::string name() const override { return "query-points-recorder"; }
  gcs::OperationResult apply(Mesh&, const gcs::ChangeSet&, const gcs::OperationContext& context) override {
    ++calls;
    if (!context.query_points) return {};
    ++with_subsample;
    const PointCloud& q = *context.query_points;
    sizes.push_back(q.size());
    normals_ok = normals_ok && q.has_normals();
    // Every subsample point is a point of the cloud (checked for a few).
    for (size_t k = 0; k < q.size(); k += 97) {
      bool found = false;
      for (size_t i = 0; i < context.points.size() && !found; ++i)
        found = context.points.points[i] == q.points[k];
      members_ok = members_ok && found;
    }
    return {};
  }
  size_t calls = 0, with_subsample = 0;
  std::vector<size_t> sizes;
  bool normals_ok = true, members_ok = true;
};

TEST(QuerySubsample, OperationsGetTheSubsampleInTheirContext) {
  const PointCloud cloud = cloud_of("torus", 6000);
  for (const size_t limit : {size_t(0), size_t(1500)}) {
    gcs::ReconstructOptions o = options(300, limit);
    o.growth.batch_splits = 50;
    gcs::Reconstructor r(cloud, o);
    auto rec = std::make_shared<QueryPointsRecorder>();
    r.add_operation(rec);
    r.run();
    ASSERT_GT(rec->calls, 2u) << limit;
    if (limit == 0) {  // 6000 points are within the automatic limit
      EXPECT_EQ(rec->with_subsample, 0u);
      continue;
    }
    EXPECT_EQ(rec->with_subsample, rec->calls);
    ASSERT_FALSE(rec->sizes.empty());
    EXPECT_LE(rec->sizes.front(), limit);
    EXPECT_GE(rec->sizes.front(), limit / 2);
    EXPECT_TRUE(rec->normals_ok);
    EXPECT_TRUE(rec->members_ok);
  }
}

TEST(QuerySubsample, LimitBelowTheTargetIsRejected) {
  const PointCloud cloud = cloud_of("torus", 3000);
  EXPECT_THROW(gcs::Reconstructor(cloud, options(500, 499)), edgefront::InvalidInput);
  EXPECT_NO_THROW(gcs::Reconstructor(cloud, options(500, 500)));
}

}  // namespace
