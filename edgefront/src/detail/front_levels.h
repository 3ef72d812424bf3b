#pragma once
// Per-vertex join levels of any level-wise front (Vertex Front, Minimal Edge Front). Internal.

#include <vector>

#include "edgefront/front_source.h"
#include "edgefront/mesh.h"

namespace edgefront::detail {

// Enclosed vertices report their level through the callback; vertices still on the front after
// `max_levels` levels are read from the front itself. -1: never reached.
template <class Front>
std::vector<int> join_levels(const Mesh& mesh, const FrontSource& source, int max_levels) {
  std::vector<int> level(mesh.n_vertices(), -1);
  Front front(mesh);
  front.set_enclosed_callback([&](VertexHandle v, int l) {
    if (level[v.idx()] < 0) level[v.idx()] = l;
  });
  front.reset(source);
  front.run(max_levels);
  for (auto [v, l] : front.front_vertices()) {
    if (level[v.idx()] < 0) level[v.idx()] = l;
  }
  return level;
}

}  // namespace edgefront::detail
