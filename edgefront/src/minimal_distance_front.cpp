// The Minimal Distance Front itself: options, reset, the settle loop (step) and the ring walk, and
// the public class. The parts it shares with mdf_unfolding.cpp and mdf_windows.cpp: detail/mdf_impl.h.
#include "edgefront/minimal_distance_front.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "detail/distance_common.h"
#include "detail/mdf_impl.h"
#include "edgefront/error.h"

namespace edgefront {

using detail::check_distance_options;
using detail::check_points;
using detail::mdf::DRec;
using detail::mdf::Window;

void MinimalDistanceFront::Impl::check_options(const DistanceOptions& o) const {
  check_distance_options(mesh, o);
  if (o.method == DistanceMethod::Fast || o.method == DistanceMethod::Dijkstra) {
    throw InvalidInput(std::string("distance: method \"") + to_string(o.method) +
                       "\" computes whole fields through geodesic_distance (with max_distance and target); the "
                       "stepwise MinimalDistanceFront runs \"mdf\" and \"windows\"");
  }
}

void MinimalDistanceFront::Impl::clear_state(const DistanceOptions& o) {
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
int MinimalDistanceFront::Impl::count_unsettled(int v) const {
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

void MinimalDistanceFront::Impl::reset(const FrontSource& source, const DistanceOptions& o) {
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

void MinimalDistanceFront::Impl::reset(const std::vector<SurfacePoint>& points, const DistanceOptions& o) {
  check_options(o);
  const std::vector<VertexHandle> verts = check_points(mesh, points);
  clear_state(o);
  reset_structure(FrontSource::from_vertices(verts));
  windowed = o.method == DistanceMethod::Windows;
  for (const SurfacePoint& p : points) {
    const Vec3 x = surface_point_position(mesh, p);
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

// The ring's connectivity, walked once per settled vertex: its outgoing halfedges and neighbours,
// counter-clockwise, taken before the front expansion at x (the cache misses of the walk are
// taken here, and the neighbours' positions are prefetched for build_ring).
void MinimalDistanceFront::Impl::start_ring(int x) {
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

bool MinimalDistanceFront::Impl::step() {
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

}  // namespace edgefront
