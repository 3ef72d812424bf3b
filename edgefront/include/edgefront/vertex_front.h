#pragma once
/// \file vertex_front.h
/// The Vertex Front (VF) of Annuth & Bohn, §2.1, algorithm 1: breadth-first expansion that keeps
/// only three vertex sets (the previous level, the current front, the next level), so its memory
/// follows the front, not the visited area. A loose set of vertices: no loops, no collisions.
///
/// Pinched vertices (split into twins, edgefront/vertex_twins.h) are one point: a vertex's twins
/// join the front with it, at the same level (as the level completes; the twins of sources are
/// sources; those of a loop
/// source's vertices start at level 0 with their whole fans), so levels count a step between twins
/// as 0.

#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "edgefront/front_source.h"
#include "edgefront/mesh.h"

namespace edgefront {

/// Stepwise Vertex Front. Reusable across queries (`reset` keeps its buffers).
/// Level semantics match `MinimalEdgeFront`: the sources join at level 0; level k processes
/// every vertex that joined at level k-1. A vertex is *enclosed* when it is processed.
///
/// With a loop source the loop's vertices join at level 0 and the front spreads only through
/// faces on the loop's ahead side: a neighbour of a loop vertex is taken only if it lies in the
/// ahead wedge of that vertex; beyond the first level the VF cannot tell sides apart (paper §2.1),
/// so the barrier is kept as a set of loop vertices that are never re-entered.
class VertexFront {
 public:
  /// A front over `mesh`, which is borrowed: it must outlive the front and must not change
  /// during a query. Call `reset` to start a query.
  explicit VertexFront(const Mesh& mesh);
  explicit VertexFront(const Mesh&& mesh) = delete;  ///< the front reads the mesh: no temporaries
  ~VertexFront();
  /// Takes over the moved-from object's state; that object may then only be destroyed or assigned to.
  VertexFront(VertexFront&&) noexcept;
  /// Takes over the moved-from object's state; that object may then only be destroyed or assigned to.
  VertexFront& operator=(VertexFront&&) noexcept;

  /// \throws InvalidInput for a bad source.
  void reset(const FrontSource& source);
  /// Processes one front vertex. Returns false when nothing is left.
  bool step();
  /// Completes the current level. Returns false when nothing was left.
  bool advance_level();
  /// Runs `levels` more levels, or to exhaustion when negative. Returns completed levels.
  int run(int levels = -1);

  /// Number of completed levels since `reset` (0 before the first level completes).
  int level() const;
  /// True when nothing is left to process.
  bool exhausted() const;
  /// Vertices in the current front (not yet processed) and in the next level.
  size_t front_size() const;
  /// Largest `front_size()` seen since `reset`.
  size_t peak_front_size() const;
  /// Bytes held by the working containers now (capacity, not size).
  size_t working_memory_bytes() const;
  /// Largest `working_memory_bytes()` seen since `reset`.
  size_t peak_working_memory_bytes() const;

  /// The join level of `v` if the VF still holds it (previous level, current front or next level).
  std::optional<int> front_level(VertexHandle v) const;

  /// Vertices that joined the front but are not processed yet, with their join levels.
  std::vector<std::pair<VertexHandle, int>> front_vertices() const;

  /// Called once per vertex when it is processed, with its join level.
  void set_enclosed_callback(std::function<void(VertexHandle, int)> cb);

  /// Checks the VF invariants (the three sets are disjoint; every neighbour of a processed
  /// vertex of a completed level is known) and throws `InternalError` naming the broken one.
  void validate() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Per-vertex join level by the Vertex Front, -1 where not reached (see `edge_front_levels`).
std::vector<int> vertex_front_levels(const Mesh& mesh, const FrontSource& source, int max_levels = -1);

}  // namespace edgefront
