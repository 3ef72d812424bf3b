#include "edgefront/vertex_front.h"

#include <gtest/gtest.h>

#include <random>

#include "edgefront/error.h"
#include "edgefront/minimal_edge_front.h"
#include "front_test_util.h"

namespace {

using namespace edgefront;

class VfOnShapes : public ::testing::TestWithParam<eftest::NamedMesh> {};

TEST_P(VfOnShapes, LevelsAreHopDistancesAndEachVertexOnce) {
  const Mesh mesh = GetParam().make();
  std::mt19937_64 rng(11);
  VertexFront front(mesh);
  std::vector<int> level(mesh.n_vertices()), times(mesh.n_vertices());
  front.set_enclosed_callback([&](VertexHandle v, int l) {
    level[v.idx()] = l;
    ++times[v.idx()];
  });
  for (int trial = 0; trial < 100; ++trial) {
    const auto sources = eftest::random_vertices(mesh, rng, 1 + trial % 3);
    std::fill(level.begin(), level.end(), -1);
    std::fill(times.begin(), times.end(), 0);
    front.reset(FrontSource::from_vertices(sources));
    front.validate();
    if (trial % 2 == 0) {
      while (front.step()) front.validate();
    } else {
      while (front.advance_level()) front.validate();
    }
    EXPECT_TRUE(front.exhausted());
    const auto bfs = eftest::bfs_levels(mesh, sources);
    for (size_t v = 0; v < mesh.n_vertices(); ++v) {
      ASSERT_EQ(level[v], bfs[v]) << GetParam().name << " trial " << trial << " vertex " << v;
      ASSERT_EQ(times[v], bfs[v] >= 0 ? 1 : 0);
    }
  }
}

TEST_P(VfOnShapes, AgreesWithTheEdgeFrontAtEveryCutoff) {
  const Mesh mesh = GetParam().make();
  std::mt19937_64 rng(5);
  for (int trial = 0; trial < 10; ++trial) {
    const auto src = FrontSource::from_vertices(eftest::random_vertices(mesh, rng, 1));
    for (int k : {0, 1, 3, -1}) {
      EXPECT_EQ(vertex_front_levels(mesh, src, k), edge_front_levels(mesh, src, k)) << "k=" << k;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Shapes, VfOnShapes, ::testing::ValuesIn(eftest::small_shapes()),
                         eftest::shape_test_name);

TEST(Vf, LoopSourceExpandsOnlyAhead) {
  const Mesh mesh = shapes::open_cylinder(16, 8);
  // The ring of vertices at the middle height, counter-clockwise seen from +z.
  std::vector<VertexHandle> ring;
  for (VertexHandle v : mesh.vertices()) {
    if (std::abs(mesh.point(v)[2] - 1.0) < 1e-9) ring.push_back(v);
  }
  ASSERT_EQ(ring.size(), 16u);
  std::sort(ring.begin(), ring.end(), [&](VertexHandle a, VertexHandle b) {
    return std::atan2(mesh.point(a)[1], mesh.point(a)[0]) < std::atan2(mesh.point(b)[1], mesh.point(b)[0]);
  });
  for (LoopSide side : {LoopSide::Left, LoopSide::Right}) {
    const FrontSource src = loop_from_vertices(mesh, ring, side);
    const auto levels = vertex_front_levels(mesh, src);
    EXPECT_EQ(levels, eftest::loop_bfs_levels(mesh, src.loop));
    EXPECT_EQ(levels, edge_front_levels(mesh, src));
    int above = 0, below = 0;
    for (VertexHandle v : mesh.vertices()) {
      if (levels[v.idx()] > 0) (mesh.point(v)[2] > 1.0 ? above : below)++;
    }
    EXPECT_TRUE((above == 0) != (below == 0)) << "one side only: above " << above << " below " << below;
  }
}

TEST(Vf, BadSourcesAreRefused) {
  const Mesh mesh = shapes::icosphere(1);
  VertexFront front(mesh);
  EXPECT_THROW(front.reset(FrontSource{}), InvalidInput);
  EXPECT_THROW(front.reset(FrontSource::vertex(VertexHandle(-1))), InvalidInput);
  EXPECT_THROW(front.reset(FrontSource::vertex(VertexHandle(static_cast<int>(mesh.n_vertices())))), InvalidInput);
}

TEST(Vf, MemoryFollowsTheFront) {
  const Mesh mesh = shapes::grid(shapes::GridOptions{.cells = 60});
  VertexFront front(mesh);
  front.reset(FrontSource::vertex(VertexHandle(static_cast<int>(mesh.n_vertices() / 2))));
  front.run();
  EXPECT_LT(front.peak_front_size(), 10 * std::sqrt(static_cast<double>(mesh.n_vertices())));
}

}  // namespace
