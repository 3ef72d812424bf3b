// The fast mode (DistanceMethod::Fast): one rule over the rings of a GeodesicRingTable, or over
// rings laid out from the mesh as their vertices settle (the per-call mode).

#include <algorithm>
#include <cmath>
#include <span>
#include <string>
#include <vector>

#include "detail/distance_common.h"
#include "detail/min_heap.h"
#include "detail/prefetch.h"
#include "edgefront/error.h"
#include "edgefront/geodesic_ring_table.h"
#include "edgefront/vertex_twins.h"

namespace edgefront {

using detail::check_distance_options;
using detail::kFlatDefect;
using detail::kTwoPi;
using detail::check_points;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// ---- Fast mode (DistanceMethod::Fast) ---------------------------------------------------------
//
// A Dijkstra over per-mesh arrays whose relaxation is one straight line in polar coordinates. The
// ring of a settled vertex x is developed into the plane by its corner angles (ring angle theta,
// 0 .. the angle sum). x keeps the distance r to its virtual source, the source's ring angle phi and
// the distance already travelled before that source (d - r: 0 for the real source, more behind a
// pseudo source). A neighbour c at ring angle theta_c and distance l from x takes, with
// alpha = phi - theta_c (the shorter way round on a closed ring),
//   d - r + sqrt(r^2 + l^2 - 2 r l cos alpha)           (law of cosines), or
//   d + l with x as pseudo source when |alpha| >= pi    (the source is in x's shadow: a saddle
//                                                        or a border corner),
// clamped to at least the straight (3D) distance from the real source and at most d + l. c keeps
// the direction toward the virtual source relative to its edge c -> x (two components); it becomes
// c's own ring angle when c settles and walks its ring.

struct FastRec {
  double d = kInf;
  double r = 0;        // distance to the virtual source (d - r travelled before it)
  double a = 0, b = 0;  // toward the virtual source: along the edge to `parent` and across it
  int parent = -1;     // -1: no direction (a vertex source)
  double bound = kInf;  // the smallest d + edge length offered by a settled neighbour (Dijkstra's value)
  int origin = -1;     // the real source the value comes from (index into the origins)
  uint8_t settled = 0;
  uint8_t by_face = 0;  // the value comes from a face with two settled corners (it overrides the others)
  uint8_t twin = 0;     // the value comes from the twin `parent` (a pinched vertex): a pseudo source
};

struct FastSeed {
  int v;  // mesh index (and rec.parent)
  FastRec rec;
};

// A queued vertex: its index in the rings (a table's locality order) and in the mesh. Equal
// distances pop by mesh index, so a query on a table settles in the per-call mode's order.
struct Node {
  int x;  // rings index
  int v;  // mesh index
  bool operator<(const Node& o) const { return v < o.v; }
};
using Heap = detail::MinHeap4<double, Node>;

// One edge of the ring of the vertex being settled, in walk order: the table's entries with the
// ring angle summed from the ring's first edge.
struct Ray {
  int v;       // rings index
  int vertex;  // mesh index
  double len;
  double theta;                 // ring angle
  double cos_theta, sin_theta;  // of theta, as the product of the corners' rotations (no cos/sin calls)
  const GeodesicRingTable::Corner* c;  // e, the corner after this edge (cos, sin, angle), face_after
};
using Rays = std::span<const Ray>;

// Ring angle of a direction given relative to ray j (components along it and across it).
double fast_angle(Rays ring, size_t j, double a, double b, bool closed, double total) {
  double phi = ring[j].theta + std::atan2(b, a);
  if (closed) {
    if (phi < 0) phi += total;
    if (phi >= total) phi -= total;
  } else {
    phi = std::clamp(phi, 0.0, total);
  }
  return phi;
}

// The unit 3D vector at ring angle phi (inside the face whose corner contains it); cos_phi and
// sin_phi are phi's cosine and sine.
Vec3 fast_direction(Rays ring, size_t first, double phi, double cos_phi, double sin_phi) {
  const size_t m = ring.size();
  size_t i = first;
  for (size_t k = 0; k + 1 < m; ++k) {
    const size_t nx = i + 1 == m ? 0 : i + 1;
    if (!ring[i].c->face_after || ring[nx].theta > phi || nx == first) break;
    i = nx;
  }
  const size_t nx = i + 1 == m ? 0 : i + 1;
  if (!(ring[i].len > 0)) return Vec3(0, 0, 0);
  const Vec3 u = ring[i].c->e / ring[i].len;
  Vec3 w = ring[nx].c->e - OpenMesh::dot(ring[nx].c->e, u) * u;
  const double lw = w.norm();
  if (!ring[i].c->face_after || !(lw > 0)) return u;
  w /= lw;
  // cos and sin of phi - theta_i.
  const Ray& ri = ring[i];
  return (cos_phi * ri.cos_theta + sin_phi * ri.sin_theta) * u + (sin_phi * ri.cos_theta - cos_phi * ri.sin_theta) * w;
}

// A vertex's ring: its shape and its edges (neighbour, length, corner) in walk order.
struct RingView {
  const GeodesicRingTable::Ring& info;
  std::span<const GeodesicRingTable::Edge> edges;
  std::span<const GeodesicRingTable::Corner> corners;
};

// Rings read from a prebuilt table.
struct TableRings {
  const GeodesicRingTable& table;
  size_t n_vertices() const { return table.n_vertices(); }
  int index(int v) const { return table.index(VertexHandle(v)); }  // of mesh vertex v
  int vertex(int x) const { return table.vertex(x).idx(); }        // mesh index at rings index x
  RingView operator()(int x) const { return {table.ring(x), table.edges(x), table.corners(x)}; }
  // Look-ahead: the next vertex's ring header, then (once that is in the cache) its edges and corners.
  void prefetch_header(int x) const { detail::prefetch(&table.ring(x)); }
  void prefetch_edges(int x) const {
    const GeodesicRingTable::Ring& r = table.ring(x);
    if (r.size == 0) return;
    detail::prefetch(table.edges(x).data());
    const GeodesicRingTable::Corner* c = table.corners(x).data();
    for (size_t b = 0; b < r.size * sizeof(GeodesicRingTable::Corner); b += 64) detail::prefetch(reinterpret_cast<const char*>(c) + b);
  }
};

// Rings laid out from the mesh when their vertex settles (the per-call mode: no table to build).
struct MeshRings {
  const Mesh& mesh;
  GeodesicRingTable::Ring info;
  std::vector<GeodesicRingTable::Edge> edges;
  std::vector<GeodesicRingTable::Corner> corners;
  size_t n_vertices() const { return mesh.n_vertices(); }
  int index(int v) const { return v; }
  int vertex(int x) const { return x; }
  RingView operator()(int x) {
    edges.clear();
    corners.clear();
    info = detail::layout_ring(mesh, x, edges, corners);
    return {info, edges, corners};
  }
  // Look-ahead: the next vertex's record and position, then its first outgoing halfedge.
  void prefetch_header(int x) const {
    detail::prefetch(&mesh.vertex(VertexHandle(x)));
    detail::prefetch(&mesh.point(VertexHandle(x)));
  }
  void prefetch_edges(int x) const {
    const HalfedgeHandle h = mesh.halfedge_handle(VertexHandle(x));
    if (h.is_valid()) detail::prefetch(&mesh.halfedge(h));
  }
};

template <class Rings>
DistanceField fast_field(Rings&& rings, const TwinRing& twins, const std::vector<FastSeed>& seeds,
                         const std::vector<Vec3>& origins, const DistanceOptions& o) {
  const size_t n = rings.n_vertices();
  std::vector<FastRec> rec(n);  // by rings index, as every index below but the output's
  Heap heap;
  for (const FastSeed& s : seeds) {
    const int x = rings.index(s.v);
    FastRec& r = rec[x];
    if (s.rec.d < r.d) {
      r = s.rec;
      if (r.parent >= 0) r.parent = rings.index(r.parent);
      heap.push(r.d, Node{x, s.v});
    }
  }

  DistanceField out;
  out.distance.assign(n, kInf);
  if (o.directions) out.direction.assign(n, Vec3(0, 0, 0));
  out.stop = DistanceStop::Exhausted;
  size_t peak = heap.size();
  std::vector<Ray> ring;  // the ring of the vertex being settled
  while (!heap.empty()) {
    // Plain names, not a structured binding: C++20 lambdas may capture those, but clang 14 cannot.
    const double d = heap.top().first;
    const Node node = heap.top().second;
    const int x = node.x;
    heap.pop();
    if (!heap.empty()) {
      const Node next = heap.top().second;
      rings.prefetch_header(next.x);
      detail::prefetch(&out.distance[static_cast<size_t>(next.v)]);  // the output, in mesh order
      if (o.directions) detail::prefetch(&out.direction[static_cast<size_t>(next.v)]);
    }
    FastRec& rx = rec[x];
    if (rx.settled || d != rx.d) continue;
    if (d > o.max_distance) {
      out.stop = DistanceStop::MaxDistance;
      break;
    }
    rx.settled = 1;
    out.distance[node.v] = d;
    out.order.push_back(VertexHandle(node.v));

    // x's ring (laid out once per mesh by a table, or now), its ring angles summed from its first edge.
    const RingView view = rings(x);
    const GeodesicRingTable::Ring& info = view.info;
    if (info.non_manifold) {
      throw TopologyError("distance: vertex " + std::to_string(node.v) +
                          " is non-manifold (several fans meet there): split it with edgefront::split_pinched_vertices "
                          "(edgefront/vertex_twins.h) before computing distances");
    }
    // A pinched vertex's twins (one point of the surface) take its distance and its direction (also
    // when one came as near from its own side: one value per point), each a pseudo source for its
    // own fan (no straight line continues through a point).
    if (twins.any()) [[unlikely]] {
      twins.for_each_twin(node.v, [&](int t) {
        const int tx = rings.index(t);
        FastRec& rt = rec[tx];
        if (rt.settled) return;
        rt = FastRec{};
        rt.d = d;
        rt.bound = d;
        rt.parent = x;
        rt.origin = rx.origin;
        rt.twin = 1;
        heap.push(d, Node{tx, t});
      });
    }
    const Vec3& px = info.point;
    const size_t m = info.size;
    const bool closed = info.closed, flat = info.flat;
    const size_t first = info.first;
    {
      ring.resize(m);
      double theta = 0, cos_theta = 1, sin_theta = 0;
      for (size_t k = 0, i = first; k < m; ++k) {
        const GeodesicRingTable::Corner& c = view.corners[i];
        ring[i] = Ray{view.edges[i].v, view.edges[i].vertex, view.edges[i].len, theta, cos_theta, sin_theta, &c};
        if (c.face_after) {
          theta += c.angle_after;
          const double c2 = cos_theta * c.cos_after - sin_theta * c.sin_after;
          sin_theta = sin_theta * c.cos_after + cos_theta * c.sin_after;
          cos_theta = c2;
        }
        i = i + 1 == m ? 0 : i + 1;
      }
    }
    const double total = info.total, cos_total = info.cos_total, sin_total = info.sin_total;
    // The source's ring angle (none at a source vertex or when the parent is not in the ring).
    double phi = 0;
    bool aimed = false;
    if (rx.parent >= 0 && rx.r > 0) {
      for (size_t j = 0; j < m; ++j) {
        if (ring[j].v == rx.parent) {
          phi = fast_angle(ring, j, rx.a, rx.b, closed, total);
          aimed = true;
          break;
        }
      }
    }
    // phi's cosine and sine: one call per settled vertex; the neighbours' angles to the source are
    // rotations of it by their own ring angles.
    double cos_phi = 1, sin_phi = 0;
    if (aimed) {
      cos_phi = std::cos(phi);
      sin_phi = std::sin(phi);
    }
    if (o.directions && aimed) out.direction[node.v] = fast_direction(ring, first, phi, cos_phi, sin_phi);
    if (o.directions && rx.twin) out.direction[node.v] = out.direction[static_cast<size_t>(rings.vertex(rx.parent))];
    if (o.target && o.target->idx() == node.v) {
      out.stop = DistanceStop::TargetReached;
      break;
    }
    const Vec3& origin = origins[static_cast<size_t>(rx.origin)];
    const double r = aimed ? rx.r : 0.0;
    const double before = d - r;
    for (size_t i = 0; i < m; ++i) {
      const Ray& ry = ring[i];
      FastRec& rc = rec[ry.v];
      if (rc.settled) continue;
      double alpha = phi - ry.theta;
      double cos_a = cos_phi * ry.cos_theta + sin_phi * ry.sin_theta;  // of alpha, before the wrap
      double sin_a = sin_phi * ry.cos_theta - cos_phi * ry.sin_theta;
      if (closed) {
        // The shorter way round: alpha -/+ the angle sum (a rotation by it).
        const double turn = alpha > 0.5 * total ? -1.0 : alpha < -0.5 * total ? 1.0 : 0.0;
        if (turn != 0) {
          alpha += turn * total;
          const double c2 = cos_a * cos_total - turn * sin_a * sin_total;
          sin_a = sin_a * cos_total + turn * cos_a * sin_total;
          cos_a = c2;
        }
      }
      double cr = 0, ca = 0, cb = 0, cd = kInf;
      double bent = kInf, bent_x = 0, bent_y = 0;  // the path bent at a ring vertex p: |S - p| + |p - c|, p - c
      const size_t prev = i == 0 ? m - 1 : i - 1;
      const size_t next = i + 1 == m ? 0 : i + 1;
      // A face (x, c, y) whose corner y is settled too, from the same source and offset: the
      // virtual source where the circles of radius r around x and y meet (on the side away from c),
      // if the line from it to c crosses the edge x-y. No angle needed: the face's own layout.
      bool by_face = false;
      const bool lit = r > 0 && std::abs(alpha) < M_PI;  // a straight line from x's source
      if (!lit) {
        cos_a = 1;
        sin_a = 0;
      }
      for (int sgn = 1; sgn >= -1; sgn -= 2) {
        const Ray& corner = sgn > 0 ? ry : ring[prev];
        if (!corner.c->face_after) continue;
        const Ray& fy = sgn > 0 ? ring[next] : ring[prev];
        const FastRec& yr = rec[fy.v];
        if (!yr.settled || yr.origin != rx.origin || !(fy.len > 0)) continue;
        const double r_y = yr.parent >= 0 ? yr.r : 0.0;
        if (std::abs((yr.d - r_y) - before) > 1e-9 * d) continue;
        const double ly = fy.len, cg = corner.c->cos_after, sg = corner.c->sin_after;
        // x's own source must lie beyond the line x-y (the circles also meet at its mirror image).
        if (r > 0 && !(lit && sgn * sin_a * cg - cos_a * sg > -1e-9)) continue;
        const double u = (r * r - r_y * r_y + ly * ly) / (2 * ly);
        const double h2 = r * r - u * u;
        if (h2 < -1e-9 * (r * r + ly * ly)) continue;
        const double hh = std::sqrt(std::max(h2, 0.0));
        const double cn = ry.len * sg;  // c's distance from the line x-y
        if (!(hh + cn > 0)) continue;
        const double cross_at = u + hh / (hh + cn) * (ry.len * cg - u);
        if (cross_at < -1e-9 * ly || cross_at > ly * (1 + 1e-9)) continue;
        // The source in x's layout (c on the x axis, the walk's positive side up).
        const double sx = u * cg - hh * sg, sy = sgn * (u * sg + hh * cg);
        const double fa = ry.len - sx, fb = -sy, fr = std::sqrt(fa * fa + fb * fb);
        if (before + fr < cd) {
          cd = before + fr;
          cr = fr;
          ca = fa;
          cb = fb;
          by_face = true;
        }
      }
      if (!by_face && lit) {
        ca = ry.len - r * cos_a;
        cb = -r * sin_a;
        // The line from c toward the source must leave c through the face between c and the ring
        // neighbour y on the source's side (the corner x-c-y): y not on x's side of it.
        const Ray* fy = alpha >= 0 ? (ry.c->face_after ? &ring[next] : nullptr)
                                       : (ring[prev].c->face_after ? &ring[prev] : nullptr);
        if (fy) {
          const Ray& corner = alpha >= 0 ? ry : ring[prev];
          // In x's development, c on the x axis, the source side up: S - c = (-ca, |cb|).
          const double yx = fy->len * corner.c->cos_after - ry.len, yy = fy->len * corner.c->sin_after;
          const double side = -ca * yy - std::abs(cb) * yx;
          bool inside = side <= 1e-12 * (std::abs(ca) + std::abs(cb)) * (std::abs(yx) + yy);
          // When the line from c to the source passes an edge of x beyond its end p, the shortest
          // path inside x's laid-out faces bends at p (p - c = (px_, py_) in this frame).
          const auto bend = [&](double px_, double py_) {
            bent_x = px_;
            bent_y = py_;
            const double sx = -ca - px_, sy = std::abs(cb) - py_;
            bent = std::sqrt(sx * sx + sy * sy) + std::sqrt(px_ * px_ + py_ * py_);
          };
          // And, unless x is intrinsically flat, it must cross every edge of x between c and the
          // source inside the edge (the ring is laid out exactly only up to its outer edges).
          double t = 0, ct = 1, st = 0;
          size_t k = i;
          for (size_t steps = flat ? m : 0; inside && steps < m; ++steps) {
            const size_t kc = alpha >= 0 ? k : (k == 0 ? m - 1 : k - 1);  // the corner crossed
            const Ray& cr_ray = ring[kc];
            if (!cr_ray.c->face_after) {
              inside = false;
              break;
            }
            t += cr_ray.c->angle_after;
            if (t >= std::abs(alpha)) break;
            const double c2 = ct * cr_ray.c->cos_after - st * cr_ray.c->sin_after;
            st = st * cr_ray.c->cos_after + ct * cr_ray.c->sin_after;
            ct = c2;
            k = alpha >= 0 ? (k + 1 == m ? 0 : k + 1) : kc;
            const double den = ct * std::abs(cb) + st * ca;  // cross(ray, S - c), S - c = (-ca, |cb|)
            if (!(den > 0) || ry.len * std::abs(cb) > ring[k].len * (1 + 1e-9) * den) {
              inside = false;
              bend(ring[k].len * ct - ry.len, ring[k].len * st);
            }
          }
          if (inside) {
            cr = std::sqrt(ca * ca + cb * cb);
            cd = before + cr;
          }
        }
      }
      if (cd == kInf && before + bent < d + ry.len) {
        // The ring vertex p as a pseudo source; c's direction toward it (the source side's sign).
        cd = before + bent;
        cr = std::sqrt(bent_x * bent_x + bent_y * bent_y);
        ca = -bent_x;
        cb = alpha >= 0 ? -bent_y : bent_y;
      }
      if (cd == kInf) {
        cr = ca = ry.len;
        cb = 0;
        cd = d + ry.len;
      }
      // Never below the straight line from the source, nor below x's own distance: vertices settle
      // in non-decreasing order, so every neighbour nearer than d + edge length settles first and
      // its bound holds (never above Dijkstra).
      const double straight2 = (px + ry.c->e - origin).sqrnorm();  // no square root when cd is above it
      if (!(cd * cd >= straight2)) cd = std::max(cd, std::sqrt(straight2));
      cd = std::max(cd, d);
      if (d + ry.len < rc.bound) rc.bound = d + ry.len;
      if (cd > rc.bound) {
        cd = rc.bound;
        if (cd == d + ry.len) {
          cr = ca = ry.len;
          cb = 0;
        }
      }
      // A face value overrides the others; any value is taken when it is shorter and c's value is
      // above the bound.
      if (by_face ? (rc.by_face && !(cd < rc.d)) : (!(cd < rc.d) || (rc.by_face && !(rc.d > rc.bound)))) continue;
      rc.by_face = by_face;
      rc.d = cd;
      rc.r = cr;
      rc.a = ca;
      rc.b = cb;
      rc.parent = x;
      rc.origin = rx.origin;
      heap.push(cd, Node{ry.v, ry.vertex});
    }
    peak = std::max(peak, heap.size());
    if (!heap.empty()) rings.prefetch_edges(heap.top().second.x);
  }
  out.peak_front = 0;
  out.peak_working_memory_bytes = n * sizeof(FastRec) + peak * sizeof(Heap::Entry) +
                                  ring.capacity() * sizeof(Ray);
  return out;
}

// The field from the seeds over the table's rings, or over rings laid out from the mesh (`table`
// null: the per-call mode).
DistanceField run(const Mesh& mesh, const GeodesicRingTable* table, const std::vector<FastSeed>& seeds,
                  const std::vector<Vec3>& origins, const DistanceOptions& options) {
  const TwinRing twins(mesh);
  if (!table) return fast_field(MeshRings{mesh, {}, {}, {}}, twins, seeds, origins, options);
  table->check(mesh);
  return fast_field(TableRings{*table}, twins, seeds, origins, options);
}

// The field from vertices (not a loop), after the checks.
DistanceField from_vertices(const Mesh& mesh, const GeodesicRingTable* table, const FrontSource& source,
                            const DistanceOptions& options) {
  validate_source(mesh, source);
  check_distance_options(mesh, options);
  std::vector<Vec3> origins;
  std::vector<FastSeed> seeds;
  for (VertexHandle v : source.vertices) {
    FastRec r;
    r.d = 0;
    r.origin = static_cast<int>(origins.size());
    seeds.push_back(FastSeed{v.idx(), r});
    origins.push_back(mesh.point(v));
  }
  return run(mesh, table, seeds, origins, options);
}

// The field from surface points, after the checks.
DistanceField from_points(const Mesh& mesh, const GeodesicRingTable* table, const std::vector<SurfacePoint>& points,
                          const DistanceOptions& options) {
  check_distance_options(mesh, options);
  check_points(mesh, points);
  std::vector<Vec3> origins;
  std::vector<FastSeed> seeds;
  for (const SurfacePoint& p : points) {
    const Vec3 x = surface_point_position(mesh, p);
    for (HalfedgeHandle h : mesh.fh_range(p.face)) {
      // The face lies before h (v -> w) in the ring walk of v: the point is at a negative angle.
      const VertexHandle v = mesh.from_vertex_handle(h);
      const Vec3 ew = mesh.point(mesh.to_vertex_handle(h)) - mesh.point(v);
      const Vec3 ep = x - mesh.point(v);
      FastRec r;
      r.d = r.r = ep.norm();
      const double lw = ew.norm();
      if (lw > 0) {
        r.a = OpenMesh::dot(ep, ew) / lw;
        r.b = -OpenMesh::cross(ew, ep).norm() / lw;
        r.parent = mesh.to_vertex_handle(h).idx();
      }
      r.origin = static_cast<int>(origins.size());
      seeds.push_back(FastSeed{v.idx(), r});
    }
    origins.push_back(x);
  }
  return run(mesh, table, seeds, origins, options);
}

}  // namespace

namespace detail {
DistanceField fast_distance(const Mesh& mesh, const FrontSource& source, const DistanceOptions& options) {
  return from_vertices(mesh, nullptr, source, options);
}
DistanceField fast_distance(const Mesh& mesh, const std::vector<SurfacePoint>& points, const DistanceOptions& options) {
  return from_points(mesh, nullptr, points, options);
}
}  // namespace detail

DistanceField geodesic_distance(const Mesh& mesh, const GeodesicRingTable& table, const FrontSource& source,
                                const DistanceOptions& options) {
  if (source.is_loop()) {
    DistanceOptions o = options;
    o.method = DistanceMethod::Mdf;  // a loop source runs the MDF
    return geodesic_distance(mesh, source, o);
  }
  return from_vertices(mesh, &table, source, options);
}

DistanceField geodesic_distance(const Mesh& mesh, const GeodesicRingTable& table,
                                const std::vector<SurfacePoint>& points, const DistanceOptions& options) {
  return from_points(mesh, &table, points, options);
}

}  // namespace edgefront
