// The baseline: Dijkstra over mesh edges (binary heap), over the mesh's halfedges or a
// GeodesicRingTable.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <queue>
#include <utility>
#include <vector>

#include "detail/distance_common.h"
#include "detail/prefetch.h"
#include "edgefront/geodesic_ring_table.h"
#include "edgefront/minimal_distance_front.h"
#include "edgefront/vertex_twins.h"

namespace edgefront {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// A queued vertex: its mesh index in the high 32 bits, its index in the edges' numbering (a
// table's locality order, or the mesh's) in the low ones. Equal distances pop by mesh index, so
// Dijkstra over a table settles in the same order as over the mesh.
using Key = std::uint64_t;
Key key_of(int vertex, int x) {
  return static_cast<Key>(static_cast<std::uint32_t>(vertex)) << 32 | static_cast<std::uint32_t>(x);
}
int index_of(Key k) { return static_cast<int>(k & 0xffffffffu); }
int vertex_of(Key k) { return static_cast<int>(k >> 32); }

// Dijkstra's state: a binary heap of (distance, vertex) and per-vertex arrays, by the edges'
// numbering; `out` by mesh index.
struct DijkstraRun {
  using Entry = std::pair<double, Key>;
  DistanceField out;
  std::vector<double> dist;  // tentative distances
  std::vector<int> via;
  std::vector<uint8_t> done;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> heap;
  bool twins_reached = false;  // a twin took its distance from a twin (see offer_twin)

  explicit DijkstraRun(size_t n) : dist(n, kInf), via(n, -1), done(n, 0) { out.distance.assign(n, kInf); }

  void seed(int x, int vertex, double d = 0) {
    if (!(d < dist[x])) return;
    dist[x] = d;
    heap.emplace(d, key_of(vertex, x));
  }

  void offer(int y, int vertex, int from, double d) {
    if (!done[y] && d < dist[y]) {
      dist[y] = d;
      via[y] = from;
      heap.emplace(d, key_of(vertex, y));
    }
  }

  // A twin (a pinched vertex: one point of the surface) of `from`, which settled at d, takes d and
  // `from` as its way, also when its own side gave it the same distance (one value per point).
  void offer_twin(int y, int vertex, int from, double d) {
    if (done[y] || d > dist[y]) return;
    twins_reached = true;
    if (d < dist[y]) heap.emplace(d, key_of(vertex, y));  // (an equal one is queued already)
    dist[y] = d;
    via[y] = from;
  }

  // Settles vertices in distance order; edges(x, f) calls f(y, mesh index of y, |x - y|) for every
  // neighbour y of x, twin_links(x, g) calls g(y, mesh index of y) for every twin y of x, point(x)
  // is x's position and vertex(x) its mesh index (for the directions), look_ahead(x, stage) may
  // prefetch what edges(x) reads (stage 0 right after the previous vertex is popped, 1 when its
  // neighbours are done).
  template <class Edges, class TwinLinks, class Point, class Vertex, class LookAhead>
  DistanceField run(const DistanceOptions& options, Edges&& edges, TwinLinks&& twin_links, Point&& point,
                    Vertex&& vertex, LookAhead&& look_ahead) {
    const size_t n = done.size();
    out.stop = DistanceStop::Exhausted;
    size_t peak = 0;
    while (!heap.empty()) {
      const auto [d, key] = heap.top();
      const int x = index_of(key);
      heap.pop();
      if (!heap.empty()) {
        look_ahead(index_of(heap.top().second), 0);
        detail::prefetch(&out.distance[static_cast<size_t>(vertex_of(heap.top().second))]);  // in mesh order
      }
      if (done[x] || d != dist[x]) continue;
      if (d > options.max_distance) {
        out.stop = DistanceStop::MaxDistance;
        break;
      }
      done[x] = 1;
      out.distance[static_cast<size_t>(vertex_of(key))] = d;
      out.order.push_back(VertexHandle(vertex_of(key)));
      if (options.target && options.target->idx() == vertex_of(key)) {
        out.stop = DistanceStop::TargetReached;
        break;
      }
      // d by an init-capture: clang 14 (the fuzz build) cannot capture a structured binding.
      edges(x, [&, dist = d](int y, int vy, double len) { offer(y, vy, x, dist + len); });
      twin_links(x, [&, dist = d](int y, int vy) { offer_twin(y, vy, x, dist); });
      peak = std::max(peak, heap.size());
      if (!heap.empty()) look_ahead(index_of(heap.top().second), 1);
    }
    if (options.directions) {
      out.direction.assign(n, Vec3(0, 0, 0));
      for (size_t x = 0; x < n; ++x) {
        if (via[x] >= 0 && done[x]) {
          const Vec3 dv = point(via[x]) - point(static_cast<int>(x));
          const double l = dv.norm();
          if (l > 0) out.direction[static_cast<size_t>(vertex(static_cast<int>(x)))] = dv / l;
        }
      }
      if (twins_reached) {
        // A twin reached from its twin (the first of its group to settle, whose way runs through
        // its own fan) points where that one points.
        for (size_t x = 0; x < n; ++x) {
          if (via[x] >= 0 && done[x] && point(via[x]) == point(static_cast<int>(x))) {
            out.direction[static_cast<size_t>(vertex(static_cast<int>(x)))] =
                out.direction[static_cast<size_t>(vertex(via[x]))];
          }
        }
      }
    }
    out.peak_working_memory_bytes = n * (sizeof(double) + sizeof(int) + 1) + peak * sizeof(Entry);
    return std::move(out);
  }
};

// |x - y|; a vertex with a NaN or infinite coordinate is refused when an edge reaches it.
double edge_length(const Mesh& mesh, int x, int y) {
  const Vec3& px = mesh.point(VertexHandle(x));
  const Vec3& py = mesh.point(VertexHandle(y));
  const double len = (py - px).norm();
  if (!std::isfinite(len)) {
    detail::check_finite_vertex(px, x);
    detail::check_finite_vertex(py, y);
  }
  return len;
}

// A mesh without twins: no twin links (the run is compiled without them).
constexpr auto no_twins = [](int, auto&&) {};

// Dijkstra's run over the mesh's own edges, from the seeds in `dij`. A vertex with a NaN or
// infinite coordinate is refused when an edge reaches it.
DistanceField run_over_mesh(const Mesh& mesh, DijkstraRun& dij, const DistanceOptions& options) {
  const auto point = [&](int v) -> const Vec3& { return mesh.point(VertexHandle(v)); };
  const auto edges = [&](int v, auto&& f) {
    for (VertexHandle y : mesh.vv_range(VertexHandle(v))) f(y.idx(), y.idx(), edge_length(mesh, v, y.idx()));
  };
  const TwinRing twins(mesh);
  if (!twins.any()) return dij.run(options, edges, no_twins, point, [](int v) { return v; }, [](int, int) {});
  return dij.run(
      options, edges, [&](int v, auto&& g) { twins.for_each_twin(v, [&](int t) { g(t, t); }); }, point,
      [](int v) { return v; }, [](int, int) {});
}

}  // namespace

DistanceField dijkstra_distance(const Mesh& mesh, const FrontSource& source, const DistanceOptions& options) {
  validate_source(mesh, source);
  detail::check_distance_options(mesh, options);
  DijkstraRun dij(mesh.n_vertices());
  if (source.is_loop()) {
    for (HalfedgeHandle h : source.loop) {
      const int v = mesh.to_vertex_handle(h).idx();
      dij.seed(v, v);
      dij.out.distance[static_cast<size_t>(v)] = 0;  // settled below
    }
    // First step only into the ahead wedges; loop vertices are never re-entered. Their twins
    // (pinched vertices) lie on the loop too, with their whole fans ahead.
    const size_t m = source.loop.size();
    const TwinRing twins(mesh);
    for (size_t i = 0; i < m; ++i) {
      const int x = mesh.to_vertex_handle(source.loop[i]).idx();
      dij.done[x] = 1;
      twins.for_each_twin(x, [&](int t) { dij.offer_twin(t, t, x, 0.0); });
      HalfedgeHandle g = mesh.next_halfedge_handle(source.loop[i]);
      while (true) {
        const int y = mesh.to_vertex_handle(g).idx();
        dij.offer(y, y, x, edge_length(mesh, x, y));
        if (g == source.loop[(i + 1) % m]) break;
        g = mesh.next_halfedge_handle(mesh.opposite_halfedge_handle(g));
      }
    }
    for (HalfedgeHandle h : source.loop) dij.out.order.push_back(mesh.to_vertex_handle(h));
  } else {
    for (VertexHandle v : source.vertices) {
      detail::check_finite_vertex(mesh.point(v), v.idx());
      dij.seed(v.idx(), v.idx());
    }
  }
  return run_over_mesh(mesh, dij, options);
}

DistanceField dijkstra_distance(const Mesh& mesh, const std::vector<SurfacePoint>& points,
                                const DistanceOptions& options) {
  detail::check_distance_options(mesh, options);
  detail::check_points(mesh, points);
  DijkstraRun dij(mesh.n_vertices());
  for (const SurfacePoint& p : points) {
    const Vec3 x = surface_point_position(mesh, p);
    for (VertexHandle v : mesh.fv_range(p.face)) dij.seed(v.idx(), v.idx(), (mesh.point(v) - x).norm());
  }
  return run_over_mesh(mesh, dij, options);
}

DistanceField dijkstra_distance(const Mesh& mesh, const GeodesicRingTable& table, const FrontSource& source,
                                const DistanceOptions& options) {
  if (source.is_loop()) return dijkstra_distance(mesh, source, options);
  validate_source(mesh, source);
  detail::check_distance_options(mesh, options);
  table.check(mesh);
  DijkstraRun dij(table.n_vertices());
  for (VertexHandle v : source.vertices) dij.seed(table.index(v), v.idx());
  const auto edges = [&](int x, auto&& f) {
    for (const GeodesicRingTable::Edge& e : table.edges(x)) f(e.v, e.vertex, e.len);
  };
  const auto point = [&](int x) -> const Vec3& { return table.ring(x).point; };
  const auto vertex = [&](int x) { return table.vertex(x).idx(); };
  const auto look_ahead = [&](int v, int stage) {  // the same look-ahead as the fast mode's on a table
    if (stage == 0) {
      detail::prefetch(&table.ring(v));
    } else if (table.ring(v).size > 0) {
      detail::prefetch(table.edges(v).data());
    }
  };
  const TwinRing twins(mesh);
  if (!twins.any()) return dij.run(options, edges, no_twins, point, vertex, look_ahead);
  const auto twin_links = [&](int x, auto&& g) {
    twins.for_each_twin(table.vertex(x).idx(), [&](int t) { g(table.index(VertexHandle(t)), t); });
  };
  return dij.run(options, edges, twin_links, point, vertex, look_ahead);
}

}  // namespace edgefront
