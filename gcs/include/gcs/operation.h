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
  std::vector<edgefront::Mesh::VertexHandle> vertices;
  std::vector<edgefront::Mesh::FaceHandle> faces;

  bool empty() const { return vertices.empty() && faces.empty(); }
};

/// What an operation may read besides the mesh. Cheap to build; valid only during the call.
struct OperationContext {
  const edgefront::PointCloud& points;  ///< the input samples (normals when the input had them)
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
};

}  // namespace gcs
