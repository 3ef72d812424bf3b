// The Delaunay flips of the GCS result (gcs/src/detail/sample_projection.h delaunay_flips,
// PostProcessOptions::delaunay_flips): long diagonals between coplanar faces are flipped, near-Delaunay
// edges where that evens the valences, creases
// stay, positions and validity are kept, and the reconstruction's smallest angles do not get worse.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "../gcs/src/detail/sample_projection.h"
#include "edgefront/error.h"
#include "edgefront/mesh.h"
#include "shapes/shapes.h"
#include "gcs/evaluation.h"
#include "gcs/reconstructor.h"

namespace {

using edgefront::Mesh;
using edgefront::Vec3;
using edgefront::VertexHandle;

// A sheared grid (cells are parallelograms with a long and a short diagonal), every cell split
// along its long diagonal: each of those diagonals has opposite angles summing to > 180 degrees.
Mesh sheared_grid(int n) {
  Mesh m;
  std::vector<VertexHandle> v;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) v.push_back(m.add_vertex(Vec3(i + 0.8 * j, j, 0)));
  const auto at = [&](int i, int j) { return v[static_cast<std::size_t>(j * (n + 1) + i)]; };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      m.add_face(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      m.add_face(at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
  }
  return m;
}

// Interior edges whose two opposite angles sum to more than 180 degrees.
// Interior edges whose opposite angles sum to more than pi + slack.
int non_delaunay_edges(const Mesh& m, double slack = 0) {
  const auto angle = [](const Vec3& apex, const Vec3& a, const Vec3& b) {
    const Vec3 u = a - apex, w = b - apex;
    return std::atan2((u % w).norm(), u | w);
  };
  int count = 0;
  for (auto e : m.edges()) {
    if (m.is_boundary(e)) continue;
    const auto h0 = m.halfedge_handle(e, 0), h1 = m.halfedge_handle(e, 1);
    const Vec3 p = m.point(m.from_vertex_handle(h0)), q = m.point(m.to_vertex_handle(h0));
    const Vec3 r = m.point(m.to_vertex_handle(m.next_halfedge_handle(h0)));
    const Vec3 t = m.point(m.to_vertex_handle(m.next_halfedge_handle(h1)));
    count += angle(r, p, q) + angle(t, q, p) > std::numbers::pi + slack + 1e-9;
  }
  return count;
}

TEST(GcsDelaunayFlips, LongDiagonalsOfAFlatGridAreFlippedAndNothingElseChanges) {
  Mesh m = sheared_grid(6);
  const Mesh before = m;
  const int bad = non_delaunay_edges(m);
  ASSERT_EQ(bad, 36);
  const double angle_before = gcs::mesh_validity(before).min_angle_deg;
  const std::size_t flips = gcs::detail::delaunay_flips(m, 0.9, 10);
  EXPECT_GE(flips, static_cast<std::size_t>(bad));
  EXPECT_EQ(non_delaunay_edges(m), 0);
  for (auto v : m.vertices()) EXPECT_EQ(m.point(v), before.point(v));
  const gcs::MeshValidity a = gcs::mesh_validity(m);
  EXPECT_EQ(m.n_faces(), before.n_faces());
  EXPECT_TRUE(a.edge_manifold && a.vertex_manifold);
  EXPECT_EQ(a.border_loops, 1u);
  EXPECT_EQ(a.self_intersecting_pairs.value_or(1), 0u);
  EXPECT_GT(a.min_angle_deg, angle_before + 10);
}

// Two faces on a long edge p-q with far-apart opposite vertices r and t (a thin quad split the
// wrong way), with fans around p and q so both keep valence > 3 after a flip.
Mesh thin_quad(double lift) {
  Mesh m;
  const VertexHandle p = m.add_vertex(Vec3(0, 0, 0)), q = m.add_vertex(Vec3(4, 0, 0));
  const VertexHandle r = m.add_vertex(Vec3(2, 0.2, lift)), t = m.add_vertex(Vec3(2, -0.4, 0));
  const VertexHandle a = m.add_vertex(Vec3(-1, 1, 0)), b = m.add_vertex(Vec3(-1, -1, 0));
  const VertexHandle c = m.add_vertex(Vec3(5, 1, 0)), d = m.add_vertex(Vec3(5, -1, 0));
  m.add_face(p, q, r);
  m.add_face(q, p, t);
  m.add_face(p, r, a);
  m.add_face(p, a, b);
  m.add_face(p, b, t);
  m.add_face(q, c, r);
  m.add_face(q, d, c);
  m.add_face(q, t, d);
  return m;
}

bool has_edge(const Mesh& m, int a, int b) {
  for (auto h : m.voh_range(VertexHandle(a)))
    if (m.to_vertex_handle(h).idx() == b) return true;
  return false;
}

TEST(GcsDelaunayFlips, ACreaseIsNotFlippedWhereTheFlatCaseIs) {
  Mesh flat = thin_quad(0.0);
  ASSERT_TRUE(has_edge(flat, 0, 1));
  EXPECT_GE(gcs::detail::delaunay_flips(flat, 0.9, 10), 1u);
  EXPECT_FALSE(has_edge(flat, 0, 1));
  EXPECT_TRUE(has_edge(flat, 2, 3));
  // r lifted: the faces on p-q meet at about 60 degrees; the angles at r and t still sum to
  // more than 180 degrees, but the crease stays.
  Mesh crease = thin_quad(0.35);
  gcs::detail::delaunay_flips(crease, 0.9, 10);
  EXPECT_TRUE(has_edge(crease, 0, 1));
  // Any flip is allowed with min_dihedral_cos -1.
  gcs::detail::delaunay_flips(crease, -1.0, 10);
  EXPECT_FALSE(has_edge(crease, 0, 1));
}

// A separate triangle pierces the thin quad: the flipped faces would be in a self-intersecting
// pair, so the flip is undone and p-q stays (the rest of the mesh may still flip).
TEST(GcsDelaunayFlips, AFlipWhoseFacesIntersectAnotherFaceIsUndone) {
  Mesh m = thin_quad(0.0);
  const VertexHandle a = m.add_vertex(Vec3(2.3, 0.05, -1)), b = m.add_vertex(Vec3(2.33, 0.11, 1));
  const VertexHandle c = m.add_vertex(Vec3(2.27, 0.11, 1));
  m.add_face(a, b, c);
  ASSERT_EQ(gcs::mesh_validity(m).self_intersecting_pairs.value_or(0), 1u);
  gcs::detail::delaunay_flips(m, 0.9, 10);
  EXPECT_TRUE(has_edge(m, 0, 1));
  EXPECT_EQ(gcs::mesh_validity(m).self_intersecting_pairs.value_or(0), 1u);
}

TEST(GcsDelaunayFlips, BadParametersAreRejected) {
  Mesh m = sheared_grid(2);
  EXPECT_THROW(gcs::detail::delaunay_flips(m, 1.5, 10), edgefront::InvalidInput);
  EXPECT_THROW(gcs::detail::delaunay_flips(m, std::nan(""), 10), edgefront::InvalidInput);
  EXPECT_THROW(gcs::detail::delaunay_flips(m, 0.9, -1), edgefront::InvalidInput);
  EXPECT_EQ(non_delaunay_edges(m), 4);  // nothing flipped by the rejected calls
}

// Sum over vertices of (valence - 6)^2, (valence - 4)^2 on a border.
int valence_deviation(const Mesh& m) {
  int sum = 0;
  for (auto v : m.vertices()) {
    const int d = static_cast<int>(m.valence(v)) - (m.is_boundary(v) ? 4 : 6);
    sum += d * d;
  }
  return sum;
}

// On a reconstruction: same vertex count and genus, no self-intersections, the smallest angle not
// worse than without the flips, and some flips made (the loop leaves thin faces).
TEST(GcsDelaunayFlips, ReconstructionKeepsTopologyAndImprovesTheSmallestAngle) {
  edgefront::shapes::SampleOptions so;
  so.points = 3000;
  const edgefront::PointCloud cloud = edgefront::shapes::sample("torus", so);
  gcs::ReconstructOptions o;
  o.target_vertices = 300;
  o.seed = 3;
  const Mesh with = gcs::reconstruct(cloud, o).mesh;
  o.post.delaunay_flips = false;
  const Mesh without = gcs::reconstruct(cloud, o).mesh;
  const gcs::MeshValidity a = gcs::mesh_validity(with), b = gcs::mesh_validity(without);
  EXPECT_EQ(with.n_vertices(), without.n_vertices());
  EXPECT_EQ(a.genus, b.genus);
  EXPECT_EQ(a.border_loops, b.border_loops);
  EXPECT_EQ(a.self_intersecting_pairs.value_or(1), 0u);
  EXPECT_TRUE(a.edge_manifold && a.vertex_manifold);
  EXPECT_GE(a.min_angle_deg, b.min_angle_deg);
  // Beyond the 30-degree band where the valences decide, every coplanar enough edge is flipped; and
  // the valences come nearer 6.
  const double band = 30.0 * std::numbers::pi / 180.0;
  EXPECT_LE(non_delaunay_edges(with, band), non_delaunay_edges(without, band));
  EXPECT_LE(valence_deviation(with), valence_deviation(without));
}

// A square grid split along one diagonal direction has valence 6 inside, and every diagonal's
// opposite angles sum to exactly 180 degrees. One diagonal turned the other way makes valences
// 5, 5, 7, 7 at no gain in angle: the flips turn it back (valence rule, inside the band), and
// nothing else (any other flip would take valences away from 6).
TEST(GcsDelaunayFlips, AFlipThatEvensTheValencesIsMadeInsideTheBand) {
  const int n = 6;
  Mesh m;
  std::vector<VertexHandle> v;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) v.push_back(m.add_vertex(Vec3(i, j, 0)));
  const auto at = [&](int i, int j) { return v[static_cast<std::size_t>(j * (n + 1) + i)]; };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      m.add_face(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      m.add_face(at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
  }
  const int regular = valence_deviation(m);
  const Mesh before = m;
  edgefront::EdgeHandle diagonal;
  for (auto h : m.voh_range(at(3, 3)))
    if (m.to_vertex_handle(h) == at(4, 4)) diagonal = m.edge_handle(h);
  ASSERT_TRUE(diagonal.is_valid());
  m.flip(diagonal);
  ASSERT_EQ(valence_deviation(m), regular + 4);
  EXPECT_EQ(gcs::detail::delaunay_flips(m, 0.9, 10), 1u);
  EXPECT_EQ(valence_deviation(m), regular);
  EXPECT_TRUE(has_edge(m, at(3, 3).idx(), at(4, 4).idx()));
  EXPECT_EQ(gcs::detail::delaunay_flips(m, 0.9, 10), 0u) << "nothing flips back and forth";
  Mesh untouched = before;
  EXPECT_EQ(gcs::detail::delaunay_flips(untouched, 0.9, 10), 0u) << "the regular grid has no flip to make";
}

}  // namespace
