// Tests of the GCS loop's neighbour cache (gcs/src/detail/neighbor_cache.h): a line holds the
// vertex's neighbours in mesh.voh_range order with the face flags, also at borders; a ring changed
// by a flip is caught by check() until the changed vertices are invalidated; rings longer than
// the line are not cached.

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "../gcs/src/detail/neighbor_cache.h"
#include "edgefront/error.h"
#include "shapes/shapes.h"

namespace {

using edgefront::Mesh;
using edgefront::VertexHandle;

void expect_line_matches(const Mesh& mesh, gcs::detail::NeighborCache& cache, VertexHandle v) {
  const gcs::detail::NeighborCache::Line* l = cache.get(mesh, v);
  ASSERT_NE(l, nullptr);
  int e = 0;
  for (auto h : mesh.voh_range(v)) {
    ASSERT_LT(e, l->count);
    EXPECT_EQ(l->nb[e], mesh.to_vertex_handle(h).idx());
    EXPECT_EQ(l->has_face(e), mesh.face_handle(h).is_valid());
    ++e;
  }
  EXPECT_EQ(e, l->count);
}

TEST(NeighborCache, LinesFollowTheHalfedgeOrderWithBorderFlags) {
  const Mesh mesh = edgefront::shapes::hemisphere(12, 6);  // open: border vertices have a faceless halfedge
  gcs::detail::NeighborCache cache;
  cache.resize(mesh.n_vertices());
  size_t border = 0;
  for (auto v : mesh.vertices()) {
    expect_line_matches(mesh, cache, v);
    border += mesh.is_boundary(v);
  }
  EXPECT_GT(border, 0u);
  EXPECT_NO_THROW(cache.check(mesh));
}

TEST(NeighborCache, AFlipIsCaughtUntilItsVerticesAreInvalidated) {
  Mesh mesh = edgefront::shapes::icosphere(2);
  gcs::detail::NeighborCache cache;
  cache.resize(mesh.n_vertices());
  for (auto v : mesh.vertices()) ASSERT_NE(cache.get(mesh, v), nullptr);
  const auto e = *mesh.edges().begin();
  ASSERT_TRUE(mesh.is_flip_ok(e));
  const auto h0 = mesh.halfedge_handle(e, 0), h1 = mesh.halfedge_handle(e, 1);
  const std::vector<VertexHandle> touched = {mesh.to_vertex_handle(h0), mesh.to_vertex_handle(h1),
                                             mesh.to_vertex_handle(mesh.next_halfedge_handle(h0)),
                                             mesh.to_vertex_handle(mesh.next_halfedge_handle(h1))};
  mesh.flip(e);
  EXPECT_THROW(cache.check(mesh), edgefront::InternalError);
  for (auto v : touched) cache.invalidate(v.idx());
  EXPECT_NO_THROW(cache.check(mesh));
  for (auto v : touched) expect_line_matches(mesh, cache, v);
  // invalidate_all drops every line: refilled from the mesh on the next get().
  cache.invalidate_all();
  EXPECT_NO_THROW(cache.check(mesh));
  for (auto v : mesh.vertices()) expect_line_matches(mesh, cache, v);
}

TEST(NeighborCache, LongRingsAreNotCached) {
  // The apex of a 20-sided cone fan has valence 20 > kMaxValence.
  Mesh mesh;
  const VertexHandle apex = mesh.add_vertex({0, 0, 1});
  std::vector<VertexHandle> rim;
  for (int k = 0; k < 20; ++k) rim.push_back(mesh.add_vertex({std::cos(k * 0.314159), std::sin(k * 0.314159), 0}));
  for (int k = 0; k < 20; ++k) mesh.add_face(apex, rim[k], rim[(k + 1) % 20]);
  gcs::detail::NeighborCache cache;
  cache.resize(mesh.n_vertices());
  EXPECT_EQ(cache.get(mesh, apex), nullptr);
  expect_line_matches(mesh, cache, rim[0]);
  EXPECT_THROW(cache.get(mesh, VertexHandle(static_cast<int>(mesh.n_vertices()))), edgefront::InternalError);
}

}  // namespace
