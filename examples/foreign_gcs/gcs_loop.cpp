#include "gcs_loop.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <optional>
#include <random>
#include <stdexcept>

#include "twist/arrays.h"
#include "twist/repair_session.h"

namespace foreign {

namespace {

Point sub(const Point& a, const Point& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(const Point& a, const Point& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double dist2(const Point& a, const Point& b) { const Point d = sub(a, b); return dot(d, d); }
Point cross(const Point& a, const Point& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

/// Nearest mesh vertex to a sample: a uniform grid over the cloud's box (cells about 1.5 mean
/// edges wide, rebuilt when the mesh has grown by half), searched in shells of cells; vertices
/// outside the box sit in a list that every query checks. Ties: lowest index.
class VertexGrid {
 public:
  void build(const HostMesh& m, const Point& lo, const Point& hi, double cell) {
    lo_ = lo;
    const double extent = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2], 1e-12});
    h_ = std::max(cell, extent / 200.0);
    for (size_t k = 0; k < 3; ++k) n_[k] = std::max(1, static_cast<int>(std::ceil((hi[k] - lo[k]) / h_)));
    cells_.assign(static_cast<size_t>(n_[0]) * static_cast<size_t>(n_[1]) * static_cast<size_t>(n_[2]), {});
    outside_.clear();
    where_.assign(m.vertex_slots(), kNone);
    for (size_t v = 0; v < m.vertex_slots(); ++v)
      if (m.alive[v] && !m.vfaces[v].empty()) insert(static_cast<int>(v), m.pos[v]);
    built_for_ = m.live_vertices();
  }
  size_t built_for() const { return built_for_; }

  void insert(int v, const Point& p) {
    if (where_.size() <= static_cast<size_t>(v)) where_.resize(2 * static_cast<size_t>(v) + 16, kNone);
    const long c = cell_of(p);
    where_[static_cast<size_t>(v)] = c;
    (c == kOutside ? outside_ : cells_[static_cast<size_t>(c)]).push_back(v);
  }
  void erase(int v) {
    if (static_cast<size_t>(v) >= where_.size() || where_[static_cast<size_t>(v)] == kNone) return;
    const long c = where_[static_cast<size_t>(v)];
    std::vector<int>& l = c == kOutside ? outside_ : cells_[static_cast<size_t>(c)];
    l.erase(std::find(l.begin(), l.end(), v));
    where_[static_cast<size_t>(v)] = kNone;
  }
  void move(int v, const Point& p) {
    const long c = cell_of(p);
    if (static_cast<size_t>(v) < where_.size() && where_[static_cast<size_t>(v)] == c) return;
    erase(v);
    insert(v, p);
  }
  bool contains(int v) const { return static_cast<size_t>(v) < where_.size() && where_[static_cast<size_t>(v)] != kNone; }

  /// The two nearest vertices (-1 when fewer exist).
  std::array<int, 2> nearest2(const HostMesh& m, const Point& q, bool want_second) const {
    std::array<int, 2> best{-1, -1};
    std::array<double, 2> bd{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
    auto offer = [&](int v) {
      const double d = dist2(m.pos[static_cast<size_t>(v)], q);
      if (d < bd[0] || (d == bd[0] && v < best[0])) {
        best[1] = best[0];
        bd[1] = bd[0];
        best[0] = v;
        bd[0] = d;
      } else if (d < bd[1] || (d == bd[1] && v < best[1])) {
        best[1] = v;
        bd[1] = d;
      }
    };
    for (int v : outside_) offer(v);
    int c[3];
    for (size_t k = 0; k < 3; ++k) c[k] = std::clamp(static_cast<int>(std::floor((q[k] - lo_[k]) / h_)), 0, n_[k] - 1);
    const int kmax = std::max({n_[0], n_[1], n_[2]});
    for (int k = 0; k <= kmax; ++k) {
      for (int dz = -k; dz <= k; ++dz) {
        const int z = c[2] + dz;
        if (z < 0 || z >= n_[2]) continue;
        for (int dy = -k; dy <= k; ++dy) {
          const int y = c[1] + dy;
          if (y < 0 || y >= n_[1]) continue;
          const bool full = std::abs(dz) == k || std::abs(dy) == k;
          for (int dx = -k; dx <= k; dx += (full || k == 0) ? 1 : 2 * k) {
            const int x = c[0] + dx;
            if (x < 0 || x >= n_[0]) continue;
            for (int v : cells_[index(x, y, z)]) offer(v);
          }
        }
      }
      const double r = static_cast<double>(k) * h_;
      if (bd[want_second ? 1 : 0] <= r * r) break;
    }
    return best;
  }

 private:
  static constexpr long kNone = -2, kOutside = -1;
  size_t index(int x, int y, int z) const {
    return (static_cast<size_t>(z) * static_cast<size_t>(n_[1]) + static_cast<size_t>(y)) * static_cast<size_t>(n_[0]) +
           static_cast<size_t>(x);
  }
  long cell_of(const Point& p) const {
    int c[3];
    for (size_t k = 0; k < 3; ++k) {
      const double t = std::floor((p[k] - lo_[k]) / h_);
      if (!(t >= 0 && t < n_[k])) return kOutside;
      c[k] = static_cast<int>(t);
    }
    return static_cast<long>(index(c[0], c[1], c[2]));
  }
  Point lo_{0, 0, 0};
  double h_ = 1;
  int n_[3] = {1, 1, 1};
  std::vector<std::vector<int>> cells_;
  std::vector<int> outside_;
  std::vector<long> where_;
  size_t built_for_ = 0;
};

/// The third corner of face t, which holds the directed edge p -> q; -1 when it does not.
int third_after(const Tri& t, int p, int q) {
  for (size_t k = 0; k < 3; ++k)
    if (t[k] == p && t[(k + 1) % 3] == q) return t[(k + 2) % 3];
  return -1;
}

class Loop {
 public:
  Loop(const Cloud& cloud, const LoopOptions& o) : cloud_(cloud), o_(o), rng_(o.seed), probe_rng_(o.seed ^ 0x9e3779b97f4a7c15ULL) {}

  LoopStats run(std::vector<Point>& out_v, std::vector<Tri>& out_f) {
    const auto t0 = std::chrono::steady_clock::now();
    init();
    const size_t cap = 8 * o_.target_vertices * o_.lambda;  // a closed run needs about 2 x target x lambda
    while (m_.live_vertices() < o_.target_vertices) {
      if (stats_.basic_steps >= cap) {
        stats_.step_limit = true;
        break;
      }
      run_batch();
    }
    if (o_.twist) {
      // The whole mesh once more, with the global orientation.
      tell_session();
      const auto s0 = std::chrono::steady_clock::now();
      const twist::EditRecord r = session_->finish();
      stats_.seconds_session += seconds_since(s0);
      replay(r);
    }
    stats_.seconds_loop = seconds_since(t0);
    compact(out_v, out_f);
    return stats_;
  }

 private:
  static double seconds_since(std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
  }

  void init() {
    if (cloud_.points.size() < 4) throw std::runtime_error("the cloud has fewer than 4 points");
    lo_ = hi_ = cloud_.points[0];
    for (const Point& p : cloud_.points)
      for (size_t k = 0; k < 3; ++k) {
        lo_[k] = std::min(lo_[k], p[k]);
        hi_[k] = std::max(hi_[k], p[k]);
      }
    const double diag = std::sqrt(dist2(lo_, hi_));
    if (!(diag > 0)) throw std::runtime_error("all points coincide");
    for (size_t k = 0; k < 3; ++k) {  // the grid's box: the cloud's, padded
      lo_[k] -= 0.05 * diag;
      hi_[k] += 0.05 * diag;
    }
    // An octahedron inside the cloud's box (half its extent per axis, at least 1% of the diagonal).
    Point c, r;
    for (size_t k = 0; k < 3; ++k) {
      c[k] = 0.5 * (lo_[k] + hi_[k]);
      r[k] = std::max(0.25 * (hi_[k] - lo_[k]), 0.01 * diag);
    }
    const Point v[6] = {{c[0] + r[0], c[1], c[2]}, {c[0] - r[0], c[1], c[2]}, {c[0], c[1] + r[1], c[2]},
                        {c[0], c[1] - r[1], c[2]}, {c[0], c[1], c[2] + r[2]}, {c[0], c[1], c[2] - r[2]}};
    for (const Point& p : v) add_vertex(p, 0.0);
    for (const Tri& t : {Tri{0, 2, 4}, Tri{2, 1, 4}, Tri{1, 3, 4}, Tri{3, 0, 4}, Tri{2, 0, 5}, Tri{1, 2, 5}, Tri{3, 1, 5},
                         Tri{0, 3, 5}})
      m_.add_face(t);

    // The session mirrors the host from its arrays; from here on it is told only what changes.
    std::vector<double> V;
    std::vector<int> F;
    for (const Point& p : m_.pos) V.insert(V.end(), p.begin(), p.end());
    for (const Tri& t : m_.faces) F.insert(F.end(), t.begin(), t.end());
    twist::SessionOptions so;
    // As EdgeFront's own GCS hook sets it (gcs/twist_operation.h): cut scattered regions too, and
    // at the end peel the flaps the cuts left and drop small turned-over patches.
    so.repair = twist::RepairOptions::in_loop();
    if (!cloud_.normals.empty()) {
      std::vector<double> P, N;
      for (const Point& p : cloud_.points) P.insert(P.end(), p.begin(), p.end());
      for (const Point& n : cloud_.normals) N.insert(N.end(), n.begin(), n.end());
      reference_ = std::make_unique<twist::ReferenceNormals>(twist::reference_from_arrays(P, N));
      so.repair.detect.reference = reference_.get();  // outlives the session (declared before it)
    }
    so.max_retwists = o_.max_retwists;
    // The border operations this loop lacks, done by the session and replayed like the rest.
    so.heal.enabled = o_.heal;
    so.heal.max_gap_edges = o_.heal_gap_edges;
    so.heal.max_hole_vertices = o_.heal_hole_vertices;
    so.heal.grow_rows = o_.heal_grow_rows;
    so.heal.min_piece_share = o_.heal_min_piece_share;
    session_ = std::make_unique<twist::RepairSession>(V, F, so);
    replay(session_->initial_record());  // empty for the octahedron
    m_.dirty.clear();
    rebuild_grid();
  }

  int add_vertex(const Point& p, double tau) {
    const int v = m_.add_vertex(p);
    tau_.push_back(tau);
    last_win_.push_back(stats_.basic_steps);
    return v;
  }

  void rebuild_grid() { grid_.build(m_, lo_, hi_, 1.5 * std::max(m_.mean_edge_length(), 1e-12)); }

  // -- The basic step -------------------------------------------------------------------------
  void basic_step() {
    const Point& s = cloud_.points[static_cast<size_t>(rng_() % cloud_.points.size())];
    const int w = grid_.nearest2(m_, s, false)[0];
    if (w < 0) throw std::runtime_error("no mesh vertex left to win a sample");
    Point& x = m_.pos[static_cast<size_t>(w)];
    for (size_t k = 0; k < 3; ++k) x[k] += o_.alpha_winner * (s[k] - x[k]);
    grid_.move(w, x);
    m_.dirty.mark_vertex(w);
    // The winner's ring: 5 rounds of tangential Laplacian smoothing (the paper's rule; the ring is
    // not pulled toward the sample).
    neighbours(w, ring_w_);
    for (int round = 0; round < 5; ++round)
      for (int u : ring_w_) {
        neighbours(u, ring_u_);
        if (ring_u_.empty()) continue;
        Point mean{0, 0, 0};
        for (int z : ring_u_)
          for (size_t k = 0; k < 3; ++k) mean[k] += m_.pos[static_cast<size_t>(z)][k];
        Point& p = m_.pos[static_cast<size_t>(u)];
        Point L;
        for (size_t k = 0; k < 3; ++k) L[k] = mean[k] / static_cast<double>(ring_u_.size()) - p[k];
        const Point n = m_.vertex_normal(u);
        const double ln = dot(L, n);
        for (size_t k = 0; k < 3; ++k) p[k] += o_.alpha_neighbour * (L[k] - ln * n[k]);
        grid_.move(u, p);
        m_.dirty.mark_vertex(u);
      }
    // Signal counter with the global decay kept in one scale (tau_ = tau / scale).
    tau_[static_cast<size_t>(w)] += 1.0 / scale_;
    last_win_[static_cast<size_t>(w)] = stats_.basic_steps;
    scale_ *= std::pow(0.5, 1.0 / (o_.half_life * static_cast<double>(m_.live_vertices())));
    if (scale_ < 1e-150) {
      for (double& t : tau_) t *= scale_;
      scale_ = 1;
    }
    ++stats_.basic_steps;
  }

  void neighbours(int v, std::vector<int>& out) const {
    out.clear();
    for (int f : m_.vfaces[static_cast<size_t>(v)])
      for (int u : m_.faces[static_cast<size_t>(f)])
        if (u != v && std::find(out.begin(), out.end(), u) == out.end()) out.push_back(u);
  }

  // -- Vertex split ---------------------------------------------------------------------------
  /// The most active vertex that can be split is split (a border vertex whose fan has no interior
  /// edge cannot: its counter is reset and the next one is taken).
  void split_most_active() {
    for (int attempt = 0; attempt < 16; ++attempt)
      if (split_once()) return;
  }

  bool split_once() {
    int v = -1;
    for (size_t i = 0; i < m_.vertex_slots(); ++i)
      if (m_.alive[i] && !m_.vfaces[i].empty() && (v < 0 || tau_[i] > tau_[static_cast<size_t>(v)])) v = static_cast<int>(i);
    if (v < 0) return true;
    bool closed = false;
    if (!m_.ring(v, ring_w_, closed) || (!closed && ring_w_.size() < 3)) {
      tau_[static_cast<size_t>(v)] = 0;  // not a single fan (never expected), or no interior edge
      return false;
    }
    const size_t k = ring_w_.size();
    // At a border vertex (an open fan ring[0] .. ring[k-1]), only its interior edges (ring[1] ..
    // ring[k-2]) are split: a border vertex wins the samples beyond the border, and splitting its
    // border edges would only lengthen the border. A fan of one face has none: no split this time.
    size_t j = closed ? 0 : 1;  // the longest edge (v, ring[j])
    double longest = -1;
    for (size_t i = j; i < (closed ? k : k - 1); ++i) {
      const double d = dist2(m_.pos[static_cast<size_t>(v)], m_.pos[static_cast<size_t>(ring_w_[i])]);
      if (d > longest) {
        longest = d;
        j = i;
      }
    }
    const int u = ring_w_[j];
    Point mid;
    for (size_t c = 0; c < 3; ++c) mid[c] = 0.5 * (m_.pos[static_cast<size_t>(v)][c] + m_.pos[static_cast<size_t>(u)][c]);
    const double half = 0.5 * tau_[static_cast<size_t>(v)];
    tau_[static_cast<size_t>(v)] = half;
    if (closed && k >= 4) {
      // The paper's vertex split: the star of v is cut in two by the edges to a = ring[j - q] and
      // b = ring[j + q]; the half around the longest edge moves to the new vertex v' at its
      // midpoint, and two faces (v, a, v'), (v, v', b) close the gap.
      const size_t q = std::max<size_t>(1, std::min((k + 2) / 4, (k - 1) / 2));
      const int a = ring_w_[(j + k - q) % k], b = ring_w_[(j + q) % k];
      const int vn = add_vertex(mid, half);
      for (size_t i = 0; i < 2 * q; ++i) {
        const int n0 = ring_w_[(j + k - q + i) % k], n1 = ring_w_[(j + k - q + i + 1) % k];
        const int f = find_face(v, n0, n1);
        if (f < 0) throw std::logic_error("vertex split: fan face missing");
        m_.set_face(f, {vn, n0, n1});
      }
      m_.add_face({v, a, vn});
      m_.add_face({v, vn, b});
      grid_.insert(vn, mid);
      ++stats_.splits;
      return true;
    } else {
      // At a border (an interior edge) or at a vertex of valence 3: split the longest edge itself.
      const int vn = add_vertex(mid, half);
      for (const auto& [p, q] : {std::pair<int, int>{v, u}, std::pair<int, int>{u, v}}) {
        int f = -1, x = -1;
        for (int g : m_.vfaces[static_cast<size_t>(v)])
          if (g != vn && (x = third_after(m_.faces[static_cast<size_t>(g)], p, q)) >= 0) {
            f = g;
            break;
          }
        if (f < 0) continue;
        m_.set_face(f, {p, vn, x});
        m_.add_face({vn, q, x});
      }
      grid_.insert(vn, mid);
      ++stats_.edge_splits;
    }
    return true;
  }

  /// The live face holding v -> a -> b in this cyclic order, -1 for none.
  int find_face(int v, int a, int b) const {
    for (int f : m_.vfaces[static_cast<size_t>(v)])
      if (third_after(m_.faces[static_cast<size_t>(f)], v, a) == b) return f;
    return -1;
  }

  // -- Collapse of inactive vertices ------------------------------------------------------------
  /// Every vertex that has not won for mu * |V| basic steps is removed by the half-edge collapse
  /// into the neighbour that gives the most regular valences (the paper's criterion), when the
  /// link condition holds and no face turns over. Interior vertices only.
  void collapse_inactive() {
    const double idle = o_.mu * static_cast<double>(m_.live_vertices());
    const size_t known = session_->vertex_slots();
    for (size_t i = 0; i < known && i < m_.vertex_slots(); ++i) {
      if (!m_.alive[i] || m_.vfaces[i].empty() || m_.live_vertices() <= 6) continue;
      if (static_cast<double>(stats_.basic_steps - last_win_[i]) <= idle) continue;
      if (try_collapse(static_cast<int>(i))) ++stats_.collapses;
    }
  }

  size_t valence(int v) {
    neighbours(v, tmp_);
    return tmp_.size();
  }

  bool try_collapse(int v) {
    bool closed = false;
    std::vector<int> ring;
    if (!m_.ring(v, ring, closed) || !closed || ring.size() < 3) return false;
    const size_t k = ring.size();
    int best = -1;
    double best_score = std::numeric_limits<double>::infinity();
    std::vector<int> nu;
    for (size_t j = 0; j < k; ++j) {
      const int u = ring[j], x = ring[(j + k - 1) % k], y = ring[(j + 1) % k];
      neighbours(u, nu);
      size_t common = 0;
      for (int z : ring)
        if (std::find(nu.begin(), nu.end(), z) != nu.end()) ++common;
      if (common != 2) continue;  // link condition
      const size_t vx = valence(x), vy = valence(y);
      if (vx <= 3 || vy <= 3) continue;
      // No face of v may turn over or degenerate when v moves onto u.
      bool ok = true;
      for (int f : m_.vfaces[static_cast<size_t>(v)]) {
        const Tri& t = m_.faces[static_cast<size_t>(f)];
        if (std::find(t.begin(), t.end(), u) != t.end()) continue;
        const Point before = m_.face_cross(f);
        Point pts[3];
        for (size_t c = 0; c < 3; ++c) pts[c] = t[c] == v ? m_.pos[static_cast<size_t>(u)] : m_.pos[static_cast<size_t>(t[c])];
        const Point after = cross(sub(pts[1], pts[0]), sub(pts[2], pts[0]));
        if (!(dot(before, after) > 0.1 * std::sqrt(dot(before, before) * dot(after, after)))) ok = false;
      }
      if (!ok) continue;
      const double a = static_cast<double>(k + valence(u)) - 10.0;
      const double score = a * a + (static_cast<double>(vx) - 7) * (static_cast<double>(vx) - 7) +
                           (static_cast<double>(vy) - 7) * (static_cast<double>(vy) - 7);
      if (score < best_score) {
        best_score = score;
        best = u;
      }
    }
    if (best < 0) return false;
    const std::vector<int> fan = m_.vfaces[static_cast<size_t>(v)];
    for (int f : fan) {
      Tri t = m_.faces[static_cast<size_t>(f)];
      if (std::find(t.begin(), t.end(), best) != t.end()) {
        m_.remove_face(f);
        continue;
      }
      for (int& c : t)
        if (c == v) c = best;
      m_.set_face(f, t);
    }
    grid_.erase(v);
    m_.remove_vertex(v);
    return true;
  }

  // -- The batch and the session ----------------------------------------------------------------
  void run_batch() {
    collapse_inactive();  // first: it only touches what the session knows already
    for (size_t split = 0; split < o_.batch_splits && m_.live_vertices() < o_.target_vertices; ++split) {
      for (size_t s = 0; s < o_.lambda; ++s) basic_step();
      split_most_active();
    }
    tell_session();
    const auto s0 = std::chrono::steady_clock::now();
    twist::EditRecord r;
    if (o_.twist && m_.live_vertices() >= o_.min_repair_vertices) {
      r = session_->repair(m_.mean_edge_length());
      ++stats_.repair_calls;
    } else {
      r = session_->sync();  // the mirror follows; pinched vertices (none expected) would be split
    }
    stats_.seconds_session += seconds_since(s0);
    replay(r);
    probe();
    ++stats_.batches;
    if (m_.live_vertices() > grid_.built_for() * 3 / 2 + 8) rebuild_grid();
    if (o_.verbose)
      std::fprintf(stderr, "batch %zu: %zu steps, %zu vertices, %zu faces; record: +%zu vertices, %zu flipped, %zu removed, +%zu faces; far probes %zu/%zu\n",
                   stats_.batches, stats_.basic_steps, m_.live_vertices(), m_.live_faces(), r.vertices_added.size(),
                   r.faces_flipped.size(), r.faces_removed.size(), r.faces_added.size(), stats_.probes_far, stats_.probes);
  }

  /// The host's changes since the last answer, in its own indices.
  void tell_session() {
    DirtySet& d = m_.dirty;
    for (int f : d.faces) {
      if (m_.face_live(f))
        session_->set_face(f, m_.faces[static_cast<size_t>(f)]);
      else
        session_->remove_face(f);
    }
    for (int v : d.removed_vertices) session_->remove_vertex(v);
    for (int v : d.vertices)
      if (m_.alive[static_cast<size_t>(v)]) session_->set_vertex(v, m_.pos[static_cast<size_t>(v)]);
    d.clear();
  }

  /// Replays a record on the host mesh and its own per-vertex data (copies inherit the original's
  /// counter and last win), and keeps the grid in step.
  void replay(const twist::EditRecord& r) {
    if (r.empty()) return;
    const size_t before = m_.vertex_slots();
    m_.replay(r, [&](int copy, int original) {
      tau_.push_back(original >= 0 ? tau_[static_cast<size_t>(original)] : 0.0);
      last_win_.push_back(original >= 0 ? last_win_[static_cast<size_t>(original)] : stats_.basic_steps);
      (void)copy;
    });
    stats_.record_vertices_added += r.vertices_added.size();
    stats_.record_faces_flipped += r.faces_flipped.size();
    stats_.record_faces_removed += r.faces_removed.size();
    stats_.record_corners_replaced += r.corners_replaced.size();
    stats_.record_faces_added += r.faces_added.size();
    stats_.heal_strips += session_->stats().heal.strips;
    stats_.heal_holes += session_->stats().heal.holes;
    stats_.heal_grown += session_->stats().heal.grown;
    for (size_t v = before; v < m_.vertex_slots(); ++v) grid_.insert(static_cast<int>(v), m_.pos[v]);
    for (const twist::VertexMoved& mv : r.vertices_moved) grid_.move(mv.vertex, m_.pos[static_cast<size_t>(mv.vertex)]);
    // Vertices left without faces (deleted by the repair, or isolated by its removals) leave the
    // grid; the ones the session still holds are removed there with the next batch.
    std::vector<int> touched;
    for (int v : r.vertices_removed) touched.push_back(v);
    for (size_t v = 0; v < m_.vertex_slots(); ++v)
      if (m_.alive[v] && m_.vfaces[v].empty()) touched.push_back(static_cast<int>(v));
    std::sort(touched.begin(), touched.end());
    touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
    for (int v : touched) {
      grid_.erase(v);
      if (m_.alive[static_cast<size_t>(v)] && m_.vfaces[static_cast<size_t>(v)].empty()) m_.remove_vertex(v);
    }
    // The record's own deletions are known to the session: not to be sent back.
    std::vector<int>& rv = m_.dirty.removed_vertices;
    rv.erase(std::remove_if(rv.begin(), rv.end(),
                            [&](int v) { return std::binary_search(r.vertices_removed.begin(), r.vertices_removed.end(), v); }),
             rv.end());
  }

  /// "Is this point far along the surface?": for a few random samples, the two mesh vertices
  /// nearest to it, and a bounded MDF query between them through the session (bound: 3 mean
  /// edges). Near in space but far along the surface means the sample lies between two layers of
  /// the mesh (a fold, or the two walls of a thin shell). A per-batch check, reported; it does not
  /// steer the loop (a separate random stream: the mesh is the same with or without it).
  void probe() {
    if (o_.probes_per_batch == 0) return;
    const double bound = 3.0 * m_.mean_edge_length();
    for (size_t i = 0; i < o_.probes_per_batch; ++i) {
      const Point& s = cloud_.points[static_cast<size_t>(probe_rng_() % cloud_.points.size())];
      const std::array<int, 2> w = grid_.nearest2(m_, s, true);
      if (w[1] < 0) return;
      ++stats_.probes;
      if (!session_->distance_between(w[0], w[1], bound)) ++stats_.probes_far;
    }
  }

  /// Live faces, and the vertices they use, renumbered in index order.
  void compact(std::vector<Point>& out_v, std::vector<Tri>& out_f) const {
    std::vector<int> id(m_.vertex_slots(), -1);
    out_v.clear();
    out_f.clear();
    for (size_t v = 0; v < m_.vertex_slots(); ++v)
      if (m_.alive[v] && !m_.vfaces[v].empty()) {
        id[v] = static_cast<int>(out_v.size());
        out_v.push_back(m_.pos[v]);
      }
    for (const Tri& t : m_.faces)
      if (t[0] >= 0) out_f.push_back({id[static_cast<size_t>(t[0])], id[static_cast<size_t>(t[1])], id[static_cast<size_t>(t[2])]});
  }

  const Cloud& cloud_;
  LoopOptions o_;
  std::mt19937_64 rng_, probe_rng_;
  HostMesh m_;
  std::vector<double> tau_;
  std::vector<size_t> last_win_;
  double scale_ = 1;
  Point lo_{}, hi_{};
  VertexGrid grid_;
  std::unique_ptr<twist::ReferenceNormals> reference_;  // before the session: it outlives it
  std::unique_ptr<twist::RepairSession> session_;
  std::vector<int> ring_w_, ring_u_, tmp_;
  LoopStats stats_;
};

}  // namespace

LoopStats run_gcs(const Cloud& cloud, const LoopOptions& options, std::vector<Point>& out_vertices,
                  std::vector<Tri>& out_faces) {
  if (options.target_vertices < 6) throw std::runtime_error("--vertices must be at least 6");
  if (!cloud.normals.empty() && cloud.normals.size() != cloud.points.size())
    throw std::runtime_error("normals do not match the points");
  if (options.heal && cloud.normals.empty())
    throw std::runtime_error("--heal needs oriented points (x y z nx ny nz): the healed faces must lie on the reference cloud");
  Loop loop(cloud, options);
  return loop.run(out_vertices, out_faces);
}

}  // namespace foreign
