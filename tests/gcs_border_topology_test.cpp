// Tests of the built-in topology changes of the GCS loop (gcs/src/detail/border_topology.h): zipping
// slits (two border chains running close and opposite) and filling slit and triangular holes, on
// small flat grids with a planar "cloud".

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <utility>
#include <vector>

#include "../gcs/src/detail/border_topology.h"
#include "edgefront/mesh_stats.h"
#include "edgefront/shapes.h"
#include "gcs/reconstructor.h"

namespace {

using edgefront::Mesh;
using edgefront::Vec3;
using edgefront::VertexHandle;

// A grid of nx x ny unit cells on z = 0, two triangles per cell, without the cells in `holes`.
Mesh grid_without(int nx, int ny, const std::set<std::pair<int, int>>& holes) {
  Mesh m;
  std::vector<VertexHandle> v;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) v.push_back(m.add_vertex(Vec3(i, j, 0)));
  const auto at = [&](int i, int j) { return v[static_cast<size_t>(j * (nx + 1) + i)]; };
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      if (holes.count({i, j})) continue;
      m.add_face(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      m.add_face(at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
  }
  m.delete_isolated_vertices();
  m.garbage_collection();
  return m;
}

// The plane z = 0 as the cloud.
gcs::detail::CloudHit plane(const Vec3& p) { return {std::abs(p[2]), Vec3(0, 0, 1)}; }

gcs::detail::ZipParams unit_params() {
  gcs::detail::ZipParams zp;
  zp.mean_edge_length = 1.0;
  zp.max_support_distance = 1.5;
  return zp;
}

size_t border_edges(const Mesh& m) {
  size_t n = 0;
  for (auto e : m.edges()) n += m.is_boundary(e);
  return n;
}

void expect_valid(Mesh& m) {
  m.garbage_collection();
  const edgefront::MeshStats s = edgefront::compute_stats(m);
  EXPECT_EQ(s.nonmanifold_vertices, 0u);
  EXPECT_EQ(s.duplicate_faces, 0u);
  EXPECT_EQ(s.components, 1u);
}

// A 12 x 7 grid with a slit hole 8 cells long and 1 wide (a loop of 18 vertices).
Mesh grid_with_slit() {
  std::set<std::pair<int, int>> slit;
  for (int i = 2; i <= 9; ++i) slit.insert({i, 3});
  return grid_without(12, 7, slit);
}

// Valid, one disk (genus 0, one border loop), every face in the plane facing +z like the grid.
void expect_flat_disk(Mesh& m) {
  expect_valid(m);
  const edgefront::MeshStats s = edgefront::compute_stats(m);
  EXPECT_EQ(s.border_loops, 1u);
  ASSERT_EQ(s.per_component.size(), 1u);
  EXPECT_EQ(s.per_component[0].genus, 0);
  m.update_face_normals();
  for (auto f : m.faces()) EXPECT_GT(m.normal(f)[2], 0.99);
}

TEST(GcsZipSlits, ANarrowHoleClosesAndOnlyTheOuterBorderRemains) {
  Mesh m = grid_with_slit();
  ASSERT_EQ(edgefront::compute_stats(m).border_loops, 2u);
  const size_t faces_before = m.n_faces();
  const size_t zipped = gcs::detail::zip_border_slits(m, plane, unit_params());
  EXPECT_GE(zipped, 1u);
  EXPECT_GT(m.n_faces(), faces_before);
  // What the strips leave at the slit's ends are small holes; the fan fill closes them.
  gcs::detail::fill_small_holes(m, plane, 8, 1.5, 0.5);
  expect_flat_disk(m);
}

TEST(GcsZipSlits, ANotchInTheOuterBorderCloses) {
  std::set<std::pair<int, int>> notch;
  for (int i = 0; i <= 7; ++i) notch.insert({i, 3});  // cut in from the left edge
  Mesh m = grid_without(12, 7, notch);
  ASSERT_EQ(edgefront::compute_stats(m).border_loops, 1u);
  const size_t before = border_edges(m);
  EXPECT_GE(gcs::detail::zip_border_slits(m, plane, unit_params()), 1u);
  EXPECT_EQ(edgefront::compute_stats(m).border_loops, 2u);  // the outer border and a small hole at the tip
  EXPECT_EQ(gcs::detail::fill_small_holes(m, plane, 8, 1.5, 0.5), 1u);
  expect_valid(m);
  EXPECT_EQ(edgefront::compute_stats(m).border_loops, 1u);
  EXPECT_LT(border_edges(m), before - 8);  // most of the notch's 16 border edges are gone
}

TEST(GcsZipSlits, WideHolesAndUnsupportedStripsStayOpen) {
  std::set<std::pair<int, int>> wide;
  for (int i = 2; i <= 9; ++i)
    for (int j = 2; j <= 4; ++j) wide.insert({i, j});  // 3 cells wide: beyond the 2-edge gap
  Mesh m = grid_without(12, 7, wide);
  const size_t faces = m.n_faces();
  EXPECT_EQ(gcs::detail::zip_border_slits(m, plane, unit_params()), 0u);
  EXPECT_EQ(m.n_faces(), faces);

  Mesh n = grid_with_slit();
  // A cloud far from the strip: no support, nothing added.
  const gcs::detail::CloudQuery far = [](const Vec3& p) { return gcs::detail::CloudHit{std::abs(p[2]) + 5.0, Vec3(0, 0, 1)}; };
  EXPECT_EQ(gcs::detail::zip_border_slits(n, far, unit_params()), 0u);
  EXPECT_EQ(edgefront::compute_stats(n).border_loops, 2u);
}

TEST(GcsZipSlits, TheLoopStaysValidWithSlitZippingOn) {
  edgefront::shapes::SampleOptions so;
  so.points = 3000;
  gcs::ReconstructOptions o;
  o.target_vertices = 400;
  o.batch_splits = 50;
  o.progress_interval = 50;
  o.zip_slits = true;
  gcs::Reconstructor r(edgefront::shapes::sample("hemisphere", so), o);
  const gcs::ReconstructResult res = r.run([&](const gcs::Progress&) {
    EXPECT_NO_THROW(r.validate());
    return true;
  });
  EXPECT_NO_THROW(r.validate());
  Mesh m = res.mesh;
  expect_valid(m);
  EXPECT_GE(edgefront::compute_stats(m).border_loops, 1u);  // an open shape keeps its border
}

TEST(GcsFillSlits, ASlitHoleIsClosedByOneStripAndTheOuterBorderRemains) {
  Mesh m = grid_with_slit();
  ASSERT_EQ(edgefront::compute_stats(m).border_loops, 2u);
  const size_t faces_before = m.n_faces();
  EXPECT_EQ(gcs::detail::fill_slit_holes(m, plane, 9, 64, 1.5, 0.5), 1u);
  EXPECT_EQ(m.n_faces(), faces_before + 16);  // a strip over 18 loop vertices: 18 - 2 triangles
  expect_flat_disk(m);
}

TEST(GcsFillSlits, UnsupportedTooLargeOrTooSmallLoopsStayOpen) {
  const gcs::detail::CloudQuery far = [](const Vec3& p) { return gcs::detail::CloudHit{std::abs(p[2]) + 5.0, Vec3(0, 0, 1)}; };
  Mesh a = grid_with_slit();
  EXPECT_EQ(gcs::detail::fill_slit_holes(a, far, 9, 64, 1.5, 0.5), 0u);  // no samples near the strip
  EXPECT_EQ(gcs::detail::fill_slit_holes(a, plane, 9, 17, 1.5, 0.5), 0u);  // 18 vertices > 17
  EXPECT_EQ(gcs::detail::fill_slit_holes(a, plane, 19, 64, 1.5, 0.5), 0u);  // 18 vertices < 19
  EXPECT_EQ(edgefront::compute_stats(a).border_loops, 2u);
  // An open sheet's outer border: a strip across it would fold back onto the sheet (normals
  // opposite to the faces it borders), so it is refused even though it lies on the samples.
  Mesh b = grid_without(4, 4, {});
  ASSERT_EQ(edgefront::compute_stats(b).border_loops, 1u);
  EXPECT_EQ(gcs::detail::fill_slit_holes(b, plane, 9, 64, 1.5, 0.5), 0u);
  EXPECT_EQ(edgefront::compute_stats(b).border_loops, 1u);
}

TEST(GcsFillSlits, ATriangularHoleIsClosedByItsOwnTriangle) {
  Mesh m = grid_without(4, 4, {});
  // Remove one triangle inside: a 3-vertex hole.
  for (auto f : m.faces()) {
    bool inner = true;
    for (auto v : m.fv_range(f)) inner = inner && !m.is_boundary(v);
    if (inner) {
      m.delete_face(f, false);
      break;
    }
  }
  m.garbage_collection();
  ASSERT_EQ(edgefront::compute_stats(m).border_loops, 2u);
  const size_t vertices = m.n_vertices();
  EXPECT_EQ(gcs::detail::fill_small_holes(m, plane, 8, 1.5, 0.5), 1u);
  EXPECT_EQ(m.n_vertices(), vertices);  // no fan vertex
  expect_valid(m);
  EXPECT_EQ(edgefront::compute_stats(m).border_loops, 1u);
}

}  // namespace
