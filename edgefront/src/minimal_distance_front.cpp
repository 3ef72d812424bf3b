#include "edgefront/minimal_distance_front.h"

#include <algorithm>
#include <array>
#include <optional>
#include <cmath>
#include <queue>
#include <string>

#include "detail/distance_common.h"
#include "detail/edge_front_core.h"
#include "detail/min_heap.h"
#include "edgefront/coordinate_range.h"
#include "edgefront/error.h"
#include "edgefront/vertex_twins.h"

namespace edgefront {

using detail::EdgeFrontCore;
using detail::kFlatDefect;
using detail::kTwoPi;
using detail::VRec;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// Three unit edge directions at a vertex with a smaller triple product count as one plane.
constexpr double kFlatDet = 1e-9;
// A settled vertex agrees with an unfolded source when their distances differ by this (relative).
constexpr double kBracketTol = 1e-3;
// Two virtual sources closer than this (relative to the distance) count as one.
constexpr double kSameSourceTol = 1e-6;

// A distance offered to a vertex, with the virtual source it comes from (fields as in DRec).
struct Candidate {
  double d = kInf;
  Vec3 source{0, 0, 0};
  double offset = 0;
  int face = -1;
  Vec3 origin{0, 0, 0};
};


// Distance record of a vertex that is reached and still needed: tentative, or settled with
// neighbours that are not settled yet (they may still take their distance from it).
// The fields every lookup reads (d, settled, unsettled) come first, in the record's first cache line.
struct DRec {
  double d = kInf;
  int unsettled = 0;     // neighbours not settled yet (set when the vertex settles; see record())
  bool settled = false;
  bool seed = false;     // a source vertex, or a vertex of a source point's face
  bool unexpanded = false;  // window mode: settled before it joined the front (see step)
  bool twin = false;     // the distance came from a twin: a pseudo source at the vertex itself (see
                         // settle_twins; `source` then marks only the twin's direction)
  int face = -1;         // the plane of `source`; -1 when `source` needs no unfolding (a source point)
  int loop_in = -1;      // loop sources: the loop halfedge into this vertex (its ahead wedge)
  double offset = 0;     // distance already travelled at `source` (a pseudo source: a vertex the
                         // shortest path bends around, such as a saddle or a border corner)
  Vec3 source{0, 0, 0};  // virtual source: where the source lies, unfolded into the plane of `face`
  Vec3 origin{0, 0, 0};  // where `source` really lies (the source point or the pseudo-source vertex)
  // A second virtual source: the best one offered from a different source position (another
  // unfolding path, or another (pseudo) source). It does not set `d`, but it is propagated too,
  // so a neighbour whose line from `source` leaves this vertex's faces gets another chance.
  Candidate alt;
};

// A point of a 2D frame (see MinimalDistanceFront::Impl::lay_out).
struct P2 {
  double x, y;
};
double cross2(P2 a, P2 b) { return a.x * b.y - a.y * b.x; }
// |(x, y)| without std::hypot's overflow care (a fifth of the windows' time; lengths here are
// mesh-sized).
double norm2(double x, double y) { return std::sqrt(x * x + y * y); }
double dot2(P2 a, P2 b) { return a.x * b.x + a.y * b.y; }

// A window (DistanceMethod::Windows): the part [b0, b1] of a halfedge's edge lit straight from a
// (pseudo) source, with the source unfolded into the halfedge's frame: its from-vertex at the
// origin, its to-vertex at (|edge|, 0), its face (the one the window lights) at y > 0, so the
// source lies at y <= 0. sigma: the distance already travelled at the source.
struct Window {
  int he;
  double b0, b1;
  P2 s;
  double sigma;
};

// Per halfedge: the last windows carried across its face (MMP's windows of an edge, bounded: a
// later window on the same halfedge keeps only the part where it is shorter than all of them), and
// the windows waiting in the heap on it (the first kPendingPerEdge; see push_window).
constexpr int kLitPerEdge = 4;
constexpr int kPendingPerEdge = 4;
struct LitSet {
  int n = 0;     // windows held (at most kLitPerEdge)
  int next = 0;  // the slot the next one replaces when full
  int np = 0;    // waiting windows listed
  std::array<Window, kLitPerEdge> w;
  std::array<int, kPendingPerEdge> pending;
};

// Round-off allowance (radians) on each side of a pseudo source's shadow (emit_vertex_windows); a
// face whose part of the shadow is no wider than kShadowSliver (three allowances) gets no window.
constexpr double kSlack = 1e-7;
constexpr double kShadowSliver = 3 * kSlack;

// A window is kept only where it is shorter by this (relative) than the windows carried across
// the same halfedge before and than the path through an end of the edge: a window that would
// only shave off less goes (MMP/ICH keep every one; this bounds their number, about 1/3 fewer on
// the scanned models, for an error of about 1e-5 relative).
constexpr double kWindowGain = 1e-5;

// Two waiting windows on a halfedge merge when their sources and distances at the source agree to
// this (relative to the edge's scale): round-off of different unfoldings (1e-13 on the synthetic
// meshes). 1e-6 merged different sources on man.off (0.04% error, values below the exact ones).
constexpr double kMergeTol = 1e-10;

// The part of w's interval where it is shorter than u (its hull: a window stays one interval).
// sigma + |s p| of the two cross at most twice along the edge (a hyperbola branch and a line).
// False: nothing is left.
bool trim_against(Window& w, const Window& u) {
  const double lo = std::max(w.b0, u.b0), hi = std::min(w.b1, u.b1);
  if (!(hi > lo)) return true;
  auto diff = [&](double t) {
    return (w.sigma + norm2(t - w.s.x, w.s.y)) - (u.sigma + norm2(t - u.s.x, u.s.y));
  };
  // Roots of sigma_w + a(t) = sigma_u + b(t): a^2 - b^2 = alpha t + beta, so
  // (alpha t + beta - delta^2)^2 = 4 delta^2 b(t)^2 with delta = sigma_u - sigma_w.
  std::array<double, 8> cut{};
  int n = 0;
  cut[n++] = w.b0;
  cut[n++] = lo;
  const double delta = u.sigma - w.sigma;
  const double alpha = 2 * (u.s.x - w.s.x);
  const double beta = w.s.x * w.s.x + w.s.y * w.s.y - u.s.x * u.s.x - u.s.y * u.s.y;
  const double g = beta - delta * delta;
  const double qa = alpha * alpha - 4 * delta * delta;
  const double qb = 2 * alpha * g + 8 * delta * delta * u.s.x;
  const double qc = g * g - 4 * delta * delta * (u.s.x * u.s.x + u.s.y * u.s.y);
  auto add_root = [&](double t) {
    if (t > lo && t < hi) cut[n++] = t;
  };
  if (std::abs(qa) > 1e-300) {
    const double disc = qb * qb - 4 * qa * qc;
    if (disc >= 0) {
      const double sq = std::sqrt(disc);
      add_root((-qb - sq) / (2 * qa));
      add_root((-qb + sq) / (2 * qa));
    }
  } else if (std::abs(qb) > 1e-300) {
    add_root(-qc / qb);
  }
  cut[n++] = hi;
  cut[n++] = w.b1;
  for (int i = 1; i < n; ++i) {  // insertion sort (at most six)
    for (int j = i; j > 0 && cut[static_cast<size_t>(j)] < cut[static_cast<size_t>(j - 1)]; --j) {
      std::swap(cut[static_cast<size_t>(j)], cut[static_cast<size_t>(j - 1)]);
    }
  }
  double keep0 = kInf, keep1 = -kInf;
  for (int i = 0; i + 1 < n; ++i) {
    const double a = cut[i], b = cut[i + 1];
    if (!(b > a)) continue;
    const double m = 0.5 * (a + b);
    const bool useful = m < lo || m > hi || diff(m) < -kWindowGain * (w.sigma + norm2(m - w.s.x, w.s.y));
    if (useful) {
      keep0 = std::min(keep0, a);
      keep1 = std::max(keep1, b);
    }
  }
  if (!(keep1 > keep0)) return false;
  w.b0 = keep0;
  w.b1 = keep1;
  return true;
}
}  // namespace

namespace detail {

void check_distance_options(const Mesh& mesh, const DistanceOptions& o) {
  if (std::isnan(o.max_distance) || o.max_distance < 0) {
    throw InvalidInput("distance: max_distance must be a non-negative number, got " + std::to_string(o.max_distance));
  }
  if (o.target && !is_live(mesh, *o.target)) {
    throw InvalidInput("distance: target vertex " + std::to_string(o.target->idx()) + " is not a vertex of the mesh");
  }
}

void check_finite_vertex(const Vec3& position, int v) {
  if (!std::isfinite(position[0]) || !std::isfinite(position[1]) || !std::isfinite(position[2]))
    throw InvalidInput("distance: vertex " + std::to_string(v) + " has a NaN or infinite coordinate");
  if (std::max({std::abs(position[0]), std::abs(position[1]), std::abs(position[2])}) > kMaxCoordinate) {
    throw InvalidInput("distance: vertex " + std::to_string(v) + " has a coordinate beyond +-" +
                       number_for_message(kMaxCoordinate) + " (coordinate_range.h): squared lengths would overflow");
  }
}

// Checks source points; returns the vertices of their faces (each once).
std::vector<VertexHandle> check_points(const Mesh& mesh, const std::vector<SurfacePoint>& points) {
  require_attributes(mesh, "distance");
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
      throw InvalidInput(which + ": barycentric coordinates sum to " + std::to_string(sum) + ", not 1");
    }
    for (VertexHandle v : mesh.fv_range(p.face)) {
      check_finite_vertex(mesh.point(v), v.idx());
      if (std::find(verts.begin(), verts.end(), v) == verts.end()) verts.push_back(v);
    }
  }
  return verts;
}

Vec3 point_of(const Mesh& mesh, const SurfacePoint& p) {
  Vec3 x(0, 0, 0);
  int k = 0;
  for (VertexHandle v : mesh.fv_range(p.face)) x += mesh.point(v) * p.bary[k++];
  return x;
}

}  // namespace detail

using detail::check_distance_options;
using detail::check_points;
using detail::point_of;

struct MinimalDistanceFront::Impl : EdgeFrontCore {
  detail::FlatMap<DRec> dt;
  detail::MinHeap4<double> heap;  // (tentative distance, vertex); stale entries are skipped
  using Entry = detail::MinHeap4<double>::Entry;
  DistanceOptions opts;
  DistanceStop stop = DistanceStop::NotStarted;
  size_t n_settled = 0;
  size_t peak_heap = 0;
  bool line_source = false;
  std::function<void(VertexHandle, double, const Vec3&)> on_settled;

  // Window mode (DistanceMethod::Windows): the windows waiting in the heap (index -1 - w), their
  // free slots, and the settled vertices whose records were dropped (a window may still reach their
  // faces; they must not be reached again), in three stages (see forget_passed):
  //   gone (open = -1): the distance, while a window on one of its edges may still be shorter
  //     somewhere;
  //   passed (open >= 0): no longer (the front is farther than the distance plus the longest edge
  //     at the vertex): any window on its edges is dominated, the vertex kills it; open: its
  //     neighbours not passed yet;
  //   forgotten: every neighbour passed too (a ring of passed vertices stops every window before
  //     its faces): nothing is kept.
  // So the window mode's memory follows the front, not the settled area.
  bool windowed = false;
  std::vector<Window> win;
  std::vector<int> free_win;
  struct Gone {
    double d;
    int open;
  };
  detail::FlatMap<Gone> gone;
  detail::MinHeap4<double> horizon;  // gone vertices by the distance beyond which they pass
  size_t peak_horizon = 0;
  detail::FlatMap<LitSet> lit_edges;  // per halfedge, the windows carried across its face lately
  size_t n_merged = 0;  // windows merged into a waiting one (statistics)
  size_t n_windows = 0;  // windows propagated (statistics)

  // Twins (pinched vertices, edgefront/vertex_twins.h; the core's `twins`): the vertices with twins
  // that joined the edge front.
  detail::FlatMap<uint8_t> twins_joined;

  // The neighbourhood of the vertex being settled, counter-clockwise: per outgoing edge its end
  // vertex, unit direction and length, the face after it (-1 in a border gap) and that face's
  // corner angle at the vertex. Rebuilt for every settled vertex; reused storage.
  struct Ray {
    int v;
    Vec3 u;
    double len;
    int face_after;
    P2 corner;  // see corner_after
    bool corner_known;
    int he;  // the outgoing halfedge x -> v
  };
  std::vector<Ray> ring;
  std::vector<double> ang;  // scratch: the ring's cumulative corner angles
  bool ring_closed = false;

  explicit Impl(const Mesh& m) : EdgeFrontCore(m, MinimalEdgeFrontOptions{}) {}

  void on_join(int v, VRec& rec) override {
    rec.level = 0;
    if (twins.any() && twins.next(v) != v) twins_joined.insert(static_cast<uint32_t>(v), 1);  // see settle_twins
  }
  int event_level() const override { return 0; }

  void check_options(const DistanceOptions& o) const {
    check_distance_options(mesh, o);
    if (o.method == DistanceMethod::Fast || o.method == DistanceMethod::Dijkstra) {
      throw InvalidInput(std::string("distance: method \"") + to_string(o.method) +
                         "\" computes whole fields through geodesic_distance (with max_distance and target); the "
                         "stepwise MinimalDistanceFront runs \"mdf\" and \"windows\"");
    }
  }

  void clear_state(const DistanceOptions& o) {
    check_options(o);
    opts = o;
    dt.clear();
    heap.clear();
    stop = DistanceStop::NotStarted;
    n_settled = 0;
    peak_heap = 0;
    line_source = false;
    windowed = false;
    if (win.capacity() > 4096) std::vector<Window>().swap(win);
    win.clear();
    free_win.clear();
    gone.clear();
    horizon.clear();
    peak_horizon = 0;
    lit_edges.clear();
    n_merged = 0;
    n_windows = 0;
    twins_joined.clear();
  }

  // Neighbours and twins (see settle_twins) not settled yet.
  // (Loop sources only: kept out of record's way.)
  [[gnu::noinline]] int count_unsettled(int v) const {
    int n = 0;
    for (VertexHandle y : mesh.vv_range(VertexHandle(v))) {
      const DRec* r = dt.find(static_cast<uint32_t>(y.idx()));
      n += !(r && r->settled);
    }
    twins.for_each_twin(v, [&](int t) {
      const DRec* r = dt.find(static_cast<uint32_t>(t));
      n += !(r && r->settled);
    });
    return n;
  }

  // The record of `v`, created on first use. Its `unsettled` count matters only once `v` is settled
  // (it tells when the record can go): settle_neighbours counts it then, on the ring it walks
  // anyway, instead of a circulation per new record here. Every neighbour that settles later
  // decrements it. Loop sources keep the count from creation on: a loop vertex's record can be
  // dropped and made again (it is reached again from behind).
  DRec& record(int v) {
    auto [r, inserted] = dt.insert(static_cast<uint32_t>(v), DRec{});
    if (inserted) {
      detail::check_finite_vertex(mesh.point(VertexHandle(v)), v);
      if (line_source) r->unsettled = count_unsettled(v);
    }
    return *r;
  }

  void offer(int v, const Candidate& k) {
    DRec& r = record(v);
    if (r.settled) return;
    // Better: shorter, or as short (to rounding) from a source nearer the true one (a smaller
    // offset). A pseudo source at a vertex that lies exactly on the straight path ties with the
    // true source; keeping the pseudo source would bend every path continued from it.
    const bool shorter = k.d < r.d * (1 - 1e-12);
    const bool tie_but_straighter = !(k.d > r.d * (1 + 1e-12)) && k.offset < r.offset;
    if (windowed) {
      // Every candidate is the length of a real path: the shortest wins, no second source.
      if (shorter || tie_but_straighter) take(v, r, k);
      return;
    }
    const bool same_source = std::isfinite(r.d) && same_virtual_source(r.source, r.offset, k.source, k.offset, r.d);
    if (!shorter && !tie_but_straighter) {
      if (!same_source && k.face >= 0 && k.d < r.alt.d) r.alt = k;
      return;
    }
    if (!same_source && std::isfinite(r.d) && r.face >= 0) {
      r.alt = Candidate{r.d, r.source, r.offset, r.face, r.origin};
    } else if (r.alt.d < kInf && same_virtual_source(r.alt.source, r.alt.offset, k.source, k.offset, k.d)) {
      r.alt.d = kInf;  // the new best is the old second source
    }
    take(v, r, k);
  }

  void take(int v, DRec& r, const Candidate& k) {
    r.d = k.d;
    r.source = k.source;
    r.offset = k.offset;
    r.face = k.face;
    r.origin = k.origin;
    heap.push(k.d, v);
    peak_heap = std::max(peak_heap, heap.size());
  }

  static bool same_virtual_source(const Vec3& a, double oa, const Vec3& b, double ob, double scale) {
    return std::abs(oa - ob) <= kSameSourceTol * scale && (a - b).norm() <= kSameSourceTol * scale;
  }

  // A source point `s` (a real one, not unfolded) in the plane of `face` (-1: s is the vertex itself).
  void offer(int v, double d, const Vec3& s, double offset, int face) {
    Candidate k;
    k.d = d;
    k.source = s;
    k.origin = s;
    k.offset = offset;
    k.face = face;
    offer(v, k);
  }

  void reset(const FrontSource& source, const DistanceOptions& o) {
    clear_state(o);
    reset_structure(source);
    line_source = source.is_loop();
    windowed = o.method == DistanceMethod::Windows && !line_source;
    if (!line_source) {
      for (uint32_t v : sources) {
        offer(static_cast<int>(v), 0.0, mesh.point(VertexHandle(static_cast<int>(v))), 0.0, -1);
        record(static_cast<int>(v)).seed = true;
      }
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
    const std::vector<VertexHandle> verts = check_points(mesh, points);
    clear_state(o);
    reset_structure(FrontSource::from_vertices(verts));
    windowed = o.method == DistanceMethod::Windows;
    for (const SurfacePoint& p : points) {
      const Vec3 x = point_of(mesh, p);
      for (VertexHandle v : mesh.fv_range(p.face)) {
        offer(v.idx(), (mesh.point(v) - x).norm(), x, 0.0, p.face.idx());
        record(v.idx()).seed = true;
      }
      if (windowed) {
        // The point lights the three edges of its face from inside: windows on their far sides.
        for (HalfedgeHandle h : mesh.fh_range(p.face)) {
          const int g = h.idx() ^ 1;
          push_window(g, 0, edge_length(g), in_frame(g, x), 0.0);
        }
      }
    }
    note_memory();
  }

  // ---- Windows (DistanceMethod::Windows) ------------------------------------------------------
  //
  // A window is carried across the face it lights when it leaves the heap, at the smallest distance
  // it gives a point of its interval: the face's third vertex takes the distance from the window's
  // source when the straight line to it crosses the interval, and the lit parts of the face's two
  // other edges become windows of the faces behind them (ICH: Xin & Wang 2009; MMP). Windows and
  // vertices leave one heap in distance order, so a vertex settles only after every window that
  // could light it more closely. A window is dropped when an end of its edge reaches the whole
  // interval more closely (ICH's filter; exact: sigma + |s p| - |a p| never grows from a toward b).

  double edge_length(int h) const {
    return (mesh.point(VertexHandle(tov(h))) - mesh.point(VertexHandle(fromv(h)))).norm();
  }

  // A point on the far side of halfedge h's face (or on the edge) in h's frame (see Window).
  P2 in_frame(int h, const Vec3& p) const {
    const Vec3& a = mesh.point(VertexHandle(fromv(h)));
    const Vec3 ab = mesh.point(VertexHandle(tov(h))) - a;
    const double l = ab.norm();
    const Vec3 w = p - a;
    const double x = OpenMesh::dot(w, ab) / l;
    return P2{x, -std::sqrt(std::max(w.sqrnorm() - x * x, 0.0))};
  }

  // The best distance known for v: its record's, or a dropped settled record's; +inf if none;
  // -inf for a passed vertex (trim then drops every window on its edges, as its distance would).
  double known_d(int v) const {
    if (const DRec* r = dt.find(static_cast<uint32_t>(v))) return r->d;
    if (const Gone* g = gone.find(static_cast<uint32_t>(v))) return g->open < 0 ? g->d : -kInf;
    return kInf;
  }

  // Moves the gone vertices whose horizon lies below d (the distance settling now; every window
  // popped or made from now on is at least d everywhere on its interval) to `passed`, and forgets
  // the passed vertices whose neighbours have all passed. Exact: a window on an edge at a passed
  // vertex v is longer everywhere than d(v) plus the edge (trim with v's distance would drop it
  // whole), and a window reaches a forgotten vertex's faces only across an edge with a passed end.
  [[gnu::noinline]] void forget_passed(double d) {
    while (!horizon.empty() && horizon.top().first < d) {
      const int v = horizon.top().second;
      horizon.pop();
      int open = 0;  // neighbours not passed (none is forgotten: that needs v passed first)
      for (VertexHandle y : mesh.vv_range(VertexHandle(v))) {
        Gone* g = gone.find(static_cast<uint32_t>(y.idx()));
        if (!g || g->open < 0) {
          ++open;
        } else if (--g->open <= 0) {
          gone.erase(static_cast<uint32_t>(y.idx()));
        }
      }
      if (open > 0) {
        gone.find(static_cast<uint32_t>(v))->open = open;
      } else {
        gone.erase(static_cast<uint32_t>(v));
      }
    }
  }

  // A window across a long edge can light a vertex more closely than any of its neighbours: it
  // settles first, before the front reaches it (expand_vertex has nothing to do then). When a
  // neighbour has settled and brought it onto the front, it is expanded (and so on outward).
  std::vector<int> late;  // scratch
  [[gnu::noinline]] void expand_late_neighbours() {
    late.clear();
    for (const Ray& r : ring) late.push_back(r.v);
    while (!late.empty()) {
      const int c = late.back();
      late.pop_back();
      DRec* rc = dt.find(static_cast<uint32_t>(c));
      if (!rc || !rc->unexpanded || !vt.find(static_cast<uint32_t>(c))) continue;
      rc->unexpanded = false;
      if (!expand_vertex(c)) continue;
      for (VertexHandle y : mesh.vv_range(VertexHandle(c))) late.push_back(y.idx());
    }
  }

  // Drops the record of a settled vertex whose neighbours are all settled.
  void drop(int v) {
    if (windowed) {
      // The windows remembered on v's edges: the front has passed them.
      double longest = 0;
      for (HalfedgeHandle h : mesh.voh_range(VertexHandle(v))) {
        lit_edges.erase(static_cast<uint32_t>(h.idx()));
        lit_edges.erase(static_cast<uint32_t>(h.idx() ^ 1));
        longest = std::max(longest, edge_length(h.idx()));
      }
      if (const DRec* r = dt.find(static_cast<uint32_t>(v))) {
        gone.insert(static_cast<uint32_t>(v), Gone{r->d, -1});
        horizon.push((r->d + longest) * (1 + 1e-9), v);
        peak_horizon = std::max(peak_horizon, horizon.size());
      }
    }
    dt.erase(static_cast<uint32_t>(v));
  }

  // ICH's filter, as a trim (MMP): the part of [b0, b1] that an end of the edge (distance da at
  // the from-vertex, db at the to-vertex, edge length l) reaches more closely along the edge goes.
  // Sound: sigma + |s p| - (da + |a p|) never grows from a toward b, so that part is an end piece;
  // the path through the end vertex is a real path. False: nothing is left.
  static bool trim(double& b0, double& b1, P2 s, double sigma, double da, double db, double l) {
    auto via_s = [&](double t) { return sigma + norm2(t - s.x, s.y); };
    constexpr double kKeep = 1 + 1e-12;  // exact: the end vertex may not carry the line on (not a pseudo source)
    if (da < kInf) {
      if (via_s(b1) > (da + b1) * kKeep) return false;
      if (via_s(b0) > (da + b0) * kKeep) {
        // sigma + |s p| = da + t: |s p| = k + t, k = da - sigma
        const double k = da - sigma, den = 2 * (s.x + k);
        if (den > 0) b0 = std::clamp((s.x * s.x + s.y * s.y - k * k) / den, b0, b1);
      }
    }
    if (db < kInf) {
      if (via_s(b0) > (db + l - b0) * kKeep) return false;
      if (via_s(b1) > (db + l - b1) * kKeep) {
        const double m = db - sigma + l, den = 2 * (m - s.x);
        if (den > 0) b1 = std::clamp((m * m - s.x * s.x - s.y * s.y) / den, b0, b1);
      }
    }
    return b1 > b0;
  }

  void push_window(int h, double b0, double b1, P2 s, double sigma) {
    if (!(b1 > b0) || !has_face(h)) return;
    push_window(h, b0, b1, s, sigma, known_d(fromv(h)), known_d(tov(h)), edge_length(h));
  }

  // The same with the distances known at the edge's ends and its length (has_face(h) checked).
  void push_window(int h, double b0, double b1, P2 s, double sigma, double d_from, double d_to, double len) {
    if (!(b1 > b0) || !trim(b0, b1, s, sigma, d_from, d_to, len)) return;
    Window nw{h, b0, b1, s, sigma};
    LitSet* found = lit_edges.find(static_cast<uint32_t>(h));
    if (found && !trim_against_lit(nw, *found)) return;
    b0 = nw.b0;
    b1 = nw.b1;
    // A window waiting on the same halfedge from the same source (another way round the vertices
    // in between, unfolded to the same place) whose interval meets this one: one window for both.
    LitSet& pe = found ? *found : *lit_edges.insert(static_cast<uint32_t>(h), LitSet{}).first;
    const double tol = kMergeTol * (len + std::abs(s.x) - s.y + sigma);
    for (int k = 0; k < pe.np; ++k) {
      Window& o = win[static_cast<size_t>(pe.pending[static_cast<size_t>(k)])];
      if (std::abs(o.sigma - sigma) > tol || std::abs(o.s.x - s.x) > tol || std::abs(o.s.y - s.y) > tol) continue;
      if (o.b0 > b1 + tol || b0 > o.b1 + tol) continue;
      const double old_min = o.sigma + norm2(o.s.x - std::clamp(o.s.x, o.b0, o.b1), o.s.y);
      const double u0 = std::min(o.b0, b0), u1 = std::max(o.b1, b1);
      const double new_min = o.sigma + norm2(o.s.x - std::clamp(o.s.x, u0, u1), o.s.y);
      ++n_merged;
      if (!(new_min < old_min)) {  // its heap entry stays right
        o.b0 = u0;
        o.b1 = u1;
        return;
      }
      // It comes out sooner: a new entry; the old one is skipped when it comes up.
      b0 = u0;
      b1 = u1;
      s = o.s;
      sigma = o.sigma;
      o.he = -1;
      pe.pending[static_cast<size_t>(k)] = pe.pending[static_cast<size_t>(--pe.np)];
      break;
    }
    const double foot = std::clamp(s.x, b0, b1);
    const double dmin = sigma + norm2(s.x - foot, s.y);
    int id;
    if (!free_win.empty()) {
      id = free_win.back();
      free_win.pop_back();
    } else {
      id = static_cast<int>(win.size());
      win.emplace_back();
    }
    win[id] = Window{h, b0, b1, s, sigma};
    if (pe.np < kPendingPerEdge) pe.pending[static_cast<size_t>(pe.np++)] = id;
    heap.push(dmin, -1 - id);
    peak_heap = std::max(peak_heap, heap.size());
  }

  // A (pseudo) source at the settled vertex x (ring built): windows on the far sides of the edges
  // opposite x in its faces.
  // shadow_only: a pseudo source (rx: x's record) lights only its shadow, the directions more than a
  // half turn away from the way to the source on both sides (the geodesics that bend at x); the
  // faces that meet it get windows.
  [[gnu::noinline]] void emit_vertex_windows(int x, double sigma, const DRec* shadow_only = nullptr) {
    const Vec3& px = mesh.point(VertexHandle(x));
    const int m = static_cast<int>(ring.size());
    // The shadow: [lo, hi] in ring angles (mod full when closed); at a border vertex also [0, hi2].
    double lo = 0, hi = -1, hi2 = -1, full = 0;
    bool known = false;
    if (shadow_only) {
      ang.assign(static_cast<size_t>(m) + 1, 0.0);
      int jf = -1;
      for (int i = 0; i < m; ++i) {
        const P2 c = corner_after(i);
        ang[static_cast<size_t>(i) + 1] = ang[static_cast<size_t>(i)] + (ring[i].face_after >= 0 ? std::atan2(c.y, c.x) : 0.0);
        if (ring[i].face_after == shadow_only->face) jf = i;
      }
      full = ang[static_cast<size_t>(m)];
      const Vec3 w = shadow_only->source - px;
      if (jf >= 0 && w.sqrnorm() > 0) {
        const Vec3& u0 = ring[jf].u;
        Vec3 nrm = OpenMesh::cross(u0, ring[(jf + 1) % m].u);
        const double nl = nrm.norm();
        if (nl > 0) {
          nrm /= nl;
          const double phi = ang[static_cast<size_t>(jf)] +
                             std::atan2(OpenMesh::dot(nrm, OpenMesh::cross(u0, w)), OpenMesh::dot(u0, w));
          constexpr double kPi = kTwoPi / 2;
          lo = phi + kPi - kSlack;
          hi = ring_closed ? phi + full - kPi + kSlack : full + kSlack;
          if (!ring_closed) hi2 = phi - kPi + kSlack;
          known = true;
        }
      }
      if (!known) shadow_only = nullptr;  // no direction known: light every face
    }
    for (int i = 0; i < m; ++i) {
      const Ray& r = ring[i];
      if (r.face_after < 0) continue;
      const int g = mesh.next_halfedge_handle(HalfedgeHandle(r.he)).idx() ^ 1;  // z -> y, across the face x, y, z
      const double len = edge_length(g);
      if (!shadow_only) {
        push_window(g, 0, len, in_frame(g, px), sigma);
        continue;
      }
      // The part of the face's corner [a0, a1] in the shadow (at most one piece: the lit
      // directions between the shadow's pieces span more than a half turn, a corner less).
      const double a0 = ang[static_cast<size_t>(i)], a1 = ang[static_cast<size_t>(i) + 1];
      double t0 = kInf, t1 = -kInf;
      if (!ring_closed && hi2 >= 0 && a0 <= hi2) {
        t0 = a0;
        t1 = std::min(a1, hi2);
      }
      for (int k = -2; k <= 2 && !(t1 >= t0); ++k) {
        if (!ring_closed && k != 0) continue;
        if (a1 + k * full >= lo && a0 + k * full <= hi) {
          t0 = std::max(a0, lo - k * full);
          t1 = std::min(a1, hi - k * full);
        }
      }
      // A face the shadow meets only within the slack (a border vertex whose source lies on the
      // border's line: the shadow is empty but for round-off) gets no window. Such a window gives
      // nothing the straight windows do not, but it came within trim_against's 1e-5 gain of them
      // and, met first on an edge, dropped them: 3e-6 relative error on a 1:100 planar grid.
      if (!(t1 - t0 > kShadowSliver)) continue;
      // The whole far edge (trimmed in push_window), not only the shadow's part of it: the wider
      // windows also trim later ones on the same edges (shadow-only intervals cost 24% more
      // windows on the armadillo).
      push_window(g, 0, len, in_frame(g, px), sigma);
    }
  }

  // Whether x (ring built) is a border vertex or its corner angles sum to more than a full turn: a
  // geodesic can bend there, so it becomes a pseudo source. The angles are added as unit complex
  // numbers; `turns` counts the full turns passed (each corner is below a half turn).
  [[gnu::noinline]] bool bends_geodesics() {
    if (!ring_closed) return true;
    double re = 1, im = 0;
    int turns = 0;
    for (int i = 0; i < static_cast<int>(ring.size()); ++i) {
      if (ring[i].face_after < 0) return true;
      const P2 c = corner_after(i);
      const double r2 = re * c.x - im * c.y, i2 = re * c.y + im * c.x;
      turns += im < 0 && i2 >= 0;
      re = r2;
      im = i2;
    }
    if (turns >= 2) return true;
    if (turns == 0) return false;
    return !(re > 0 && im >= 0 && im <= kFlatDefect);  // more than a full turn, beyond round-off
  }

  static bool trim_against_lit(Window& w, const LitSet& ls) {
    for (int i = 0; i < ls.n; ++i) {
      if (!trim_against(w, ls.w[static_cast<size_t>(i)])) return false;
    }
    return true;
  }

  // Carries window w across its face (see above).
  // (Not inlined: the window code stays out of the default mode's hot loop.)
  // id: its slot, to take off its halfedge's list of waiting windows.
  [[gnu::noinline]] void propagate_window(Window w, int id) {
    ++n_windows;
    const int h = w.he;
    LitSet* ls = lit_edges.find(static_cast<uint32_t>(h));
    if (ls) {
      for (int k = 0; k < ls->np; ++k) {
        if (ls->pending[static_cast<size_t>(k)] == id) {
          ls->pending[static_cast<size_t>(k)] = ls->pending[static_cast<size_t>(--ls->np)];
          break;
        }
      }
    }
    const int hn = nexth(h);
    const int a = fromv(h), b = tov(h), c = tov(hn);
    const Vec3& pa = mesh.point(VertexHandle(a));
    const Vec3& pb = mesh.point(VertexHandle(b));
    const Vec3& pc = mesh.point(VertexHandle(c));
    const double l = (pb - pa).norm(), la = (pc - pa).norm(), lb = (pc - pb).norm();
    if (!(l > 0) || !(la > 0) || !(lb > 0)) return;
    const P2 s = w.s;
    // The ends' distances may have dropped since the window was made.
    const double da = known_d(a), db = known_d(b);
    if (!trim(w.b0, w.b1, s, w.sigma, da, db, l)) return;
    if (ls && !trim_against_lit(w, *ls)) return;
    // Remembered for the later windows on h.
    if (!ls) ls = lit_edges.insert(static_cast<uint32_t>(h), LitSet{}).first;
    ls->w[static_cast<size_t>(ls->next)] = w;
    ls->next = (ls->next + 1) % kLitPerEdge;
    ls->n = std::min(ls->n + 1, kLitPerEdge);
    const double cx = (l * l + la * la - lb * lb) / (2 * l);
    const double cy = std::sqrt(std::max(la * la - cx * cx, 0.0));
    if (!(cy > 0)) return;
    const P2 c2{cx, cy};
    const double tol = 1e-12 * l;
    const int g_ac = prevh(h) ^ 1;  // a -> c, lighting the face behind a-c
    const int g_cb = hn ^ 1;        // c -> b
    if (s.y > -tol) {
      // The source lies on the edge (a source point on it): it sees the whole face.
      if (s.x < w.b0 - tol || s.x > w.b1 + tol) return;
      offer_window_vertex(c, w.sigma + norm2(cx - s.x, cy), s, w.sigma, h, l, c2);
      const double dc = known_d(c);
      push_child(g_ac, P2{0, 0}, c2, la, 0, 1, s, w.sigma, da, dc);
      push_child(g_cb, c2, P2{l, 0}, lb, 0, 1, s, w.sigma, dc, db);
      return;
    }
    // Where the line from the source through c crosses the edge.
    const double tc = s.x + (cx - s.x) * (-s.y) / (cy - s.y);
    if (tc >= w.b0 - tol && tc <= w.b1 + tol) {
      offer_window_vertex(c, w.sigma + norm2(cx - s.x, cy - s.y), s, w.sigma, h, l, c2);
    }
    // The lit parts of a-c and c-b: where the lines through b0 and b1 (and c) meet them.
    auto meet = [&](double t, P2 p, P2 q) {
      const P2 d{t - s.x, -s.y};
      const double den = cross2(d, P2{q.x - p.x, q.y - p.y});
      if (den == 0) return t <= tc ? 0.0 : 1.0;
      return std::clamp(cross2(d, P2{s.x - p.x, s.y - p.y}) / den, 0.0, 1.0);
    };
    const double dc = known_d(c);  // after c's offer
    if (w.b0 < tc) {
      const double t1 = std::min(w.b1, tc);
      push_child(g_ac, P2{0, 0}, c2, la, meet(w.b0, P2{0, 0}, c2), t1 >= tc ? 1.0 : meet(t1, P2{0, 0}, c2), s,
                 w.sigma, da, dc);
    }
    if (w.b1 > tc) {
      const double t0 = std::max(w.b0, tc);
      push_child(g_cb, c2, P2{l, 0}, lb, t0 <= tc ? 0.0 : meet(t0, c2, P2{l, 0}), meet(w.b1, c2, P2{l, 0}), s,
                 w.sigma, dc, db);
    }
  }

  // The window on halfedge g whose edge runs from p to q (length len) in the parent's frame, lit
  // over [u0, u1] (fractions from p), with the parent's source s; dp, dq: the distances known at p
  // and q (the parent already looked them up).
  void push_child(int g, P2 p, P2 q, double len, double u0, double u1, P2 s, double sigma, double dp, double dq) {
    if (!(u1 > u0) || !has_face(g)) return;
    const P2 ex{(q.x - p.x) / len, (q.y - p.y) / len};
    const P2 ey{-ex.y, ex.x};
    const P2 w{s.x - p.x, s.y - p.y};
    push_window(g, u0 * len, u1 * len, P2{dot2(w, ex), std::min(dot2(w, ey), 0.0)}, sigma, dp, dq, len);
  }

  // The face-vertex c of halfedge h's face takes distance d from the window's source s (in h's
  // frame; c at c2, the edge of length l).
  void offer_window_vertex(int c, double d, P2 s, double sigma, int h, double l, P2 c2) {
    if (gone.find(static_cast<uint32_t>(c))) return;
    if (const DRec* rc = dt.find(static_cast<uint32_t>(c)); rc && (rc->settled || !(d < rc->d))) return;
    // The source in 3D, in the plane of h's face (for the direction at c).
    const Vec3& pa = mesh.point(VertexHandle(fromv(h)));
    const Vec3 ex = (mesh.point(VertexHandle(tov(h))) - pa) / l;
    Vec3 ey = (mesh.point(VertexHandle(tov(nexth(h)))) - pa) - ex * c2.x;
    const double ly = ey.norm();
    if (ly > 0) ey /= ly;
    Candidate k;
    k.d = d;
    k.source = pa + ex * s.x + ey * s.y;
    k.origin = k.source;
    k.offset = sigma;
    k.face = mesh.face_handle(HalfedgeHandle(h)).idx();
    offer(c, k);
  }

  // ---- Candidates from a settled vertex x for its neighbour c ---------------------------------
  //
  // They are worked out in a 2D frame of a face t0 at the edge x-c: x at the origin, c at (e, 0),
  // t0's third vertex y at a positive angle. x's virtual source is laid out in that frame by
  // unfolding the faces around x from x's face to t0 (rotations about x's edges: exact). The
  // straight line from the source to c is taken when it crosses every edge of x in between inside
  // the edge and passes x on c's side (a line that leaves x's faces is taken only where they are
  // one plane). This is one source per vertex, not a window per edge: a line may stray from the
  // faces the source was unfolded along before x, so a value can come out slightly short of the
  // geodesic; it is never below the straight line from the real source (checked).


  static constexpr int kMaxCross = 64;
  struct Layout {
    P2 s{0, 0};  // the virtual source
    P2 y{0, 0};  // t0's third vertex
    double e = 0;  // |xc|
    // When the line leaves x's faces unverified: the shortest path from s to c inside the
    // unfolded faces (a taut string bent around ring vertices; see taut_string), its length, and
    // the bend nearest c (ring index, 2D position, string length from s to it); bend_ray = -1: none.
    double bent = kInf;
    int bend_ray = -1;
    P2 bend{0, 0};
    double to_bend = 0;
    double worth = kInf;  // c's distance so far: a bent path is of use only below it
  };

  // Lays out rx's source for the edge x-c (c = ring[ic].v) in the face after (after = true) or
  // before the edge; jf is the ray whose face_after is rx.face.
  bool lay_out(const DRec& rx, int x, int ic, int jf, bool after, Layout& L) {
    L.bend_ray = -1;
    const int m = static_cast<int>(ring.size());
    const int c = ring[ic].v;
    auto wrap = [&](int i) { return wrap_ray(i); };
    if (!ring_closed && !after && ic == 0) return false;
    const int t0_ray = after ? ic : wrap(ic - 1);  // the ray whose face_after is t0
    if (ring[t0_ray].face_after < 0) return false;
    const int y_ray = after ? wrap(ic + 1) : wrap(ic - 1);
    if (!ring_closed && after && ic + 1 >= m) return false;
    L.e = ring[ic].len;
    const P2 a0 = corner_after(t0_ray);
    L.y = {ring[y_ray].len * a0.x, ring[y_ray].len * a0.y};
    const P2 c2{L.e, 0};
    const Vec3& px = mesh.point(VertexHandle(x));

    if (jf == t0_ray) {
      // The source lies in t0's plane: project.
      const Vec3& uc = ring[ic].u;
      Vec3 v = ring[y_ray].u - uc * OpenMesh::dot(ring[y_ray].u, uc);
      const double vl = v.norm();
      if (!(vl > 0)) return false;
      v /= vl;
      auto place = [&](const Vec3& p) {
        const Vec3 w = p - px;
        return P2{OpenMesh::dot(w, uc), OpenMesh::dot(w, v)};
      };
      L.s = place(rx.source);
      // The line must reach c from inside t0's corner at c...
      const P2 cx{-L.e, 0}, cy{L.y.x - L.e, L.y.y}, cs{L.s.x - L.e, L.s.y};
      const double tol = 1e-12 * (L.e * L.e + dot2(cy, cy) + dot2(cs, cs));
      if (cross2(cy, cs) > tol || cross2(cs, cx) > tol) return false;
      // ...and, when the source lies beyond x-y, cross x-y into the face behind it.
      if (cross2(L.y, L.s) < -tol) {
        const int back = after ? ring[y_ray].face_after : ring[wrap(y_ray - 1)].face_after;
        if (back < 0 || (!ring_closed && !after && y_ray == 0)) return false;
      }
      return true;
    }

    // Walk from t0 away from c around x to x's face, collecting the crossed edges.
    // Angles are unit 2D vectors (cos, sin); adding angles multiplies them as complex numbers.
    auto turn = [](P2 a, P2 b) { return P2{a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x}; };
    struct CrossedRay {
      P2 dir;  // (cos, sin) of its angle from c
      double len;
    };
    std::array<CrossedRay, kMaxCross> rays;
    std::array<int, kMaxCross> ray_index;  // their ring indices
    int n_rays = 0;
    const int dir = after ? 1 : -1;
    P2 beta = a0;
    int near_ray = after ? ic + 1 : ic - 1;  // unwrapped indices
    int face_ray = after ? ic + 1 : ic - 2;
    for (int steps = 0;; ++steps) {
      if (steps >= m - 1 || n_rays >= kMaxCross) return false;
      if (!ring_closed && (near_ray < 0 || near_ray >= m || face_ray < 0 || face_ray >= m)) return false;
      const Ray& r = ring[wrap(near_ray)];
      if (r.v == c) return false;  // went all the way round
      ray_index[n_rays] = wrap(near_ray);
      rays[n_rays++] = {beta, r.len};
      const Ray& fr = ring[wrap(face_ray)];
      if (fr.face_after < 0) return false;  // a border gap before reaching x's face
      if (fr.face_after == rx.face) break;
      beta = turn(beta, corner_after(wrap(face_ray)));
      if (beta.y < 0 || (beta.y == 0 && beta.x < 0)) return false;  // a half turn or more
      near_ray += dir;
      face_ray += dir;
    }
    // x's face: its edge at x that was crossed (near) and its other edge (far). A point of its
    // plane at angle psi from the near edge (toward the far one) goes to angle beta + psi.
    const Vec3& u_near = ring[wrap(near_ray)].u;
    const Vec3& u_far = ring[wrap(near_ray + dir)].u;
    const Vec3 w = rx.source - px;
    const double rs = w.norm();
    if (!(rs > 0)) return false;
    const Vec3 cw = OpenMesh::cross(u_near, w);
    const double sin_psi = (OpenMesh::dot(cw, OpenMesh::cross(u_near, u_far)) >= 0 ? 1 : -1) * cw.norm() / rs;
    if (sin_psi < -1e-9) return false;  // the source lies on the near side: the line does not come that way
    const P2 psi{OpenMesh::dot(u_near, w) / rs, std::max(sin_psi, 0.0)};
    const P2 theta = turn(beta, psi);
    if (theta.y < 1e-12 && (theta.y < 0 || theta.x < 0)) return false;  // it would pass x on the other side
    L.s = {rs * theta.x, rs * theta.y};
    bool leaves_fan = false, enters_xy = true;
    std::array<bool, kMaxCross> beyond{};
    for (int k = 0; k < n_rays; ++k) {
      const P2 d = rays[k].dir;
      const double denom = d.x * L.s.y - d.y * (L.s.x - c2.x);
      if (denom == 0) return false;
      const double t = d.y * c2.x / denom;
      if (t < -1e-12 || t > 1 + 1e-12) return false;
      const double rho = d.x * (c2.x + t * (L.s.x - c2.x)) + d.y * t * L.s.y;
      if (rho > rays[k].len * (1 + 1e-9)) {
        if (k == 0) enters_xy = false;  // it must enter t0 through x-y
        leaves_fan = true;  // passes beyond the edge's far end
        beyond[k] = true;
      }
    }
    if (!leaves_fan) return true;
    // A line that leaves x's faces crosses faces this unfolding did not see. It is still taken
    // where those faces are one plane (this keeps planar regions exact), and where y, the other
    // end of the edge it enters t0 through, is settled from the same source at the distance this
    // unfolding gives it: then the lines to x and to y bracket the one to c (the fast-marching
    // update of the face x, y, c, with the source's position instead of a triangulation).
    if (enters_xy) {
      if (fan_is_flat(t0_ray, n_rays + 1, dir)) return true;
      const DRec* ry = dt.find(static_cast<uint32_t>(ring[y_ray].v));
      if (ry && ry->settled && ry->offset == rx.offset && ry->origin == rx.origin) {
        const double dy = rx.offset + std::sqrt((L.s.x - L.y.x) * (L.s.x - L.y.x) + (L.s.y - L.y.y) * (L.s.y - L.y.y));
        if (std::abs(dy - ry->d) <= kBracketTol * ry->d) return true;
      }
    } else if (lit_around_c(rx, c, HalfedgeHandle(ring[ic].he), after, L)) {
      return true;
    }
    // Neither the line nor the string (never shorter) helps c unless the line is below c's distance.
    if (!(rx.offset + std::hypot(L.e - L.s.x, L.s.y) < L.worth)) return false;
    // Where every ring vertex the line passes beyond is intrinsically flat (corner angles summing
    // to a full turn: a plane, or a plane folded or rolled without stretching), the faces around it
    // unfold into the plane of x's without a gap or overlap: the line is as good as one inside them.
    bool flat = true;
    for (int k = 0; k < n_rays && flat; ++k) {
      flat = !beyond[k] || intrinsically_flat(ring[ray_index[k]].v);
    }
    if (flat) return true;
    taut_string(L, rays.data(), ray_index.data(), n_rays);
    return false;
  }

  // The bracket (above) one face further: a line that passes beyond y reaches c through another
  // face of c. c's faces after t0, away from x, are unfolded about c until the one whose corner at
  // c the line comes through; it is taken when both ends of that face's edge opposite c are
  // settled from the same source at the distances this unfolding gives them (the fast-marching
  // update of that face). At most kAroundC faces, less than a half turn.
  static constexpr int kAroundC = 4;
  bool lit_around_c(const DRec& rx, int c, HalfedgeHandle hxc, bool after, const Layout& L) const {
    const P2 pc{L.e, 0};
    const P2 toward{L.s.x - pc.x, L.s.y - pc.y};
    auto lit = [&](int v, P2 p) {
      const DRec* r = dt.find(static_cast<uint32_t>(v));
      if (!r || !r->settled || r->offset != rx.offset || !(r->origin == rx.origin)) return false;
      return std::abs(rx.offset + std::hypot(L.s.x - p.x, L.s.y - p.y) - r->d) <= kBracketTol * r->d;
    };
    // h: the halfedge c -> w (w_1 = y), in the face after it on the walk; prev: the corner before.
    HalfedgeHandle h = after ? mesh.next_halfedge_handle(hxc)
                             : mesh.opposite_halfedge_handle(mesh.prev_halfedge_handle(mesh.opposite_halfedge_handle(hxc)));
    P2 pw = L.y, prev{0, 0};
    int w = mesh.to_vertex_handle(h).idx();
    double turned = std::atan2(std::abs(cross2(P2{-pc.x, 0}, P2{pw.x - pc.x, pw.y - pc.y})),
                               dot2(P2{-pc.x, 0}, P2{pw.x - pc.x, pw.y - pc.y}));
    for (int k = 0; k < kAroundC; ++k) {
      // The next face about c and its corner w2.
      const HalfedgeHandle g = after ? mesh.opposite_halfedge_handle(h) : h;  // the face's halfedge on c-w
      if (!mesh.face_handle(g).is_valid()) return false;
      const HalfedgeHandle h2 = after ? mesh.next_halfedge_handle(g)
                                      : mesh.opposite_halfedge_handle(mesh.prev_halfedge_handle(g));
      const int w2 = mesh.to_vertex_handle(h2).idx();
      // Unfold w2 across c-w, on the side away from prev.
      const P2 cw{pw.x - pc.x, pw.y - pc.y};
      const double lcw = std::hypot(cw.x, cw.y);
      if (!(lcw > 0)) return false;
      const Vec3& p3 = mesh.point(VertexHandle(w2));
      const double lc = (p3 - mesh.point(VertexHandle(c))).norm(), lw = (p3 - mesh.point(VertexHandle(w))).norm();
      const double along = (lc * lc - lw * lw + lcw * lcw) / (2 * lcw);
      const double hgt = std::sqrt(std::max(lc * lc - along * along, 0.0));
      const double side = cross2(cw, P2{prev.x - pc.x, prev.y - pc.y}) > 0 ? -1 : 1;
      const P2 u{cw.x / lcw, cw.y / lcw};
      const P2 pw2{pc.x + u.x * along - u.y * side * hgt, pc.y + u.y * along + u.x * side * hgt};
      const P2 cw2{pw2.x - pc.x, pw2.y - pc.y};
      turned += std::atan2(std::abs(cross2(cw, cw2)), dot2(cw, cw2));
      if (turned >= kTwoPi / 2) return false;
      // Does the line come through this corner (between c->w and c->w2)?
      const double s1 = cross2(cw, toward), s2 = cross2(toward, cw2), s0 = cross2(cw, cw2);
      if (s1 * s0 > 0 && s2 * s0 > 0) {
        // ...across the edge w-w2 (the source lies beyond it), both ends lit.
        if (cross2(P2{pw2.x - pw.x, pw2.y - pw.y}, P2{L.s.x - pw.x, L.s.y - pw.y}) *
                cross2(P2{pw2.x - pw.x, pw2.y - pw.y}, P2{pc.x - pw.x, pc.y - pw.y}) >= 0) {
          return false;
        }
        return lit(w, pw) && lit(w2, pw2);
      }
      prev = pw;
      pw = pw2;
      w = w2;
      h = h2;
    }
    return false;
  }

  // The shortest path from L.s to c (at (L.e, 0)) that stays inside the unfolded faces between
  // them, whose outer corners are the crossed rays' far ends (in order from c): the straight line
  // where it can, bent around the corners it would pass beyond (a convex chain, built like a
  // monotone hull). Every piece crosses only faces of the unfolding, so its length is that of a
  // real path from the source (unlike the straight line that leaves them), and it is never longer
  // than the path through x. Only for lines that leave x's faces unverified (about one layout in
  // ten on the bunny; half of those are skipped by Layout::worth).
  template <class CrossedRay>
  void taut_string(Layout& L, const CrossedRay* rays, const int* ray_index, int n_rays) const {
    std::array<P2, kMaxCross + 2> pt;
    std::array<int, kMaxCross + 2> id;
    int n = 0;
    auto push = [&](P2 p, int i) {
      // keep only right turns (x lies to the left of the way from c to the source)
      while (n >= 2 && cross2(P2{pt[n - 1].x - pt[n - 2].x, pt[n - 1].y - pt[n - 2].y},
                              P2{p.x - pt[n - 1].x, p.y - pt[n - 1].y}) >= 0) {
        --n;
      }
      pt[n] = p;
      id[n++] = i;
    };
    push(P2{L.e, 0}, -1);
    for (int k = 0; k < n_rays; ++k) push(P2{rays[k].dir.x * rays[k].len, rays[k].dir.y * rays[k].len}, ray_index[k]);
    push(L.s, -1);
    if (n < 3) return;  // no bend: the line only grazed a corner
    double len = 0;
    for (int k = n - 1; k >= 1; --k) {
      if (k == 1) L.to_bend = len;
      len += std::hypot(pt[k].x - pt[k - 1].x, pt[k].y - pt[k - 1].y);
    }
    L.bent = len;
    L.bend_ray = id[1];
    L.bend = pt[1];
  }

  // Whether v's corner angles sum to a full turn within kFlatDefect (false at a border vertex).
  // The angles are added as unit complex numbers (no trigonometry); each is below a half turn, so
  // the full turns passed are counted where the running sum crosses from below to above the axis.
  bool intrinsically_flat(int v) const {
    const VertexHandle vh(v);
    const Vec3& p = mesh.point(vh);
    const HalfedgeHandle h0 = mesh.halfedge_handle(vh);
    if (!h0.is_valid() || mesh.is_boundary(h0)) return false;  // OpenMesh keeps a border halfedge here
    double re = 1, im = 0;
    int turns = 0;
    HalfedgeHandle h = h0;
    int guard = 0;
    do {
      const HalfedgeHandle hn = mesh.next_halfedge_handle(h);
      const Vec3 a = mesh.point(mesh.to_vertex_handle(h)) - p;
      const Vec3 b = mesh.point(mesh.to_vertex_handle(hn)) - p;
      const double cs = OpenMesh::dot(a, b), sn = OpenMesh::cross(a, b).norm();
      const double l = std::sqrt(cs * cs + sn * sn);
      if (!(l > 0)) return false;
      const double r2 = (re * cs - im * sn) / l, i2 = (re * sn + im * cs) / l;
      turns += im < 0 && i2 >= 0;
      re = r2;
      im = i2;
      h = mesh.opposite_halfedge_handle(mesh.prev_halfedge_handle(h));  // the next outgoing halfedge
      if (mesh.is_boundary(h) || ++guard > (1 << 16)) return false;
    } while (h != h0);
    turns += im < 0;
    return turns == 1 && re > 0 && std::abs(im) <= kFlatDefect;
  }

  // Whether the `count` faces around x, starting with the face after ray `first` and going in
  // direction `dir`, lie in one plane: every two neighbours do when their three edges at x do.
  bool fan_is_flat(int first, int count, int dir) const {
    auto ray = [&](int i) -> const Ray& { return ring[wrap_ray(i)]; };
    for (int k = 0; k + 1 < count; ++k) {
      const int i = first + dir * k;  // face k lies between rays i and i + dir
      const double det =
          OpenMesh::dot(ray(i).u, OpenMesh::cross(ray(i + dir).u, ray(i + 2 * dir).u));
      if (std::abs(det) > kFlatDet) return false;
    }
    return true;
  }

  // The candidate distances of `c` from its settled neighbour `x` (record `rx`), offered to `c`.
  // `hxc` is the halfedge x -> c.
  void propagate(int x, const DRec& rx, int c, HalfedgeHandle hxc) {
    const Vec3& px = mesh.point(VertexHandle(x));

    // (1) Through x as a vertex: the Dijkstra bound; x becomes the pseudo source.
    const FaceHandle f_left = mesh.face_handle(hxc);
    Candidate through_x;
    through_x.d = rx.d + (px - mesh.point(VertexHandle(c))).norm();
    through_x.source = px;
    through_x.origin = px;
    through_x.offset = rx.d;
    through_x.face = f_left.is_valid() ? f_left.idx() : mesh.face_handle(mesh.opposite_halfedge_handle(hxc)).idx();
    offer(c, through_x);
    if (windowed) return;  // the straight lines come from the windows
    // (2) The straight lines: from x's virtual source and from x's second source (see DRec) when
    // the first finds no way to c or the second is straighter (a smaller offset: it bends later or
    // not at all). A vertex keeps the source its own shortest path bends at, but the path to a
    // neighbour past it can pass that pseudo source on the other side, unbent: from the bent
    // source alone such neighbours came out up to 17% too long on homer
    // (bench/results/geodesic-accuracy.md, session 12).
    // A straight line is never shorter at c than at x: nothing to gain if c is already there.
    const DRec* rc = dt.find(static_cast<uint32_t>(c));
    if (rc && rc->d <= rx.d) return;
    const double dc = rc ? rc->d : kInf;
    bool found = false;
    if (!(rx.face < 0 || (rx.d == rx.offset && (rx.source - px).sqrnorm() == 0))) {  // else x is the (pseudo) source
      found = propagate_line(x, rx, c, hxc, dc);
    }
    if ((!found || rx.alt.offset < rx.offset) && rx.alt.d < kInf && rx.alt.face >= 0 && (rx.alt.source - px).sqrnorm() > 0) {
      DRec ra = rx;  // the second source, settled at x's distance
      ra.source = rx.alt.source;
      ra.offset = rx.alt.offset;
      ra.face = rx.alt.face;
      ra.origin = rx.alt.origin;
      propagate_line(x, ra, c, hxc, dc);
    }
  }

  // The straight-line candidate of `c` from rx's virtual source (rx.d: x's settled distance).
  // dc: c's distance before (a bound for the bent path, see Layout::worth).
  bool propagate_line(int x, const DRec& rx, int c, HalfedgeHandle hxc, double dc) {
    const Vec3& px = mesh.point(VertexHandle(x));
    const Vec3& pc = mesh.point(VertexHandle(c));
    const double e = (px - pc).norm();
    const int f_left = mesh.face_handle(hxc).idx();
    const int f_right = mesh.face_handle(mesh.opposite_halfedge_handle(hxc)).idx();

    // (2) x's virtual source, unfolded into either face at x-c, when the straight line crosses
    // x's faces in between.
    const double euclid_bound = rx.offset + (pc - rx.origin).norm();
    // Where c and x's source face lie in x's ring (the same for both faces at x-c).
    int ic = -1, jf = -1;
    for (int i = 0; i < static_cast<int>(ring.size()); ++i) {
      if (ring[i].v == c && ic < 0) ic = i;
      if (ring[i].face_after == rx.face) jf = i;
    }
    if (ic < 0 || jf < 0) return false;
    Candidate best, bent;
    Layout L;
    L.worth = dc;
    for (const bool after : {true, false}) {
      const int t0 = after ? f_left : f_right;
      if (t0 < 0) continue;
      const bool straight = lay_out(rx, x, ic, jf, after, L);
      if (!straight && L.bend_ray < 0) continue;
      // Causality: c may lie nearer the source than x (a vertex whose neighbours are all farther,
      // reached across a long edge); it cannot be settled before x any more, so it gets x's
      // distance, the nearest to the truth that keeps the settle order, and keeps the unfolded
      // source for its own neighbours. Rejecting the line would leave c the path around x.
      if (!straight) {
        // The string reaches its bend vertex along faces this unfolding saw, but the source may
        // not light that vertex (another way round may be the shortest): the bend must be settled,
        // and the string is trusted no shorter than the bend's own distance. (Without this some
        // values came out below the Euclidean distance.)
        const DRec* rb = dt.find(static_cast<uint32_t>(ring[L.bend_ray].v));
        if (!rb || !rb->settled) continue;
        const double at_bend = rx.offset + L.to_bend;
        if (rb->d > at_bend) {
          L.bent += rb->d - at_bend;
          L.to_bend = rb->d - rx.offset;
        }
      }
      const double d = std::max(rx.d, rx.offset + (straight ? std::sqrt((L.e - L.s.x) * (L.e - L.s.x) + L.s.y * L.s.y) : L.bent));
      // Never below the straight line from where the source really is (an unfolding is exact
      // only along the faces it went through; a line that strays from them can come out too short).
      if (d < euclid_bound * (1 - 1e-12) || !(d < (straight ? best.d : bent.d))) continue;
      Candidate cand;
      // Back to 3D in t0's plane: c's edge direction and the in-plane perpendicular toward y.
      const Vec3 uc = (pc - px) / e;
      const Vec3& py = mesh.point(VertexHandle(after ? mesh.to_vertex_handle(mesh.next_halfedge_handle(hxc)).idx()
                                                     : mesh.to_vertex_handle(mesh.next_halfedge_handle(
                                                           mesh.opposite_halfedge_handle(hxc))).idx()));
      Vec3 v = (py - px) - uc * OpenMesh::dot(py - px, uc);
      const double vl = v.norm();
      if (!(vl > 0)) continue;
      v /= vl;
      auto to3 = [&](P2 q) { return px + uc * q.x + v * q.y; };
      cand.d = d;
      cand.face = t0;
      if (straight) {
        cand.source = to3(L.s);
        cand.offset = rx.offset;
        cand.origin = rx.origin;
        best = cand;
      } else {
        // The string's bend nearest c is c's pseudo source (it is not taken as a way found: x's
        // second source may still have a straight line).
        cand.source = to3(L.bend);
        cand.offset = rx.offset + L.to_bend;
        cand.origin = mesh.point(VertexHandle(ring[L.bend_ray].v));
        bent = cand;
      }
    }
    if (bent.face >= 0 && bent.d < best.d) offer(c, bent);
    if (best.face >= 0) offer(c, best);
    return best.face >= 0;
  }

  // The ring's connectivity, walked once per settled vertex: its outgoing halfedges and neighbours,
  // counter-clockwise, taken before the front expansion at x (the cache misses of the walk are
  // taken here, and the neighbours' positions are prefetched for build_ring).
  void start_ring(int x) {
    ring.clear();
    const VertexHandle vx(x);
    const HalfedgeHandle h0 = mesh.halfedge_handle(vx);
    if (!h0.is_valid()) return;
    // At a border vertex OpenMesh's outgoing halfedge has no face: start just after that gap.
    ring_closed = !mesh.is_boundary(h0);
    const HalfedgeHandle start = ring_closed ? h0 : mesh.ccw_rotated_halfedge_handle(h0);
    HalfedgeHandle h = start;
    do {
      const VertexHandle y = mesh.to_vertex_handle(h);
      detail::prefetch(&mesh.point(y));
      Ray r{};
      r.v = y.idx();
      r.he = h.idx();
      ring.push_back(r);
      h = mesh.ccw_rotated_halfedge_handle(h);
    } while (h != start && ring.size() < (1u << 16));
  }

  // The ring's geometry (start_ring(x) first).
  void build_ring(int x) {
    const Vec3& px = mesh.point(VertexHandle(x));
    for (Ray& r : ring) {
      const Vec3 w = mesh.point(VertexHandle(r.v)) - px;
      const double len = w.norm();
      const FaceHandle f = mesh.face_handle(HalfedgeHandle(r.he));
      r.u = len > 0 ? w / len : w;
      r.len = len;
      r.face_after = f.is_valid() ? f.idx() : -1;
      r.corner = P2{1, 0};
      r.corner_known = false;
    }
  }

  // The ring index of the k-th outgoing halfedge in OpenMesh's circulation order (clockwise from
  // the vertex's halfedge), the order in which neighbours take their offers.
  int voh_order(int k) const {
    const int m = static_cast<int>(ring.size());
    return ring_closed ? (k == 0 ? 0 : m - k) : m - 1 - k;
  }

  // A ring index taken modulo the ring's size, without an integer division (the walks stay within
  // a turn or two; the divisions were a tenth of lay_out's time).
  int wrap_ray(int i) const {
    const int m = static_cast<int>(ring.size());
    while (i < 0) i += m;
    while (i >= m) i -= m;
    return i;
  }

  // The corner angle at x of the face after ray i as (cos, sin) (computed on first use).
  P2 corner_after(int i) {
    Ray& r = ring[i];
    if (!r.corner_known) {
      const Vec3& a = r.u;
      const Vec3& b = ring[i + 1 == static_cast<int>(ring.size()) ? 0 : i + 1].u;
      const double c = OpenMesh::dot(a, b), s = OpenMesh::cross(a, b).norm();
      const double l = std::sqrt(c * c + s * s);
      r.corner = l > 0 ? P2{c / l, s / l} : P2{1, 0};
      r.corner_known = true;
    }
    return r.corner;
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

  // The twins of the settled vertex x (a pinched vertex: one point of the surface) take its
  // distance and its direction `dir` (also when one came as near from its own side: one value per
  // point), each a pseudo source for its own fan (no line continues through a point: the MDF's and
  // the windows' own rule at a vertex the front cannot pass; the default mode keeps the twin's
  // own way as its second source), and with the front tracked each joins it as a seed unless it
  // is on the front or has been (twins_joined): its fan is then processed from there. A settled
  // vertex's record stays while a twin is not settled (they count as neighbours), so a twin is
  // never reached again. Returns the number of twins not settled yet.
  [[gnu::noinline]] int settle_twins(int x, const DRec& rx) {
    const double d = rx.d;
    const Vec3 dir = direction_of(x, rx);
    int open = 0;
    const bool track = opts.track_front || windowed;
    twins.for_each_twin(x, [&](int t) {
      DRec* rt = dt.find(static_cast<uint32_t>(t));
      if (rt && rt->settled) {
        if (--rt->unsettled <= 0) drop(t);
        return;
      }
      ++open;
      const bool joined = twins_joined.contains(static_cast<uint32_t>(t));
      if (rt) {
        --rt->unsettled;  // (a loop source's count; rewritten when t settles otherwise)
        // Taken whatever t's own value (no settled twin lies nearer: it would have settled
        // first); the default mode keeps t's own way as its second source.
        if (!windowed && std::isfinite(rt->d) && rt->face >= 0) {
          rt->alt = Candidate{rt->d, rt->source, rt->offset, rt->face, rt->origin};
        }
        rt->d = kInf;
      }
      // The pseudo source sits at the pinch (origin, offset d, no face); `source` only marks the
      // direction (direction_of), as it is not unfolded.
      Candidate k;
      k.d = d;
      k.origin = mesh.point(VertexHandle(t));
      k.source = k.origin + dir;
      k.offset = d;
      offer(t, k);
      dt.find(static_cast<uint32_t>(t))->twin = true;  // (kept if a tie replaces it: windows all around)
      if (track && !joined && !vt.contains(static_cast<uint32_t>(t))) seed_twin(t, true);
    });
    return open;
  }

  void settle_neighbours(int x) {
    DRec rx = *dt.find(static_cast<uint32_t>(x));  // copy: offers may rehash the table
    build_ring(x);
    int open = 0;  // neighbours (and twins) not settled yet
    auto visit = [&](int c, HalfedgeHandle hxc) {
      DRec* rc = dt.find(static_cast<uint32_t>(c));
      open += !(rc && rc->settled);
      if (rc) {
        --rc->unsettled;
        if (rc->settled) {
          if (rc->unsettled <= 0) drop(c);
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
      for (int k = 0; k < static_cast<int>(ring.size()); ++k) {
        const Ray& r = ring[voh_order(k)];
        if (std::find(wedge.begin(), wedge.end(), r.v) != wedge.end()) {
          visit(r.v, HalfedgeHandle(r.he));
        } else if (DRec* ry = dt.find(static_cast<uint32_t>(r.v))) {
          --ry->unsettled;
          if (ry->settled && ry->unsettled <= 0) drop(r.v);
        }
      }
    } else {
      for (int k = 0; k < static_cast<int>(ring.size()); ++k) {
        const Ray& r = ring[voh_order(k)];
        visit(r.v, HalfedgeHandle(r.he));
      }
    }
    if (twins.any()) [[unlikely]] open += settle_twins(x, rx);
    // Window mode: the sources, and the vertices a geodesic can bend at, light their faces' far
    // edges (a twin's pseudo source all around: its distance came through a point).
    if (windowed && (rx.d == 0 || rx.twin || bends_geodesics())) {
      emit_vertex_windows(x, rx.d, rx.d == 0 || rx.twin ? nullptr : &rx);
    }
    DRec* r = dt.find(static_cast<uint32_t>(x));
    if (r && !line_source) r->unsettled = open;
    if (r && r->unsettled <= 0) drop(x);
  }

  bool step() {
    while (!heap.empty()) {
      const auto [d, v] = heap.top();
      if (v < 0) [[unlikely]] {  // a window
        if (d > opts.max_distance) {
          stop = DistanceStop::MaxDistance;
          return false;
        }
        heap.pop();
        const Window w = win[static_cast<size_t>(-1 - v)];
        free_win.push_back(-1 - v);
        if (w.he < 0) continue;  // merged into another window
        propagate_window(w, -1 - v);
        continue;
      }
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
      if (windowed) {
        forget_passed(d);
        r = dt.find(static_cast<uint32_t>(v));
      }
      r->settled = true;
      ++n_settled;
      // Without the front (DistanceOptions::track_front off), the check the front makes when a
      // vertex joins it is made here, before the ring walk relies on the vertex's single fan.
      const bool track = opts.track_front || windowed;
      if (!track) check_joining(v);
      // The ring walk first: its cache misses overlap the caller's callback.
      start_ring(v);
      const Vec3 dir = direction_of(v, *r);
      if (on_settled) on_settled(VertexHandle(v), d, dir);
      const bool expanded = track && expand_vertex(v);
      if (windowed && !expanded && !r->seed) r->unexpanded = true;
      settle_neighbours(v);
      if (windowed) expand_late_neighbours();
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

  // Everything but the edge front's own containers (memory_bytes()).
  size_t distance_bytes() const {
    return dt.memory_bytes() + peak_heap * sizeof(Entry) + win.capacity() * sizeof(Window) + gone.memory_bytes() +
           lit_edges.memory_bytes() + peak_horizon * sizeof(Entry) + twins_joined.memory_bytes();
  }
  size_t total_bytes() const { return memory_bytes() + distance_bytes(); }
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
  return impl_->peak_bytes + impl_->distance_bytes();
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

const char* to_string(DistanceMethod method) {
  switch (method) {
    case DistanceMethod::Mdf: return "mdf";
    case DistanceMethod::Windows: return "windows";
    case DistanceMethod::Fast: return "fast";
    case DistanceMethod::Dijkstra: return "dijkstra";
  }
  return "unknown";
}

DistanceMethod parse_distance_method(const std::string& name) {
  for (DistanceMethod m : {DistanceMethod::Mdf, DistanceMethod::Windows, DistanceMethod::Fast, DistanceMethod::Dijkstra}) {
    if (name == to_string(m)) return m;
  }
  throw InvalidInput("distance: unknown method \"" + name + "\" (one of mdf, windows, fast, dijkstra)");
}

DistanceField geodesic_distance(const Mesh& mesh, const FrontSource& source, const DistanceOptions& options) {
  if (options.method == DistanceMethod::Dijkstra) return dijkstra_distance(mesh, source, options);
  if (options.method == DistanceMethod::Fast && !source.is_loop()) return detail::fast_distance(mesh, source, options);
  DistanceOptions o = options;
  if (o.method == DistanceMethod::Fast) o.method = DistanceMethod::Mdf;  // a loop source runs the MDF
  MinimalDistanceFront front(mesh);
  front.reset(source, o);
  return collect(mesh, front, o);
}

DistanceField geodesic_distance(const Mesh& mesh, const std::vector<SurfacePoint>& points,
                                const DistanceOptions& options) {
  if (options.method == DistanceMethod::Dijkstra) return dijkstra_distance(mesh, points, options);
  if (options.method == DistanceMethod::Fast) return detail::fast_distance(mesh, points, options);
  MinimalDistanceFront front(mesh);
  front.reset(points, options);
  return collect(mesh, front, options);
}

}  // namespace edgefront
