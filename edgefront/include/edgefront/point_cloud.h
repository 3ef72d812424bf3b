#pragma once
/// \file point_cloud.h
/// An oriented or unoriented point set: the input of the reconstructor.

#include <vector>

#include "edgefront/mesh.h"

namespace edgefront {

/// Points with optional per-point unit normals (`normals` is empty or the same size as `points`).
struct PointCloud {
  std::vector<Vec3> points;
  std::vector<Vec3> normals;

  bool has_normals() const { return !normals.empty() && normals.size() == points.size(); }
  size_t size() const { return points.size(); }
  bool empty() const { return points.empty(); }
};

}  // namespace edgefront
