#pragma once
// Checks and helpers shared by the distance modes (minimal_distance_front.cpp, fast_distance.cpp,
// dijkstra_distance.cpp). Internal.

#include <vector>

#include "edgefront/geodesic_ring_table.h"
#include "edgefront/mesh.h"
#include "edgefront/minimal_distance_front.h"

namespace edgefront::detail {

inline constexpr double kTwoPi = 6.283185307179586;
// A vertex whose corner angles sum to a full turn within this (radians) is intrinsically flat.
inline constexpr double kFlatDefect = 1e-10;

// \throws InvalidInput for a NaN or negative max_distance or a target that is not a live vertex.
void check_distance_options(const Mesh& mesh, const DistanceOptions& o);
// \throws InvalidInput when the position of vertex v has a NaN or infinite coordinate, or one
// beyond kMaxCoordinate (coordinate_range.h). Each mode checks a vertex when it first reaches it
// (O(front), not O(mesh)).
void check_finite_vertex(const Vec3& position, int v);
// Checks source points; returns the vertices of their faces (each once).
std::vector<VertexHandle> check_points(const Mesh& mesh, const std::vector<SurfacePoint>& points);

// Lays out vertex x's ring (GeodesicRingTable's layout): appends its edges and corners to the
// arrays and returns its Ring (begin: where it starts in them). \throws
// InternalError when the ring does not close.
GeodesicRingTable::Ring layout_ring(const Mesh& mesh, int x, std::vector<GeodesicRingTable::Edge>& edges,
                                    std::vector<GeodesicRingTable::Corner>& corners);

// The fast mode per call: each settled vertex's ring is laid out when it settles (no table; the
// same fields as with a GeodesicRingTable, bit for bit). Vertex sources (not loops) and points.
DistanceField fast_distance(const Mesh& mesh, const FrontSource& source, const DistanceOptions& options);
DistanceField fast_distance(const Mesh& mesh, const std::vector<SurfacePoint>& points, const DistanceOptions& options);

}  // namespace edgefront::detail
