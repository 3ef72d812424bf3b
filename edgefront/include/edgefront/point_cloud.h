#pragma once
/// \file point_cloud.h
/// An oriented or unoriented point set: the input of the reconstructor.

#include <vector>

#include "edgefront/mesh.h"

namespace edgefront {

/// Points with optional per-point unit normals (`normals` is empty or the same size as `points`).
struct PointCloud {
  std::vector<Vec3> points;   ///< positions, in the data's length unit
  std::vector<Vec3> normals;  ///< empty (unoriented), or one unit normal per point, same order

  /// True when there is one normal per point (and at least one point).
  bool has_normals() const { return !normals.empty() && normals.size() == points.size(); }
  /// Number of points.
  size_t size() const { return points.size(); }
  /// True without points.
  bool empty() const { return points.empty(); }
};

}  // namespace edgefront
