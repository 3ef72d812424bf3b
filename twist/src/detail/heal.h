#pragma once
// The session's border heal (SessionOptions::heal): after a repair, border chains that now run
// opposite and lie close are zipped, and small holes are closed by a fan, where the new faces lie
// on the reference cloud and agree with the faces they border.

#include <cstddef>
#include <vector>

#include "edgefront/mesh.h"
#include "twist/reference_normals.h"
#include "twist/repair_session.h"

namespace twist::detail {

/// What one heal added.
struct HealCounts {
  std::size_t strips = 0;  ///< strips zipped between two border chains
  std::size_t holes = 0;   ///< holes closed by a fan (or their own triangle)
  std::size_t grown = 0;   ///< faces grown beyond borders (grow_borders)
};

/// Removes the components with fewer than `share` x the largest component's faces (the largest
/// stays); returns the faces removed. Deleted elements are not collected.
std::size_t remove_small_pieces(edgefront::Mesh& mesh, double share);

/// One row of border growth (HealOptions::grow_rows, see its comment) with `mean_edge_length` > 0
/// as the unit and `min_support` reference points per new vertex. Returns the faces added (new
/// vertices and faces appended to the mesh; deleted elements are not collected).
std::size_t grow_borders(edgefront::Mesh& mesh, const ReferenceNormals& reference, double mean_edge_length,
                         std::size_t min_support);

/// Heals the borders of `mesh` (see the file comment) with `mean_edge_length` > 0 as the unit;
/// the faces it adds are appended to `added`. Deleted elements are not collected.
HealCounts heal_borders(edgefront::Mesh& mesh, const ReferenceNormals& reference, double mean_edge_length,
                        const HealOptions& options, std::vector<edgefront::FaceHandle>& added);

}  // namespace twist::detail
