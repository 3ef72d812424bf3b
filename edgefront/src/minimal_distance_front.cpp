#include "edgefront/minimal_distance_front.h"

#include <algorithm>
#include <cmath>
#include <queue>
#include <string>

#include "detail/edge_front_core.h"

namespace edgefront {

using detail::EdgeFrontCore;
using detail::VRec;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// Normals closer than this count as one plane (unfolding is then the identity).
constexpr double kSmoothDot = 0.985;
// Two corners see the same virtual source when the unfolded sources lie this close (relative).
constexpr double kConsistency = 0.05;

// Distance record of a vertex that is reached and still needed: tentative, or settled with
// neighbours that are not settled yet (they may still take their distance from it).
struct DRec {
  double d = kInf;
  Vec3 source{0, 0, 0};  // virtual source: where the source lies, unfolded into the plane of `face`
  double offset = 0;     // distance already travelled at `source` (a pseudo source: a vertex the
                         // shortest path bends around, such as a saddle or a border corner)
  int face = -1;         // the plane of `source`; -1 when `source` needs no unfolding (a source point)
  int loop_in = -1;      // loop sources: the loop halfedge into this vertex (its ahead wedge)
  Vec3 normal{0, 0, 0};  // unit normal of `face`, filled in when the vertex settles
  int unsettled = 0;     // neighbours not settled yet
  bool settled = false;
};

Vec3 face_normal(const Mesh& mesh, int f) {
  auto h = mesh.halfedge_handle(FaceHandle(f));
  const Vec3& a = mesh.point(mesh.from_vertex_handle(h));
  h = mesh.next_halfedge_handle(h);
  const Vec3& b = mesh.point(mesh.from_vertex_handle(h));
  const Vec3& c = mesh.point(mesh.to_vertex_handle(h));
  Vec3 n = OpenMesh::cross(b - a, c - a);
  const double l = n.norm();
  return l > 0 ? n / l : n;
}

// Rotates p about the line through `o` so that the plane with normal n1 maps onto the plane with
// normal n2 (the unfolding across the line where the two planes meet).
Vec3 unfold(const Vec3& p, const Vec3& o, const Vec3& n1, const Vec3& n2) {
  Vec3 k = OpenMesh::cross(n1, n2);
  const double s = k.norm();
  const double c = OpenMesh::dot(n1, n2);
  if (s < 1e-15) return p;  // coplanar (or folded flat: nothing sensible to rotate)
  k /= s;
  const Vec3 v = p - o;
  // Rodrigues: v cos + (k x v) sin + k (k.v)(1 - cos), with sin = s, cos = c.
  return o + v * c + OpenMesh::cross(k, v) * s + k * (OpenMesh::dot(k, v) * (1 - c));
}

std::string dname(double d) { return std::to_string(d); }

}  // namespace

struct MinimalDistanceFront::Impl : EdgeFrontCore {
  detail::FlatMap<DRec> dt;
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> heap;
  DistanceOptions opts;
  DistanceStop stop = DistanceStop::NotStarted;
  size_t n_settled = 0;
  size_t peak_heap = 0;
  bool line_source = false;
  std::function<void(VertexHandle, double, const Vec3&)> on_settled;

  explicit Impl(const Mesh& m) : EdgeFrontCore(m, MinimalEdgeFrontOptions{}) {}

  void on_join(int, VRec& rec) override { rec.level = 0; }
  int event_level() const override { return 0; }

  void check_options(const DistanceOptions& o) const {
    if (std::isnan(o.max_distance) || o.max_distance < 0) {
      throw InvalidInput("distance: max_distance must be a non-negative number, got " + dname(o.max_distance));
    }
    if (o.target && !is_live(mesh, *o.target)) {
      throw InvalidInput("distance: target vertex " + std::to_string(o.target->idx()) + " is not a vertex of the mesh");
    }
  }

  void clear_state(const DistanceOptions& o) {
    check_options(o);
    opts = o;
    dt.clear();
    heap = decltype(heap)();
    stop = DistanceStop::NotStarted;
    n_settled = 0;
    peak_heap = 0;
    line_source = false;
  }

  int count_unsettled(int v) const {
    int n = 0;
    for (VertexHandle y : mesh.vv_range(VertexHandle(v))) {
      const DRec* r = dt.find(static_cast<uint32_t>(y.idx()));
      n += !(r && r->settled);
    }
    return n;
  }

  DRec& record(int v) {
    auto [r, inserted] = dt.insert(static_cast<uint32_t>(v), DRec{});
    if (inserted) r->unsettled = count_unsettled(v);
    return *r;
  }

  void offer(int v, double d, const Vec3& s, double offset, int face) {
    DRec& r = record(v);
    if (r.settled || !(d < r.d)) return;
    r.d = d;
    r.source = s;
    r.offset = offset;
    r.face = face;
    heap.emplace(d, v);
    peak_heap = std::max(peak_heap, heap.size());
  }

  void reset(const FrontSource& source, const DistanceOptions& o) {
    clear_state(o);
    reset_structure(source);
    line_source = source.is_loop();
    if (!line_source) {
      for (uint32_t v : sources) offer(static_cast<int>(v), 0.0, mesh.point(VertexHandle(static_cast<int>(v))), 0.0, -1);
    } else {
      for (HalfedgeHandle h : source.loop) {
        const int v = mesh.to_vertex_handle(h).idx();
        offer(v, 0.0, mesh.point(VertexHandle(v)), 0.0, -1);
        record(v).loop_in = h.idx();
      }
    }
    note_memory();
  }

  void reset(const std::vector<SurfacePoint>& points, const DistanceOptions& o) {
    check_options(o);
    if (points.empty()) throw InvalidInput("distance: no source points given");
    std::vector<VertexHandle> verts;
    for (size_t i = 0; i < points.size(); ++i) {
      const SurfacePoint& p = points[i];
      const std::string which = "distance: source point " + std::to_string(i);
      if (!is_live(mesh, p.face)) {
        throw InvalidInput(which + ": face " + std::to_string(p.face.idx()) + " is not a face of the mesh");
      }
      double sum = 0;
      for (double b : p.bary) {
        if (!std::isfinite(b) || b < -1e-12) {
          throw InvalidInput(which + ": barycentric coordinates must be finite and non-negative");
        }
        sum += b;
      }
      if (std::abs(sum - 1.0) > 1e-9) {
        throw InvalidInput(which + ": barycentric coordinates sum to " + dname(sum) + ", not 1");
      }
      for (VertexHandle v : mesh.fv_range(p.face)) {
        if (std::find(verts.begin(), verts.end(), v) == verts.end()) verts.push_back(v);
      }
    }
    clear_state(o);
    reset_structure(FrontSource::from_vertices(verts));
    for (const SurfacePoint& p : points) {
      Vec3 x(0, 0, 0);
      int k = 0;
      for (VertexHandle v : mesh.fv_range(p.face)) x += mesh.point(v) * p.bary[k++];
      for (VertexHandle v : mesh.fv_range(p.face)) offer(v.idx(), (mesh.point(v) - x).norm(), x, 0.0, p.face.idx());
    }
    note_memory();
  }

  // Is the straight line from `s` to `c` (all in the plane with normal n) arriving through the
  // segment a-b of the face (a, b, c)? `interior_ab` says whether a face lies beyond a-b.
  static bool arrives_through(const Vec3& s, const Vec3& pc, const Vec3& pa, const Vec3& pb, const Vec3& n,
                              bool interior_ab) {
    const Vec3 ca = pa - pc, cb = pb - pc, cs = s - pc;
    const double scale = ca.sqrnorm() + cb.sqrnorm() + cs.sqrnorm();
    const double tol = 1e-12 * scale;
    const double sab = OpenMesh::dot(n, OpenMesh::cross(ca, cb));
    const double sas = OpenMesh::dot(n, OpenMesh::cross(ca, cs)) * (sab < 0 ? -1 : 1);
    const double ssb = OpenMesh::dot(n, OpenMesh::cross(cs, cb)) * (sab < 0 ? -1 : 1);
    if (sas < -tol || ssb < -tol) return false;  // outside the corner at c
    // Beyond the line a-b (seen from c): then the path crosses a-b and needs a face there.
    const double side_c = OpenMesh::dot(n, OpenMesh::cross(pb - pa, pc - pa));
    const double side_s = OpenMesh::dot(n, OpenMesh::cross(pb - pa, s - pa));
    const bool beyond = side_c * side_s < -tol * std::abs(side_c);
    return !beyond || interior_ab;
  }

  // The candidate distances of `c` from its settled neighbour `x` (record `rx`), offered to `c`.
  // `hxc` is the halfedge x -> c.
  void propagate(int x, const DRec& rx, int c, HalfedgeHandle hxc) {
    const Vec3& px = mesh.point(VertexHandle(x));
    const Vec3& pc = mesh.point(VertexHandle(c));
    const Vec3 xc = px - pc;
    const double e = xc.norm();
    const HalfedgeHandle hcx = mesh.opposite_halfedge_handle(hxc);
    const int f_left = mesh.face_handle(hxc).idx(), f_right = mesh.face_handle(hcx).idx();

    // (1) Through x as a vertex: the Dijkstra bound; x becomes the pseudo source.
    offer(c, rx.d + e, px, rx.d, f_left >= 0 ? f_left : f_right);
    if (rx.d == rx.offset && (rx.source - px).sqrnorm() == 0) return;  // x is the (pseudo) source: done
    // Every other candidate is at least rx.d (causality): nothing to gain if c is already there.
    if (const DRec* rc = dt.find(static_cast<uint32_t>(c)); rc && rc->d <= rx.d) return;

    double best = kInf;
    Vec3 best_s;
    double best_offset = 0;
    int best_f = -1;
    // Causality: a path through x (or through the edge x-y) is not shorter at c than at its
    // corners; a shorter one means the line does not really come that way.
    auto consider = [&](const Vec3& s, double offset, int f, double at_least) {
      const double d = offset + (s - pc).norm();
      if (d >= at_least * (1 - 1e-12) && d < best) {
        best = d;
        best_s = s;
        best_offset = offset;
        best_f = f;
      }
    };
    const Vec3& n_x = rx.normal;
    for (int side = 0; side < 2; ++side) {
      const int t0 = side == 0 ? f_left : f_right;
      if (t0 < 0) continue;
      // The halfedge x -> y of t0 (y its third vertex) and the face beyond x-y.
      const HalfedgeHandle hxy = side == 0 ? mesh.opposite_halfedge_handle(mesh.next_halfedge_handle(mesh.next_halfedge_handle(hxc)))
                                           : mesh.next_halfedge_handle(hcx);
      // side 0: face(x->c) = (x, c, y): its halfedge y->x is next(next(x->c)); x->y is its opposite.
      // side 1: face(c->x) = (c, x, y): next(c->x) = x->y.
      const int y = mesh.to_vertex_handle(hxy).idx();
      const Vec3& py = mesh.point(VertexHandle(y));
      const HalfedgeHandle in_t0 = side == 0 ? mesh.opposite_halfedge_handle(hxy) : hxy;
      const int t_back = mesh.face_handle(mesh.opposite_halfedge_handle(in_t0)).idx();
      const bool interior_xy = t_back >= 0;
      const Vec3 n0 = face_normal(mesh, t0);

      // (2) x's own virtual source, unfolded exactly into t0: it lies in t0's plane already, in
      // the face across x-y (an unfolding about that edge), or in a plane parallel to t0's.
      // On a smooth stretch (normals within kSmoothDot) the rotation about x that takes x's plane
      // onto t0's is a close stand-in for unfolding along the faces between them.
      Vec3 sx_in_t0 = pc;
      bool sx_known = false;
      if (rx.face >= 0) {
        const double nd = OpenMesh::dot(n_x, n0);
        if (rx.face == t0 || rx.face == t_back || nd > kSmoothDot) {
          sx_in_t0 = rx.face == t0 ? rx.source : unfold(rx.source, px, n_x, n0);
          sx_known = true;
          if (arrives_through(sx_in_t0, pc, px, py, n0, interior_xy)) consider(sx_in_t0, rx.offset, t0, rx.d);
        }
      }
      // (3) Both corners settled: the source where the two distances meet in t0's plane
      // (fast-marching unfolding), if the line from there arrives through x-y.
      const DRec* ry = dt.find(static_cast<uint32_t>(y));
      if (ry && ry->settled && std::isfinite(ry->d) && rx.offset == 0 && ry->offset == 0) {
        const Vec3 xy = py - px;
        const double len = xy.norm();
        if (len > 0) {
          const Vec3 u = xy / len;
          const Vec3 v = OpenMesh::cross(n0, u);
          const double sc = OpenMesh::dot(pc - px, v);
          const double sx = (rx.d * rx.d - ry->d * ry->d + len * len) / (2 * len);
          double sy2 = rx.d * rx.d - sx * sx;
          if (sy2 > -1e-12 * (rx.d * rx.d + 1e-300)) {
            sy2 = std::max(sy2, 0.0);
            const double sy = (sc > 0 ? -1 : 1) * std::sqrt(sy2);
            const Vec3 s = px + u * sx + v * sy;
            // Only where x and y see the same source: two different sources (or two sides of a
            // cut locus) would meet at a point that is no source at all.
            bool consistent = sx_known && (s - sx_in_t0).norm() <= kConsistency * (rx.d + len);
            if (consistent) {
              consistent = false;
              if (ry->face >= 0) {
                const Vec3& ny = ry->normal;
                if (OpenMesh::dot(ny, n0) > kSmoothDot || ry->face == t0 || ry->face == t_back) {
                  const Vec3 sy_in_t0 = ry->face == t0 ? ry->source : unfold(ry->source, py, ny, n0);
                  consistent = (s - sy_in_t0).norm() <= kConsistency * (ry->d + len);
                }
              }
            }
            if (consistent && arrives_through(s, pc, px, py, n0, interior_xy)) consider(s, 0.0, t0, std::max(rx.d, ry->d));
          }
        }
      }
    }
    if (best_f >= 0) offer(c, best, best_s, best_offset, best_f);
  }

  // The line source: a loop vertex x gives its wedge neighbours their distance to the loop's two
  // segments at x.
  void propagate_from_line(int x, const DRec& rx, int c) {
    const HalfedgeHandle hin(rx.loop_in);
    const Vec3& pc = mesh.point(VertexHandle(c));
    const Vec3& px = mesh.point(VertexHandle(x));
    double best = kInf;
    Vec3 foot = px;
    auto try_segment = [&](const Vec3& q) {
      const Vec3 along = q - px;
      const double t = std::clamp(OpenMesh::dot(pc - px, along) / std::max(along.sqrnorm(), 1e-300), 0.0, 1.0);
      const Vec3 f = px + along * t;
      const double d = (pc - f).norm();
      if (d < best) {
        best = d;
        foot = f;
      }
    };
    // The loop's segments at x: from its predecessor, and to the neighbour whose loop halfedge
    // starts at x.
    try_segment(mesh.point(mesh.from_vertex_handle(hin)));
    for (VertexHandle y : mesh.vv_range(VertexHandle(x))) {
      const DRec* ry = dt.find(static_cast<uint32_t>(y.idx()));
      if (ry && ry->loop_in >= 0 && mesh.from_vertex_handle(HalfedgeHandle(ry->loop_in)).idx() == x) {
        try_segment(mesh.point(y));
      }
    }
    const HalfedgeHandle hxc = mesh.find_halfedge(VertexHandle(x), VertexHandle(c));
    offer(c, best, foot, 0.0, hxc.is_valid() ? mesh.face_handle(hxc).idx() : -1);
  }

  void settle_neighbours(int x) {
    DRec rx = *dt.find(static_cast<uint32_t>(x));  // copy: offers may rehash the table
    auto visit = [&](int c, HalfedgeHandle hxc) {
      DRec* rc = dt.find(static_cast<uint32_t>(c));
      if (rc) {
        --rc->unsettled;
        if (rc->settled) {
          if (rc->unsettled <= 0) dt.erase(static_cast<uint32_t>(c));
          return;
        }
      }
      if (rx.loop_in >= 0 && line_source && rx.d == 0) {
        propagate_from_line(x, rx, c);
      } else {
        propagate(x, rx, c, hxc);
      }
    };
    if (rx.loop_in >= 0) {
      // A loop vertex: its back side is a barrier; only the ahead wedge takes distances from it,
      // but every neighbour counts it as settled.
      const HalfedgeHandle hin(rx.loop_in);
      std::vector<int> wedge;
      HalfedgeHandle g = mesh.next_halfedge_handle(hin);
      for (int i = 0; i < 1 << 20; ++i) {
        wedge.push_back(mesh.to_vertex_handle(g).idx());
        if (!mesh.face_handle(mesh.opposite_halfedge_handle(g)).is_valid()) break;
        const HalfedgeHandle nxt = mesh.next_halfedge_handle(mesh.opposite_halfedge_handle(g));
        // stop at the loop's outgoing halfedge: its end vertex has loop_in == nxt
        const DRec* rn = dt.find(static_cast<uint32_t>(mesh.to_vertex_handle(g).idx()));
        if (rn && rn->loop_in == g.idx()) break;
        g = nxt;
      }
      for (HalfedgeHandle h : mesh.voh_range(VertexHandle(x))) {
        const VertexHandle y = mesh.to_vertex_handle(h);
        if (std::find(wedge.begin(), wedge.end(), y.idx()) != wedge.end()) {
          visit(y.idx(), h);
        } else if (DRec* ry = dt.find(static_cast<uint32_t>(y.idx()))) {
          --ry->unsettled;
          if (ry->settled && ry->unsettled <= 0) dt.erase(static_cast<uint32_t>(y.idx()));
        }
      }
    } else {
      for (HalfedgeHandle h : mesh.voh_range(VertexHandle(x))) visit(mesh.to_vertex_handle(h).idx(), h);
    }
    DRec* r = dt.find(static_cast<uint32_t>(x));
    if (r && r->unsettled <= 0) dt.erase(static_cast<uint32_t>(x));
  }

  bool step() {
    while (!heap.empty()) {
      const auto [d, v] = heap.top();
      DRec* r = dt.find(static_cast<uint32_t>(v));
      if (!r || r->settled || r->d != d) {
        heap.pop();
        continue;
      }
      if (d > opts.max_distance) {
        stop = DistanceStop::MaxDistance;
        return false;
      }
      heap.pop();
      r->settled = true;
      if (r->face >= 0) r->normal = face_normal(mesh, r->face);
      ++n_settled;
      const Vec3 dir = direction_of(v, *r);
      if (on_settled) on_settled(VertexHandle(v), d, dir);
      expand_vertex(v);
      settle_neighbours(v);
      note_memory();
      if (opts.target && opts.target->idx() == v) {
        stop = DistanceStop::TargetReached;
        return false;
      }
      return true;
    }
    stop = DistanceStop::Exhausted;
    return false;
  }

  Vec3 direction_of(int v, const DRec& r) const {
    Vec3 dir = r.source - mesh.point(VertexHandle(v));
    const double l = dir.norm();
    return l > 1e-300 && r.d > 0 ? dir / l : Vec3(0, 0, 0);
  }

  size_t total_bytes() const {
    return memory_bytes() + dt.memory_bytes() + peak_heap * sizeof(Entry);
  }
};

MinimalDistanceFront::MinimalDistanceFront(const Mesh& mesh) : impl_(std::make_unique<Impl>(mesh)) {}
MinimalDistanceFront::~MinimalDistanceFront() = default;
MinimalDistanceFront::MinimalDistanceFront(MinimalDistanceFront&&) noexcept = default;
MinimalDistanceFront& MinimalDistanceFront::operator=(MinimalDistanceFront&&) noexcept = default;

void MinimalDistanceFront::reset(const FrontSource& source, const DistanceOptions& options) {
  impl_->reset(source, options);
}
void MinimalDistanceFront::reset(const std::vector<SurfacePoint>& points, const DistanceOptions& options) {
  impl_->reset(points, options);
}
bool MinimalDistanceFront::step() { return impl_->step(); }
DistanceStop MinimalDistanceFront::run() {
  while (impl_->step()) {
  }
  return impl_->stop;
}
DistanceStop MinimalDistanceFront::stop_reason() const { return impl_->stop; }
void MinimalDistanceFront::set_settled_callback(std::function<void(VertexHandle, double, const Vec3&)> cb) {
  impl_->on_settled = std::move(cb);
}
std::optional<double> MinimalDistanceFront::distance(VertexHandle v) const {
  if (!v.is_valid()) return std::nullopt;
  const DRec* r = impl_->dt.find(static_cast<uint32_t>(v.idx()));
  if (!r || !std::isfinite(r->d)) return std::nullopt;
  return r->d;
}
size_t MinimalDistanceFront::front_size() const { return impl_->live_nodes; }
size_t MinimalDistanceFront::peak_front_size() const { return impl_->peak_nodes; }
size_t MinimalDistanceFront::working_memory_bytes() const { return impl_->total_bytes(); }
size_t MinimalDistanceFront::peak_working_memory_bytes() const {
  return impl_->peak_bytes + impl_->dt.memory_bytes() + impl_->peak_heap * sizeof(Impl::Entry);
}
size_t MinimalDistanceFront::settled_count() const { return impl_->n_settled; }

void MinimalDistanceFront::validate() const {
  impl_->EdgeFrontCore::validate(std::nullopt);
  impl_->dt.for_each([](uint32_t v, const DRec& r) {
    if (!(r.d >= 0) || std::isnan(r.d)) {
      throw InternalError("distance front invariant broken: vertex " + std::to_string(v) + " has distance " +
                          std::to_string(r.d));
    }
  });
}

namespace {
DistanceField collect(const Mesh& mesh, MinimalDistanceFront& front, const DistanceOptions& options) {
  DistanceField out;
  out.distance.assign(mesh.n_vertices(), kInf);
  if (options.directions) out.direction.assign(mesh.n_vertices(), Vec3(0, 0, 0));
  front.set_settled_callback([&](VertexHandle v, double d, const Vec3& dir) {
    if (out.distance[v.idx()] != kInf) return;  // a loop vertex reached again from behind
    out.distance[v.idx()] = d;
    if (options.directions) out.direction[v.idx()] = dir;
    out.order.push_back(v);
  });
  out.stop = front.run();
  out.peak_front = front.peak_front_size();
  out.peak_working_memory_bytes = front.peak_working_memory_bytes();
  return out;
}
}  // namespace

DistanceField geodesic_distance(const Mesh& mesh, const FrontSource& source, const DistanceOptions& options) {
  MinimalDistanceFront front(mesh);
  front.reset(source, options);
  return collect(mesh, front, options);
}

DistanceField geodesic_distance(const Mesh& mesh, const std::vector<SurfacePoint>& points,
                                const DistanceOptions& options) {
  MinimalDistanceFront front(mesh);
  front.reset(points, options);
  return collect(mesh, front, options);
}

DistanceField dijkstra_distance(const Mesh& mesh, const FrontSource& source, const DistanceOptions& options) {
  validate_source(mesh, source);
  if (std::isnan(options.max_distance) || options.max_distance < 0) {
    throw InvalidInput("distance: max_distance must be a non-negative number, got " + dname(options.max_distance));
  }
  if (options.target && !is_live(mesh, *options.target)) {
    throw InvalidInput("distance: target vertex " + std::to_string(options.target->idx()) + " is not a vertex of the mesh");
  }
  DistanceField out;
  const size_t n = mesh.n_vertices();
  out.distance.assign(n, kInf);
  std::vector<int> via(n, -1);
  std::vector<uint8_t> done(n, 0);
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> heap;
  if (source.is_loop()) {
    for (HalfedgeHandle h : source.loop) {
      const int v = mesh.to_vertex_handle(h).idx();
      out.distance[v] = 0;
      heap.emplace(0.0, v);
    }
    // First step only into the ahead wedges; loop vertices are never re-entered.
    const size_t m = source.loop.size();
    for (size_t i = 0; i < m; ++i) {
      const int x = mesh.to_vertex_handle(source.loop[i]).idx();
      done[x] = 1;
      HalfedgeHandle g = mesh.next_halfedge_handle(source.loop[i]);
      while (true) {
        const int y = mesh.to_vertex_handle(g).idx();
        const double d = (mesh.point(VertexHandle(y)) - mesh.point(VertexHandle(x))).norm();
        if (!done[y] && d < out.distance[y]) {
          out.distance[y] = d;
          via[y] = x;
          heap.emplace(d, y);
        }
        if (g == source.loop[(i + 1) % m]) break;
        g = mesh.next_halfedge_handle(mesh.opposite_halfedge_handle(g));
      }
    }
    for (HalfedgeHandle h : source.loop) out.order.push_back(mesh.to_vertex_handle(h));
  } else {
    for (VertexHandle v : source.vertices) {
      out.distance[v.idx()] = 0;
      heap.emplace(0.0, v.idx());
    }
  }
  out.stop = DistanceStop::Exhausted;
  size_t peak = 0;
  while (!heap.empty()) {
    const auto [d, v] = heap.top();
    heap.pop();
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
    const Vec3& pv = mesh.point(VertexHandle(v));
    for (VertexHandle y : mesh.vv_range(VertexHandle(v))) {
      const double nd = d + (mesh.point(y) - pv).norm();
      if (!done[y.idx()] && nd < out.distance[y.idx()]) {
        out.distance[y.idx()] = nd;
        via[y.idx()] = v;
        heap.emplace(nd, y.idx());
      }
    }
    peak = std::max(peak, heap.size());
  }
  // Unsettled tentative values are not answers.
  for (size_t v = 0; v < n; ++v) {
    if (!done[v]) out.distance[v] = kInf;
  }
  if (options.directions) {
    out.direction.assign(n, Vec3(0, 0, 0));
    for (size_t v = 0; v < n; ++v) {
      if (via[v] >= 0 && done[v]) {
        const Vec3 dv = mesh.point(VertexHandle(via[v])) - mesh.point(VertexHandle(static_cast<int>(v)));
        const double l = dv.norm();
        if (l > 0) out.direction[v] = dv / l;
      }
    }
  }
  out.peak_working_memory_bytes = n * (sizeof(double) + sizeof(int) + 1) + peak * sizeof(Entry);
  return out;
}

}  // namespace edgefront
