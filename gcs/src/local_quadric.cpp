#include "detail/local_quadric.h"

#include <algorithm>
#include <cmath>

namespace gcs::detail {

using edgefront::PointIndex;
using edgefront::Vec3;

namespace {

constexpr std::size_t kMinNeighbours = 8;
constexpr double kSameSideCos = 0.5;  // neighbours' normals within 60 degrees

Eigen::Vector3d eig(const Vec3& p) { return {p[0], p[1], p[2]}; }

}  // namespace

QuadricFitter::QuadricFitter(const edgefront::PointCloud& cloud)
    : points_(cloud.points),
      normals_(cloud.has_normals() ? &cloud.normals : nullptr),
      own_index_(std::make_unique<PointIndex>(cloud.points)),
      index_(own_index_.get()) {}

QuadricFitter::QuadricFitter(const edgefront::PointCloud& cloud, const PointIndex& index)
    : points_(cloud.points), normals_(cloud.has_normals() ? &cloud.normals : nullptr), index_(&index) {}

QuadricFitter::QuadricFitter(const std::vector<Vec3>& points, const PointIndex& index)
    : points_(points), normals_(nullptr), index_(&index) {}

bool QuadricFitter::fit(std::size_t i, std::size_t k, LocalQuadric& q) {
  gather(i, k, k);
  if (normals_ && pts_.size() < k) gather(i, 2 * k, k);  // the other wall took some places
  return fit_gathered(q);
}

bool QuadricFitter::fit_from(std::size_t i, std::size_t k, const std::vector<PointIndex::Neighbor>& candidates,
                             LocalQuadric& q) {
  near_.clear();
  for (const PointIndex::Neighbor& h : candidates) {
    if (normals_ && ((*normals_)[h.index] | (*normals_)[i]) < kSameSideCos) continue;
    near_.push_back({h.index, (points_[h.index] - points_[i]).sqrnorm()});
  }
  if (near_.size() < k) return fit(i, k, q);  // e.g. the other wall of a thin shell in the cell
  std::nth_element(near_.begin(), near_.begin() + static_cast<std::ptrdiff_t>(k), near_.end(),
                   [](const PointIndex::Neighbor& a, const PointIndex::Neighbor& b) {
                     return a.distance2 != b.distance2 ? a.distance2 < b.distance2 : a.index < b.index;
                   });
  pts_.clear();
  for (std::size_t j = 0; j < k; ++j) pts_.push_back(eig(points_[near_[j].index]));
  return fit_gathered(q);
}

bool QuadricFitter::fit_gathered(LocalQuadric& q) {
  const std::size_t m = pts_.size();
  if (m < kMinNeighbours) return false;
  q.origin.setZero();
  for (const Eigen::Vector3d& p : pts_) q.origin += p;
  q.origin /= static_cast<double>(m);
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3d& p : pts_) cov += (p - q.origin) * (p - q.origin).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(cov);
  const Eigen::Vector3d ev = es.eigenvalues();  // ascending
  if (!(ev[1] > 1e-12 * ev[2])) return false;    // collinear or coincident neighbours
  q.n = es.eigenvectors().col(0);
  q.v = es.eigenvectors().col(1);
  q.u = es.eigenvectors().col(2);
  // Least squares by the normal equations, in coordinates scaled to the neighbourhood's extent
  // (well conditioned: every entry of a row is at most about 1).
  const double scale = 1.0 / std::sqrt(ev[2] / static_cast<double>(m));
  Eigen::Matrix<double, 6, 6> ata = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Matrix<double, 6, 1> atb = Eigen::Matrix<double, 6, 1>::Zero(), row;
  double btb = 0;
  for (const Eigen::Vector3d& p : pts_) {
    const Eigen::Vector3d d = (p - q.origin) * scale;
    const double x = d.dot(q.u), y = d.dot(q.v), z = d.dot(q.n);
    row << x * x, x * y, y * y, x, y, 1;
    ata.selfadjointView<Eigen::Lower>().rankUpdate(row);
    atb += z * row;
    btb += z * z;
  }
  const Eigen::LDLT<Eigen::Matrix<double, 6, 6>> ldlt(ata.selfadjointView<Eigen::Lower>());
  if (ldlt.info() != Eigen::Success) return false;
  Eigen::Matrix<double, 6, 1> c = ldlt.solve(atb);
  if (!c.allFinite()) return false;
  const double ss = std::max(0.0, btb - c.dot(atb)) / (scale * scale);
  // Back to unscaled coordinates: z = s z', x' = s x.
  q.coef << c[0] * scale, c[1] * scale, c[2] * scale, c[3], c[4], c[5] / scale;
  q.residual = std::sqrt(ss / static_cast<double>(m - 6));
  q.spread = std::sqrt((ev[1] + ev[2]) / static_cast<double>(m));
  return std::isfinite(q.residual);
}


void QuadricFitter::gather(std::size_t i, std::size_t query, std::size_t k) {
  index_->k_nearest(points_[i], query, hits_);
  pts_.clear();
  for (const PointIndex::Neighbor& h : hits_) {
    if (pts_.size() == k) break;
    if (normals_ && ((*normals_)[h.index] | (*normals_)[i]) < kSameSideCos) continue;
    pts_.push_back(eig(points_[h.index]));
  }
}

}  // namespace gcs::detail
