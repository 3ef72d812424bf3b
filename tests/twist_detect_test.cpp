// Tests of twist/detect.h: the detector finds exactly one region on the deterministic twisted
// meshes, none on correct ones, and rejects bad input clearly.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "edgefront/error.h"
#include "edgefront/shapes.h"
#include "twist/detect.h"
#include "twist/twisted_shapes.h"

namespace {

using edgefront::FaceHandle;
using edgefront::Mesh;
using edgefront::Vec3;

// Share of the faces built twisted (truth disagrees) that lie in the region.
double covered_twisted(const twist::TwistedShape& s, const twist::TwistRegion& r, size_t* twisted_total) {
  size_t twisted = 0, covered = 0;
  std::vector<char> in(s.mesh.n_faces(), 0);
  for (FaceHandle f : r.faces) in[static_cast<size_t>(f.idx())] = 1;
  for (FaceHandle f : s.mesh.faces()) {
    const auto t = s.truth(s.mesh.calc_face_centroid(f));
    if (!t || OpenMesh::dot(s.mesh.calc_face_normal(f), *t) > 0) continue;
    ++twisted;
    covered += in[static_cast<size_t>(f.idx())];
  }
  if (twisted_total) *twisted_total = twisted;
  return twisted ? static_cast<double>(covered) / static_cast<double>(twisted) : 0.0;
}

TEST(TwistDetect, TwistedTubeGivesExactlyOneRegionCoveringTheInvertedHalf) {
  const twist::TwistedShape s = twist::twisted_tube();
  const auto regions = twist::detect(s.mesh);
  ASSERT_EQ(regions.size(), 1u);
  size_t twisted = 0;
  EXPECT_EQ(covered_twisted(s, regions[0], &twisted), 1.0);
  EXPECT_GT(twisted, 0u);
  EXPECT_GT(regions[0].flagged_faces, 0u);
  EXPECT_FALSE(regions[0].border.empty());
  for (size_t i = 0; i < regions[0].border.size(); ++i) EXPECT_FALSE(regions[0].border_on_mesh_border[i]);
}

TEST(TwistDetect, FlippedDiskGivesExactlyOneRegionCoveringTheDisk) {
  const twist::TwistedShape s = twist::flipped_disk_plate();
  const auto regions = twist::detect(s.mesh);
  ASSERT_EQ(regions.size(), 1u);
  size_t twisted = 0;
  EXPECT_EQ(covered_twisted(s, regions[0], &twisted), 1.0);
  EXPECT_GT(twisted, 0u);
  EXPECT_LT(regions[0].faces.size(), s.mesh.n_faces() / 2);
}

}  // namespace
