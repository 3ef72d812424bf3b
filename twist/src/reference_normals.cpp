#include "twist/reference_normals.h"

#include <cmath>
#include <string>

#include "detail/geometry.h"
#include "edgefront/error.h"
#include "edgefront/point_index.h"

namespace twist {

using edgefront::InvalidInput;
using edgefront::Vec3;

struct ReferenceNormals::Impl {
  edgefront::PointCloud cloud;
  edgefront::PointIndex index;
  explicit Impl(edgefront::PointCloud c) : cloud(std::move(c)), index(cloud.points) {}
};

namespace {
edgefront::PointCloud checked(edgefront::PointCloud cloud) {
  if (cloud.empty()) throw InvalidInput("reference normals: the point cloud is empty");
  if (!cloud.has_normals()) {
    throw InvalidInput("reference normals: the point cloud has " + std::to_string(cloud.normals.size()) + " normals for " +
                       std::to_string(cloud.points.size()) + " points (need one unit normal per point)");
  }
  for (size_t i = 0; i < cloud.size(); ++i) {
    const Vec3& p = cloud.points[i];
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
      throw InvalidInput("reference normals: point " + std::to_string(i) + " is not finite");
    }
    const double len = cloud.normals[i].norm();
    if (!(len > 0) || !std::isfinite(len)) {
      throw InvalidInput("reference normals: normal " + std::to_string(i) + " is zero or not finite");
    }
    cloud.normals[i] /= len;
  }
  return cloud;
}
}  // namespace

ReferenceNormals::ReferenceNormals(edgefront::PointCloud cloud)
    : impl_(std::make_unique<Impl>(checked(std::move(cloud)))) {}
ReferenceNormals::~ReferenceNormals() = default;
ReferenceNormals::ReferenceNormals(ReferenceNormals&&) noexcept = default;
ReferenceNormals& ReferenceNormals::operator=(ReferenceNormals&&) noexcept = default;

size_t ReferenceNormals::nearest(const Vec3& p) const { return impl_->index.nearest(p).index; }
Vec3 ReferenceNormals::nearest_normal(const Vec3& p) const { return impl_->cloud.normals[nearest(p)]; }
const edgefront::PointCloud& ReferenceNormals::cloud() const { return impl_->cloud; }

double orientation_consistency(const edgefront::Mesh& mesh, const ReferenceNormals& reference) {
  double total = 0;
  double agree = 0;
  for (edgefront::FaceHandle f : mesh.faces()) {
    const auto p = detail::face_points(mesh, f);
    const double a = detail::area(p);
    const Vec3 n = detail::unit_normal(p);
    if (!(a > 0) || n.sqrnorm() == 0) continue;
    total += a;
    if (OpenMesh::dot(n, reference.nearest_normal(detail::centroid(p))) > 0) agree += a;
  }
  if (!(total > 0)) throw InvalidInput("orientation consistency: the mesh has no face of positive area");
  return agree / total;
}

}  // namespace twist
