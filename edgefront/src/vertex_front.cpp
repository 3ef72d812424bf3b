#include "edgefront/vertex_front.h"

#include <algorithm>
#include <string>

#include "detail/front_levels.h"
#include "detail/flat_map.h"
#include "detail/prefetch.h"
#include "edgefront/error.h"
#include "edgefront/vertex_twins.h"

namespace edgefront {

namespace {
constexpr uint8_t kOld = 1;      // processed in the previous level
constexpr uint8_t kFront = 2;    // joined in the last completed level, to be processed now
constexpr uint8_t kNew = 3;      // joined in the level being built
constexpr uint8_t kBarrier = 4;  // a loop source vertex: never re-entered
}  // namespace

struct VertexFront::Impl {
  const Mesh& mesh;
  detail::FlatMap<uint8_t> state;
  std::vector<uint32_t> old_list, front_list, new_list;
  size_t pos = 0;
  int completed = 0;
  bool level_open = false;
  size_t level_steps = 0;
  size_t peak_front = 0;
  size_t peak_bytes = 0;
  bool loop_source = false;
  std::vector<HalfedgeHandle> loop;  // loop source: ahead wedges for the first level
  std::function<void(VertexHandle, int)> on_enclosed;
  // A pinched vertex's twins (one point of the surface) join with it, at the same level (when the
  // level closes).
  TwinRing twins;

  explicit Impl(const Mesh& m) : mesh(m), twins(m) {}

  // Adds the twins of vertex `v` that the front does not know yet with `state` to `list`.
  [[gnu::noinline]] void add_twins(uint32_t v, uint8_t s, std::vector<uint32_t>& list) {
    twins.for_each_twin(static_cast<int>(v), [&](int t) {
      if (this->state.insert(static_cast<uint32_t>(t), s).second) list.push_back(static_cast<uint32_t>(t));
    });
  }

  void reset(const FrontSource& source) {
    validate_source(mesh, source);
    state.clear();
    old_list.clear();
    front_list.clear();
    new_list.clear();
    pos = 0;
    completed = 0;
    level_open = false;
    peak_front = 0;
    peak_bytes = 0;
    loop_source = source.is_loop();
    loop = source.loop;
    twins = TwinRing(mesh);
    if (loop_source) {
      for (HalfedgeHandle h : loop) {
        const auto v = static_cast<uint32_t>(mesh.to_vertex_handle(h).idx());
        state.insert(v, kBarrier);
        front_list.push_back(v);
      }
    } else {
      for (VertexHandle v : source.vertices) {
        state.insert(static_cast<uint32_t>(v.idx()), kFront);
        front_list.push_back(static_cast<uint32_t>(v.idx()));
      }
    }
    // Twins of the sources are sources (a loop vertex's twins start with their whole fans).
    if (twins.any()) {
      const size_t given = front_list.size();
      for (size_t i = 0; i < given; ++i) add_twins(front_list[i], kFront, front_list);
    }
    note();
  }

  void visit_neighbour(VertexHandle y) {
    auto [st, inserted] = state.insert(static_cast<uint32_t>(y.idx()), kNew);
    if (inserted) new_list.push_back(static_cast<uint32_t>(y.idx()));
  }

  // Look-ahead for the level being processed: the vertex record of the vertex 8 places ahead, its
  // first outgoing halfedge 4 places ahead (the circulator's first loads; the mesh does not fit in
  // cache).
  void prefetch_ahead() const {
    constexpr size_t kNear = 4, kFar = 8;
    if (pos + kFar < front_list.size()) {
      detail::prefetch(&mesh.vertex(VertexHandle(static_cast<int>(front_list[pos + kFar]))));
    }
    if (pos + kNear < front_list.size()) {
      const HalfedgeHandle h = mesh.halfedge_handle(VertexHandle(static_cast<int>(front_list[pos + kNear])));
      if (h.is_valid()) detail::prefetch(&mesh.halfedge(h));
    }
  }

  void process(uint32_t x) {
    const VertexHandle vx(static_cast<int>(x));
    if (loop_source && completed == 0 && *state.find(x) == kBarrier) {
      // First level from a line: only the fan ahead of the loop at this vertex.
      const size_t n = loop.size();
      for (size_t i = 0; i < n; ++i) {
        if (static_cast<uint32_t>(mesh.to_vertex_handle(loop[i]).idx()) != x) continue;
        HalfedgeHandle g = mesh.next_halfedge_handle(loop[i]);
        const HalfedgeHandle h2 = loop[(i + 1) % n];
        while (true) {
          visit_neighbour(mesh.to_vertex_handle(g));
          if (g == h2) break;
          g = mesh.next_halfedge_handle(mesh.opposite_halfedge_handle(g));
        }
      }
    } else {
      for (VertexHandle y : mesh.vv_range(vx)) visit_neighbour(y);
    }
    if (on_enclosed) on_enclosed(vx, completed);
  }

  bool step() {
    while (true) {
      if (!level_open) {
        if (front_list.empty()) return false;
        level_open = true;
        pos = 0;
        level_steps = 0;
      }
      if (pos < front_list.size()) {
        prefetch_ahead();
        process(front_list[pos++]);
        ++level_steps;
        peak_front = std::max(peak_front, front_list.size() - pos + new_list.size());
        return true;
      }
      close_level();
    }
  }

  void close_level() {
    // The twins of the vertices that joined in this level join with them (one look per level).
    if (twins.any()) [[unlikely]] {
      const size_t joined = new_list.size();
      for (size_t i = 0; i < joined; ++i) add_twins(new_list[i], kNew, new_list);
    }
    // Swap containers: old <- front, front <- new. Entries of the old level are forgotten: on a
    // manifold the neighbours of the new front lie in old, front or new (paper, algorithm 1).
    for (uint32_t v : old_list) {
      uint8_t* s = state.find(v);
      if (s && *s == kOld) state.erase(v);
    }
    old_list.swap(front_list);
    for (uint32_t v : old_list) {
      uint8_t* s = state.find(v);
      if (s && *s == kFront) *s = kOld;
    }
    front_list.swap(new_list);
    new_list.clear();
    for (uint32_t v : front_list) *state.find(v) = kFront;
    if (level_steps > 0) ++completed;
    level_open = false;
    note();
  }

  bool advance_level() {
    if (!level_open) {
      if (front_list.empty()) return false;
      level_open = true;
      pos = 0;
      level_steps = 0;
    }
    while (pos < front_list.size()) {
      prefetch_ahead();
      process(front_list[pos++]);
      ++level_steps;
    }
    peak_front = std::max(peak_front, new_list.size());
    const bool any = level_steps > 0;
    close_level();
    return any;
  }

  size_t memory() const {
    return state.memory_bytes() + (old_list.capacity() + front_list.capacity() + new_list.capacity()) * 4;
  }
  void note() { peak_bytes = std::max(peak_bytes, memory()); }
};

VertexFront::VertexFront(const Mesh& mesh) : impl_(std::make_unique<Impl>(mesh)) {}
VertexFront::~VertexFront() = default;
VertexFront::VertexFront(VertexFront&&) noexcept = default;
VertexFront& VertexFront::operator=(VertexFront&&) noexcept = default;
void VertexFront::reset(const FrontSource& source) { impl_->reset(source); }
bool VertexFront::step() { return impl_->step(); }
bool VertexFront::advance_level() { return impl_->advance_level(); }
int VertexFront::run(int levels) {
  int done = 0;
  while ((levels < 0 || done < levels) && impl_->advance_level()) ++done;
  return done;
}
int VertexFront::level() const { return impl_->completed; }
bool VertexFront::exhausted() const {
  return !impl_->level_open ? impl_->front_list.empty()
                            : impl_->pos >= impl_->front_list.size() && impl_->new_list.empty();
}
size_t VertexFront::front_size() const {
  return impl_->front_list.size() - std::min(impl_->pos, impl_->front_list.size()) + impl_->new_list.size();
}
size_t VertexFront::peak_front_size() const { return impl_->peak_front; }
size_t VertexFront::working_memory_bytes() const { return impl_->memory(); }
size_t VertexFront::peak_working_memory_bytes() const { return impl_->peak_bytes; }
std::optional<int> VertexFront::front_level(VertexHandle v) const {
  const uint8_t* s = impl_->state.find(static_cast<uint32_t>(v.idx()));
  if (!s) return std::nullopt;
  const int c = impl_->completed;
  switch (*s) {
    case kOld: return c - 1;
    case kFront: return c;
    case kNew: return c + 1;
    default: return 0;  // kBarrier: a loop source vertex
  }
}
std::vector<std::pair<VertexHandle, int>> VertexFront::front_vertices() const {
  const Impl& m = *impl_;
  std::vector<std::pair<VertexHandle, int>> out;
  for (size_t i = m.level_open ? m.pos : 0; i < m.front_list.size(); ++i) {
    out.emplace_back(VertexHandle(static_cast<int>(m.front_list[i])), m.completed);
  }
  for (uint32_t v : m.new_list) out.emplace_back(VertexHandle(static_cast<int>(v)), m.completed + 1);
  return out;
}
void VertexFront::set_enclosed_callback(std::function<void(VertexHandle, int)> cb) {
  impl_->on_enclosed = std::move(cb);
}

void VertexFront::validate() const {
  const Impl& m = *impl_;
  auto fail = [](const std::string& what) { throw InternalError("vertex front invariant broken: " + what); };
  size_t n_old = 0, n_front = 0, n_new = 0;
  m.state.for_each([&](uint32_t, uint8_t s) {
    n_old += s == kOld;
    n_front += s == kFront;
    n_new += s == kNew;
  });
  if (n_new != m.new_list.size()) fail("the new set and its list differ");
  for (uint32_t v : m.front_list) {
    const uint8_t* s = m.state.find(v);
    if (!s || (*s != kFront && *s != kBarrier)) fail("vertex " + std::to_string(v) + " listed in the front is not marked");
  }
  if (!m.level_open && !m.loop_source && m.completed > 0) {
    // Completed level L: every vertex of the front (hop distance L) has a neighbour processed in
    // level L-1 (it or one of its twins, which joined with it), and no neighbour that was
    // forgotten as "older" than that could be new.
    for (uint32_t v : m.front_list) {
      bool has_old = false;
      auto look = [&](int u) {
        for (VertexHandle y : m.mesh.vv_range(VertexHandle(u))) {
          const uint8_t* s = m.state.find(static_cast<uint32_t>(y.idx()));
          has_old = has_old || (s && *s == kOld);
        }
      };
      look(static_cast<int>(v));
      m.twins.for_each_twin(static_cast<int>(v), look);
      if (!has_old) fail("front vertex " + std::to_string(v) + " has no neighbour in the previous level");
    }
  }
  (void)n_old;
  (void)n_front;
}

std::vector<int> vertex_front_levels(const Mesh& mesh, const FrontSource& source, int max_levels) {
  return detail::join_levels<VertexFront>(mesh, source, max_levels);
}

}  // namespace edgefront
