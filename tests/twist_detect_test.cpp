// Tests of twist/detect.h: exactly one region on the deterministic twisted meshes, none on
// correct ones, incremental detection stays local, and bad input throws clearly.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "edgefront/error.h"
#include "shapes/shapes.h"
#include "twist/detect.h"
#include "shapes/twisted_shapes.h"

namespace {

using edgefront::FaceHandle;
using edgefront::InvalidInput;
using edgefront::Mesh;
using edgefront::Vec3;

// Faces built twisted (their truth disagrees with their normal), and how many lie in `r`.
std::pair<size_t, size_t> twisted_covered(const twist::TwistedShape& s, const twist::TwistRegion& r) {
  std::vector<char> in(s.mesh.n_faces(), 0);
  for (FaceHandle f : r.faces) in[static_cast<size_t>(f.idx())] = 1;
  size_t twisted = 0, covered = 0;
  for (FaceHandle f : s.mesh.faces()) {
    const auto t = s.truth(s.mesh.calc_face_centroid(f));
    if (!t || OpenMesh::dot(s.mesh.calc_face_normal(f), *t) > 0) continue;
    ++twisted;
    covered += static_cast<size_t>(in[static_cast<size_t>(f.idx())]);
  }
  return {twisted, covered};
}

// Faces of `r` whose truth agrees with them (right faces the region would wrongly flip).
size_t right_faces_in(const twist::TwistedShape& s, const twist::TwistRegion& r) {
  size_t n = 0;
  for (FaceHandle f : r.faces) {
    const auto t = s.truth(s.mesh.calc_face_centroid(f));
    if (t && OpenMesh::dot(s.mesh.calc_face_normal(f), *t) > 0) ++n;
  }
  return n;
}

twist::TwistedTubeOptions small_tube() {
  twist::TwistedTubeOptions o;
  o.along = 24;
  o.around = 16;
  o.length = 1.6;
  return o;
}

TEST(TwistDetect, TwistedTubeGivesExactlyOneRegionHoldingTheInvertedHalf) {
  const twist::TwistedShape s = twist::twisted_tube(small_tube());
  const auto regions = twist::detect(s.mesh);
  ASSERT_EQ(regions.size(), 1u);
  const auto [twisted, covered] = twisted_covered(s, regions[0]);
  EXPECT_GT(twisted, s.mesh.n_faces() / 3);
  EXPECT_EQ(covered, twisted) << "every inverted face is in the region";
  EXPECT_EQ(right_faces_in(s, regions[0]), 0u) << "no right face is in the region";
  EXPECT_GT(regions[0].flagged_faces, 0u);
  ASSERT_FALSE(regions[0].border.empty());
  for (size_t i = 0; i < regions[0].border.size(); ++i) EXPECT_FALSE(regions[0].border_on_mesh_border[i]);
}

TEST(TwistDetect, FlippedDiskGivesExactlyOneRegionHoldingTheDisk) {
  const twist::TwistedShape s = twist::flipped_disk_plate();
  const auto regions = twist::detect(s.mesh);
  ASSERT_EQ(regions.size(), 1u);
  const auto [twisted, covered] = twisted_covered(s, regions[0]);
  EXPECT_GT(twisted, 0u);
  EXPECT_EQ(covered, twisted);
  EXPECT_EQ(right_faces_in(s, regions[0]), 0u);
  EXPECT_LT(regions[0].faces.size(), s.mesh.n_faces() / 2);
  bool facing = false;
  for (const auto& e : regions[0].evidence) facing = facing || e.kind == twist::EvidenceKind::FacingLayer;
  EXPECT_TRUE(facing) << "the disk faces the bottom layer";
}

TEST(TwistDetect, BorderLoopsAreClosedWithTheRegionOnTheirRight) {
  const twist::TwistedShape s = twist::flipped_disk_plate();
  const auto regions = twist::detect(s.mesh);
  ASSERT_EQ(regions.size(), 1u);
  std::vector<char> in(s.mesh.n_faces(), 0);
  for (FaceHandle f : regions[0].faces) in[static_cast<size_t>(f.idx())] = 1;
  for (const auto& loop : regions[0].border) {
    ASSERT_GE(loop.size(), 3u);
    for (size_t i = 0; i < loop.size(); ++i) {
      const auto h = loop[i];
      const auto next = loop[(i + 1) % loop.size()];
      EXPECT_EQ(s.mesh.to_vertex_handle(h), s.mesh.from_vertex_handle(next));
      const FaceHandle behind = s.mesh.opposite_face_handle(h);
      ASSERT_TRUE(behind.is_valid());
      EXPECT_TRUE(in[static_cast<size_t>(behind.idx())]);
      const FaceHandle ahead = s.mesh.face_handle(h);
      EXPECT_TRUE(!ahead.is_valid() || !in[static_cast<size_t>(ahead.idx())]);
    }
  }
}

TEST(TwistDetect, CorrectMeshesGiveNoRegion) {
  struct Case {
    std::string name;
    double thickness;
  };
  for (const Case& c : {Case{"icosphere", 0.1}, Case{"torus", 0.1}, Case{"vault-shell", 0.2}, Case{"vault-shell", 0.05},
                        Case{"vault-shell", 0.02}, Case{"thin-plate", 0.05}, Case{"vault-sheet", 0.1},
                        Case{"groin-vault", 0.1}, Case{"nested-spheres", 0.1}}) {
    edgefront::shapes::MeshOptions mo;
    mo.resolution = 24;
    mo.shape.thickness = c.thickness;
    const Mesh m = edgefront::shapes::make(c.name, mo);
    const auto result = twist::detect_regions(m);
    EXPECT_EQ(result.regions.size(), 0u) << c.name << " t=" << c.thickness;
    EXPECT_EQ(result.stats.flagged_faces, 0u) << c.name << " t=" << c.thickness;
    EXPECT_EQ(result.stats.faces_tested, m.n_faces()) << c.name;
  }
}

TEST(TwistDetect, AHairpinGapLooksLikeAnInvertedWallWithoutReference) {
  // The documented limit: two right surface parts facing each other across a gap narrower than
  // the radius cannot be told from an inverted thin wall by geometry alone.
  edgefront::shapes::MeshOptions mo;
  mo.resolution = 12;
  const Mesh m = edgefront::shapes::make("hairpin", mo);
  EXPECT_FALSE(twist::detect(m).empty());
  twist::DetectOptions o;
  o.radius = 0.02;  // below the gap (0.05): no layer is found
  EXPECT_TRUE(twist::detect(m, o).empty());
}

TEST(TwistDetect, WithReferenceNormalsAHairpinGapIsNoTwist) {
  // Two right surface parts facing each other across a gap narrower than the radius (as a
  // kitten's tail over its back in a coarse reconstruction): the reference confirms both sides,
  // so the facing layers mark no twist.
  edgefront::shapes::MeshOptions mo;
  mo.resolution = 12;
  const Mesh m = edgefront::shapes::make("hairpin", mo);
  ASSERT_FALSE(twist::detect(m).empty()) << "without reference the gap looks like an inverted wall";
  edgefront::shapes::SampleOptions so;
  so.points = 4000;
  const twist::ReferenceNormals ref(edgefront::shapes::sample_mesh(m, so));
  twist::DetectOptions o;
  o.reference = &ref;
  const auto result = twist::detect_regions(m, o);
  EXPECT_TRUE(result.regions.empty());
}

TEST(TwistDetect, FacesFlippedOverInACreaseAreNoTwist) {
  // A clean closed genus-1 surface as a reconstruction in progress leaves it: every vertex
  // jittered, and one vertex dragged across the opposite edge of one of its triangles, so that
  // the triangle and its neighbour there are turned over against their right surroundings (a
  // tangle the loop's smoothing undoes). The reference (samples of the untangled torus) judges
  // those faces wrong, yet they are no wrongly oriented patch: no region, with or without it.
  edgefront::shapes::MeshOptions mo;
  mo.resolution = 24;
  const Mesh clean = edgefront::shapes::make("torus", mo);
  Mesh m = clean;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-0.01, 0.01);
  for (auto v : m.vertices()) m.set_point(v, m.point(v) + Vec3(jitter(rng), jitter(rng), jitter(rng)));
  const FaceHandle f(100);
  auto fv = m.fv_range(f).begin();
  const auto a = *fv++, b = *fv++, c = *fv;
  const Vec3 mid = 0.5 * (m.point(b) + m.point(c));
  m.set_point(a, mid + 0.6 * (mid - m.point(a)));  // a crosses bc: f turns over
  edgefront::shapes::SampleOptions so;
  so.points = 6000;
  const twist::ReferenceNormals ref(edgefront::shapes::sample_mesh(clean, so));
  twist::DetectOptions o;
  o.reference = &ref;
  ASSERT_LT(twist::reference_vote(ref, o, m.calc_face_centroid(f), m.calc_face_normal(f)), 0)
      << "the turned face disagrees with the reference";
  const auto with_reference = twist::detect_regions(m, o);
  EXPECT_TRUE(with_reference.regions.empty()) << with_reference.regions.size() << " region(s)";
  EXPECT_GT(with_reference.stats.flagged_faces, 0u);
  EXPECT_TRUE(twist::detect(m).empty());
}

TEST(TwistDetect, IncrementalDetectionFromAFewChangedFacesFindsTheWholeRegionLocally) {
  const twist::TwistedShape s = twist::flipped_disk_plate();
  const auto full = twist::detect(s.mesh);
  ASSERT_EQ(full.size(), 1u);
  twist::DetectOptions o;
  o.incremental.restrict_to = std::vector<FaceHandle>{full[0].faces.front()};
  o.incremental.audit_faces = 8;
  const auto local = twist::detect_regions(s.mesh, o);
  ASSERT_EQ(local.regions.size(), 1u);
  const auto [twisted, covered] = twisted_covered(s, local.regions[0]);
  EXPECT_EQ(covered, twisted);
  EXPECT_EQ(right_faces_in(s, local.regions[0]), 0u);
  EXPECT_LT(local.stats.faces_tested, s.mesh.n_faces() / 2) << "the detector stays near the region";

  // On a right mesh: nothing found, and only the changed and audited faces are tested.
  edgefront::shapes::MeshOptions mo;
  mo.resolution = 24;
  mo.shape.thickness = 0.05;
  const Mesh plate = edgefront::shapes::make("thin-plate", mo);
  o.incremental.restrict_to = std::vector<FaceHandle>{FaceHandle(0), FaceHandle(1), FaceHandle(2)};
  const auto quiet = twist::detect_regions(plate, o);
  EXPECT_TRUE(quiet.regions.empty());
  EXPECT_LE(quiet.stats.faces_tested, 3u + o.incremental.audit_faces);
}

TEST(TwistDetect, ReferenceNormalsDecideTheSide) {
  const twist::TwistedShape s = twist::flipped_disk_plate();
  const edgefront::PointCloud cloud = twist::truth_points(s);
  const twist::ReferenceNormals ref(cloud);
  twist::DetectOptions o;
  o.reference = &ref;
  const auto regions = twist::detect(s.mesh, o);
  ASSERT_EQ(regions.size(), 1u);
  const auto [twisted, covered] = twisted_covered(s, regions[0]);
  EXPECT_EQ(covered, twisted);
  EXPECT_EQ(right_faces_in(s, regions[0]), 0u);
  EXPECT_LT(twist::face_orientation_agreement(s.mesh, ref), 0.95);
}

TEST(TwistDetect, OnAWallThinnerThanTheEdgesTheNearestNormalIsNoEvidence) {
  // A pillbox plate 0.004 thick (edges about 0.115: the two walls are closer than a twentieth of
  // an edge) with a disk turned over. Which wall's reference point is nearest a face there is
  // chance (a GCS mesh on such a wall has its two layers cross everywhere), so by default
  // (thin_wall = 0.35 mean edges) a rejection by the nearest normal is no evidence there: every
  // turned-over face is undecided; with the rule off each is rejected and the detector finds the
  // disk. On the default plate (0.1 thick, about one edge) the rule changes nothing.
  auto votes = [](const twist::TwistedShape& s, const twist::ReferenceNormals& ref, double thin_wall) {
    twist::DetectOptions o;
    o.vote.thin_wall = thin_wall;
    double mean_edge = 0;
    for (auto e : s.mesh.edges()) mean_edge += s.mesh.calc_edge_length(e);
    mean_edge /= static_cast<double>(s.mesh.n_edges());
    std::array<size_t, 3> count{0, 0, 0};  // rejected, undecided, confirmed
    for (FaceHandle f : s.mesh.faces()) {
      const Vec3 c = s.mesh.calc_face_centroid(f), n = s.mesh.calc_face_normal(f);
      const auto t = s.truth(c);
      if (!t || OpenMesh::dot(n, *t) > 0) continue;  // only the turned-over faces
      ++count[static_cast<size_t>(twist::reference_vote(ref, o, c, n, mean_edge) + 1)];
    }
    return count;
  };
  // Reference points spaced closer than the reach (a quarter edge: 15 points per face with a
  // truth, as a scan samples a surface), so that both walls are found within it.
  auto dense_truth = [](const twist::TwistedShape& s) {
    edgefront::PointCloud cloud;
    for (FaceHandle f : s.mesh.faces()) {
      const auto t = s.truth(s.mesh.calc_face_centroid(f));
      if (!t) continue;
      std::array<Vec3, 3> p;
      size_t i = 0;
      for (auto v : s.mesh.fv_range(f)) p[i++] = s.mesh.point(v);
      for (int a = 0; a <= 4; ++a) {
        for (int b = 0; a + b <= 4; ++b) {
          cloud.points.push_back((a * p[0] + b * p[1] + (4 - a - b) * p[2]) / 4.0);
          cloud.normals.push_back(*t);
        }
      }
    }
    return cloud;
  };
  twist::FlippedDiskOptions thin_options;
  thin_options.thickness = 0.004;
  thin_options.fold_height = 0.001;  // the fold band stays between the walls (as the disk lies in the top one)
  const twist::TwistedShape thin = twist::flipped_disk_plate(thin_options);
  const twist::ReferenceNormals thin_ref(dense_truth(thin));
  const auto thin_votes = votes(thin, thin_ref, 0.35);
  EXPECT_GT(thin_votes[1], 0u);
  EXPECT_EQ(thin_votes[0], 0u);
  EXPECT_EQ(thin_votes[2], 0u);
  const auto off = votes(thin, thin_ref, 0);
  EXPECT_EQ(off[0], thin_votes[1]);
  twist::DetectOptions o;
  o.reference = &thin_ref;
  o.vote.thin_wall = 0;
  const auto regions = twist::detect(thin.mesh, o);
  ASSERT_EQ(regions.size(), 1u);
  const auto [twisted, covered] = twisted_covered(thin, regions[0]);
  EXPECT_EQ(covered, twisted);
  const twist::TwistedShape thick = twist::flipped_disk_plate();
  const twist::ReferenceNormals thick_ref(dense_truth(thick));
  EXPECT_EQ(votes(thick, thick_ref, 0.35), votes(thick, thick_ref, 0));
  EXPECT_EQ(votes(thick, thick_ref, 0.35)[1], 0u);
  EXPECT_GT(votes(thick, thick_ref, 0.35)[0], 0u);
  const Vec3 c(0.6, 0.1, 0.001);
  EXPECT_NEAR(thin_ref.wall_thickness(c), 0.004, 1e-9);
  // Just under the top of the thick plate the 16 nearest points all lie on the top wall.
  EXPECT_EQ(thick_ref.wall_thickness(Vec3(0.6, 0.1, 0.045)), std::numeric_limits<double>::infinity());
  EXPECT_NEAR(thick_ref.wall_thickness(Vec3(0.6, 0.1, 0.045), 100000), 0.1, 1e-9);
  EXPECT_THROW(thin_ref.wall_thickness(c, 0), InvalidInput);
  o.vote.thin_wall = 5;
  EXPECT_THROW(twist::detect(thin.mesh, o), InvalidInput);
}

TEST(TwistDetect, ReversedSeamOfACutMobiusStripIsFound) {
  const Mesh m = edgefront::shapes::mobius_strip(48, 4);
  EXPECT_EQ(twist::reversed_seams(m).size(), 4u);
  const Mesh cyl = edgefront::shapes::open_cylinder(16, 4);
  EXPECT_TRUE(twist::reversed_seams(cyl).empty());
}

TEST(TwistDetect, BadInputThrowsNamingTheProblem) {
  Mesh empty;
  try {
    twist::detect(empty);
    FAIL() << "no exception";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("no faces"), std::string::npos) << e.what();
  }
  Mesh m = edgefront::shapes::icosphere(1);
  auto bad = [&](auto set, const std::string& word) {
    twist::DetectOptions o;
    set(o);
    try {
      twist::detect(m, o);
      ADD_FAILURE() << "no exception for " << word;
    } catch (const InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find(word), std::string::npos) << e.what();
    }
  };
  bad([](twist::DetectOptions& o) { o.radius = -1; }, "radius");
  bad([](twist::DetectOptions& o) { o.radius = std::numeric_limits<double>::quiet_NaN(); }, "radius");
  bad([](twist::DetectOptions& o) { o.experimental.surface_factor = 0.5; }, "experimental.surface_factor");
  bad([](twist::DetectOptions& o) { o.regions.grow_levels = 0; }, "regions.grow_levels");
  bad([](twist::DetectOptions& o) { o.experimental.fold_cos = 0.5; }, "experimental.fold_cos");
  bad([](twist::DetectOptions& o) { o.experimental.facing_cos = 0; }, "experimental.facing_cos");
  bad([](twist::DetectOptions& o) { o.vote.thin_wall = 5; }, "vote.thin_wall");
  bad(
      [](twist::DetectOptions& o) {
        o.incremental.restrict_to = std::vector<FaceHandle>{FaceHandle(100000)};
      },
      "incremental.restrict_to");
  m.set_point(edgefront::VertexHandle(3), Vec3(std::numeric_limits<double>::quiet_NaN(), 0, 0));
  EXPECT_THROW(twist::detect(m), InvalidInput);

  EXPECT_THROW(twist::ReferenceNormals(edgefront::PointCloud{}), InvalidInput);
  edgefront::PointCloud no_normals;
  no_normals.points = {Vec3(0, 0, 0)};
  EXPECT_THROW(twist::ReferenceNormals{no_normals}, InvalidInput);
  EXPECT_THROW(twist::twisted_tube(twist::TwistedTubeOptions{3, 16, 2.0, 0.5, 0.1, -1}), InvalidInput);
}

}  // namespace
