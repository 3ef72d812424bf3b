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
void ReferenceNormals::within(const Vec3& p, double radius, std::vector<size_t>& out) const {
  impl_->index.radius_search(p, radius, out);
}
const edgefront::PointCloud& ReferenceNormals::cloud() const { return impl_->cloud; }

int ReferenceNormals::judge(const Vec3& centre, const Vec3& normal, size_t candidates, double normal_weight,
                           double margin) const {
  if (candidates == 0) throw InvalidInput("reference normals: judge needs at least one candidate");
  if (!(normal_weight >= 1) || !std::isfinite(normal_weight)) {
    throw InvalidInput("reference normals: judge's normal_weight must be finite and >= 1");
  }
  if (!(margin >= 1) || !std::isfinite(margin)) throw InvalidInput("reference normals: judge's margin must be finite and >= 1");
  if (normal.sqrnorm() == 0) return 0;
  thread_local std::vector<edgefront::PointIndex::Neighbor> near;
  impl_->index.k_nearest(centre, candidates, near);
  const double w2 = normal_weight * normal_weight;
  double agree = std::numeric_limits<double>::infinity(), disagree = agree;  // squared weighted distances
  for (const auto& nb : near) {
    const Vec3 d = impl_->cloud.points[nb.index] - centre;
    const double along = OpenMesh::dot(d, normal);
    const double cost = d.sqrnorm() + (w2 - 1) * along * along;
    double& best = OpenMesh::dot(impl_->cloud.normals[nb.index], normal) > 0 ? agree : disagree;
    best = std::min(best, cost);
  }
  const double m2 = margin * margin;
  if (agree * m2 < disagree) return 1;
  if (disagree * m2 < agree) return -1;
  if (agree == 0 && disagree > 0) return 1;
  if (disagree == 0 && agree > 0) return -1;
  return 0;
}

double ReferenceNormals::wall_thickness(const Vec3& p, size_t candidates) const {
  if (candidates == 0) throw InvalidInput("reference normals: wall_thickness needs at least one candidate");
  thread_local std::vector<edgefront::PointIndex::Neighbor> near;
  impl_->index.k_nearest(p, candidates, near);
  if (near.empty()) return std::numeric_limits<double>::infinity();
  const Vec3& p0 = impl_->cloud.points[near.front().index];
  const Vec3& n0 = impl_->cloud.normals[near.front().index];
  for (const auto& nb : near) {  // nearest first
    if (OpenMesh::dot(impl_->cloud.normals[nb.index], n0) < -0.5) return std::abs(OpenMesh::dot(impl_->cloud.points[nb.index] - p0, n0));
  }
  return std::numeric_limits<double>::infinity();
}

std::optional<size_t> ReferenceNormals::nearest_facing(const Vec3& p, const Vec3& normal, size_t candidates) const {
  if (candidates == 0) throw InvalidInput("reference normals: nearest_facing needs at least one candidate");
  thread_local std::vector<edgefront::PointIndex::Neighbor> near;
  impl_->index.k_nearest(p, candidates, near);
  for (const auto& nb : near) {  // nearest first
    if (OpenMesh::dot(impl_->cloud.normals[nb.index], normal) > 0) return nb.index;
  }
  return std::nullopt;
}

double face_orientation_agreement(const edgefront::Mesh& mesh, const ReferenceNormals& reference) {
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
  if (!(total > 0)) throw InvalidInput("twist::face_orientation_agreement: the mesh has no face of positive area");
  return agree / total;
}

}  // namespace twist
