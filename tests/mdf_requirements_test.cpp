// Issue 4's stated behaviour of the distance front, checked the same way in every mode: the
// Minimal Distance Front (default), its window mode, its fast mode (per call and on a
// GeodesicRingTable), the stepwise MinimalDistanceFront and the Dijkstra baseline. Bad input is
// refused with InvalidInput by all of them; unreached vertices (another component, behind a loop,
// deleted, beyond max_distance) are infinite, never 0; the order, directions and stop reasons
// agree with the distances. Plus the properties of /work/shared/notes/edge-fronts.md that
// minimal_distance_front_test.cpp does not check: cones (4), symmetry at the stated 0.1% (6),
// triangulation independence (7), and the working memory of a whole field following the front;
// and the README's three-line example.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "edgefront/error.h"
#include "edgefront/front_source.h"
#include "edgefront/geodesic_ring_table.h"
#include "edgefront/mesh_io.h"
#include "edgefront/minimal_distance_front.h"
#include "shapes/shapes.h"
#include "front_test_util.h"

namespace {

using namespace edgefront;

constexpr double kInf = std::numeric_limits<double>::infinity();

/// One way of computing a distance field; `from_points` is empty for Dijkstra (vertices and loops only).
struct Mode {
  std::string name;
  std::function<DistanceField(const Mesh&, const FrontSource&, const DistanceOptions&)> from_source;
  std::function<DistanceField(const Mesh&, const std::vector<SurfacePoint>&, const DistanceOptions&)> from_points;
};

DistanceOptions with(DistanceOptions o, bool windows, bool fast) {
  o.method = fast ? DistanceMethod::Fast : windows ? DistanceMethod::Windows : DistanceMethod::Mdf;
  return o;
}

/// The stepwise front, run to its stop; the field is assembled from the settled callback.
template <class Source>
DistanceField stepwise(const Mesh& mesh, const Source& source, const DistanceOptions& options) {
  MinimalDistanceFront front(mesh);
  front.reset(source, options);
  DistanceField f;
  f.distance.assign(mesh.n_vertices(), kInf);
  f.direction.assign(mesh.n_vertices(), Vec3(0, 0, 0));
  front.set_settled_callback([&](VertexHandle v, double d, const Vec3& dir) {
    f.distance[v.idx()] = d;
    f.direction[v.idx()] = dir;
    f.order.push_back(v);
  });
  f.stop = front.run();
  f.peak_front = front.peak_front_size();
  f.peak_working_memory_bytes = front.peak_working_memory_bytes();
  return f;
}

std::vector<Mode> modes() {
  std::vector<Mode> out;
  for (const bool windows : {false, true}) {
    out.push_back({windows ? "windows" : "mdf",
                   [windows](const Mesh& m, const FrontSource& s, const DistanceOptions& o) {
                     return geodesic_distance(m, s, with(o, windows, false));
                   },
                   [windows](const Mesh& m, const std::vector<SurfacePoint>& p, const DistanceOptions& o) {
                     return geodesic_distance(m, p, with(o, windows, false));
                   }});
    out.push_back({windows ? "stepwise-windows" : "stepwise",
                   [windows](const Mesh& m, const FrontSource& s, const DistanceOptions& o) {
                     return stepwise(m, s, with(o, windows, false));
                   },
                   [windows](const Mesh& m, const std::vector<SurfacePoint>& p, const DistanceOptions& o) {
                     return stepwise(m, p, with(o, windows, false));
                   }});
  }
  out.push_back({"fast",
                 [](const Mesh& m, const FrontSource& s, const DistanceOptions& o) {
                   return geodesic_distance(m, s, with(o, false, true));
                 },
                 [](const Mesh& m, const std::vector<SurfacePoint>& p, const DistanceOptions& o) {
                   return geodesic_distance(m, p, with(o, false, true));
                 }});
  out.push_back({"fast-table",
                 [](const Mesh& m, const FrontSource& s, const DistanceOptions& o) {
                   return geodesic_distance(m, GeodesicRingTable(m), s, o);
                 },
                 [](const Mesh& m, const std::vector<SurfacePoint>& p, const DistanceOptions& o) {
                   return geodesic_distance(m, GeodesicRingTable(m), p, o);
                 }});
  out.push_back({"dijkstra",
                 [](const Mesh& m, const FrontSource& s, const DistanceOptions& o) { return dijkstra_distance(m, s, o); },
                 nullptr});
  return out;
}

/// An icosphere with vertex 3 deleted (not garbage-collected) and a face that went with it.
struct MeshWithHoles {
  Mesh mesh = shapes::icosphere(2);
  VertexHandle dead_vertex{3};
  FaceHandle dead_face;
  MeshWithHoles() {
    for (FaceHandle f : mesh.vf_range(dead_vertex)) dead_face = f;
    mesh.delete_vertex(dead_vertex, false);
  }
};

// ---- bad input: the same InvalidInput from every mode ----

TEST(MdfRequirements, EveryModeRefusesTheSameBadInput) {
  const Mesh mesh = shapes::icosphere(2);
  const MeshWithHoles holes;
  const VertexHandle v0(0);
  std::vector<HalfedgeHandle> around_face;  // closed and simple: face 0's halfedges
  for (HalfedgeHandle h : mesh.fh_range(FaceHandle(0))) around_face.push_back(h);
  std::vector<HalfedgeHandle> twice = around_face;
  twice.insert(twice.end(), around_face.begin(), around_face.end());
  // Face 0's halfedges in the wrong order: the first ends where the third starts.
  const std::vector<HalfedgeHandle> not_chained = {around_face[0], around_face[2], around_face[1]};

  struct SourceCase {
    std::string what;
    const Mesh* mesh;
    FrontSource source;
    DistanceOptions options;
  };
  const std::vector<SourceCase> source_cases = {
      {"vertex out of range", &mesh, FrontSource::vertex(VertexHandle(100000)), {}},
      {"vertex -1", &mesh, FrontSource::vertex(VertexHandle(-1)), {}},
      {"no source", &mesh, FrontSource{}, {}},
      {"vertex given twice", &mesh, FrontSource::from_vertices({v0, v0}), {}},
      {"deleted vertex", &holes.mesh, FrontSource::vertex(holes.dead_vertex), {}},
      {"vertex on an empty mesh", nullptr, FrontSource::vertex(v0), {}},
      {"max_distance -1", &mesh, FrontSource::vertex(v0), {.max_distance = -1}},
      {"max_distance NaN", &mesh, FrontSource::vertex(v0), {.max_distance = std::nan("")}},
      {"max_distance -inf", &mesh, FrontSource::vertex(v0), {.max_distance = -kInf}},
      {"target out of range", &mesh, FrontSource::vertex(v0), {.target = VertexHandle(100000)}},
      {"target deleted", &holes.mesh, FrontSource::vertex(v0), {.target = holes.dead_vertex}},
      {"loop not chained", &mesh, FrontSource::from_halfedges(not_chained), {}},
      {"loop around a face twice", &mesh, FrontSource::from_halfedges(twice), {}},
      {"loop of invalid halfedges", &mesh,
       FrontSource::from_halfedges({HalfedgeHandle(100000), HalfedgeHandle(100001), HalfedgeHandle(100002)}), {}},
      {"vertices and a loop", &mesh, FrontSource{{v0}, around_face}, {}},
  };
  struct PointCase {
    std::string what;
    const Mesh* mesh;
    std::vector<SurfacePoint> points;
    DistanceOptions options;
  };
  const double nan = std::nan("");
  const std::vector<PointCase> point_cases = {
      {"no points", &mesh, {}, {}},
      {"face out of range", &mesh, {{FaceHandle(100000), {1, 0, 0}}}, {}},
      {"face -1", &mesh, {{FaceHandle(-1), {1, 0, 0}}}, {}},
      {"deleted face", &holes.mesh, {{holes.dead_face, {1, 0, 0}}}, {}},
      {"coordinates sum to 1.5", &mesh, {{FaceHandle(0), {0.5, 0.5, 0.5}}}, {}},
      {"negative coordinate", &mesh, {{FaceHandle(0), {-0.5, 1.0, 0.5}}}, {}},
      {"NaN coordinate", &mesh, {{FaceHandle(0), {nan, 0.5, 0.5}}}, {}},
      {"infinite coordinate", &mesh, {{FaceHandle(0), {kInf, 0, 0}}}, {}},
      {"second point bad", &mesh, {{FaceHandle(0), {1, 0, 0}}, {FaceHandle(1), {0.2, 0.2, 0.2}}}, {}},
      {"max_distance NaN", &mesh, {{FaceHandle(0), {1, 0, 0}}}, {.max_distance = nan}},
      {"target deleted", &holes.mesh, {{FaceHandle(0), {1, 0, 0}}}, {.target = holes.dead_vertex}},
  };
  ASSERT_TRUE(holes.dead_face.is_valid());
  const Mesh empty;
  for (const Mode& mode : modes()) {
    for (const SourceCase& c : source_cases) {
      const Mesh& m = c.mesh ? *c.mesh : empty;
      EXPECT_THROW(mode.from_source(m, c.source, c.options), InvalidInput) << mode.name << ": " << c.what;
    }
    if (!mode.from_points) continue;
    for (const PointCase& c : point_cases) {
      EXPECT_THROW(mode.from_points(*c.mesh, c.points, c.options), InvalidInput) << mode.name << ": " << c.what;
    }
  }
}

TEST(MdfRequirements, NonFiniteCoordinatesAreRefusedWhenReached) {
  // A mesh built in code is not checked on input: a vertex with a NaN or infinite coordinate must
  // not pass for an unreachable one. Every mode refuses it when it reaches it.
  Mesh mesh = shapes::icosphere(1);
  const VertexHandle bad(5);
  mesh.set_point(bad, Vec3(std::nan(""), 0, 0));
  FaceHandle touching;
  for (FaceHandle f : mesh.vf_range(bad)) touching = f;
  for (const Mode& mode : modes()) {
    EXPECT_THROW(mode.from_source(mesh, FrontSource::vertex(VertexHandle(0)), {}), InvalidInput) << mode.name;
    EXPECT_THROW(mode.from_source(mesh, FrontSource::vertex(bad), {}), InvalidInput) << mode.name;
    if (mode.from_points) {
      EXPECT_THROW(mode.from_points(mesh, {{touching, {1.0 / 3, 1.0 / 3, 1.0 / 3}}}, {}), InvalidInput) << mode.name;
    }
  }
  mesh.set_point(bad, Vec3(0, std::numeric_limits<double>::infinity(), 0));
  EXPECT_THROW(geodesic_distance(mesh, FrontSource::vertex(VertexHandle(0))), InvalidInput);
  EXPECT_THROW(dijkstra_distance(mesh, FrontSource::vertex(VertexHandle(0))), InvalidInput);
  // Beyond max_distance it is never reached, so the query runs: O(front), not a scan of the mesh.
  Mesh far = shapes::icosphere(2);
  const VertexHandle opposite = *std::max_element(far.vertices().begin(), far.vertices().end(),
      [&](VertexHandle a, VertexHandle b) { return (far.point(a) - far.point(VertexHandle(0))).norm() <
                                                   (far.point(b) - far.point(VertexHandle(0))).norm(); });
  far.set_point(opposite, Vec3(std::nan(""), 0, 0));
  const DistanceField near = geodesic_distance(far, FrontSource::vertex(VertexHandle(0)), {.max_distance = 0.5});
  EXPECT_EQ(near.stop, DistanceStop::MaxDistance);
}

// ---- unreached vertices: infinite, never 0 ----

TEST(MdfRequirements, UnreachedVerticesAreInfiniteInEveryMode) {
  const Mesh nested = shapes::nested_spheres(1);
  const auto hops = eftest::bfs_levels(nested, {VertexHandle(0)});
  const MeshWithHoles holes;
  const Mesh sphere = shapes::icosphere(2);
  std::vector<HalfedgeHandle> around_face;  // ahead: face 0 itself
  for (HalfedgeHandle h : sphere.fh_range(FaceHandle(0))) around_face.push_back(h);
  std::vector<HalfedgeHandle> outside;  // the same loop reversed: ahead is the rest of the sphere
  for (auto it = around_face.rbegin(); it != around_face.rend(); ++it) outside.push_back(sphere.opposite_halfedge_handle(*it));
  for (const Mode& mode : modes()) {
    const DistanceField other = mode.from_source(nested, FrontSource::vertex(VertexHandle(0)), {});
    size_t unreached = 0;
    for (VertexHandle v : nested.vertices()) {
      const double d = other.distance[v.idx()];
      ASSERT_EQ(std::isinf(d) && d > 0, hops[v.idx()] < 0) << mode.name << ": vertex " << v.idx() << " at " << d;
      unreached += hops[v.idx()] < 0;
      if (v.idx() != 0) {
        EXPECT_GT(d, 0) << mode.name;
      }
    }
    ASSERT_GT(unreached, 0u);
    EXPECT_EQ(other.order.size(), nested.n_vertices() - unreached) << mode.name;
    EXPECT_EQ(other.stop, DistanceStop::Exhausted) << mode.name;
    if (mode.from_points) {  // a point on a face next to vertex 0: the same component
      const FaceHandle face = *nested.vf_range(VertexHandle(0)).begin();
      const DistanceField pf = mode.from_points(nested, {{face, {0.2, 0.3, 0.5}}}, {});
      for (VertexHandle v : nested.vertices()) {
        EXPECT_EQ(std::isinf(pf.distance[v.idx()]), hops[v.idx()] < 0) << mode.name << ": vertex " << v.idx();
        EXPECT_GT(pf.distance[v.idx()], 0) << mode.name << ": the point lies inside the face";
      }
    }

    // A deleted vertex is never reached (the others are: the sphere stays connected).
    const DistanceField h = mode.from_source(holes.mesh, FrontSource::vertex(VertexHandle(0)), {});
    EXPECT_EQ(h.distance[holes.dead_vertex.idx()], kInf) << mode.name;
    EXPECT_EQ(h.order.size(), holes.mesh.n_vertices() - 1) << mode.name;
    EXPECT_EQ(std::count(h.order.begin(), h.order.end(), holes.dead_vertex), 0) << mode.name;

    // A loop source measures only ahead of it (windows and fast modes run a loop as the default
    // mode does).
    const DistanceField inside = mode.from_source(sphere, FrontSource::from_halfedges(around_face), {});
    const DistanceField rest = mode.from_source(sphere, FrontSource::from_halfedges(outside), {});
    for (VertexHandle v : sphere.vertices()) {
      const bool on_loop = std::any_of(around_face.begin(), around_face.end(),
                                       [&](HalfedgeHandle g) { return sphere.to_vertex_handle(g) == v; });
      EXPECT_EQ(inside.distance[v.idx()], on_loop ? 0.0 : kInf) << mode.name << ": vertex " << v.idx();
      if (on_loop) {
        EXPECT_EQ(rest.distance[v.idx()], 0.0) << mode.name;
      } else {
        EXPECT_TRUE(std::isfinite(rest.distance[v.idx()]) && rest.distance[v.idx()] > 0) << mode.name << ": " << v.idx();
      }
    }
    EXPECT_EQ(inside.order.size(), 3u) << mode.name;
    EXPECT_EQ(rest.order.size(), sphere.n_vertices()) << mode.name;
  }
}

// ---- outputs: distance, direction, order and stop agree, in every mode ----

TEST(MdfRequirements, OrderDirectionsAndStopAgreeWithTheDistances) {
  const Mesh sphere = shapes::icosphere(3);
  const Mesh plane = shapes::grid(shapes::GridOptions{.cells = 12, .variant = shapes::GridVariant::jittered});
  const std::vector<VertexHandle> sources = {VertexHandle(0), VertexHandle(50)};
  for (const Mode& mode : modes()) {
    const DistanceField f = mode.from_source(sphere, FrontSource::from_vertices(sources), {.max_distance = 1.0});
    EXPECT_EQ(f.stop, DistanceStop::MaxDistance) << mode.name;
    std::vector<int> seen(sphere.n_vertices(), 0);
    for (VertexHandle v : f.order) ++seen[v.idx()];
    size_t finite = 0;
    for (VertexHandle v : sphere.vertices()) {
      const double d = f.distance[v.idx()];
      const bool is_source = std::find(sources.begin(), sources.end(), v) != sources.end();
      ASSERT_EQ(seen[v.idx()], std::isfinite(d) ? 1 : 0) << mode.name << ": the order holds the reached vertices once";
      if (!std::isfinite(d)) {
        ASSERT_EQ(d, kInf) << mode.name;
        ASSERT_EQ(f.direction[v.idx()], Vec3(0, 0, 0)) << mode.name << ": unreached vertex " << v.idx();
        continue;
      }
      ++finite;
      ASSERT_LE(d, 1.0) << mode.name;
      ASSERT_EQ(d == 0, is_source) << mode.name << ": vertex " << v.idx();
      if (is_source) {
        ASSERT_EQ(f.direction[v.idx()], Vec3(0, 0, 0)) << mode.name << ": source " << v.idx();
      } else {
        ASSERT_NEAR(f.direction[v.idx()].norm(), 1.0, 1e-9) << mode.name << ": vertex " << v.idx();
      }
    }
    EXPECT_GT(finite, 20u) << mode.name;
    EXPECT_LT(finite, sphere.n_vertices()) << mode.name;
    for (size_t i = 1; i < f.order.size(); ++i) {
      ASSERT_GE(f.distance[f.order[i].idx()], f.distance[f.order[i - 1].idx()] - 1e-9) << mode.name;
    }
    EXPECT_GT(f.peak_working_memory_bytes, 0u) << mode.name;

    // Stop reasons: everything, a target, the target as source, an unreachable target, d_max 0.
    EXPECT_EQ(mode.from_source(sphere, FrontSource::vertex(VertexHandle(0)), {}).stop, DistanceStop::Exhausted);
    const DistanceField t = mode.from_source(sphere, FrontSource::vertex(VertexHandle(0)), {.target = VertexHandle(300)});
    EXPECT_EQ(t.stop, DistanceStop::TargetReached) << mode.name;
    ASSERT_FALSE(t.order.empty());
    EXPECT_EQ(t.order.back(), VertexHandle(300)) << mode.name;
    EXPECT_TRUE(std::isfinite(t.distance[300])) << mode.name;
    const DistanceField self = mode.from_source(sphere, FrontSource::vertex(VertexHandle(5)), {.target = VertexHandle(5)});
    EXPECT_EQ(self.stop, DistanceStop::TargetReached) << mode.name;
    EXPECT_EQ(self.order, std::vector<VertexHandle>{VertexHandle(5)}) << mode.name;
    const Mesh nested = shapes::nested_spheres(1);
    const DistanceField away =
        mode.from_source(nested, FrontSource::vertex(VertexHandle(0)), {.target = VertexHandle(int(nested.n_vertices()) - 1)});
    EXPECT_EQ(away.stop, DistanceStop::Exhausted) << mode.name;
    EXPECT_EQ(away.distance.back(), kInf) << mode.name;
    const DistanceField zero = mode.from_source(sphere, FrontSource::from_vertices(sources), {.max_distance = 0});
    EXPECT_EQ(zero.stop, DistanceStop::MaxDistance) << mode.name;
    EXPECT_EQ(zero.order.size(), 2u) << mode.name;
    EXPECT_EQ(std::count_if(zero.distance.begin(), zero.distance.end(), [](double d) { return std::isfinite(d); }), 2)
        << mode.name;

    // On a plane every direction points toward the source (for Dijkstra: to the previous vertex
    // of a monotone edge path, still closer to the source).
    const VertexHandle s(70);
    const DistanceField p = mode.from_source(plane, FrontSource::vertex(s), {});
    for (VertexHandle v : plane.vertices()) {
      if (v == s) continue;
      ASSERT_GT(OpenMesh::dot(p.direction[v.idx()], plane.point(s) - plane.point(v)), 0) << mode.name << ": " << v.idx();
    }
  }
}

// ---- the reusable object across source kinds and options ----

TEST(MdfRequirements, ReusedFrontMatchesFreshFieldsAcrossSourceKinds) {
  const Mesh mesh = shapes::grid(shapes::GridOptions{.cells = 10, .variant = shapes::GridVariant::jittered});
  // The boundary of the block of 3x3 cells between grid rows and columns 2 and 5 (vertex 11 j + i),
  // counter-clockwise; measured outside it.
  std::vector<VertexHandle> ring;
  for (const int v : {24, 25, 26, 27, 38, 49, 60, 59, 58, 57, 46, 35}) ring.push_back(VertexHandle(v));
  const FrontSource loop = loop_from_vertices(mesh, ring, LoopSide::Right);
  const std::vector<SurfacePoint> points = {{FaceHandle(77), {0.2, 0.3, 0.5}}, {FaceHandle(150), {0.0, 1.0, 0.0}}};
  MinimalDistanceFront front(mesh);
  for (const bool windows : {false, true}) {
    struct Query {
      std::function<void()> reset;
      std::function<DistanceField()> fresh;
    };
    const DistanceOptions plain{.method = windows ? DistanceMethod::Windows : DistanceMethod::Mdf};
    const DistanceOptions bounded{.max_distance = 0.4, .method = plain.method};
    const DistanceOptions targeted{.target = VertexHandle(60), .method = plain.method};
    const std::vector<Query> queries = {
        {[&] { front.reset(FrontSource::vertex(VertexHandle(60)), plain); },
         [&] { return geodesic_distance(mesh, FrontSource::vertex(VertexHandle(60)), plain); }},
        {[&] { front.reset(loop, plain); }, [&] { return geodesic_distance(mesh, loop, plain); }},
        {[&] { front.reset(points, bounded); }, [&] { return geodesic_distance(mesh, points, bounded); }},
        {[&] { front.reset(FrontSource::vertex(VertexHandle(3)), targeted); },
         [&] { return geodesic_distance(mesh, FrontSource::vertex(VertexHandle(3)), targeted); }},
        {[&] { front.reset(points, plain); }, [&] { return geodesic_distance(mesh, points, plain); }},
    };
    std::vector<double> d;
    std::vector<VertexHandle> order;
    front.set_settled_callback([&](VertexHandle v, double x, const Vec3&) {
      d[v.idx()] = x;
      order.push_back(v);
    });
    for (size_t q = 0; q < queries.size(); ++q) {
      d.assign(mesh.n_vertices(), kInf);
      order.clear();
      queries[q].reset();
      const DistanceStop stop = front.run();
      const DistanceField expected = queries[q].fresh();
      EXPECT_EQ(d, expected.distance) << "query " << q << (windows ? " (windows)" : "");
      EXPECT_EQ(order, expected.order) << "query " << q;
      EXPECT_EQ(stop, expected.stop) << "query " << q;
      EXPECT_EQ(front.settled_count(), expected.order.size()) << "query " << q;
    }
  }
}

// Stepwise: each step settles exactly one vertex, whose distance the front still knows.
TEST(MdfRequirements, EachStepSettlesOneVertex) {
  const Mesh mesh = shapes::torus(16, 8);
  MinimalDistanceFront front(mesh);
  front.reset(FrontSource::vertex(VertexHandle(9)), {.max_distance = 1.5});
  EXPECT_EQ(front.stop_reason(), DistanceStop::NotStarted);
  EXPECT_EQ(front.settled_count(), 0u);
  size_t calls = 0;
  VertexHandle last;
  double last_d = -1;
  front.set_settled_callback([&](VertexHandle v, double d, const Vec3&) {
    ++calls;
    last = v;
    last_d = d;
  });
  size_t steps = 0;
  while (front.step()) {
    ++steps;
    ASSERT_EQ(calls, steps);
    ASSERT_EQ(front.settled_count(), steps);
    const std::optional<double> known = front.distance(last);
    ASSERT_TRUE(known.has_value()) << "vertex " << last.idx();
    ASSERT_EQ(*known, last_d);
  }
  EXPECT_EQ(front.stop_reason(), DistanceStop::MaxDistance);
  EXPECT_EQ(calls, steps);
  EXPECT_FALSE(front.step());  // stays stopped
  EXPECT_EQ(calls, steps);
  const DistanceField f = geodesic_distance(mesh, FrontSource::vertex(VertexHandle(9)), {.max_distance = 1.5});
  EXPECT_EQ(steps, f.order.size());
  EXPECT_GT(steps, 10u);
  EXPECT_LT(steps, mesh.n_vertices());
}

// ---- properties of edge-fronts.md not covered elsewhere ----

// Property 4 on a cone (a pyramid over a regular polygon, apex included: flat but for the apex):
// the exact distance is the straight line in the unrolled sector, where generator i lies at angle
// i * alpha (alpha: the apex angle of one face) and a vertex at its distance from the apex.
TEST(MdfRequirements, ConeUnrollsExactly) {
  const int around = 32;
  const double radius = 1.0, height = 1.5;
  const Mesh mesh = shapes::cone(around, 12, radius, height);
  const Vec3 apex(0, 0, height);
  const double slant = std::hypot(radius, height);
  const double alpha = 2 * std::asin(radius * std::sin(M_PI / around) / slant);
  auto generator = [&](const Vec3& p) {
    const long i = std::lround(std::atan2(p[1], p[0]) / (2 * M_PI / around));
    return static_cast<int>((i % around + around) % around);
  };
  auto exact = [&](VertexHandle a, VertexHandle b) {
    const double ra = (mesh.point(a) - apex).norm(), rb = (mesh.point(b) - apex).norm();
    int steps = std::abs(generator(mesh.point(a)) - generator(mesh.point(b)));
    steps = std::min(steps, around - steps);
    const double angle = ra < 1e-12 || rb < 1e-12 ? 0.0 : steps * alpha;  // < pi: the chord
    return std::sqrt(std::max(0.0, ra * ra + rb * rb - 2 * ra * rb * std::cos(angle)));
  };
  std::mt19937_64 rng(3);
  const auto sources = eftest::random_vertices(mesh, rng, 4);
  for (const Mode& mode : modes()) {
    double sum = 0;
    size_t count = 0;
    for (VertexHandle s : sources) {
      const DistanceField f = mode.from_source(mesh, FrontSource::vertex(s), {});
      for (VertexHandle v : mesh.vertices()) {
        if (v == s) continue;
        sum += std::abs(f.distance[v.idx()] - exact(s, v)) / exact(s, v);
        ++count;
      }
    }
    const double mean = sum / static_cast<double>(count);
    if (mode.name == "dijkstra") {
      EXPECT_GT(mean, 0.01);  // edge paths: 8.6% here; the reference is not trivially met
    } else {
      EXPECT_LT(mean, 1e-9) << mode.name;  // measured below 2e-15 in every mode (issue: 0.1%)
    }
  }
}

// Property 6: |d(a,b) - d(b,a)| / d(a,b) averages at most 0.1%: every pair of 8 random vertices
// of a 2562-vertex bumpy sphere, one whole field per vertex, in each front mode (Dijkstra's edge
// paths are symmetric by construction). Mdf.DistancesAreNearlySymmetric only asserts 1.5%.
TEST(MdfRequirements, SymmetryWithinTheStatedBound) {
  const Mesh mesh = shapes::bumpy_sphere(4, 1.0, 0.15, 3.0);
  std::mt19937_64 rng(6);
  const auto sources = eftest::random_vertices(mesh, rng, 8);
  for (const Mode& mode : modes()) {
    if (mode.name == "dijkstra" || mode.name.rfind("stepwise", 0) == 0) continue;  // stepwise: the same fields
    std::vector<std::vector<double>> fields;
    for (VertexHandle s : sources) fields.push_back(mode.from_source(mesh, FrontSource::vertex(s), {}).distance);
    double sum = 0;
    size_t pairs = 0;
    for (size_t a = 0; a < sources.size(); ++a) {
      for (size_t b = a + 1; b < sources.size(); ++b, ++pairs) {
        const double dab = fields[a][sources[b].idx()], dba = fields[b][sources[a].idx()];
        sum += std::abs(dab - dba) / dab;
      }
    }
    // Measured: mdf 0.086%, windows 2.2e-5%, fast 0.036% (the coarse mesh is the hard case:
    // 0.080% for mdf with 10242 vertices).
    EXPECT_LT(sum / static_cast<double>(pairs), 1e-3) << mode.name;
  }
}

// Property 7: the same surface under two triangulations (a height field with every quad's
// diagonal flipped) gives the same distances at the shared vertices, within the error of
// property 5 (measured mean 0.007% / 0.004% / 0.005% for mdf / windows / fast), where Dijkstra's
// edge paths differ by 20% on average.
TEST(MdfRequirements, TriangulationIndependence) {
  const Mesh a = shapes::landscape(16, 1.0, 0.15, 3.0);
  Mesh b = a;
  size_t flipped = 0;
  for (EdgeHandle e : b.edges()) {
    const HalfedgeHandle h = b.halfedge_handle(e, 0);
    const Vec3 p = b.point(b.from_vertex_handle(h)), q = b.point(b.to_vertex_handle(h));
    if (std::abs(p[0] - q[0]) > 1e-9 && std::abs(p[1] - q[1]) > 1e-9) {
      ASSERT_TRUE(b.is_flip_ok(e));
      b.flip(e);
      ++flipped;
    }
  }
  ASSERT_EQ(flipped, 16u * 16u);  // one diagonal per quad
  const VertexHandle s(8 * 17 + 9);
  for (const Mode& mode : modes()) {
    const DistanceField fa = mode.from_source(a, FrontSource::vertex(s), {});
    const DistanceField fb = mode.from_source(b, FrontSource::vertex(s), {});
    double sum = 0;
    for (VertexHandle v : a.vertices()) {
      if (v != s) sum += std::abs(fa.distance[v.idx()] - fb.distance[v.idx()]) / fa.distance[v.idx()];
    }
    const double mean = sum / static_cast<double>(a.n_vertices() - 1);
    if (mode.name == "dijkstra") {
      EXPECT_GT(mean, 0.05);
    } else {
      EXPECT_LT(mean, 5e-4) << mode.name;
    }
  }
}

// Peak working memory follows the front, not the mesh: a whole field along a cylinder 4x as
// long (the same front, a ring around it) reports the same peak, with and without the edge front.
TEST(MdfRequirements, WholeFieldWorkingMemoryFollowsTheFront) {
  for (const bool track : {true, false}) {
    std::array<size_t, 2> bytes{};
    for (int k = 0; k < 2; ++k) {
      const int along = k == 0 ? 100 : 400;
      const Mesh mesh = shapes::open_cylinder(12, along, 1.0, 0.25 * along);
      const DistanceField f = geodesic_distance(mesh, FrontSource::vertex(VertexHandle(0)), {.track_front = track});
      ASSERT_EQ(f.stop, DistanceStop::Exhausted);
      bytes[k] = f.peak_working_memory_bytes;
    }
    EXPECT_GT(bytes[0], 0u);
    EXPECT_LT(bytes[1], bytes[0] * 5 / 4) << (track ? "tracked" : "untracked");  // measured: equal
  }
}

// The README's "distance field in three lines", as written there (the path from the data
// directory): a whole field on the bundled bumpy sphere.
TEST(MdfRequirements, ReadmeThreeLineExample) {
  const std::string path = std::string(EDGEFRONT_DATA_DIR) + "/bumpy-sphere.off";
  edgefront::Mesh mesh = edgefront::load_mesh(path);
  auto field = edgefront::geodesic_distance(mesh, edgefront::FrontSource::vertex(edgefront::VertexHandle(0)));
  ASSERT_EQ(field.distance.size(), 642u);
  ASSERT_EQ(field.direction.size(), 642u);
  ASSERT_EQ(field.order.size(), 642u);
  EXPECT_EQ(field.order.front(), VertexHandle(0));
  EXPECT_EQ(field.distance[0], 0.0);
  for (size_t i = 1; i < 642; ++i) {
    EXPECT_TRUE(std::isfinite(field.distance[i]) && field.distance[i] > 0) << i;
    EXPECT_NEAR(field.direction[i].norm(), 1.0, 1e-9) << i;
  }
}

}  // namespace
