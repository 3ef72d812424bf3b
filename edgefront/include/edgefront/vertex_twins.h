#pragma once
/// \file vertex_twins.h
/// Vertex twins: several vertices of a mesh that stand for one point of the surface.
///
/// A *pinched* (non-manifold) vertex is one where several fans of faces meet at a single vertex:
/// a figure's part touching the body at one point, two triangles sharing only a corner. A
/// half-edge mesh stores each fan around its own vertex, so the readers and the array conversion
/// split such a vertex into one vertex per fan (the original keeps the first fan, copies are
/// appended) and link the copies as *twins*; `split_pinched_vertices` does the same on a mesh
/// built in code. The fronts, distance methods and connection paths treat a group of twins as
/// one point: when one is reached, the others are reached at the same distance (level), and the
/// surface stays connected through the pinch (minimal_edge_front.h, minimal_distance_front.h,
/// connection_path.h say how).
///
/// Twins are stored on the mesh (an OpenMesh vertex property, copied with the mesh) as a ring:
/// each vertex names the next vertex of its group, a vertex without twins names itself.
/// Renumbering the vertices (garbage collection) does not update the ring: call `clear_twins`
/// before, and link the groups again after, if they are still needed.

#include <string>
#include <vector>

#include "edgefront/error.h"
#include "edgefront/mesh.h"

namespace edgefront {

/// Links `group` (>= 2 distinct live vertices, none already in a group) as twins of each other.
/// Their positions should coincide (they are one point of the surface); this is not checked.
/// \throws InvalidInput for fewer than 2 vertices, a dead or repeated vertex, or a vertex that
///         already has twins.
void link_twins(Mesh& mesh, const std::vector<VertexHandle>& group);

/// Removes every twin link (the property is removed from the mesh).
void clear_twins(Mesh& mesh);

/// True when some vertex of `mesh` has a twin. O(vertices).
bool has_twins(const Mesh& mesh);

/// The twins of `v` (not `v` itself), in ring order; empty when `v` has none or is not a vertex.
std::vector<VertexHandle> twins_of(const Mesh& mesh, VertexHandle v);

/// Splits every pinched vertex of a mesh built in code: a vertex where OpenMesh keeps several
/// fans of faces (each with a border gap; `Mesh::is_manifold` is false there) keeps its first fan
/// (the one of its outgoing halfedge) and each further fan moves to a new vertex at the same
/// position, appended to the mesh and linked as a twin of it (a vertex that has twins already
/// gets the copies into its group). Face and halfedge indices do not change, and the existing
/// vertices keep their indices. The fronts and distance methods refuse unsplit pinched vertices
/// (`TopologyError` naming this function); the mesh loader and the array conversion split them
/// on their own. Returns, per copy in the order appended, the vertex it was split from (empty:
/// nothing to split).
std::vector<VertexHandle> split_pinched_vertices(Mesh& mesh);

/// Read access for code that asks per vertex (the fronts): looks the property up once. O(1) to
/// make; it reads the mesh as it is when made (make a new one after adding vertices).
class TwinRing {
 public:
  /// Reads the twin property of `mesh` (borrowed: it must outlive the ring and keep its vertices).
  explicit TwinRing(const Mesh& mesh);
  explicit TwinRing(const Mesh&& mesh) = delete;  ///< the ring reads the mesh: no temporaries
  /// True when the mesh holds twin links (else `next` is the identity); `link_twins` is the only
  /// thing that makes it true, `clear_twins` makes it false.
  bool any() const { return next_ != nullptr; }
  /// The next vertex of `v`'s group (`v` itself when it has no twins). `v` must be a vertex.
  VertexHandle next(VertexHandle v) const { return VertexHandle(next(v.idx())); }
  /// The same on vertex indices.
  int next(int v) const {
    if (next_ == nullptr) return v;
    const int n = next_[v];
    return n > 0 && n <= n_ ? n - 1 : v;
  }
  /// Calls f(t) for every twin t of vertex index `v` (not `v` itself), in ring order.
  /// \throws InvalidInput when the ring does not lead back to `v` (links broken by a renumbering).
  template <class F>
  void for_each_twin(int v, F&& f) const {
    if (next_ == nullptr) return;
    int steps = 0;
    for (int t = next(v); t != v; t = next(t)) {
      if (++steps > n_) {
        throw InvalidInput("twins: the twin links of vertex " + std::to_string(v) +
                           " do not lead back to it (renumbered without clear_twins?)");
      }
      f(t);
    }
  }

 private:
  const int* next_ = nullptr;  // per vertex, 1 + the next twin's index (0: none); null without twins
  int n_ = 0;                  // number of vertices
};

}  // namespace edgefront
