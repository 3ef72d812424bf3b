#pragma once
// The directed search of connection paths: bidirectional A* over the mesh edges. Internal.

#include <cstddef>
#include <vector>

#include "detail/flat_map.h"
#include "edgefront/mesh.h"

namespace edgefront::detail {

struct DirectedPathResult {
  std::vector<VertexHandle> vertices;  // empty: not connected
  size_t processed = 0;                // vertices settled by both searches
  size_t memory_bytes = 0;             // tables and queues at their largest
};

/// Bidirectional A* with the average potential p(v) = (h_t(v) - h_s(v)) / 2 (consistent in both
/// directions when h is), h the straight-line distance (edge lengths) or the straight-line
/// distance over the mesh's longest edge (hops). Stops when the two smallest keys add up to the
/// best meeting: the path is shortest in the metric. Tables are per query (O(visited)).
class DirectedPathSearch {
 public:
  explicit DirectedPathSearch(const Mesh& mesh) : mesh_(mesh) {}
  DirectedPathResult find(VertexHandle s, VertexHandle t, bool hops);

 private:
  struct Label {
    double g = 0.0;
    int pred = -1;
    bool closed = false;
  };
  const Mesh& mesh_;
  double longest_edge_ = -1.0;  // computed on the first hop query
  FlatMap<Label> labels_[2];
};

}  // namespace edgefront::detail
