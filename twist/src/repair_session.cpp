// RepairSession: a mirror of the host's mesh, the host's edits applied to it all or nothing, the
// incremental repair, and the edit records that bring the host up to the mirror.

#include "twist/repair_session.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <optional>
#include <string>

#include "detail/geometry.h"
#include "detail/heal.h"
#include "detail/host_mirror.h"
#include "edgefront/error.h"
#include "edgefront/minimal_distance_front.h"
#include "edgefront/vertex_twins.h"

namespace twist {

using edgefront::FaceHandle;
using edgefront::HalfedgeHandle;
using edgefront::InvalidInput;
using edgefront::Mesh;
using edgefront::Vec3;
using edgefront::VertexHandle;

namespace {

constexpr double kMaxCoordinate = 1e150;

[[noreturn]] void refuse(const std::string& what) { throw InvalidInput("twist::RepairSession: " + what); }

std::string corners_text(const std::array<int, 3>& c) {
  std::string out = "(";
  for (size_t k = 0; k < 3; ++k) {
    out += std::to_string(c[k]);
    out += k < 2 ? ", " : ")";
  }
  return out;
}

/// The host's edits of one kind in a batch, by index, the last edit of an index winning.
template <class T>
class EditList {
 public:
  using Item = std::pair<int, std::optional<T>>;  ///< (index, value; nullopt: remove)
  void set(int i, std::optional<T> e) { items_.emplace_back(i, std::move(e)); }
  bool empty() const { return items_.empty(); }
  void clear() { items_.clear(); }
  /// Sorts by index and keeps the last edit of each index (call before reading).
  void settle() {
    // Sort (index, arrival) keys, then keep the last arrival of each index.
    order_.resize(items_.size());
    for (size_t i = 0; i < items_.size(); ++i) {
      order_[i] = static_cast<std::uint64_t>(static_cast<std::uint32_t>(items_[i].first)) << 32 | static_cast<std::uint32_t>(i);
    }
    std::sort(order_.begin(), order_.end());
    settled_.clear();
    for (size_t i = 0; i < order_.size(); ++i) {
      if (i + 1 < order_.size() && order_[i + 1] >> 32 == order_[i] >> 32) continue;  // a later edit wins
      settled_.push_back(std::move(items_[order_[i] & 0xffffffffu]));
    }
    items_.swap(settled_);
  }
  typename std::vector<Item>::const_iterator begin() const { return items_.begin(); }
  typename std::vector<Item>::const_iterator end() const { return items_.end(); }
  /// The settled edit of index i, or null.
  const std::optional<T>* find(int i) const {
    const auto it = std::lower_bound(items_.begin(), items_.end(), i, [](const Item& a, int x) { return a.first < x; });
    return it != items_.end() && it->first == i ? &it->second : nullptr;
  }

 private:
  std::vector<Item> items_, settled_;
  std::vector<std::uint64_t> order_;
};

}  // namespace

struct RepairSession::Impl {
  SessionOptions options;
  edgefront::ArrayMesh converted;  // its mesh is the mirror
  detail::HostMirror host;
  EditRecord initial;
  TwistRepairer repairer;
  SessionStats stats;
  std::vector<int> use_count;  // per host vertex: faces using it (recounted when stale and needed)
  bool use_count_stale = false;
  size_t live_faces = 0;       // host faces
  // The batch, applied in index order (deterministic).
  EditList<std::array<int, 3>> face_edits;
  EditList<std::array<double, 3>> vertex_edits;
  std::unique_ptr<edgefront::MinimalDistanceFront> front;
  size_t front_vertices = 0, front_faces = 0;  // the mirror's size when the front was made
  double mean_edge = 0;
  size_t mean_edge_faces = 0;  // live faces when it was computed

  std::vector<FaceHandle> healed;  // faces the last heal added: the next repair looks at them

  static const SessionOptions& checked(const SessionOptions& o) {
    const HealOptions& h = o.heal;
    if (!h.enabled) return o;
    if (o.repair.detect.reference == nullptr) {
      refuse("heal needs a reference cloud (SessionOptions::repair.detect.reference): the new faces must lie on it");
    }
    for (const double x : {h.max_gap_edges, h.max_support_edges}) {
      if (!(x >= 0) || !std::isfinite(x)) refuse("heal distances must be finite and >= 0");
    }
    if (!std::isfinite(h.min_normal_agreement)) refuse("heal min_normal_agreement must be finite");
    if (h.grow_rows > 8) refuse("heal grow_rows must be at most 8 (rows grown per answer), got " + std::to_string(h.grow_rows));
    if (h.grow_min_support < 1) refuse("heal grow_min_support must be at least 1");
    if (!(h.min_piece_share >= 0 && h.min_piece_share < 1)) refuse("heal min_piece_share must be in [0, 1)");
    return o;
  }

  static RepairOptions repair_options(RepairOptions o) {
    o.garbage_collect = false;  // the mirror keeps its indices, as the host does
    return o;
  }

  Impl(const edgefront::VertexArrayView& v, const edgefront::FaceArrayView& f, SessionOptions o)
      : options(checked(o)),
        converted(edgefront::mesh_from_arrays(v, f, options.conversion)),
        host(detail::host_of_conversion(v, f, converted)),
        repairer(repair_options(options.repair), options.max_retwists) {
    initial = detail::bring_up_to_date(host, mirror());
    count_uses();
  }

  void count_uses() {
    use_count.assign(host.vertex_slots(), 0);
    live_faces = 0;
    for (size_t s = 0; s < host.face_slots(); ++s) {
      if (host.faces[3 * s] < 0) continue;
      ++live_faces;
      for (size_t k = 0; k < 3; ++k) ++use_count[static_cast<size_t>(host.faces[3 * s + k])];
    }
    use_count_stale = false;
  }

  Mesh& mirror() { return converted.mesh; }
  const Mesh& mirror() const { return converted.mesh; }
  bool vertex_alive(int v) const {
    return v >= 0 && static_cast<size_t>(v) < host.mirror_of_vertex.size() && host.mirror_of_vertex[static_cast<size_t>(v)] >= 0;
  }
  bool face_alive(int f) const {
    return f >= 0 && static_cast<size_t>(f) < host.mirror_of_face.size() && host.mirror_of_face[static_cast<size_t>(f)] >= 0;
  }
  std::array<int, 3> host_face(int f) const {
    const size_t b = 3 * static_cast<size_t>(f);
    return {host.faces[b], host.faces[b + 1], host.faces[b + 2]};
  }

  /// New indices: free slots below `slots`, or exactly the next ones (no gaps).
  template <class Edits, class Alive>
  static void check_new_indices(const Edits& edits, size_t slots, const Alive& alive, const char* what) {
    size_t appended = 0;
    for (const auto& [i, e] : edits) appended += e && static_cast<size_t>(i) >= slots ? 1 : 0;
    for (const auto& [i, e] : edits) {
      if (e && !alive(i) && static_cast<size_t>(i) >= slots + appended) {
        refuse(std::string(what) + " " + std::to_string(i) + " leaves a gap: new indices are free ones below " +
               std::to_string(slots) + " or the next ones");
      }
    }
  }

  /// Applies the batch to the mirror and the host's state, all or nothing; fills `changed` with
  /// the mirror faces the repair should look at. Then splits the vertices the batch left pinched.
  void commit(std::vector<FaceHandle>& changed) {
    for (FaceHandle f : healed) {
      if (edgefront::is_live(mirror(), f)) changed.push_back(f);
    }
    healed.clear();
    if (face_edits.empty() && vertex_edits.empty()) return;
    struct Clear {
      Impl& s;
      ~Clear() {
        s.face_edits.clear();
        s.vertex_edits.clear();
      }
    } clear{*this};
    Mesh& m = mirror();
    const size_t nv_slots = host.vertex_slots(), nf_slots = host.face_slots();
    face_edits.settle();
    vertex_edits.settle();
    if (use_count_stale) {
      bool removes_vertex = false;
      for (const auto& [v, e] : vertex_edits) removes_vertex = removes_vertex || !e;
      if (removes_vertex) count_uses();
    }

    // 1. Checks, nothing touched yet.
    check_new_indices(vertex_edits, nv_slots, [&](int v) { return vertex_alive(v); }, "vertex");
    check_new_indices(face_edits, nf_slots, [&](int f) { return face_alive(f); }, "face");
    auto alive_after = [&](int v) {
      const auto* e = vertex_edits.find(v);
      return e ? e->has_value() : vertex_alive(v);
    };
    std::map<int, long> use_change;
    for (const auto& [f, e] : face_edits) {
      if (!e && !face_alive(f)) refuse("face " + std::to_string(f) + " cannot be removed: it is not a face");
      if (face_alive(f)) {
        for (int v : host_face(f)) --use_change[v];
      }
      if (!e) continue;
      const auto& c = *e;
      for (int v : c) {
        if (!alive_after(v)) refuse("face " + std::to_string(f) + " " + corners_text(c) + " uses vertex " + std::to_string(v) + ", which is not a vertex");
        ++use_change[v];
      }
      if (c[0] == c[1] || c[1] == c[2] || c[0] == c[2]) refuse("face " + std::to_string(f) + " " + corners_text(c) + " repeats a vertex");
    }
    for (const auto& [v, e] : vertex_edits) {
      if (e) {
        for (double x : *e) {
          if (!(std::abs(x) <= kMaxCoordinate)) refuse("vertex " + std::to_string(v) + " gets a non-finite or huge coordinate");
        }
      } else {
        if (!vertex_alive(v)) refuse("vertex " + std::to_string(v) + " cannot be removed: it is not a vertex");
        const long uses = use_count[static_cast<size_t>(v)] + use_change[v];
        if (uses != 0) refuse("vertex " + std::to_string(v) + " cannot be removed: " + std::to_string(uses) + " faces use it");
      }
    }

    // 2. The mirror, undone on a face it cannot hold.
    std::vector<std::pair<VertexHandle, Vec3>> moved;  // (vertex, old position)
    std::vector<std::pair<int, VertexHandle>> added_vertices;
    std::vector<std::pair<int, FaceHandle>> removed_faces;  // (host slot, old mirror face)
    std::vector<VertexHandle> removed_corners;              // their corners, 3 per face
    std::vector<std::pair<int, FaceHandle>> added_faces;
    auto mirror_vertex = [&](int v) {
      if (vertex_alive(v)) return VertexHandle(host.mirror_of_vertex[static_cast<size_t>(v)]);
      for (const auto& [id, mv] : added_vertices)
        if (id == v) return mv;
      return VertexHandle();
    };
    for (const auto& [v, e] : vertex_edits) {
      if (!e) continue;
      const Vec3 p((*e)[0], (*e)[1], (*e)[2]);
      if (vertex_alive(v)) {
        const VertexHandle mv(host.mirror_of_vertex[static_cast<size_t>(v)]);
        moved.emplace_back(mv, m.point(mv));
        m.set_point(mv, p);
      } else {
        added_vertices.emplace_back(v, m.add_vertex(p));
      }
    }
    for (const auto& [f, e] : face_edits) {
      if (!face_alive(f)) continue;
      const FaceHandle mf(host.mirror_of_face[static_cast<size_t>(f)]);
      for (VertexHandle v : m.fv_range(mf)) removed_corners.push_back(v);
      m.delete_face(mf, false);
      removed_faces.emplace_back(f, mf);
    }
    auto undo = [&](int f, const std::array<int, 3>& c, const std::string& why) {
      for (auto it = added_faces.rbegin(); it != added_faces.rend(); ++it) m.delete_face(it->second, false);
      for (const auto& removed : removed_faces) {
        const int slot = removed.first;
        const std::array<int, 3> a = host_face(slot);
        const FaceHandle back = m.add_face(VertexHandle(host.mirror_of_vertex[static_cast<size_t>(a[0])]),
                                           VertexHandle(host.mirror_of_vertex[static_cast<size_t>(a[1])]),
                                           VertexHandle(host.mirror_of_vertex[static_cast<size_t>(a[2])]));
        EF_CHECK(back.is_valid(), "RepairSession: a face removed by a refused batch could not be put back");
        m.set_normal(back, m.calc_face_normal(back));
        host.map_face(static_cast<size_t>(slot), back.idx(), m);
      }
      for (const auto& [v, old] : moved) m.set_point(v, old);
      for (const auto& [id, v] : added_vertices) m.delete_vertex(v, false);
      refuse("face " + std::to_string(f) + " " + corners_text(c) + " does not fit a half-edge mesh: " + why +
             " (nothing of the batch was applied)");
    };
    for (const auto& [f, e] : face_edits) {
      if (!e) continue;
      const auto& c = *e;
      const VertexHandle a[3] = {mirror_vertex(c[0]), mirror_vertex(c[1]), mirror_vertex(c[2])};
      for (int k = 0; k < 3; ++k) {
        if (!m.is_isolated(a[k]) && !m.is_boundary(a[k])) undo(f, c, "vertex " + std::to_string(c[static_cast<size_t>(k)]) + " is closed all around");
        const HalfedgeHandle h = m.find_halfedge(a[k], a[(k + 1) % 3]);
        if (h.is_valid() && !m.is_boundary(h)) {
          undo(f, c, "another face runs along " + std::to_string(c[static_cast<size_t>(k)]) + " -> " +
                         std::to_string(c[static_cast<size_t>((k + 1) % 3)]) + " in the same direction, or the edge has two faces");
        }
      }
      const FaceHandle nf = m.add_face(a[0], a[1], a[2]);
      if (!nf.is_valid()) undo(f, c, "it would join two fans of a vertex the mesh cannot re-link");
      m.set_normal(nf, m.calc_face_normal(nf));
      added_faces.emplace_back(f, nf);
    }

    // 3. Done: the host's state and the maps.
    for (const auto& [v, e] : vertex_edits) {
      if (e) continue;
      const int mv = host.mirror_of_vertex[static_cast<size_t>(v)];
      m.delete_vertex(VertexHandle(mv), false);
      host.host_of_vertex[static_cast<size_t>(mv)] = -1;
      host.mirror_of_vertex[static_cast<size_t>(v)] = -1;
    }
    for (const auto& [id, v] : added_vertices) {
      const size_t i = static_cast<size_t>(id);
      if (i >= host.vertex_slots()) {
        host.vertices.resize(3 * (i + 1), std::nan(""));
        host.mirror_of_vertex.resize(i + 1, -1);
        use_count.resize(i + 1, 0);
      }
      host.mirror_of_vertex[i] = v.idx();
      host.host_of_vertex.resize(m.n_vertices(), -1);
      host.host_of_vertex[static_cast<size_t>(v.idx())] = id;
    }
    for (const auto& [v, e] : vertex_edits) {
      if (e) std::copy(e->begin(), e->end(), host.vertices.begin() + 3 * static_cast<std::ptrdiff_t>(v));
    }
    host.host_of_face.resize(m.n_faces(), -1);
    for (const auto& [f, old] : removed_faces) {
      if (!use_count_stale) {
        for (int v : host_face(f)) --use_count[static_cast<size_t>(v)];
      }
      std::fill_n(host.faces.begin() + 3 * static_cast<std::ptrdiff_t>(f), 3, -1);
      host.map_face(static_cast<size_t>(f), -1, m);
      --live_faces;
    }
    for (const auto& [f, nf] : added_faces) {
      const size_t i = static_cast<size_t>(f);
      if (i >= host.face_slots()) host.faces.resize(3 * (i + 1), -1);
      const auto& c = **face_edits.find(f);
      std::copy(c.begin(), c.end(), host.faces.begin() + 3 * static_cast<std::ptrdiff_t>(i));
      if (!use_count_stale) {
        for (int v : c) ++use_count[static_cast<size_t>(v)];
      }
      host.map_face(i, nf.idx(), m);
      ++live_faces;
      changed.push_back(nf);
    }
    host.mirror_vertices_seen = m.n_vertices();
    host.mirror_faces_seen = m.n_faces();
    for (const auto& mv : moved) {
      for (FaceHandle f : m.vf_range(mv.first)) changed.push_back(f);
    }
    stats.faces_changed = changed.size();

    // 4. Vertices the batch left pinched: one copy per extra fan (the record adds them).
    std::vector<VertexHandle> touched;
    auto touch = [&](const std::array<int, 3>& c) {
      for (int v : c)
        if (vertex_alive(v)) touched.push_back(VertexHandle(host.mirror_of_vertex[static_cast<size_t>(v)]));
    };
    for (const auto& [f, e] : face_edits)
      if (e) touch(*e);
    touched.insert(touched.end(), removed_corners.begin(), removed_corners.end());
    std::sort(touched.begin(), touched.end());
    touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
    stats.pinched_split = 0;
    const size_t faces_before_split = m.n_faces();
    for (VertexHandle v : touched) {
      if (!edgefront::is_live(m, v) || m.is_manifold(v)) continue;
      const size_t first_copy = m.n_vertices();
      detail::split_fans(m, v);
      ++stats.pinched_split;
      std::vector<VertexHandle> group{v};
      for (size_t i = first_copy; i < m.n_vertices(); ++i) group.push_back(VertexHandle(static_cast<int>(i)));
      if (edgefront::twins_of(m, v).empty()) edgefront::link_twins(m, group);
    }
    for (size_t i = faces_before_split; i < m.n_faces(); ++i) {
      if (edgefront::is_live(m, FaceHandle(static_cast<int>(i)))) changed.push_back(FaceHandle(static_cast<int>(i)));
    }
    std::sort(changed.begin(), changed.end());
    changed.erase(std::unique(changed.begin(), changed.end()), changed.end());
    if (stats.pinched_split > 0) {  // the splits deleted faces listed before
      changed.erase(std::remove_if(changed.begin(), changed.end(), [&](FaceHandle f) { return !edgefront::is_live(m, f); }),
                    changed.end());
    }
  }

  /// The record since the last one: a pass over the mirror when something changed it.
  EditRecord record(bool changed) {
    ++stats.calls;
    if (!changed && mirror().n_vertices() == host.mirror_vertices_seen && mirror().n_faces() == host.mirror_faces_seen) {
      EditRecord r;
      r.vertices_before = host.vertex_slots();
      r.faces_before = host.face_slots();
      return r;
    }
    EditRecord r = detail::bring_up_to_date(host, mirror());
    use_count.resize(host.vertex_slots(), 0);
    live_faces += r.faces_added.size();
    live_faces -= r.faces_removed.size();
    use_count_stale = use_count_stale || !r.corners_replaced.empty() || !r.faces_removed.empty() || !r.faces_added.empty();
    return r;
  }

  /// The heal (when on) on the mirror; true when it added faces.
  bool heal(double mean_edge_length) {
    stats.heal = {};
    if (!options.heal.enabled) return false;
    const detail::HealCounts c =
        detail::heal_borders(mirror(), *options.repair.detect.reference, mean_edge_length, options.heal, healed);
    stats.heal = {.strips = c.strips, .holes = c.holes, .grown = c.grown, .faces_added = healed.size()};
    return !healed.empty();
  }

  double estimated_mean_edge() {
    if (mean_edge == 0 || 10 * std::max(live_faces, mean_edge_faces) > 11 * std::min(live_faces, mean_edge_faces)) {
      mean_edge = detail::mean_edge_length(mirror());
      mean_edge_faces = live_faces;
    }
    return mean_edge;
  }

  void require_synced(const char* what) const {
    if (!face_edits.empty() || !vertex_edits.empty()) {
      refuse(std::string(what) + ": edits are pending; call sync(), repair() or finish() first");
    }
  }
  VertexHandle query_vertex(int v, const char* what) const {
    if (!vertex_alive(v)) refuse(std::string(what) + ": vertex " + std::to_string(v) + " is not a vertex");
    return VertexHandle(host.mirror_of_vertex[static_cast<size_t>(v)]);
  }
  edgefront::MinimalDistanceFront& distance_front() {
    if (!front || front_vertices != mirror().n_vertices() || front_faces != mirror().n_faces()) {
      front = std::make_unique<edgefront::MinimalDistanceFront>(mirror());
      front_vertices = mirror().n_vertices();
      front_faces = mirror().n_faces();
    }
    return *front;
  }
};

RepairSession::RepairSession(const edgefront::VertexArrayView& vertices, const edgefront::FaceArrayView& faces,
                             SessionOptions options)
    : impl_(std::make_unique<Impl>(vertices, faces, std::move(options))) {}
RepairSession::~RepairSession() = default;
RepairSession::RepairSession(RepairSession&&) noexcept = default;
RepairSession& RepairSession::operator=(RepairSession&&) noexcept = default;

const EditRecord& RepairSession::initial_record() const { return impl_->initial; }
const edgefront::ConversionReport& RepairSession::conversion() const { return impl_->converted.report; }

void RepairSession::set_vertex(int v, const std::array<double, 3>& position) {
  if (v < 0) refuse("vertex index " + std::to_string(v) + " is negative");
  impl_->vertex_edits.set(v, position);
}

void RepairSession::set_vertices(std::span<const int> ids, const edgefront::VertexArrayView& positions) {
  positions.check_values("RepairSession::set_vertices positions");
  if (positions.rows() != ids.size()) {
    refuse("set_vertices: " + std::to_string(ids.size()) + " ids for " + std::to_string(positions.rows()) + " positions");
  }
  for (size_t i = 0; i < ids.size(); ++i) {
    if (ids[i] < 0) refuse("vertex index " + std::to_string(ids[i]) + " is negative");
  }
  for (size_t i = 0; i < ids.size(); ++i) impl_->vertex_edits.set(ids[i], std::array<double, 3>{positions.at(i, 0), positions.at(i, 1), positions.at(i, 2)});
}

void RepairSession::set_face(int f, const std::array<int, 3>& corners) {
  if (f < 0) refuse("face index " + std::to_string(f) + " is negative");
  impl_->face_edits.set(f, corners);
}

void RepairSession::remove_face(int f) {
  if (f < 0) refuse("face index " + std::to_string(f) + " is negative");
  impl_->face_edits.set(f, std::nullopt);
}

void RepairSession::remove_vertex(int v) {
  if (v < 0) refuse("vertex index " + std::to_string(v) + " is negative");
  impl_->vertex_edits.set(v, std::nullopt);
}

bool RepairSession::pending() const { return !impl_->face_edits.empty() || !impl_->vertex_edits.empty(); }

EditRecord RepairSession::sync() {
  std::vector<FaceHandle> changed;
  impl_->commit(changed);
  impl_->stats.heal = {};  // no heal here
  return impl_->record(false);
}

EditRecord RepairSession::repair(double mean_edge_length) {
  Impl& s = *impl_;
  if (!(mean_edge_length >= 0) || !std::isfinite(mean_edge_length)) refuse("repair: mean_edge_length must be finite and >= 0");
  std::vector<FaceHandle> changed;
  s.commit(changed);
  const double mel = mean_edge_length > 0 ? mean_edge_length : s.estimated_mean_edge();
  s.stats.report = s.repairer.repair_changed(s.mirror(), changed, mel);
  const bool healed = s.heal(mel);
  const RepairReport& r = s.stats.report;
  return s.record(healed || r.repairs > 0 || r.faces_removed > 0 || r.regions_cut_out > 0 || r.faces_flipped > 0);
}

EditRecord RepairSession::finish() {
  Impl& s = *impl_;
  std::vector<FaceHandle> changed;
  s.commit(changed);
  if (s.options.heal.enabled) s.heal(s.estimated_mean_edge());
  s.healed.clear();  // the full repair looks at every face
  s.stats.report = s.repairer.finish(s.mirror());
  if (s.options.heal.enabled && s.options.heal.grow_rows > 0) {
    // With growth: the holes and slits the full repair opened (flaps peeled, turned patches
    // dropped) are healed once more, without growth (nothing is repaired after it).
    HealOptions again = s.options.heal;
    again.grow_rows = 0;
    std::vector<FaceHandle> added;
    const detail::HealCounts c = detail::heal_borders(s.mirror(), *s.options.repair.detect.reference, s.estimated_mean_edge(), again, added);
    s.stats.heal.strips += c.strips;
    s.stats.heal.holes += c.holes;
    s.stats.heal.faces_added += added.size();
  }
  if (s.options.heal.enabled) s.stats.heal.piece_faces_removed = detail::remove_small_pieces(s.mirror(), s.options.heal.min_piece_share);
  return s.record(true);
}

std::vector<int> RepairSession::detect() {
  Impl& s = *impl_;
  s.require_synced("detect");
  DetectOptions o = s.options.repair.detect;
  o.incremental.restrict_to.reset();
  o.incremental.face_grid = nullptr;
  const DetectResult found = detect_regions(s.mirror(), o);
  std::vector<int> out(s.host.face_slots(), -1);
  for (size_t i = 0; i < found.regions.size(); ++i) {
    for (FaceHandle f : found.regions[i].faces) {
      const int slot = s.host.host_of_face[static_cast<size_t>(f.idx())];
      if (slot >= 0) out[static_cast<size_t>(slot)] = static_cast<int>(i);
    }
  }
  return out;
}

std::optional<double> RepairSession::distance_between(int from, int to, double max_distance) {
  Impl& s = *impl_;
  s.require_synced("distance_between");
  const VertexHandle a = s.query_vertex(from, "distance_between"), b = s.query_vertex(to, "distance_between");
  return edgefront::distance_between(s.distance_front(), a, b, max_distance, s.host.host_of_vertex);
}

edgefront::SparseDistances RepairSession::distances_within(std::span<const int> sources, double max_distance) {
  Impl& s = *impl_;
  s.require_synced("distances_within");
  if (sources.empty()) refuse("distances_within: no source vertex given");
  std::vector<VertexHandle> vs;
  for (int v : sources) vs.push_back(s.query_vertex(v, "distances_within"));
  return edgefront::distances_within(s.distance_front(), vs, max_distance, edgefront::DistanceMethod::Mdf, s.host.host_of_vertex);
}

size_t RepairSession::vertex_slots() const { return impl_->host.vertex_slots(); }
size_t RepairSession::face_slots() const { return impl_->host.face_slots(); }
const SessionStats& RepairSession::stats() const { return impl_->stats; }
const Mesh& RepairSession::mirror() const { return impl_->mirror(); }
VertexHandle RepairSession::mirror_vertex(int v) const {
  return impl_->vertex_alive(v) ? VertexHandle(impl_->host.mirror_of_vertex[static_cast<size_t>(v)]) : VertexHandle();
}
int RepairSession::host_vertex(VertexHandle v) const { return impl_->host.host_vertex(v.idx()); }
edgefront::FaceHandle RepairSession::mirror_face(int f) const {
  return impl_->face_alive(f) ? FaceHandle(impl_->host.mirror_of_face[static_cast<size_t>(f)]) : FaceHandle();
}
int RepairSession::host_face(FaceHandle f) const {
  const auto& map = impl_->host.host_of_face;
  return f.is_valid() && static_cast<size_t>(f.idx()) < map.size() ? map[static_cast<size_t>(f.idx())] : -1;
}

}  // namespace twist
