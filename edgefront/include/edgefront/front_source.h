#pragma once
/// \file front_source.h
/// Where a front starts: one vertex, several vertices, or a closed simple edge path ("line").

#include <vector>

#include "edgefront/mesh.h"

namespace edgefront {

/// The starting set of a Vertex Front, Minimal Edge Front or Minimal Distance Front.
///
/// - `vertices`: one or more distinct, live vertices (paper §2.1/§2.2: the starting point).
/// - `loop`: a closed, non-self-intersecting edge path given as halfedges in order, each ending
///   where the next begins. The front expands only to the side *ahead* of the loop, which is the
///   side of `mesh.face_handle(h)` for each halfedge `h` (the left side in OpenMesh's
///   counter-clockwise convention). The other side is treated as a barrier (a border) and is
///   never entered from the loop; if the surface wraps around (a non-separating loop on a torus),
///   the front reaches the barrier from behind and stops there.
///
/// Build one with the named constructors; `validate_source` checks it against a mesh.
struct FrontSource {
  std::vector<VertexHandle> vertices;  ///< source vertices (empty for a loop source)
  std::vector<HalfedgeHandle> loop;    ///< the closed halfedge loop, in order (empty for vertex sources)

  /// A single source vertex `v`.
  static FrontSource vertex(VertexHandle v) { return FrontSource{{v}, {}}; }
  /// Several source vertices (distinct, live), all at level 0 / distance 0.
  static FrontSource from_vertices(std::vector<VertexHandle> vs) { return FrontSource{std::move(vs), {}}; }
  /// A loop source from halfedges in order (each ending where the next begins; closed).
  static FrontSource from_halfedges(std::vector<HalfedgeHandle> hs) { return FrontSource{{}, std::move(hs)}; }

  /// True for a loop source (`loop` not empty).
  bool is_loop() const { return !loop.empty(); }
};

/// Which side of a vertex loop is ahead, for `loop_from_vertices`.
enum class LoopSide {
  Left,   ///< the faces to the left of the path v0 -> v1 -> ... (counter-clockwise side)
  Right,  ///< the faces to the right of the path
};

/// Builds a loop source from a closed vertex path v0, v1, ..., v(n-1) (v0 is not repeated at
/// the end): consecutive vertices (and v(n-1), v0) must be joined by mesh edges.
/// \throws InvalidInput naming the first pair that is not an edge, a repeated vertex, a path of
///         fewer than 3 vertices, or a side that has no face along some edge.
FrontSource loop_from_vertices(const Mesh& mesh, const std::vector<VertexHandle>& path,
                               LoopSide side = LoopSide::Left);

/// Checks a source against the mesh.
/// \throws InvalidInput when the source is empty, names an invalid or deleted handle or a
///         repeated vertex, or when the loop is not closed, not simple (a vertex twice), or has
///         no face ahead of some halfedge.
void validate_source(const Mesh& mesh, const FrontSource& source);

}  // namespace edgefront
