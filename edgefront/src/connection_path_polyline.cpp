// The geodesic polyline of a connection path: corridor of faces around the vertex chain, unfolded
// into the plane and straightened with the funnel algorithm; corridor moved to the other side of a
// vertex wherever that shortens the path. See geodesic_polyline in connection_path.h.

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <string>
#include <unordered_map>
#include <unordered_set>

#include "edgefront/connection_path.h"
#include "edgefront/error.h"
#include "edgefront/vertex_twins.h"

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
    for (size_t i = 1; i < along.size(); ++i) {
      if (along[i] != strip.back()) append_fan(strip, along[i], chain[i]);
      strip.push_back(along[i]);
    }
    return strip;
  }

  // Appends the faces strictly between strip.back() and f around their common vertex w, the
  // shorter way round (the straightening's flips correct the side where that was wrong).
  void append_fan(std::vector<FaceHandle>& strip, FaceHandle f, VertexHandle w) const {
    std::vector<FaceHandle> a, b;
    const bool ok_a = fan_between(strip.back(), f, w, true, a);
    const bool ok_b = fan_between(strip.back(), f, w, false, b);
    EF_CHECK(ok_a || ok_b, "geodesic polyline: no way around a path vertex");
    const auto& way = ok_a && (!ok_b || a.size() <= b.size()) ? a : b;
    strip.insert(strip.end(), way.begin(), way.end());
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
    return straighten(corridor(chain), s, t, max_flips, converged);
  }

  // Straightens the corridor `strip` (consecutive faces share an edge; s a corner of the first
  // face, t of the last): funnel, then corridor moves around the corners while they shorten it.
  std::vector<PathPoint> straighten(std::vector<FaceHandle> strip, VertexHandle s, VertexHandle t, int max_flips,
                                    bool* converged) {
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
    if (p.halfedge.is_valid()) p.location = surface_point_on_edge(mesh_, p.halfedge, 0.0);  // an isolated vertex has none
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
        pt.location = surface_point_on_edge(mesh_, pt.halfedge, pt.t);
        push(pt);
      }
      push(vertex_point(VertexHandle(apex_vertex(portals, apexes[k]))));
    }
    return out;
  }

 private:
  const Mesh& mesh_;
};

// The band step: the shortest path from s to t over the vertices and `k` Steiner points per edge
// of a band of faces around a polyline (A* with the straight-line bound; inside a face the
// straight segment between two of its boundary points is exact), then the corridor of the faces
// that path crosses, straightened as above. The band is every face with a vertex within `radius`
// (edge-path distance) of the polyline's edges, so the work follows the band, not the mesh.
class BandSearch {
 public:
  explicit BandSearch(const Mesh& mesh) : mesh_(mesh), st_(mesh) {}

  // Returns false when the band holds no path (cannot happen when the polyline is valid).
  bool corridor(const std::vector<PathPoint>& polyline, double radius, int k, std::vector<FaceHandle>& strip) {
    collect_band(polyline, radius);
    index_band(k);
    // Steiner paths are longer than the geodesics they follow (a few percent with one point per
    // edge); a way through the band that is longer than this bound cannot straighten into a
    // shorter polyline in practice, so the search does not queue it.
    bound_ = kSteinerSlack * polyline_length(polyline);
    const int s = vertex_local_.at(polyline.front().vertex.idx());
    const int t = vertex_local_.at(polyline.back().vertex.idx());
    if (!search(s, t)) return false;
    // The faces the path crosses (each node was reached through one), joined around its vertices.
    std::vector<int> nodes;
    for (int n = t; n != s; n = pred_[static_cast<size_t>(n)]) nodes.push_back(n);
    std::reverse(nodes.begin(), nodes.end());
    strip.clear();
    int node = s;
    for (size_t i = 0; i < nodes.size(); ++i) {
      const FaceHandle f = band_[static_cast<size_t>(pred_face_[static_cast<size_t>(nodes[i])])];
      if (!strip.empty() && f != strip.back() && !share_edge(strip.back(), f)) {
        // The path passes the vertex `node` between two faces around it: add the fan between them.
        EF_CHECK(node < nv_, "band polyline: faces of an edge point share no edge");
        st_.append_fan(strip, f, verts_[static_cast<size_t>(node)]);
      }
      if (strip.empty() || f != strip.back()) strip.push_back(f);
      node = nodes[i];
    }
    return !strip.empty();
  }

  size_t band_vertices() const { return verts_.size(); }
  Straightener& straightener() { return st_; }

 private:
  bool share_edge(FaceHandle f, FaceHandle g) const {
    for (HalfedgeHandle h : mesh_.fh_range(f)) {
      if (mesh_.face_handle(mesh_.opposite_halfedge_handle(h)) == g) return true;
    }
    return false;
  }

  void collect_band(const std::vector<PathPoint>& polyline, double radius) {
    using Item = std::pair<double, int>;
    std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
    reach_.clear();
    auto seed = [&](VertexHandle v) {
      if (reach_.emplace(v.idx(), 0.0).second) queue.emplace(0.0, v.idx());
    };
    for (const PathPoint& p : polyline) {
      if (p.vertex.is_valid()) {
        seed(p.vertex);
      } else {
        seed(mesh_.from_vertex_handle(p.halfedge));
        seed(mesh_.to_vertex_handle(p.halfedge));
      }
    }
    while (!queue.empty()) {
      const auto [d, vi] = queue.top();
      queue.pop();
      if (d > reach_.at(vi)) continue;
      const VertexHandle v(vi);
      for (HalfedgeHandle h : mesh_.voh_range(v)) {
        const VertexHandle u = mesh_.to_vertex_handle(h);
        const double du = d + mesh_.calc_edge_length(h);
        if (du > radius) continue;
        auto [it, fresh] = reach_.emplace(u.idx(), du);
        if (!fresh && du >= it->second) continue;
        it->second = du;
        queue.emplace(du, u.idx());
      }
    }
    band_.clear();
    in_band_.clear();
    for (const auto& [vi, d] : reach_) {
      for (FaceHandle f : mesh_.vf_range(VertexHandle(vi))) {
        if (in_band_.insert(f.idx()).second) band_.push_back(f);
      }
    }
  }

  int vertex_id(VertexHandle v) {
    auto [it, fresh] = vertex_local_.emplace(v.idx(), static_cast<int>(verts_.size()));
    if (fresh) verts_.push_back(v);
    return it->second;
  }

  void index_band(int k) {
    k_ = k;
    vertex_local_.clear();
    verts_.clear();
    for (FaceHandle f : band_) {
      for (VertexHandle v : mesh_.fv_range(f)) vertex_id(v);
    }
    nv_ = static_cast<int>(verts_.size());
    std::unordered_map<int, int> edge_local;
    edges_.clear();
    const size_t per_face = static_cast<size_t>(3 + 3 * k);
    face_nodes_.assign(band_.size() * per_face, -1);
    for (size_t fi = 0; fi < band_.size(); ++fi) {
      size_t at = fi * per_face;
      // The face's boundary nodes as a ring: per halfedge its Steiner points from its from-vertex
      // on, then its to-vertex.
      for (HalfedgeHandle h : mesh_.fh_range(band_[fi])) {
        const EdgeHandle e = mesh_.edge_handle(h);
        auto [it, fresh] = edge_local.emplace(e.idx(), static_cast<int>(edges_.size()));
        if (fresh) edges_.push_back(e);
        const bool forward = mesh_.halfedge_handle(e, 0) == h;
        for (int j = 0; j < k; ++j) face_nodes_[at++] = nv_ + it->second * k + (forward ? j : k - 1 - j);
        face_nodes_[at++] = vertex_local_.at(mesh_.to_vertex_handle(h).idx());
      }
    }
    // Two nodes on one side of a face that are not neighbours on the ring: the straight segment
    // between them runs through the nodes in between, so the search need not relax it.
    const int m = static_cast<int>(per_face);
    collinear_.assign(per_face * per_face, 0);
    auto sides = [&](int slot) {  // sides holding a slot (side i: slots i(k+1)-1 .. i(k+1)+k)
      const int side = slot / (k + 1);
      return slot % (k + 1) == k ? std::pair<int, int>{side, (side + 1) % 3} : std::pair<int, int>{side, side};
    };
    for (int a = 0; a < m; ++a) {
      for (int b = 0; b < m; ++b) {
        const int gap = std::abs(a - b), ring = std::min(gap, m - gap);
        const auto [a1, a2] = sides(a);
        const auto [b1, b2] = sides(b);
        const bool shared = a1 == b1 || a1 == b2 || a2 == b1 || a2 == b2;
        collinear_[static_cast<size_t>(a * m + b)] = shared && ring > 1 ? 1 : 0;
      }
    }
    const size_t n = static_cast<size_t>(nv_) + edges_.size() * static_cast<size_t>(k);
    pos_.resize(n);
    for (int i = 0; i < nv_; ++i) pos_[static_cast<size_t>(i)] = mesh_.point(verts_[static_cast<size_t>(i)]);
    for (size_t e = 0; e < edges_.size(); ++e) {
      const HalfedgeHandle h = mesh_.halfedge_handle(edges_[e], 0);
      const Vec3 a = mesh_.point(mesh_.from_vertex_handle(h)), b = mesh_.point(mesh_.to_vertex_handle(h));
      for (int j = 0; j < k; ++j) {
        const double u = static_cast<double>(j + 1) / (k + 1);
        pos_[static_cast<size_t>(nv_) + e * static_cast<size_t>(k) + static_cast<size_t>(j)] = a + u * (b - a);
      }
    }
    // Node -> band faces (compressed rows).
    first_.assign(n + 1, 0);
    for (int id : face_nodes_) ++first_[static_cast<size_t>(id) + 1];
    for (size_t i = 0; i < n; ++i) first_[i + 1] += first_[i];
    node_faces_.resize(face_nodes_.size());
    std::vector<size_t> fill(first_.begin(), first_.end() - 1);
    for (size_t i = 0; i < face_nodes_.size(); ++i)
      node_faces_[fill[static_cast<size_t>(face_nodes_[i])]++] = static_cast<int>(i);  // face * per_face + slot
  }

  bool search(int s, int t) {
    const size_t n = pos_.size();
    dist_.assign(n, std::numeric_limits<double>::infinity());
    pred_.assign(n, -1);
    pred_face_.assign(n, -1);
    const Vec3 target = pos_[static_cast<size_t>(t)];
    using Item = std::pair<double, int>;
    std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
    dist_[static_cast<size_t>(s)] = 0;
    queue.emplace((pos_[static_cast<size_t>(s)] - target).norm(), s);
    const size_t per_face = static_cast<size_t>(3 + 3 * k_);
    while (!queue.empty()) {
      const auto [key, a] = queue.top();
      queue.pop();
      const size_t ai = static_cast<size_t>(a);
      if (key > dist_[ai] + (pos_[ai] - target).norm() + 1e-12 * (1 + key)) continue;
      if (a == t) return true;
      for (size_t j = first_[ai]; j < first_[ai + 1]; ++j) {
        const size_t f = static_cast<size_t>(node_faces_[j]) / per_face, slot = static_cast<size_t>(node_faces_[j]) % per_face;
        const unsigned char* skip = &collinear_[slot * per_face];
        for (size_t q = f * per_face; q < (f + 1) * per_face; ++q) {
          if (skip[q - f * per_face]) continue;
          const size_t b = static_cast<size_t>(face_nodes_[q]);
          const double db = dist_[ai] + (pos_[b] - pos_[ai]).norm();
          if (db >= dist_[b]) continue;
          const double fb = db + (pos_[b] - target).norm();
          if (fb > bound_) continue;
          dist_[b] = db;
          pred_[b] = a;
          pred_face_[b] = static_cast<int>(f);
          queue.emplace(fb, static_cast<int>(b));
        }
      }
    }
    return false;
  }

  const Mesh& mesh_;
  Straightener st_;
  std::unordered_map<int, double> reach_;
  std::vector<FaceHandle> band_;
  std::unordered_set<int> in_band_;
  std::unordered_map<int, int> vertex_local_;
  std::vector<VertexHandle> verts_;
  std::vector<EdgeHandle> edges_;
  static constexpr double kSteinerSlack = 1.1;
  int nv_ = 0, k_ = 0;
  double bound_ = 0;
  std::vector<int> face_nodes_, node_faces_, pred_, pred_face_;
  std::vector<size_t> first_;
  std::vector<unsigned char> collinear_;
  std::vector<Vec3> pos_;
  std::vector<double> dist_;
};

// The pieces of a path between the twin steps (consecutive vertices that are twins: the path
// passes a pinched vertex, where no straight line continues): calls piece(first, last) for each
// maximal range of `n` items without such a step, in order; `twins_at(i)` says whether items i and
// i + 1 are twins. Returns false (no call) when the path has no twin step.
template <class TwinsAt, class Piece>
bool for_each_piece(size_t n, TwinsAt&& twins_at, Piece&& piece) {
  bool split = false;
  for (size_t i = 0; i + 1 < n && !split; ++i) split = twins_at(i);
  if (!split) return false;
  size_t first = 0;
  for (size_t i = 0; i + 1 < n; ++i) {
    if (!twins_at(i)) continue;
    piece(first, i);
    first = i + 1;
  }
  piece(first, n - 1);
  return true;
}

bool twins_of_each_other(const TwinRing& twins, VertexHandle a, VertexHandle b) {
  bool found = false;
  if (a.is_valid() && b.is_valid()) twins.for_each_twin(a.idx(), [&](int t) { found = found || t == b.idx(); });
  return found;
}

}  // namespace

std::vector<PathPoint> band_polyline(const Mesh& mesh, const std::vector<PathPoint>& polyline, double band_radius,
                                     int steiner_points, int max_flips, bool* converged, size_t* band_vertices) {
  if (!(std::isfinite(band_radius) && band_radius >= 0))
    throw InvalidInput("band polyline: the band radius must be finite and not negative, got " +
                       std::to_string(band_radius));
  if (steiner_points < 0 || steiner_points > 64)
    throw InvalidInput("band polyline: steiner_points must be in 0..64, got " + std::to_string(steiner_points));
  if (max_flips < 0) throw InvalidInput("band polyline: max_flips must not be negative");
  if (polyline.empty()) throw InvalidInput("band polyline: the polyline is empty");
  if (!polyline.front().vertex.is_valid() || !polyline.back().vertex.is_valid() ||
      !is_live(mesh, polyline.front().vertex) || !is_live(mesh, polyline.back().vertex))
    throw InvalidInput("band polyline: the polyline must start and end at live mesh vertices");
  for (const PathPoint& p : polyline) {
    if (!p.vertex.is_valid() && !(p.halfedge.is_valid() && p.halfedge.idx() < static_cast<int>(mesh.n_halfedges())))
      throw InvalidInput("band polyline: a point is neither a vertex nor on a valid halfedge");
  }
  if (band_vertices) *band_vertices = 0;
  if (converged) *converged = true;
  // Through a pinched vertex: each piece between twin steps on its own.
  const TwinRing twins(mesh);
  std::vector<PathPoint> joined;
  const bool split = for_each_piece(
      polyline.size(), [&](size_t i) { return twins_of_each_other(twins, polyline[i].vertex, polyline[i + 1].vertex); },
      [&](size_t first, size_t last) {
        const std::vector<PathPoint> piece(polyline.begin() + static_cast<long>(first),
                                           polyline.begin() + static_cast<long>(last) + 1);
        bool done = true;
        size_t band = 0;
        const std::vector<PathPoint> out =
            band_polyline(mesh, piece, band_radius, steiner_points, max_flips, &done, &band);
        joined.insert(joined.end(), out.begin(), out.end());
        if (converged) *converged = *converged && done;
        if (band_vertices) *band_vertices += band;
      });
  if (split) return joined;
  const VertexHandle s = polyline.front().vertex, t = polyline.back().vertex;
  if (s == t || polyline.size() < 3) return polyline;
  BandSearch band(mesh);
  std::vector<FaceHandle> strip;
  const bool found = band.corridor(polyline, band_radius, steiner_points, strip);
  if (band_vertices) *band_vertices = band.band_vertices();
  if (!found) return polyline;
  bool done = false;
  auto out = band.straightener().straighten(std::move(strip), s, t, max_flips, &done);
  if (!(polyline_length(out) < polyline_length(polyline))) return polyline;
  if (converged) *converged = done;
  return out;
}

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
  // Through a pinched vertex: each piece between twin steps on its own (the point is on the path).
  const TwinRing twins(mesh);
  std::vector<PathPoint> joined;
  if (converged) *converged = true;
  const bool split = for_each_piece(
      chain.size(), [&](size_t i) { return twins_of_each_other(twins, chain[i], chain[i + 1]); },
      [&](size_t first, size_t last) {
        const std::vector<VertexHandle> piece(chain.begin() + static_cast<long>(first),
                                              chain.begin() + static_cast<long>(last) + 1);
        bool done = true;
        const std::vector<PathPoint> out = st.run(piece, max_flips, &done);
        joined.insert(joined.end(), out.begin(), out.end());
        if (converged) *converged = *converged && done;
      });
  if (split) return joined;
  return st.run(chain, max_flips, converged);
}

std::vector<SurfacePoint> surface_points(const std::vector<PathPoint>& polyline) {
  std::vector<SurfacePoint> out;
  out.reserve(polyline.size());
  for (const PathPoint& p : polyline) out.push_back(p.location);
  return out;
}

double polyline_length(const std::vector<PathPoint>& points) {
  double sum = 0;
  for (size_t i = 1; i < points.size(); ++i) sum += (points[i].position - points[i - 1].position).norm();
  return sum;
}

}  // namespace edgefront
