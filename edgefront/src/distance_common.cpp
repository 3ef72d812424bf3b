// The input checks shared by the distance modes (detail/distance_common.h).
#include <algorithm>
#include <cmath>
#include <string>

#include "detail/distance_common.h"
#include "edgefront/coordinate_range.h"
#include "edgefront/error.h"

namespace edgefront::detail {

void check_distance_options(const Mesh& mesh, const DistanceOptions& o) {
  if (std::isnan(o.max_distance) || o.max_distance < 0) {
    throw InvalidInput("distance: max_distance must be a non-negative number, got " + std::to_string(o.max_distance));
  }
  if (o.target && !is_live(mesh, *o.target)) {
    throw InvalidInput("distance: target vertex " + std::to_string(o.target->idx()) + " is not a vertex of the mesh");
  }
}

void check_finite_vertex(const Vec3& position, int v) {
  if (!std::isfinite(position[0]) || !std::isfinite(position[1]) || !std::isfinite(position[2]))
    throw InvalidInput("distance: vertex " + std::to_string(v) + " has a NaN or infinite coordinate");
  if (std::max({std::abs(position[0]), std::abs(position[1]), std::abs(position[2])}) > kMaxCoordinate) {
    throw InvalidInput("distance: vertex " + std::to_string(v) + " has a coordinate beyond +-" +
                       number_for_message(kMaxCoordinate) + " (coordinate_range.h): squared lengths would overflow");
  }
}

// Checks source points; returns the vertices of their faces (each once).
std::vector<VertexHandle> check_points(const Mesh& mesh, const std::vector<SurfacePoint>& points) {
  require_attributes(mesh, "distance");
  if (points.empty()) throw InvalidInput("distance: no source points given");
  std::vector<VertexHandle> verts;
  for (size_t i = 0; i < points.size(); ++i) {
    const SurfacePoint& p = points[i];
    const std::string which = "distance: source point " + std::to_string(i);
    if (!is_live(mesh, p.face)) {
      throw InvalidInput(which + ": face " + std::to_string(p.face.idx()) + " is not a face of the mesh");
    }
    double sum = 0;
    for (double b : p.bary) {
      if (!std::isfinite(b) || b < -1e-12) {
        throw InvalidInput(which + ": barycentric coordinates must be finite and non-negative");
      }
      sum += b;
    }
    if (std::abs(sum - 1.0) > 1e-9) {
      throw InvalidInput(which + ": barycentric coordinates sum to " + std::to_string(sum) + ", not 1");
    }
    for (VertexHandle v : mesh.fv_range(p.face)) {
      check_finite_vertex(mesh.point(v), v.idx());
      if (std::find(verts.begin(), verts.end(), v) == verts.end()) verts.push_back(v);
    }
  }
  return verts;
}

}  // namespace edgefront::detail
