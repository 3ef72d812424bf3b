#pragma once
// A quadric height field fitted to a point's nearest points (the noise estimate and the
// smoothing of cloud_noise.h, the fitted normals of cloud_normals.h).
//
// Around a point, z = a x^2 + b xy + c y^2 + d x + e y + f is fitted by least squares to its
// neighbours, in the frame (origin, u, v, n) of their principal axes (origin their centroid, n the
// smallest axis). With normals, neighbours whose normal differs from the point's by more than 60
// degrees are left out (the other wall of a thin shell).

#include <cstddef>
#include <memory>
#include <vector>

#include <Eigen/Dense>

#include "edgefront/point_cloud.h"
#include "edgefront/point_index.h"

namespace gcs::detail {

struct LocalQuadric {
  Eigen::Vector3d origin, u, v, n;
  Eigen::Matrix<double, 6, 1> coef;
  double residual = 0;  // standard deviation of the heights around the fit (6 parameters corrected)
  double spread = 0;    // RMS distance of the neighbours from the origin in the (u, v) plane

  double height(double x, double y) const {
    return coef[0] * x * x + coef[1] * x * y + coef[2] * y * y + coef[3] * x + coef[4] * y + coef[5];
  }
  // The unit normal of the height field above the point p (on the side of n).
  Eigen::Vector3d normal_at(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d d = p - origin;
    const double x = d.dot(u), y = d.dot(v);
    const double fx = 2 * coef[0] * x + coef[1] * y + coef[3], fy = coef[1] * x + 2 * coef[2] * y + coef[4];
    return (n - fx * u - fy * v).normalized();
  }
};

class QuadricFitter {
 public:
  // Over `cloud` (its normals, when it has them, select the neighbours), with its own k-d tree.
  explicit QuadricFitter(const edgefront::PointCloud& cloud);
  // Over `cloud` with an existing k-d tree over its points (one tree shared by the fitters of
  // several threads: edgefront/parallel.h).
  QuadricFitter(const edgefront::PointCloud& cloud, const edgefront::PointIndex& index);
  // Over `points` with an existing k-d tree over them; no normals.
  QuadricFitter(const std::vector<edgefront::Vec3>& points, const edgefront::PointIndex& index);

  const edgefront::PointIndex& index() const { return *index_; }

  // Fits to point i's k nearest neighbours (on its side). False when the neighbourhood is too small
  // or degenerate.
  bool fit(std::size_t i, std::size_t k, LocalQuadric& q);

  // The same, with the neighbours taken among `candidates` (the nearest points of a point close
  // to i: one k-d tree query serves the points around it); fewer than k of them on i's side: fit().
  bool fit_from(std::size_t i, std::size_t k, const std::vector<edgefront::PointIndex::Neighbor>& candidates,
                LocalQuadric& q);

  // The indices of the neighbours of the last fit() (without normals: point i's k nearest).
  const std::vector<edgefront::PointIndex::Neighbor>& last_hits() const { return hits_; }

 private:
  bool fit_gathered(LocalQuadric& q);
  void gather(std::size_t i, std::size_t query, std::size_t k);

  const std::vector<edgefront::Vec3>& points_;
  const std::vector<edgefront::Vec3>* normals_;  // null: not used
  std::unique_ptr<edgefront::PointIndex> own_index_;
  const edgefront::PointIndex* index_;
  std::vector<edgefront::PointIndex::Neighbor> hits_;
  std::vector<edgefront::PointIndex::Neighbor> near_;
  std::vector<Eigen::Vector3d> pts_;
};

}  // namespace gcs::detail
