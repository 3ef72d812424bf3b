// The window mode of the Minimal Distance Front (DistanceMethod::Windows): windows per halfedge,
// carried across faces in distance order with the vertices. State: detail/mdf_impl.h.
#include <algorithm>
#include <array>
#include <cmath>

#include "detail/distance_common.h"
#include "detail/mdf_impl.h"

namespace edgefront {

using detail::kFlatDefect;
using detail::kTwoPi;
using detail::mdf::cross2;
using detail::mdf::dot2;
using detail::mdf::kInf;
using detail::mdf::kLitPerEdge;
using detail::mdf::kPendingPerEdge;
using detail::mdf::norm2;
using detail::mdf::P2;
using detail::mdf::Window;

// ---- Windows (DistanceMethod::Windows) ------------------------------------------------------
//
// A window is carried across the face it lights when it leaves the heap, at the smallest distance
// it gives a point of its interval: the face's third vertex takes the distance from the window's
// source when the straight line to it crosses the interval, and the lit parts of the face's two
// other edges become windows of the faces behind them (ICH: Xin & Wang 2009; MMP). Windows and
// vertices leave one heap in distance order, so a vertex settles only after every window that
// could light it more closely. A window is dropped when an end of its edge reaches the whole
// interval more closely (ICH's filter; exact: sigma + |s p| - |a p| never grows from a toward b).

namespace {

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

// The best distance known for v: its record's, or a dropped settled record's; +inf if none;
// -inf for a passed vertex (trim then drops every window on its edges, as its distance would).
double MinimalDistanceFront::Impl::known_d(int v) const {
  if (const DRec* r = dt.find(static_cast<uint32_t>(v))) return r->d;
  if (const Gone* g = gone.find(static_cast<uint32_t>(v))) return g->open < 0 ? g->d : -kInf;
  return kInf;
}

// Moves the gone vertices whose horizon lies below d (the distance settling now; every window
// popped or made from now on is at least d everywhere on its interval) to `passed`, and forgets
// the passed vertices whose neighbours have all passed. Exact: a window on an edge at a passed
// vertex v is longer everywhere than d(v) plus the edge (trim with v's distance would drop it
// whole), and a window reaches a forgotten vertex's faces only across an edge with a passed end.
void MinimalDistanceFront::Impl::forget_passed(double d) {
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
void MinimalDistanceFront::Impl::expand_late_neighbours() {
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

// ICH's filter, as a trim (MMP): the part of [b0, b1] that an end of the edge (distance da at
// the from-vertex, db at the to-vertex, edge length l) reaches more closely along the edge goes.
// Sound: sigma + |s p| - (da + |a p|) never grows from a toward b, so that part is an end piece;
// the path through the end vertex is a real path. False: nothing is left.
bool MinimalDistanceFront::Impl::trim(double& b0, double& b1, P2 s, double sigma, double da, double db,
                                      double l) {
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

void MinimalDistanceFront::Impl::push_window(int h, double b0, double b1, P2 s, double sigma) {
  if (!(b1 > b0) || !has_face(h)) return;
  push_window(h, b0, b1, s, sigma, known_d(fromv(h)), known_d(tov(h)), edge_length(h));
}

// The same with the distances known at the edge's ends and its length (has_face(h) checked).
void MinimalDistanceFront::Impl::push_window(int h, double b0, double b1, P2 s, double sigma, double d_from,
                                             double d_to, double len) {
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
void MinimalDistanceFront::Impl::emit_vertex_windows(int x, double sigma, const DRec* shadow_only) {
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
bool MinimalDistanceFront::Impl::bends_geodesics() {
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

bool MinimalDistanceFront::Impl::trim_against_lit(Window& w, const LitSet& ls) {
  for (int i = 0; i < ls.n; ++i) {
    if (!trim_against(w, ls.w[static_cast<size_t>(i)])) return false;
  }
  return true;
}

// Carries window w across its face (see above).
// (Not inlined: the window code stays out of the default mode's hot loop.)
// id: its slot, to take off its halfedge's list of waiting windows.
void MinimalDistanceFront::Impl::propagate_window(Window w, int id) {
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
void MinimalDistanceFront::Impl::push_child(int g, P2 p, P2 q, double len, double u0, double u1, P2 s,
                                            double sigma, double dp, double dq) {
  if (!(u1 > u0) || !has_face(g)) return;
  const P2 ex{(q.x - p.x) / len, (q.y - p.y) / len};
  const P2 ey{-ex.y, ex.x};
  const P2 w{s.x - p.x, s.y - p.y};
  push_window(g, u0 * len, u1 * len, P2{dot2(w, ex), std::min(dot2(w, ey), 0.0)}, sigma, dp, dq, len);
}

// The face-vertex c of halfedge h's face takes distance d from the window's source s (in h's
// frame; c at c2, the edge of length l).
void MinimalDistanceFront::Impl::offer_window_vertex(int c, double d, P2 s, double sigma, int h, double l,
                                                     P2 c2) {
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

}  // namespace edgefront
