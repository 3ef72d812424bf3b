// The geodesic polyline of a connection path: corridor of faces around the vertex chain, unfolded
// into the plane and straightened with the funnel algorithm; corridor moved to the other side of a
// vertex wherever that shortens the path. See geodesic_polyline in connection_path.h.

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <unordered_map>

#include "edgefront/connection_path.h"
#include "edgefront/error.h"

namespace edgefront {

namespace {

struct P2 {
  double x = 0, y = 0;
};
P2 operator-(P2 a, P2 b) { return {a.x - b.x, a.y - b.y}; }
P2 operator+(P2 a, P2 b) { return {a.x + b.x, a.y + b.y}; }
P2 operator*(double s, P2 a) { return {s * a.x, s * a.y}; }
double cross(P2 a, P2 b) { return a.x * b.y - a.y * b.x; }
// > 0 when c lies left of the ray o -> a.
double orient(P2 o, P2 a, P2 c) { return cross(a - o, c - o); }
double norm(P2 a) { return std::hypot(a.x, a.y); }
bool same(P2 a, P2 b) { return a.x == b.x && a.y == b.y; }

struct Portal {
  int left = -1, right = -1;  // vertex indices
  P2 l, r;                    // unfolded positions
  HalfedgeHandle h;           // from right to left (invalid for the end portals)
};

struct Apex {
  int portal = 0;
  bool left = true;  // which end of that portal
};

class Straightener {
 public:
  explicit Straightener(const Mesh& mesh) : mesh_(mesh) {}

  // Face rotating around v: `ccw` crosses the edge leaving v in f, otherwise the edge entering v.
  FaceHandle rotate(FaceHandle f, VertexHandle v, bool ccw) const {
    for (HalfedgeHandle h : mesh_.fh_range(f)) {
      if (mesh_.to_vertex_handle(h) != v) continue;
      const HalfedgeHandle across = ccw ? mesh_.next_halfedge_handle(h) : h;
      return mesh_.face_handle(mesh_.opposite_halfedge_handle(across));
    }
    return FaceHandle();
  }
  // The faces strictly between a and b around v in direction `ccw`; false when a border blocks.
  bool fan_between(FaceHandle a, FaceHandle b, VertexHandle v, bool ccw, std::vector<FaceHandle>& out) const {
    out.clear();
    FaceHandle f = a;
    const size_t limit = mesh_.valence(v) + 2;
    for (size_t i = 0; i < limit; ++i) {
      f = rotate(f, v, ccw);
      if (!f.is_valid()) return false;
      if (f == b) return true;
      out.push_back(f);
    }
    return false;
  }
  bool contains(FaceHandle f, VertexHandle v) const {
    for (VertexHandle u : mesh_.fv_range(f)) {
      if (u == v) return true;
    }
    return false;
  }

  // The initial corridor: one face along each chain edge (the left one where it exists), joined
  // around each inner chain vertex by the shorter way.
  std::vector<FaceHandle> corridor(const std::vector<VertexHandle>& chain) const {
    std::vector<FaceHandle> along;
    for (size_t i = 0; i + 1 < chain.size(); ++i) {
      const HalfedgeHandle h = mesh_.find_halfedge(chain[i], chain[i + 1]);
      if (!h.is_valid()) {
        throw InvalidInput("geodesic polyline: chain vertices " + std::to_string(chain[i].idx()) + " and " +
                           std::to_string(chain[i + 1].idx()) + " are not joined by an edge");
      }
      FaceHandle f = mesh_.face_handle(h);
      if (!f.is_valid()) f = mesh_.face_handle(mesh_.opposite_halfedge_handle(h));
      if (!f.is_valid()) throw InvalidInput("geodesic polyline: an edge of the chain has no face");
      along.push_back(f);
    }
    std::vector<FaceHandle> strip{along[0]};
    std::vector<FaceHandle> a, b;
    for (size_t i = 1; i < along.size(); ++i) {
      if (along[i] != strip.back()) {
        const bool ok_a = fan_between(strip.back(), along[i], chain[i], true, a);
        const bool ok_b = fan_between(strip.back(), along[i], chain[i], false, b);
        EF_CHECK(ok_a || ok_b, "geodesic polyline: no way around a chain vertex");
        const auto& way = ok_a && (!ok_b || a.size() <= b.size()) ? a : b;
        strip.insert(strip.end(), way.begin(), way.end());
      }
      strip.push_back(along[i]);
    }
    return strip;
  }

  // Removes loops (a face met again) and the faces at either end that only turn around the end
  // vertex.
  void tidy(std::vector<FaceHandle>& strip, VertexHandle s, VertexHandle t) const {
    std::vector<FaceHandle> out;
    std::unordered_map<int, size_t> at;
    for (FaceHandle f : strip) {
      auto it = at.find(f.idx());
      if (it != at.end()) {
        while (out.size() > it->second + 1) {
          at.erase(out.back().idx());
          out.pop_back();
        }
        continue;
      }
      at[f.idx()] = out.size();
      out.push_back(f);
    }
    size_t first = 0;
    while (first + 1 < out.size() && contains(out[first + 1], s)) ++first;
    size_t last = out.size() - 1;
    while (last > first && contains(out[last - 1], t)) --last;
    strip.assign(out.begin() + static_cast<long>(first), out.begin() + static_cast<long>(last) + 1);
  }

  // Unfolds the strip into portals: the start vertex, the shared edges, the end vertex. `s` must
  // be a corner of the first face, `t` of the last.
  void unfold(const std::vector<FaceHandle>& strip, VertexHandle s, VertexHandle t, std::vector<Portal>& portals) const {
    portals.clear();
    std::array<std::pair<int, P2>, 3> cur;
    {
      std::array<VertexHandle, 3> v;
      int i = 0;
      for (VertexHandle u : mesh_.fv_range(strip[0])) v[i++] = u;
      const Vec3 a = mesh_.point(v[0]), b = mesh_.point(v[1]), c = mesh_.point(v[2]);
      const double lab = (b - a).norm();
      cur[0] = {v[0].idx(), P2{0, 0}};
      cur[1] = {v[1].idx(), P2{lab, 0}};
      cur[2] = {v[2].idx(), place(P2{0, 0}, P2{lab, 0}, (c - a).norm(), (c - b).norm(), true)};
    }
    auto pos = [&](int v) {
      for (const auto& [u, p] : cur) {
        if (u == v) return p;
      }
      EF_CHECK(false, "geodesic polyline: unfolding lost a vertex");
      return P2{};
    };
    portals.push_back(Portal{s.idx(), s.idx(), pos(s.idx()), pos(s.idx()), HalfedgeHandle()});
    for (size_t j = 0; j + 1 < strip.size(); ++j) {
      HalfedgeHandle shared;
      for (HalfedgeHandle h : mesh_.fh_range(strip[j])) {
        if (mesh_.face_handle(mesh_.opposite_halfedge_handle(h)) == strip[j + 1]) {
          shared = h;
          break;
        }
      }
      EF_CHECK(shared.is_valid(), "geodesic polyline: consecutive corridor faces share no edge");
      const int r = mesh_.from_vertex_handle(shared).idx(), l = mesh_.to_vertex_handle(shared).idx();
      const P2 pr = pos(r), pl = pos(l);
      portals.push_back(Portal{l, r, pl, pr, shared});
      const HalfedgeHandle o = mesh_.opposite_halfedge_handle(shared);
      const VertexHandle c = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(o));
      const Vec3 c3 = mesh_.point(c);
      const P2 pc = place(pr, pl, (c3 - mesh_.point(VertexHandle(r))).norm(),
                          (c3 - mesh_.point(VertexHandle(l))).norm(), false);
      cur = {std::pair<int, P2>{r, pr}, {l, pl}, {c.idx(), pc}};
    }
    portals.push_back(Portal{t.idx(), t.idx(), pos(t.idx()), pos(t.idx()), HalfedgeHandle()});
  }

  // The point at distances da from a and db from b, left of a -> b or right of it.
  static P2 place(P2 a, P2 b, double da, double db, bool left) {
    const P2 e = b - a;
    const double len = norm(e);
    if (len == 0) return a + P2{da, 0};
    const P2 u = (1.0 / len) * e, n{-u.y, u.x};
    const double x = (da * da - db * db + len * len) / (2 * len);
    const double y = std::sqrt(std::max(0.0, da * da - x * x));
    return a + x * u + (left ? y : -y) * n;
  }

  static P2 apex_pos(const std::vector<Portal>& portals, const Apex& a) {
    return a.left ? portals[a.portal].l : portals[a.portal].r;
  }
  static int apex_vertex(const std::vector<Portal>& portals, const Apex& a) {
    return a.left ? portals[a.portal].left : portals[a.portal].right;
  }

  // The funnel algorithm over the portals: the corners of the shortest path through them.
  static std::vector<Apex> funnel(const std::vector<Portal>& portals) {
    std::vector<Apex> out{Apex{0, true}};
    const int n = static_cast<int>(portals.size());
    P2 apex = portals[0].l, lb = apex, rb = apex;
    int li = 0, ri = 0;
    for (int i = 1; i < n; ++i) {
      const P2 L = portals[i].l, R = portals[i].r;
      if (orient(apex, rb, R) >= 0) {
        if (same(apex, rb) || orient(apex, lb, R) < 0) {
          rb = R;
          ri = i;
        } else {
          if (!same(lb, apex)) out.push_back(Apex{li, true});
          apex = lb;
          rb = lb;
          ri = li;
          i = li;
          continue;
        }
      }
      if (orient(apex, lb, L) <= 0) {
        if (same(apex, lb) || orient(apex, rb, L) > 0) {
          lb = L;
          li = i;
        } else {
          if (!same(rb, apex)) out.push_back(Apex{ri, false});
          apex = rb;
          lb = rb;
          li = ri;
          i = ri;
          continue;
        }
      }
    }
    out.push_back(Apex{n - 1, true});
    return out;
  }

  static double length(const std::vector<Portal>& portals, const std::vector<Apex>& apexes) {
    double sum = 0;
    for (size_t i = 1; i < apexes.size(); ++i)
      sum += norm(apex_pos(portals, apexes[i]) - apex_pos(portals, apexes[i - 1]));
    return sum;
  }

  // The faces strip[lo..hi] around the corner w at portal p (which lies between strip[p-1] and
  // strip[p], both containing w). False for an end portal.
  bool fan_range(const std::vector<FaceHandle>& strip, int p, VertexHandle w, int& lo, int& hi) const {
    lo = p - 1;
    hi = p;
    if (lo < 0 || hi >= static_cast<int>(strip.size())) return false;
    while (lo > 0 && contains(strip[lo - 1], w)) --lo;
    while (hi + 1 < static_cast<int>(strip.size()) && contains(strip[hi + 1], w)) ++hi;
    return true;
  }

  // Moves the corridor to the other side of the corner w at portal p. False when impossible.
  bool flip(std::vector<FaceHandle>& strip, int p, VertexHandle w) const {
    int lo = 0, hi = 0;
    if (!fan_range(strip, p, w, lo, hi)) return false;
    const bool ccw = rotate(strip[lo], w, true) == strip[lo + 1];
    std::vector<FaceHandle> other;
    if (!fan_between(strip[lo], strip[hi], w, !ccw, other)) return false;
    std::vector<FaceHandle> next(strip.begin(), strip.begin() + lo + 1);
    next.insert(next.end(), other.begin(), other.end());
    next.insert(next.end(), strip.begin() + hi, strip.end());
    strip.swap(next);
    return true;
  }

  enum class Trial { impossible, no_gain, gain };
  // A change of the corridor: strip[fa..fb] becomes `faces`.
  struct Window {
    int fa = 0, fb = 0;
    std::vector<FaceHandle> faces;
  };

  // Flips the corridor around the corner of apexes[k] (into `win`) and tells whether that
  // shortens the path between apexes[k-1] and apexes[k+1], straightened on that stretch alone.
  Trial try_flip(const std::vector<FaceHandle>& strip, const std::vector<Portal>& portals, const std::vector<Apex>& apexes,
                 size_t k, Window& win, std::vector<FaceHandle>& local, std::vector<Portal>& local_portals) const {
    const int p = apexes[k].portal, pa = apexes[k - 1].portal, pb = apexes[k + 1].portal;
    const VertexHandle w(apex_vertex(portals, apexes[k]));
    const VertexHandle wa(apex_vertex(portals, apexes[k - 1])), wb(apex_vertex(portals, apexes[k + 1]));
    int lo = 0, hi = 0;
    if (!fan_range(strip, p, w, lo, hi)) return Trial::impossible;
    const int m = static_cast<int>(strip.size());
    // Faces holding the neighbouring corners (portal q lies between strip[q-1] and strip[q]; the
    // end portals are the first face's and the last face's corner).
    win.fa = pa == 0 ? 0 : std::min(pa, lo);
    win.fb = pb == m ? m - 1 : std::max(pb - 1, hi);
    if (!contains(strip[static_cast<size_t>(win.fa)], wa) || !contains(strip[static_cast<size_t>(win.fb)], wb))
      return Trial::impossible;
    win.faces.assign(strip.begin() + win.fa, strip.begin() + win.fb + 1);
    if (!flip(win.faces, p - win.fa, w)) return Trial::impossible;
    local = win.faces;
    tidy(local, wa, wb);
    if (local.empty()) return Trial::no_gain;
    unfold(local, wa, wb, local_portals);
    const double before = norm(apex_pos(portals, apexes[k]) - apex_pos(portals, apexes[k - 1])) +
                          norm(apex_pos(portals, apexes[k + 1]) - apex_pos(portals, apexes[k]));
    const double after = length(local_portals, funnel(local_portals));
    return after < before - 1e-12 * std::max(1.0, before) ? Trial::gain : Trial::no_gain;
  }

  // `strip` with the first `count` windows (in order, not overlapping) applied.
  static void splice(const std::vector<FaceHandle>& strip, const std::vector<Window>& wins, size_t count,
                     std::vector<FaceHandle>& out) {
    out.clear();
    int at = 0;
    for (size_t i = 0; i < count; ++i) {
      out.insert(out.end(), strip.begin() + at, strip.begin() + wins[i].fa);
      out.insert(out.end(), wins[i].faces.begin(), wins[i].faces.end());
      at = wins[i].fb + 1;
    }
    out.insert(out.end(), strip.begin() + at, strip.end());
  }

  std::vector<PathPoint> run(const std::vector<VertexHandle>& chain, int max_flips, bool* converged) {
    const VertexHandle s = chain.front(), t = chain.back();
    std::vector<PathPoint> out;
    if (chain.size() == 1) {
      out.push_back(vertex_point(s));
      if (converged) *converged = true;
      return out;
    }
    std::vector<FaceHandle> strip = corridor(chain);
    tidy(strip, s, t);
    std::vector<Portal> portals, trial_portals;
    unfold(strip, s, t, portals);
    std::vector<Apex> apexes = funnel(portals);
    double len = length(portals, apexes);
    // A pass tries to move the corridor to the other side of each inner corner, judging each
    // move on the stretch between the corner's two neighbouring corners alone (cost follows the
    // corner's fan, not the path). The moves that shorten their stretch and do not overlap are
    // applied together and the whole corridor is straightened once; if that is not shorter
    // (a loop cut away by tidy), they are tried one by one. Passes repeat until nothing shortens.
    std::vector<FaceHandle> trial, local;
    std::vector<Window> wins;
    Window win;
    int flips = 0;
    bool improved = true;
    while (improved && flips < max_flips) {
      improved = false;
      wins.clear();
      for (size_t k = 1; k + 1 < apexes.size() && flips < max_flips; ++k) {
        const Trial outcome = try_flip(strip, portals, apexes, k, win, local, trial_portals);
        if (outcome == Trial::impossible) continue;
        ++flips;
        if (outcome == Trial::no_gain) continue;
        if (!wins.empty() && win.fa <= wins.back().fb) continue;  // overlaps: the next pass
        wins.push_back(win);
      }
      const auto accept = [&](const std::vector<Window>& ws, size_t count) {
        splice(strip, ws, count, trial);
        tidy(trial, s, t);
        if (trial.empty()) return false;
        unfold(trial, s, t, trial_portals);
        std::vector<Apex> ta = funnel(trial_portals);
        const double tl = length(trial_portals, ta);
        if (!(tl < len - 1e-12 * std::max(1.0, len))) return false;
        strip.swap(trial);
        portals.swap(trial_portals);
        apexes.swap(ta);
        len = tl;
        return true;
      };
      improved = !wins.empty() && accept(wins, wins.size());
      for (size_t i = 0; !improved && wins.size() > 1 && i < wins.size(); ++i) {
        const std::vector<Window> one{wins[i]};
        improved = accept(one, 1);
      }
    }
    if (converged) *converged = !improved;
    return points(portals, apexes);
  }

  PathPoint vertex_point(VertexHandle v) const {
    PathPoint p;
    p.vertex = v;
    p.position = mesh_.point(v);
    for (HalfedgeHandle h : mesh_.voh_range(v)) {
      p.halfedge = h;
      break;
    }
    p.t = 0.0;
    return p;
  }

  // The polyline: apexes, and between them the crossings with every portal passed.
  std::vector<PathPoint> points(const std::vector<Portal>& portals, const std::vector<Apex>& apexes) const {
    std::vector<PathPoint> out;
    auto push = [&](const PathPoint& p) {
      if (!out.empty() && p.vertex.is_valid() && out.back().vertex == p.vertex) return;
      out.push_back(p);
    };
    push(vertex_point(VertexHandle(apex_vertex(portals, apexes[0]))));
    for (size_t k = 1; k < apexes.size(); ++k) {
      const P2 a = apex_pos(portals, apexes[k - 1]), b = apex_pos(portals, apexes[k]);
      for (int p = apexes[k - 1].portal + 1; p < apexes[k].portal; ++p) {
        const Portal& q = portals[p];
        const P2 e = q.l - q.r, d = b - a;
        const double den = cross(e, d);
        double u = den != 0 ? cross(a - q.r, d) / den : 0.5;
        u = std::clamp(u, 0.0, 1.0);
        PathPoint pt;
        pt.halfedge = q.h;
        pt.t = u;
        const Vec3 from = mesh_.point(VertexHandle(q.right)), to = mesh_.point(VertexHandle(q.left));
        pt.position = from + u * (to - from);
        if (u <= 1e-12) {
          pt.vertex = VertexHandle(q.right);
          pt.t = 0;
          pt.position = from;
        } else if (u >= 1 - 1e-12) {
          pt.vertex = VertexHandle(q.left);
          pt.t = 1;
          pt.position = to;
        }
        push(pt);
      }
      push(vertex_point(VertexHandle(apex_vertex(portals, apexes[k]))));
    }
    return out;
  }

 private:
  const Mesh& mesh_;
};

}  // namespace

std::vector<PathPoint> geodesic_polyline(const Mesh& mesh, const std::vector<VertexHandle>& chain, int max_flips,
                                         bool* converged) {
  if (chain.empty()) throw InvalidInput("geodesic polyline: the vertex chain is empty");
  for (VertexHandle v : chain) {
    if (!is_live(mesh, v)) {
      throw InvalidInput("geodesic polyline: vertex " + std::to_string(v.idx()) + " is not a live vertex");
    }
  }
  if (max_flips < 0) throw InvalidInput("geodesic polyline: max_flips must not be negative");
  Straightener st(mesh);
  return st.run(chain, max_flips, converged);
}

double polyline_length(const std::vector<PathPoint>& points) {
  double sum = 0;
  for (size_t i = 1; i < points.size(); ++i) sum += (points[i].position - points[i - 1].position).norm();
  return sum;
}

}  // namespace edgefront
