#pragma once
/// \file cloud_normals.h
/// Normals for a point cloud that has none: fitted to each point's neighbours (unsigned; the
/// reconstructor orients them afterwards over the k-nearest-neighbour graph).
///
/// \code
///   edgefront::PointCloud cloud = edgefront::read_points("scan.xyz");   // no normals
///   const edgefront::PointIndex index(cloud.points);
///   std::vector<edgefront::Vec3> n = gcs::fit_normals(cloud.points, index);  // NaN: undefined
/// \endcode
///
/// Method: around every point a quadric height field is fitted to its `neighbours` nearest points
/// (gcs/src/detail/local_quadric.h, the fit of the noise estimate), and its normal is taken *at
/// the point*, not the plane's: a coarse, curved neighbourhood (a scanned model's vertex set)
/// has a well-defined normal that a plane through it misses by up to half the angle the surface
/// turns across it. What the quadric does not explain, its residual, divided by the
/// neighbourhood's extent (the RMS distance of the neighbours from their centroid in the tangent
/// plane), tells a smooth surface (curvature is fitted: a small ratio at any sampling) from a
/// neighbourhood without one normal: noise comparable to the spacing, two sheets, a sharp edge
/// or corner. A point whose own fit exceeds `max_residual` takes, among the fits of its
/// neighbours' neighbourhoods that contain it and pass through it, the one with the smallest
/// ratio (a point near a crease takes the normal of a neighbourhood on its own side of it); the
/// normal is NaN when even that one exceeds `max_residual`.
///
/// Against the truth (bench/bench_normals; figures in bench/results/gcs.md): on CGAL's models'
/// vertex sets almost all normals lie within 30 degrees of the mesh's vertex normals and few are
/// NaN, far better than a plane fit with a flatness test. The defaults (12 neighbours, 0.15) are
/// the best of a sweep over 12/16/20 neighbours and 0.1/0.15/0.2/0.3.
///
/// Cost: one k-d tree query and two small solves per point (microseconds).

#include <cstddef>
#include <vector>

#include "edgefront/mesh.h"
#include "edgefront/point_index.h"

namespace gcs {

/// Options of `fit_normals`.
struct NormalFitOptions {
  /// Neighbours of a point the quadric is fitted to (the point included), in [8, 256].
  std::size_t neighbours = 12;
  /// A fit whose residual exceeds this share of the neighbourhood's extent gives no normal, > 0.
  double max_residual = 0.15;
  /// Let a point whose own fit is refused take the best-fitting neighbourhood of a neighbour that
  /// contains it (see the file comment); false: the point's own fit only.
  bool best_neighbourhood = true;
  /// Take the quadric's normal at the point; false: the fitted plane's (the smallest principal
  /// axis of the neighbours).
  bool quadric_normal = true;
  /// Threads for the fits, >= 0; 0 (the default) = all cores. The normals are the same bytes for
  /// any count.
  unsigned threads = 0;
};

/// Unit normals of `points` (unsigned: either sign), NaN (all three coordinates) where undefined.
/// `index` is a PointIndex over exactly `points`. Deterministic. \throws edgefront::InvalidInput
/// for bad options or an index of another size. With `residuals`, also the residual (standard
/// deviation of the heights around the fit) of the fit each normal came from, NaN with the normal.
std::vector<edgefront::Vec3> fit_normals(const std::vector<edgefront::Vec3>& points, const edgefront::PointIndex& index,
                                         const NormalFitOptions& options = {},
                                         std::vector<double>* residuals = nullptr);

}  // namespace gcs
