// gcs/arrays.h: reconstruction from plain arrays gives the bytes of `reconstruct`.

#include "gcs/arrays.h"

#include <gtest/gtest.h>

#include "edgefront/error.h"
#include "shapes/shapes.h"

namespace {

using namespace edgefront;

TEST(GcsArrays, SameMeshAsTheReconstructor) {
  shapes::SampleOptions so;
  so.points = 1500;
  const PointCloud cloud = shapes::sample("icosphere", so);
  std::vector<double> P, N;
  for (size_t i = 0; i < cloud.size(); ++i) {
    P.insert(P.end(), {cloud.points[i][0], cloud.points[i][1], cloud.points[i][2]});
    N.insert(N.end(), {cloud.normals[i][0], cloud.normals[i][1], cloud.normals[i][2]});
  }
  gcs::ReconstructOptions o;
  o.target_vertices = 150;
  const gcs::ArrayReconstruction a = gcs::reconstruct_arrays(P, N, o);
  const MeshArrays ref = mesh_to_arrays(gcs::reconstruct(cloud, o).mesh);
  EXPECT_EQ(a.mesh.vertices, ref.vertices);
  EXPECT_EQ(a.mesh.faces, ref.faces);
  EXPECT_GE(a.mesh.n_vertices(), 140u);
  EXPECT_EQ(a.stop_reason, gcs::StopReason::target_reached);
}

TEST(GcsArrays, BadArraysAreRefusedNamingTheRow) {
  const std::vector<double> P = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1};
  try {
    gcs::reconstruct_arrays(P, std::vector<double>{0, 0, 1, 0, 0, 1, 0, std::nan(""), 1, 0, 0, 1, 0, 0, 1});
    FAIL() << "a NaN normal was accepted";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("row 2"), std::string::npos) << e.what();
  }
  EXPECT_THROW(gcs::reconstruct_arrays(P, std::vector<double>{0, 0, 1}), InvalidInput);
  EXPECT_THROW(gcs::reconstruct_arrays(std::vector<double>{0, 0}), InvalidInput);
}

}  // namespace
