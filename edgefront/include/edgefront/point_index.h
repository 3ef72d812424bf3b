#pragma once
/// \file point_index.h
/// A k-d tree over a fixed set of points: nearest, k nearest and radius queries. One index for
/// the whole project (the reconstructor's cloud, the evaluation's samples, the twist detector's
/// face centres); nanoflann stays behind this header, so users need not find it. The queries are
/// const and may run from several threads at once.

#include <cstddef>
#include <memory>
#include <vector>

#include "edgefront/mesh.h"

namespace edgefront {

/// A k-d tree over a fixed set of points (see the file comment). The points are fixed at
/// construction. The queries are const and may run from several threads at once on one index
/// (k_nearest keeps its scratch per thread). Movable, not copyable.
class PointIndex {
 public:
  /// Builds the tree over `points` (kept inside; read them back with points()). An empty set is
  /// allowed: nearest() then throws, k_nearest() and radius_search() find nothing.
  /// \throws InvalidInput if a coordinate is NaN or infinite (naming the point).
  explicit PointIndex(std::vector<Vec3> points);
  ~PointIndex();
  /// Takes over the moved-from index's tree and points; that index may then only be destroyed or
  /// assigned to.
  PointIndex(PointIndex&&) noexcept;
  /// Takes over the moved-from index's tree and points (as the move constructor).
  PointIndex& operator=(PointIndex&&) noexcept;
  PointIndex(const PointIndex&) = delete;
  PointIndex& operator=(const PointIndex&) = delete;

  /// One query result: the point's index and its squared distance to the query.
  struct Neighbor {
    size_t index = 0;      ///< index into points()
    double distance2 = 0;  ///< squared Euclidean distance to the query (length unit squared)
  };

  /// The nearest point (ties: any of them). \throws InvalidInput on an empty index.
  Neighbor nearest(const Vec3& p) const;
  /// The min(k, size()) nearest points, nearest first, written to `out` (cleared first).
  /// \param p the query point.
  /// \param k how many neighbours (0: none).
  /// \param out receives the neighbours (index and squared distance).
  void k_nearest(const Vec3& p, size_t k, std::vector<Neighbor>& out) const;
  /// Indices of the points closer than `radius` to `p` (strictly), in increasing index order
  /// (deterministic whatever the tree's traversal), written to `out` (cleared first).
  /// \param p the query point.
  /// \param radius the search radius, in the points' length unit; negative or NaN finds nothing.
  /// \param out receives the point indices.
  void radius_search(const Vec3& p, double radius, std::vector<size_t>& out) const;

  /// The points the tree was built over, in the order given.
  const std::vector<Vec3>& points() const;
  /// Number of points.
  size_t size() const;
  /// True without points.
  bool empty() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace edgefront
