#pragma once
/// \file vertex_twins.h
/// Vertex twins: several vertices of a mesh that stand for one point of the surface.
///
/// A *pinched* (non-manifold) vertex is one where several fans of faces meet at a single vertex:
/// a figure's part touching the body at one point, two triangles sharing only a corner. A
/// half-edge mesh stores each fan around its own vertex, so the readers and the array conversion
/// split such a vertex into one vertex per fan (the original keeps the first fan, copies are
/// appended) and link the copies as *twins*. The fronts and distance methods treat a group of
/// twins as one point: when one settles, the others settle at the same distance and level, so
/// the surface stays connected through the pinch.
///
/// Twins are stored on the mesh (an OpenMesh vertex property, copied with the mesh) as a ring:
/// each vertex names the next vertex of its group, a vertex without twins names itself.
/// Renumbering the vertices (garbage collection) does not update the ring: call `clear_twins`
/// before, and link the groups again after, if they are still needed.

#include <vector>

#include "edgefront/mesh.h"

namespace edgefront {

/// Links `group` (>= 2 distinct live vertices, none already in a group) as twins of each other.
/// Their positions should coincide (they are one point of the surface); this is not checked.
/// \throws InvalidInput for fewer than 2 vertices, a dead or repeated vertex, or a vertex that
///         already has twins.
void link_twins(Mesh& mesh, const std::vector<VertexHandle>& group);

/// Removes every twin link (the property is removed from the mesh).
void clear_twins(Mesh& mesh);

/// True when some vertex of `mesh` has a twin.
bool has_twins(const Mesh& mesh);

/// The twins of `v` (not `v` itself), in ring order; empty when `v` has none or is not a vertex.
std::vector<VertexHandle> twins_of(const Mesh& mesh, VertexHandle v);

/// Read access for code that asks per vertex (the fronts): looks the property up once.
class TwinRing {
 public:
  explicit TwinRing(const Mesh& mesh);
  explicit TwinRing(const Mesh&& mesh) = delete;  ///< the ring reads the mesh: no temporaries
  /// True when the mesh has twins at all (else `next` is the identity).
  bool any() const { return any_; }
  /// The next vertex of `v`'s group (`v` itself when it has no twins). `v` must be a vertex.
  VertexHandle next(VertexHandle v) const;

 private:
  const Mesh* mesh_;
  OpenMesh::VPropHandleT<int> prop_;
  bool any_ = false;
};

}  // namespace edgefront
