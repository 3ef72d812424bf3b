#include "edgefront/vertex_twins.h"

#include <gtest/gtest.h>

#include "edgefront/error.h"

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

}  // namespace
