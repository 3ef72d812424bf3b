// Tests of the reconstructor's query subsample (ReconstructOptions::max_query_points): a cloud
// with normals larger than the limit is queried through a spatially even subsample in the
// topology passes and the projection; the results keep the shape's topology, are deterministic,
// and clouds within the limit (or without normals) give the same bytes as without a limit.
// Small limits (a few thousand points) stand in for the automatic one (>= 100,000).

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "edgefront/error.h"
#include "edgefront/mesh_stats.h"
#include "edgefront/shapes.h"
#include "gcs/reconstructor.h"

namespace {

using edgefront::Mesh;
using edgefront::PointCloud;

PointCloud cloud_of(const std::string& shape, size_t points) {
  edgefront::shapes::SampleOptions o;
  o.points = points;
  return edgefront::shapes::sample(shape, o);
}

gcs::ReconstructOptions options(size_t target, size_t max_query_points) {
  gcs::ReconstructOptions o;
  o.target_vertices = target;
  o.max_query_points = max_query_points;
  return o;
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
  EXPECT_NE(flat_points(whole.mesh), flat_points(sub.mesh));
}

INSTANTIATE_TEST_SUITE_P(Shapes, QuerySubsampleTopology, ::testing::Values("hemisphere", "torus"));

TEST(QuerySubsample, DeterministicForASeed) {
  const PointCloud cloud = cloud_of("torus", 8000);
  const gcs::ReconstructResult a = gcs::reconstruct(cloud, options(300, 1500));
  const gcs::ReconstructResult b = gcs::reconstruct(cloud, options(300, 1500));
  EXPECT_EQ(flat_points(a.mesh), flat_points(b.mesh));
  EXPECT_EQ(flat_faces(a.mesh), flat_faces(b.mesh));
}

TEST(QuerySubsample, CloudWithinTheLimitOrWithoutNormalsIsUsedWhole) {
  const PointCloud cloud = cloud_of("torus", 2500);
  const gcs::ReconstructResult automatic = gcs::reconstruct(cloud, options(200, 0));
  const gcs::ReconstructResult at_limit = gcs::reconstruct(cloud, options(200, 2500));
  EXPECT_EQ(flat_points(automatic.mesh), flat_points(at_limit.mesh));
  EXPECT_EQ(flat_faces(automatic.mesh), flat_faces(at_limit.mesh));

  PointCloud bare = cloud;
  bare.normals.clear();
  const gcs::ReconstructResult bare_automatic = gcs::reconstruct(bare, options(200, 0));
  const gcs::ReconstructResult bare_limited = gcs::reconstruct(bare, options(200, 1000));
  EXPECT_EQ(flat_points(bare_automatic.mesh), flat_points(bare_limited.mesh));
  EXPECT_EQ(flat_faces(bare_automatic.mesh), flat_faces(bare_limited.mesh));
}

TEST(QuerySubsample, LimitBelowTheTargetIsRejected) {
  const PointCloud cloud = cloud_of("torus", 3000);
  EXPECT_THROW(gcs::Reconstructor(cloud, options(500, 499)), edgefront::InvalidInput);
  EXPECT_NO_THROW(gcs::Reconstructor(cloud, options(500, 500)));
}

}  // namespace
