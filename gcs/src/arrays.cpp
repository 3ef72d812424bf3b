// Reconstruction on plain arrays.

#include "gcs/arrays.h"

#include <string>

#include "edgefront/error.h"

namespace gcs {

ArrayReconstruction reconstruct_arrays(const edgefront::VertexArrayView& points, const edgefront::VertexArrayView& normals,
                                       const ReconstructOptions& options) {
  points.check_values("points");
  edgefront::PointCloud cloud;
  cloud.points.reserve(points.rows());
  for (size_t i = 0; i < points.rows(); ++i) cloud.points.push_back(points.point(i));
  if (normals.size() > 0) {
    normals.check_values("normals");
    if (normals.rows() != points.rows()) {
      throw edgefront::InvalidInput("normals: " + std::to_string(normals.rows()) + " rows for " +
                                    std::to_string(points.rows()) + " points");
    }
    cloud.normals.reserve(normals.rows());
    for (size_t i = 0; i < normals.rows(); ++i) cloud.normals.push_back(normals.point(i));
  }
  ReconstructResult r = reconstruct(std::move(cloud), options);
  ArrayReconstruction out;
  out.mesh = edgefront::mesh_to_arrays(r.mesh);
  out.stop_reason = r.stop_reason;
  out.basic_steps = r.basic_steps;
  out.batches = r.batches;
  return out;
}

}  // namespace gcs
