// A settled vertex's candidates for its neighbours in the Minimal Distance Front: through the
// vertex, along the straight line from its virtual source unfolded across its faces (or a taut
// string around them), from a loop source; its twins; dropping records no longer needed. The
// per-neighbour work of the settle loop, kept in one translation unit. State: detail/mdf_impl.h.
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "detail/distance_common.h"
#include "detail/mdf_impl.h"

namespace edgefront {

using detail::kFlatDefect;
using detail::kTwoPi;
using detail::mdf::Candidate;
using detail::mdf::cross2;
using detail::mdf::dot2;
using detail::mdf::kInf;
using detail::mdf::P2;

namespace {

// Three unit edge directions at a vertex with a smaller triple product count as one plane.
constexpr double kFlatDet = 1e-9;
// A settled vertex agrees with an unfolded source when their distances differ by this (relative).
constexpr double kBracketTol = 1e-3;
// At most this many edges crossed by one unfolding (lay_out), and faces turned about c (lit_around_c).
constexpr int kMaxCross = 64;
constexpr int kAroundC = 4;
}  // namespace

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

struct MinimalDistanceFront::Impl::Layout {
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
bool MinimalDistanceFront::Impl::lay_out(const DRec& rx, int x, int ic, int jf, bool after, Layout& L) {
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
bool MinimalDistanceFront::Impl::lit_around_c(const DRec& rx, int c, HalfedgeHandle hxc, bool after,
                                              const Layout& L) const {
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
void MinimalDistanceFront::Impl::taut_string(Layout& L, const CrossedRay* rays, const int* ray_index,
                                             int n_rays) const {
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
bool MinimalDistanceFront::Impl::intrinsically_flat(int v) const {
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
bool MinimalDistanceFront::Impl::fan_is_flat(int first, int count, int dir) const {
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
void MinimalDistanceFront::Impl::propagate(int x, const DRec& rx, int c, HalfedgeHandle hxc) {
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
bool MinimalDistanceFront::Impl::propagate_line(int x, const DRec& rx, int c, HalfedgeHandle hxc, double dc) {
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

// The ring's geometry (start_ring(x) first).
void MinimalDistanceFront::Impl::build_ring(int x) {
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

// The line source: a loop vertex x gives its wedge neighbours their distance to the loop's two
// segments at x.
void MinimalDistanceFront::Impl::propagate_from_line(int x, const DRec& rx, int c) {
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
int MinimalDistanceFront::Impl::settle_twins(int x, const DRec& rx) {
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

void MinimalDistanceFront::Impl::settle_neighbours(int x) {
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

// Drops the record of a settled vertex whose neighbours are all settled.
void MinimalDistanceFront::Impl::drop(int v) {
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

}  // namespace edgefront
