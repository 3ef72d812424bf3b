#pragma once
// The Minimal Distance Front's state (MinimalDistanceFront::Impl) and the records its parts share.
// Internal. The parts:
//   minimal_distance_front.cpp  the front: options, reset, the settle loop (step), the ring walk;
//                               the public class;
//   mdf_unfolding.cpp           a settled vertex's candidates for its neighbours: through the vertex,
//                               along straight lines from its virtual source unfolded across its faces
//                               (and taut strings), from a loop source; twins; dropping records;
//   mdf_windows.cpp             DistanceMethod::Windows: windows per halfedge;
//   geodesic_distance.cpp       the one-off queries (geodesic_distance, method names);
//   distance_common.cpp         the input checks shared with the other distance modes.
// The settle loop's per-vertex helpers (offers, records, the ring's corners) are inline here; the
// per-neighbour work (propagate, lay_out) stays in one translation unit with settle_neighbours.

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <vector>

#include "detail/distance_common.h"
#include "detail/edge_front_core.h"
#include "detail/flat_map.h"
#include "detail/min_heap.h"
#include "edgefront/minimal_distance_front.h"

namespace edgefront::detail::mdf {

inline constexpr double kInf = std::numeric_limits<double>::infinity();
// Two virtual sources closer than this (relative to the distance) count as one.
inline constexpr double kSameSourceTol = 1e-6;

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
inline double cross2(P2 a, P2 b) { return a.x * b.y - a.y * b.x; }
// |(x, y)| without std::hypot's overflow care (a fifth of the windows' time; lengths here are
// mesh-sized).
inline double norm2(double x, double y) { return std::sqrt(x * x + y * y); }
inline double dot2(P2 a, P2 b) { return a.x * b.x + a.y * b.y; }

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
inline constexpr int kLitPerEdge = 4;
inline constexpr int kPendingPerEdge = 4;
struct LitSet {
  int n = 0;     // windows held (at most kLitPerEdge)
  int next = 0;  // the slot the next one replaces when full
  int np = 0;    // waiting windows listed
  std::array<Window, kLitPerEdge> w;
  std::array<int, kPendingPerEdge> pending;
};

}  // namespace edgefront::detail::mdf

namespace edgefront {

struct MinimalDistanceFront::Impl : detail::EdgeFrontCore {
  using Candidate = detail::mdf::Candidate;
  using DRec = detail::mdf::DRec;
  using P2 = detail::mdf::P2;
  using Window = detail::mdf::Window;
  using LitSet = detail::mdf::LitSet;
  using VRec = detail::VRec;

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
  std::vector<int> late;  // scratch (expand_late_neighbours)

  explicit Impl(const Mesh& m) : EdgeFrontCore(m, MinimalEdgeFrontOptions{}) {}

  void on_join(int v, VRec& rec) override {
    rec.level = 0;
    if (twins.any() && twins.next(v) != v) twins_joined.insert(static_cast<uint32_t>(v), 1);  // see settle_twins
  }
  int event_level() const override { return 0; }

  // ---- The front (minimal_distance_front.cpp) -------------------------------------------------

  void check_options(const DistanceOptions& o) const;
  void clear_state(const DistanceOptions& o);
  // Neighbours and twins (see settle_twins) not settled yet.
  // (Loop sources only: kept out of record's way.)
  [[gnu::noinline]] int count_unsettled(int v) const;
  void reset(const FrontSource& source, const DistanceOptions& o);
  void reset(const std::vector<SurfacePoint>& points, const DistanceOptions& o);
  void start_ring(int x);
  bool step();

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
    } else if (r.alt.d < detail::mdf::kInf &&
               same_virtual_source(r.alt.source, r.alt.offset, k.source, k.offset, k.d)) {
      r.alt.d = detail::mdf::kInf;  // the new best is the old second source
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
    constexpr double kTol = detail::mdf::kSameSourceTol;
    return std::abs(oa - ob) <= kTol * scale && (a - b).norm() <= kTol * scale;
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

  // ---- A settled vertex's candidates for its neighbours (mdf_unfolding.cpp) ------------------

  struct Layout;
  void build_ring(int x);
  void settle_neighbours(int x);
  [[gnu::noinline]] int settle_twins(int x, const DRec& rx);
  void drop(int v);
  void propagate(int x, const DRec& rx, int c, HalfedgeHandle hxc);
  bool propagate_line(int x, const DRec& rx, int c, HalfedgeHandle hxc, double dc);
  bool lay_out(const DRec& rx, int x, int ic, int jf, bool after, Layout& L);
  bool lit_around_c(const DRec& rx, int c, HalfedgeHandle hxc, bool after, const Layout& L) const;
  template <class CrossedRay>
  void taut_string(Layout& L, const CrossedRay* rays, const int* ray_index, int n_rays) const;
  bool intrinsically_flat(int v) const;
  bool fan_is_flat(int first, int count, int dir) const;
  void propagate_from_line(int x, const DRec& rx, int c);

  // ---- Windows (mdf_windows.cpp) ---------------------------------------------------------------

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

  double known_d(int v) const;
  [[gnu::noinline]] void forget_passed(double d);
  [[gnu::noinline]] void expand_late_neighbours();
  static bool trim(double& b0, double& b1, P2 s, double sigma, double da, double db, double l);
  void push_window(int h, double b0, double b1, P2 s, double sigma);
  void push_window(int h, double b0, double b1, P2 s, double sigma, double d_from, double d_to, double len);
  [[gnu::noinline]] void emit_vertex_windows(int x, double sigma, const DRec* shadow_only = nullptr);
  [[gnu::noinline]] bool bends_geodesics();
  static bool trim_against_lit(Window& w, const LitSet& ls);
  [[gnu::noinline]] void propagate_window(Window w, int id);
  void push_child(int g, P2 p, P2 q, double len, double u0, double u1, P2 s, double sigma, double dp,
                  double dq);
  void offer_window_vertex(int c, double d, P2 s, double sigma, int h, double l, P2 c2);
};

}  // namespace edgefront
