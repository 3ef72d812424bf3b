#pragma once
/// \file operation.h
/// The hook API of the GCS reconstructor: operations that the refinement loop calls after each
/// batch of vertex splits with the mesh and the elements changed since their last call.
///
/// An operation may change the mesh in any way that keeps it a valid OpenMesh triangle mesh
/// (cut, flip, delete faces or vertices, add vertices, e.g. duplicating them along a cut, create
/// borders). It must not call `garbage_collection()` (handles in the change set and in the loop's
/// state are indices), and should leave face normals it made stale to the loop (the loop
/// recomputes what it needs). After an operation reports `mesh_changed`, the reconstructor
/// re-synchronizes its own state (signal counters, spatial index, activity) with the mesh; see
/// `Reconstructor::validate`.
///
/// Renumbering: on large meshes the loop renumbers the mesh's elements in spatial order now and
/// then, between two calls (memory locality of the basic step; deleted elements are dropped). An
/// operation that keeps handles from one call to the next must translate them then: it opts in
/// with `can_follow_renumbering` and gets the old -> new maps in `on_renumbered`. By default an
/// operation does not opt in, and the loop does not renumber while it is registered.
///
/// \code
///   class DeleteFarFaces : public gcs::Operation {
///    public:
///     std::string name() const override { return "delete-far-faces"; }
///     gcs::OperationResult apply(edgefront::Mesh& mesh, const gcs::ChangeSet& changed,
///                                const gcs::OperationContext& context) override {
///       gcs::OperationResult r;
///       for (auto f : changed.faces) { /* ... mesh.delete_face(f); r.mesh_changed = true; */ }
///       return r;
///     }
///   };
///   reconstructor.add_operation(std::make_shared<DeleteFarFaces>());
/// \endcode

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "edgefront/mesh.h"
#include "edgefront/point_cloud.h"

namespace gcs {

/// Elements created, moved or re-connected since the operation's previous call (or since the
/// start, for its first call). Every handle is live (valid and not deleted) at the time of the
/// call; each appears once; both lists are sorted by index.
struct ChangeSet {
  std::vector<edgefront::Mesh::VertexHandle> vertices;  ///< changed vertices, by increasing index
  std::vector<edgefront::Mesh::FaceHandle> faces;       ///< changed faces, by increasing index

  /// True when nothing changed.
  bool empty() const { return vertices.empty() && faces.empty(); }
};

/// Old index -> new index of the mesh's elements after the reconstructor renumbered its mesh (-1:
/// the element was deleted and is gone). Halfedges follow their edge with the same direction:
/// halfedge 2e + s becomes 2 edge[e] + s. Positions, connectivity and each vertex's and face's
/// circulation start are unchanged; only the indices change.
struct MeshRenumbering {
  std::vector<int> vertex;  ///< by old vertex index
  std::vector<int> edge;    ///< by old edge index
  std::vector<int> face;    ///< by old face index

  /// The new handle of an old one; an invalid handle when the element is gone or `old` is
  /// invalid or out of range.
  edgefront::VertexHandle operator()(edgefront::VertexHandle old) const {
    return edgefront::VertexHandle(lookup(vertex, old.idx()));
  }
  /// The same for a face.
  edgefront::FaceHandle operator()(edgefront::FaceHandle old) const { return edgefront::FaceHandle(lookup(face, old.idx())); }
  /// The same for an edge.
  edgefront::EdgeHandle operator()(edgefront::EdgeHandle old) const { return edgefront::EdgeHandle(lookup(edge, old.idx())); }
  /// The same for a halfedge (it follows its edge, keeping its direction).
  edgefront::HalfedgeHandle operator()(edgefront::HalfedgeHandle old) const {
    const int e = old.is_valid() ? lookup(edge, old.idx() / 2) : -1;
    return edgefront::HalfedgeHandle(e < 0 ? -1 : 2 * e + old.idx() % 2);
  }

 private:
  static int lookup(const std::vector<int>& map, int i) {
    return i >= 0 && static_cast<std::size_t>(i) < map.size() ? map[static_cast<std::size_t>(i)] : -1;
  }
};

/// What an operation may read besides the mesh. Cheap to build; valid only during the call.
struct OperationContext {
  const edgefront::PointCloud& points;  ///< the input samples (normals when the input had them)
  /// For a large cloud with normals that the loop queries through a spatially even subsample
  /// (InputOptions::max_query_points): that subsample, points with their normals, in the
  /// same coordinates as `points`; an operation that searches the samples may use it instead (a
  /// k-d tree over it is cheaper to build and to query). nullptr when the loop uses the whole cloud.
  const edgefront::PointCloud* query_points = nullptr;
  double mean_edge_length = 0;          ///< over the live edges of the mesh, at the call
  double bbox_diagonal = 0;             ///< of the input points
  std::size_t live_vertices = 0;        ///< live vertices of the mesh, at the call
  std::size_t target_vertices = 0;      ///< the reconstruction's target vertex count
  std::uint64_t basic_steps = 0;        ///< basic steps done so far
  std::size_t batch = 0;                ///< 1-based index of the batch that just ended
  bool final_call = false;              ///< true for the extra call after the loop stopped
};

/// What an operation reports.
struct OperationResult {
  bool mesh_changed = false;  ///< true when the operation changed the mesh in any way
  std::string summary;        ///< short human-readable text (empty when nothing happened)
};

/// A mesh operation the reconstructor calls after each refinement batch (see the file comment).
class Operation {
 public:
  virtual ~Operation() = default;
  /// Short name used in reports, e.g. "twist-repair".
  virtual std::string name() const = 0;
  /// Called with the current mesh and the elements changed since this operation's previous call.
  /// May throw an `edgefront::Error`; the reconstructor then stops and rethrows it.
  virtual OperationResult apply(edgefront::Mesh& mesh, const ChangeSet& changed,
                                const OperationContext& context) = 0;
  /// Asked right before the loop would renumber the mesh (see the file comment): true when the
  /// operation can translate the handles it keeps (in `on_renumbered`). The default, false, keeps
  /// the loop from renumbering while this operation is registered; the loop asks again later.
  virtual bool can_follow_renumbering() const { return false; }
  /// Called right after the loop renumbered the mesh (only after `can_follow_renumbering` returned
  /// true), with the renumbered mesh and the maps from old to new indices. Handles kept from an
  /// earlier call are old handles: translate them with `map`. The next `apply` gets a change set
  /// in the new numbering (the elements changed since the previous call, as usual).
  virtual void on_renumbered(const edgefront::Mesh& mesh, const MeshRenumbering& map) {
    (void)mesh;
    (void)map;
  }
};

}  // namespace gcs
