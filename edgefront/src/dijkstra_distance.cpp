// The baseline: Dijkstra over mesh edges (binary heap), over the mesh's halfedges or a
// GeodesicRingTable.

#include <algorithm>
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

namespace edgefront {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Dijkstra's state: a binary heap of (distance, vertex) and per-vertex arrays.
struct DijkstraRun {
  using Entry = std::pair<double, int>;
  DistanceField out;
  std::vector<int> via;
  std::vector<uint8_t> done;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> heap;

  explicit DijkstraRun(size_t n) : via(n, -1), done(n, 0) { out.distance.assign(n, kInf); }

  void offer(int y, int from, double d) {
    if (!done[y] && d < out.distance[y]) {
      out.distance[y] = d;
      via[y] = from;
      heap.emplace(d, y);
    }
  }

  // Settles vertices in distance order; edges(v, f) calls f(y, |v - y|) for every neighbour y of v,
  // point(v) is v's position (for the directions), look_ahead(v, stage) may prefetch what edges(v)
  // reads (stage 0 right after the previous vertex is popped, 1 when its neighbours are done).
  template <class Edges, class Point, class LookAhead>
  DistanceField run(const DistanceOptions& options, Edges&& edges, Point&& point, LookAhead&& look_ahead) {
    const size_t n = done.size();
    out.stop = DistanceStop::Exhausted;
    size_t peak = 0;
    while (!heap.empty()) {
      const auto [d, v] = heap.top();
      heap.pop();
      if (!heap.empty()) look_ahead(heap.top().second, 0);
      if (done[v] || d != out.distance[v]) continue;
      if (d > options.max_distance) {
        out.distance[v] = kInf;
        out.stop = DistanceStop::MaxDistance;
        break;
      }
      done[v] = 1;
      out.order.push_back(VertexHandle(v));
      if (options.target && options.target->idx() == v) {
        out.stop = DistanceStop::TargetReached;
        break;
      }
      edges(v, [&](int y, double len) { offer(y, v, d + len); });
      peak = std::max(peak, heap.size());
      if (!heap.empty()) look_ahead(heap.top().second, 1);
    }
    // Unsettled tentative values are not answers.
    for (size_t v = 0; v < n; ++v) {
      if (!done[v]) out.distance[v] = kInf;
    }
    if (options.directions) {
      out.direction.assign(n, Vec3(0, 0, 0));
      for (size_t v = 0; v < n; ++v) {
        if (via[v] >= 0 && done[v]) {
          const Vec3 dv = point(via[v]) - point(static_cast<int>(v));
          const double l = dv.norm();
          if (l > 0) out.direction[v] = dv / l;
        }
      }
    }
    out.peak_working_memory_bytes = n * (sizeof(double) + sizeof(int) + 1) + peak * sizeof(Entry);
    return std::move(out);
  }
};

}  // namespace

DistanceField dijkstra_distance(const Mesh& mesh, const FrontSource& source, const DistanceOptions& options) {
  validate_source(mesh, source);
  detail::check_distance_options(mesh, options);
  DijkstraRun dij(mesh.n_vertices());
  if (source.is_loop()) {
    for (HalfedgeHandle h : source.loop) {
      const int v = mesh.to_vertex_handle(h).idx();
      dij.out.distance[v] = 0;
      dij.heap.emplace(0.0, v);
    }
    // First step only into the ahead wedges; loop vertices are never re-entered.
    const size_t m = source.loop.size();
    for (size_t i = 0; i < m; ++i) {
      const int x = mesh.to_vertex_handle(source.loop[i]).idx();
      dij.done[x] = 1;
      HalfedgeHandle g = mesh.next_halfedge_handle(source.loop[i]);
      while (true) {
        const int y = mesh.to_vertex_handle(g).idx();
        dij.offer(y, x, (mesh.point(VertexHandle(y)) - mesh.point(VertexHandle(x))).norm());
        if (g == source.loop[(i + 1) % m]) break;
        g = mesh.next_halfedge_handle(mesh.opposite_halfedge_handle(g));
      }
    }
    for (HalfedgeHandle h : source.loop) dij.out.order.push_back(mesh.to_vertex_handle(h));
  } else {
    for (VertexHandle v : source.vertices) {
      dij.out.distance[v.idx()] = 0;
      dij.heap.emplace(0.0, v.idx());
    }
  }
  const auto point = [&](int v) -> const Vec3& { return mesh.point(VertexHandle(v)); };
  return dij.run(
      options,
      [&](int v, auto&& f) {
        const Vec3& pv = point(v);
        for (VertexHandle y : mesh.vv_range(VertexHandle(v))) f(y.idx(), (mesh.point(y) - pv).norm());
      },
      point, [](int, int) {});
}

DistanceField dijkstra_distance(const Mesh& mesh, const GeodesicRingTable& table, const FrontSource& source,
                                const DistanceOptions& options) {
  if (source.is_loop()) return dijkstra_distance(mesh, source, options);
  validate_source(mesh, source);
  detail::check_distance_options(mesh, options);
  table.check(mesh);
  DijkstraRun dij(table.n_vertices());
  for (VertexHandle v : source.vertices) {
    dij.out.distance[v.idx()] = 0;
    dij.heap.emplace(0.0, v.idx());
  }
  return dij.run(
      options,
      [&](int v, auto&& f) {
        for (const GeodesicRingTable::Edge& e : table.edges(v)) f(e.v, e.len);
      },
      [&](int v) -> const Vec3& { return table.ring(v).point; },
      [&](int v, int stage) {  // the same look-ahead as the fast mode's on a table
        if (stage == 0) {
          detail::prefetch(&table.ring(v));
        } else if (table.ring(v).size > 0) {
          detail::prefetch(table.edges(v).data());
        }
      });
}

}  // namespace edgefront
