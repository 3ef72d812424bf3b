#pragma once
// Re-joining borders after a twist repair (issue 7: "let the loop re-grow and re-join only
// orientation-compatible borders"). A repair cuts a twisted region off and flips it, or flips the
// other side; along the cut both sides then run the same way and cannot be glued back, but the
// flipped piece and its neighbours often meet other borders that now run opposite to theirs
// (a wall torn in two by several cuts). Those are joined here with the loop's own border
// operations, which only join chains whose halfedges run opposite and whose strip agrees with
// the faces on both sides (orientation-compatible) and lies on the cloud.

#include <cstddef>

#include "border_topology.h"
#include "edgefront/mesh.h"

namespace gcs::detail {

struct RejoinParams {
  double mean_edge_length = 0;      ///< of the mesh, > 0
  double max_support_distance = 0;  ///< strip faces must lie this close to the cloud, > 0
  double max_gap_edges = 2.0;       ///< border chains closer than this many mean edges are zipped
  std::size_t max_zips = 32;        ///< strips added per call
};

struct RejoinResult {
  std::size_t strips = 0;       ///< chains of two different border loops zipped together
  std::size_t loops_merged = 0;  ///< whole loop pairs joined by `merge_border_loops`
};

/// Zips border chains of different loops that run close and opposite (`zip_border_slits` across
/// loops), then merges whole loop pairs (`merge_border_loops`). Returns what was joined; the mesh
/// stays a valid manifold oriented triangle mesh (deleted elements not collected). Does nothing
/// when a parameter is not positive.
RejoinResult rejoin_borders(edgefront::Mesh& mesh, const CloudQuery& cloud, const RejoinParams& params);

}  // namespace gcs::detail
