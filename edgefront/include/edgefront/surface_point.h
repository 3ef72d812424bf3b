#pragma once
/// \file surface_point.h
/// A location on the surface of a triangle mesh: a face and barycentric coordinates. The one way
/// the libraries say "a point on the surface": geodesic sources (`geodesic_distance`,
/// `MinimalDistanceFront::reset`), the points of a geodesic polyline (`PathPoint::location`,
/// connection_path.h), and the array API's (face row, barycentric) pairs.

#include <array>

#include "edgefront/mesh.h"

namespace edgefront {

/// A point on the surface: a face and barycentric coordinates (non-negative, summing to 1) with
/// respect to the face's vertices in OpenMesh's `fv_range` order. A point on an edge has a zero
/// coordinate, a point at a vertex a single 1 (either face of the edge, any face of the vertex,
/// names the same point).
struct SurfacePoint {
  FaceHandle face;  ///< a live face of the mesh
  /// Barycentric coordinates with respect to the face's vertices in `fv_range` order: each >= 0,
  /// finite, summing to 1 within 1e-9 (default: the centroid).
  std::array<double, 3> bary = {1.0 / 3, 1.0 / 3, 1.0 / 3};
};

/// The mesh vertex `v` as a surface point: on its first live incident face (in `vf_range`
/// order), with coordinate 1 at `v`.
/// \throws edgefront::InvalidInput when `v` is invalid, deleted, out of range or has no face.
SurfacePoint surface_point_at_vertex(const Mesh& mesh, VertexHandle v);

/// The point at parameter `t` along the edge of halfedge `h` (0: its from-vertex, 1: its
/// to-vertex) as a surface point: on the face of `h`, or of its twin when `h` is a border
/// halfedge, with coordinates 1 - t and t at the two ends of the edge and 0 at the third corner.
/// \throws edgefront::InvalidInput when `h` is invalid, deleted or out of range, when neither
///         side of its edge has a face, or when `t` is not in [0, 1].
SurfacePoint surface_point_on_edge(const Mesh& mesh, HalfedgeHandle h, double t);

/// The position of `p` in space: the barycentric combination of its face's corners.
/// \throws edgefront::InvalidInput when `p.face` is not a live face of the mesh.
Vec3 surface_point_position(const Mesh& mesh, const SurfacePoint& p);

}  // namespace edgefront
