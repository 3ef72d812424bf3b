#pragma once
// The self-intersecting face pairs of a mesh (the pairs gcs::count_self_intersections counts).

#include <utility>
#include <vector>

#include "edgefront/mesh.h"

namespace gcs::detail {

/// The pairs of live faces of `mesh` that intersect beyond their shared vertices/edges, as face
/// indices (first < second), sorted. \throw edgefront::InvalidInput for non-finite coordinates.
std::vector<std::pair<int, int>> self_intersecting_face_pairs(const edgefront::Mesh& mesh);

}  // namespace gcs::detail
