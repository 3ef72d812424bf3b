// edgefront/arrays.h: the array views, the conversion (its report and index maps, pinched
// vertices, dropped faces, bad input), read_mesh through the same builder, and GeodesicSolver's
// entry points against the same queries on an edgefront::Mesh.

#include "edgefront/arrays.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <numeric>
#include <random>
#include <string>

#include "edgefront/error.h"
#include "edgefront/geodesic_ring_table.h"
#include "edgefront/mesh_io.h"
#include "edgefront/minimal_edge_front.h"
#include "shapes/shapes.h"
#include "edgefront/vertex_twins.h"

namespace {

using namespace edgefront;

/// A closed body (an icosphere) with three closed tetrahedra, each touching it at one vertex:
/// three pinched vertices. Rows: the sphere's faces, then 4 per tetrahedron.
MeshArrays pinched_body() {
  MeshArrays a = mesh_to_arrays(shapes::icosphere(2));
  const int body_vertices = static_cast<int>(a.n_vertices());
  for (int t = 0; t < 3; ++t) {
    const int apex = 10 * t + 3;  // a sphere vertex
    const Vec3 p(a.vertices[3 * apex], a.vertices[3 * apex + 1], a.vertices[3 * apex + 2]);
    const Vec3 n = p.normalized();
    const Vec3 u = OpenMesh::cross(std::abs(n[0]) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0), n).normalized();
    const Vec3 w = OpenMesh::cross(n, u);
    const int base = static_cast<int>(a.n_vertices());
    for (int k = 0; k < 3; ++k) {
      const double ang = 2 * std::numbers::pi * k / 3;
      const Vec3 q = p + 0.3 * n + 0.15 * (std::cos(ang) * u + std::sin(ang) * w);
      a.vertices.insert(a.vertices.end(), {q[0], q[1], q[2]});
    }
    // Outward tetrahedron apex, base, base+1, base+2 (the base triangle faces away from the body).
    const int b0 = base, b1 = base + 1, b2 = base + 2;
    for (std::array<int, 3> f : {std::array<int, 3>{apex, b1, b0}, {apex, b2, b1}, {apex, b0, b2}, {b0, b1, b2}})
      a.faces.insert(a.faces.end(), f.begin(), f.end());
  }
  EXPECT_EQ(a.n_vertices(), static_cast<size_t>(body_vertices) + 9);
  return a;
}

std::vector<std::array<int, 3>> rows_of(const std::vector<int>& f) {
  std::vector<std::array<int, 3>> out;
  for (size_t i = 0; i + 2 < f.size(); i += 3) out.push_back({f[i], f[i + 1], f[i + 2]});
  return out;
}

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "(no InvalidInput thrown)";
}

TEST(Arrays, RoundTripKeepsEveryIndex) {
  const Mesh sphere = shapes::icosphere(2);
  const MeshArrays a = mesh_to_arrays(sphere);
  ASSERT_EQ(a.n_vertices(), sphere.n_vertices());
  ASSERT_EQ(a.n_faces(), sphere.n_faces());
  const ArrayMesh m = mesh_from_arrays(a.vertices, a.faces);
  EXPECT_FALSE(m.report.changed());
  EXPECT_EQ(m.report.isolated_vertices, 0u);
  EXPECT_EQ(m.mesh.n_vertices(), sphere.n_vertices());
  const MeshArrays b = mesh_to_arrays(m.mesh);
  EXPECT_EQ(b.vertices, a.vertices);
  EXPECT_EQ(b.faces, a.faces);  // each row starts where it started: add_face(a, b, c) gives a b c
  for (size_t r = 0; r < a.n_faces(); ++r) {
    EXPECT_EQ(m.face_of_row[r], static_cast<int>(r));
    EXPECT_EQ(m.face_row[r], static_cast<int>(r));
  }
  // float and int64 views give the same mesh up to float rounding.
  std::vector<float> vf(a.vertices.begin(), a.vertices.end());
  std::vector<std::int64_t> f64(a.faces.begin(), a.faces.end());
  const MeshArrays c = mesh_to_arrays(mesh_from_arrays(vf, f64).mesh);
  EXPECT_EQ(c.faces, a.faces);
  for (size_t i = 0; i < a.vertices.size(); ++i) EXPECT_EQ(c.vertices[i], static_cast<double>(vf[i]));
}

TEST(Arrays, PinchedVerticesAreSplitIntoCopiesLinkedAsTwins) {
  const MeshArrays a = pinched_body();
  const size_t n = a.n_vertices();
  const ArrayMesh m = mesh_from_arrays(a.vertices, a.faces);
  EXPECT_EQ(m.report.pinched_vertices, 3u);
  EXPECT_EQ(m.report.vertex_copies, 3u);
  EXPECT_TRUE(m.report.dropped_faces.empty());
  ASSERT_EQ(m.mesh.n_vertices(), n + 3);
  ASSERT_EQ(m.mesh.n_faces(), a.n_faces());
  for (int t = 0; t < 3; ++t) {
    const int apex = 10 * t + 3;
    const VertexHandle copy(static_cast<int>(n) + t);  // copies in the order of their originals
    EXPECT_EQ(m.vertex_row[copy.idx()], apex);
    EXPECT_EQ(m.mesh.point(copy), m.mesh.point(VertexHandle(apex)));
    EXPECT_EQ(twins_of(m.mesh, VertexHandle(apex)), std::vector<VertexHandle>{copy});
    // The body's fan (lower rows) keeps the vertex; the tetrahedron's three faces use the copy.
    for (size_t r = a.n_faces() - 12 + 4 * t; r < a.n_faces() - 12 + 4 * t + 3; ++r) {
      const FaceHandle f(m.face_of_row[r]);
      bool uses_copy = false;
      for (VertexHandle v : m.mesh.fv_range(f)) uses_copy |= v == copy;
      EXPECT_TRUE(uses_copy) << "row " << r;
    }
  }
  for (VertexHandle v : m.mesh.vertices()) EXPECT_TRUE(m.mesh.is_manifold(v)) << v.idx();
  for (HalfedgeHandle h : m.mesh.halfedges()) EXPECT_FALSE(m.mesh.is_boundary(h));  // still closed
}

TEST(Arrays, ReadMeshSplitsPinchedVerticesWithTheSameBuilder) {
  const MeshArrays a = pinched_body();
  const std::filesystem::path file = std::filesystem::path(::testing::TempDir()) / "pinched_body.off";
  {
    std::ofstream out(file);
    out.precision(17);
    out << "OFF\n" << a.n_vertices() << " " << a.n_faces() << " 0\n";
    for (size_t i = 0; i < a.n_vertices(); ++i) out << a.vertices[3 * i] << " " << a.vertices[3 * i + 1] << " " << a.vertices[3 * i + 2] << "\n";
    for (size_t r = 0; r < a.n_faces(); ++r) out << "3 " << a.faces[3 * r] << " " << a.faces[3 * r + 1] << " " << a.faces[3 * r + 2] << "\n";
  }
  const MeshReadResult read = read_mesh(file);
  EXPECT_EQ(read.report.pinched_vertices, 3u);
  EXPECT_EQ(read.report.vertex_copies, 3u);
  EXPECT_EQ(read.report.faces_dropped_nonmanifold, 0u);
  bool warned = false;
  for (const std::string& w : read.report.warnings) warned |= w.find("3 pinched vertices were split") != std::string::npos;
  EXPECT_TRUE(warned);
  const ArrayMesh m = mesh_from_arrays(a.vertices, a.faces);
  const MeshArrays from_file = mesh_to_arrays(read.mesh), from_arrays = mesh_to_arrays(m.mesh);
  EXPECT_EQ(from_file.faces, from_arrays.faces);
  EXPECT_EQ(from_file.vertices, from_arrays.vertices);
  EXPECT_EQ(twins_of(read.mesh, VertexHandle(3)), twins_of(m.mesh, VertexHandle(3)));
  std::filesystem::remove(file);
}

TEST(Arrays, FacesAHalfEdgeMeshCannotHoldAreDroppedByRowOrRefused) {
  const std::vector<double> v = {0, 0, 0, 1, 0, 0, 0.5, 1, 0, 0.5, -1, 0, 0.5, 0, 1, 0.5, 0, -1};
  // Rows: 0 and 1 share edge 0-1 properly; 2 is a third face on it; 3 runs 1 -> 0 like row 1.
  const std::vector<int> f = {0, 1, 2, 1, 0, 3, 0, 1, 4, 5, 1, 0};
  const ArrayMesh m = mesh_from_arrays(v, f);
  ASSERT_EQ(m.report.dropped_faces.size(), 2u);
  EXPECT_EQ(m.report.dropped_faces[0].row, 2u);
  EXPECT_EQ(m.report.dropped_faces[0].reason, FaceDropReason::EdgeHasTwoFaces);
  EXPECT_EQ((m.report.dropped_faces[0].edge), (std::array<int, 2>{0, 1}));
  EXPECT_EQ(m.report.dropped_faces[1].row, 3u);
  EXPECT_EQ(m.face_of_row, (std::vector<int>{0, 1, -1, -1}));
  EXPECT_EQ(m.face_row, (std::vector<int>{0, 1}));
  EXPECT_EQ(m.report.isolated_vertices, 2u);  // 4 and 5 lost their only faces
  EXPECT_TRUE(m.report.changed());

  // The same direction as an earlier face, with the edge still free on the other side.
  const ArrayMesh same = mesh_from_arrays(v, std::vector<int>{0, 1, 2, 0, 1, 3});
  ASSERT_EQ(same.report.dropped_faces.size(), 1u);
  EXPECT_EQ(same.report.dropped_faces[0].reason, FaceDropReason::EdgeSameDirection);

  const std::string refused = message_of([&] { mesh_from_arrays(v, f, {.drop_nonmanifold_faces = false}); });
  EXPECT_NE(refused.find("row 2"), std::string::npos) << refused;
  EXPECT_NE(refused.find("0 -> 1"), std::string::npos) << refused;
  EXPECT_NE(refused.find("two faces"), std::string::npos) << refused;
}

TEST(Arrays, BadArraysAreRefusedNamingTheRow) {
  const std::vector<double> v = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  const std::vector<int> f = {0, 1, 2, 0, 2, 3};
  auto expect = [](const std::string& msg, std::initializer_list<const char*> parts) {
    for (const char* p : parts) EXPECT_NE(msg.find(p), std::string::npos) << "'" << p << "' not in: " << msg;
  };
  std::vector<double> nan = v;
  nan[7] = std::numeric_limits<double>::quiet_NaN();
  expect(message_of([&] { mesh_from_arrays(nan, f); }), {"vertices", "row 2", "column 1", "nan"});
  std::vector<double> inf = v;
  inf[9] = -std::numeric_limits<double>::infinity();
  expect(message_of([&] { mesh_from_arrays(inf, f); }), {"row 3", "column 0", "-inf"});
  std::vector<double> huge = v;
  huge[2] = 1e200;
  expect(message_of([&] { mesh_from_arrays(huge, f); }), {"row 0", "column 2", "overflow"});
  std::vector<float> fnan(v.begin(), v.end());
  fnan[4] = std::numeric_limits<float>::quiet_NaN();
  expect(message_of([&] { mesh_from_arrays(fnan, f); }), {"row 1", "column 1"});
  expect(message_of([&] { mesh_from_arrays(v, std::vector<int>{0, 1, 2, 0, 2, 4}); }), {"faces", "row 1", "index 4", "[0, 4)"});
  expect(message_of([&] { mesh_from_arrays(v, std::vector<int>{0, 1, 2, -1, 2, 3}); }), {"row 1", "index -1"});
  expect(message_of([&] { mesh_from_arrays(v, std::vector<std::int64_t>{0, 1, 2, 0, 2, std::int64_t{1} << 40}); }),
         {"row 1", "1099511627776"});
  expect(message_of([&] { mesh_from_arrays(v, std::vector<int>{0, 1, 2, 3, 2, 3}); }), {"row 1", "repeats vertex 3"});
  expect(message_of([&] { mesh_from_arrays(std::vector<double>(v.begin(), v.end() - 1), f); }), {"vertices", "11 values", "n x 3"});
  expect(message_of([&] { mesh_from_arrays(VertexArrayView(v.data(), 3, 4), f); }), {"vertices", "rows of 4"});
  expect(message_of([&] { mesh_from_arrays(v, FaceArrayView(f.data(), 3, 2)); }), {"faces", "rows of 2"});
  expect(message_of([&] { mesh_from_arrays(std::vector<double>{}, f); }), {"vertices", "empty"});
  expect(message_of([&] { mesh_from_arrays(v, std::vector<int>{}); }), {"faces", "empty"});
}

/// Expects `m` to be, element for element, the mesh that OpenMesh's add_face builds from the same
/// vertices and the same corners row by row (the builder emulates add_face on flat arrays).
void expect_add_face_mesh(const Mesh& m) {
  const MeshArrays a = mesh_to_arrays(m);
  Mesh ref;
  for (size_t i = 0; i < a.n_vertices(); ++i) ref.add_vertex(Vec3(a.vertices[3 * i], a.vertices[3 * i + 1], a.vertices[3 * i + 2]));
  for (size_t f = 0; f < a.n_faces(); ++f) {
    ASSERT_TRUE(ref.add_face(VertexHandle(a.faces[3 * f]), VertexHandle(a.faces[3 * f + 1]), VertexHandle(a.faces[3 * f + 2])).is_valid());
  }
  ref.update_face_normals();
  ASSERT_EQ(m.n_vertices(), ref.n_vertices());
  ASSERT_EQ(m.n_edges(), ref.n_edges());
  ASSERT_EQ(m.n_faces(), ref.n_faces());
  for (HalfedgeHandle h : ref.halfedges()) {
    ASSERT_EQ(m.to_vertex_handle(h), ref.to_vertex_handle(h)) << "halfedge " << h.idx();
    ASSERT_EQ(m.next_halfedge_handle(h), ref.next_halfedge_handle(h)) << "halfedge " << h.idx();
    ASSERT_EQ(m.prev_halfedge_handle(h), ref.prev_halfedge_handle(h)) << "halfedge " << h.idx();
    ASSERT_EQ(m.face_handle(h), ref.face_handle(h)) << "halfedge " << h.idx();
  }
  for (VertexHandle v : ref.vertices()) ASSERT_EQ(m.halfedge_handle(v), ref.halfedge_handle(v)) << "vertex " << v.idx();
  for (FaceHandle f : ref.faces()) {
    ASSERT_EQ(m.halfedge_handle(f), ref.halfedge_handle(f)) << "face " << f.idx();
    ASSERT_EQ(m.normal(f), ref.normal(f)) << "face " << f.idx();
  }
}

TEST(Arrays, TheBuilderGivesTheMeshAddFaceGives) {
  expect_add_face_mesh(mesh_from_arrays(mesh_to_arrays(shapes::icosphere(2)).vertices, mesh_to_arrays(shapes::icosphere(2)).faces).mesh);
  const MeshArrays p = pinched_body();
  expect_add_face_mesh(mesh_from_arrays(p.vertices, p.faces).mesh);
  const MeshArrays torus = mesh_to_arrays(shapes::torus(12, 6));
  std::mt19937 rng(3);
  for (int trial = 0; trial < 30; ++trial) {
    std::vector<std::array<int, 3>> rows = rows_of(torus.faces);
    std::shuffle(rows.begin(), rows.end(), rng);
    rows.resize(rows.size() - static_cast<size_t>(trial % 10) * 7);
    for (size_t i = 0; i < rows.size(); i += 11) std::rotate(rows[i].begin(), rows[i].begin() + 1, rows[i].end());
    std::vector<int> f;
    for (const auto& r : rows) f.insert(f.end(), r.begin(), r.end());
    SCOPED_TRACE("trial " + std::to_string(trial));
    expect_add_face_mesh(mesh_from_arrays(torus.vertices, f).mesh);
  }
}

// Any row order and any removal of faces: every face that fits is added, every vertex manifold.
TEST(Arrays, ShuffledAndHoledMeshesAlwaysBuild) {
  const MeshArrays torus = mesh_to_arrays(shapes::torus(16, 8));
  std::mt19937 rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<std::array<int, 3>> rows = rows_of(torus.faces);
    std::shuffle(rows.begin(), rows.end(), rng);
    rows.resize(rows.size() - static_cast<size_t>(trial) * 9);  // holes, and pinched vertices between them
    std::vector<int> f;
    for (const auto& r : rows) f.insert(f.end(), r.begin(), r.end());
    const ArrayMesh m = mesh_from_arrays(torus.vertices, f);
    EXPECT_TRUE(m.report.dropped_faces.empty());
    EXPECT_EQ(m.mesh.n_faces(), rows.size());
    for (VertexHandle v : m.mesh.vertices()) ASSERT_TRUE(m.mesh.is_manifold(v)) << "trial " << trial;
    if (trial == 0) {
      EXPECT_EQ(m.report.vertex_copies, 0u);
    }
  }
}

// -------------------------------------------------------------------------------------------
// GeodesicSolver

TEST(GeodesicSolverArrays, FieldsMatchTheMeshQueriesInEveryMethod) {
  const Mesh mesh = shapes::bumpy_sphere(2);
  const MeshArrays a = mesh_to_arrays(mesh);
  const GeodesicSolver solver(a.vertices, a.faces);
  const std::vector<int> sources = {0, 17};
  for (DistanceMethod method : {DistanceMethod::Mdf, DistanceMethod::Windows, DistanceMethod::Fast, DistanceMethod::Dijkstra}) {
    const DistanceArrays d = solver.distance_from_vertices(sources, {.method = method, .max_distance = 1.5, .directions = true});
    const DistanceField ref = geodesic_distance(mesh, FrontSource::from_vertices({VertexHandle(0), VertexHandle(17)}),
                                                {.max_distance = 1.5, .method = method});
    ASSERT_EQ(d.distance.size(), mesh.n_vertices());
    ASSERT_EQ(d.direction.size(), 3 * mesh.n_vertices());
    EXPECT_EQ(d.stop, DistanceStop::MaxDistance) << to_string(method);
    for (size_t i = 0; i < mesh.n_vertices(); ++i) {
      EXPECT_EQ(d.distance[i], ref.distance[i]) << to_string(method) << " vertex " << i;
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(d.direction[3 * i + k], ref.direction[i][k], 1e-12);
    }
  }
}

TEST(GeodesicSolverArrays, PointLoopAndTargetSources) {
  const Mesh mesh = shapes::icosphere(3);
  const MeshArrays a = mesh_to_arrays(mesh);
  const GeodesicSolver solver(a.vertices, a.faces);
  // A point at a corner of row 5 (in the row's order) is that vertex.
  for (int k = 0; k < 3; ++k) {
    std::vector<double> bary(3, 0.0);
    bary[static_cast<size_t>(k)] = 1.0;
    const DistanceArrays d = solver.distance_from_points(std::vector<int>{5}, bary);
    EXPECT_EQ(d.distance[static_cast<size_t>(a.faces[15 + static_cast<size_t>(k)])], 0.0);
  }
  const DistanceArrays centre = solver.distance_from_points(std::vector<int>{5}, std::vector<double>{1.0 / 3, 1.0 / 3, 1.0 / 3});
  const DistanceField ref_centre = geodesic_distance(mesh, std::vector<SurfacePoint>{{FaceHandle(5), {1.0 / 3, 1.0 / 3, 1.0 / 3}}});
  EXPECT_EQ(centre.distance, ref_centre.distance);
  // A loop: the ring around vertex 0, both sides.
  std::vector<int> ring;
  for (HalfedgeHandle h : mesh.voh_range(VertexHandle(0))) ring.push_back(mesh.to_vertex_handle(h).idx());
  std::reverse(ring.begin(), ring.end());  // counter-clockwise seen from outside
  const DistanceArrays left = solver.distance_from_loop(ring, LoopSide::Left);
  const DistanceArrays right = solver.distance_from_loop(ring, LoopSide::Right);
  const std::vector<VertexHandle> loop_vs = [&] {
    std::vector<VertexHandle> vs;
    for (int v : ring) vs.push_back(VertexHandle(v));
    return vs;
  }();
  EXPECT_EQ(left.distance, geodesic_distance(mesh, loop_from_vertices(mesh, loop_vs, LoopSide::Left)).distance);
  EXPECT_EQ(right.distance, geodesic_distance(mesh, loop_from_vertices(mesh, loop_vs, LoopSide::Right)).distance);
  EXPECT_TRUE(std::isinf(left.distance[0]) != std::isinf(right.distance[0]));  // vertex 0 lies on one side
  // A target stops the field.
  const DistanceArrays t = solver.distance_from_vertices(std::vector<int>{0}, {.target = 40});
  EXPECT_EQ(t.stop, DistanceStop::TargetReached);
  EXPECT_TRUE(std::isfinite(t.distance[40]));
}

TEST(GeodesicSolverArrays, BoundedQueriesVisitOnlyWhatTheyNeed) {
  const Mesh mesh = shapes::icosphere(4);
  const MeshArrays a = mesh_to_arrays(mesh);
  GeodesicSolver solver(a.vertices, a.faces);
  const DistanceArrays full = solver.distance_from_vertices(std::vector<int>{7});
  const SparseDistances near = solver.distances_within(std::vector<int>{7}, 0.2);
  EXPECT_EQ(near.stop, DistanceStop::MaxDistance);
  size_t within = 0;
  for (double d : full.distance) within += d <= 0.2;
  EXPECT_EQ(near.vertex.size(), within);
  EXPECT_LT(near.vertex.size(), mesh.n_vertices() / 10);
  for (size_t i = 0; i < near.vertex.size(); ++i) EXPECT_EQ(near.distance[i], full.distance[static_cast<size_t>(near.vertex[i])]);
  EXPECT_TRUE(std::is_sorted(near.distance.begin(), near.distance.end()));
  // Near along the surface or not.
  const int close = near.vertex.back();
  ASSERT_TRUE(solver.distance_between(7, close, 0.2).has_value());
  EXPECT_EQ(*solver.distance_between(7, close, 0.2), full.distance[static_cast<size_t>(close)]);
  int far = 0;
  for (size_t i = 0; i < full.distance.size(); ++i)
    if (full.distance[i] > full.distance[static_cast<size_t>(far)]) far = static_cast<int>(i);
  EXPECT_FALSE(solver.distance_between(7, far, 0.2).has_value());
  EXPECT_THROW(solver.distances_within(std::vector<int>{7}, 0.2, DistanceMethod::Fast), InvalidInput);
}

TEST(GeodesicSolverArrays, LevelsAndPaths) {
  const Mesh mesh = shapes::torus(24, 12);
  const MeshArrays a = mesh_to_arrays(mesh);
  GeodesicSolver solver(a.vertices, a.faces);
  EXPECT_EQ(solver.levels(std::vector<int>{3}), edge_front_levels(mesh, FrontSource::vertex(VertexHandle(3))));
  EXPECT_EQ(solver.levels(std::vector<int>{3}, 2), edge_front_levels(mesh, FrontSource::vertex(VertexHandle(3)), 2));
  const PathArrays p = solver.connection_path(0, 150, {.polyline = true});
  const ConnectionPath ref = connection_path(mesh, VertexHandle(0), VertexHandle(150), {.polyline = true});
  ASSERT_EQ(p.status, PathStatus::Found);
  ASSERT_EQ(p.vertices.size(), ref.vertices.size());
  for (size_t i = 0; i < p.vertices.size(); ++i) EXPECT_EQ(p.vertices[i], ref.vertices[i].idx());
  EXPECT_EQ(p.length, ref.length);
  ASSERT_EQ(p.points.size(), 3 * ref.polyline.size());
  ASSERT_EQ(p.edge.size(), 2 * ref.polyline.size());
  ASSERT_EQ(p.t.size(), ref.polyline.size());
  EXPECT_EQ(p.edge.front(), 0);
  EXPECT_EQ(p.edge.back(), 150);
  for (size_t i = 0; i < ref.polyline.size(); ++i) {
    EXPECT_EQ(p.points[3 * i], ref.polyline[i].position[0]);
    // The point lies on the named edge at t.
    const Vec3 a0 = mesh.point(VertexHandle(p.edge[2 * i])), a1 = mesh.point(VertexHandle(p.edge[2 * i + 1]));
    const Vec3 q = a0 + p.t[i] * (a1 - a0);
    EXPECT_NEAR((q - ref.polyline[i].position).norm(), 0.0, 1e-12);
    // The same point as a face row and barycentric coordinates in the row's corner order.
    ASSERT_GE(p.face[i], 0);
    Vec3 x(0, 0, 0);
    for (size_t k = 0; k < 3; ++k) {
      const int corner = a.faces[3 * static_cast<size_t>(p.face[i]) + k];
      x += mesh.point(VertexHandle(corner)) * p.barycentric[3 * i + k];
    }
    EXPECT_NEAR((x - ref.polyline[i].position).norm(), 0.0, 1e-12);
  }
  // Polyline points are sources as they are: the field from the middle one is the C++ field from
  // its PathPoint::location.
  const size_t mid = ref.polyline.size() / 2;
  const DistanceArrays from_mid = solver.distance_from_points(std::span<const int>(&p.face[mid], 1),
                                                              std::span<const double>(&p.barycentric[3 * mid], 3));
  const DistanceField ref_mid = geodesic_distance(mesh, {ref.polyline[mid].location});
  ASSERT_EQ(from_mid.distance.size(), ref_mid.distance.size());
  for (size_t v = 0; v < ref_mid.distance.size(); ++v) EXPECT_NEAR(from_mid.distance[v], ref_mid.distance[v], 1e-9) << v;
  const PathArrays line = solver.polyline(p.vertices);
  EXPECT_EQ(line.vertices, p.vertices);
  EXPECT_LE(line.length, ref.edge_length + 1e-12);
}

TEST(GeodesicSolverArrays, PinchedBodyRunsInEveryMethod) {
  const MeshArrays a = pinched_body();
  GeodesicSolver solver(a.vertices, a.faces);
  const size_t n = a.n_vertices();
  ASSERT_EQ(solver.n_vertices(), n);
  ASSERT_EQ(solver.converted().mesh.n_vertices(), n + 3);
  for (DistanceMethod method : {DistanceMethod::Mdf, DistanceMethod::Windows, DistanceMethod::Fast, DistanceMethod::Dijkstra}) {
    const DistanceArrays d = solver.distance_from_vertices(std::vector<int>{0}, {.method = method});
    ASSERT_EQ(d.distance.size(), n) << to_string(method);  // one entry per input vertex
    for (int t = 0; t < 3; ++t) EXPECT_TRUE(std::isfinite(d.distance[static_cast<size_t>(10 * t + 3)])) << to_string(method);
  }
  EXPECT_EQ(solver.levels(std::vector<int>{0}).size(), n);
  EXPECT_EQ(solver.connection_path(0, 23).status, PathStatus::Found);
}

TEST(GeodesicSolverArrays, BadQueriesAreRefused) {
  const MeshArrays a = mesh_to_arrays(shapes::icosphere(1));
  GeodesicSolver solver(a.vertices, a.faces);
  EXPECT_THROW(solver.distance_from_vertices(std::vector<int>{}), InvalidInput);
  EXPECT_THROW(solver.distance_from_vertices(std::vector<int>{-1}), InvalidInput);
  EXPECT_THROW(solver.distance_from_vertices(std::vector<int>{42}), InvalidInput);
  EXPECT_THROW(solver.distance_from_vertices(std::vector<int>{0}, {.max_distance = -1}), InvalidInput);
  EXPECT_THROW(solver.distance_from_vertices(std::vector<int>{0}, {.target = 42}), InvalidInput);
  EXPECT_THROW(solver.distance_from_points(std::vector<int>{0}, std::vector<double>{0.5, 0.5}), InvalidInput);
  EXPECT_THROW(solver.distance_from_points(std::vector<int>{80}, std::vector<double>{1, 0, 0}), InvalidInput);
  EXPECT_THROW(solver.distance_from_points(std::vector<int>{0}, std::vector<double>{0.7, 0.7, 0}), InvalidInput);
  EXPECT_THROW(solver.distance_from_loop(std::vector<int>{0, 1}), InvalidInput);
  EXPECT_THROW(solver.distances_within(std::vector<int>{0}, std::nan("")), InvalidInput);
  EXPECT_THROW(solver.connection_path(0, 99), InvalidInput);
}

}  // namespace
