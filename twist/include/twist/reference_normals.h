#pragma once
/// \file reference_normals.h
/// Oriented reference points (a point cloud with normals) that decide which side of a surface is
/// right: the normal of the nearest reference point. Used by the twist detector and repair when
/// the reconstructor's input cloud has normals, and to measure the faces' orientation agreement.

#include <cstddef>
#include <memory>
#include <optional>
#include <vector>

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
  /// Takes over the moved-from object's points and tree; that object may then only be destroyed or assigned to.
  ReferenceNormals(ReferenceNormals&&) noexcept;
  /// Takes over the moved-from object's points and tree; that object may then only be destroyed or assigned to.
  ReferenceNormals& operator=(ReferenceNormals&&) noexcept;

  /// Index of the reference point nearest to `p` (ties: lowest index).
  size_t nearest(const edgefront::Vec3& p) const;
  /// Unit normal of the reference point nearest to `p`.
  edgefront::Vec3 nearest_normal(const edgefront::Vec3& p) const;
  /// Indices of the reference points closer than `radius` to `p`, in increasing index order
  /// (deterministic), written to `out` (cleared first); nothing for a negative or NaN radius.
  void within(const edgefront::Vec3& p, double radius, std::vector<size_t>& out) const;
  /// How the reference judges the orientation of a face at `centre` with unit normal `normal`:
  /// +1 agrees, -1 disagrees, 0 ambiguous. Among the `candidates` nearest points, distances
  /// count offsets along `normal` `normal_weight` times (tangential^2 + (normal_weight *
  /// along)^2), so the points of the face's own wall (in its plane) are nearest; the vote is
  /// the side of the nearest agreeing (n.n_ref > 0) or disagreeing point when it is nearer than
  /// the other kind by the factor `margin` (in distance), else ambiguous: a face between the two
  /// walls of a wall thinner than the mesh's edges (both walls about equally far, one agreeing,
  /// one not, whichever way the face points) has no decidable side. A zero `normal` is
  /// ambiguous. \throws edgefront::InvalidInput when `candidates` is 0, `normal_weight` < 1 or
  /// `margin` < 1 (or not finite).
  int judge(const edgefront::Vec3& centre, const edgefront::Vec3& normal, size_t candidates = 16,
            double normal_weight = 4.0, double margin = 1.5) const;
  /// The thickness of the wall at `p`: the offset, along the normal n0 of the reference point
  /// nearest to `p`, between that point and the nearest of the `candidates` nearest points whose
  /// normal opposes n0 (n.n0 < -0.5), i.e. the distance between the two sides of a thin wall
  /// that `p` lies on or between; infinity when no candidate opposes (a wall thicker than the
  /// candidates reach). \throws edgefront::InvalidInput when `candidates` is 0.
  double wall_thickness(const edgefront::Vec3& p, size_t candidates = 16) const;
  /// Index of the reference point nearest to `p` among its `candidates` nearest whose normal
  /// agrees with `normal` (n.normal > 0): the point of the wall that a surface facing `normal`
  /// at `p` approximates, where two walls facing opposite ways are both near. None when no
  /// candidate agrees. \throws edgefront::InvalidInput when `candidates` is 0.
  std::optional<size_t> nearest_facing(const edgefront::Vec3& p, const edgefront::Vec3& normal, size_t candidates = 16) const;
  /// The reference points and their normals, as given.
  const edgefront::PointCloud& cloud() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Area-weighted share (in [0, 1]) of the live, non-degenerate faces of `mesh` whose normal
/// agrees (positive dot product) with the normal of the reference point nearest to the face's
/// centroid: one vote per face, deterministic, no sampling. No per-component sign is forgiven.
///
/// Not the same measure as `gcs::orientation_consistency` (gcs/evaluation.h), which compares
/// area-uniform random samples of the mesh (count and seed in its options) with their nearest
/// ground-truth normals and also reports the share per connected component and with each
/// component's sign forgiven. Its `raw` field estimates the same share as this function, but
/// the two differ by the sampling (a face's centroid against points spread over the face). Use
/// this one to check a twist repair (cheap, exact for a given mesh, what ef-twist prints); use
/// gcs::orientation_consistency (or gcs::evaluate) to judge a reconstruction.
/// \throws edgefront::InvalidInput when the mesh has no face of positive area.
double face_orientation_agreement(const edgefront::Mesh& mesh, const ReferenceNormals& reference);

}  // namespace twist
