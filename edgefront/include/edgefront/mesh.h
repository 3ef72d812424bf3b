#pragma once
/// \file mesh.h
/// The one mesh type of EdgeFront: an OpenMesh triangle mesh with double-precision points.
/// All OpenMesh types reach the rest of the project through this header.

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

namespace edgefront {

/// Traits of the mesh: double-precision points and normals, status attributes on vertices,
/// edges, halfedges and faces (needed for deletion and garbage collection), face normals, and
/// explicit previous-halfedge links (O(1) `prev_halfedge_handle`).
struct MeshTraits : public OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;   ///< vertex positions: three doubles, in the input's length unit
  using Normal = OpenMesh::Vec3d;  ///< face (and vertex) normals: three doubles, unit length when computed
  VertexAttributes(OpenMesh::Attributes::Status);  ///< deletion status per vertex
  EdgeAttributes(OpenMesh::Attributes::Status);    ///< deletion status per edge
  /// Deletion status and an explicit previous-halfedge link per halfedge.
  HalfedgeAttributes(OpenMesh::Attributes::Status | OpenMesh::Attributes::PrevHalfedge);
  /// Deletion status and a normal per face.
  FaceAttributes(OpenMesh::Attributes::Status | OpenMesh::Attributes::Normal);
};

/// The triangle mesh used everywhere in EdgeFront.
using Mesh = OpenMesh::TriMesh_ArrayKernelT<MeshTraits>;

/// A point or vector in 3D: three doubles (`[0]`, `[1]`, `[2]`), in the input's length unit.
using Vec3 = OpenMesh::Vec3d;
/// A vertex of a `Mesh`: its index (`idx()`, 0-based) or invalid (-1, `is_valid()` false).
using VertexHandle = OpenMesh::VertexHandle;
/// A directed edge of a `Mesh` (index or invalid); the two halves of edge e are 2e and 2e+1.
using HalfedgeHandle = OpenMesh::HalfedgeHandle;
/// An undirected edge of a `Mesh` (index or invalid).
using EdgeHandle = OpenMesh::EdgeHandle;
/// A triangle of a `Mesh` (index or invalid).
using FaceHandle = OpenMesh::FaceHandle;

/// True when `mesh` has the attributes `MeshTraits` promise: status on vertices, edges, halfedges
/// and faces, and face normals. `Mesh::assign(other)` from an OpenMesh mesh of other traits
/// (floats, no status) copies only connectivity and points and leaves them out; every entry point
/// that reads them refuses such a mesh (`require_attributes`). Convert with
/// `edgefront::mesh_from_openmesh` (edgefront/arrays.h) or call `restore_attributes` after `assign`.
bool has_attributes(const Mesh& mesh);
/// Adds the attributes `has_attributes` checks (no element deleted) and computes the face normals.
void restore_attributes(Mesh& mesh);
/// Checks `has_attributes(mesh)`.
/// \param mesh the mesh to check.
/// \param what names the caller in the message (e.g. "distance").
/// \throws InvalidInput naming `what` when `has_attributes(mesh)` is false, with the fix.
void require_attributes(const Mesh& mesh, const char* what);

/// True when `v` names an existing, non-deleted vertex of `mesh`.
inline bool is_live(const Mesh& mesh, VertexHandle v) {
  return v.is_valid() && static_cast<size_t>(v.idx()) < mesh.n_vertices() && !mesh.status(v).deleted();
}
/// True when `h` names an existing, non-deleted halfedge of `mesh`.
inline bool is_live(const Mesh& mesh, HalfedgeHandle h) {
  return h.is_valid() && static_cast<size_t>(h.idx()) < mesh.n_halfedges() && !mesh.status(h).deleted();
}
/// True when `f` names an existing, non-deleted face of `mesh`.
inline bool is_live(const Mesh& mesh, FaceHandle f) {
  return f.is_valid() && static_cast<size_t>(f.idx()) < mesh.n_faces() && !mesh.status(f).deleted();
}

}  // namespace edgefront
