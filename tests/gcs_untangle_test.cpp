// Resolving self-intersecting face pairs of the GCS result (gcs/src/detail/untangle.h,
// PostProcessOptions::resolve_self_intersections): a poked vertex is smoothed back, crossings
// smoothing cannot undo are cut out, a mesh without crossings is untouched, bad parameters are
// refused, a cut never splits the mesh, and a thin vault shell that comes out of the loop with crossings is returned without.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "../gcs/src/detail/self_intersection.h"
#include "../gcs/src/detail/untangle.h"
#include "edgefront/error.h"
#include "edgefront/mesh.h"
#include "edgefront/mesh_stats.h"
#include "shapes/shapes.h"
#include "gcs/evaluation.h"
#include "gcs/reconstructor.h"

namespace {

using edgefront::Mesh;
using edgefront::Vec3;
using edgefront::VertexHandle;

// An nu x nw grid of cells in the plane through `origin` spanned by u and w, added to m.
std::vector<VertexHandle> add_grid(Mesh& m, int nu, int nw, const Vec3& origin, const Vec3& u, const Vec3& w) {
  std::vector<VertexHandle> v;
  for (int j = 0; j <= nw; ++j)
    for (int i = 0; i <= nu; ++i) v.push_back(m.add_vertex(origin + double(i) * u + double(j) * w));
  const auto at = [&](int i, int j) { return v[static_cast<std::size_t>(j * (nu + 1) + i)]; };
  for (int j = 0; j < nw; ++j) {
    for (int i = 0; i < nu; ++i) {
      m.add_face(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      m.add_face(at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
  }
  return v;
}

std::vector<VertexHandle> add_grid(Mesh& m, int n, const Vec3& origin, const Vec3& u, const Vec3& w) {
  return add_grid(m, n, n, origin, u, w);
}

// No sample anywhere near: hole fills are refused.
gcs::detail::CloudHit far_cloud(const Vec3&) {
  gcs::detail::CloudHit h;
  h.distance = std::numeric_limits<double>::infinity();
  return h;
}

bool same_mesh(const Mesh& a, const Mesh& b) {
  if (a.n_vertices() != b.n_vertices() || a.n_faces() != b.n_faces()) return false;
  for (auto v : a.vertices())
    if (a.point(v) != b.point(VertexHandle(v.idx()))) return false;
  for (auto f : a.faces()) {
    auto ia = a.cfv_begin(f);
    auto ib = b.cfv_begin(edgefront::FaceHandle(f.idx()));
    for (int k = 0; k < 3; ++k, ++ia, ++ib)
      if (ia->idx() != ib->idx()) return false;
  }
  return true;
}

gcs::detail::UntangleParams params(double max_move) {
  gcs::detail::UntangleParams p;
  p.max_move = max_move;
  p.fill_support = 1.0;
  return p;
}

TEST(GcsUntangle, AVertexPokedThroughTheLayerBelowIsSmoothedBack) {
  // Two parallel 8 x 8 sheets 0.3 apart; the middle vertex of the upper one is pulled 0.6 down,
  // through the lower one (what the loop does to a thin shell's wall).
  Mesh m;
  const std::vector<VertexHandle> upper = add_grid(m, 8, Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0));
  add_grid(m, 8, Vec3(0.3, 0.3, -0.3), Vec3(1, 0, 0), Vec3(0, 1, 0));
  const VertexHandle poked = upper[4 * 9 + 4];
  m.point(poked) = Vec3(4, 4, -0.6);
  const std::size_t crossing = gcs::count_self_intersections(m);
  ASSERT_GT(crossing, 0u);
  const std::size_t faces = m.n_faces();
  const gcs::detail::UntangleReport r = gcs::detail::untangle(m, far_cloud, params(1.0));
  EXPECT_EQ(r.pairs_before, crossing);
  EXPECT_EQ(r.pairs_after, 0u);
  EXPECT_EQ(gcs::count_self_intersections(m), 0u);
  EXPECT_GE(r.vertices_moved, 1u);
  EXPECT_EQ(r.faces_removed, 0u);
  EXPECT_EQ(m.n_faces(), faces);
  EXPECT_GT(m.point(poked)[2], -0.3);  // back above the lower sheet
  // max_move bounds the way back: with 0.2 the vertex stays below the lower sheet, so the pair
  // is cut out instead (one face of each pair) and nothing crosses either.
  Mesh bounded;
  const std::vector<VertexHandle> u2 = add_grid(bounded, 8, Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0));
  add_grid(bounded, 8, Vec3(0.3, 0.3, -0.3), Vec3(1, 0, 0), Vec3(0, 1, 0));
  bounded.point(u2[4 * 9 + 4]) = Vec3(4, 4, -0.6);
  const gcs::detail::UntangleReport b = gcs::detail::untangle(bounded, far_cloud, params(0.2));
  EXPECT_LE(bounded.point(u2[4 * 9 + 4])[2], -0.39);
  EXPECT_GT(b.faces_removed, 0u);
  EXPECT_EQ(b.pairs_after, 0u);
  EXPECT_EQ(gcs::count_self_intersections(bounded), 0u);
}

TEST(GcsUntangle, FlatSheetsThatCrossAreCutApartAndStayManifold) {
  // A vertical strip through a horizontal sheet: both flat, so smoothing cannot part them (the
  // strip shrinks within its plane) and the crossing faces are cut out; the strip's faces touch
  // its border, the sheet's interior faces do not, so only the strip loses faces.
  Mesh m;
  add_grid(m, 6, Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0));
  add_grid(m, 1, Vec3(2.5, 2.2, -0.5), Vec3(0, 1.6, 0), Vec3(0, 0, 1));
  const std::size_t sheet_faces = 72;
  ASSERT_GT(gcs::count_self_intersections(m), 0u);
  const Mesh copy = m;
  const gcs::detail::UntangleReport r = gcs::detail::untangle(m, far_cloud, params(0.5));
  EXPECT_EQ(r.pairs_after, 0u);
  EXPECT_GT(r.faces_removed, 0u);
  EXPECT_EQ(r.holes_filled, 0u);
  for (auto v : m.vertices()) EXPECT_LE((m.point(v) - copy.point(v)).norm(), 0.5);  // max_move
  m.garbage_collection();
  EXPECT_EQ(m.n_faces(), sheet_faces);  // the strip's two faces went, the sheet is whole
  const gcs::MeshValidity v = gcs::mesh_validity(m);
  EXPECT_TRUE(v.edge_manifold && v.vertex_manifold);
  EXPECT_EQ(v.self_intersecting_pairs.value_or(1), 0u);
  // Deterministic: the same input gives the same mesh.
  Mesh again = copy;
  gcs::detail::untangle(again, far_cloud, params(0.5));
  again.garbage_collection();
  EXPECT_TRUE(same_mesh(m, again));
}

TEST(GcsUntangle, ACutThatWouldSplitTheMeshIsNotMade) {
  // A strip one cell wide and 12 long with a blade (one quad) through its middle cell: cutting
  // the strip's faces there would cut the strip in two pieces of more than 8 faces, so the
  // blade's faces go instead, and the strip stays whole.
  Mesh m;
  add_grid(m, 12, 1, Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0));
  add_grid(m, 1, 1, Vec3(6.5, -0.6, -0.5), Vec3(0, 2.2, 0), Vec3(0, 0, 1));
  ASSERT_GT(gcs::count_self_intersections(m), 0u);
  const gcs::detail::UntangleReport r = gcs::detail::untangle(m, far_cloud, params(0.5));
  EXPECT_EQ(r.pairs_after, 0u);
  m.garbage_collection();
  EXPECT_EQ(m.n_faces(), 24u);  // the whole strip, no blade
  const gcs::MeshValidity v = gcs::mesh_validity(m);
  EXPECT_EQ(v.components, 1u);
  EXPECT_TRUE(v.edge_manifold && v.vertex_manifold);
  EXPECT_EQ(v.self_intersecting_pairs.value_or(1), 0u);
}

// A closed cube of half side h around c (12 triangles, facing out), added to m.
void add_cube(Mesh& m, const Vec3& c, double h) {
  std::vector<VertexHandle> v;
  for (int k = 0; k < 8; ++k) v.push_back(m.add_vertex(c + h * Vec3(k & 1 ? 1 : -1, k & 2 ? 1 : -1, k & 4 ? 1 : -1)));
  const int faces[12][3] = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                            {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  for (const auto& f : faces) m.add_face(v[f[0]], v[f[1]], v[f[2]]);
}

TEST(GcsUntangle, EachHoleIsFilledOnItsOwnWhenItsFillCrossesNothing) {
  // An 8 x 8 sheet on z = 0 with a one-cell hole at (1, 1), pierced at cell (5, 5) by a small
  // closed cube (the cloud: the cube's surface, and the plane 0.5 off the sheet, so the sheet's
  // two faces there are the ones farther from the samples and are cut). The cut leaves a hole the
  // cube passes through: filling it crosses the cube again, so it stays open. The other hole's
  // fill crosses nothing and is kept (before, one crossing fill made the step keep none).
  Mesh m;
  add_grid(m, 8, Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0));
  for (auto f : m.faces()) {
    const Vec3 c = gcs::detail::centroid(m, f);
    if (c[0] > 1 && c[0] < 2 && c[1] > 1 && c[1] < 2) m.delete_face(f, false);
  }
  m.garbage_collection();
  add_cube(m, Vec3(5.5, 5.5, 0), 0.3);
  ASSERT_EQ(edgefront::compute_stats(m).border_loops, 2u);
  ASSERT_GT(gcs::count_self_intersections(m), 0u);
  const auto cloud = [](const Vec3& p) {
    Vec3 q;
    for (int k = 0; k < 3; ++k) q[k] = std::abs(p[k] - 5.5 * (k < 2)) - 0.3;
    const Vec3 out(std::max(q[0], 0.0), std::max(q[1], 0.0), std::max(q[2], 0.0));
    const double cube = std::abs(out.norm() + std::min(std::max({q[0], q[1], q[2]}), 0.0));
    gcs::detail::CloudHit h;
    h.distance = std::min(cube, std::abs(p[2]) + 0.5);
    h.normal = Vec3(0, 0, 1);
    return h;
  };
  const gcs::detail::UntangleReport r = gcs::detail::untangle(m, cloud, params(0.05));
  EXPECT_EQ(r.pairs_after, 0u);
  EXPECT_EQ(r.faces_removed, 2u);  // the sheet's two faces in the cube's cell
  EXPECT_EQ(r.holes_filled, 1u);
  m.garbage_collection();
  const edgefront::MeshStats s = edgefront::compute_stats(m);
  EXPECT_EQ(s.border_loops, 2u);  // the sheet's outer border and the cut hole
  EXPECT_EQ(s.components, 2u);
  EXPECT_EQ(gcs::count_self_intersections(m), 0u);
}

TEST(GcsUntangle, AMeshWithoutCrossingsIsUntouchedAndBadParametersAreRefused) {
  Mesh m;
  add_grid(m, 5, Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0));
  m.point(VertexHandle(14)) += Vec3(0.2, 0.1, 0.3);  // not flat, but nothing crosses
  const Mesh before = m;
  const gcs::detail::UntangleReport r = gcs::detail::untangle(m, far_cloud, params(1.0));
  EXPECT_EQ(r.pairs_before, 0u);
  EXPECT_EQ(r.vertices_moved + r.faces_removed + r.holes_filled, 0u);
  EXPECT_TRUE(same_mesh(m, before));
  for (const double bad : {0.0, -1.0, std::nan(""), std::numeric_limits<double>::infinity()})
    EXPECT_THROW(gcs::detail::untangle(m, far_cloud, params(bad)), edgefront::InvalidInput);
  gcs::detail::UntangleParams p = params(1.0);
  p.relax_rate = 0;
  EXPECT_THROW(gcs::detail::untangle(m, far_cloud, p), edgefront::InvalidInput);
  p.relax_rate = 1.5;
  EXPECT_THROW(gcs::detail::untangle(m, far_cloud, p), edgefront::InvalidInput);
  p = params(1.0);
  p.relax_iterations = -1;
  EXPECT_THROW(gcs::detail::untangle(m, far_cloud, p), edgefront::InvalidInput);
  p = params(1.0);
  p.pull_back_passes = -1;
  EXPECT_THROW(gcs::detail::untangle(m, far_cloud, p), edgefront::InvalidInput);
  p = params(1.0);
  p.min_face_cos = 1.5;
  EXPECT_THROW(gcs::detail::untangle(m, far_cloud, p), edgefront::InvalidInput);
}

TEST(GcsUntangle, AThinVaultShellIsReturnedWithoutCrossings) {
  // t/R 0.1 at 300 vertices: the loop's mesh has crossing faces (the walls are about an edge
  // apart); the returned mesh has none, with resolve_self_intersections on (the default).
  edgefront::shapes::SampleOptions so;
  so.points = 3000;
  so.seed = 1;
  so.shape.thickness = 0.1;
  const edgefront::PointCloud shell = edgefront::shapes::sample("vault-shell", so);
  const auto run = [&](bool resolve) {
    gcs::ReconstructOptions o;
    o.target_vertices = 300;
    o.seed = 2;
    o.post.resolve_self_intersections = resolve;
    return gcs::Reconstructor(shell, o).run();
  };
  const gcs::ReconstructResult kept = run(false);
  const std::size_t crossing = gcs::count_self_intersections(kept.mesh);
  ASSERT_GT(crossing, 0u);  // the case exercises the step
  EXPECT_EQ(kept.crossing_pairs_found, 0u);
  const gcs::ReconstructResult r = run(true);
  EXPECT_EQ(r.crossing_pairs_found, crossing);
  EXPECT_EQ(r.crossing_pairs_left, 0u);
  const gcs::MeshValidity v = gcs::mesh_validity(r.mesh);
  EXPECT_EQ(v.self_intersecting_pairs.value_or(1), 0u);
  EXPECT_TRUE(v.edge_manifold && v.vertex_manifold);
  EXPECT_EQ(v.components, gcs::mesh_validity(kept.mesh).components);
  EXPECT_LE(v.border_loops, gcs::mesh_validity(kept.mesh).border_loops);
}

}  // namespace
