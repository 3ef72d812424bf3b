#include "edgefront/minimal_edge_front.h"

#include <algorithm>
#include <random>

#include "detail/front_levels.h"
#include "detail/edge_front_core.h"

namespace edgefront {

using detail::EdgeFrontCore;
using detail::kVertexBarrierOnly;
using detail::kVertexSeed;
using detail::VRec;

// Level scheduling (paper, algorithm 2): level k expands every vertex that joined in level k-1,
// all of its occurrences, in the order they joined (or shuffled with `order_seed`).
struct MinimalEdgeFront::Impl : EdgeFrontCore {
  std::vector<uint32_t> due;       // vertices that joined in the last completed level
  std::vector<uint32_t> next_due;  // vertices joining in the level being built
  size_t due_pos = 0;
  int cur = -1;
  int completed = 0;
  bool level_open = false;

  Impl(const Mesh& m, MinimalEdgeFrontOptions o) : EdgeFrontCore(m, o) {}

  int building() const { return completed + 1; }
  void on_join(int v, VRec& rec) override {
    rec.level = building();
    next_due.push_back(static_cast<uint32_t>(v));
  }
  int event_level() const override { return level_open ? building() : completed; }

  void reset(const FrontSource& source) {
    due.clear();
    next_due.clear();
    due_pos = 0;
    cur = -1;
    completed = 0;
    level_open = false;
    reset_structure(source);
    due = sources;
    note_memory();
  }

  bool expand_next_in_level() {
    while (true) {
      if (cur >= 0) {
        VRec* rec = vt.find(static_cast<uint32_t>(cur));
        if (rec && rec->level == completed && !(rec->state & kVertexBarrierOnly)) {
          if ((rec->state & kVertexSeed) && rec->head < 0) {
            expand_seed(cur);
            return true;
          }
          // One single edge expansion per call, so a caller can watch each one.
          const int n = find_active_occurrence(cur);
          if (n >= 0) {
            expand(n);
            return true;
          }
        }
        cur = -1;
      }
      if (due_pos < due.size()) {
        // The connectivity of the vertices a few places ahead is fetched while these expand.
        // Two stages: the front halfedges of the vertex 8 places ahead, the first fan halfedge of
        // each of its wedges 4 places ahead.
        constexpr size_t kNear = 4, kFar = 8;
        if (due_pos + kFar < due.size()) prefetch_occurrences(static_cast<int>(due[due_pos + kFar]), 0);
        if (due_pos + kNear < due.size()) prefetch_occurrences(static_cast<int>(due[due_pos + kNear]), 1);
        cur = static_cast<int>(due[due_pos++]);
        continue;
      }
      return false;
    }
  }

  bool open_level() {
    if (level_open) return true;
    if (due.empty()) return false;
    level_open = true;
    due_pos = 0;
    unit_expansions = 0;
    if (options.order_seed != 0) {
      std::mt19937_64 rng(options.order_seed + static_cast<uint64_t>(completed));
      std::shuffle(due.begin(), due.end(), rng);
    }
    return true;
  }

  void close_level() {
    if (twins.any()) [[unlikely]] join_twins_of_level();
    if (unit_expansions > 0) ++completed;
    level_open = false;
    due.swap(next_due);
    next_due.clear();
    due_pos = 0;
    cur = -1;
    if (unit_expansions == 0) due.clear();
    note_memory();
  }

  bool step() {
    while (true) {
      if (!open_level()) return false;
      if (expand_next_in_level()) return true;
      const bool any = unit_expansions > 0;
      close_level();
      if (!any) return false;
    }
  }

  bool advance_level() {
    if (!open_level()) return false;
    while (expand_next_in_level()) {
    }
    const bool any = unit_expansions > 0;
    close_level();
    return any;
  }

  // A pinched vertex's twins join with it, at the same level (see the header), as seeds: when the
  // level completes (one look per level, not per joining vertex), those that did not join in it
  // themselves (a vertex joins once: one that joined and was enclosed again is not on the front).
  // A loop source's vertex joins again when the front reaches it from behind: its twins started
  // with it (reset_structure).
  std::vector<uint32_t> joined_pinched;  // scratch
  [[gnu::noinline]] void join_twins_of_level() {
    joined_pinched.clear();
    for (uint32_t v : next_due) {
      if (twins.next(static_cast<int>(v)) == static_cast<int>(v)) continue;
      if (std::find(sources.begin(), sources.end(), v) != sources.end()) continue;
      joined_pinched.push_back(v);
    }
    std::sort(joined_pinched.begin(), joined_pinched.end());
    const size_t n = joined_pinched.size();
    for (size_t i = 0; i < n; ++i) {
      twins.for_each_twin(static_cast<int>(joined_pinched[i]), [&](int t) {
        if (!std::binary_search(joined_pinched.begin(), joined_pinched.begin() + static_cast<long>(n),
                                static_cast<uint32_t>(t))) {
          seed_twin(t, true);
        }
      });
    }
  }

  size_t scheduler_bytes() const {
    return (due.capacity() + next_due.capacity() + joined_pinched.capacity()) * sizeof(uint32_t);
  }
};

// ---------------------------------------------------------------------------------------------

MinimalEdgeFront::MinimalEdgeFront(const Mesh& mesh, MinimalEdgeFrontOptions options)
    : impl_(std::make_unique<Impl>(mesh, options)) {}
MinimalEdgeFront::~MinimalEdgeFront() = default;
MinimalEdgeFront::MinimalEdgeFront(MinimalEdgeFront&&) noexcept = default;
MinimalEdgeFront& MinimalEdgeFront::operator=(MinimalEdgeFront&&) noexcept = default;

void MinimalEdgeFront::reset(const FrontSource& source) { impl_->reset(source); }
bool MinimalEdgeFront::step() { return impl_->step(); }
bool MinimalEdgeFront::advance_level() { return impl_->advance_level(); }
FrontStop MinimalEdgeFront::run(int levels) {
  if (levels < 0) {
    while (impl_->advance_level()) {
    }
    return FrontStop::Exhausted;
  }
  for (int i = 0; i < levels; ++i) {
    if (!impl_->advance_level()) return FrontStop::Exhausted;
  }
  return exhausted() ? FrontStop::Exhausted : FrontStop::LevelReached;
}
int MinimalEdgeFront::level() const { return impl_->completed; }
bool MinimalEdgeFront::at_level_boundary() const { return !impl_->level_open; }
bool MinimalEdgeFront::exhausted() const {
  const Impl& m = *impl_;
  if (m.level_open) return false;
  for (uint32_t v : m.due) {
    const VRec* rec = m.vt.find(v);
    if (rec && !(rec->state & kVertexBarrierOnly) &&
        ((rec->state & kVertexSeed) || m.find_active_occurrence(static_cast<int>(v)) >= 0)) {
      return false;
    }
  }
  return true;
}
std::vector<FrontLoop> MinimalEdgeFront::loops() const { return impl_->loops(); }
size_t MinimalEdgeFront::loop_count() const {
  return impl_->options.track_loops ? static_cast<size_t>(impl_->loop_count) : impl_->loops().size();
}
size_t MinimalEdgeFront::front_size() const { return impl_->live_nodes; }
size_t MinimalEdgeFront::peak_front_size() const { return impl_->peak_nodes; }
size_t MinimalEdgeFront::working_memory_bytes() const {
  return impl_->memory_bytes() + impl_->scheduler_bytes();
}
size_t MinimalEdgeFront::peak_working_memory_bytes() const { return impl_->peak_bytes; }
size_t MinimalEdgeFront::expansions() const { return impl_->n_expansions; }
size_t MinimalEdgeFront::minimizations() const { return impl_->n_minimizations; }
size_t MinimalEdgeFront::collisions() const { return impl_->n_collisions; }

std::optional<int> MinimalEdgeFront::front_level(VertexHandle v) const {
  const VRec* rec = impl_->vt.find(static_cast<uint32_t>(v.idx()));
  if (!v.is_valid() || !rec || (rec->state & kVertexBarrierOnly)) return std::nullopt;
  return rec->level;
}
std::vector<std::pair<VertexHandle, int>> MinimalEdgeFront::front_vertices() const {
  std::vector<std::pair<VertexHandle, int>> out;
  impl_->vt.for_each([&](uint32_t v, const VRec& rec) {
    if (!(rec.state & kVertexBarrierOnly)) out.emplace_back(VertexHandle(static_cast<int>(v)), rec.level);
  });
  std::sort(out.begin(), out.end(), [](auto& a, auto& b) { return a.first.idx() < b.first.idx(); });
  return out;
}
void MinimalEdgeFront::set_enclosed_callback(std::function<void(VertexHandle, int)> cb) {
  impl_->on_enclosed = std::move(cb);
}
void MinimalEdgeFront::set_event_callback(std::function<void(const FrontEvent&)> cb) {
  impl_->on_event = std::move(cb);
}
void MinimalEdgeFront::validate() const {
  impl_->validate(impl_->level_open ? std::nullopt : std::optional<int>(impl_->completed));
}

std::vector<int> edge_front_levels(const Mesh& mesh, const FrontSource& source, int max_levels) {
  return detail::join_levels<MinimalEdgeFront>(mesh, source, max_levels);
}

}  // namespace edgefront
