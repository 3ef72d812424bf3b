// Tests of the spatial (Morton) ordering used by the GCS loop for memory locality
// (gcs/src/detail/spatial_order.h): the mesh keeps its connectivity, orientation and circulation
// starts under renumbering; and a reconstruction that renumbers its mesh (no operations
// registered, more than 2048 vertices) stays valid and deterministic.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <iterator>
#include <map>
#include <set>
#include <vector>

#include "../gcs/src/detail/spatial_order.h"
#include "edgefront/error.h"
#include "edgefront/mesh_stats.h"
#include "shapes/shapes.h"
#include "gcs/reconstructor.h"

namespace {

using edgefront::Mesh;
using edgefront::Vec3;
using edgefront::VertexHandle;

using Tri = std::array<std::array<double, 3>, 3>;

std::array<double, 3> key(const Vec3& p) { return {p[0], p[1], p[2]}; }

// Each face as its corner positions, rotated so that the smallest comes first (orientation kept).
std::multiset<Tri> oriented_faces(const Mesh& mesh) {
  std::multiset<Tri> out;
  for (auto f : mesh.faces()) {
    Tri t;
    int k = 0;
    for (auto v : mesh.fv_range(f)) t[k++] = key(mesh.point(v));
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    out.insert(t);
  }
  return out;
}

// Per vertex position: the positions of its neighbours in circulation order.
std::map<std::array<double, 3>, std::vector<std::array<double, 3>>> rings(const Mesh& mesh) {
  std::map<std::array<double, 3>, std::vector<std::array<double, 3>>> out;
  for (auto v : mesh.vertices()) {
    auto& r = out[key(mesh.point(v))];
    for (auto u : mesh.vv_range(v)) r.push_back(key(mesh.point(u)));
  }
  return out;
}

TEST(SpatialOrder, MortonOrderIsASortedPermutationWithTiesByIndex) {
  std::vector<Vec3> pts;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      for (int k = 0; k < 4; ++k) pts.emplace_back(3 - i, j, 3 - k);
  pts.push_back(Vec3(0, 0, 0));  // a duplicate of an earlier point: comes right after it
  const std::vector<size_t> order = gcs::detail::morton_order(pts);
  ASSERT_EQ(order.size(), pts.size());
  std::vector<size_t> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  for (size_t i = 0; i < sorted.size(); ++i) ASSERT_EQ(sorted[i], i);
  // The first two are the two copies of the box's lowest corner, the original first.
  EXPECT_EQ(pts[order[0]], Vec3(0, 0, 0));
  EXPECT_EQ(order[1], pts.size() - 1);
  // Z-order over a 4^3 lattice: each aligned 2x2x2 block is 8 consecutive entries.
  for (size_t b = 0; b < order.size() - 1; b += 8) {
    Vec3 lo = pts[order[b + 1]], hi = lo;
    for (size_t i = b + 1; i < std::min(order.size(), b + 9); ++i) {
      lo.minimize(pts[order[i]]);
      hi.maximize(pts[order[i]]);
    }
    EXPECT_EQ((hi - lo).max(), 1.0) << "block " << b / 8;
  }
  EXPECT_TRUE(gcs::detail::morton_order({}).empty());
}

// Large sets are sorted by a radix sort, small ones by a comparison sort: the two must agree. A
// 6000-point set (radix) and its 3000-point subset (comparison) with the same bounding box (both
// hold its two corners), hence the same codes: the subset keeps its relative order.
TEST(SpatialOrder, MortonOrderOfALargeSetAgreesWithASmallOne) {
  std::vector<Vec3> pts{Vec3(0, 0, 0), Vec3(1, 1, 1)};
  unsigned x = 12345;
  const auto next = [&x] {
    x = x * 1103515245u + 12345u;
    return static_cast<double>((x >> 8) % 1000) / 999.0;
  };
  while (pts.size() < 5000) pts.emplace_back(next(), next(), next());
  for (size_t i = 0; i < 1000; ++i) pts.push_back(pts[(i * 7) % 5000]);  // duplicates: ties by index
  std::vector<size_t> subset_ids;  // in increasing index order, with both corners
  for (size_t i = 0; i < pts.size(); ++i)
    if (i < 2 || i % 2 == 1) subset_ids.push_back(i);
  std::vector<Vec3> subset;
  for (const size_t i : subset_ids) subset.push_back(pts[i]);
  ASSERT_GE(pts.size(), 4096u);
  ASSERT_LT(subset.size(), 4096u);
  const std::vector<size_t> big = gcs::detail::morton_order(pts), small = gcs::detail::morton_order(subset);
  std::vector<char> in_subset(pts.size(), 0);
  for (const size_t i : subset_ids) in_subset[i] = 1;
  std::vector<size_t> restricted;
  for (const size_t i : big)
    if (in_subset[i]) restricted.push_back(i);
  ASSERT_EQ(restricted.size(), small.size());
  for (size_t k = 0; k < small.size(); ++k) ASSERT_EQ(restricted[k], subset_ids[small[k]]) << "position " << k;
}

TEST(SpatialOrder, StrideSubsampleTakesOnePerRunAtASeededPosition) {
  using gcs::detail::stride_subsample;
  std::vector<size_t> all(50);
  for (size_t i = 0; i < all.size(); ++i) all[i] = i;
  EXPECT_EQ(stride_subsample(50, 50, 3), all);  // within the limit: everything
  EXPECT_EQ(stride_subsample(50, 1000, 3), all);
  std::set<size_t> offsets;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const std::vector<size_t> s = stride_subsample(1005, 100, seed);  // runs of 11
    EXPECT_EQ(s, stride_subsample(1005, 100, seed));
    ASSERT_FALSE(s.empty());
    EXPECT_LE(s.size(), 100u);
    EXPECT_GE(s.size(), 91u);
    EXPECT_LT(s[0], 11u);
    for (size_t k = 1; k < s.size(); ++k) EXPECT_EQ(s[k] - s[k - 1], 11u);
    EXPECT_LT(s.back(), 1005u);
    offsets.insert(s[0]);
  }
  EXPECT_GE(offsets.size(), 5u) << "the seed chooses the position in the run";
  EXPECT_THROW(stride_subsample(10, 0, 1), edgefront::InternalError);
}

// A 128 x 128 lattice (16,384 points) shuffled, in coarse Morton order, subsampled to at most
// 1,024 (as the reconstructor's query subsample): every 16 x 16 tile (256 points, 16 expected
// picks) gets between 8 and 24 (a uniform random choice of 1,024 points misses that range in some
// of the 64 tiles for about 4 seeds in 5; standard deviation 3.9).
TEST(SpatialOrder, CoarseMortonStrideSubsampleIsEvenAndDeterministic) {
  std::vector<Vec3> pts;
  for (int i = 0; i < 128; ++i)
    for (int j = 0; j < 128; ++j) pts.emplace_back(i, j, 0.25 * ((i * 7 + j * 3) % 5));
  for (size_t i = pts.size() - 1; i > 0; --i) std::swap(pts[i], pts[(i * 2654435761u) % (i + 1)]);
  const std::vector<size_t> order = gcs::detail::coarse_morton_order(pts);
  EXPECT_EQ(order, gcs::detail::coarse_morton_order(pts));
  ASSERT_EQ(std::set<size_t>(order.begin(), order.end()).size(), pts.size());
  EXPECT_LT(*std::max_element(order.begin(), order.end()), pts.size());
  const auto subsample = [&](std::uint64_t seed) {
    std::vector<size_t> s = gcs::detail::stride_subsample(pts.size(), 1024, seed);
    for (size_t& i : s) i = order[i];
    return s;
  };
  for (std::uint64_t seed : {1u, 2u, 7u}) {
    const std::vector<size_t> s = subsample(seed);
    EXPECT_EQ(s, subsample(seed));
    EXPECT_LE(s.size(), 1024u);
    EXPECT_GE(s.size(), 1000u);
    EXPECT_EQ(std::set<size_t>(s.begin(), s.end()).size(), s.size());
    std::map<std::pair<int, int>, int> tiles;
    for (const size_t i : s) {
      ASSERT_LT(i, pts.size());
      ++tiles[{static_cast<int>(pts[i][0]) / 16, static_cast<int>(pts[i][1]) / 16}];
    }
    EXPECT_EQ(tiles.size(), 64u) << "seed " << seed;
    for (const auto& [tile, count] : tiles) {
      EXPECT_GE(count, 8) << "tile " << tile.first << "," << tile.second << " seed " << seed;
      EXPECT_LE(count, 24) << "tile " << tile.first << "," << tile.second << " seed " << seed;
    }
  }
  EXPECT_NE(subsample(1), subsample(2));
  EXPECT_TRUE(gcs::detail::coarse_morton_order({}).empty());
}

TEST(SpatialOrder, RenumberingKeepsTheMeshAndDropsDeletedElements) {
  Mesh mesh = edgefront::shapes::hemisphere(16, 6);  // has a border
  // Delete a few faces (and the vertices they leave isolated): the renumbering drops them.
  for (int i = 0; i < 5; ++i) mesh.delete_face(edgefront::FaceHandle(3 * i + 7), true);
  const auto faces_before = oriented_faces(mesh);
  const auto rings_before = rings(mesh);
  const edgefront::MeshStats stats_before = edgefront::compute_stats(mesh);
  const size_t live_v = static_cast<size_t>(std::distance(mesh.vertices().begin(), mesh.vertices().end()));
  const size_t nv_old = mesh.n_vertices(), nf_old = mesh.n_faces();

  const gcs::MeshRenumbering map = gcs::detail::renumber_spatially(mesh);
  ASSERT_EQ(map.vertex.size(), nv_old);
  ASSERT_EQ(map.face.size(), nf_old);
  EXPECT_EQ(mesh.n_vertices(), live_v);  // deleted elements gone
  for (auto v : mesh.vertices()) EXPECT_FALSE(mesh.status(v).deleted());
  EXPECT_EQ(oriented_faces(mesh), faces_before);
  EXPECT_EQ(rings(mesh), rings_before);  // same neighbours, same circulation start and order
  const edgefront::MeshStats s = edgefront::compute_stats(mesh);
  EXPECT_EQ(s.border_loops, stats_before.border_loops);
  EXPECT_EQ(s.components, stats_before.components);
  EXPECT_EQ(s.nonmanifold_vertices, stats_before.nonmanifold_vertices);
  // Vertex indices follow the Morton order of the positions.
  std::vector<Vec3> pos;
  for (auto v : mesh.vertices()) pos.push_back(mesh.point(v));
  const std::vector<size_t> order = gcs::detail::morton_order(pos);
  for (size_t i = 0; i < order.size(); ++i) EXPECT_EQ(order[i], i);
  // Boundary vertices keep a boundary outgoing halfedge (OpenMesh's invariant).
  for (auto v : mesh.vertices())
    if (mesh.is_boundary(v)) {
      EXPECT_TRUE(mesh.is_boundary(mesh.halfedge_handle(v)));
    }
  // The maps send every live old element to a distinct new one.
  std::set<int> seen;
  for (const int n : map.vertex)
    if (n >= 0) {
      EXPECT_TRUE(seen.insert(n).second);
    }
  EXPECT_EQ(seen.size(), live_v);
}

// 2200 vertices without operations: the loop renumbers its mesh at 2048 vertices (10 basic steps
// per split keep the test fast).
TEST(SpatialOrder, ReconstructionThatRenumbersStaysValidAndDeterministic) {
  edgefront::shapes::SampleOptions so;
  so.points = 2500;  // at least one point per target vertex
  const edgefront::PointCloud cloud = edgefront::shapes::sample("torus", so);
  gcs::ReconstructOptions o;
  o.target_vertices = 2200;
  o.growth.steps_per_split = 10;
  o.growth.batch_splits = 50;
  o.progress_interval = 400;
  gcs::Reconstructor r(cloud, o);
  size_t checks = 0;
  const gcs::ReconstructResult a = r.run([&](const gcs::Progress&) {
    r.validate();
    ++checks;
    return true;
  });
  EXPECT_GE(checks, 5u);
  r.validate();
  EXPECT_EQ(a.stop_reason, gcs::StopReason::target_reached);
  const gcs::ReconstructResult b = gcs::reconstruct(cloud, o);
  ASSERT_EQ(a.mesh.n_vertices(), b.mesh.n_vertices());
  ASSERT_EQ(a.mesh.n_faces(), b.mesh.n_faces());
  for (auto v : a.mesh.vertices()) ASSERT_EQ(a.mesh.point(v), b.mesh.point(v));
  const edgefront::MeshStats s = edgefront::compute_stats(a.mesh);
  EXPECT_EQ(s.nonmanifold_vertices, 0u);
  // Renumbered at 2048 vertices: the two ends of an edge are mostly close in the numbering (for a
  // random numbering the median index gap is about 0.29 n).
  std::vector<int> gaps;
  for (auto e : a.mesh.edges()) {
    const auto h = a.mesh.halfedge_handle(e, 0);
    gaps.push_back(std::abs(a.mesh.from_vertex_handle(h).idx() - a.mesh.to_vertex_handle(h).idx()));
  }
  std::nth_element(gaps.begin(), gaps.begin() + gaps.size() / 2, gaps.end());
  EXPECT_LT(gaps[gaps.size() / 2], static_cast<int>(a.mesh.n_vertices() / 20)) << "median index gap over the edges";
}

}  // namespace
