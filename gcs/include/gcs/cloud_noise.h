#pragma once
/// \file cloud_noise.h
/// Noise in a point cloud: how much, and smoothing it away before a reconstruction.
///
/// A scan's points scatter around the surface. A reconstruction that puts its vertices on the
/// points (its post-processing projects and fits the mesh to the samples) carries that scatter into
/// the mesh; against the true surface it is then no better than an interpolating method. On a
/// bumpy sphere of 5,210 points with Gaussian noise of 0.24 point spacings, smoothing the cloud
/// first brings the 5K-vertex mesh 3 times closer to the true surface (bench/results/gcs-noise.md).
///
/// \code
///   edgefront::PointCloud cloud = edgefront::read_points("scan.xyz");
///   gcs::NoiseEstimate e = gcs::estimate_noise(cloud);
///   if (e.ratio() > 0.05) gcs::smooth_noise(cloud);   // what the reconstructor does by default
/// \endcode
///
/// Method: around a point, a quadric height field z = f(x, y) is fitted by least squares to its
/// nearest points, in the frame of their principal axes (z along the smallest one). What the quadric
/// does not explain is the noise plus the surface's own misfit, which is not small where the
/// sampling is coarse for the surface's detail (a scanned model's vertex set: CGAL's elephant,
/// armadillo, dragon and man leave 0.09-0.16 point spacings at 10 neighbours without any noise).
/// The two are told apart by fitting twice, to k and to 2k neighbours: noise leaves the same
/// residual at both, the misfit grows (its square at least 4 times). With normals, neighbours whose
/// normal differs from the point's by more than 60 degrees are left out: the other wall of a thin
/// shell is not noise.
///
/// Cost (one thread): the estimate looks at 5,000 points at most (a fraction of a second even for
/// 1M points, most of it passes over the points to find its patches); smoothing costs tens of
/// microseconds per point, most of it in k-d tree queries, which the points of a small cell share
/// (figures: bench/results/gcs-noise.md). Memory: the cloud once more, and a k-d tree over it.

#include <cstddef>

#include "edgefront/point_cloud.h"

namespace gcs {

/// The noise of a cloud, from `estimate_noise`.
struct NoiseEstimate {
  /// The noise's standard deviation along the normal: sqrt(max(0, (4 r^2 - R^2) / 3)) with r the
  /// `residual` and R the `wide_residual` (what is left when the misfit, assumed to grow at least
  /// 4-fold in square from r to R, is taken out; pure noise gives about r).
  double noise = 0;
  /// Median over the points of the quadric fit's residual at `NoiseOptions::neighbours` (standard
  /// deviation, corrected for the fit's 6 parameters): noise and misfit together.
  double residual = 0;
  /// The same at twice as many neighbours.
  double wide_residual = 0;
  /// Median distance from a point to its nearest other point.
  double spacing = 0;
  /// Points whose neighbourhood was used (a degenerate or too small one is skipped).
  std::size_t points_used = 0;
  /// noise / spacing (0 when the spacing is 0).
  double ratio() const { return spacing > 0 ? noise / spacing : 0; }
};

/// Options of `estimate_noise`.
struct NoiseOptions {
  /// Neighbours of a point the quadric is fitted to (the point included), in [8, 256]; the second
  /// fit takes twice as many. Small, so that the neighbourhood stays on one wall of a thin shell
  /// whose walls are a few spacings apart.
  std::size_t neighbours = 10;
  /// At most this many points are looked at (an even stride over the cloud); >= 1. A cloud of more
  /// than 4 times as many is looked at in 16 patches (cubes around evenly strided points, holding
  /// about this many points in all), so that no k-d tree over the whole cloud is built.
  std::size_t max_points = 5000;
  /// Threads for the fits, >= 0; 0 (the default) = all cores. The estimate is the same for any
  /// count.
  unsigned threads = 0;
};

/// Estimates the noise of `cloud`. \throws edgefront::InvalidInput for fewer than 8 points, a
/// non-finite coordinate, normals that do not match the points, or bad options.
NoiseEstimate estimate_noise(const edgefront::PointCloud& cloud, const NoiseOptions& options = {});

/// Options of `smooth_noise`.
struct SmoothNoiseOptions {
  /// Neighbours of a point the quadric is fitted to, in [8, 256]. More average the noise better and
  /// round off detail more. On noisy synthetic shapes (smooth bumps, a torus, a creased pointed
  /// vault; noise 0.06-0.7 point spacings) 64 comes closer to the true surface than 40 or 20
  /// (bench/results/gcs-noise.md).
  std::size_t neighbours = 64;
  /// Threads, >= 0; 0 (the default) = all cores. The points are the same bytes for any count.
  unsigned threads = 0;
};

/// Moves every point of `cloud` along the quadric's normal onto the quadric fitted to its neighbours
/// (of the ORIGINAL cloud: up to round-off, the result does not depend on the point order).
/// Normals are kept.
/// Returns the number of points moved; points whose neighbourhood is degenerate stay. There is no
/// limit on the move: an outlier lands on the surface of its neighbours, and detail smaller than
/// the neighbourhood is rounded off (which is why the reconstructor smooths only noisy clouds).
/// \throws edgefront::InvalidInput as `estimate_noise`.
std::size_t smooth_noise(edgefront::PointCloud& cloud, const SmoothNoiseOptions& options = {});

}  // namespace gcs
