#pragma once
/// \file minimal_edge_front.h
/// The Minimal Edge Front (MEF) of Annuth & Bohn, "Geodesic Mesh Processing with Edge-Front based
/// Data Structures", §2.2, algorithm 2.
///
/// The front is one or more closed loops of mesh halfedges. Each loop has the processed surface on
/// its right and the unprocessed surface ahead, on its left (OpenMesh's counter-clockwise faces:
/// `face_handle(h)` is ahead of a front halfedge `h`). A *single edge expansion* takes a front
/// vertex `v` between two consecutive front halfedges `u->v`, `v->w` and replaces them by the arc
/// of `v`'s fan that lies ahead; `v` becomes enclosed. *Minimization* redirects the path `u->v->w`
/// through the third edge of a triangle ahead of it. A *collision* is a vertex of a new arc that is
/// already on the front: loops split or merge there. A loop that encloses no surface *annihilates*.
/// Halfedges on the mesh border cannot expand and stay in their loops (inert), so loops are always
/// closed.
///
/// Levels: level k expands every vertex that joined the front in level k-1 (all of its
/// occurrences, whatever order), so the level at which a vertex joins the front is its
/// breadth-first hop distance from the source set.
///
/// Pinched vertices (several fans at one point, split into twins: edgefront/vertex_twins.h) are
/// one point of the surface, the paper's collision in reverse: the twins of a vertex that joined
/// the front join at the same level as seeds (when the level completes; a `Pinch` event each),
/// unless the front has reached them itself, and at the next level each seed expands its whole fan
/// into a loop of its own, like a source vertex (unless the front has reached it from its own side
/// by then: it is then an ordinary front vertex). So the loop count grows by one per twin at a
/// pinch; where the parts beyond it are joined elsewhere too, those loops meet the others there in
/// ordinary collisions (merges). The twins of source vertices are sources (level 0);
/// the twins of a loop source's vertices start at level 0 with their whole fans (the loop does not
/// divide them). Hop distances count a step between twins as 0.
///
/// Memory: the working set (loop nodes, the front-vertex table, the level lists) holds O(front)
/// elements in open-addressing tables; nothing proportional to the mesh is allocated per query.
/// A `MinimalEdgeFront` object can be `reset` for many queries and keeps its buffers.

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "edgefront/front_source.h"
#include "edgefront/mesh.h"

namespace edgefront {

/// Something that happened during an expansion, reported to `MinimalEdgeFront::set_event_callback`.
struct FrontEvent {
  /// What happened.
  enum class Kind {
    Collision,     ///< a new arc touched the front at `vertex`; loops re-paired there
    Split,         ///< a collision split one loop into two (reported with loop tracking on)
    Merge,         ///< a collision merged two loops into one (reported with loop tracking on)
    Annihilation,  ///< a loop enclosed no more surface and vanished; `vertex` was its last vertex
    BorderReached, ///< an expansion at `vertex` reached the mesh border
    Pinch,         ///< `vertex`, a twin of a vertex that joined the front (a pinched vertex, see
                   ///< above), joined with it as a seed: it starts a loop of its own around its fan
  };
  Kind kind = Kind::Collision;  ///< what happened
  VertexHandle vertex;          ///< where it happened (see `Kind`)
  int level = 0;  ///< the level being built when it happened
};

/// One closed loop of the front, in order. `vertices[i]` is the end of `halfedges[i]`.
struct FrontLoop {
  std::vector<HalfedgeHandle> halfedges;  ///< the loop's halfedges, each ending where the next begins
  std::vector<VertexHandle> vertices;     ///< `vertices[i]` = to-vertex of `halfedges[i]`
  bool inert = false;    ///< every halfedge lies on the mesh border: the loop rests there
  bool barrier = false;  ///< the back side of a loop source, never expanded (see `FrontSource`)
};

/// Options of the Minimal Edge Front.
struct MinimalEdgeFrontOptions {
  /// Decide for every collision whether it split or merged loops (walks the smaller side; cost
  /// O(min(loop lengths)) per collision) and report `Split`/`Merge` events and `loop_count()`.
  bool track_loops = false;
  /// Keep an O(mesh) record of enclosed vertices so that `validate()` can also check that every
  /// front halfedge has unprocessed surface ahead and that no vertex is enclosed twice. For tests.
  bool debug_tracking = false;
  /// When non-zero (any value), the vertices of each level are expanded in a pseudo-random order drawn from
  /// this seed instead of the order they joined in. Levels do not depend on it; tests use it to
  /// show that.
  uint64_t order_seed = 0;
};

/// Why a run stopped.
enum class FrontStop {
  NotStarted,    ///< no expansion yet
  LevelReached,  ///< the requested number of levels is complete
  Exhausted,     ///< nothing left to expand: the front annihilated or rests on borders
};

/// The Minimal Edge Front, stepwise or by levels. Reusable: `reset` starts a new query and keeps
/// buffers. The mesh must outlive the front and must not change during a query.
class MinimalEdgeFront {
 public:
  /// A front over `mesh`, which is borrowed (it must outlive the front). Call `reset` to start a
  /// query (it checks the source and the mesh's attributes).
  explicit MinimalEdgeFront(const Mesh& mesh, MinimalEdgeFrontOptions options = {});
  explicit MinimalEdgeFront(const Mesh&& mesh, MinimalEdgeFrontOptions options = {}) = delete;  ///< no temporaries
  ~MinimalEdgeFront();
  /// Takes over the moved-from object's state; that object may then only be destroyed or assigned to.
  MinimalEdgeFront(MinimalEdgeFront&&) noexcept;
  /// Takes over the moved-from object's state; that object may then only be destroyed or assigned to.
  MinimalEdgeFront& operator=(MinimalEdgeFront&&) noexcept;

  /// Starts a new query from `source`. The sources join at level 0.
  /// \throws InvalidInput for a bad source (see `validate_source`).
  void reset(const FrontSource& source);

  /// Performs one single edge expansion (the next one of the current level, starting the next
  /// level when one is complete). Returns false when nothing is left to expand.
  /// \throws TopologyError when the expansion meets a non-manifold vertex (one not split into
  ///         twins: see `split_pinched_vertices`).
  bool step();

  /// Completes the current level (or performs the next one when the last is complete).
  /// Returns false when nothing was left to expand.
  bool advance_level();

  /// Runs `levels` more complete levels, or to exhaustion when `levels < 0`.
  FrontStop run(int levels = -1);

  /// Number of completed levels: after `advance_level()` from a fresh vertex source it is 1 and
  /// the front is the link of the vertex.
  int level() const;
  /// True when the current level has been completed (no level is half-done).
  bool at_level_boundary() const;
  /// True when nothing is left to expand (the front annihilated or rests on borders).
  bool exhausted() const;

  /// The loops of the front, in order (O(front)).
  std::vector<FrontLoop> loops() const;
  /// Number of loops; O(front) unless loop tracking is on.
  size_t loop_count() const;
  /// Halfedges currently in the front (inert ones included).
  size_t front_size() const;
  /// Largest `front_size()` seen since `reset`.
  size_t peak_front_size() const;
  /// Bytes held by the working containers now (capacity, not size).
  size_t working_memory_bytes() const;
  /// Largest `working_memory_bytes()` seen since `reset` (sampled at each level boundary and at
  /// each step).
  size_t peak_working_memory_bytes() const;
  /// Number of single edge expansions since `reset`.
  size_t expansions() const;
  /// Number of minimizations (a path u->v->w redirected through a triangle ahead) since `reset`.
  size_t minimizations() const;
  /// Number of collisions (`FrontEvent::Kind::Collision`) since `reset`.
  size_t collisions() const;

  /// The level at which `v` joined the front, if `v` is on the front now.
  std::optional<int> front_level(VertexHandle v) const;
  /// Vertices on the front now (each once), with their join levels.
  std::vector<std::pair<VertexHandle, int>> front_vertices() const;

  /// Called once for every vertex when it becomes enclosed, with the level at which it joined
  /// the front. A vertex resting on the border with no surface ahead counts as enclosed.
  void set_enclosed_callback(std::function<void(VertexHandle, int)> cb);
  /// Called for every `FrontEvent` as it happens (`Split`/`Merge` only with `track_loops`).
  /// An empty function removes the callback.
  void set_event_callback(std::function<void(const FrontEvent&)> cb);

  /// Checks every structural property of the front and throws `InternalError` naming the first
  /// one broken: loops closed and linked, consecutive halfedges share a vertex, every non-border
  /// front halfedge has a face ahead, each halfedge at most once, the vertex table matches the
  /// loops, the wedges of a vertex's occurrences are disjoint, no zero-width spikes; at a level
  /// boundary also that the front is minimal and every front vertex joined in the last level.
  /// With `debug_tracking` also that nothing ahead of the front is enclosed.
  void validate() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Per-vertex join level (breadth-first hop distance from the source), or -1 for vertices not
/// reached within `max_levels` levels (all levels when negative) or in another component.
/// Vertices of a loop source have level 0; the side behind the loop is not entered.
std::vector<int> edge_front_levels(const Mesh& mesh, const FrontSource& source, int max_levels = -1);

}  // namespace edgefront
