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
#include "shapes/shapes.h"
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

TEST(GcsCleanTopology, TheLargestPieceOnAPartOfTheCloudOfItsOwnIsKept) {
  // A 30 x 2 strip without columns 20 and 27: pieces of 80 (columns 0-19), 24 (21-26) and 8 faces
  // (28-29). The sample nearest to a face is numbered by its column.
  const Mesh start = grid_without(30, 2, {{20, 0}, {20, 1}, {27, 0}, {27, 1}});
  const auto cloud = [](const Vec3& p) {
    return gcs::detail::CloudHit{std::abs(p[2]), Vec3(0, 0, 1), p, static_cast<size_t>(p[0])};
  };
  const auto pieces = [](const Mesh& m) { return edgefront::compute_stats(m).components; };
  ASSERT_EQ(pieces(start), 3u);
  {  // the cloud in one part (or no parts known): both small pieces are under half of 80 faces
    Mesh m = start;
    EXPECT_EQ(gcs::detail::clean_topology(m, 1, 0.5), 32u);
    Mesh n = start;
    const gcs::detail::FaceNearest nearest = gcs::detail::face_nearest(n, cloud);
    EXPECT_EQ(gcs::detail::clean_topology(n, 1, 0.5, {&nearest, [](size_t) { return 0; }}), 32u);
    EXPECT_EQ(pieces(n), 1u);
  }
  {  // columns 21-29 a part of the cloud of their own: its largest piece (24 faces) is a separate
     // surface and stays; the 8-face one is a fragment, judged as before, and goes
    Mesh m = start;
    const gcs::detail::FaceNearest nearest = gcs::detail::face_nearest(m, cloud);
    EXPECT_EQ(gcs::detail::clean_topology(m, 1, 0.5, {&nearest, [](size_t column) { return column > 20 ? 1 : 0; }}),
              8u);
    EXPECT_EQ(pieces(m), 2u);
    m.garbage_collection();
    EXPECT_EQ(m.n_faces(), 80u + 24u);
  }
}

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
  o.growth.batch_splits = 50;
  o.progress_interval = 50;
  o.experimental.zip_slits = true;
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

// A tube around the z axis: `rings` rings of 12 vertices at z = z0, z0 + 1, ..., radius r,
// faces pointing away from the axis; its two ends are border loops.
void add_tube(Mesh& m, double z0, int rings, double r) {
  constexpr int n = 12;
  std::vector<VertexHandle> v;
  for (int k = 0; k < rings; ++k)
    for (int i = 0; i < n; ++i) {
      const double a = 2.0 * M_PI * i / n;
      v.push_back(m.add_vertex(Vec3(r * std::cos(a), r * std::sin(a), z0 + k)));
    }
  const auto at = [&](int k, int i) { return v[static_cast<size_t>(k * n + (i % n))]; };
  for (int k = 0; k + 1 < rings; ++k)
    for (int i = 0; i < n; ++i) {
      m.add_face(at(k, i), at(k, i + 1), at(k + 1, i + 1));
      m.add_face(at(k, i), at(k + 1, i + 1), at(k + 1, i));
    }
}

// The cylinder of radius 2 around the z axis as the cloud (outward normals).
gcs::detail::CloudHit cylinder(const Vec3& p) {
  const double rho = std::hypot(p[0], p[1]);
  return {std::abs(rho - 2.0), rho > 0 ? Vec3(p[0] / rho, p[1] / rho, 0) : Vec3(1, 0, 0)};
}

// Every face points away from the z axis.
void expect_outward(Mesh& m) {
  m.update_face_normals();
  for (auto f : m.faces()) {
    Vec3 c(0, 0, 0);
    for (auto v : m.fv_range(f)) c += m.point(v);
    EXPECT_GT((m.normal(f) | Vec3(c[0], c[1], 0).normalized()), 0.8);
  }
}

TEST(GcsTrimMerge, TwoTubesWhoseRimsSlidPastEachOtherAreJoinedAfterTrimmingARing) {
  // Tube A: z = 0 ... 3 (radius 2); tube B: z = 2.6 ... 5.6 (radius 2.05): B's lower rim lies
  // 0.4 below A's upper rim, just outside it. The strip between the two rims folds back.
  Mesh m;
  add_tube(m, 0.0, 4, 2.0);
  add_tube(m, 2.6, 4, 2.05);
  ASSERT_EQ(edgefront::compute_stats(m).border_loops, 4u);
  gcs::detail::MergeParams mp;
  mp.mean_edge_length = 1.0;
  mp.max_support_distance = 1.5;
  Mesh untrimmed = m;
  EXPECT_EQ(gcs::detail::merge_border_loops(untrimmed, cylinder, mp), 0u);  // the fold is refused
  EXPECT_EQ(untrimmed.n_faces(), m.n_faces());
  mp.max_trim_rings = 2;
  EXPECT_EQ(gcs::detail::merge_border_loops(m, cylinder, mp), 1u);
  m.garbage_collection();
  const edgefront::MeshStats s = edgefront::compute_stats(m);
  EXPECT_EQ(s.components, 1u);
  EXPECT_EQ(s.border_loops, 2u);  // the tube's two ends
  EXPECT_EQ(s.nonmanifold_vertices, 0u);
  ASSERT_EQ(s.per_component.size(), 1u);
  EXPECT_EQ(s.per_component[0].genus, 0);
  expect_outward(m);
  // The overlap is gone: no vertex of A above z = 2.5 and none of B below it.
  for (auto v : m.vertices()) {
    const Vec3& p = m.point(v);
    const bool of_a = std::abs(std::hypot(p[0], p[1]) - 2.0) < 0.01;
    EXPECT_TRUE(of_a ? p[2] < 2.5 : p[2] > 2.5) << p;
  }
}

// A 10 x 10 grid on z = 0 with a 2 x 2 hole in the middle whose 8 rim vertices are raised to z = 2
// (a curled rim: a fan over the hole lies off the samples and folds against the steep faces).
Mesh grid_with_raised_hole() {
  Mesh m = grid_without(10, 10, {{4, 4}, {4, 5}, {5, 4}, {5, 5}});
  for (auto v : m.vertices())
    if (m.is_boundary(v) && m.point(v)[0] >= 4 && m.point(v)[0] <= 6 && m.point(v)[1] >= 4 && m.point(v)[1] <= 6)
      m.point(v)[2] = 2.0;
  return m;
}

TEST(GcsTrimFill, ASmallHoleWithACurledRimClosesAfterTrimmingARing) {
  Mesh m = grid_with_raised_hole();
  ASSERT_EQ(edgefront::compute_stats(m).border_loops, 2u);
  const size_t faces = m.n_faces();
  EXPECT_EQ(gcs::detail::fill_small_holes(m, plane, 8, 1.5, 0.5), 0u);  // no trimming: refused
  EXPECT_EQ(gcs::detail::fill_small_holes(m, plane, 8, 1.5, 0.5, {.rings = 2, .max_loop_length = 7.9}), 0u);  // loop too long
  EXPECT_EQ(m.n_faces(), faces);
  EXPECT_EQ(gcs::detail::fill_small_holes(m, plane, 8, 1.5, 0.5, {.rings = 2, .max_loop_length = 10}), 1u);
  m.garbage_collection();
  for (auto v : m.vertices()) EXPECT_LT(std::abs(m.point(v)[2]), 1e-12) << m.point(v);  // the raised rim is gone
  expect_flat_disk(m);
}

TEST(GcsTrimFill, ASlitWithCurledRimsIsZippedAfterTrimmingARing) {
  Mesh m = grid_with_slit();
  for (auto v : m.vertices())  // raise the slit's 18 border vertices (not the outer border)
    if (m.is_boundary(v) && m.point(v)[1] >= 3 && m.point(v)[1] <= 4 && m.point(v)[0] >= 2 && m.point(v)[0] <= 10)
      m.point(v)[2] = 2.0;
  ASSERT_EQ(edgefront::compute_stats(m).border_loops, 2u);
  const size_t faces = m.n_faces();
  EXPECT_EQ(gcs::detail::fill_slit_holes(m, plane, 9, 64, 1.5, 0.5), 0u);  // the strip lies off the samples
  EXPECT_EQ(m.n_faces(), faces);
  EXPECT_EQ(gcs::detail::fill_slit_holes(m, plane, 9, 64, 1.5, 0.5, 2), 1u);
  m.garbage_collection();
  for (auto v : m.vertices()) EXPECT_LT(std::abs(m.point(v)[2]), 1e-12) << m.point(v);
  expect_flat_disk(m);
}

TEST(GcsJoinComponents, TwoSheetsSideBySideAreZippedOnlyAcrossComponents) {
  // Two 5 x 7 grids one unit apart (x = 0 ... 5 and x = 6 ... 11): their facing borders run
  // opposite within the 2-edge gap.
  Mesh m = grid_without(11, 7, {{5, 0}, {5, 1}, {5, 2}, {5, 3}, {5, 4}, {5, 5}, {5, 6}});
  ASSERT_EQ(edgefront::compute_stats(m).components, 2u);
  gcs::detail::ZipParams zp = unit_params();
  zp.across_loops = true;
  zp.only_across_components = true;
  EXPECT_GE(gcs::detail::zip_border_slits(m, plane, zp), 1u);
  m.garbage_collection();
  EXPECT_EQ(edgefront::compute_stats(m).components, 1u);
  expect_valid(m);
  // Within one component (a slit hole) nothing is zipped.
  Mesh slit = grid_with_slit();
  EXPECT_EQ(gcs::detail::zip_border_slits(slit, plane, zp), 0u);
  EXPECT_EQ(edgefront::compute_stats(slit).border_loops, 2u);
}

TEST(GcsJoinComponents, ASmallPlanarCloudEndsAsOneSheet) {
  // 2000 grid samples at 300 vertices, seed 2: a corner is torn off as a second piece unless the
  // two pieces' facing borders are zipped back (join_components).
  edgefront::shapes::SampleOptions so;
  so.points = 2000;
  gcs::ReconstructOptions o;
  o.target_vertices = 300;
  o.seed = 2;
  for (const bool join : {false, true}) {
    o.topology.join_components = join;
    Mesh m = gcs::reconstruct(edgefront::shapes::sample("grid", so), o).mesh;
    const edgefront::MeshStats s = edgefront::compute_stats(m);
    EXPECT_EQ(s.nonmanifold_vertices, 0u);
    if (join) {
      EXPECT_EQ(s.components, 1u);
      EXPECT_EQ(s.border_loops, 1u);
    } else {
      EXPECT_GE(s.components, 2u) << "without the join a piece is torn off";
    }
  }
}

}  // namespace

TEST(GcsFillChecked, HolesAreFilledOneAtATimeAndTheTriangulationOnlyWhereFlagged) {
  // A 10 x 6 grid with two one-cell holes (4-vertex loops), at x = 2 and x = 7.
  const Mesh start = grid_without(10, 6, {{2, 2}, {7, 2}});
  ASSERT_EQ(edgefront::compute_stats(start).border_loops, 3u);
  {
    // The fill of the hole at x = 7 is not accepted (say it crosses something): the other hole is
    // still filled (one at a time, not all or nothing).
    Mesh m = start;
    const auto accept = [&](Mesh& trial) {  // only fills whose new faces lie at x < 5
      for (auto f : trial.faces())
        if (static_cast<size_t>(f.idx()) >= start.n_faces() && gcs::detail::centroid(trial, f)[0] > 5) return false;
      return true;
    };
    EXPECT_EQ(gcs::detail::fill_small_holes_checked(m, plane, 8, 1.5, 0.5, {}, accept), 1u);
    m.garbage_collection();
    EXPECT_EQ(edgefront::compute_stats(m).border_loops, 2u);
    size_t near_right_hole = 0;  // faces within the right hole's cell
    for (auto f : m.faces()) {
      const Vec3 c = gcs::detail::centroid(m, f);
      near_right_hole += c[0] > 7 && c[0] < 8 && c[1] > 2 && c[1] < 3;
    }
    EXPECT_EQ(near_right_hole, 0u);
    EXPECT_EQ(m.n_faces(), start.n_faces() + 4);  // the left hole's fan
  }
  {
    // A fan is refused (agreement above 1 is impossible): the holes stay open, except where a
    // vertex is flagged, where the triangulation of least area (two triangles, no new vertex) closes it.
    Mesh m = start;
    const size_t vertices = m.n_vertices();
    EXPECT_EQ(gcs::detail::fill_small_holes_checked(m, plane, 8, 1.5, 1.01, {}, [](Mesh&) { return true; }), 0u);
    std::vector<char> flagged(m.n_vertices(), 0);
    for (auto v : m.vertices())
      if (m.is_boundary(v) && m.point(v)[0] == 8 && m.point(v)[1] == 3) flagged[static_cast<size_t>(v.idx())] = 1;
    EXPECT_EQ(gcs::detail::fill_small_holes_checked(m, plane, 8, 1.5, 1.01, flagged, [](Mesh&) { return true; }), 1u);
    EXPECT_EQ(m.n_vertices(), vertices);
    m.garbage_collection();
    EXPECT_EQ(edgefront::compute_stats(m).border_loops, 2u);
    EXPECT_EQ(m.n_faces(), start.n_faces() + 2);
    m.update_face_normals();
    for (auto f : m.faces()) EXPECT_GT(m.normal(f)[2], 0.99);
    // Off the samples: refused.
    Mesh far = start;
    EXPECT_EQ(gcs::detail::fill_small_holes_checked(far, [](const Vec3& p) { return gcs::detail::CloudHit{std::abs(p[2]) + 2.0, Vec3(0, 0, 1)}; },
                                                    8, 1.5, 1.01, flagged, [](Mesh&) { return true; }), 0u);
  }
}
