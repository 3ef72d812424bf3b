#pragma once
// A compact copy of each vertex's 1-ring (the GCS basic step's ring gather and winner normal).
//
// Walking a vertex's outgoing halfedges in OpenMesh touches its vertex record and one edge record
// per neighbour, spread over memory; the basic step does that for the winner and each of its
// neighbours (about 40 halfedges per step). This cache keeps, per vertex, one 64-byte line with
// the neighbours in the order of mesh.voh_range(v) (from mesh.halfedge_handle(v), so sums over
// them are taken in the same order as a halfedge walk) and a bit per neighbour telling whether the
// outgoing halfedge to it has a face. A line is filled on first use and stays valid until the
// owner invalidates it: the owner must call invalidate(v) for every vertex whose ring (neighbours,
// their order or the faces between them, or its outgoing halfedge) may have changed, or
// invalidate_all(). check() compares the valid lines with the mesh (for validate()).

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "edgefront/error.h"
#include "edgefront/mesh.h"

namespace gcs::detail {

class NeighborCache {
 public:
  static constexpr int kMaxValence = 14;  // larger rings are not cached (get() returns null)

  struct alignas(64) Line {
    std::uint32_t epoch = 0;      // valid when equal to the cache's epoch
    std::uint16_t face_mask = 0;  // bit e: the outgoing halfedge to nb[e] has a face
    std::uint8_t count = 0;       // neighbours
    std::uint8_t uncached = 0;    // 1: the valence exceeds kMaxValence (not stored)
    std::int32_t nb[kMaxValence];
    bool has_face(int e) const { return (face_mask >> e) & 1u; }
  };
  static_assert(sizeof(Line) == 64, "one cache line per vertex");

  /// Makes room for vertex ids < n (new lines invalid).
  void resize(std::size_t n) {
    if (n > lines_.size()) lines_.resize(n);
  }
  /// Asks the memory system for v's line ahead of a get().
  void prefetch(int v) const {
    if (static_cast<std::size_t>(v) < lines_.size()) __builtin_prefetch(&lines_[static_cast<std::size_t>(v)]);
  }
  void invalidate(int v) {
    if (static_cast<std::size_t>(v) < lines_.size()) lines_[static_cast<std::size_t>(v)].epoch = 0;
  }
  void invalidate_all() {
    if (++epoch_ == 0) {  // wrapped: clear the lines once
      for (Line& l : lines_) l.epoch = 0;
      epoch_ = 1;
    }
  }

  /// v's line, filled from the mesh when not valid; null when v has more than kMaxValence
  /// neighbours or no outgoing halfedge (the caller then walks the mesh). v must be below the
  /// size given to resize() (lines are never reallocated here: earlier lines stay valid).
  const Line* get(const edgefront::Mesh& mesh, edgefront::VertexHandle v) {
    const std::size_t i = static_cast<std::size_t>(v.idx());
    EF_CHECK(i < lines_.size(), "neighbour cache: vertex id beyond resize()");
    Line& l = lines_[i];
    if (l.epoch != epoch_) fill(mesh, v, l);
    return l.uncached ? nullptr : &l;
  }

  /// Throws InternalError when a valid line disagrees with the mesh (deleted vertices skipped).
  void check(const edgefront::Mesh& mesh) const {
    for (std::size_t i = 0; i < lines_.size() && i < mesh.n_vertices(); ++i) {
      const Line& l = lines_[i];
      const edgefront::VertexHandle v(static_cast<int>(i));
      if (l.epoch != epoch_ || mesh.status(v).deleted()) continue;
      Line fresh;
      fill(mesh, v, fresh);
      bool same = fresh.uncached == l.uncached && fresh.count == l.count && fresh.face_mask == l.face_mask;
      for (int e = 0; same && e < l.count; ++e) same = fresh.nb[e] == l.nb[e];
      EF_CHECK(same, "neighbour cache: the ring of vertex " + std::to_string(i) + " changed without an invalidation");
    }
  }

 private:
  void fill(const edgefront::Mesh& mesh, edgefront::VertexHandle v, Line& l) const {
    l.epoch = epoch_;
    l.count = 0;
    l.face_mask = 0;
    l.uncached = 0;
    const edgefront::HalfedgeHandle h0 = mesh.halfedge_handle(v);
    if (!h0.is_valid()) {
      l.uncached = 1;
      return;
    }
    edgefront::HalfedgeHandle h = h0;
    int n = 0;
    do {
      if (n == kMaxValence) {
        l.uncached = 1;
        l.count = 0;
        l.face_mask = 0;
        return;
      }
      l.nb[n] = mesh.to_vertex_handle(h).idx();
      if (mesh.face_handle(h).is_valid()) l.face_mask = static_cast<std::uint16_t>(l.face_mask | (1u << n));
      ++n;
      h = mesh.next_halfedge_handle(mesh.opposite_halfedge_handle(h));
    } while (h != h0);
    l.count = static_cast<std::uint8_t>(n);
  }

  std::vector<Line> lines_;
  std::uint32_t epoch_ = 1;
};

}  // namespace gcs::detail
