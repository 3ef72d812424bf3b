// twist/arrays.h: detection, one-shot repair and global orientation on plain arrays.

#include "twist/arrays.h"

#include <gtest/gtest.h>

#include "edgefront/error.h"
#include "shapes/shapes.h"
#include "shapes/twisted_shapes.h"

namespace {

using namespace edgefront;

TEST(TwistArrays, DetectLabelsTheTwistedRowsAndRepairFixesThem) {
  const twist::TwistedShape shape = twist::flipped_disk_plate();
  const MeshArrays a = mesh_to_arrays(shape.mesh);
  const PointCloud truth = twist::truth_points(shape);
  std::vector<double> P, N;
  for (size_t i = 0; i < truth.size(); ++i) {
    P.insert(P.end(), {truth.points[i][0], truth.points[i][1], truth.points[i][2]});
    N.insert(N.end(), {truth.normals[i][0], truth.normals[i][1], truth.normals[i][2]});
  }
  const twist::ReferenceNormals ref = twist::reference_from_arrays(P, N);
  twist::DetectOptions d;
  d.reference = &ref;
  const twist::ArrayDetection found = twist::detect_arrays(a.vertices, a.faces, d);
  ASSERT_EQ(found.face_region.size(), a.n_faces());
  ASSERT_FALSE(found.region_faces.empty());
  const std::vector<twist::TwistRegion> regions = twist::detect(shape.mesh, d);
  ASSERT_EQ(regions.size(), found.region_faces.size());
  for (FaceHandle f : regions[0].faces) EXPECT_EQ(found.face_region[static_cast<size_t>(f.idx())], 0);
  EXPECT_EQ(found.region_faces[0], regions[0].faces.size());

  twist::RepairOptions o;
  o.detect.reference = &ref;
  const twist::ArrayRepair r = twist::repair_arrays(a.vertices, a.faces, o);
  std::vector<double> V = a.vertices;
  std::vector<int> F = a.faces;
  twist::apply(r.record, V, F);
  twist::compact_faces(F);
  const ArrayMesh repaired = mesh_from_arrays(V, F);
  EXPECT_DOUBLE_EQ(twist::truth_consistency(repaired.mesh, shape), 1.0);
  EXPECT_LT(twist::truth_consistency(shape.mesh, shape), 0.99);  // 0.979 before
}

TEST(TwistArrays, OrientFlipsAnInsideOutSphere) {
  MeshArrays a = mesh_to_arrays(shapes::icosphere(2));
  for (size_t r = 0; r < a.n_faces(); ++r) std::swap(a.faces[3 * r + 1], a.faces[3 * r + 2]);
  const twist::ArrayRepair r = twist::orient_arrays(a.vertices, a.faces);
  EXPECT_EQ(r.report.components_flipped, 1u);
  EXPECT_EQ(r.record.faces_flipped.size(), a.n_faces());
  EXPECT_TRUE(r.record.corners_replaced.empty());
  EXPECT_TRUE(r.record.faces_added.empty());
  std::vector<double> V = a.vertices;
  std::vector<int> F = a.faces;
  twist::apply(r.record, V, F);
  EXPECT_EQ(F, mesh_to_arrays(shapes::icosphere(2)).faces);
  // Already outward: nothing to do.
  const MeshArrays b = mesh_to_arrays(shapes::icosphere(2));
  EXPECT_TRUE(twist::orient_arrays(b.vertices, b.faces).record.empty());
}

TEST(TwistArrays, BadInputIsRefused) {
  const MeshArrays a = mesh_to_arrays(shapes::icosphere(1));
  EXPECT_THROW(twist::repair_arrays(a.vertices, std::vector<int>{0, 1}), InvalidInput);
  EXPECT_THROW(twist::detect_arrays(std::vector<double>{0, 0, std::nan("")}, std::vector<int>{0, 0, 0}), InvalidInput);
  EXPECT_THROW(twist::reference_from_arrays(std::vector<double>{0, 0, 0, 1, 1, 1}, std::vector<double>{0, 0, 1}), InvalidInput);
  EXPECT_THROW(twist::reference_from_arrays(std::vector<double>{0, 0, 0}, std::vector<double>{0, 0, 0}), InvalidInput);
  twist::RepairOptions o;
  o.max_repairs = 0;
  EXPECT_THROW(twist::repair_arrays(a.vertices, a.faces, o), InvalidInput);
}

}  // namespace
