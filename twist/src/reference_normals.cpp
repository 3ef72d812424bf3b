#include "twist/reference_normals.h"

#include <cmath>
#include <limits>
#include <vector>
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

Vec3 ReferenceNormals::side_normal(const Vec3& centre, const Vec3& normal, size_t candidates, double normal_weight) const {
  if (candidates == 0) throw InvalidInput("reference normals: side_normal needs at least one candidate");
  if (!(normal_weight >= 1) || !std::isfinite(normal_weight)) {
    throw InvalidInput("reference normals: side_normal's normal_weight must be finite and >= 1");
  }
  if (normal.sqrnorm() == 0) return nearest_normal(centre);
  thread_local std::vector<edgefront::PointIndex::Neighbor> near;
  impl_->index.k_nearest(centre, candidates, near);
  const double w2 = normal_weight * normal_weight;
  size_t best = near.front().index;
  double best_cost = std::numeric_limits<double>::infinity();
  for (const auto& nb : near) {
    const size_t i = nb.index;
    const Vec3 d = impl_->cloud.points[i] - centre;
    const double along = OpenMesh::dot(d, normal);
    const double cost = d.sqrnorm() + (w2 - 1) * along * along;
    if (cost < best_cost) {
      best_cost = cost;
      best = i;
    }
  }
  return impl_->cloud.normals[best];
}

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
