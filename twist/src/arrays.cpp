// The twist detector and repair on plain arrays.

#include "twist/arrays.h"

#include <string>

#include "detail/host_mirror.h"
#include "edgefront/error.h"

namespace twist {

using edgefront::FaceArrayView;
using edgefront::InvalidInput;
using edgefront::VertexArrayView;

ReferenceNormals reference_from_arrays(const VertexArrayView& points, const VertexArrayView& normals) {
  points.check_values("reference points");
  normals.check_values("reference normals");
  if (points.rows() != normals.rows()) {
    throw InvalidInput("reference normals: " + std::to_string(normals.rows()) + " rows for " + std::to_string(points.rows()) +
                       " points");
  }
  edgefront::PointCloud cloud;
  cloud.points.reserve(points.rows());
  cloud.normals.reserve(points.rows());
  for (size_t i = 0; i < points.rows(); ++i) {
    cloud.points.push_back(points.point(i));
    cloud.normals.push_back(normals.point(i));
  }
  return ReferenceNormals(std::move(cloud));
}

ArrayDetection detect_arrays(const VertexArrayView& vertices, const FaceArrayView& faces, const DetectOptions& options) {
  if (options.incremental.restrict_to)
    throw InvalidInput("twist::detect_arrays: restrict_to names mesh faces; it is not for arrays");
  if (options.incremental.face_grid)
    throw InvalidInput("twist::detect_arrays: a face grid belongs to a mesh; it is not for arrays");
  const edgefront::ArrayMesh converted = edgefront::mesh_from_arrays(vertices, faces);
  const DetectResult found = detect_regions(converted.mesh, options);
  ArrayDetection out;
  out.face_region.assign(converted.face_of_row.size(), -1);
  for (size_t i = 0; i < found.regions.size(); ++i) {
    const TwistRegion& region = found.regions[i];
    for (edgefront::FaceHandle f : region.faces) out.face_region[static_cast<size_t>(converted.face_row[static_cast<size_t>(f.idx())])] = static_cast<int>(i);
    out.region_faces.push_back(region.faces.size());
    out.region_flagged.push_back(region.flagged_faces);
  }
  out.stats = found.stats;
  out.conversion = converted.report;
  return out;
}

ArrayRepair repair_arrays(const VertexArrayView& vertices, const FaceArrayView& faces, const RepairOptions& options) {
  if (options.detect.incremental.restrict_to)
    throw InvalidInput("twist::repair_arrays: restrict_to names mesh faces; it is not for arrays");
  if (options.detect.incremental.face_grid)
    throw InvalidInput("twist::repair_arrays: a face grid belongs to a mesh; it is not for arrays");
  edgefront::ArrayMesh converted = edgefront::mesh_from_arrays(vertices, faces);
  detail::HostMirror host = detail::host_of_conversion(vertices, faces, converted);
  RepairOptions o = options;
  o.garbage_collect = false;  // the host's indices are never compacted
  ArrayRepair out;
  out.report = repair(converted.mesh, o);
  out.record = detail::bring_up_to_date(host, converted.mesh);
  out.conversion = converted.report;
  return out;
}

ArrayRepair orient_arrays(const VertexArrayView& vertices, const FaceArrayView& faces, const RepairOptions& options) {
  edgefront::ArrayMesh converted = edgefront::mesh_from_arrays(vertices, faces);
  detail::HostMirror host = detail::host_of_conversion(vertices, faces, converted);
  RepairOptions o = options;
  o.garbage_collect = false;  // the host's indices are never compacted
  ArrayRepair out;
  out.report = orient(converted.mesh, o);
  out.record = detail::bring_up_to_date(host, converted.mesh);
  out.conversion = converted.report;
  return out;
}

}  // namespace twist
