#pragma once
// Post-processing of the GCS result: moving the vertices onto the sampled surface.
//
// The loop leaves each vertex where the winner moves and the tangential smoothing put it: near the
// samples on average, but off the surface by the jitter of the last moves (a vertex is a running
// average of the samples it won, which lie on a curved surface). Moving it onto the tangent plane
// of its nearest sample puts it on the surface up to that plane's curvature error.

#include <cstddef>

#include "border_topology.h"
#include "edgefront/mesh.h"

namespace gcs::detail {

/// Moves every vertex x of `mesh` onto the tangent plane of its nearest sample p (normal n, taken
/// from `nearest`; its sign does not matter): x - ((x - p).n) n / |n|^2. Positions are computed
/// from the unmoved mesh, then applied vertex by vertex in index order. A vertex stays where it is
/// when its sample has no usable normal (NaN or zero), when the move is longer than `max_move`,
/// or when one of its faces would turn by more than acos(min_face_cos). `nearest` must fill
/// CloudHit::point. Returns the number of vertices moved.
std::size_t project_to_samples(edgefront::Mesh& mesh, const CloudQuery& nearest, double max_move,
                               double min_face_cos = 0.5);

/// Flips interior edges toward a Delaunay triangulation on the surface with even valences: an
/// edge whose two opposite angles sum to more than pi + 30 degrees is flipped; within 30 degrees
/// of pi the valences of its four vertices decide (sum of squared deviations from 6, 4 on a
/// border): an edge above pi is flipped unless that raises the sum, one below when that lowers it
/// by at least 2; either only when both its faces and both new faces are
/// nearly coplanar (every pair of their unit normals has a cosine >= min_dihedral_cos, so creases
/// stay) and both its ends keep valence >= 3 (>= 2 on a border); passes over all edges until
/// none flips (at most max_passes). If a face whose triangle a flip replaced is in a
/// self-intersecting pair afterwards, all flips are undone and the run is repeated without
/// flipping the edges of those faces (at most 4 runs; after that nothing is flipped). Vertex
/// positions do not change. Returns the number of flips kept. \throw edgefront::InvalidInput for min_dihedral_cos outside [-1, 1] or
/// max_passes < 0.
std::size_t delaunay_flips(edgefront::Mesh& mesh, double min_dihedral_cos, int max_passes);

}  // namespace gcs::detail
