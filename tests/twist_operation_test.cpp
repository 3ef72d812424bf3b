// Tests of gcs/twist_operation.h: the twist repair as a GCS hook, called directly with a change
// set (no GCS randomness).

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "edgefront/mesh_stats.h"
#include "gcs/twist_operation.h"
#include "twist/twisted_shapes.h"

namespace {

using edgefront::FaceHandle;

gcs::ChangeSet all_faces(const edgefront::Mesh& mesh) {
  gcs::ChangeSet c;
  for (FaceHandle f : mesh.faces()) c.faces.push_back(f);
  for (auto v : mesh.vertices()) c.vertices.push_back(v);
  return c;
}

TEST(TwistOperation, RepairsFromTheChangeSetWithoutGarbageCollection) {
  twist::TwistedShape s = twist::flipped_disk_plate();
  const edgefront::PointCloud no_points;
  gcs::OperationContext ctx{no_points};
  ctx.live_vertices = s.mesh.n_vertices();
  gcs::TwistOperation op;
  EXPECT_EQ(op.name(), "twist-repair");
  const size_t faces = s.mesh.n_faces();
  const gcs::OperationResult r = op.apply(s.mesh, all_faces(s.mesh), ctx);
  EXPECT_TRUE(r.mesh_changed);
  EXPECT_FALSE(r.summary.empty());
  EXPECT_EQ(op.stats().repairs, 1u);
  EXPECT_GT(s.mesh.n_faces(), faces) << "flipped faces were re-added; deleted ones stay until the loop collects them";
  s.mesh.garbage_collection();
  EXPECT_DOUBLE_EQ(twist::truth_consistency(s.mesh, s), 1.0);
  EXPECT_EQ(edgefront::compute_stats(s.mesh).nonmanifold_vertices, 0u);
}

TEST(TwistOperation, WaitsForEnoughVerticesAndUsesPointNormals) {
  twist::TwistedShape s = twist::flipped_disk_plate();
  const edgefront::PointCloud cloud = twist::truth_points(s);
  gcs::OperationContext ctx{cloud};
  ctx.live_vertices = 10;  // below min_vertices: nothing happens
  gcs::TwistOperation op;
  EXPECT_FALSE(op.apply(s.mesh, all_faces(s.mesh), ctx).mesh_changed);
  EXPECT_EQ(op.stats().repairs, 0u);
  ctx.final_call = true;  // the final call always repairs
  EXPECT_TRUE(op.apply(s.mesh, gcs::ChangeSet{}, ctx).mesh_changed);
  s.mesh.garbage_collection();
  EXPECT_DOUBLE_EQ(twist::truth_consistency(s.mesh, s), 1.0);
}

}  // namespace
