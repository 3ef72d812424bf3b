// Tests of gcs/evaluation.h and the gcs-eval tool: known answers on generated meshes and
// analytic samples (sphere discretisation error, self-comparison, a translated plane, orientation
// of correct, flipped and half-flipped surfaces, self-intersections, genus), bad input, and real
// runs of the built executable.

#include <gtest/gtest.h>

#include "app_test_util.h"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <limits>
#include <numbers>
#include <regex>
#include <string>
#include <vector>

#include "edgefront/error.h"
#include "edgefront/mesh.h"
#include "edgefront/mesh_io.h"
#include "edgefront/mesh_stats.h"
#include "edgefront/point_cloud_io.h"
#include "shapes/shapes.h"
#include "gcs/evaluation.h"

namespace {

namespace fs = std::filesystem;
using edgefront::InvalidInput;
using edgefront::Mesh;
using edgefront::PointCloud;
using edgefront::Vec3;
using edgefront::VertexHandle;
namespace shapes = edgefront::shapes;

gcs::EvaluationOptions fast(std::size_t samples = 20000) {
  gcs::EvaluationOptions o;
  o.samples = samples;
  return o;
}

/// `src` translated by `offset`, optionally with every face reversed; appended to `dst`.
void append(Mesh& dst, const Mesh& src, const Vec3& offset = Vec3(0, 0, 0), bool reversed = false) {
  std::vector<VertexHandle> map(src.n_vertices());
  for (const auto v : src.vertices())
    map[static_cast<std::size_t>(v.idx())] = dst.add_vertex(src.point(v) + offset);
  for (const auto f : src.faces()) {
    std::vector<VertexHandle> fv;
    for (const auto v : src.fv_range(f)) fv.push_back(map[static_cast<std::size_t>(v.idx())]);
    if (reversed) std::reverse(fv.begin(), fv.end());
    ASSERT_TRUE(dst.add_face(fv).is_valid());
  }
}

Mesh transformed(const Mesh& src, const Vec3& offset, bool reversed = false) {
  Mesh m;
  append(m, src, offset, reversed);
  return m;
}

PointCloud shifted(PointCloud c, const Vec3& offset) {
  for (Vec3& p : c.points) p += offset;
  return c;
}

PointCloud sphere_samples(std::size_t n, std::uint64_t seed = 7) {
  shapes::SampleOptions o;
  o.points = n;
  o.seed = seed;
  return shapes::sample("icosphere", o);
}

// ---------------------------------------------------------------------------------------------
// Distances: known answers

TEST(GcsEval, SphereMeshAgainstAnalyticSamplesMatchesTheDiscretisationError) {
  const Mesh mesh = shapes::icosphere(4);  // 5120 faces, vertices on the unit sphere
  const std::size_t n = 20000;
  const PointCloud gt = sphere_samples(n);
  const gcs::Evaluation e = gcs::evaluate(mesh, gcs::GroundTruth::from_points(gt), fast());

  // Ground truth -> mesh: a point on the unit sphere at angle r from the foot of a face whose
  // plane is at distance h from the centre lies about s - r²/2 above the face, s = 1 - h the
  // sagitta. The corners have r² = 2s, and over a (near-)equilateral triangle the mean of r² is a
  // quarter of the squared circumradius: the mean distance is s - s/4 = 0.75 s.
  double sag_area = 0, area = 0;
  for (const auto f : mesh.faces()) {
    auto it = mesh.cfv_iter(f);
    const Vec3 a = mesh.point(*it), b = mesh.point(*++it), c = mesh.point(*++it);
    const Vec3 n_f = ((b - a) % (c - a));
    const double area_f = 0.5 * n_f.norm();
    sag_area += area_f * (1.0 - (a | n_f.normalized()));
    area += area_f;
  }
  const double expected_gt_to_mesh = 0.75 * sag_area / area;
  EXPECT_NEAR(e.gt_to_result.mean, expected_gt_to_mesh, 0.05 * expected_gt_to_mesh);
  EXPECT_EQ(e.gt_to_result.count, n);

  // Mesh -> ground truth: the nearest of n uniform points on the sphere is, on average, at
  // 1 / (2 sqrt(density)) (planar Poisson process); the mesh's own deviation is far smaller.
  const double expected_mesh_to_gt = 0.5 / std::sqrt(static_cast<double>(n) / (4 * std::numbers::pi));
  EXPECT_NEAR(e.result_to_gt.mean, expected_mesh_to_gt, 0.1 * expected_mesh_to_gt);
  EXPECT_NEAR(e.chamfer_l1, 0.5 * (e.result_to_gt.mean + e.gt_to_result.mean), 1e-15);
  EXPECT_NEAR(e.gt_bbox_diagonal, 2 * std::sqrt(3.0), 0.02);
  EXPECT_LT(e.scale(e.chamfer_l1), 0.5);  // small: well under 0.5% of the diagonal

  // Order statistics are consistent.
  for (const gcs::OneSidedDistance* d : {&e.result_to_gt, &e.gt_to_result}) {
    EXPECT_LE(d->median, d->p95);
    EXPECT_LE(d->p95, d->max);
    EXPECT_LE(d->mean, d->rms);
  }
  EXPECT_DOUBLE_EQ(e.hausdorff, std::max(e.result_to_gt.max, e.gt_to_result.max));
  EXPECT_DOUBLE_EQ(e.hausdorff_p95, std::max(e.result_to_gt.p95, e.gt_to_result.p95));
  // Analytic normals against a fine mesh.
  ASSERT_TRUE(e.normal_consistency.has_value());
  EXPECT_GT(*e.normal_consistency, 0.99);
}

TEST(GcsEval, MeshAgainstItselfIsZeroDistanceAndPerfectScores) {
  const Mesh mesh = shapes::torus(48, 16);
  const gcs::Evaluation e = gcs::evaluate(mesh, gcs::GroundTruth::from_mesh(mesh), fast());
  EXPECT_TRUE(e.ground_truth_is_mesh);
  EXPECT_LT(e.chamfer_l1, 1e-12);
  EXPECT_LT(e.hausdorff, 1e-12);
  ASSERT_EQ(e.fscores.size(), 2u);
  for (const gcs::FScore& f : e.fscores) {
    EXPECT_DOUBLE_EQ(f.fscore, 1.0);
    EXPECT_DOUBLE_EQ(f.precision, 1.0);
    EXPECT_DOUBLE_EQ(f.recall, 1.0);
  }
  EXPECT_NEAR(e.fscores[0].threshold, 0.005 * e.gt_bbox_diagonal, 1e-15);
  ASSERT_TRUE(e.orientation.has_value());
  EXPECT_DOUBLE_EQ(e.orientation->raw, 1.0);
  EXPECT_NEAR(*e.normal_consistency, 1.0, 1e-12);
}

TEST(GcsEval, TranslatedPlaneHasChamferAndHausdorffEqualToTheOffset) {
  shapes::GridOptions g;
  g.cells = 8;
  const Mesh plane = shapes::grid(g);  // [-1,1]², z = 0: bbox diagonal 2 sqrt(2)
  const double offset = 0.02;          // 0.707% of the diagonal: between the two thresholds
  const Mesh moved = transformed(plane, Vec3(0, 0, offset));
  for (const bool mesh_gt : {true, false}) {
    SCOPED_TRACE(mesh_gt ? "mesh ground truth" : "point ground truth");
    PointCloud cloud = shapes::sample_mesh(plane, {.points = 5000, .seed = 3, .shape = {}});
    const gcs::GroundTruth gt =
        mesh_gt ? gcs::GroundTruth::from_mesh(plane) : gcs::GroundTruth::from_points(cloud);
    const gcs::Evaluation e = gcs::evaluate(moved, gt, fast());
    // Ground truth -> result is exactly the offset; for a point set, result -> ground truth is
    // the offset plus the in-plane gap to the nearest point, so only the mesh case is exact there.
    EXPECT_NEAR(e.gt_to_result.mean, offset, 1e-12);
    EXPECT_NEAR(e.gt_to_result.max, offset, 1e-12);
    if (mesh_gt) {
      EXPECT_NEAR(e.gt_bbox_diagonal, 2 * std::sqrt(2.0), 1e-12);
      EXPECT_NEAR(e.chamfer_l1, offset, 1e-12);
      EXPECT_NEAR(e.hausdorff, offset, 1e-12);
      EXPECT_NEAR(e.scale(e.chamfer_l1), 100 * offset / (2 * std::sqrt(2.0)), 1e-9);
      EXPECT_DOUBLE_EQ(e.fscores[0].fscore, 0.0);  // 0.5% = 0.0141 < offset
      EXPECT_DOUBLE_EQ(e.fscores[1].fscore, 1.0);  // 1% = 0.0283 > offset
    } else {
      EXPECT_GT(e.result_to_gt.mean, offset);
      EXPECT_DOUBLE_EQ(e.fscores[0].recall, 0.0);
      EXPECT_DOUBLE_EQ(e.fscores[1].recall, 1.0);
    }
  }
}

TEST(GcsEval, PointToSampleVariantAddsTheSamplingGap) {
  // A plane against itself, measured point-to-point between two independent sample sets: the
  // nearest of n uniform points at density n / area lies 1 / (2 sqrt(density)) away on average
  // (a little more near the border), instead of 0 measured exactly.
  const Mesh plane = shapes::grid({.cells = 10});  // area 4
  gcs::EvaluationOptions o = fast();
  o.exact_surface_distance = false;
  const gcs::Evaluation e = gcs::evaluate(plane, gcs::GroundTruth::from_mesh(plane), o);
  const double gap = 0.5 / std::sqrt(static_cast<double>(o.samples) / 4.0);
  EXPECT_FALSE(e.exact_surface_distance);
  EXPECT_NEAR(e.result_to_gt.mean, gap, 0.1 * gap);
  EXPECT_NEAR(e.gt_to_result.mean, gap, 0.1 * gap);
  EXPECT_NE(gcs::evaluation_to_json(e).find("\"distance_to_mesh\": \"nearest_sample\""), std::string::npos);
  EXPECT_LT(gcs::evaluate(plane, gcs::GroundTruth::from_mesh(plane), fast()).chamfer_l1, 1e-12);
}

// ---------------------------------------------------------------------------------------------
// Orientation consistency

TEST(GcsEval, OrientationOfACorrectAndOfAFlippedSphere) {
  const Mesh sphere = shapes::icosphere(3);
  const PointCloud gt = sphere_samples(10000);
  const gcs::OrientationConsistency good = gcs::orientation_consistency(sphere, gt, fast());
  EXPECT_DOUBLE_EQ(good.raw, 1.0);
  EXPECT_DOUBLE_EQ(good.per_component, 1.0);
  ASSERT_EQ(good.components.size(), 1u);
  EXPECT_FALSE(good.components[0].flipped);
  EXPECT_EQ(good.components[0].faces, sphere.n_faces());

  const Mesh flipped = transformed(sphere, Vec3(0, 0, 0), true);
  const gcs::OrientationConsistency bad = gcs::orientation_consistency(flipped, gt, fast());
  EXPECT_DOUBLE_EQ(bad.raw, 0.0);
  EXPECT_DOUBLE_EQ(bad.per_component, 1.0);
  EXPECT_TRUE(bad.components[0].flipped);
  EXPECT_GT(bad.unsigned_consistency, 0.99);

  // evaluate reports the same figures (same samples and seed).
  const gcs::Evaluation e = gcs::evaluate(flipped, gcs::GroundTruth::from_points(gt), fast());
  ASSERT_TRUE(e.orientation.has_value());
  EXPECT_DOUBLE_EQ(e.orientation->raw, bad.raw);
  EXPECT_DOUBLE_EQ(e.orientation->per_component, bad.per_component);
}

TEST(GcsEval, HalfFlippedAreaSeparateComponentsVersusOneComponent) {
  const Mesh sphere = shapes::icosphere(3);
  const PointCloud one = sphere_samples(10000);
  // Two equal spheres, separate components; the second one reversed.
  Mesh two;
  append(two, sphere, Vec3(-2, 0, 0));
  append(two, sphere, Vec3(2, 0, 0), true);
  PointCloud gt = shifted(one, Vec3(-2, 0, 0));
  const PointCloud right = shifted(sphere_samples(10000, 8), Vec3(2, 0, 0));
  gt.points.insert(gt.points.end(), right.points.begin(), right.points.end());
  gt.normals.insert(gt.normals.end(), right.normals.begin(), right.normals.end());
  const gcs::OrientationConsistency sep = gcs::orientation_consistency(two, gt, fast());
  EXPECT_NEAR(sep.raw, 0.5, 0.02);
  EXPECT_DOUBLE_EQ(sep.per_component, 1.0);  // each component fixed by its own sign
  ASSERT_EQ(sep.components.size(), 2u);
  EXPECT_FALSE(sep.components[0].flipped);
  EXPECT_TRUE(sep.components[1].flipped);
  EXPECT_NEAR(sep.components[0].area_share, 0.5, 0.02);

  // One component, the ground truth's normals reversed on its lower half: no single sign helps.
  PointCloud half = one;
  for (std::size_t i = 0; i < half.size(); ++i) {
    if (half.points[i][2] < 0) half.normals[i] = -half.normals[i];
  }
  const gcs::OrientationConsistency joined = gcs::orientation_consistency(sphere, half, fast());
  EXPECT_NEAR(joined.raw, 0.5, 0.02);
  EXPECT_NEAR(joined.per_component, std::max(joined.raw, 1.0 - joined.raw), 1e-12);
  EXPECT_LT(joined.per_component, 0.53);
}

TEST(GcsEval, UnorientedGroundTruthHasNoOrientation) {
  PointCloud gt = sphere_samples(2000);
  gt.normals.clear();
  const gcs::Evaluation e =
      gcs::evaluate(shapes::icosphere(2), gcs::GroundTruth::from_points(gt), fast(2000));
  EXPECT_FALSE(e.orientation.has_value());
  EXPECT_FALSE(e.normal_consistency.has_value());
  EXPECT_NE(gcs::format_evaluation(e).find("orientation consistency: n/a"), std::string::npos);
  EXPECT_NE(gcs::evaluation_to_json(e).find("\"orientation_consistency\": null"), std::string::npos);
  EXPECT_THROW(gcs::orientation_consistency(shapes::icosphere(2), gt, fast()), InvalidInput);
}

// ---------------------------------------------------------------------------------------------
// Validity

Mesh make_mesh(const std::vector<Vec3>& points, const std::vector<std::array<int, 3>>& faces) {
  Mesh m;
  for (const Vec3& p : points) m.add_vertex(p);
  for (const auto& f : faces)
    EXPECT_TRUE(m.add_face(VertexHandle(f[0]), VertexHandle(f[1]), VertexHandle(f[2])).is_valid());
  return m;
}

TEST(GcsEval, SelfIntersectionsOfSpheresAndPlanes) {
  EXPECT_EQ(gcs::count_self_intersections(shapes::icosphere(4)), 0u);
  EXPECT_EQ(gcs::count_self_intersections(shapes::torus(64, 24)), 0u);
  EXPECT_EQ(gcs::count_self_intersections(shapes::make("vault-shell", {.resolution = 32, .shape = {}})), 0u);
  // Planar meshes: every neighbour is coplanar; in z = 0 and tilted out of the axis planes.
  const Mesh plane = shapes::grid({.cells = 12});
  EXPECT_EQ(gcs::count_self_intersections(plane), 0u);
  Mesh tilted = plane;
  for (const auto v : tilted.vertices()) {
    const Vec3 p = tilted.point(v);
    tilted.set_point(v, Vec3(p[0], 0.6 * p[1], 0.8 * p[1] + 0.3 * p[0] + 1e3));
  }
  EXPECT_EQ(gcs::count_self_intersections(tilted), 0u);

  // Two interpenetrating spheres in one mesh: the faces along the intersection circle.
  Mesh both;
  append(both, shapes::icosphere(3));
  append(both, shapes::icosphere(3), Vec3(0.8, 0, 0));
  const std::size_t n = gcs::count_self_intersections(both);
  EXPECT_GT(n, 20u);
  // Moved apart, they no longer intersect.
  Mesh apart;
  append(apart, shapes::icosphere(3));
  append(apart, shapes::icosphere(3), Vec3(2.5, 0, 0));
  EXPECT_EQ(gcs::count_self_intersections(apart), 0u);
}

TEST(GcsEval, SelfIntersectionsOfFacesSharingAVertexOrAnEdge) {
  // Sharing an edge, bent (not coplanar): no intersection.
  EXPECT_EQ(gcs::count_self_intersections(
                make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.5, -1, 0.3}}, {{{0, 1, 2}}, {{1, 0, 3}}})),
            0u);
  // Sharing an edge, folded flat onto each other (coplanar, same side): one pair.
  EXPECT_EQ(gcs::count_self_intersections(
                make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.6, 0.6, 0}}, {{{0, 1, 2}}, {{1, 0, 3}}})),
            1u);
  // Sharing a vertex only, touching there: no intersection.
  EXPECT_EQ(gcs::count_self_intersections(make_mesh(
                {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0.2}, {0, -1, 0.5}}, {{{0, 1, 2}}, {{0, 3, 4}}})),
            0u);
  // Sharing a vertex, the second triangle pierces the first: one pair.
  EXPECT_EQ(gcs::count_self_intersections(make_mesh(
                {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {1, 0.5, -1}, {1, 0.5, 1}}, {{{0, 1, 2}}, {{0, 3, 4}}})),
            1u);
  // No shared vertex, one triangle through the other: one pair; far apart: none.
  EXPECT_EQ(gcs::count_self_intersections(
                make_mesh({{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0.5, 0.5, -1}, {0.6, 0.5, 1}, {0.5, 0.7, 1}},
                          {{{0, 1, 2}}, {{3, 4, 5}}})),
            1u);
  EXPECT_EQ(gcs::count_self_intersections(
                make_mesh({{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {5.5, 0.5, -1}, {5.6, 0.5, 1}, {5.5, 0.7, 1}},
                          {{{0, 1, 2}}, {{3, 4, 5}}})),
            0u);
  // Coplanar overlap without a shared vertex.
  EXPECT_EQ(gcs::count_self_intersections(
                make_mesh({{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0.5, 0.5, 0}, {3, 0.5, 0}, {0.5, 3, 0}},
                          {{{0, 1, 2}}, {{3, 4, 5}}})),
            1u);
}

TEST(GcsEval, ValidityOfATorusAndOfAnOpenGrid) {
  const Mesh torus = shapes::torus(32, 12);
  const gcs::MeshValidity t = gcs::mesh_validity(torus);
  EXPECT_DOUBLE_EQ(t.genus, 1.0);
  EXPECT_EQ(t.euler_characteristic, 0);
  EXPECT_EQ(t.components, 1u);
  EXPECT_TRUE(t.closed);
  EXPECT_TRUE(t.vertex_manifold);
  EXPECT_EQ(t.self_intersecting_pairs, std::optional<std::size_t>(0));
  EXPECT_EQ(t.valence_histogram, edgefront::compute_stats(torus).valence_histogram);

  // Regular grid: right isosceles triangles, every smallest angle is 45 degrees.
  const Mesh plane = shapes::grid({.cells = 6});
  const gcs::MeshValidity g = gcs::mesh_validity(plane, false);
  EXPECT_EQ(g.border_loops, 1u);
  EXPECT_FALSE(g.closed);
  EXPECT_DOUBLE_EQ(g.genus, 0.0);
  EXPECT_NEAR(g.min_angle_deg, 45.0, 1e-9);
  EXPECT_NEAR(g.median_min_angle_deg, 45.0, 1e-9);
  EXPECT_DOUBLE_EQ(g.faces_min_angle_below_30, 0.0);
  EXPECT_NEAR(g.area, 4.0, 1e-12);
  EXPECT_FALSE(g.self_intersecting_pairs.has_value());

  // Two separate components: genus per component, summed.
  Mesh pair;
  append(pair, torus);
  append(pair, shapes::icosphere(2), Vec3(5, 0, 0));
  const gcs::MeshValidity p = gcs::mesh_validity(pair);
  EXPECT_EQ(p.components, 2u);
  EXPECT_EQ(p.component_genus, (std::vector<double>{1.0, 0.0}));
  EXPECT_DOUBLE_EQ(p.genus, 1.0);
}

TEST(GcsEval, DeletedElementsAreIgnored) {
  // A mesh the way an editing loop leaves it: a face deleted, not garbage-collected.
  Mesh mesh = shapes::icosphere(3);
  mesh.delete_face(edgefront::FaceHandle(0), false);
  const gcs::Evaluation e =
      gcs::evaluate(mesh, gcs::GroundTruth::from_points(sphere_samples(5000)), fast(5000));
  EXPECT_EQ(e.validity.faces, shapes::icosphere(3).n_faces() - 1);
  EXPECT_EQ(e.validity.border_loops, 1u);
  EXPECT_FALSE(e.validity.closed);
  EXPECT_EQ(e.validity.self_intersecting_pairs, std::optional<std::size_t>(0));
  EXPECT_DOUBLE_EQ(e.orientation->raw, 1.0);
  std::size_t faces = 0;
  for (const auto& c : e.orientation->components) faces += c.faces;
  EXPECT_EQ(faces, e.validity.faces);
}

// ---------------------------------------------------------------------------------------------
// Bad input

TEST(GcsEval, BadInputIsAClearError) {
  const Mesh sphere = shapes::icosphere(2);
  const PointCloud gt = sphere_samples(1000);
  auto expect_invalid = [](auto&& call, const std::string& hint) {
    try {
      call();
      ADD_FAILURE() << "no exception, expected one mentioning '" << hint << "'";
    } catch (const InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find(hint), std::string::npos) << e.what();
    }
  };
  const gcs::GroundTruth points = gcs::GroundTruth::from_points(gt);
  expect_invalid([&] { gcs::evaluate(Mesh(), points, fast()); }, "empty");
  Mesh no_faces;
  no_faces.add_vertex(Vec3(0, 0, 0));
  no_faces.add_vertex(Vec3(1, 0, 0));
  expect_invalid([&] { gcs::evaluate(no_faces, points, fast()); }, "no faces");
  Mesh flat = make_mesh({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, {{{0, 1, 2}}});
  expect_invalid([&] { gcs::evaluate(flat, points, fast()); }, "positive area");
  Mesh nan_mesh = sphere;
  nan_mesh.set_point(VertexHandle(5), Vec3(std::numeric_limits<double>::quiet_NaN(), 0, 0));
  expect_invalid([&] { gcs::evaluate(nan_mesh, points, fast()); }, "vertex 5");
  expect_invalid([&] { gcs::evaluate(sphere, gcs::GroundTruth::from_points(PointCloud{}), fast()); },
                 "empty");
  PointCloud nan_gt = gt;
  nan_gt.points[17][1] = std::numeric_limits<double>::infinity();
  expect_invalid([&] { gcs::evaluate(sphere, gcs::GroundTruth::from_points(nan_gt), fast()); }, "point 17");
  PointCloud zero_normal = gt;
  zero_normal.normals[3] = Vec3(0, 0, 0);
  expect_invalid([&] { gcs::evaluate(sphere, gcs::GroundTruth::from_points(zero_normal), fast()); },
                 "point 3");
  PointCloud short_normals = gt;
  short_normals.normals.pop_back();
  expect_invalid([&] { gcs::evaluate(sphere, gcs::GroundTruth::from_points(short_normals), fast()); },
                 "normals");
  PointCloud same;
  same.points.assign(10, Vec3(1, 2, 3));
  expect_invalid([&] { gcs::evaluate(sphere, gcs::GroundTruth::from_points(same), fast()); }, "no extent");
  expect_invalid([&] { gcs::evaluate(sphere, gcs::GroundTruth::from_mesh(no_faces), fast()); }, "no faces");
  expect_invalid([&] { gcs::evaluate(sphere, points, fast(0)); }, "samples");
  gcs::EvaluationOptions bad_threshold = fast();
  bad_threshold.fscore_thresholds = {0.01, -1.0};
  expect_invalid([&] { gcs::evaluate(sphere, points, bad_threshold); }, "threshold");
  bad_threshold.fscore_thresholds = {std::numeric_limits<double>::quiet_NaN()};
  expect_invalid([&] { gcs::evaluate(sphere, points, bad_threshold); }, "threshold");
}

TEST(GcsEval, SameSeedSameFiguresOtherSeedClose) {
  const Mesh mesh = shapes::make("bumpy-sphere", {.resolution = 40, .shape = {}});
  const gcs::GroundTruth gt = gcs::GroundTruth::from_points(sphere_samples(5000));
  const gcs::Evaluation a = gcs::evaluate(mesh, gt, fast(5000));
  const gcs::Evaluation b = gcs::evaluate(mesh, gt, fast(5000));
  EXPECT_EQ(gcs::evaluation_to_json(a), gcs::evaluation_to_json(b));
  gcs::EvaluationOptions other = fast(5000);
  other.seed = 99;
  const gcs::Evaluation c = gcs::evaluate(mesh, gt, other);
  EXPECT_NE(a.result_to_gt.mean, c.result_to_gt.mean);
  EXPECT_NEAR(a.chamfer_l1, c.chamfer_l1, 0.05 * a.chamfer_l1);
  EXPECT_EQ(a.gt_to_result.mean, c.gt_to_result.mean);  // all ground-truth points, no sampling
}

// ---------------------------------------------------------------------------------------------
// The gcs-eval tool

class GcsEvalApp : public eftest::AppTest {
 protected:
  GcsEvalApp() : AppTest("gcs-eval") {}
  std::string file(const std::string& name) const { return eftest::shell_quoted((dir_ / name).string()); }
  void expect_error(const std::string& args, int code, const std::string& hint) const {
    const eftest::CommandResult r = run(args);
    EXPECT_EQ(r.exit_code, code) << args << "\n" << r.err;
    EXPECT_EQ(r.err.rfind("gcs-eval: error: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(hint), std::string::npos) << r.err;
    EXPECT_EQ(r.out, "");
  }
  static double json_number(const std::string& json, const std::string& key) {
    std::smatch m;
    const std::regex re("\"" + key + "\": ([-0-9.eE+]+)");
    if (!std::regex_search(json, m, re)) {
      ADD_FAILURE() << key << " not in " << json;
      return std::numeric_limits<double>::quiet_NaN();
    }
    return std::stod(m[1].str());
  }
};

TEST_F(GcsEvalApp, TableAndJsonAgreeWithTheLibrary) {
  const Mesh mesh = shapes::icosphere(3);
  const PointCloud gt = sphere_samples(3000);
  edgefront::write_mesh(mesh, dir_ / "sphere.off");
  edgefront::write_points(gt, dir_ / "gt.xyz");

  const eftest::CommandResult table =
      run(file("sphere.off") + " " + file("gt.xyz") + " --samples 4000 --seed 5");
  ASSERT_EQ(table.exit_code, 0) << table.err;
  for (const char* key :
       {"chamfer-L1:", "hausdorff 95%:", "F-score @ 0.50%:", "F-score @ 1.00%:", "normal consistency:",
        "orientation consistency: 1.0000 as is", "self-intersecting pairs: 0",
        "euler / genus:", "valence histogram:", "min angle:", "point set, 3000 points"}) {
    EXPECT_NE(table.out.find(key), std::string::npos) << key << "\n" << table.out;
  }

  const eftest::CommandResult json =
      run(file("sphere.off") + " " + file("gt.xyz") + " --samples 4000 --seed 5 --json");
  ASSERT_EQ(json.exit_code, 0) << json.err;
  gcs::EvaluationOptions o;
  o.samples = 4000;
  o.seed = 5;
  const gcs::Evaluation e =
      gcs::evaluate(edgefront::load_mesh(dir_ / "sphere.off"),
                    gcs::GroundTruth::from_points(edgefront::read_points(dir_ / "gt.xyz")), o);
  EXPECT_EQ(json.out, gcs::evaluation_to_json(e));
  EXPECT_NEAR(json_number(json.out, "chamfer_l1"), e.chamfer_l1, 1e-15);
  EXPECT_NEAR(json_number(json.out, "genus"), 0.0, 0.0);
}

TEST_F(GcsEvalApp, GroundTruthKindIsDecidedByContent) {
  const Mesh torus = shapes::torus(24, 10);
  edgefront::write_mesh(torus, dir_ / "torus.off");
  edgefront::write_mesh(torus, dir_ / "torus.ply");
  Mesh points_only;
  for (const auto v : torus.vertices()) points_only.add_vertex(torus.point(v));
  edgefront::write_mesh(points_only, dir_ / "vertices.off");

  const eftest::CommandResult as_mesh =
      run(file("torus.off") + " " + file("torus.ply") + " --samples 2000 --json");
  ASSERT_EQ(as_mesh.exit_code, 0) << as_mesh.err;
  EXPECT_NE(as_mesh.out.find("\"kind\": \"mesh\""), std::string::npos);
  EXPECT_LT(json_number(as_mesh.out, "chamfer_l1"), 1e-12);
  EXPECT_NEAR(json_number(as_mesh.out, "raw"), 1.0, 0.0);

  const eftest::CommandResult as_points =
      run(file("torus.off") + " " + file("vertices.off") + " --samples 2000 --json");
  ASSERT_EQ(as_points.exit_code, 0) << as_points.err;
  EXPECT_NE(as_points.out.find("\"kind\": \"points\""), std::string::npos);
  EXPECT_NE(as_points.out.find("\"orientation_consistency\": null"), std::string::npos);  // no normals
  EXPECT_NEAR(json_number(as_points.out, "points"), static_cast<double>(torus.n_vertices()), 0.0);
}

TEST_F(GcsEvalApp, ErrorsAndExitCodes) {
  const Mesh sphere = shapes::icosphere(2);
  edgefront::write_mesh(sphere, dir_ / "sphere.off");
  edgefront::write_points(sphere_samples(500), dir_ / "gt.xyz");
  Mesh no_faces;
  no_faces.add_vertex(Vec3(0, 0, 0));
  no_faces.add_vertex(Vec3(1, 1, 1));
  edgefront::write_mesh(no_faces, dir_ / "nofaces.off");

  expect_error(file("missing.off") + " " + file("gt.xyz"), 1, "missing.off");
  expect_error(file("sphere.off") + " " + file("missing.xyz"), 1, "missing.xyz");
  expect_error(file("nofaces.off") + " " + file("gt.xyz"), 1, "no faces");
  const std::string nan_points =
      eftest::shell_quoted((fs::path(EDGEFRONT_TEST_DATA_DIR) / "bad" / "nan_points.xyz").string());
  expect_error(file("sphere.off") + " " + nan_points, 1, "nan_points.xyz");
  const std::string empty =
      eftest::shell_quoted((fs::path(EDGEFRONT_TEST_DATA_DIR) / "bad" / "no_points.xyz").string());
  expect_error(file("sphere.off") + " " + empty, 1, "no_points.xyz");
  expect_error(file("sphere.off") + " " + file("gt.xyz") + " --samples 0", 2, "samples");
  expect_error(file("sphere.off"), 2, "GT");

  // A non-manifold file: the reader drops a face, and the report says so.
  const std::string nonmanifold =
      eftest::shell_quoted((fs::path(EDGEFRONT_TEST_DATA_DIR) / "bad" / "nonmanifold.off").string());
  const eftest::CommandResult nm = run(nonmanifold + " " + nonmanifold + " --samples 100 --json");
  EXPECT_EQ(nm.exit_code, 0) << nm.err;
  EXPECT_NEAR(json_number(nm.out, "faces_dropped_when_read"), 1.0, 0.0);
  EXPECT_NE(nm.err.find("gcs-eval: warning: mesh:"), std::string::npos) << nm.err;

  const eftest::CommandResult help = run("--help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_NE(help.out.find("--samples"), std::string::npos);
}

}  // namespace
