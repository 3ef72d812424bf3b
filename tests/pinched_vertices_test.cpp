// Pinched vertices split into twins (edgefront/vertex_twins.h) are one point of the surface in
// every front, distance method and connection path. Most tests run on shapes::pinched_body: a
// horn torus whose inner equator closed to a point (a pinch inside the body) with two cones
// touching its outer equator by their apexes, split into twins as the mesh loader splits it.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "edgefront/connection_path.h"
#include "edgefront/error.h"
#include "edgefront/geodesic_ring_table.h"
#include "edgefront/minimal_distance_front.h"
#include "edgefront/minimal_edge_front.h"
#include "shapes/shapes.h"
#include "edgefront/vertex_front.h"
#include "edgefront/vertex_twins.h"

namespace {

using namespace edgefront;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr int kAround = 12;

const shapes::PinchedBody& body() {
  static const shapes::PinchedBody b = shapes::pinched_body(kAround);
  return b;
}
// The same mesh without its twin links: the three parts meet nowhere.
const Mesh& unlinked() {
  static const Mesh m = [] {
    Mesh copy = body().mesh;
    clear_twins(copy);
    return copy;
  }();
  return m;
}

Vec3 at(const Mesh& mesh, VertexHandle v) { return mesh.point(v); }

// A cone's lateral vertex on generator m (0 .. kAround-1) of ring t (1 .. rings).
VertexHandle cone_side(int cone, int t, int m) {
  return body().cone_sides[static_cast<size_t>(cone)][static_cast<size_t>((t - 1) * kAround + m)];
}
int cone_rings() { return static_cast<int>(body().cone_sides[0].size()) / kAround; }
VertexHandle apex_copy(int cone) { return body().pinches[static_cast<size_t>(cone)][1]; }
VertexHandle centre_up() { return body().pinches[2][0]; }
VertexHandle centre_down() { return body().pinches[2][1]; }

// The torus vertex nearest p (the torus's vertices come first; unique positions but the pinches).
VertexHandle vertex_at(const Mesh& mesh, const Vec3& p) {
  VertexHandle best;
  double bd = kInf;
  for (VertexHandle v : mesh.vertices()) {
    const double d = (mesh.point(v) - p).norm();
    if (d < bd) {
      bd = d;
      best = v;
    }
  }
  return best;
}
// The torus vertex at angle 2πi/kAround around z on row j of the tube (0: the outer equator; the
// rows j and -j are mirror images).
VertexHandle torus_vertex(int i, int j) {
  const double u = 2 * M_PI * i / kAround, v = 2 * M_PI * j / kAround;
  return vertex_at(body().mesh, Vec3((1 + std::cos(v)) * std::cos(u), (1 + std::cos(v)) * std::sin(u), std::sin(v)));
}
// The torus vertices next to the centre: on the upper side at u = 0, and its mirror image.
VertexHandle near_centre(bool upper) { return torus_vertex(0, upper ? kAround / 2 - 1 : kAround / 2 + 1); }

// Hop distance with steps between twins counting 0 (0-1 breadth-first search); -1 unreached.
// With a loop: the loop's vertices (and their twins) at 0, the first step from a loop vertex only
// into its ahead wedge, the loop never entered again.
std::vector<int> twin_hops(const Mesh& mesh, const std::vector<VertexHandle>& sources,
                           const std::vector<HalfedgeHandle>& loop = {}) {
  const TwinRing twins(mesh);
  std::vector<int> d(mesh.n_vertices(), std::numeric_limits<int>::max());
  std::deque<int> q;
  for (VertexHandle s : sources) {
    d[s.idx()] = 0;
    q.push_back(s.idx());
  }
  for (HalfedgeHandle h : loop) d[mesh.to_vertex_handle(h).idx()] = 0;
  for (HalfedgeHandle h : loop) {
    twins.for_each_twin(mesh.to_vertex_handle(h).idx(), [&](int t) {
      if (d[t] > 0) {
        d[t] = 0;
        q.push_back(t);
      }
    });
  }
  for (size_t i = 0; i < loop.size(); ++i) {
    for (HalfedgeHandle g = mesh.next_halfedge_handle(loop[i]);;
         g = mesh.next_halfedge_handle(mesh.opposite_halfedge_handle(g))) {
      const int y = mesh.to_vertex_handle(g).idx();
      if (d[y] > 1) {
        d[y] = 1;
        q.push_back(y);
      }
      if (g == loop[(i + 1) % loop.size()]) break;
    }
  }
  while (!q.empty()) {
    const int x = q.front();
    q.pop_front();
    twins.for_each_twin(x, [&](int t) {
      if (d[t] > d[x]) {
        d[t] = d[x];
        q.push_front(t);
      }
    });
    for (VertexHandle y : mesh.vv_range(VertexHandle(x))) {
      if (d[y.idx()] > d[x] + 1) {
        d[y.idx()] = d[x] + 1;
        q.push_back(y.idx());
      }
    }
  }
  for (int& v : d) {
    if (v == std::numeric_limits<int>::max()) v = -1;
  }
  return d;
}

// ---- the shape -------------------------------------------------------------------------------

TEST(PinchedBody, ClosedManifoldPartsJoinedOnlyByTheirThreeTwinGroups) {
  const shapes::PinchedBody& b = body();
  const Mesh& mesh = b.mesh;
  EXPECT_EQ(mesh.n_vertices(), b.input_vertices + 3);
  for (VertexHandle v : mesh.vertices()) {
    EXPECT_TRUE(mesh.is_manifold(v)) << v.idx();
    EXPECT_FALSE(mesh.is_boundary(v)) << v.idx();
  }
  double volume = 0;
  for (FaceHandle f : mesh.faces()) {
    std::vector<Vec3> p;
    for (VertexHandle v : mesh.fv_range(f)) p.push_back(mesh.point(v));
    volume += OpenMesh::dot(p[0], OpenMesh::cross(p[1], p[2])) / 6;
  }
  EXPECT_GT(volume, 0);  // outward
  for (size_t k = 0; k < 3; ++k) {
    const auto& g = b.pinches[k];
    EXPECT_LT(g[0].idx(), static_cast<int>(b.input_vertices));  // the original, then its copy
    EXPECT_GE(g[1].idx(), static_cast<int>(b.input_vertices));
    EXPECT_EQ(twins_of(mesh, g[0]), std::vector<VertexHandle>{g[1]});
    EXPECT_EQ(mesh.point(g[0]), mesh.point(g[1]));
  }
  EXPECT_EQ(mesh.point(centre_up()), Vec3(0, 0, 0));
  EXPECT_EQ(mesh.point(b.pinches[0][0]), Vec3(2, 0, 0));
  EXPECT_EQ(mesh.point(b.pinches[1][0]), Vec3(-2, 0, 0));
  // Three components without the links, one with them.
  const std::vector<int> apart = twin_hops(unlinked(), {VertexHandle(0)});
  EXPECT_EQ(std::count(apart.begin(), apart.end(), -1),
            static_cast<long>(b.cone_sides[0].size() + b.cone_sides[1].size() + 4));
  const std::vector<int> joined = twin_hops(mesh, {VertexHandle(0)});
  EXPECT_EQ(std::count(joined.begin(), joined.end(), -1), 0);
  // Mirror-symmetric in z, positions exactly.
  for (VertexHandle v : mesh.vertices()) {
    const Vec3 p = mesh.point(v), q(p[0], p[1], -p[2]);
    EXPECT_EQ(mesh.point(vertex_at(mesh, q)), q) << v.idx();
  }
  // The cones' lateral vertices lie on straight lines from their apexes through the first ring.
  for (int c = 0; c < 2; ++c) {
    const Vec3 a = at(mesh, apex_copy(c));
    for (int m = 0; m < kAround; ++m) {
      const Vec3 u = (at(mesh, cone_side(c, 1, m)) - a).normalized();
      for (int t = 2; t <= cone_rings(); ++t) {
        EXPECT_NEAR(OpenMesh::dot((at(mesh, cone_side(c, t, m)) - a).normalized(), u), 1.0, 1e-14);
      }
    }
  }
  EXPECT_THROW(shapes::pinched_body(7), InvalidInput);
  EXPECT_THROW(shapes::pinched_body(4), InvalidInput);
}

// ---- distances -------------------------------------------------------------------------------

struct Mode {
  std::string name;
  DistanceMethod method;
  bool track_front = true;
  bool table = false;
};
const std::vector<Mode>& modes() {
  static const std::vector<Mode> m = {
      {"mdf", DistanceMethod::Mdf},
      {"mdf-untracked", DistanceMethod::Mdf, false},
      {"windows", DistanceMethod::Windows},
      {"fast", DistanceMethod::Fast},
      {"fast-table", DistanceMethod::Fast, true, true},
      {"dijkstra", DistanceMethod::Dijkstra},
      {"dijkstra-table", DistanceMethod::Dijkstra, true, true},
  };
  return m;
}

template <class Source>
DistanceField field(const Mesh& mesh, const Mode& mode, const Source& source, DistanceOptions o = {}) {
  o.method = mode.method;
  o.track_front = mode.track_front;
  if (!mode.table) return geodesic_distance(mesh, source, o);
  const GeodesicRingTable table(mesh);
  if (mode.method != DistanceMethod::Dijkstra) return geodesic_distance(mesh, table, source, o);
  if constexpr (std::is_same_v<Source, FrontSource>) return dijkstra_distance(mesh, table, source, o);
  return geodesic_distance(mesh, source, o);  // (no table variant for points)
}

// Every group of twins has one distance (and one direction, to round-off), and the settle order
// is non-decreasing and lists each reached vertex once.
void expect_one_point_per_group(const Mesh& mesh, const DistanceField& f, const std::string& what) {
  for (const auto& g : body().pinches) {
    EXPECT_EQ(f.distance[g[0].idx()], f.distance[g[1].idx()]) << what << " twins " << g[0].idx();
    if (!f.direction.empty()) {
      EXPECT_LT((f.direction[g[0].idx()] - f.direction[g[1].idx()]).norm(), 1e-12) << what << " twins " << g[0].idx();
    }
  }
  std::vector<int> seen(mesh.n_vertices(), 0);
  for (size_t i = 0; i < f.order.size(); ++i) {
    EXPECT_EQ(seen[f.order[i].idx()]++, 0) << what;
    if (i > 0) {
      EXPECT_GE(f.distance[f.order[i].idx()], f.distance[f.order[i - 1].idx()] * (1 - 1e-12)) << what << " at " << i;
    }
  }
  size_t reached = 0;
  for (double d : f.distance) reached += std::isfinite(d);
  EXPECT_EQ(reached, f.order.size()) << what;
}

// From a cone's side to the other cone: through both cone pinches. The cones are developable
// and every lateral vertex lies on a straight edge path from the apex: each method gives the apex
// the source's slant distance, and every lateral vertex of the other cone its apex's distance
// plus its own slant distance (the sum of the parts).
TEST(PinchedDistances, AcrossTheConePinchesDistancesAreTheSumOfTheParts) {
  const Mesh& mesh = body().mesh;
  const VertexHandle s = cone_side(0, cone_rings(), 2);
  const double slant0 = (at(mesh, s) - at(mesh, apex_copy(0))).norm();
  for (const Mode& mode : modes()) {
    const DistanceField f = field(mesh, mode, FrontSource::vertex(s));
    EXPECT_EQ(f.stop, DistanceStop::Exhausted) << mode.name;
    expect_one_point_per_group(mesh, f, mode.name);
    EXPECT_EQ(f.order.size(), mesh.n_vertices()) << mode.name;  // all of it, through the pinches
    EXPECT_NEAR(f.distance[apex_copy(0).idx()], slant0, 1e-12 * slant0) << mode.name;
    const double d1 = f.distance[apex_copy(1).idx()];
    EXPECT_GT(d1, slant0 + 3.9) << mode.name;  // beyond the torus (4 apart in a straight line)
    for (VertexHandle q : body().cone_sides[1]) {
      const double expected = d1 + (at(mesh, q) - at(mesh, apex_copy(1))).norm();
      EXPECT_NEAR(f.distance[q.idx()], expected, 1e-12 * expected) << mode.name << " vertex " << q.idx();
    }
    for (VertexHandle v : mesh.vertices()) {
      EXPECT_GE(f.distance[v.idx()], (at(mesh, v) - at(mesh, s)).norm() * (1 - 1e-12)) << mode.name;
    }
    // The same mesh without its twin links: the source's cone is all there is.
    const DistanceField apart = field(unlinked(), mode, FrontSource::vertex(s));
    EXPECT_EQ(apart.order.size(), body().cone_sides[0].size() + 2) << mode.name;
    EXPECT_EQ(apart.distance[apex_copy(1).idx()], kInf) << mode.name;
  }
}

// The pinch inside the body: from the torus vertex next to the centre on the upper side, its
// mirror image on the lower side is reached through the centre (twice the edge), not around the
// tube; from the centre itself the field is mirror-symmetric.
TEST(PinchedDistances, ThroughThePinchInsideTheBody) {
  const Mesh& mesh = body().mesh;
  const VertexHandle up = near_centre(true), down = near_centre(false);
  const double edge = (at(mesh, up) - at(mesh, centre_up())).norm();
  for (const Mode& mode : modes()) {
    const DistanceField f = field(mesh, mode, FrontSource::vertex(up));
    expect_one_point_per_group(mesh, f, mode.name);
    EXPECT_NEAR(f.distance[centre_down().idx()], edge, 1e-15) << mode.name;
    EXPECT_NEAR(f.distance[down.idx()], 2 * edge, 1e-12 * edge) << mode.name;
    const DistanceField apart = field(unlinked(), mode, FrontSource::vertex(up));
    EXPECT_GT(apart.distance[down.idx()], 4 * edge) << mode.name;  // around the tube

    const DistanceField c = field(mesh, mode, FrontSource::vertex(centre_up()));
    expect_one_point_per_group(mesh, c, mode.name);
    EXPECT_EQ(c.distance[centre_down().idx()], 0.0) << mode.name;
    double worst = 0;
    for (VertexHandle v : mesh.vertices()) {
      const Vec3 p = mesh.point(v);
      const double d = c.distance[v.idx()], m = c.distance[vertex_at(mesh, Vec3(p[0], p[1], -p[2])).idx()];
      ASSERT_TRUE(std::isfinite(d)) << mode.name;
      worst = std::max(worst, std::abs(d - m) / std::max(d, 1e-300));
    }
    EXPECT_LT(worst, 1e-12) << mode.name;
  }
}

// Sources at a pinch, surface points, loops, max_distance and target.
TEST(PinchedDistances, PointLoopBoundedAndTargetQueries) {
  const Mesh& mesh = body().mesh;
  const VertexHandle down = near_centre(false);
  // A point in a face of the upper fan at the centre: the centre is a corner of its face.
  FaceHandle face;
  for (FaceHandle f : mesh.vf_range(centre_up())) face = f;
  const SurfacePoint p{face, {0.2, 0.3, 0.5}};
  Vec3 x(0, 0, 0);
  int k = 0;
  for (VertexHandle v : mesh.fv_range(face)) x += mesh.point(v) * p.bary[k++];
  const double to_centre = x.norm();
  const double edge = (at(mesh, down) - at(mesh, centre_down())).norm();
  // The torus's outer equator as a loop: it passes both cone pinches, whose copies (the apexes)
  // lie on it too: each cone's lateral vertices are at their slant distance, on both sides.
  std::vector<VertexHandle> equator;
  for (int i = 0; i < kAround; ++i) equator.push_back(torus_vertex(i, 0));
  for (const Mode& mode : modes()) {
    SCOPED_TRACE(mode.name);
    const std::vector<SurfacePoint> points{p};
    const DistanceField f = field(mesh, mode, points);
    expect_one_point_per_group(mesh, f, mode.name);
    EXPECT_NEAR(f.distance[centre_down().idx()], to_centre, 1e-12) << mode.name;
    EXPECT_NEAR(f.distance[down.idx()], to_centre + edge, 1e-12) << mode.name;

    for (LoopSide side : {LoopSide::Left, LoopSide::Right}) {
      SCOPED_TRACE("equator loop");
      const DistanceField l = field(mesh, mode, loop_from_vertices(mesh, equator, side));
      expect_one_point_per_group(mesh, l, mode.name);
      for (int c = 0; c < 2; ++c) {
        EXPECT_EQ(l.distance[apex_copy(c).idx()], 0.0) << mode.name;
        for (VertexHandle q : body().cone_sides[static_cast<size_t>(c)]) {
          const double slant = (at(mesh, q) - at(mesh, apex_copy(c))).norm();
          EXPECT_NEAR(l.distance[q.idx()], slant, 1e-12 * slant) << mode.name << " vertex " << q.idx();
        }
      }
    }
    // A loop around a cone's first ring, facing away from its apex: the rest of the body lies
    // behind it (reached only through the apex), facing the apex: all of it, through the pinch.
    std::vector<VertexHandle> ring;
    for (int m = 0; m < kAround; ++m) ring.push_back(cone_side(0, 1, m));
    // The apex's distance to the loop: to its vertices (Dijkstra) or to its segments (at least).
    const double ring_slant = (at(mesh, ring[0]) - at(mesh, apex_copy(0))).norm();
    const Vec3 seg = at(mesh, ring[1]) - at(mesh, ring[0]);
    const double to_segment = OpenMesh::cross(seg, at(mesh, apex_copy(0)) - at(mesh, ring[0])).norm() / seg.norm();
    size_t reached[2] = {0, 0};
    for (LoopSide side : {LoopSide::Left, LoopSide::Right}) {
      SCOPED_TRACE("cone loop");
      const DistanceField l = field(mesh, mode, loop_from_vertices(mesh, ring, side));
      const bool to_apex = std::isfinite(l.distance[apex_copy(0).idx()]);
      reached[to_apex] = l.order.size();
      if (to_apex) {
        EXPECT_LE(l.distance[apex_copy(0).idx()], ring_slant * (1 + 1e-12)) << mode.name;
        EXPECT_GE(l.distance[apex_copy(0).idx()], to_segment * (1 - 1e-12)) << mode.name;
        EXPECT_EQ(l.distance[body().pinches[0][0].idx()], l.distance[apex_copy(0).idx()]) << mode.name;
        const double d1 = l.distance[apex_copy(1).idx()];
        for (VertexHandle q : body().cone_sides[1]) {
          const double expected = d1 + (at(mesh, q) - at(mesh, apex_copy(1))).norm();
          EXPECT_NEAR(l.distance[q.idx()], expected, 1e-12 * expected) << mode.name;
        }
      }
    }
    EXPECT_EQ(reached[1], mesh.n_vertices() - (kAround * (cone_rings() - 1) + 1)) << mode.name;
    EXPECT_EQ(reached[0], static_cast<size_t>(kAround * cone_rings() + 1)) << mode.name;

    // Bounded: past the first pinch, not to the second.
    const VertexHandle s = cone_side(0, cone_rings(), 0);
    const DistanceField full = field(mesh, mode, FrontSource::vertex(s));
    const double bound = full.distance[apex_copy(0).idx()] + 1.0;
    const DistanceField b = field(mesh, mode, FrontSource::vertex(s), {.max_distance = bound});
    EXPECT_EQ(b.stop, DistanceStop::MaxDistance) << mode.name;
    expect_one_point_per_group(mesh, b, mode.name);
    EXPECT_TRUE(std::isfinite(b.distance[body().pinches[0][0].idx()])) << mode.name;
    EXPECT_EQ(b.distance[apex_copy(1).idx()], kInf) << mode.name;
    for (VertexHandle v : b.order) EXPECT_EQ(b.distance[v.idx()], full.distance[v.idx()]) << mode.name;
    // A target beyond both pinches.
    const VertexHandle target = cone_side(1, 1, 5);
    const DistanceField t = field(mesh, mode, FrontSource::vertex(s), {.target = target});
    EXPECT_EQ(t.stop, DistanceStop::TargetReached) << mode.name;
    EXPECT_EQ(t.order.back(), target) << mode.name;
    EXPECT_EQ(t.distance[target.idx()], full.distance[target.idx()]) << mode.name;
  }
}

// The stepwise front, with and without windows: the edge front under the distances stays valid
// at every step and passes into each part through its pinch.
TEST(PinchedDistances, StepwiseFrontStaysValidThroughThePinches) {
  const Mesh& mesh = body().mesh;
  for (DistanceMethod method : {DistanceMethod::Mdf, DistanceMethod::Windows}) {
    MinimalDistanceFront front(mesh);
    std::vector<double> settled(mesh.n_vertices(), -1);
    front.set_settled_callback([&](VertexHandle v, double d, const Vec3&) { settled[v.idx()] = d; });
    front.reset(FrontSource::vertex(cone_side(0, 2, 3)), {.method = method});
    size_t steps = 0, peak = 0;
    while (front.step()) {
      front.validate();
      peak = std::max(peak, front.front_size());
      ++steps;
    }
    EXPECT_EQ(steps, mesh.n_vertices());
    EXPECT_EQ(front.front_size(), 0u);  // every part closed: the front annihilated everywhere
    EXPECT_GT(peak, 0u);
    for (double d : settled) EXPECT_GE(d, 0);
  }
}

// ---- level fronts ---------------------------------------------------------------------------

TEST(PinchedLevels, MefAndVfLevelsAreHopDistancesWithTwinsOnePoint) {
  const Mesh& mesh = body().mesh;
  std::vector<FrontSource> sources = {FrontSource::vertex(cone_side(0, cone_rings(), 0)),
                                      FrontSource::vertex(near_centre(true)), FrontSource::vertex(centre_down()),
                                      FrontSource::from_vertices({cone_side(1, 1, 0), VertexHandle(7)})};
  std::vector<VertexHandle> ring, equator;
  for (int m = 0; m < kAround; ++m) ring.push_back(cone_side(0, 1, m));
  for (int i = 0; i < kAround; ++i) equator.push_back(torus_vertex(i, 0));
  for (LoopSide side : {LoopSide::Left, LoopSide::Right}) sources.push_back(loop_from_vertices(mesh, ring, side));
  const size_t first_equator = sources.size();  // the equator loops come last
  for (LoopSide side : {LoopSide::Left, LoopSide::Right}) {
    sources.push_back(loop_from_vertices(mesh, equator, side));  // through two pinches
  }
  for (size_t i = 0; i < sources.size(); ++i) {
    const FrontSource& src = sources[i];
    const std::vector<int> mef = edge_front_levels(mesh, src), vf = vertex_front_levels(mesh, src);
    EXPECT_EQ(mef, vf) << "source " << i;
    EXPECT_EQ(mef, twin_hops(mesh, src.vertices, src.loop)) << "source " << i;
    for (const auto& g : body().pinches) EXPECT_EQ(mef[g[0].idx()], mef[g[1].idx()]) << "source " << i;

    // Stepwise: valid after every expansion and at every level boundary (with the checks that
    // need the enclosed set), each vertex enclosed once (a loop's vertex twice where the front
    // comes back to it from behind: the equator's, through the centre), whatever order a level is
    // taken in.
    for (uint64_t seed : {0u, 5u}) {
      MinimalEdgeFront front(mesh, {.track_loops = true, .debug_tracking = true, .order_seed = seed});
      std::vector<int> enclosed(mesh.n_vertices(), 0), level(mesh.n_vertices(), -1);
      size_t pinch_events = 0;
      front.set_enclosed_callback([&](VertexHandle v, int l) {
        if (enclosed[v.idx()]++ == 0) level[v.idx()] = l;
      });
      front.set_event_callback([&](const FrontEvent& e) {
        if (e.kind != FrontEvent::Kind::Pinch) return;
        ++pinch_events;
        EXPECT_EQ(front.front_level(e.vertex), e.level);  // joins as the level being built
      });
      front.reset(src);
      while (front.step()) front.validate();
      front.validate();
      EXPECT_TRUE(front.exhausted());
      EXPECT_EQ(level, mef) << "source " << i << " seed " << seed;
      const bool whole = std::count(mef.begin(), mef.end(), -1) == 0;
      for (VertexHandle v : mesh.vertices()) {
        const bool on_loop = std::any_of(src.loop.begin(), src.loop.end(),
                                         [&](HalfedgeHandle h) { return mesh.to_vertex_handle(h) == v; });
        if (mef[v.idx()] >= 0) {
          EXPECT_EQ(enclosed[v.idx()], on_loop && i >= first_equator ? 2 : 1) << v.idx() << " source " << i;
        }
      }
      // A pinch the front passes is reported where a twin joins only through it: the cones'
      // (the centre's twins are reached from both sides at once, by the symmetry).
      if (i == 0) {
        EXPECT_EQ(pinch_events, 2u);
      }
      if (whole && !src.is_loop()) {
        EXPECT_GE(pinch_events, 1u);
      }
      EXPECT_EQ(front.loop_count(), front.loops().size());
    }
  }
}

// Loops at a pinch: from a cone's side, a new loop starts beyond its apex (the torus's fan) and
// the count drops again where a part is used up.
TEST(PinchedLevels, APinchStartsALoopOfItsOwn) {
  const Mesh& mesh = body().mesh;
  MinimalEdgeFront front(mesh, {.track_loops = true});
  std::vector<FrontEvent> pinches;
  front.set_event_callback([&](const FrontEvent& e) {
    if (e.kind == FrontEvent::Kind::Pinch) pinches.push_back(e);
  });
  front.reset(FrontSource::vertex(cone_side(0, 1, 0)));
  std::vector<size_t> loops;
  while (front.advance_level()) {
    front.validate();
    loops.push_back(front.loop_count());
  }
  ASSERT_EQ(pinches.size(), 2u);  // the cones' apexes (the centre is reached from both sides at once)
  EXPECT_EQ(pinches[0].vertex, body().pinches[0][0]);  // the apex is next to the source: level 1
  EXPECT_EQ(pinches[0].level, 1);
  ASSERT_GE(loops.size(), 3u);
  // Level 1 ends with the cone's loop; level 2 has the torus's loop beside it.
  EXPECT_EQ(loops[0], 1u);
  EXPECT_EQ(loops[1], 2u);
  EXPECT_EQ(loops.back(), 0u);
}

// ---- connection paths -----------------------------------------------------------------------

void expect_chain(const Mesh& mesh, const ConnectionPath& p, VertexHandle from, VertexHandle to,
                  const std::string& what) {
  ASSERT_EQ(p.status, PathStatus::Found) << what;
  ASSERT_FALSE(p.vertices.empty()) << what;
  EXPECT_EQ(p.vertices.front(), from) << what;
  EXPECT_EQ(p.vertices.back(), to) << what;
  size_t edges = 0, twin_steps = 0;
  for (size_t i = 1; i < p.vertices.size(); ++i) {
    const auto tw = twins_of(mesh, p.vertices[i - 1]);
    const bool twin = std::find(tw.begin(), tw.end(), p.vertices[i]) != tw.end();
    const bool edge = mesh.find_halfedge(p.vertices[i - 1], p.vertices[i]).is_valid();
    EXPECT_TRUE(twin || edge) << what << " step " << i;
    edges += edge;
    twin_steps += twin;
  }
  EXPECT_EQ(p.edges, edges) << what;
  EXPECT_EQ(twin_steps, 2u) << what;  // through both cone pinches
}

TEST(PinchedPaths, PathsPassThroughThePinches) {
  const Mesh& mesh = body().mesh;
  const VertexHandle from = cone_side(0, cone_rings(), 1), to = cone_side(1, cone_rings(), 4);
  const int hops = twin_hops(mesh, {from})[to.idx()];
  const double exact = geodesic_distance(mesh, FrontSource::vertex(from), {.method = DistanceMethod::Windows})
                           .distance[to.idx()];
  ConnectionPathFinder finder(mesh);
  for (PathMethod method : {PathMethod::VertexFront, PathMethod::MinimalEdgeFront, PathMethod::MinimalDistance}) {
    for (int variant = 0; variant < 4; ++variant) {
      ConnectionPathOptions o{.method = method};
      o.confine = variant == 1;
      o.directed = variant == 2;
      o.mdf_recursion = variant == 3;
      o.polyline = method == PathMethod::MinimalDistance;
      const std::string what = "method " + std::to_string(static_cast<int>(method)) + " variant " + std::to_string(variant);
      const ConnectionPath p = finder.find(from, to, o);
      expect_chain(mesh, p, from, to, what);
      if (method != PathMethod::MinimalDistance) {
        EXPECT_EQ(p.edges, static_cast<size_t>(hops)) << what;
        continue;
      }
      // The polyline passes both pinch points; its pieces share faces.
      ASSERT_GE(p.polyline.size(), 3u) << what;
      size_t twin_points = 0;
      for (size_t i = 1; i < p.polyline.size(); ++i) {
        const PathPoint &a = p.polyline[i - 1], &b = p.polyline[i];
        if (a.vertex.is_valid() && b.vertex.is_valid()) {
          const auto tw = twins_of(mesh, a.vertex);
          if (std::find(tw.begin(), tw.end(), b.vertex) != tw.end()) {
            ++twin_points;
            EXPECT_EQ(a.position, b.position) << what;
          }
        }
      }
      EXPECT_EQ(twin_points, 2u) << what;
      EXPECT_NEAR(p.polyline_length, exact, 1e-3 * exact) << what;
      EXPECT_EQ(p.length, p.polyline_length) << what;
    }
  }
  // Twins are one point: the path between them has no edge.
  const ConnectionPath same = finder.find(body().pinches[2][0], body().pinches[2][1]);
  EXPECT_EQ(same.vertices, (std::vector<VertexHandle>{body().pinches[2][0], body().pinches[2][1]}));
  EXPECT_EQ(same.edges, 0u);
  EXPECT_EQ(same.length, 0.0);
  // Many targets from one source, traced through the pinches.
  const std::vector<VertexHandle> targets = {to, near_centre(false), cone_side(0, 1, 0)};
  const std::vector<ConnectionPath> many = finder.find_many(from, targets, {.method = PathMethod::MinimalEdgeFront});
  const std::vector<int> h = twin_hops(mesh, {from});
  for (size_t i = 0; i < targets.size(); ++i) {
    ASSERT_EQ(many[i].status, PathStatus::Found);
    EXPECT_EQ(many[i].edges, static_cast<size_t>(h[targets[i].idx()]));
  }
  // Without the links the parts are apart.
  EXPECT_EQ(connection_path(unlinked(), from, to).status, PathStatus::NoPath);
}

TEST(PinchedPaths, PolylineOfAChainThroughAPinch) {
  const Mesh& mesh = body().mesh;
  const VertexHandle up = near_centre(true), down = near_centre(false);
  bool converged = false;
  const std::vector<PathPoint> line = geodesic_polyline(mesh, {up, centre_up(), centre_down(), down}, 100, &converged);
  EXPECT_TRUE(converged);
  ASSERT_EQ(line.size(), 4u);
  EXPECT_EQ(line[1].vertex, centre_up());
  EXPECT_EQ(line[2].vertex, centre_down());
  EXPECT_NEAR(polyline_length(line), 2 * (at(mesh, up) - at(mesh, centre_up())).norm(), 1e-12);
  EXPECT_THROW(geodesic_polyline(mesh, {up, down}), InvalidInput);  // neither an edge nor twins
  const std::vector<PathPoint> banded = band_polyline(mesh, line, 0.5);
  EXPECT_EQ(banded.size(), 4u);
}

// ---- several fans at one point in a mesh built in code -----------------------------------------

// Three triangles sharing only vertex 0: OpenMesh keeps them as one vertex with three fans.
Mesh three_wings() {
  Mesh mesh;
  const VertexHandle c = mesh.add_vertex({0, 0, 0});
  for (int k = 0; k < 3; ++k) {
    const double a = 2 * M_PI * k / 3;
    const VertexHandle p = mesh.add_vertex({std::cos(a), std::sin(a), 0});
    const VertexHandle q = mesh.add_vertex({std::cos(a + 0.5), std::sin(a + 0.5), 0});
    mesh.add_face(c, p, q);
  }
  return mesh;
}

TEST(PinchedMeshInCode, UnsplitVertexIsRefusedNamingTheSplitAndRunsOnceSplit) {
  Mesh mesh = three_wings();
  ASSERT_FALSE(mesh.is_manifold(VertexHandle(0)));
  for (const Mode& mode : modes()) {
    if (mode.method == DistanceMethod::Dijkstra) continue;  // edges only: it runs
    try {
      field(mesh, mode, FrontSource::vertex(VertexHandle(1)));
      ADD_FAILURE() << mode.name << " accepted a non-manifold vertex";
    } catch (const TopologyError& e) {
      EXPECT_NE(std::string(e.what()).find("split_pinched_vertices"), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(edge_front_levels(mesh, FrontSource::vertex(VertexHandle(1))), TopologyError);

  const std::vector<VertexHandle> origin = split_pinched_vertices(mesh);
  ASSERT_EQ(origin, (std::vector<VertexHandle>{VertexHandle(0), VertexHandle(0)}));
  ASSERT_EQ(mesh.n_vertices(), 9u);
  EXPECT_EQ(twins_of(mesh, VertexHandle(0)), (std::vector<VertexHandle>{VertexHandle(7), VertexHandle(8)}));
  const Vec3 p1 = mesh.point(VertexHandle(1));
  for (const Mode& mode : modes()) {
    const DistanceField f = field(mesh, mode, FrontSource::vertex(VertexHandle(1)));
    EXPECT_EQ(f.order.size(), 9u) << mode.name;
    for (int v = 3; v <= 6; ++v) {  // the other wings: through the centre
      const double expected = p1.norm() + mesh.point(VertexHandle(v)).norm();
      EXPECT_NEAR(f.distance[v], expected, 1e-12) << mode.name << " vertex " << v;
    }
  }
  const std::vector<int> levels = edge_front_levels(mesh, FrontSource::vertex(VertexHandle(1)));
  EXPECT_EQ(levels, (std::vector<int>{1, 0, 1, 2, 2, 2, 2, 1, 1}));
  EXPECT_EQ(vertex_front_levels(mesh, FrontSource::vertex(VertexHandle(1))), levels);
  const ConnectionPath p = connection_path(mesh, VertexHandle(1), VertexHandle(5), {.method = PathMethod::MinimalEdgeFront});
  EXPECT_EQ(p.edges, 2u);
  EXPECT_EQ(p.vertices.size(), 4u);
}

}  // namespace
