// Lifetime safety: classes that keep a `const Mesh&` refuse temporaries at compile time, and the
// options that point at a caller's object say so in their type (`Borrowed`).

#include <gtest/gtest.h>

#include <type_traits>

#include "edgefront/borrowed.h"
#include "edgefront/connection_path.h"
#include "edgefront/minimal_distance_front.h"
#include "edgefront/minimal_edge_front.h"
#include "edgefront/vertex_front.h"
#include "edgefront/vertex_twins.h"
#include "render/scene.h"
#include "twist/detect.h"

namespace {

using edgefront::Mesh;

static_assert(std::is_constructible_v<edgefront::MinimalDistanceFront, const Mesh&>);
static_assert(!std::is_constructible_v<edgefront::MinimalDistanceFront, Mesh&&>);
static_assert(!std::is_constructible_v<edgefront::MinimalDistanceFront, const Mesh&&>);
static_assert(std::is_constructible_v<edgefront::MinimalEdgeFront, const Mesh&>);
static_assert(!std::is_constructible_v<edgefront::MinimalEdgeFront, Mesh&&>);
static_assert(!std::is_constructible_v<edgefront::MinimalEdgeFront, Mesh&&, edgefront::MinimalEdgeFrontOptions>);
static_assert(std::is_constructible_v<edgefront::VertexFront, const Mesh&>);
static_assert(!std::is_constructible_v<edgefront::VertexFront, Mesh&&>);
static_assert(std::is_constructible_v<edgefront::ConnectionPathFinder, const Mesh&>);
static_assert(!std::is_constructible_v<edgefront::ConnectionPathFinder, Mesh&&>);
static_assert(!std::is_constructible_v<edgefront::TwinRing, Mesh&&>);

// Options holding a pointer to a caller's object borrow it, and say so.
static_assert(std::is_same_v<decltype(twist::DetectOptions::reference), edgefront::Borrowed<const twist::ReferenceNormals>>);
static_assert(std::is_same_v<decltype(twist::IncrementalOptions::face_grid),
                             edgefront::Borrowed<const twist::FaceGrid>>);
static_assert(std::is_same_v<decltype(edgefront::render::Scene::mesh), edgefront::Borrowed<const Mesh>>);

TEST(Lifetime, BorrowedReadsLikeThePointer) {
  const int x = 7;
  edgefront::Borrowed<const int> b;
  EXPECT_FALSE(b);
  EXPECT_TRUE(b == nullptr);
  b = &x;
  EXPECT_TRUE(b);
  EXPECT_EQ(*b, 7);
  EXPECT_EQ(b.get(), &x);
  const int* raw = b;
  EXPECT_EQ(raw, &x);
}

}  // namespace
