#pragma once
// The edge-front core shared by the Minimal Edge Front and the Minimal Distance Front. Internal.

#include <algorithm>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "detail/flat_map.h"
#include "detail/prefetch.h"
#include "edgefront/error.h"
#include "edgefront/front_source.h"
#include "edgefront/mesh.h"
#include "edgefront/minimal_edge_front.h"
#include "edgefront/vertex_twins.h"

namespace edgefront::detail {


constexpr uint8_t kNodeLive = 1;
constexpr uint8_t kNodeAttached = 2;  // listed at its end vertex in the vertex table
constexpr uint8_t kNodeSource = 4;    // an original halfedge of a loop source
constexpr uint8_t kNodeBarrier = 8;   // the reversed twin of a loop source halfedge: never expands

constexpr uint8_t kVertexSeed = 1;         // a source vertex not expanded yet
constexpr uint8_t kVertexBarrierOnly = 2;  // only barrier occurrences left
constexpr uint8_t kVertexReported = 4;     // the enclosed callback has seen this join
constexpr uint8_t kVertexOnLoop = 8;       // a vertex of a loop source (may join twice: both sides)

struct Node {
  int he = -1;
  int to = -1;  // tov(he), kept here so that the hot paths need not reload the halfedge
  int prev = -1;
  int next = -1;
  int vnext = -1;  // next incoming node at the same end vertex
  uint8_t flags = 0;
};

struct VRec {
  int head = -1;  // first incoming node at this vertex
  int level = 0;
  uint8_t state = 0;
};

inline std::string vname(int v) { return "vertex " + std::to_string(v); }


// The loops of an edge front and their surgery: single edge expansion, minimization, collisions,
// annihilation, borders and loop-source barriers (paper §2.2). What to expand next is up to the
// scheduler that derives from it (levels for the MEF, distances for the MDF).
class EdgeFrontCore {
 public:
  const Mesh& mesh;
  MinimalEdgeFrontOptions options;

  std::vector<Node> nodes;
  std::vector<int> free_nodes;
  size_t live_nodes = 0;
  size_t peak_nodes = 0;
  size_t peak_bytes = 0;

  detail::FlatMap<VRec> vt;

  size_t n_expansions = 0;
  size_t n_minimizations = 0;
  size_t n_collisions = 0;
  long loop_count = 0;

  // scratch
  std::vector<int> seg;
  std::vector<int> seg_to;  // tov(seg[i]), known from the fan walk without loading seg[i]
  std::vector<int> dirty;
  std::vector<int> collided;
  std::vector<int> ins;
  std::vector<int> outs;
  std::vector<int> partner;

  std::vector<uint8_t> dbg_enclosed;  // debug_tracking only

  std::function<void(VertexHandle, int)> on_enclosed;
  std::function<void(const FrontEvent&)> on_event;

  // Pinched vertices split into twins (edgefront/vertex_twins.h): one point of the surface. A twin
  // that joins the front as a seed (seed_twin) expands its whole fan into a loop of its own, like a
  // source vertex. When they join is the scheduler's (the MEF: at the end of the level a group
  // member joined in; the MDF: when a member settles).
  TwinRing twins;

  EdgeFrontCore(const Mesh& m, MinimalEdgeFrontOptions o) : mesh(m), options(o), twins(m) {}
  virtual ~EdgeFrontCore() = default;
  EdgeFrontCore(const EdgeFrontCore&) = delete;
  EdgeFrontCore& operator=(const EdgeFrontCore&) = delete;

  // ---- scheduler hooks ----
  // A vertex joins the front (a new record) or a loop-source vertex joins again from behind.
  virtual void on_join(int v, VRec& rec) = 0;
  // The level reported with events.
  virtual int event_level() const = 0;
  // Expansions counted in the current scheduling unit (a level for the MEF).
  size_t unit_expansions = 0;

  // ---- mesh helpers (indices) ----
  int nexth(int h) const { return mesh.next_halfedge_handle(HalfedgeHandle(h)).idx(); }
  int prevh(int h) const { return mesh.prev_halfedge_handle(HalfedgeHandle(h)).idx(); }
  int opph(int h) const { return h ^ 1; }
  int tov(int h) const { return mesh.to_vertex_handle(HalfedgeHandle(h)).idx(); }
  int fromv(int h) const { return mesh.from_vertex_handle(HalfedgeHandle(h)).idx(); }
  bool has_face(int h) const { return mesh.face_handle(HalfedgeHandle(h)).is_valid(); }
  // Memory hints: the mesh's connectivity is the working set that does not fit in cache, and the
  // fan walks know a few loads ahead which records they will need.
  void prefetch_halfedge(int h) const { prefetch(&mesh.halfedge(HalfedgeHandle(h))); }
  void prefetch_vertex(int v) const { prefetch(&mesh.vertex(VertexHandle(v))); }
  void emit(FrontEvent::Kind k, int v) {
    if (on_event) on_event(FrontEvent{k, VertexHandle(v), event_level()});
  }

  // ---- node pool ----
  int new_node(int he, uint8_t flags) { return new_node(he, flags, tov(he)); }
  // `to` must be tov(he); the hot paths know it without loading the halfedge.
  int new_node(int he, uint8_t flags, int to) {
    int id;
    if (!free_nodes.empty()) {
      id = free_nodes.back();
      free_nodes.pop_back();
    } else {
      id = static_cast<int>(nodes.size());
      nodes.emplace_back();
    }
    Node& n = nodes[id];
    n.he = he;
    n.to = to;
    n.prev = n.next = n.vnext = -1;
    n.flags = static_cast<uint8_t>(kNodeLive | flags);
    ++live_nodes;
    peak_nodes = std::max(peak_nodes, live_nodes);
    return id;
  }
  void free_node(int id) {
    detach(id);
    nodes[id].flags = 0;
    free_nodes.push_back(id);
    --live_nodes;
  }
  void link(int a, int b) {
    nodes[a].next = b;
    nodes[b].prev = a;
  }

  // ---- vertex table ----
  // Lists node `id` at its end vertex, creating the vertex record (a new join) when absent.
  // Returns true when the vertex already had other incoming nodes (a collision candidate).
  bool attach(int id) {
    const int v = nodes[id].to;
    auto [rec, inserted] = vt.insert(static_cast<uint32_t>(v), VRec{});
    bool had_nodes = false;
    if (inserted) {
      check_joining(v);
      rec->state = 0;
      on_join(v, *rec);
      if (options.debug_tracking) {
        EF_CHECK(!dbg_enclosed[v], "vertex " + std::to_string(v) + " joins the front after it was enclosed");
      }
    } else {
      had_nodes = rec->head >= 0;
      if (rec->state & kVertexBarrierOnly) {
        // The front reached a loop source's barrier from behind: the vertex joins again on that side.
        rec->state = kVertexOnLoop;
        on_join(v, *rec);
      }
      rec->state &= static_cast<uint8_t>(~kVertexSeed);
    }
    nodes[id].vnext = rec->head;
    rec->head = id;
    nodes[id].flags |= kNodeAttached;
    return had_nodes;
  }

  // Twin `t` of a vertex that joined (or settled) joins the front as a seed, unless it is on the
  // front already. Returns whether it joined. `event`: report a Pinch event.
  [[gnu::noinline]] bool seed_twin(int t, bool event) {
    auto [rec, inserted] = vt.insert(static_cast<uint32_t>(t), VRec{});
    if (!inserted) return false;
    check_joining(t);
    rec->state = kVertexSeed;
    on_join(t, *rec);
    if (options.debug_tracking) {
      EF_CHECK(!dbg_enclosed[t], "vertex " + std::to_string(t) + " joins the front after it was enclosed");
    }
    if (event) emit(FrontEvent::Kind::Pinch, t);
    return true;
  }
  void detach(int id) {
    Node& n = nodes[id];
    if (!(n.flags & kNodeAttached)) return;
    n.flags &= static_cast<uint8_t>(~kNodeAttached);
    VRec* rec = vt.find(static_cast<uint32_t>(n.to));
    EF_CHECK(rec != nullptr, "attached node without vertex record");
    int* p = &rec->head;
    while (*p != id) {
      EF_CHECK(*p >= 0, "node missing from its vertex list");
      p = &nodes[*p].vnext;
    }
    *p = n.vnext;
    n.vnext = -1;
  }
  void erase_vertex(int v) {
    VRec* rec = vt.find(static_cast<uint32_t>(v));
    if (!rec) return;
    for (int id = rec->head; id >= 0;) {
      const int nx = nodes[id].vnext;
      nodes[id].flags &= static_cast<uint8_t>(~kNodeAttached);
      nodes[id].vnext = -1;
      id = nx;
    }
    vt.erase(static_cast<uint32_t>(v));
  }

  // ---- occurrence classification ----
  bool occ_inert(int n_in) const {
    const int h1 = nodes[n_in].he;
    const int h2 = nodes[nodes[n_in].next].he;
    return !has_face(h1) && !has_face(h2);
  }
  bool occ_barrier(int n_in) const {
    return (nodes[n_in].flags & kNodeBarrier) && (nodes[nodes[n_in].next].flags & kNodeBarrier);
  }
  bool occ_active(int n_in) const { return !occ_inert(n_in) && !occ_barrier(n_in); }
  bool false_spike(int a, int b) const {
    const uint8_t fa = nodes[a].flags, fb = nodes[b].flags;
    return ((fa & kNodeSource) && (fb & kNodeBarrier)) || ((fa & kNodeBarrier) && (fb & kNodeSource));
  }

  // ---- non-manifold vertices ----
  // OpenMesh represents only vertex non-manifoldness (several border gaps at one vertex); a front
  // refuses such a vertex when it joins. Checking every joining vertex costs two dependent cache
  // misses (its outgoing halfedge, then that halfedge's face), about 15% of a full MEF sweep. So a
  // query that has checked an eighth of the mesh's vertices checks the whole mesh once instead (one
  // sequential pass over the halfedges, cheaper than the remaining checks) and, if no vertex is
  // non-manifold, checks nothing more in this query. Smaller queries never get there: their cost
  // stays proportional to what they visit. Nothing is kept across queries (the mesh may change
  // between them).
  size_t manifold_checks_left = 0;  // per-vertex checks before the whole-mesh pass
  bool mesh_manifold = false;       // the whole-mesh pass found no non-manifold vertex

  void require_manifold(int v) const {
    if (mesh_manifold) return;
    if (mesh.is_boundary(VertexHandle(v)) && !mesh.is_manifold(VertexHandle(v))) {
      throw TopologyError("edge front: " + vname(v) + " is non-manifold (several fans meet there): split it with "
                          "edgefront::split_pinched_vertices (edgefront/vertex_twins.h) before running a front");
    }
  }
  void check_joining(int v) {
    if (mesh_manifold) return;
    require_manifold(v);
    if (manifold_checks_left > 0 && --manifold_checks_left == 0) mesh_manifold = no_nonmanifold_vertex();
  }
  bool no_nonmanifold_vertex() const {
    // A non-manifold vertex has an outgoing border halfedge; closed meshes have none at all. The
    // loop reads only the face of each halfedge (deleted ones are skipped on the rare border path).
    const int n = static_cast<int>(mesh.n_halfedges());
    for (int i = 0; i < n; ++i) {
      const HalfedgeHandle h(i);
      if (mesh.face_handle(h).is_valid() || mesh.status(h).deleted()) continue;
      if (!mesh.is_manifold(mesh.from_vertex_handle(h))) return false;
    }
    return true;
  }

  // ---- reset ----
  // Starts the front of `source`: seeds for vertex sources, the loop and its barrier for a loop
  // source. The source vertices (join level 0) are left in `sources`.
  std::vector<uint32_t> sources;
  void reset_structure(const FrontSource& source) {
    validate_source(mesh, source);
    nodes.clear();
    free_nodes.clear();
    live_nodes = peak_nodes = 0;
    vt.clear();
    sources.clear();
    unit_expansions = 0;
    n_expansions = n_minimizations = n_collisions = 0;
    loop_count = 0;
    peak_bytes = 0;
    mesh_manifold = false;
    manifold_checks_left = std::max<size_t>(mesh.n_vertices() / 8, 1);
    if (options.debug_tracking) dbg_enclosed.assign(mesh.n_vertices(), 0);
    twins = TwinRing(mesh);

    if (!source.vertices.empty()) {
      for (VertexHandle v : source.vertices) {
        require_manifold(v.idx());
        auto [rec, inserted] = vt.insert(static_cast<uint32_t>(v.idx()), VRec{});
        rec->level = 0;
        rec->state = kVertexSeed;
        sources.push_back(static_cast<uint32_t>(v.idx()));
      }
    } else {
      const size_t n = source.loop.size();
      std::vector<int> act(n), bar(n);
      for (size_t i = 0; i < n; ++i) act[i] = new_node(source.loop[i].idx(), kNodeSource);
      for (size_t i = 0; i < n; ++i) bar[i] = new_node(opph(source.loop[i].idx()), kNodeBarrier);
      for (size_t i = 0; i < n; ++i) {
        link(act[i], act[(i + 1) % n]);
        // barrier runs backwards: bar[i] = opp(loop[i]) goes to from(loop[i]); next is opp(loop[i-1]).
        link(bar[i], bar[(i + n - 1) % n]);
      }
      loop_count = 2;
      for (size_t i = 0; i < n; ++i) {
        const int v = tov(nodes[act[i]].he);
        require_manifold(v);
        auto [rec, inserted] = vt.insert(static_cast<uint32_t>(v), VRec{});
        rec->level = 0;
        rec->state = kVertexOnLoop;
        sources.push_back(static_cast<uint32_t>(v));
      }
      for (size_t i = 0; i < n; ++i) {
        for (int id : {act[i], bar[i]}) {
          VRec* rec = vt.find(static_cast<uint32_t>(tov(nodes[id].he)));
          nodes[id].vnext = rec->head;
          rec->head = id;
          nodes[id].flags |= kNodeAttached;
        }
      }
      dirty.clear();
      for (uint32_t v : sources) dirty.push_back(static_cast<int>(v));
      settle();
    }
    // The twins of the source vertices are source vertices too (one point of the surface); those
    // of a loop's vertices start with their whole fans (the loop does not divide them).
    if (twins.any()) {
      const size_t given = sources.size();
      for (size_t i = 0; i < given; ++i) {
        twins.for_each_twin(static_cast<int>(sources[i]), [&](int t) {
          if (!vt.contains(static_cast<uint32_t>(t))) {
            require_manifold(t);
            VRec* rec = vt.insert(static_cast<uint32_t>(t), VRec{}).first;
            rec->level = 0;
            rec->state = kVertexSeed;
            sources.push_back(static_cast<uint32_t>(t));
          }
        });
      }
    }
    note_memory();
  }

  // ---- the single edge expansion ----
  // Builds in `seg` the path that replaces the occurrence (h1, h2) at their common vertex: the
  // outer edges of the fan ahead, and the two border halfedges through the vertex where the fan
  // has a gap. Returns the number of faces in the wedge.
  int build_wedge(int h1, int h2, int v) {
    seg.clear();
    seg_to.clear();
    int faces = 0;
    constexpr size_t guard = size_t{1} << 24;  // the fan of a manifold vertex always closes
    int g = nexth(h1);
    for (size_t i = 0;; ++i) {
      if (i > guard) {
        throw TopologyError("edge front: the fan of " + vname(v) + " does not close; the vertex is non-manifold");
      }
      push_fan_step(g, v, faces);
      if (g == h2) break;
      g = nexth(opph(g));
    }
    return faces;
  }

  // One step of a fan walk around v at the outgoing halfedge g: the outer edge of g's face, or the
  // two border halfedges through v at a gap. The outer edge opp(next(g)) ends where g does.
  void push_fan_step(int g, int v, int& faces) {
    const HalfedgeHandle gh(g);
    const int a = mesh.to_vertex_handle(gh).idx();
    if (mesh.face_handle(gh).is_valid()) {
      const int outer = opph(mesh.next_halfedge_handle(gh).idx());
      prefetch_halfedge(outer);
      prefetch_vertex(a);
      seg.push_back(outer);
      seg_to.push_back(a);
      ++faces;
    } else {
      seg.push_back(mesh.prev_halfedge_handle(gh).idx());
      seg_to.push_back(v);
      seg.push_back(g);
      seg_to.push_back(a);
    }
  }

  void expand(int n1) {
    const int n2 = nodes[n1].next;
    const int h1 = nodes[n1].he, h2 = nodes[n2].he;
    const int v = nodes[n1].to;  // checked for manifoldness when it joined
    const int faces = build_wedge(h1, h2, v);
    EF_CHECK(faces > 0, "expanding an occurrence with nothing ahead at " + vname(v));
    const bool border = seg.size() > static_cast<size_t>(faces);
    const bool keep_first = seg.front() == h1;
    const bool keep_last = seg.back() == h2;
    EF_CHECK(nodes[n2].next != n1, "two-node loop at " + vname(v));
    const int p = keep_first ? n1 : nodes[n1].prev;
    const int q = keep_last ? n2 : nodes[n2].next;
    if (!keep_first) free_node(n1);
    if (!keep_last) free_node(n2);
    collided.clear();
    int last = p;
    const size_t b = keep_first ? 1 : 0;
    const size_t e = seg.size() - (keep_last ? 1 : 0);
    for (size_t i = b; i < e; ++i) {
      const int x = seg_to[i];
      const int id = new_node(seg[i], 0, x);
      link(last, id);
      last = id;
      if (attach(id) && x != v && i + 1 < seg.size()) collided.push_back(x);
    }
    link(last, q);
    ++n_expansions;
    ++unit_expansions;
    if (border) emit(FrontEvent::Kind::BorderReached, v);
    dirty.clear();
    dirty.push_back(v);
    dirty.push_back(fromv(h1));
    dirty.push_back(nodes[n2].to);
    for (size_t i = b; i < e; ++i) dirty.push_back(seg_to[i]);
    resolve_collisions();
    settle();
    note_memory();
  }

  void expand_seed(int s) {
    VRec* rec = vt.find(static_cast<uint32_t>(s));
    rec->state &= static_cast<uint8_t>(~kVertexSeed);
    const VertexHandle sv(s);
    if (mesh.is_isolated(sv)) {
      enclose(s);
      return;
    }
    require_manifold(s);
    // Start at the outgoing border halfedge of a border vertex so that the gap is handled once.
    int h0 = mesh.halfedge_handle(sv).idx();
    for (auto oh : mesh.voh_range(sv)) {
      if (mesh.is_boundary(oh)) {
        h0 = oh.idx();
        break;
      }
    }
    // The occurrence "(prev(h0)... h0)" around the whole fan: rotate from h0 back to h0.
    seg.clear();
    seg_to.clear();
    int faces = 0;
    constexpr size_t guard = size_t{1} << 24;
    int g = h0;
    for (size_t i = 0;; ++i) {
      EF_CHECK(i <= guard, "fan of " + vname(s) + " does not close");
      push_fan_step(g, s, faces);
      g = nexth(opph(g));
      if (g == h0) break;
    }
    const bool border = seg.size() > static_cast<size_t>(faces);
    collided.clear();
    dirty.clear();
    std::vector<int> ids(seg.size());
    for (size_t i = 0; i < seg.size(); ++i) ids[i] = new_node(seg[i], 0, seg_to[i]);
    for (size_t i = 0; i < seg.size(); ++i) link(ids[i], ids[(i + 1) % seg.size()]);
    ++loop_count;
    for (size_t i = 0; i < seg.size(); ++i) {
      const int x = seg_to[i];
      if (attach(ids[i]) && x != s) collided.push_back(x);
      dirty.push_back(x);
    }
    dirty.push_back(s);
    ++n_expansions;
    ++unit_expansions;
    if (border) emit(FrontEvent::Kind::BorderReached, s);
    resolve_collisions();
    settle();
    note_memory();
  }

  // ---- collisions: re-pair the occurrences at a vertex by rotation ----
  int count_cycles(const std::vector<int>& starts) {
    // Distinct loops through the given nodes (O(loop length)); used only with loop tracking.
    detail::FlatMap<int> seen;
    int cycles = 0;
    for (int s : starts) {
      if (seen.contains(static_cast<uint32_t>(s))) continue;
      ++cycles;
      int id = s;
      do {
        seen.insert(static_cast<uint32_t>(id), 1);
        id = nodes[id].next;
      } while (id != s);
    }
    return cycles;
  }

  void resolve_collisions() {
    for (int x : collided) {
      VRec* rec = vt.find(static_cast<uint32_t>(x));
      if (!rec || rec->head < 0) continue;
      ins.clear();
      for (int id = rec->head; id >= 0; id = nodes[id].vnext) ins.push_back(id);
      if (ins.size() < 2) continue;
      require_manifold(x);
      ++n_collisions;
      emit(FrontEvent::Kind::Collision, x);
      int before = 0;
      if (options.track_loops) before = count_cycles(ins);
      outs.clear();
      for (int id : ins) outs.push_back(nodes[id].next);
      partner.assign(ins.size(), -1);
      const size_t guard = mesh.valence(VertexHandle(x)) + 2;
      for (size_t k = 0; k < ins.size(); ++k) {
        const int hin = nodes[ins[k]].he;
        auto find_out = [&](int g) -> int {
          for (int o : outs) {
            if (nodes[o].he == g) return o;
          }
          return -1;
        };
        int o = find_out(opph(hin));
        if (o >= 0 && false_spike(ins[k], o)) o = -1;
        int g = nexth(hin);
        for (size_t i = 0; o < 0; ++i) {
          EF_CHECK(i <= guard, "no partner for a front halfedge at " + vname(x));
          o = find_out(g);
          g = nexth(opph(g));
        }
        partner[k] = o;
      }
      for (size_t k = 0; k < ins.size(); ++k) {
        for (size_t j = k + 1; j < ins.size(); ++j) {
          EF_CHECK(partner[k] != partner[j], "two front halfedges pair with one at " + vname(x));
        }
      }
      for (size_t k = 0; k < ins.size(); ++k) link(ins[k], partner[k]);
      if (options.track_loops) {
        const int after = count_cycles(ins);
        loop_count += after - before;
        if (after > before) emit(FrontEvent::Kind::Split, x);
        if (after < before) emit(FrontEvent::Kind::Merge, x);
      }
      dirty.push_back(x);
    }
    collided.clear();
  }

  // ---- settle: spikes, minimization, enclosure ----
  void remove_spike(int a) {
    // a = c->x, b = x->c: both sides of the edge are processed; drop both halfedges.
    const int b = nodes[a].next;
    const int pa = nodes[a].prev;
    const int c = nodes[pa].to;  // = fromv(a's halfedge)
    const int nb = nodes[b].next;
    if (pa == b) {
      free_node(a);
      free_node(b);
      --loop_count;
      emit(FrontEvent::Kind::Annihilation, c);
    } else {
      free_node(a);
      free_node(b);
      link(pa, nb);
    }
    dirty.push_back(c);
  }

  void minimize(int n_in) {
    // (u->x, x->w) around the single face (u, x, w) ahead becomes u->w.
    const int n_out = nodes[n_in].next;
    const int h2 = nodes[n_out].he;
    const int p = nodes[n_in].prev;
    const int u = nodes[p].to;  // loops are closed: the predecessor ends where n_in starts
    const int w = nodes[n_out].to;
    const int x = nodes[n_in].to;
    const int q = nodes[n_out].next;
    const int nh = opph(nexth(h2));  // ends at w
    if (p == n_out) {
      // A two-node loop cannot enclose a face; guarded by the spike rule.
      EF_CHECK(false, "two-node loop at " + vname(x));
    }
    free_node(n_in);
    free_node(n_out);
    const int id = new_node(nh, 0, w);
    link(p, id);
    link(id, q);
    attach(id);
    ++n_minimizations;
    dirty.push_back(u);
    dirty.push_back(w);
    dirty.push_back(x);
  }

  void enclose(int v) {
    VRec* rec = vt.find(static_cast<uint32_t>(v));
    if (!rec) return;
    const int level = rec->level;
    const bool reported = rec->state & kVertexReported;
    bool barrier = false;
    for (int id = rec->head; id >= 0; id = nodes[id].vnext) barrier = barrier || occ_barrier(id);
    const bool on_loop = rec->state & kVertexOnLoop;
    if (barrier) {
      rec->state = static_cast<uint8_t>(kVertexBarrierOnly | kVertexReported | kVertexOnLoop);
    } else {
      erase_vertex(v);
    }
    if (!reported) {
      if (options.debug_tracking) {
        EF_CHECK(!dbg_enclosed[v] || on_loop, "vertex " + std::to_string(v) + " enclosed twice");
        dbg_enclosed[v] = 1;
      }
      if (on_enclosed) on_enclosed(VertexHandle(v), level);
    }
  }

  void settle() {
    while (!dirty.empty()) {
      const int x = dirty.back();
      dirty.pop_back();
      VRec* rec = vt.find(static_cast<uint32_t>(x));
      if (!rec) continue;
      if (rec->state & (kVertexSeed | kVertexBarrierOnly)) continue;
      bool changed = false;
      for (int id = rec->head; id >= 0; id = nodes[id].vnext) {
        const int nx = nodes[id].next;
        if (nodes[nx].he == opph(nodes[id].he) && !false_spike(id, nx)) {
          remove_spike(id);
          changed = true;
          break;
        }
        const int h1 = nodes[id].he;
        if (has_face(h1) && nexth(h1) == nodes[nx].he && !occ_barrier(id)) {
          minimize(id);
          changed = true;
          break;
        }
      }
      if (changed) {
        dirty.push_back(x);
        continue;
      }
      bool active = false;
      for (int id = rec->head; id >= 0 && !active; id = nodes[id].vnext) active = occ_active(id);
      if (!active) enclose(x);
    }
  }

  // ---- scheduling ----
  int find_active_occurrence(int v) const {
    const VRec* rec = vt.find(static_cast<uint32_t>(v));
    if (!rec) return -1;
    for (int id = rec->head; id >= 0; id = nodes[id].vnext) {
      if (occ_active(id)) return id;
    }
    return -1;
  }

  // Prefetch for a vertex about to be expanded: the halfedge `depth` steps into the fan walk of
  // each of its wedges (0: the front halfedge itself). The records before it must be in cache
  // already (prefetched with smaller depths a little earlier), or this waits for them.
  void prefetch_occurrences(int v, int depth) const {
    const VRec* rec = vt.find(static_cast<uint32_t>(v));
    if (!rec) return;
    for (int id = rec->head; id >= 0; id = nodes[id].vnext) {
      int g = nodes[id].he;
      const int h2 = nodes[nodes[id].next].he;
      for (int k = 0; k < depth && g != h2; ++k) g = k == 0 ? nexth(g) : nexth(opph(g));
      prefetch_halfedge(g);
    }
  }

  // Expands every active occurrence of `v` (the full fan of a seed). Returns false when `v` has
  // nothing ahead (not on the front, enclosed, or only barrier occurrences left).
  bool expand_vertex(int v) {
    VRec* rec = vt.find(static_cast<uint32_t>(v));
    if (!rec || (rec->state & kVertexBarrierOnly)) return false;
    if ((rec->state & kVertexSeed) && rec->head < 0) {
      expand_seed(v);
      return true;
    }
    bool any = false;
    for (int n = find_active_occurrence(v); n >= 0; n = find_active_occurrence(v)) {
      expand(n);
      any = true;
    }
    return any;
  }

  size_t memory_bytes() const {
    return nodes.capacity() * sizeof(Node) + free_nodes.capacity() * sizeof(int) + vt.memory_bytes() +
           sources.capacity() * sizeof(uint32_t) +
           (seg.capacity() + seg_to.capacity() + dirty.capacity() + collided.capacity() + ins.capacity() + outs.capacity() +
            partner.capacity()) *
               sizeof(int);
  }
  void note_memory() { peak_bytes = std::max(peak_bytes, memory_bytes()); }

  // ---- inspection ----
  std::vector<FrontLoop> loops() const {
    std::vector<FrontLoop> out;
    std::vector<uint8_t> seen(nodes.size(), 0);
    for (size_t i = 0; i < nodes.size(); ++i) {
      if (!(nodes[i].flags & kNodeLive) || seen[i]) continue;
      FrontLoop loop;
      loop.inert = true;
      loop.barrier = true;
      int id = static_cast<int>(i);
      do {
        seen[id] = 1;
        loop.halfedges.push_back(HalfedgeHandle(nodes[id].he));
        loop.vertices.push_back(VertexHandle(tov(nodes[id].he)));
        loop.inert = loop.inert && !has_face(nodes[id].he);
        loop.barrier = loop.barrier && (nodes[id].flags & kNodeBarrier);
        id = nodes[id].next;
      } while (id != static_cast<int>(i));
      out.push_back(std::move(loop));
    }
    return out;
  }

  // Throws InternalError naming the first broken property. With `level_boundary`, also checks
  // that the front is minimal and that every front vertex joined at that level.
  void validate(std::optional<int> level_boundary) const;
};


// ---------------------------------------------------------------------------------------------
// Validator of the core

inline void EdgeFrontCore::validate(std::optional<int> level_boundary) const {
  auto fail = [](const std::string& property, const std::string& detail) {
    throw InternalError("edge front invariant broken: " + property + ": " + detail);
  };
  detail::FlatMap<int> he_seen;
  size_t live = 0;
  for (size_t i = 0; i < nodes.size(); ++i) {
    const Node& n = nodes[i];
    if (!(n.flags & kNodeLive)) continue;
    ++live;
    const std::string where = "node " + std::to_string(i) + " (halfedge " + std::to_string(n.he) + ")";
    if (n.next < 0 || n.prev < 0 || !(nodes[n.next].flags & kNodeLive) || !(nodes[n.prev].flags & kNodeLive)) {
      fail("closed loops", where + " has a dangling link");
    }
    if (nodes[n.next].prev != static_cast<int>(i) || nodes[n.prev].next != static_cast<int>(i)) {
      fail("closed loops", where + ": next(prev(e)) != e");
    }
    if (tov(n.he) != fromv(nodes[n.next].he)) {
      fail("consecutive elements share a vertex", where + " ends at " + vname(tov(n.he)) +
                                                      " but its successor starts at " +
                                                      vname(fromv(nodes[n.next].he)));
    }
    if (!he_seen.insert(static_cast<uint32_t>(n.he), 1).second) {
      fail("each halfedge at most once", "halfedge " + std::to_string(n.he) + " is in the front twice");
    }
    if (nodes[n.next].he == opph(n.he) && !false_spike(static_cast<int>(i), n.next)) {
      fail("no zero-width spikes", where + " is followed by its own opposite");
    }
    const bool attached = n.flags & kNodeAttached;
    const VRec* rec = vt.find(static_cast<uint32_t>(tov(n.he)));
    if (attached != (rec != nullptr)) {
      if (!attached && occ_active(static_cast<int>(i))) {
        fail("vertex table matches loops", where + ": active occurrence at " + vname(tov(n.he)) +
                                                " whose vertex is not on the front");
      }
      if (attached) fail("vertex table matches loops", where + " is attached but its vertex is not in the table");
    }
    if (options.debug_tracking && has_face(n.he) && !(n.flags & kNodeBarrier)) {
      const int opposite = tov(nexth(n.he));
      if (dbg_enclosed[opposite] && !vt.contains(static_cast<uint32_t>(opposite))) {
        fail("unprocessed surface ahead", where + " has enclosed " + vname(opposite) + " ahead of it");
      }
    }
  }
  if (live != live_nodes) fail("node count", "pool says " + std::to_string(live_nodes) + ", found " + std::to_string(live));

  size_t listed = 0;
  vt.for_each([&](uint32_t v, const VRec& rec) {
    std::vector<int> wedge_faces;
    bool any_active = false;
    for (int id = rec.head; id >= 0; id = nodes[id].vnext) {
      ++listed;
      if (!(nodes[id].flags & kNodeLive) || !(nodes[id].flags & kNodeAttached)) {
        fail("vertex table matches loops", vname(static_cast<int>(v)) + " lists a dead or detached node");
      }
      if (tov(nodes[id].he) != static_cast<int>(v)) {
        fail("vertex table matches loops", vname(static_cast<int>(v)) + " lists a node ending elsewhere");
      }
      if (occ_active(id)) any_active = true;
      if (occ_inert(id)) continue;
      // Wedge of this occurrence: faces from face(h1) clockwise to face(h2).
      const int h1 = nodes[id].he, h2 = nodes[nodes[id].next].he;
      int g = nexth(h1);
      const size_t guard = mesh.valence(VertexHandle(static_cast<int>(v))) + 2;
      for (size_t i = 0;; ++i) {
        if (i > guard) fail("wedges", "the wedge at " + vname(static_cast<int>(v)) + " does not close");
        if (has_face(g)) wedge_faces.push_back(mesh.face_handle(HalfedgeHandle(g)).idx());
        if (g == h2) break;
        g = nexth(opph(g));
      }
    }
    std::sort(wedge_faces.begin(), wedge_faces.end());
    if (std::adjacent_find(wedge_faces.begin(), wedge_faces.end()) != wedge_faces.end()) {
      fail("front sides never touch or cross", "two occurrences of " + vname(static_cast<int>(v)) +
                                                   " have the same face ahead");
    }
    const bool seed = rec.state & kVertexSeed;
    const bool barrier_only = rec.state & kVertexBarrierOnly;
    if (!seed && !barrier_only && !any_active) {
      fail("enclosed vertices leave the front", vname(static_cast<int>(v)) + " has nothing ahead but is still listed");
    }
    if (level_boundary && !seed && !barrier_only && rec.level != *level_boundary) {
      fail("levels are hop distances", vname(static_cast<int>(v)) + " is on the front with level " +
                                           std::to_string(rec.level) + " after level " + std::to_string(*level_boundary));
    }
    if (level_boundary) {
      for (int id = rec.head; id >= 0; id = nodes[id].vnext) {
        const int h1 = nodes[id].he, h2 = nodes[nodes[id].next].he;
        if (has_face(h1) && nexth(h1) == h2 && !occ_barrier(id)) {
          fail("minimal", vname(static_cast<int>(v)) + " can still be minimized at a level boundary");
        }
      }
    }
  });
  size_t attached_count = 0;
  for (const Node& n : nodes) attached_count += (n.flags & kNodeLive) && (n.flags & kNodeAttached);
  if (attached_count != listed) fail("vertex table matches loops", "attached nodes and table lists differ");
  if (options.track_loops && static_cast<long>(loops().size()) != loop_count) {
    fail("loop count", "tracked " + std::to_string(loop_count) + ", found " + std::to_string(loops().size()));
  }
}


}  // namespace edgefront::detail
