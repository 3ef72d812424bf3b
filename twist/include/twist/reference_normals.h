#pragma once
/// \file reference_normals.h
/// Oriented reference points (a point cloud with normals) that decide which side of a surface is
/// right: the normal of the nearest reference point. Used by the twist detector and repair when
/// the reconstructor's input cloud has normals, and to measure orientation consistency.

#include <memory>

#include "edgefront/mesh.h"
#include "edgefront/point_cloud.h"

namespace twist {

/// A point cloud with unit normals and a k-d tree over its points (built once, queried often).
class ReferenceNormals {
 public:
  /// \throws edgefront::InvalidInput when the cloud is empty, has no normals (or a normal count
  ///         different from the point count), or holds non-finite points or zero/non-finite
  ///         normals (the message names the first bad index).
  explicit ReferenceNormals(edgefront::PointCloud cloud);
  ~ReferenceNormals();
  ReferenceNormals(ReferenceNormals&&) noexcept;
  ReferenceNormals& operator=(ReferenceNormals&&) noexcept;

  /// Index of the reference point nearest to `p` (ties: lowest index).
  size_t nearest(const edgefront::Vec3& p) const;
  /// Unit normal of the reference point nearest to `p`.
  edgefront::Vec3 nearest_normal(const edgefront::Vec3& p) const;
  /// Unit normal of the reference point that stands for the surface a face at `centre` with unit
  /// normal `normal` lies on: among the `candidates` nearest points, the one with the smallest
  /// distance when offsets along `normal` count `normal_weight` times (tangential^2 +
  /// (normal_weight * along)^2). On a wall thinner than the mesh's edges the plainly nearest
  /// point is often on the other side of the wall; the point of the face's own side lies in its
  /// plane. A zero `normal` gives `nearest_normal(centre)`.
  /// \throws edgefront::InvalidInput when `candidates` is 0 or `normal_weight` < 1 or not finite.
  edgefront::Vec3 side_normal(const edgefront::Vec3& centre, const edgefront::Vec3& normal, size_t candidates = 16,
                              double normal_weight = 4.0) const;
  const edgefront::PointCloud& cloud() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Area-weighted share (in [0, 1]) of the live, non-degenerate faces of `mesh` whose normal
/// agrees (positive dot product) with the normal of the reference point nearest to the face's
/// centroid. No per-component sign is forgiven: this is the absolute orientation consistency.
/// \throws edgefront::InvalidInput when the mesh has no face of positive area.
double orientation_consistency(const edgefront::Mesh& mesh, const ReferenceNormals& reference);

}  // namespace twist
