#pragma once
// Keeping the GCS loop from ending as a collapsed double layer on open (planar, near-planar,
// landscape) clouds.
//
// The problem: the closed start box collapses onto an open sheet from both sides; its top and its
// bottom both land on the samples with opposite orientations, both win samples, each gets holes
// where the other wins, and the unsigned support test of the border creation keeps both (many
// border loops, self-intersections, half of the area wrongly oriented). With oriented samples
// (input normals, or fitted normals oriented by orient_normals) two things prevent it:
//  - oriented_nearest: the winner of a sample is the nearest mesh vertex whose normal agrees with
//    the sample's normal (dot > 0), so the layer that faces away never wins, goes inactive and is
//    collapsed;
//  - remove_opposed_faces: faces that lie on the cloud but face against the nearest sample's
//    normal are removed (a signed support test), which removes what is left of that layer.

#include <cstddef>
#include <functional>
#include <vector>

#include "border_topology.h"
#include "vertex_grid.h"
#include "edgefront/mesh.h"
#include "edgefront/point_cloud.h"
#include "edgefront/point_index.h"

namespace gcs::detail {

/// The area-weighted normal of v (sum of the cross products of its faces; not normalized).
edgefront::Vec3 vertex_normal_sum(const edgefront::Mesh& mesh, edgefront::VertexHandle v);

/// The nearest vertex of `grid` to `sample` whose vertex normal agrees with `normal` (positive
/// dot product), among the `max_candidates` nearest vertices and no farther than the nearest one's
/// distance plus `max_extra_distance`. When none agrees, returns the plain nearest vertex. -1 only
/// for an empty grid. The grid is left exactly as it was (candidates are taken out one by one and
/// put back); ties as in VertexGrid::nearest (smaller id), so the result is deterministic.
int oriented_nearest(const edgefront::Mesh& mesh, VertexGrid& grid, const edgefront::Vec3& sample,
                     const edgefront::Vec3& normal, int max_candidates, double max_extra_distance);

/// The rest of oriented_nearest for a caller that found the nearest vertex `first` itself
/// (grid.nearest(sample)) and saw that its normal does not agree: the same answer as
/// oriented_nearest (the basic step computes the winner's normal from its cached ring).
int oriented_nearest_after(const edgefront::Mesh& mesh, VertexGrid& grid, const edgefront::Vec3& sample,
                           const edgefront::Vec3& normal, int first, int max_candidates, double max_extra_distance);

struct OpposedParams {
  double max_distance = 0;  ///< only faces whose centroid is this close to the cloud are judged
  double min_cos = 0.3;     ///< removed when cos(face normal, sample normal) < -min_cos
  /// components that lost faces and have fewer than this share of the largest one's faces go too
  double split_fraction = 0.25;
  std::size_t min_component_faces = 8;   ///< then components smaller than this are removed
  double min_component_fraction = 0.05;  ///< ... or smaller than this share of the largest
  /// The part of the cloud (cloud_parts) that sample i belongs to, or empty. Given, a piece that
  /// split_fraction or the small-component rule would remove is kept when it is a separate surface
  /// (border_topology.h: separate_surfaces; nested spheres' inner one, reached through a tunnel
  /// whose faces were removed), not a fragment of the largest one's layer.
  std::function<int(std::size_t)> sample_part;
};

/// Removes the faces whose normal points against the (oriented) normal of the input sample
/// nearest to their centroid, then cleans non-manifold fans and tiny components (clean_topology),
/// then removes the pieces that the removal cut off and that have fewer than split_fraction of the
/// largest component's faces (unless they lie on a part of the cloud of their own, sample_part).
/// `nearest` holds every face's nearest sample by face index (as remove_unsupported_faces found it,
/// or face_nearest), its distance and its oriented normal (NaN normal: that face is not judged);
/// the mesh must not have moved since. Never removes 90% or more of the faces. Returns the number
/// of faces removed. \throws edgefront::InternalError when `nearest` has fewer entries than faces.
std::size_t remove_opposed_faces(edgefront::Mesh& mesh, const FaceNearest& nearest, const OpposedParams& params);

/// The parts of a point cloud that lie apart: the connected components of its symmetric
/// k-nearest-neighbour graph, labelled 0, 1, ... in the order of their first point. Nested spheres'
/// two spheres are two parts, a connected scan is one. `index` is a PointIndex over `points`.
std::vector<int> cloud_parts(const std::vector<edgefront::Vec3>& points, const edgefront::PointIndex& index,
                             std::size_t k = 8);

/// How much the normals point away from the points' centroid c: the sum of n.(p - c) / |n| over
/// the points with a usable normal, divided by their count times the largest |p - c|. About 0.5-1
/// for a closed surface with outward normals (1 for a sphere), 0 for an open flat sheet, negative
/// for inward normals; 0 without usable normals.
double normal_flux(const std::vector<edgefront::Vec3>& points, const std::vector<edgefront::Vec3>& normals);

/// Orients unsigned normals (e.g. fitted to each point's neighbours) consistently, for clouds
/// without normals: a spanning tree of the k-nearest-neighbour graph that prefers parallel
/// normals (Hoppe et al. 1992) carries one point's sign to all; then the global sign is outward
/// (sum of n.(p - c) over the points positive) or, when that sum is below 5% of what a sphere would
/// give (an open, nearly flat sheet), along the positive side of the thinnest principal axis.
/// Normals with a NaN or zero are left alone and skipped. Returns false (normals then partly
/// flipped, not to be used) when the graph does not connect all usable points.
/// The sign carried along an edge is the one that makes the two normals mirror images in the plane
/// bisecting the edge (see agree() in the source): across a crease or between the two walls of a
/// thin shell this is right where Hoppe's n_i . n_j is not. `noise` (optional, per point: the
/// standard deviation of the points' heights around their fitted surface, as fit_normals gives)
/// keeps noise along the normal from reading as two walls. Points that the k-nearest graph leaves
/// apart (islands cut off by undefined normals, a small densely sampled detail) are linked by
/// wider searches to points up to 4 times those points' k-th-neighbour distance away.
/// `refined` false: neither (Hoppe's n_i . n_j, the k-nearest graph as it is; the reconstructor
/// with InputOptions::quadric_normals off).
bool orient_normals(const std::vector<edgefront::Vec3>& points, const edgefront::PointIndex& index,
                    std::vector<edgefront::Vec3>& normals, std::size_t k = 8,
                    const std::vector<double>* noise = nullptr, bool refined = true);

}  // namespace gcs::detail
