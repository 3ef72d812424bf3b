// GeodesicRingTable and the fast mode / Dijkstra run on it.

#include "edgefront/geodesic_ring_table.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "edgefront/error.h"
#include "shapes/shapes.h"
#include "front_test_util.h"

namespace {

using namespace edgefront;

void expect_same_field(const DistanceField& a, const DistanceField& b, const std::string& what) {
  ASSERT_EQ(a.distance.size(), b.distance.size()) << what;
  for (size_t v = 0; v < a.distance.size(); ++v) ASSERT_EQ(a.distance[v], b.distance[v]) << what << " vertex " << v;
  ASSERT_EQ(a.direction.size(), b.direction.size()) << what;
  for (size_t v = 0; v < a.direction.size(); ++v) ASSERT_EQ(a.direction[v], b.direction[v]) << what << " vertex " << v;
  EXPECT_EQ(a.order, b.order) << what;
  EXPECT_EQ(a.stop, b.stop) << what;
}

// The neighbours are the vertex's neighbours in the mesh's circulation order (table and mesh
// indices), with their edge lengths; the corners are the angles between consecutive edges with their cosines and sines; the
// angle sum is 2 pi at interior vertices of a flat grid (flat), and a border ring starts after its
// gap.
TEST(GeodesicRingTable, LayoutMatchesTheMesh) {
  const Mesh meshes[] = {
      shapes::grid(shapes::GridOptions{.cells = 6, .variant = shapes::GridVariant::jittered, .seed = 2}),
      shapes::bumpy_sphere(1)};
  for (const Mesh& mesh : meshes) {
    const bool planar = &mesh == &meshes[0];
    const GeodesicRingTable table(mesh);
    ASSERT_EQ(table.n_vertices(), mesh.n_vertices());
    size_t edges = 0;
    for (VertexHandle v : mesh.vertices()) {
      const int x = table.index(v);
      ASSERT_EQ(table.vertex(x), v);
      const auto edge = table.edges(x);
      const auto corners = table.corners(x);
      const GeodesicRingTable::Ring& info = table.ring(x);
      const size_t m = info.size;
      ASSERT_EQ(edge.size(), m);
      ASSERT_EQ(corners.size(), m);
      edges += m;
      EXPECT_EQ(info.point, mesh.point(v));
      size_t k = 0;
      for (VertexHandle y : mesh.vv_range(v)) {
        ASSERT_LT(k, m);
        EXPECT_EQ(edge[k].v, table.index(y));
        EXPECT_EQ(edge[k].vertex, y.idx());
        EXPECT_NEAR(edge[k].len, (mesh.point(y) - mesh.point(v)).norm(), 1e-15);
        EXPECT_EQ(corners[k].e, mesh.point(y) - mesh.point(v));
        ++k;
      }
      EXPECT_EQ(k, m);
      EXPECT_EQ(info.closed, !mesh.is_boundary(v));
      double sum = 0;
      for (size_t i = 0; i < m; ++i) {
        const auto& c = corners[i];
        const size_t nx = (i + 1) % m;
        if (c.face_after) {
          EXPECT_NEAR(c.angle_after, std::acos(OpenMesh::dot(c.e, corners[nx].e) / (edge[i].len * edge[nx].len)), 1e-12);
          EXPECT_NEAR(c.cos_after, std::cos(c.angle_after), 1e-12);
          EXPECT_NEAR(c.sin_after, std::sin(c.angle_after), 1e-12);
          sum += c.angle_after;
        } else {
          EXPECT_FALSE(info.closed);
          EXPECT_EQ(nx, info.first);  // the gap is just before the first edge
        }
      }
      EXPECT_NEAR(info.total, sum, 1e-12);
      EXPECT_NEAR(info.cos_total, std::cos(sum), 1e-12);
      EXPECT_NEAR(info.sin_total, std::sin(sum), 1e-12);
      if (planar && info.closed) {
        EXPECT_TRUE(info.flat) << v.idx();
      }
      if (!info.closed) {
        EXPECT_FALSE(info.flat);
      }
    }
    EXPECT_EQ(edges, mesh.n_halfedges());
    EXPECT_GE(table.memory_bytes(), edges * (sizeof(GeodesicRingTable::Edge) + sizeof(GeodesicRingTable::Corner)));
  }
  const GeodesicRingTable sphere(shapes::icosphere(1));
  EXPECT_FALSE(sphere.ring(sphere.index(VertexHandle(0))).flat);  // a sphere's vertex is not flat
}

// The table's order depends on the positions only (a shuffled copy of the mesh gets the same
// points in the same order), `index` and `vertex` are inverse permutations, and neighbours lie
// close in it: the median index distance across an edge is a small fraction of a shuffled order's.
TEST(GeodesicRingTable, LocalityOrder) {
  const Mesh mesh = shapes::bumpy_sphere(4);
  const size_t n = mesh.n_vertices();
  ASSERT_GT(n, 2000u);
  std::vector<int> perm(n);  // shuffled index -> mesh index
  for (size_t i = 0; i < n; ++i) perm[i] = static_cast<int>(i);
  std::mt19937_64 rng(3);
  std::shuffle(perm.begin(), perm.end(), rng);
  Mesh shuffled;
  std::vector<VertexHandle> to(n);
  for (size_t i = 0; i < n; ++i) to[static_cast<size_t>(perm[i])] = shuffled.add_vertex(mesh.point(VertexHandle(perm[i])));
  for (FaceHandle f : mesh.faces()) {
    std::vector<VertexHandle> fv;
    for (VertexHandle v : mesh.fv_range(f)) fv.push_back(to[static_cast<size_t>(v.idx())]);
    ASSERT_TRUE(shuffled.add_face(fv).is_valid());
  }
  const GeodesicRingTable a(mesh), b(shuffled);
  std::vector<int> gap_table, gap_shuffled;
  for (size_t i = 0; i < n; ++i) {
    const int x = static_cast<int>(i);
    ASSERT_EQ(a.index(a.vertex(x)), x);
    ASSERT_EQ(a.ring(x).point, b.ring(x).point);
    ASSERT_EQ(to[static_cast<size_t>(a.vertex(x).idx())], b.vertex(x));
    for (const GeodesicRingTable::Edge& e : a.edges(x)) gap_table.push_back(std::abs(e.v - x));
    const VertexHandle s = to[i];
    for (VertexHandle y : shuffled.vv_range(s)) gap_shuffled.push_back(std::abs(y.idx() - s.idx()));
  }
  for (auto* g : {&gap_table, &gap_shuffled}) std::nth_element(g->begin(), g->begin() + g->size() / 2, g->end());
  const int median_table = gap_table[gap_table.size() / 2], median_shuffled = gap_shuffled[gap_shuffled.size() / 2];
  EXPECT_LT(median_table, median_shuffled / 20) << median_table << " " << median_shuffled;
  // Same fields on both meshes, vertex for vertex (the rings start at other edges: to round-off).
  const DistanceField fa = geodesic_distance(mesh, a, FrontSource::vertex(VertexHandle(5)));
  const DistanceField fb = geodesic_distance(shuffled, b, FrontSource::vertex(to[5]));
  for (size_t v = 0; v < n; ++v) {
    ASSERT_NEAR(fa.distance[v], fb.distance[static_cast<size_t>(to[v].idx())], 1e-12 * (1 + fa.distance[v])) << v;
  }
}

// One table serves many queries (vertex, several vertices, points; max_distance, target, no
// directions) with the same fields as the per-call fast mode, which builds its own table.
TEST(GeodesicRingTable, ManyQueriesOnOneTable) {
  for (const Mesh& mesh : {shapes::torus(20, 8), shapes::hemisphere(16, 6), shapes::vault_shell(8)}) {
    const GeodesicRingTable table(mesh);
    std::mt19937_64 rng(5);
    for (int trial = 0; trial < 6; ++trial) {
      const auto sources = eftest::random_vertices(mesh, rng, 1 + trial % 3);
      DistanceOptions o{.method = DistanceMethod::Fast};
      if (trial == 1) o.max_distance = 0.5;
      if (trial == 2) o.target = sources.size() > 1 ? sources[1] : VertexHandle(7);
      if (trial == 3) o.directions = false;
      const FrontSource src = FrontSource::from_vertices(sources);
      expect_same_field(geodesic_distance(mesh, table, src, o), geodesic_distance(mesh, src, o), "vertices");
      const std::vector<SurfacePoint> pts{{FaceHandle(trial * 7), {0.2, 0.3, 0.5}}};
      expect_same_field(geodesic_distance(mesh, table, pts, o), geodesic_distance(mesh, pts, o), "points");
    }
  }
}

// Dijkstra over the table: the same field as over the mesh's halfedges.
TEST(GeodesicRingTable, DijkstraOnTheTable) {
  const Mesh mesh = shapes::bumpy_sphere(3);
  ASSERT_GT(mesh.n_vertices(), 200u);
  const GeodesicRingTable table(mesh);
  for (const DistanceOptions& o : {DistanceOptions{}, DistanceOptions{.max_distance = 0.7},
                                   DistanceOptions{.target = VertexHandle(30)}}) {
    const FrontSource src = FrontSource::from_vertices({VertexHandle(3), VertexHandle(200)});
    const DistanceField t = dijkstra_distance(mesh, table, src, o);
    expect_same_field(t, dijkstra_distance(mesh, src, o), "dijkstra");
    EXPECT_EQ(t.peak_working_memory_bytes, dijkstra_distance(mesh, src, o).peak_working_memory_bytes);
  }
  // A loop source runs the mesh's Dijkstra.
  const Mesh cyl = shapes::open_cylinder(12, 4);
  std::vector<HalfedgeHandle> loop;
  for (HalfedgeHandle h : cyl.halfedges()) {
    if (cyl.is_boundary(h)) {
      HalfedgeHandle g = h;
      do {
        loop.push_back(cyl.opposite_halfedge_handle(g));  // the inner side of the border
        g = cyl.next_halfedge_handle(g);
      } while (g != h);
      std::reverse(loop.begin(), loop.end());
      break;
    }
  }
  const FrontSource ls = FrontSource::from_halfedges(loop);
  expect_same_field(dijkstra_distance(cyl, GeodesicRingTable(cyl), ls), dijkstra_distance(cyl, ls), "loop");
}

// A table built before the mesh changed is refused; bad sources and options through the table.
TEST(GeodesicRingTable, StaleTableAndBadInput) {
  Mesh mesh = shapes::icosphere(1);
  const GeodesicRingTable table(mesh);
  EXPECT_TRUE(table.matches(mesh));
  const FrontSource src = FrontSource::vertex(VertexHandle(0));
  EXPECT_THROW(geodesic_distance(mesh, table, FrontSource::vertex(VertexHandle(1000))), InvalidInput);
  EXPECT_THROW(geodesic_distance(mesh, table, src, {.max_distance = std::nan("")}), InvalidInput);
  EXPECT_THROW(geodesic_distance(mesh, table, src, {.target = VertexHandle(-3)}), InvalidInput);
  EXPECT_THROW(geodesic_distance(mesh, table, std::vector<SurfacePoint>{}), InvalidInput);
  EXPECT_THROW(geodesic_distance(mesh, table, std::vector<SurfacePoint>{{FaceHandle(0), {0.5, 0.5, 0.5}}}),
               InvalidInput);
  EXPECT_THROW(dijkstra_distance(mesh, table, src, {.max_distance = -1}), InvalidInput);

  const Mesh other = shapes::icosphere(2);
  EXPECT_FALSE(table.matches(other));
  EXPECT_THROW(geodesic_distance(other, table, src), InvalidInput);
  EXPECT_THROW(dijkstra_distance(other, table, src), InvalidInput);
  const VertexHandle a = mesh.add_vertex(Vec3(2, 0, 0));
  EXPECT_THROW(geodesic_distance(mesh, table, src), InvalidInput);
  mesh.delete_vertex(a);
  mesh.garbage_collection();
  EXPECT_TRUE(table.matches(mesh));  // the same counts again
  mesh.delete_face(FaceHandle(0), false);
  mesh.garbage_collection();
  EXPECT_FALSE(table.matches(mesh));
  EXPECT_THROW(geodesic_distance(mesh, table, std::vector<SurfacePoint>{{FaceHandle(1), {1, 0, 0}}}), InvalidInput);
  try {
    geodesic_distance(other, table, src);
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("rebuild"), std::string::npos) << e.what();
  }
}

// A non-manifold vertex: the table marks it, a query refuses it when it settles (not before).
TEST(GeodesicRingTable, NonManifoldVertex) {
  Mesh mesh = shapes::grid(shapes::GridOptions{.cells = 2});
  VertexHandle corner;
  for (VertexHandle v : mesh.vertices())
    if ((mesh.point(v) - Vec3(1, 1, 0)).norm() < 1e-9) corner = v;
  ASSERT_TRUE(corner.is_valid());
  const VertexHandle t1 = mesh.add_vertex(Vec3(2, 1.2, 0));
  const VertexHandle t2 = mesh.add_vertex(Vec3(2, 1.8, 0));
  ASSERT_TRUE(mesh.add_face(corner, t1, t2).is_valid());
  const GeodesicRingTable table(mesh);
  EXPECT_TRUE(table.ring(table.index(corner)).non_manifold);
  EXPECT_THROW(geodesic_distance(mesh, table, FrontSource::vertex(t1)), TopologyError);
  const DistanceField f =
      geodesic_distance(mesh, table, FrontSource::vertex(VertexHandle(0)), {.max_distance = 0.4});
  EXPECT_EQ(f.stop, DistanceStop::MaxDistance);  // the corner is not reached: no error
}

}  // namespace
