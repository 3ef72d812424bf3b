// gcs::Reconstructor, batches: after each batch of splits the built-in topology pass (border
// creation, loop merging, slit zipping, hole filling) and the registered operations run, and the
// loop's state is brought back in line with the mesh (resync); run() drives the growth and the
// batches; validate() checks the state.
#include <algorithm>
#include <cmath>
#include <string>

#include "detail/double_layer.h"
#include "detail/reconstructor_impl.h"
#include "edgefront/error.h"
#include "edgefront/mesh_stats.h"

namespace gcs {

namespace {

// Holes whose fan fill is refused are retried with rings trimmed only when their border is at most
// this many mean edge lengths long (TopologyOptions::border_trim_rings).
constexpr double kTrimHoleEdges = 10.0;
// Border loops of at most this many vertices are small holes, closed by a fan around their centroid
// (a loop one vertex longer is a slit, zipped by fill_slit_holes up to fill_slits_max_vertices).
constexpr std::size_t kSmallHoleVertices = 8;
// A hole's fan or a slit's strip must agree with the faces it borders: mean cosine of their normals.
constexpr double kFillNormalAgreement = 0.5;
// Faces whose centroid is at least this many mean edge lengths from the nearest sample are also
// removed when their normal is far from that sample's (BorderParams::min_normal_cos): farther than
// the chord error of a mesh on a curved surface, a face should lie on the samples' tangent plane.
constexpr double kNormalGateEdges = 0.3;
// The border creation removes pieces of fewer faces than this (debris cut off by the removals)
// unless they lie on a part of the cloud of their own.
constexpr std::size_t kMinComponentFaces = 8;
// Between batches the topology pass runs again only once the live vertex count grew by this factor
// (or on the final call): a pass costs a query per face, a batch adds only a few hundred vertices.
constexpr double kTopologyRegrowth = 1.1;
// Operations that removed parts on the final call (e.g. twisted regions cut out) have the loop grow
// back when the mesh is below this share of the target; at most kRegrowRounds times.
constexpr double kShrunkShare = 0.9;
constexpr int kRegrowRounds = 3;

}  // namespace

void Reconstructor::Impl::snapshot_faces() {
  face_snapshot.assign(mesh.n_faces(), {-1, -1, -1});
  for (auto f : mesh.faces()) {
    auto it = mesh.cfv_iter(f);
    face_snapshot[f.idx()] = {it->idx(), (++it)->idx(), (++it)->idx()};
  }
}

void Reconstructor::Impl::resync() {
  // Keep the mesh manifold without isolated vertices (an operation may leave a bow tie).
  detail::clean_topology(mesh, 0);
  if (mesh.n_vertices() < tau.size() || mesh.n_faces() < fstamp.size()) {
    full_rebuild();
    return;
  }
  ensure_sizes();
  size_t n_live = 0;
  for (size_t i = 0; i < mesh.n_vertices(); ++i) {
    const VertexHandle v(static_cast<int>(i));
    const bool is_live = !mesh.status(v).deleted();
    if (!is_live) {
      if (grid.contains(static_cast<int>(i))) grid.remove(static_cast<int>(i));
      drop_tau(static_cast<int>(i));
      continue;
    }
    ++n_live;
    if (!grid.contains(static_cast<int>(i))) {
      grid.insert(static_cast<int>(i), mesh.point(v));
      set_tau(static_cast<int>(i), 0.0);
      last_win[i] = steps;
      stamp(v);
    } else if (grid.position(static_cast<int>(i)) != mesh.point(v)) {
      grid.move(static_cast<int>(i), mesh.point(v));
      stamp(v);
    }
  }
  for (size_t i = 0; i < mesh.n_faces(); ++i) {
    const FaceHandle f(static_cast<int>(i));
    const bool was = i < face_snapshot.size() && face_snapshot[i][0] >= 0;
    if (mesh.status(f).deleted()) {
      if (was)
        for (int k : face_snapshot[i]) {
          neighbors.invalidate(k);
          if (!mesh.status(VertexHandle(k)).deleted()) vstamp[k] = clock;
        }
      continue;
    }
    auto it = mesh.cfv_iter(f);
    const std::array<int, 3> now = {it->idx(), (++it)->idx(), (++it)->idx()};
    if (!was || now != face_snapshot[i]) {
      fstamp[i] = clock;
      for (int k : now) {
        vstamp[k] = clock;
        neighbors.invalidate(k);
      }
      if (was)
        for (int k : face_snapshot[i]) {
          neighbors.invalidate(k);
          if (!mesh.status(VertexHandle(k)).deleted()) vstamp[k] = clock;
        }
    }
  }
  live = n_live;
  update_decay();
  snapshot_faces();
}

void Reconstructor::Impl::full_rebuild() {
  neighbors.invalidate_all();
  tau.assign(mesh.n_vertices(), -1.0);
  order.clear();
  scale = 1.0;
  last_win.assign(mesh.n_vertices(), steps);
  vstamp.assign(mesh.n_vertices(), clock);
  fstamp.assign(mesh.n_faces(), clock);
  grid.reset(grid.cell_size());
  grid.resize(mesh.n_vertices());
  live = 0;
  for (auto v : mesh.vertices()) {
    grid.insert(v.idx(), mesh.point(v));
    set_tau(v.idx(), 0.0);
    ++live;
  }
  update_decay();
  snapshot_faces();
}

void Reconstructor::Impl::rebuild_grid_if_needed(double target) {
  if (target <= 0) return;
  const double ratio = grid.cell_size() / target;
  if (ratio > 0.5 && ratio < 2.0) return;
  grid.reset(target);
  for (auto v : mesh.vertices()) grid.insert(v.idx(), mesh.point(v));
}

ChangeSet Reconstructor::Impl::changes_since(std::uint64_t last) const {
  ChangeSet cs;
  for (auto v : mesh.vertices())
    if (vstamp[v.idx()] > last) cs.vertices.push_back(v);
  for (auto f : mesh.faces()) {
    bool changed = fstamp[f.idx()] > last;
    for (auto v : mesh.fv_range(f)) changed = changed || vstamp[v.idx()] > last;
    if (changed) cs.faces.push_back(f);
  }
  return cs;
}

bool Reconstructor::Impl::topology_pass(bool force, double ell) {
  if (!opt.topology.create_borders && !opt.topology.merge_borders) return false;
  if (live < opt.topology.min_vertices) return false;
  if (!force && topology_last_live > 0 && static_cast<double>(live) < kTopologyRegrowth * static_cast<double>(topology_last_live))
    return false;
  const auto t0 = Clock::now();
  topology_last_live = live;
  const double support = support_distance(ell);
  const double bridge = bridge_distance(ell);
  const detail::CloudQuery dist = [this](const Vec3& p) { return cloud_query(p); };
  const size_t trim_rings = opt.topology.border_trim_rings;
  bool changed = false;
  const auto tally = [&changed](size_t& total, size_t n) {
    total += n;
    changed = changed || n > 0;
  };
  if (opt.topology.create_borders) {
    detail::BorderParams bp;
    bp.max_support_distance = support;
    bp.max_edge_length = opt.topology.long_edge_factor * ell;
    bp.min_component_faces = kMinComponentFaces;
    bp.normal_check_distance = kNormalGateEdges * ell;
    bp.film_samples = encloses ? opt.topology.film_samples : 0;
    // Both removals spare a piece lying on a part of the cloud of its own (a separate surface).
    const auto sample_part = [this](size_t k) { return query_point_part(k); };
    bp.sample_part = sample_part;
    // The support test's nearest sample per face goes on to the opposed-face test (same
    // centroids: nothing moves in between), with the sample's oriented normal.
    detail::FaceNearest nearest;
    tally(faces_removed, detail::remove_unsupported_faces(
                             mesh, dist, bp,
                             [this](const Vec3& p, size_t k, std::vector<detail::CloudHit>& out) {
                               oriented_neighbors(p, k, out);
                             },
                             oriented ? &nearest : nullptr));
    if (oriented) {
      for (auto f : mesh.faces()) {
        detail::CloudHit& hit = nearest[static_cast<size_t>(f.idx())];
        if (hit.index != detail::CloudHit::kNoSample) hit.normal = query_oriented_normal(hit.index);
      }
      tally(faces_removed,
            detail::remove_opposed_faces(mesh, nearest, {.max_distance = support, .sample_part = sample_part}));
    }
  }
  if (opt.topology.merge_borders) {
    detail::MergeParams mp;
    mp.mean_edge_length = ell;
    mp.max_support_distance = bridge;
    mp.max_trim_rings = trim_rings;
    tally(loops_merged, detail::merge_border_loops(mesh, dist, mp));
    // zip_slits zips within and across loops; otherwise torn-off pieces of an open sheet are
    // joined back (join_components: only across components).
    const bool join = !opt.experimental.zip_slits && opt.topology.join_components && !encloses &&
                      edgefront::connected_components(mesh).count > 1;
    if (opt.experimental.zip_slits || join) {
      detail::ZipParams zp;
      zp.mean_edge_length = ell;
      zp.max_support_distance = bridge;
      zp.across_loops = join;
      zp.only_across_components = join;
      tally(slits_zipped, detail::zip_border_slits(mesh, dist, zp));
    }
  }
  if (opt.topology.create_borders) {
    tally(holes_filled, detail::fill_small_holes(mesh, dist, kSmallHoleVertices, bridge, kFillNormalAgreement, {.rings = trim_rings, .max_loop_length = kTrimHoleEdges * ell}));
    if (opt.topology.fill_slits_max_vertices > kSmallHoleVertices)
      tally(holes_filled, detail::fill_slit_holes(mesh, dist, kSmallHoleVertices + 1, opt.topology.fill_slits_max_vertices,
                                                     bridge, kFillNormalAgreement,
                                                     trim_rings));
  }
  if (changed) resync();
  seconds_topology += seconds_since(t0);
  return true;
}

void Reconstructor::Impl::end_batch(bool final_call) {
  ++batches;
  splits_in_batch = 0;
  // The mean edge length (a pass over all edges) is computed again only where the mesh may
  // have changed.
  double ell = mean_edge_length();
  rebuild_grid_if_needed(ell);
  snapshot_faces();
  if (topology_pass(final_call, ell)) ell = mean_edge_length();
  ell = run_operations(final_call, ell);
  // The topology pass and the operations may change the mean edge length: with or without
  // operations registered, the grid is checked at the same point (an operation that changes
  // nothing leaves the run as it is without it).
  rebuild_grid_if_needed(ell);
}

double Reconstructor::Impl::run_operations(bool final_call, double ell) {
  if (ops.empty()) return ell;
  OperationContext ctx{cloud};
  ctx.query_points = subsample.empty() ? nullptr : &subsample;
  ctx.mean_edge_length = ell;
  ctx.bbox_diagonal = bbox_diagonal;
  ctx.target_vertices = opt.target_vertices;
  ctx.basic_steps = steps;
  ctx.batch = batches;
  ctx.final_call = final_call;
  for (Registered& r : ops) {
    ctx.live_vertices = live;
    const ChangeSet cs = changes_since(r.last);
    ++clock;
    const auto t0 = Clock::now();
    const OperationResult res = r.op->apply(mesh, cs, ctx);
    const double dt = seconds_since(t0);
    r.report.seconds += dt;
    seconds_ops += dt;
    ++r.report.calls;
    if (!res.summary.empty()) r.report.last_summary = res.summary;
    if (res.mesh_changed) {
      ++r.report.changes;
      resync();
      ctx.mean_edge_length = mean_edge_length();
    }
    r.last = clock;
    ++clock;
  }
  return ctx.mean_edge_length;
}

ReconstructResult Reconstructor::Impl::run(const ProgressCallback& progress) {
  const auto t0 = Clock::now();
  auto post = [&](double fraction) {
    if (!progress) return;
    Progress p;
    p.phase = Phase::post_processing;
    p.phase_fraction = fraction;
    p.vertices = live;
    p.target_vertices = opt.target_vertices;
    p.basic_steps = steps;
    p.seconds = seconds_since(t0);
    (void)progress(p);
  };
  if (finished) return make_result(0.0, post);
  const std::uint64_t step_limit =
      opt.growth.max_steps_per_vertex == 0 ? std::numeric_limits<std::uint64_t>::max()
                                    : opt.growth.max_steps_per_vertex * static_cast<std::uint64_t>(opt.target_vertices);
  size_t splits_since_progress = 0;
  auto report = [&]() {
    if (!progress) return true;
    Progress p;
    p.phase = Phase::growth;
    p.phase_fraction = opt.target_vertices ? std::min(1.0, static_cast<double>(live) / static_cast<double>(opt.target_vertices)) : 1.0;
    p.vertices = live;
    p.target_vertices = opt.target_vertices;
    p.basic_steps = steps;
    p.seconds = seconds_since(t0);
    return progress(p);
  };
  StopReason reason = StopReason::target_reached;
  // Operations on the final call (e.g. the twist repair cutting out a region) can shrink the
  // mesh below the target: then the loop grows it back and calls them again, a few times.
  // (The final border pass trims a few unsupported triangles: that much is not shrinking.)
  auto shrunk = [&] { return static_cast<double>(live) < kShrunkShare * static_cast<double>(opt.target_vertices); };
  for (int round = 0;; ++round) {
  while (live < opt.target_vertices) {
    if (steps >= step_limit) {
      reason = StopReason::step_limit;
      break;
    }
    grow_until_split();
    if (++splits_in_batch >= batch_size()) end_batch(false);
    if (++splits_since_progress >= opt.progress_interval) {
      splits_since_progress = 0;
      if (!report()) {
        reason = StopReason::cancelled;
        break;
      }
    }
  }
  if (reason == StopReason::cancelled) break;
  end_batch(true);
  if (reason != StopReason::target_reached || !shrunk() || round + 1 >= kRegrowRounds) break;
  }
  if (reason == StopReason::target_reached && shrunk()) reason = StopReason::shrunk_by_operations;
  if (reason != StopReason::cancelled) {
    finished = true;
    finished_reason = reason;
    report();
  }
  // After a cancel the callback is not called again (the post-processing still runs, unreported).
  ReconstructResult r = make_result(seconds_since(t0), reason == StopReason::cancelled ? std::function<void(double)>() : post);
  r.stop_reason = reason;
  return r;
}

void Reconstructor::Impl::validate() const {
  auto fail = [](const std::string& m) { throw edgefront::InternalError("gcs validate: " + m); };
  const size_t nv = mesh.n_vertices();
  if (tau.size() < nv || last_win.size() < nv || vstamp.size() < nv || grid.capacity() < nv)
    fail("per-vertex state is smaller than the mesh's vertex array");
  if (fstamp.size() < mesh.n_faces()) fail("per-face state is smaller than the mesh's face array");
  size_t n_live = 0;
  for (size_t i = 0; i < nv; ++i) {
    const VertexHandle v(static_cast<int>(i));
    const int id = static_cast<int>(i);
    if (mesh.status(v).deleted()) {
      if (grid.contains(id)) fail("deleted vertex " + std::to_string(i) + " is in the spatial grid");
      if (tau[i] >= 0) fail("deleted vertex " + std::to_string(i) + " has a signal counter");
      continue;
    }
    ++n_live;
    grid.check(id, mesh.point(v));
    if (!(tau[i] >= 0) || !std::isfinite(tau[i])) fail("vertex " + std::to_string(i) + " has no valid counter");
    if (!order.contains(id) || order.value(id) != tau[i])
      fail("vertex " + std::to_string(i) + " is missing from the counter order");
    if (!mesh.is_manifold(v)) fail("vertex " + std::to_string(i) + " is not manifold");
    if (mesh.valence(v) < 2) fail("vertex " + std::to_string(i) + " has valence " + std::to_string(mesh.valence(v)));
    const Vec3& p = mesh.point(v);
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
      fail("vertex " + std::to_string(i) + " has a non-finite position");
    std::vector<int> nb;
    for (auto u : mesh.vv_range(v)) {
      if (mesh.status(u).deleted()) fail("vertex " + std::to_string(i) + " has a deleted neighbour");
      nb.push_back(u.idx());
    }
    std::sort(nb.begin(), nb.end());
    if (std::adjacent_find(nb.begin(), nb.end()) != nb.end())
      fail("vertex " + std::to_string(i) + " has two edges to the same neighbour");
  }
  try {
    neighbors.check(mesh);
  } catch (const std::exception& e) {
    fail(e.what());
  }
  if (n_live != live) fail("live vertex count " + std::to_string(live) + " != mesh " + std::to_string(n_live));
  if (grid.size() != n_live) fail("spatial grid holds " + std::to_string(grid.size()) + " vertices, mesh has " + std::to_string(n_live));
  try {
    order.check();
  } catch (const std::exception& e) {
    fail(e.what());
  }
  if (order.size() != n_live) fail("counter order holds " + std::to_string(order.size()) + " vertices, mesh has " + std::to_string(n_live));
  for (auto f : mesh.faces()) {
    int k = 0;
    std::array<int, 3> vs{};
    for (auto h : mesh.fh_range(f)) {
      if (k == 3) fail("face " + std::to_string(f.idx()) + " is not a triangle");
      if (mesh.status(h).deleted()) fail("face " + std::to_string(f.idx()) + " has a deleted halfedge");
      if (mesh.face_handle(h) != f) fail("face " + std::to_string(f.idx()) + ": halfedge does not point back");
      if (mesh.next_halfedge_handle(mesh.prev_halfedge_handle(h)) != h) fail("face " + std::to_string(f.idx()) + ": prev/next links disagree");
      const VertexHandle v = mesh.to_vertex_handle(h);
      if (mesh.status(v).deleted()) fail("face " + std::to_string(f.idx()) + " uses a deleted vertex");
      vs[k++] = v.idx();
    }
    if (k != 3) fail("face " + std::to_string(f.idx()) + " is not a triangle");
    if (vs[0] == vs[1] || vs[1] == vs[2] || vs[0] == vs[2]) fail("face " + std::to_string(f.idx()) + " repeats a vertex");
  }
  for (auto h : mesh.halfedges()) {
    if (mesh.opposite_halfedge_handle(mesh.opposite_halfedge_handle(h)) != h) fail("halfedge opposite link broken");
    if (mesh.to_vertex_handle(mesh.opposite_halfedge_handle(h)) != mesh.from_vertex_handle(h)) fail("halfedge vertex link broken");
    if (mesh.is_boundary(h) && mesh.is_boundary(mesh.opposite_halfedge_handle(h))) fail("edge without faces");
  }
}

}  // namespace gcs
