// Connection paths (paper §2.4): two fronts grow alternately from both ends, the first vertex on
// both fronts is the middle, the halves are found recursively. See connection_path.h.

#include "edgefront/connection_path.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <string>

#include "detail/directed_path.h"
#include "detail/flat_map.h"
#include "edgefront/error.h"
#include "edgefront/front_source.h"
#include "edgefront/minimal_distance_front.h"
#include "edgefront/minimal_edge_front.h"
#include "edgefront/vertex_front.h"
#include "edgefront/vertex_twins.h"

namespace edgefront {

namespace {

constexpr int kMaxDepth = 200;  // the recursion halves the path; far beyond any real depth

// One of the two fronts of a search, behind one interface for the three front kinds.
class Side {
 public:
  virtual ~Side() = default;
  virtual void reset(VertexHandle v) = 0;
  // One unit of growth: a complete level (VF, MEF) or one settled vertex (MDF). False when
  // nothing was left to grow.
  virtual bool advance() = 0;
  // The level / distance of `v` if the front still holds it (on the front, or just behind it).
  virtual std::optional<double> known(VertexHandle v) const = 0;
  // Level-based fronts: the vertices on the front now, with their levels.
  virtual void for_each_front(const std::function<void(VertexHandle, double)>& f) const = 0;
  virtual size_t peak_memory() const = 0;
  virtual size_t peak_front() const = 0;
  // Called for every vertex the front processes (encloses / settles), with its level / distance.
  std::function<void(VertexHandle, double)> on_processed;
  size_t processed = 0;
  double radius = 0.0;  // the last processed value
};

// The Vertex Front or the Minimal Edge Front: one level per advance.
template <class Front>
class LevelSide final : public Side {
 public:
  explicit LevelSide(const Mesh& mesh) : front_(mesh) {
    front_.set_enclosed_callback([this](VertexHandle v, int level) {
      ++processed;
      radius = level;
      if (on_processed) on_processed(v, level);
    });
  }
  void reset(VertexHandle v) override {
    front_.reset(FrontSource::vertex(v));
    radius = 0;
  }
  bool advance() override { return front_.advance_level(); }
  std::optional<double> known(VertexHandle v) const override {
    const auto l = front_.front_level(v);
    return l ? std::optional<double>(*l) : std::nullopt;
  }
  void for_each_front(const std::function<void(VertexHandle, double)>& f) const override {
    for (const auto& [v, l] : front_.front_vertices()) f(v, l);
  }
  size_t peak_memory() const override { return front_.peak_working_memory_bytes(); }
  size_t peak_front() const override { return front_.peak_front_size(); }

 private:
  Front front_;
};

class MdfSide final : public Side {
 public:
  explicit MdfSide(const Mesh& mesh) : front_(mesh) {
    front_.set_settled_callback([this](VertexHandle v, double d, const Vec3&) {
      ++processed;
      radius = std::max(radius, d);
      if (on_processed) on_processed(v, d);
    });
  }
  void reset(VertexHandle v) override {
    front_.reset(FrontSource::vertex(v), DistanceOptions{.directions = false});
    radius = 0;
  }
  bool advance() override { return front_.step(); }
  std::optional<double> known(VertexHandle v) const override { return front_.distance(v); }
  void for_each_front(const std::function<void(VertexHandle, double)>&) const override {}
  size_t peak_memory() const override { return front_.peak_working_memory_bytes(); }
  size_t peak_front() const override { return front_.peak_front_size(); }

 private:
  MinimalDistanceFront front_;
};

struct Meeting {
  bool found = false;
  VertexHandle vertex;
  double from_value = 0.0;  // level / distance from the search's first end
  double to_value = 0.0;
};

// Keeps the best meeting vertex: smallest sum, then the most even split, then the lowest index.
bool is_twin(const TwinRing& twins, VertexHandle a, VertexHandle b) {
  bool found = false;
  twins.for_each_twin(a.idx(), [&](int t) { found = found || t == b.idx(); });
  return found;
}
// The same vertex or twins: one point of the surface.
bool same_point(const TwinRing& twins, VertexHandle a, VertexHandle b) { return a == b || is_twin(twins, a, b); }

struct MeetingPicker {
  MeetingPicker(VertexHandle from, VertexHandle to, const TwinRing& ring) : s(from), t(to), twins(ring) {}
  VertexHandle s, t;
  const TwinRing& twins;
  Meeting best;
  // The ends of the enclosing searches: they are on the path already (MDF distances are not a
  // metric; without this a half could choose its parent's other end and recurse forever).
  const std::vector<VertexHandle>* banned = nullptr;
  void consider(VertexHandle v, double a, double b) {
    // Not an end, nor its twin (the same point: no progress).
    if (same_point(twins, v, s) || same_point(twins, v, t)) return;
    if (banned && std::any_of(banned->begin(), banned->end(), [&](VertexHandle e) { return same_point(twins, v, e); })) {
      return;
    }
    if (!best.found) {
      best = Meeting{true, v, a, b};
      return;
    }
    const double sum = a + b, best_sum = best.from_value + best.to_value;
    const double tol = 1e-12 * std::max(1.0, best_sum);
    if (sum < best_sum - tol) {
      best = Meeting{true, v, a, b};
    } else if (sum <= best_sum + tol) {
      const double skew = std::abs(a - b), best_skew = std::abs(best.from_value - best.to_value);
      if (skew < best_skew - tol || (skew <= best_skew + tol && v.idx() < best.vertex.idx())) {
        best = Meeting{true, v, a, b};
      }
    }
  }
};

bool adjacent(const Mesh& mesh, VertexHandle a, VertexHandle b) {
  for (VertexHandle y : mesh.vv_range(a)) {
    if (y == b) return true;
  }
  return false;
}

// When a and b (a != b) are one edge apart with twins counting as one point (the same point, or
// an edge between their groups), appends the vertices after a up to b (a twin of a, the edge's
// far end, b: each step an edge or twins; the fewest) and returns true.
bool one_step(const Mesh& mesh, const TwinRing& twins, VertexHandle a, VertexHandle b, std::vector<VertexHandle>& out) {
  if (adjacent(mesh, a, b) || is_twin(twins, a, b)) {
    out.push_back(b);
    return true;
  }
  if (!twins.any()) return false;
  std::vector<VertexHandle> ga{a}, gb{b};
  twins.for_each_twin(a.idx(), [&](int x) { ga.emplace_back(x); });
  twins.for_each_twin(b.idx(), [&](int x) { gb.emplace_back(x); });
  for (VertexHandle x : ga) {
    for (VertexHandle y : gb) {
      if (!adjacent(mesh, x, y)) continue;
      if (x != a) out.push_back(x);
      out.push_back(y);
      if (y != b) out.push_back(b);
      return true;
    }
  }
  return false;
}

// Drops the detours of a chain through a group of twins (a, b, c of one group: a, c; a, b, a: a).
void compact_twin_runs(const TwinRing& twins, std::vector<VertexHandle>& chain) {
  if (!twins.any()) return;
  std::vector<VertexHandle> out;
  for (size_t i = 0; i < chain.size();) {
    size_t j = i;
    while (j + 1 < chain.size() && is_twin(twins, chain[j], chain[j + 1])) ++j;
    out.push_back(chain[i]);
    if (j > i && chain[j] != chain[i]) out.push_back(chain[j]);
    i = j + 1;
  }
  chain.swap(out);
}

double edge_length_of(const Mesh& mesh, const std::vector<VertexHandle>& chain) {
  double sum = 0.0;
  for (size_t i = 1; i < chain.size(); ++i) sum += (mesh.point(chain[i]) - mesh.point(chain[i - 1])).norm();
  return sum;
}

// The mesh edges of a chain (steps between twins are none).
size_t edge_count(const TwinRing& twins, const std::vector<VertexHandle>& chain) {
  size_t n = 0;
  for (size_t i = 1; i < chain.size(); ++i) n += !is_twin(twins, chain[i - 1], chain[i]);
  return n;
}

}  // namespace

struct ConnectionPathFinder::Impl {
  const Mesh& mesh;
  std::unique_ptr<Side> sides[3][3];  // per method: the two fronts of a search, find_many's source
  detail::DirectedPathSearch directed;
  // find_many: the source's levels / distances over the area its front covered.
  detail::FlatMap<double> source_values;
  // MDF searches: the settled distances of both sides.
  detail::FlatMap<double> settled[2];

  TwinRing twins;                   // pinched vertices (made per query: the mesh may change between)
  ConnectionPath* stats = nullptr;  // the result whose counters a search adds to
  bool recording = false;           // level searches record what they process (confine)
  std::vector<VertexHandle> banned; // ends of the enclosing searches (see MeetingPicker)

  explicit Impl(const Mesh& m) : mesh(m), directed(m), twins(m) {}

  Side& side(PathMethod m, int which) {
    const int i = static_cast<int>(m);
    auto& slot = sides[i][which];
    if (!slot) {
      switch (m) {
        case PathMethod::VertexFront: slot = std::make_unique<LevelSide<VertexFront>>(mesh); break;
        case PathMethod::MinimalEdgeFront: slot = std::make_unique<LevelSide<MinimalEdgeFront>>(mesh); break;
        case PathMethod::MinimalDistance: slot = std::make_unique<MdfSide>(mesh); break;
      }
    }
    return *slot;
  }

  void check_vertex(VertexHandle v, const char* what) const {
    require_attributes(mesh, "connection path");
    if (!is_live(mesh, v)) {
      throw InvalidInput(std::string("connection path: the ") + what + " vertex " + std::to_string(v.idx()) +
                         " is not a live vertex of the mesh (" + std::to_string(mesh.n_vertices()) + " vertices)");
    }
  }
  static void check_options(const ConnectionPathOptions& o) {
    if (!(std::isfinite(o.polyline_band) && o.polyline_band >= 0)) {
      throw InvalidInput("connection path: polyline_band must be finite and not negative, got " +
                         std::to_string(o.polyline_band));
    }
    if (o.polyline_steiner < 0 || o.polyline_steiner > 64) {
      throw InvalidInput("connection path: polyline_steiner must be in 0..64, got " +
                         std::to_string(o.polyline_steiner));
    }
    if (o.max_polyline_flips <= 0) {
      throw InvalidInput("connection path: max_polyline_flips must be positive, got " +
                         std::to_string(o.max_polyline_flips));
    }
  }

  // The bytes of the values a map holds (key and value per vertex; the table's spare capacity,
  // kept across queries, is not counted).
  static size_t values_bytes(const detail::FlatMap<double>& m) { return m.size() * (sizeof(uint32_t) + sizeof(double)); }

  // Working memory: `fronts` bytes of fronts plus `region` bytes of per-vertex values at once.
  void note_memory(size_t fronts, size_t region) {
    stats->region_memory_bytes = std::max(stats->region_memory_bytes, region);
    stats->peak_working_memory_bytes = std::max(stats->peak_working_memory_bytes, fronts + region);
  }

  void account(const Side& a, const Side& b, size_t before_a, size_t before_b) {
    stats->processed += (a.processed - before_a) + (b.processed - before_b);
    stats->peak_front_size = std::max({stats->peak_front_size, a.peak_front(), b.peak_front()});
    stats->peak_front_memory_bytes = std::max({stats->peak_front_memory_bytes, a.peak_memory(), b.peak_memory()});
    note_memory(a.peak_memory() + b.peak_memory(), 0);
    ++stats->searches;
  }

  // Two level-based fronts (VF or MEF) grown alternately, one level each, until a vertex is known
  // to both. At the first level where the closed regions {d_s <= a} and {d_t <= b} meet, a + b is
  // the hop distance, and a vertex on one front is processed by, or on, the other.
  Meeting meet_levels(PathMethod m, VertexHandle s, VertexHandle t) {
    Side& a = side(m, 0);
    Side& b = side(m, 1);
    const size_t pa = a.processed, pb = b.processed;
    a.reset(s);
    b.reset(t);
    MeetingPicker pick(s, t, twins);
    pick.banned = &banned;
    Meeting result;
    if (recording) {
      settled[0].clear();
      settled[1].clear();
    }
    for (int turn = 0;; turn ^= 1) {
      Side& x = turn == 0 ? a : b;
      const Side& y = turn == 0 ? b : a;
      auto check = [&](VertexHandle v, double lx) {
        if (const auto ly = y.known(v)) {
          if (turn == 0) pick.consider(v, lx, *ly);
          else pick.consider(v, *ly, lx);
        }
      };
      x.on_processed = [&](VertexHandle v, double lx) {
        if (recording) settled[turn].insert(static_cast<uint32_t>(v.idx()), lx);
        check(v, lx);
      };
      const bool grew = x.advance();
      x.on_processed = nullptr;
      if (!grew) break;  // this side's component is exhausted without meeting: no path
      x.for_each_front(check);
      if (pick.best.found) {
        result = pick.best;
        break;
      }
    }
    account(a, b, pa, pb);
    if (recording) {
      note_memory(a.peak_memory() + b.peak_memory(), values_bytes(settled[0]) + values_bytes(settled[1]));
    }
    return result;
  }

  // Confinement: the half of the path from the meeting vertex `m` (value `vm` on `side`) back to
  // that side's end `e`, traced inside the region the side's front processed (recorded in
  // `settled[side]`): each step goes to a neighbour one level lower (levels) or to the neighbour
  // with the smallest distance plus edge length among those with a smaller distance (MDF). The
  // neighbours of a vertex's twins count as its own (a twin has the same value): a step through
  // one puts the twin into the chain first. Appends m .. e; false when the region has no way down
  // (the caller then searches).
  bool trace(int side, bool levels, VertexHandle m, double vm, VertexHandle e, std::vector<VertexHandle>& out) const {
    return trace_in(settled[side], levels, m, vm, e, out);
  }
  bool trace_in(const detail::FlatMap<double>& values, bool levels, VertexHandle m, double vm, VertexHandle e,
                std::vector<VertexHandle>& out) const {
    out.assign(1, m);
    VertexHandle v = m;
    double dv = vm;
    const size_t limit = values.size() + 2;
    while (v != e) {
      if (out.size() > limit) return false;
      VertexHandle next, via;
      double best = std::numeric_limits<double>::infinity(), dnext = 0;
      auto look = [&](VertexHandle w) {  // the neighbours of v or of its twin w
        for (VertexHandle u : mesh.vv_range(w)) {
          const double* du = values.find(static_cast<uint32_t>(u.idx()));
          if (!du) continue;
          if (levels) {
            if (*du != dv - 1) continue;
            if (!next.is_valid() || u.idx() < next.idx()) {
              next = u;
              via = w;
              dnext = *du;
            }
          } else {
            if (!(*du < dv)) continue;
            const double key = *du + (mesh.point(u) - mesh.point(w)).norm();
            if (key < best) {
              best = key;
              next = u;
              via = w;
              dnext = *du;
            }
          }
        }
      };
      look(v);
      twins.for_each_twin(v.idx(), [&](int t) {
        if (VertexHandle(t) == e) {  // the end is this point
          next = via = e;
          dnext = dv;
        } else if (next != e) {
          look(VertexHandle(t));
        }
      });
      if (!next.is_valid()) return false;
      if (via != v) out.push_back(via);
      if (next != via) out.push_back(next);
      v = next;
      dv = dnext;
    }
    return true;
  }

  // Two MDFs, the one with the smaller radius grows by one settled vertex, until the radii sum
  // reaches the best meeting (bidirectional Dijkstra's stopping rule on the MDF's distances).
  Meeting meet_distance(VertexHandle s, VertexHandle t) {
    Side& a = side(PathMethod::MinimalDistance, 0);
    Side& b = side(PathMethod::MinimalDistance, 1);
    const size_t pa = a.processed, pb = b.processed;
    a.reset(s);
    b.reset(t);
    MeetingPicker pick(s, t, twins);
    pick.banned = &banned;
    // The fronts forget settled vertices once their neighbours are settled; the meeting test
    // remembers the settled distances of both sides so that a vertex met late still pairs two
    // final distances (with the fronts' memory alone the sums came out up to 3% longer).
    settled[0].clear();
    settled[1].clear();
    auto other_value = [&](int side, VertexHandle v) -> std::optional<double> {
      if (const double* d = settled[side].find(static_cast<uint32_t>(v.idx()))) return *d;
      return (side == 0 ? a : b).known(v);
    };
    a.on_processed = [&](VertexHandle v, double d) {
      settled[0].insert(static_cast<uint32_t>(v.idx()), d);
      if (const auto o = other_value(1, v)) pick.consider(v, d, *o);
    };
    b.on_processed = [&](VertexHandle v, double d) {
      settled[1].insert(static_cast<uint32_t>(v.idx()), d);
      if (const auto o = other_value(0, v)) pick.consider(v, *o, d);
    };
    bool alive[2] = {true, true};
    while (alive[0] || alive[1]) {
      if (pick.best.found && a.radius + b.radius >= pick.best.from_value + pick.best.to_value) break;
      int which = !alive[0] ? 1 : !alive[1] ? 0 : (b.radius < a.radius ? 1 : 0);
      if (!(which == 0 ? a : b).advance()) {
        alive[which] = false;
        if (!pick.best.found) break;  // one component exhausted, nothing met: no path
      }
    }
    a.on_processed = nullptr;
    b.on_processed = nullptr;
    account(a, b, pa, pb);
    note_memory(a.peak_memory() + b.peak_memory(), values_bytes(settled[0]) + values_bytes(settled[1]));
    return pick.best;
  }

  Meeting meet(PathMethod m, VertexHandle s, VertexHandle t) {
    return m == PathMethod::MinimalDistance ? meet_distance(s, t) : meet_levels(m, s, t);
  }

  // Appends the path s..t without s (s and t connected), recursing on both halves.
  void build(PathMethod m, VertexHandle s, VertexHandle t, int depth, std::vector<VertexHandle>& out) {
    if (s == t || one_step(mesh, twins, s, t, out)) return;
    Meeting mid;
    if (depth < kMaxDepth) mid = meet(m, s, t);
    if (!mid.found) {
      // Only MDF halves can get here (every candidate on the path already, or too deep): the
      // shortest edge path by the directed search closes the gap.
      const auto d = directed.find(s, t, m != PathMethod::MinimalDistance);
      EF_CHECK(!d.vertices.empty(), "the halves of a found connection path are not connected");
      stats->processed += d.processed;
      ++stats->searches;
      out.insert(out.end(), d.vertices.begin() + 1, d.vertices.end());
      return;
    }
    banned.push_back(s);
    banned.push_back(t);
    build(m, s, mid.vertex, depth + 1, out);
    build(m, mid.vertex, t, depth + 1, out);
    banned.pop_back();
    banned.pop_back();
  }

  void finish(const Mesh& msh, ConnectionPath& r, const ConnectionPathOptions& o, bool length_is_estimate) {
    r.status = PathStatus::Found;
    compact_twin_runs(twins, r.vertices);
    r.edges = edge_count(twins, r.vertices);
    r.edge_length = edge_length_of(msh, r.vertices);
    if (!length_is_estimate) r.length = r.edge_length;
    if (o.polyline) {
      r.polyline = geodesic_polyline(msh, r.vertices, o.max_polyline_flips, &r.polyline_converged);
      r.polyline_length = polyline_length(r.polyline);
      if (o.method == PathMethod::MinimalDistance && !o.directed && r.edges >= 2) {
        // A second corridor: the shortest edge path's (directed search). Straightening converges
        // to a locally shortest path; starting from two corridors and keeping the shorter misses
        // the global one less often (elephant: 99.6% instead of 99.0% of pairs within 0.5%).
        const auto d = directed.find(r.vertices.front(), r.vertices.back(), false);
        r.processed += d.processed;
        bool converged = false;
        auto other = geodesic_polyline(msh, d.vertices, o.max_polyline_flips, &converged);
        const double len = polyline_length(other);
        if (len < r.polyline_length) {
          r.polyline.swap(other);
          r.polyline_length = len;
          r.polyline_converged = converged;
        }
      }
      if (o.polyline_band > 0 && r.polyline.size() >= 3) {
        size_t band = 0;
        bool converged = false;
        auto wide = band_polyline(msh, r.polyline, o.polyline_band * r.polyline_length, o.polyline_steiner,
                                  o.max_polyline_flips, &converged, &band);
        r.processed += band;
        const double len = polyline_length(wide);
        if (len < r.polyline_length) {
          r.polyline.swap(wide);
          r.polyline_length = len;
          r.polyline_converged = converged;
        }
      }
      r.length = r.polyline_length;
    }
  }

  ConnectionPath find(VertexHandle from, VertexHandle to, const ConnectionPathOptions& o) {
    check_vertex(from, "from");
    check_vertex(to, "to");
    check_options(o);
    twins = TwinRing(mesh);
    ConnectionPath r;
    stats = &r;
    r.vertices = {from};
    if (from == to || one_step(mesh, twins, from, to, r.vertices)) {
      finish(mesh, r, o, false);
      return r;
    }
    r.vertices.clear();
    if (o.directed) {
      const bool hops = o.method != PathMethod::MinimalDistance;
      const auto d = directed.find(from, to, hops);
      r.processed = d.processed;
      r.searches = 1;
      r.peak_working_memory_bytes = r.region_memory_bytes = d.memory_bytes;
      if (d.vertices.empty()) return r;
      r.vertices = d.vertices;
      finish(mesh, r, o, false);
      return r;
    }
    banned.clear();
    recording = o.confine;
    const Meeting top = meet(o.method, from, to);
    recording = false;
    if (!top.found) return r;
    banned = {from, to};
    const bool levels = o.method != PathMethod::MinimalDistance;
    // The MDF's meeting test keeps both sides' settled distances anyway: tracing the halves down
    // them is free of new searches (the default); level fronts record them only with `confine`.
    const bool tracing = o.confine || (!levels && !o.mdf_recursion);
    std::vector<VertexHandle> half[2];
    const bool traced[2] = {tracing && trace(0, levels, top.vertex, top.from_value, from, half[0]),
                            tracing && trace(1, levels, top.vertex, top.to_value, to, half[1])};
    if (traced[0]) {
      r.vertices.assign(half[0].rbegin(), half[0].rend());  // from .. m
    } else {
      r.vertices.push_back(from);
      build(o.method, from, top.vertex, 1, r.vertices);
    }
    if (traced[1]) {
      r.vertices.insert(r.vertices.end(), half[1].begin() + 1, half[1].end());  // after m .. to
    } else {
      build(o.method, top.vertex, to, 1, r.vertices);
    }
    const bool estimate = o.method == PathMethod::MinimalDistance;
    if (estimate) r.length = top.from_value + top.to_value;
    finish(mesh, r, o, estimate);
    return r;
  }

  std::vector<ConnectionPath> find_many(VertexHandle from, const std::vector<VertexHandle>& targets,
                                        const ConnectionPathOptions& o) {
    check_vertex(from, "from");
    for (VertexHandle t : targets) check_vertex(t, "target");
    check_options(o);
    twins = TwinRing(mesh);
    banned.clear();
    std::vector<ConnectionPath> out(targets.size());
    if (targets.empty()) return out;
    const bool distance = o.method == PathMethod::MinimalDistance;

    // One source front for all targets, grown only when a target is not processed yet, and kept
    // between targets; it records the levels / distances of what it processes. Each path is then
    // traced from its target down those values to the source: no front per target.
    Side& src = side(o.method, 2);
    source_values.clear();
    src.reset(from);
    src.on_processed = [&](VertexHandle v, double d) { source_values.insert(static_cast<uint32_t>(v.idx()), d); };
    bool alive = true;
    std::vector<VertexHandle> chain;
    for (size_t i = 0; i < targets.size(); ++i) {
      ConnectionPath& r = out[i];
      stats = &r;
      const VertexHandle t = targets[i];
      const size_t p0 = src.processed;
      const uint32_t key = static_cast<uint32_t>(t.idx());
      while (alive && !source_values.contains(key)) alive = src.advance();
      r.processed += src.processed - p0;
      r.searches = src.processed > p0 ? 1 : 0;
      r.peak_front_size = src.peak_front();
      r.peak_front_memory_bytes = src.peak_memory();
      note_memory(src.peak_memory(), values_bytes(source_values));
      r.vertices = {from};
      if (t == from || one_step(mesh, twins, from, t, r.vertices)) {
        finish(mesh, r, o, false);
        continue;
      }
      r.vertices.clear();
      const double* dt = source_values.find(key);
      if (!dt) continue;  // the source's component is exhausted without it: no path
      const double length = *dt;
      if (trace_in(source_values, !distance, t, length, from, chain)) {
        r.vertices.assign(chain.rbegin(), chain.rend());
        if (distance) r.length = length;
        finish(mesh, r, o, distance);
      } else {
        // Only MDF ties (a vertex without a strictly nearer processed neighbour) get here.
        src.on_processed = nullptr;
        ConnectionPathOptions single_options = o;
        single_options.directed = single_options.confine = false;
        const ConnectionPath single = find(from, t, single_options);
        src.on_processed = [&](VertexHandle v, double d) {
          source_values.insert(static_cast<uint32_t>(v.idx()), d);
        };
        ConnectionPath merged = single;
        merged.processed += r.processed;
        merged.peak_front_size = std::max(r.peak_front_size, single.peak_front_size);
        merged.peak_front_memory_bytes = std::max(r.peak_front_memory_bytes, single.peak_front_memory_bytes);
        merged.region_memory_bytes = std::max(r.region_memory_bytes, single.region_memory_bytes);
        merged.peak_working_memory_bytes = std::max(r.peak_working_memory_bytes,
                                                    single.peak_working_memory_bytes + r.peak_working_memory_bytes);
        r = std::move(merged);
      }
    }
    src.on_processed = nullptr;
    return out;
  }
};

ConnectionPathFinder::ConnectionPathFinder(const Mesh& mesh) : impl_(std::make_unique<Impl>(mesh)) {}
ConnectionPathFinder::~ConnectionPathFinder() = default;
ConnectionPathFinder::ConnectionPathFinder(ConnectionPathFinder&&) noexcept = default;
ConnectionPathFinder& ConnectionPathFinder::operator=(ConnectionPathFinder&&) noexcept = default;

ConnectionPath ConnectionPathFinder::find(VertexHandle from, VertexHandle to, const ConnectionPathOptions& options) {
  return impl_->find(from, to, options);
}

std::vector<ConnectionPath> ConnectionPathFinder::find_many(VertexHandle from, const std::vector<VertexHandle>& targets,
                                                            const ConnectionPathOptions& options) {
  return impl_->find_many(from, targets, options);
}

ConnectionPath connection_path(const Mesh& mesh, VertexHandle from, VertexHandle to,
                               const ConnectionPathOptions& options) {
  ConnectionPathFinder finder(mesh);
  return finder.find(from, to, options);
}

}  // namespace edgefront
