#include "edgefront/vertex_twins.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "edgefront/error.h"
#include "shapes/shapes.h"

namespace {

using edgefront::Mesh;
using edgefront::VertexHandle;

// Two triangles that touched at one point, stored as two fans: vertices 0 and 3 coincide.
Mesh bowtie() {
  Mesh mesh;
  const VertexHandle a = mesh.add_vertex({0, 0, 0});
  const VertexHandle b = mesh.add_vertex({1, 0, 0});
  const VertexHandle c = mesh.add_vertex({0, 1, 0});
  const VertexHandle a2 = mesh.add_vertex({0, 0, 0});
  const VertexHandle d = mesh.add_vertex({-1, 0, 0});
  const VertexHandle e = mesh.add_vertex({0, -1, 0});
  mesh.add_face(a, b, c);
  mesh.add_face(a2, d, e);
  return mesh;
}

TEST(VertexTwins, LinkedGroupIsARing) {
  Mesh mesh = bowtie();
  EXPECT_FALSE(edgefront::has_twins(mesh));
  EXPECT_TRUE(edgefront::twins_of(mesh, VertexHandle(0)).empty());
  EXPECT_EQ(edgefront::TwinRing(mesh).next(VertexHandle(0)), VertexHandle(0));

  edgefront::link_twins(mesh, {VertexHandle(0), VertexHandle(3)});
  EXPECT_TRUE(edgefront::has_twins(mesh));
  EXPECT_EQ(edgefront::twins_of(mesh, VertexHandle(0)), std::vector<VertexHandle>{VertexHandle(3)});
  EXPECT_EQ(edgefront::twins_of(mesh, VertexHandle(3)), std::vector<VertexHandle>{VertexHandle(0)});
  EXPECT_TRUE(edgefront::twins_of(mesh, VertexHandle(1)).empty());
  const edgefront::TwinRing ring(mesh);
  EXPECT_TRUE(ring.any());
  EXPECT_EQ(ring.next(VertexHandle(0)), VertexHandle(3));
  EXPECT_EQ(ring.next(VertexHandle(3)), VertexHandle(0));
  EXPECT_EQ(ring.next(VertexHandle(4)), VertexHandle(4));

  const Mesh copy = mesh;  // the links travel with the mesh
  EXPECT_EQ(edgefront::twins_of(copy, VertexHandle(3)), std::vector<VertexHandle>{VertexHandle(0)});

  edgefront::clear_twins(mesh);
  EXPECT_FALSE(edgefront::has_twins(mesh));
  EXPECT_FALSE(edgefront::TwinRing(mesh).any());
}

TEST(VertexTwins, ThreeTwinsInRingOrder) {
  Mesh mesh = bowtie();
  const VertexHandle extra = mesh.add_vertex({0, 0, 0});
  edgefront::link_twins(mesh, {VertexHandle(0), VertexHandle(3), extra});
  EXPECT_EQ(edgefront::twins_of(mesh, VertexHandle(3)), (std::vector<VertexHandle>{extra, VertexHandle(0)}));
}

TEST(VertexTwins, BadGroupsAreRefused) {
  Mesh mesh = bowtie();
  EXPECT_THROW(edgefront::link_twins(mesh, {VertexHandle(0)}), edgefront::InvalidInput);
  EXPECT_THROW(edgefront::link_twins(mesh, {VertexHandle(0), VertexHandle(0)}), edgefront::InvalidInput);
  EXPECT_THROW(edgefront::link_twins(mesh, {VertexHandle(0), VertexHandle(99)}), edgefront::InvalidInput);
  EXPECT_FALSE(edgefront::has_twins(mesh));  // nothing half-applied
  edgefront::link_twins(mesh, {VertexHandle(0), VertexHandle(3)});
  EXPECT_THROW(edgefront::link_twins(mesh, {VertexHandle(3), VertexHandle(1)}), edgefront::InvalidInput);
  EXPECT_EQ(edgefront::twins_of(mesh, VertexHandle(1)).size(), 0u);
}

// The faces' corners as (original vertex) triples: what a split must keep.
std::vector<std::array<int, 3>> corners(const Mesh& mesh, const std::vector<VertexHandle>& origin, size_t n0) {
  std::vector<std::array<int, 3>> out;
  for (edgefront::FaceHandle f : mesh.faces()) {
    std::array<int, 3> c{};
    int k = 0;
    for (VertexHandle v : mesh.fv_range(f)) {
      c[k++] = static_cast<size_t>(v.idx()) < n0 ? v.idx() : origin[static_cast<size_t>(v.idx()) - n0].idx();
    }
    out.push_back(c);
  }
  return out;
}

TEST(VertexTwins, SplitPinchedVerticesOfAMeshBuiltInCode) {
  Mesh mesh;  // two triangles sharing only vertex 0 (one OpenMesh vertex with two fans)
  const VertexHandle a = mesh.add_vertex({0, 0, 0});
  const VertexHandle b = mesh.add_vertex({1, 0, 0}), c = mesh.add_vertex({0, 1, 0});
  const VertexHandle d = mesh.add_vertex({-1, 0, 0}), e = mesh.add_vertex({0, -1, 0});
  mesh.add_face(a, b, c);
  mesh.add_face(a, d, e);
  ASSERT_FALSE(mesh.is_manifold(a));
  const auto before = corners(mesh, {}, mesh.n_vertices());
  const std::vector<VertexHandle> origin = edgefront::split_pinched_vertices(mesh);
  ASSERT_EQ(origin, std::vector<VertexHandle>{a});
  ASSERT_EQ(mesh.n_vertices(), 6u);
  EXPECT_EQ(corners(mesh, origin, 5), before);  // the same faces, one corner moved to the copy
  for (VertexHandle v : mesh.vertices()) EXPECT_TRUE(mesh.is_manifold(v)) << v.idx();
  EXPECT_EQ(mesh.point(VertexHandle(5)), mesh.point(a));
  EXPECT_EQ(edgefront::twins_of(mesh, a), std::vector<VertexHandle>{VertexHandle(5)});
  EXPECT_EQ(mesh.valence(a), 2u);
  EXPECT_EQ(mesh.valence(VertexHandle(5)), 2u);
  // Each fan's border is a loop of its own again.
  for (edgefront::HalfedgeHandle h : mesh.halfedges()) {
    if (!mesh.is_boundary(h)) continue;
    EXPECT_EQ(mesh.next_halfedge_handle(mesh.next_halfedge_handle(mesh.next_halfedge_handle(h))), h);
  }
  EXPECT_TRUE(edgefront::split_pinched_vertices(mesh).empty());  // nothing left to split
}

TEST(VertexTwins, SplitKeepsExistingGroupsAndFaceIndices) {
  // A 2x2 grid with triangles hung on two of its corners; one corner already has a twin.
  Mesh mesh = edgefront::shapes::grid(edgefront::shapes::GridOptions{.cells = 2});
  const size_t n0 = mesh.n_vertices(), f0 = mesh.n_faces();
  std::vector<VertexHandle> corner;
  for (VertexHandle v : mesh.vertices()) {
    const auto p = mesh.point(v);
    if (std::abs(std::abs(p[0]) - 1) < 1e-12 && std::abs(std::abs(p[1]) - 1) < 1e-12) corner.push_back(v);
  }
  ASSERT_EQ(corner.size(), 4u);
  for (int k = 0; k < 2; ++k) {
    const auto p = mesh.point(corner[static_cast<size_t>(k)]);
    const VertexHandle t1 = mesh.add_vertex(p + edgefront::Vec3(1, 0.2, 0) * p[0]);
    const VertexHandle t2 = mesh.add_vertex(p + edgefront::Vec3(1, 0.8, 0) * p[0]);
    ASSERT_TRUE(mesh.add_face(corner[static_cast<size_t>(k)], t1, t2).is_valid());
    ASSERT_FALSE(mesh.is_manifold(corner[static_cast<size_t>(k)]));
  }
  const VertexHandle loose = mesh.add_vertex(mesh.point(corner[1]));  // an isolated twin
  edgefront::link_twins(mesh, {corner[1], loose});
  const size_t n1 = mesh.n_vertices();
  const std::vector<VertexHandle> origin = edgefront::split_pinched_vertices(mesh);
  ASSERT_EQ(origin, (std::vector<VertexHandle>{corner[0], corner[1]}));
  EXPECT_EQ(mesh.n_faces(), f0 + 2);
  EXPECT_EQ(edgefront::twins_of(mesh, corner[0]), std::vector<VertexHandle>{VertexHandle(static_cast<int>(n1))});
  const auto group = edgefront::twins_of(mesh, corner[1]);
  EXPECT_EQ(group, (std::vector<VertexHandle>{VertexHandle(static_cast<int>(n1) + 1), loose}));
  for (VertexHandle v : mesh.vertices()) EXPECT_TRUE(mesh.is_manifold(v)) << v.idx();
  EXPECT_LT(static_cast<size_t>(corner[0].idx()), n0);
}
}  // namespace
