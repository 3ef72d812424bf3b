#pragma once
// The region steps of a detection (regions.cpp), used by detect.cpp's detect_pass. Internal.

#include <unordered_map>
#include <utility>
#include <vector>

#include "edgefront/mesh.h"
#include "edgefront/minimal_edge_front.h"
#include "twist/detect.h"

namespace twist::detail {

/// The border of a face set as closed loops of halfedges with the set on their right, and per
/// loop whether it lies on the mesh border.
std::pair<std::vector<std::vector<edgefront::HalfedgeHandle>>, std::vector<bool>> border_loops(
    const edgefront::Mesh& mesh, const std::vector<edgefront::FaceHandle>& faces);
/// Step 2: the flagged faces grown by a Minimal Edge Front; its loops.
std::vector<edgefront::FrontLoop> grow_front(const edgefront::Mesh& mesh, const std::vector<edgefront::FaceHandle>& order,
                                             int grow_levels);
/// Step 3: the regions behind the front.
std::vector<TwistRegion> regions_behind_front(const edgefront::Mesh& mesh, const std::vector<edgefront::FaceHandle>& order,
                                             const std::unordered_map<int, Evidence>& flagged,
                                             const std::vector<edgefront::FrontLoop>& loops,
                                             std::unordered_map<int, int>& region_of);
/// Step 4: enclosed pieces joined to the regions.
void fill_enclosed_pieces(const edgefront::Mesh& mesh, const std::vector<edgefront::FrontLoop>& loops,
                          std::unordered_map<int, int>& region_of, std::vector<TwistRegion>& regions);

}  // namespace twist::detail
