// Tests of the closing of false borders (gcs/src/detail/close_borders.h,
// PostProcessOptions::close_false_borders): a torus whose tube is torn open lengthwise, with the
// samples of the whole torus, is closed again (genus 1, the patch outward and on the surface, no
// crossing); the same tear without samples beyond it (a real hole) and an open vault sheet stay as
// they are; bad parameters and options are refused.

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "../gcs/src/detail/close_borders.h"
#include "../gcs/src/detail/self_intersection.h"
#include "edgefront/error.h"
#include "edgefront/mesh_stats.h"
#include "gcs/reconstructor.h"
#include "shapes/shapes.h"

namespace {

using edgefront::Mesh;
using edgefront::Vec3;

constexpr double kMajor = 1.0, kMinor = 0.35;

// The point of the torus' core circle nearest to p.
Vec3 core_point(const Vec3& p) {
  const double r = std::hypot(p[0], p[1]);
  return r > 0 ? Vec3(p[0] / r * kMajor, p[1] / r * kMajor, 0) : Vec3(kMajor, 0, 0);
}

// A torus (the shapes library's, 48 x 16 segments) with its tube torn open lengthwise: the faces
// over a third of the way around the axis on the tube's outer upper side are removed.
Mesh torn_torus() {
  Mesh m = edgefront::shapes::torus(48, 16, kMajor, kMinor);
  for (auto f : m.faces()) {
    Vec3 c(0, 0, 0);
    for (auto v : m.fv_range(f)) c += m.point(v) / 3.0;
    const double around = std::atan2(c[1], c[0]);
    const Vec3 out = c - core_point(c);
    const double tube = std::atan2(out[2], std::hypot(c[0], c[1]) - kMajor);  // 0: outer equator
    if (around > 0.2 && around < 2.3 && tube > 0.1 && tube < 1.3) m.delete_face(f, true);
  }
  m.garbage_collection();
  return m;
}

edgefront::PointCloud torus_samples() {
  edgefront::shapes::SampleOptions so;
  so.points = 20000;
  so.shape.radius = kMajor;
  so.shape.minor_radius = kMinor;
  return edgefront::shapes::sample("torus", so);
}

gcs::detail::CloseBordersParams params_for(const Mesh& m) {
  gcs::detail::CloseBordersParams p;
  p.mean_edge_length = edgefront::compute_stats(m).mean_edge_length;
  return p;
}

TEST(GcsCloseBorders, ATubeTornOpenLengthwiseIsClosedOnTheSamples) {
  Mesh m = torn_torus();
  const edgefront::MeshStats before = edgefront::compute_stats(m);
  ASSERT_EQ(before.border_loops, 1u);
  const size_t old_vertices = m.n_vertices();
  const edgefront::PointCloud cloud = torus_samples();
  const gcs::detail::CloseBordersReport r = gcs::detail::close_false_borders(m, cloud.points, cloud.normals, params_for(m));
  EXPECT_EQ(r.loops, 1u);
  EXPECT_EQ(r.false_loops, 1u);
  EXPECT_EQ(r.closed, 1u);
  EXPECT_GT(r.vertices_added, 10u);
  m.garbage_collection();
  const edgefront::MeshStats after = edgefront::compute_stats(m);
  EXPECT_EQ(after.border_loops, 0u);
  EXPECT_EQ(after.components, 1u);
  EXPECT_EQ(after.nonmanifold_vertices, 0u);
  EXPECT_EQ(after.degenerate_faces, 0u);
  ASSERT_EQ(after.per_component.size(), 1u);
  EXPECT_EQ(after.per_component[0].genus, 1.0);
  EXPECT_TRUE(gcs::detail::self_intersecting_face_pairs(m).empty());
  // The patch's vertices lie on the torus, and every face faces outward (away from the core).
  for (auto v : m.vertices()) {
    if (static_cast<size_t>(v.idx()) < old_vertices) continue;
    const Vec3 p = m.point(v);
    EXPECT_NEAR((p - core_point(p)).norm(), kMinor, 0.02 * kMinor) << "vertex " << v.idx();
  }
  for (auto f : m.faces()) {
    Vec3 c(0, 0, 0);
    for (auto v : m.fv_range(f)) c += m.point(v) / 3.0;
    EXPECT_GT(m.calc_face_normal(f) | (c - core_point(c)), 0.0) << "face " << f.idx();
  }
}

TEST(GcsCloseBorders, ARealHoleAndAnOpenSheetStayOpen) {
  {  // the torn torus sampled as it is: nothing lies beyond its border
    Mesh m = torn_torus();
    const Mesh copy = m;
    edgefront::shapes::SampleOptions so;
    so.points = 20000;
    const edgefront::PointCloud cloud = edgefront::shapes::sample_mesh(copy, so);
    const gcs::detail::CloseBordersReport r = gcs::detail::close_false_borders(m, cloud.points, cloud.normals, params_for(m));
    EXPECT_EQ(r.loops, 1u);
    EXPECT_EQ(r.false_loops, 0u);
    EXPECT_EQ(r.closed, 0u);
    EXPECT_EQ(m.n_faces(), copy.n_faces());
    EXPECT_EQ(edgefront::compute_stats(m).border_loops, 1u);
  }
  {  // a vault sheet and its analytic samples, with and without their normals
    edgefront::shapes::MeshOptions mo;
    mo.resolution = 24;
    for (bool with_normals : {true, false}) {
      Mesh m = edgefront::shapes::make("vault-sheet", mo);
      const size_t faces = m.n_faces();
      edgefront::shapes::SampleOptions so;
      so.points = 20000;
      const edgefront::PointCloud cloud = edgefront::shapes::sample("vault-sheet", so);
      const std::vector<Vec3> none;
      const gcs::detail::CloseBordersReport r =
          gcs::detail::close_false_borders(m, cloud.points, with_normals ? cloud.normals : none, params_for(m));
      EXPECT_EQ(r.loops, 1u);
      EXPECT_EQ(r.closed, 0u) << "with normals: " << with_normals;
      EXPECT_EQ(m.n_faces(), faces);
    }
  }
}

TEST(GcsCloseBorders, BadParametersAndOptionsAreRefused) {
  Mesh m = torn_torus();
  const edgefront::PointCloud cloud = torus_samples();
  const auto refused = [&](const gcs::detail::CloseBordersParams& p, const std::vector<Vec3>& normals,
                           const std::string& what) {
    try {
      gcs::detail::close_false_borders(m, cloud.points, normals, p);
      ADD_FAILURE() << "not refused: " << what;
    } catch (const edgefront::InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  gcs::detail::CloseBordersParams p = params_for(m);
  p.mean_edge_length = std::nan("");
  refused(p, cloud.normals, "mean_edge_length");
  p = params_for(m);
  p.covered_edges = -1;
  refused(p, cloud.normals, "distances");
  p = params_for(m);
  p.min_rim_cos = 2;
  refused(p, cloud.normals, "min_rim_cos");
  refused(params_for(m), std::vector<Vec3>(3, Vec3(0, 0, 1)), "normals");
  EXPECT_EQ(edgefront::compute_stats(m).border_loops, 1u);  // nothing changed

  for (std::size_t bad : {std::size_t{2}, std::size_t{5000}}) {
    gcs::ReconstructOptions o;
    o.target_vertices = 500;
    o.post.close_borders_max_vertices = bad;
    try {
      gcs::Reconstructor r(cloud, o);
      ADD_FAILURE() << "not refused: " << bad;
    } catch (const edgefront::InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find("close_borders_max_vertices"), std::string::npos) << e.what();
    }
  }
  EXPECT_FALSE(gcs::ReconstructOptions::open_sheet().post.close_false_borders);
  EXPECT_TRUE(gcs::ReconstructOptions::scan().post.close_false_borders);
}

}  // namespace
