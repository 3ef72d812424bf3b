// gcs::Reconstructor, the growth: the basic step (winner search, winner move, tangential smoothing
// of its ring, signal counters), the vertex split with its valence flips, the collapse of inactive
// vertices and the spatial renumbering. This is the hot path: what a basic step calls is defined
// here or inline in detail/reconstructor_impl.h.
#include <algorithm>
#include <cmath>
#include <utility>

#include "detail/double_layer.h"
#include "detail/reconstructor_impl.h"
#include "edgefront/error.h"

namespace gcs {

namespace {

// The valence flips after a split (improve_valences) run at most this many passes over the edges
// around the two vertices, and flip only edges whose two faces' unit normals have at least this
// cosine (about 37 degrees: creases stay).
constexpr int kValencePasses = 3;
constexpr double kValenceFlipMinCos = 0.8;
// A collapse is refused when it turns a remaining face by more than about 78 degrees (cosine below
// this) or leaves it degenerate (twice its area below this share of the squared bounding-box
// diagonal).
constexpr double kCollapseMinFaceCos = 0.2;
constexpr double kCollapseMinArea = 1e-14;

}  // namespace

void Reconstructor::Impl::ensure_sizes() {
  const size_t nv = mesh.n_vertices(), nf = mesh.n_faces();
  if (tau.size() < nv) {
    tau.resize(nv, -1.0);  // -1: not in `order`
    last_win.resize(nv, steps);
    vstamp.resize(nv, clock);
    grid.resize(nv);
    neighbors.resize(nv);
  }
  if (fstamp.size() < nf) fstamp.resize(nf, clock);
}

void Reconstructor::Impl::renormalize() {
  for (size_t v = 0; v < tau.size(); ++v)
    if (tau[v] >= 0) tau[v] *= scale;
  order.scale_all(scale);
  scale = 1.0;
}

void Reconstructor::Impl::stamp_ring(VertexHandle v) {
  stamp(v);
  for (auto u : mesh.vv_range(v)) stamp(u);
}

double Reconstructor::Impl::mean_adjacent_edge_length(VertexHandle v) const {
  double s = 0;
  int k = 0;
  for (auto h : mesh.voh_range(v)) {
    s += mesh.calc_edge_length(h);
    ++k;
  }
  return k ? s / k : 0.0;
}

void Reconstructor::Impl::basic_step() {
  // The samples are drawn one step ahead (the same sequence) so that the next one's point and
  // normal can be fetched from memory while this step runs (a large cloud is far bigger than
  // the caches).
  if (next_sample == kNoSample) next_sample = static_cast<size_t>(draw_mod(rng()));
  const size_t si = next_sample;
  next_sample = static_cast<size_t>(draw_mod(rng()));
  __builtin_prefetch(&draw[next_sample]);
  __builtin_prefetch(reinterpret_cast<const char*>(&draw[next_sample]) + sizeof(DrawSample) - 1);
  const Vec3& s = draw[si].point;
  int wi = grid.nearest(s);
  EF_CHECK(wi >= 0, "the mesh has no vertex");
  const bool smooth = opt.growth.neighbor_rate > 0 && opt.growth.smoothing_iterations > 0;
  // Facing the sample's side once the mesh hugs the cloud (detail/double_layer.h): the nearest
  // vertex wins when its normal agrees with the sample's (the normal summed over the ring just
  // gathered, as detail::vertex_normal_sum would), otherwise detail::oriented_nearest_after picks.
  const bool facing = oriented && live >= opt.topology.min_vertices;
  if (smooth || facing) gather_ring(VertexHandle(wi));
  if (facing && !((ring_normal_sum(wi) | draw[si].normal) > 0)) {
    // Skipping unfaced samples (ExperimentalOptions::skip_unfaced_samples), the search goes wider:
    // the missing layer's border vertices must be found to grow it back.
    const bool skip = opt.experimental.skip_unfaced_samples && cloud.has_normals();
    const int other = detail::oriented_nearest_after(mesh, grid, s, draw[si].normal, wi, skip ? 32 : 8,
                                                     (skip ? 4 : 2) * grid.cell_size());
    if (other == wi && skip) {  // no vertex nearby faces the sample's side
      end_step();
      return;
    }
    if (other != wi) {
      wi = other;
      gather_ring(VertexHandle(wi));
    }
  }
  const VertexHandle w(wi);
  mesh.point(w) += opt.growth.winner_rate * (s - mesh.point(w));
  grid.move(wi, mesh.point(w));
  stamp(w);
  if (smooth) {
    // The passes update the mesh positions in place (member by member, as in the paper's loop).
    Vec3* const pos = &mesh.point(VertexHandle(0));
    for (int it = 0; it < opt.growth.smoothing_iterations; ++it) {
      if (it == 0) {
        for (RingCache::Member& m : ring.members) smooth_member_first(pos, m);
      } else {
        for (const RingCache::Member& m : ring.members) smooth_member(pos, m);
      }
    }
    for (const RingCache::Member& m : ring.members) {
      grid.move(m.vid, pos[m.vid]);
      vstamp[static_cast<size_t>(m.vid)] = clock;
    }
  }
  tau[wi] += 1.0 / scale;
  order.set(wi, tau[wi]);
  last_win[wi] = steps;
  end_step();
}

template <class F>
void Reconstructor::Impl::with_ring(VertexHandle v, WalkedRing& scratch, F&& f) {
  if (const detail::NeighborCache::Line* l = neighbors.get(mesh, v)) {
    f(static_cast<int>(l->count), l->nb, [l](int e) { return l->has_face(e); });
    return;
  }
  scratch.nb.clear();
  scratch.face.clear();
  for (auto h : mesh.voh_range(v)) {
    scratch.nb.push_back(mesh.to_vertex_handle(h).idx());
    scratch.face.push_back(mesh.face_handle(h).is_valid() ? 1 : 0);
  }
  const char* face = scratch.face.data();
  f(static_cast<int>(scratch.nb.size()), scratch.nb.data(), [face](int e) { return face[e] != 0; });
}

void Reconstructor::Impl::gather_ring(VertexHandle w) {
  ring.members.clear();
  with_ring(w, walked_winner, [&](int count, const int* wnb, auto winner_face) {
    // The members' lines and positions are fetched together (independent misses overlap).
    for (int i = 0; i < count; ++i) {
      neighbors.prefetch(wnb[i]);
      __builtin_prefetch(&mesh.point(VertexHandle(wnb[i])));
    }
    int n = 0;  // entries used
    for (int i = 0; i < count; ++i) {
      RingCache::Member m{wnb[i], n, 0};
      m.winner_face = winner_face(i);
      // Around v, the face of outgoing halfedge e (v, a_e, b_e) is the face on the far side of
      // halfedge e - 1 in this clockwise order, so b_e = a_(e-1) (cyclically: the first entry's
      // is the last neighbour). At a border halfedge (no face) b_e = -1, and the border
      // neighbours are a_e and a_(e-1) (the end of the incoming border halfedge); with several
      // border halfedges, the last one counts.
      with_ring(VertexHandle(m.vid), walked_member, [&](int k, const int* nb, auto has_face) {
        if (static_cast<size_t>(n + k) > ring.entries.size()) ring.entries.resize(2 * ring.entries.size() + static_cast<size_t>(k) + 64);
        RingCache::Entry* const out = ring.entries.data() + n;
        int border_e = -1;
        for (int e = 0; e < k; ++e) {
          __builtin_prefetch(&mesh.point(VertexHandle(nb[e])));
          const bool f = has_face(e);
          if (!f) border_e = e;
          out[e] = {nb[e], f ? nb[e == 0 ? k - 1 : e - 1] : -1};
        }
        n += k;
        m.end = n;
        if (k > 0) m.inv_k = 1.0 / static_cast<double>(k);
        if (border_e >= 0) {
          m.border_a = nb[border_e];
          m.border_b = nb[border_e == 0 ? k - 1 : border_e - 1];
        }
      });
      ring.members.push_back(m);
    }
  });
}

Vec3 Reconstructor::Impl::ring_normal_sum(int wi) const {
  Vec3 n(0, 0, 0);
  const Vec3& x = mesh.point(VertexHandle(wi));
  const size_t k = ring.members.size();
  for (size_t i = 0; i < k; ++i) {
    if (!ring.members[i].winner_face) continue;
    const Vec3& a = mesh.point(VertexHandle(ring.members[i].vid));
    const Vec3& b = mesh.point(VertexHandle(ring.members[i == 0 ? k - 1 : i - 1].vid));
    n += (a - x) % (b - x);
  }
  return n;
}

void Reconstructor::Impl::smooth_member(Vec3* pos, const RingCache::Member& m) const {
  if (m.end <= m.begin) return;
  Vec3& x = pos[m.vid];
  const double x0 = x[0], x1 = x[1], x2 = x[2];
  double l0, l1, l2;
  if (m.border_a >= 0) {
    const Vec3& a = pos[m.border_a];
    const Vec3& b = pos[m.border_b];
    l0 = (a[0] + b[0]) * 0.5 - x0;
    l1 = (a[1] + b[1]) * 0.5 - x1;
    l2 = (a[2] + b[2]) * 0.5 - x2;
  } else {
    double s0 = 0, s1 = 0, s2 = 0;
    const RingCache::Entry* const entries = ring.entries.data();
    for (int e = m.begin; e < m.end; ++e) {
      const Vec3& a = pos[entries[e].a];
      s0 += a[0];
      s1 += a[1];
      s2 += a[2];
    }
    l0 = s0 * m.inv_k - x0;
    l1 = s1 * m.inv_k - x1;
    l2 = s2 * m.inv_k - x2;
  }
  const double d = (l0 * m.n0 + l1 * m.n1 + l2 * m.n2) * m.inv_nn;
  x[0] = x0 + opt.growth.neighbor_rate * (l0 - d * m.n0);
  x[1] = x1 + opt.growth.neighbor_rate * (l1 - d * m.n1);
  x[2] = x2 + opt.growth.neighbor_rate * (l2 - d * m.n2);
}

void Reconstructor::Impl::smooth_member_first(Vec3* pos, RingCache::Member& m) const {
  if (m.end <= m.begin) return;
  const double x0 = pos[m.vid][0], x1 = pos[m.vid][1], x2 = pos[m.vid][2];
  double n0 = 0, n1 = 0, n2 = 0;
  const RingCache::Entry* const entries = ring.entries.data();
  for (int e = m.begin; e < m.end; ++e) {
    const RingCache::Entry en = entries[e];
    if (en.b < 0) continue;
    const double u0 = pos[en.a][0] - x0, u1 = pos[en.a][1] - x1, u2 = pos[en.a][2] - x2;
    const double v0 = pos[en.b][0] - x0, v1 = pos[en.b][1] - x1, v2 = pos[en.b][2] - x2;
    n0 += u1 * v2 - u2 * v1;
    n1 += u2 * v0 - u0 * v2;
    n2 += u0 * v1 - u1 * v0;
  }
  const double nn = n0 * n0 + n1 * n1 + n2 * n2;
  const double inv_nn = nn > 0 ? 1.0 / nn : 0.0;
  // No usable normal (degenerate faces, or a square that overflows): the plain Laplacian.
  const bool usable = std::isfinite(inv_nn) && std::isfinite(nn);
  m.n0 = usable ? n0 : 0.0;
  m.n1 = usable ? n1 : 0.0;
  m.n2 = usable ? n2 : 0.0;
  m.inv_nn = usable ? inv_nn : 0.0;
  smooth_member(pos, m);
}

unsigned Reconstructor::Impl::valence_of(VertexHandle x) {
  const detail::NeighborCache::Line* l = neighbors.get(mesh, x);
  return l ? l->count : static_cast<unsigned>(mesh.valence(x));
}

bool Reconstructor::Impl::border_of(VertexHandle x) {
  const detail::NeighborCache::Line* l = neighbors.get(mesh, x);
  return l ? !(l->count > 0 && l->has_face(0)) : mesh.is_boundary(x);
}

bool Reconstructor::Impl::flip_geometry_ok(EdgeHandle e) const {
  const HalfedgeHandle h0 = mesh.halfedge_handle(e, 0), h1 = mesh.halfedge_handle(e, 1);
  const Vec3& p = mesh.point(mesh.from_vertex_handle(h0));
  const Vec3& q = mesh.point(mesh.to_vertex_handle(h0));
  const Vec3& r = mesh.point(mesh.to_vertex_handle(mesh.next_halfedge_handle(h0)));
  const Vec3& s = mesh.point(mesh.to_vertex_handle(mesh.next_halfedge_handle(h1)));
  const Vec3 n_old = face_normal_of(p, q, r).normalized() + face_normal_of(q, p, s).normalized();
  const Vec3 n1 = face_normal_of(p, s, r), n2 = face_normal_of(s, q, r);
  return (n1 | n_old) > 0 && (n2 | n_old) > 0 && n1.norm() > 0 && n2.norm() > 0;
}

bool Reconstructor::Impl::try_flip(HalfedgeHandle h) {
  const EdgeHandle e = mesh.edge_handle(h);
  if (mesh.is_boundary(e) || !mesh.is_flip_ok(e)) return false;
  const VertexHandle a = mesh.from_vertex_handle(h) , b = mesh.to_vertex_handle(h);
  // Neither end may drop below valence 3 (interior) / 2 (border).
  for (const VertexHandle x : {a, b}) {
    if (valence_of(x) <= (border_of(x) ? 2u : 3u)) return false;
  }
  if (!flip_geometry_ok(e)) return false;
  const VertexHandle r = mesh.to_vertex_handle(mesh.next_halfedge_handle(mesh.halfedge_handle(e, 0)));
  const VertexHandle s = mesh.to_vertex_handle(mesh.next_halfedge_handle(mesh.halfedge_handle(e, 1)));
  mesh.flip(e);
  for (const VertexHandle x : {a, b, r, s}) {
    stamp(x);
    neighbors.invalidate(x.idx());
  }
  return true;
}

void Reconstructor::Impl::improve_valences(VertexHandle v, VertexHandle m) {
  const auto dev = [&](VertexHandle x, int delta) {
    const int ideal = border_of(x) ? 4 : 6;
    const int d = static_cast<int>(valence_of(x)) + delta - ideal;
    return d * d;
  };
  std::vector<EdgeHandle> edges;
  for (int pass = 0; pass < kValencePasses; ++pass) {
    edges.clear();
    for (const VertexHandle c : {v, m}) {
      for (auto h : mesh.voh_range(c)) {
        for (auto g : mesh.voh_range(mesh.to_vertex_handle(h))) edges.push_back(mesh.edge_handle(g));
      }
    }
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    bool flipped = false;
    for (const EdgeHandle e : edges) {
      if (mesh.status(e).deleted() || mesh.is_boundary(e)) continue;
      const HalfedgeHandle h0 = mesh.halfedge_handle(e, 0), h1 = mesh.halfedge_handle(e, 1);
      const VertexHandle p = mesh.from_vertex_handle(h0), q = mesh.to_vertex_handle(h0);
      const VertexHandle r = mesh.to_vertex_handle(mesh.next_halfedge_handle(h0));
      const VertexHandle s = mesh.to_vertex_handle(mesh.next_halfedge_handle(h1));
      const int before = dev(p, 0) + dev(q, 0) + dev(r, 0) + dev(s, 0);
      const int after = dev(p, -1) + dev(q, -1) + dev(r, 1) + dev(s, 1);
      if (after >= before) continue;
      const Vec3 n0 = face_normal_of(mesh.point(p), mesh.point(q), mesh.point(r)).normalized();
      const Vec3 n1 = face_normal_of(mesh.point(q), mesh.point(p), mesh.point(s)).normalized();
      if ((n0 | n1) < kValenceFlipMinCos) continue;  // keep creases
      if (try_flip(h0)) flipped = true;
    }
    if (!flipped) break;
  }
}

void Reconstructor::Impl::split_most_active() {
  EF_CHECK(!order.empty(), "no vertex to split");
  const VertexHandle v(order.top());
  HalfedgeHandle longest;
  double best = -1;
  int best_to = std::numeric_limits<int>::max();
  for (auto h : mesh.voh_range(v)) {
    const double l = mesh.calc_edge_sqr_length(h);
    const int to = mesh.to_vertex_handle(h).idx();
    if (l > best || (l == best && to < best_to)) {
      best = l;
      best_to = to;
      longest = h;
    }
  }
  EF_CHECK(longest.is_valid(), "the most active vertex has no edge");
  const VertexHandle u = mesh.to_vertex_handle(longest);
  const Vec3 mid = (mesh.point(v) + mesh.point(u)) * 0.5;
  const VertexHandle m = mesh.split(mesh.edge_handle(longest), mid);
  ensure_sizes();
  neighbors.invalidate(m.idx());  // and its ring: v, u and the two opposite corners
  for (auto x : mesh.vv_range(m)) neighbors.invalidate(x.idx());
  // Walk equally both ways from the split edge: each flip moves one neighbour of v to m.
  bool left_ok = true, right_ok = true;
  for (bool left = true; (left_ok || right_ok) && valence_of(v) > valence_of(m) + 1; left = !left) {
    if (left && left_ok) {
      const HalfedgeHandle h = mesh.find_halfedge(v, m);
      left_ok = mesh.face_handle(h).is_valid() &&
                try_flip(mesh.prev_halfedge_handle(h));  // edge (a, v) of face (v, m, a)
    } else if (!left && right_ok) {
      const HalfedgeHandle h = mesh.find_halfedge(m, v);
      right_ok = mesh.face_handle(h).is_valid() &&
                 try_flip(mesh.next_halfedge_handle(h));  // edge (v, b) of face (m, v, b)
    }
  }
  improve_valences(v, m);
  stamp_ring(v);
  stamp_ring(m);
  // Share v's counter in proportion to the vertices' areas.
  const double av = std::pow(mean_adjacent_edge_length(v), 2), am = std::pow(mean_adjacent_edge_length(m), 2);
  const double t = true_tau(v.idx());
  const double share = (av + am) > 0 ? av / (av + am) : 0.5;
  set_tau(v.idx(), t * share);
  set_tau(m.idx(), t * (1 - share));
  last_win[m.idx()] = steps;
  grid.insert(m.idx(), mesh.point(m));
  ++live;
  ++splits;
  update_decay();
  reorder_if_due();
}

void Reconstructor::Impl::reorder_if_due() {
  if (live < next_reorder_live) return;
  for (const Registered& r : ops)
    if (!r.op->can_follow_renumbering()) return;  // asked again at the next split
  next_reorder_live = live + live / 2;
  const MeshRenumbering map = detail::renumber_spatially(mesh);
  const size_t nv = mesh.n_vertices(), nf = mesh.n_faces();
  std::vector<double> new_tau(nv, -1.0);
  std::vector<std::uint64_t> new_last_win(nv, steps), new_vstamp(nv, clock), new_fstamp(nf, clock);
  for (size_t i = 0; i < map.vertex.size(); ++i) {
    const int n = map.vertex[i];
    if (n < 0) continue;
    new_tau[n] = tau[i];
    new_last_win[n] = last_win[i];
    new_vstamp[n] = vstamp[i];
  }
  std::vector<std::array<int, 3>> new_snapshot(nf, {-1, -1, -1});
  for (size_t i = 0; i < map.face.size(); ++i) {
    const int n = map.face[i];
    if (n < 0) continue;
    new_fstamp[n] = fstamp[i];
    if (i < face_snapshot.size() && face_snapshot[i][0] >= 0)
      for (int k = 0; k < 3; ++k) new_snapshot[n][k] = map.vertex[face_snapshot[i][k]];
  }
  tau = std::move(new_tau);
  last_win = std::move(new_last_win);
  vstamp = std::move(new_vstamp);
  fstamp = std::move(new_fstamp);
  face_snapshot = std::move(new_snapshot);
  neighbors.invalidate_all();
  neighbors.resize(nv);
  order.clear();
  grid.reset(grid.cell_size());
  grid.resize(nv);
  for (size_t i = 0; i < nv; ++i) {
    EF_CHECK(tau[i] >= 0, "reorder: a live vertex had no counter");
    order.set(static_cast<int>(i), tau[i]);
    grid.insert(static_cast<int>(i), mesh.point(VertexHandle(static_cast<int>(i))));
  }
  for (Registered& r : ops) r.op->on_renumbered(mesh, map);
}

double Reconstructor::Impl::collapse_cost(HalfedgeHandle h) {
  const double a = valence_of(mesh.from_vertex_handle(h)), b = valence_of(mesh.to_vertex_handle(h));
  double sum = (a + b - 10) * (a + b - 10);
  for (const HalfedgeHandle g : std::array<HalfedgeHandle, 2>{h, mesh.opposite_halfedge_handle(h)}) {
    if (!mesh.face_handle(g).is_valid()) continue;
    const double c = valence_of(mesh.to_vertex_handle(mesh.next_halfedge_handle(g)));
    sum += (c - 7) * (c - 7);
  }
  return std::sqrt(sum) / 3.0;
}

bool Reconstructor::Impl::collapse_geometry_ok(HalfedgeHandle h) const {
  const VertexHandle v0 = mesh.from_vertex_handle(h), v1 = mesh.to_vertex_handle(h);
  const Vec3& x0 = mesh.point(v0);
  const Vec3& x1 = mesh.point(v1);
  for (auto g : mesh.voh_range(v0)) {
    if (!mesh.face_handle(g).is_valid()) continue;
    const VertexHandle a = mesh.to_vertex_handle(g), b = mesh.to_vertex_handle(mesh.next_halfedge_handle(g));
    if (a == v1 || b == v1) continue;
    const Vec3 n_old = face_normal_of(x0, mesh.point(a), mesh.point(b));
    const Vec3 n_new = face_normal_of(x1, mesh.point(a), mesh.point(b));
    const double ln = n_new.norm(), lo = n_old.norm();
    if (!(ln > kCollapseMinArea * bbox_diagonal * bbox_diagonal) || lo == 0) return false;
    if ((n_new | n_old) < kCollapseMinFaceCos * ln * lo) return false;
  }
  return true;
}

bool Reconstructor::Impl::try_collapse(VertexHandle v) {
  if (live <= 8) return false;
  const bool border = mesh.is_boundary(v);
  HalfedgeHandle best;
  double best_cost = std::numeric_limits<double>::infinity();
  for (auto h : mesh.voh_range(v)) {
    if (border && !mesh.is_boundary(mesh.edge_handle(h))) continue;
    const VertexHandle u = mesh.to_vertex_handle(h);
    if (valence_of(v) + valence_of(u) < 7) continue;  // would leave a valence-2 vertex
    bool opp_ok = true;
    for (const HalfedgeHandle g : std::array<HalfedgeHandle, 2>{h, mesh.opposite_halfedge_handle(h)}) {
      if (!mesh.face_handle(g).is_valid()) continue;
      const VertexHandle c = mesh.to_vertex_handle(mesh.next_halfedge_handle(g));
      if (valence_of(c) <= (border_of(c) ? 2u : 3u)) opp_ok = false;
    }
    if (!opp_ok) continue;
    const double cost = collapse_cost(h);
    if (cost < best_cost && mesh.is_collapse_ok(h) && collapse_geometry_ok(h)) {
      best_cost = cost;
      best = h;
    }
  }
  if (!best.is_valid()) return false;
  const VertexHandle u = mesh.to_vertex_handle(best);
  const double t = true_tau(v.idx());
  for (auto x : mesh.vv_range(v)) neighbors.invalidate(x.idx());  // u and v's other neighbours
  neighbors.invalidate(v.idx());
  mesh.collapse(best);
  drop_tau(v.idx());
  grid.remove(v.idx());
  set_tau(u.idx(), true_tau(u.idx()) + t);
  stamp_ring(u);
  --live;
  ++collapses;
  return true;
}

void Reconstructor::Impl::collapse_inactive() {
  const std::uint64_t window = collapse_window();
  const size_t nv = mesh.n_vertices();
  for (size_t i = 0; i < nv; ++i) {
    const VertexHandle v(static_cast<int>(i));
    if (mesh.status(v).deleted() || tau[i] < 0) continue;
    if (last_win[i] + window >= steps) continue;
    try_collapse(v);
  }
  update_decay();
}

void Reconstructor::Impl::basic_steps(std::uint64_t n) {
  for (std::uint64_t i = 0; i < n; ++i) basic_step();
}

void Reconstructor::Impl::grow_until_split() {
  for (int i = 0; i < opt.growth.steps_per_split; ++i) {
    basic_step();
    if (opt.growth.inactivity_window > 0 && steps >= next_collapse_scan) {
      collapse_inactive();
      next_collapse_scan = steps + std::max<std::uint64_t>(1, collapse_window());
    }
  }
  split_most_active();
}

}  // namespace gcs
