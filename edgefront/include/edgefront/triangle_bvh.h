#pragma once
/// \file triangle_bvh.h
/// A bounding-volume hierarchy over triangles (the one the libraries share): the nearest triangle
/// to a point, and the triangles whose boxes overlap a box (the candidate pairs of a
/// self-intersection count).

#include <algorithm>
#include <array>
#include <cstddef>
#include <limits>
#include <utility>
#include <vector>

#include "edgefront/error.h"
#include "edgefront/geometry.h"

namespace edgefront {

/// A static hierarchy of axis-aligned boxes over a list of triangles (each triangle's
/// `contact_box`): median splits on the longest axis of the centroids' box, up to kLeafSize
/// triangles per leaf, depth <= log2(n) + 1.
/// Built once, then queried from any number of threads (the queries do not modify it).
class TriangleBvh {
 public:
  /// Builds the hierarchy over `triangles` (indices into this list are the answers).
  /// \throws edgefront::InvalidInput when `triangles` is empty or a corner is not finite (naming
  ///         the triangle).
  explicit TriangleBvh(std::vector<Triangle> triangles);

  /// The triangles, as given.
  const std::vector<Triangle>& triangles() const { return tris_; }
  /// The box the hierarchy holds for triangle `tri` (an index into triangles()): its
  /// `Triangle::contact_box`, so that box overlaps find every pair `triangles_intersect` accepts.
  const AlignedBox& box(int tri) const { return boxes_[static_cast<std::size_t>(tri)]; }

  /// The answer of `nearest`.
  struct Hit {
    double dist2 = std::numeric_limits<double>::infinity();  ///< squared distance to the triangle
    int tri = -1;                                             ///< index into triangles()
  };

  /// The triangle nearest to `x` (exact point-to-triangle distance; ties: lowest index).
  Hit nearest(const Vec3& x) const;

  /// Number of triangles.
  int size() const { return static_cast<int>(order_.size()); }
  /// The k-th triangle in the hierarchy's leaf order (spatially coherent), k in [0, size()).
  int in_order(int k) const { return order_[static_cast<std::size_t>(k)]; }

  /// Calls f(tri) for each triangle at leaf-order position >= `first` whose box overlaps `query`
  /// (in leaf order). With `first` = k + 1 for the triangle at position k, every overlapping
  /// pair is visited once.
  template <class F>
  void for_each_overlapping(const AlignedBox& query, int first, F&& f) const {
    std::array<int, kMaxDepth> stack;
    int top = 0;
    stack[static_cast<std::size_t>(top++)] = 0;
    while (top > 0) {
      const Node& node = nodes_[static_cast<std::size_t>(stack[static_cast<std::size_t>(--top)])];
      if (node.end <= first || !node.box.overlaps(query)) continue;
      if (node.left < 0) {
        for (int i = std::max(node.begin, first); i < node.end; ++i) {
          const int t = order_[static_cast<std::size_t>(i)];
          if (boxes_[static_cast<std::size_t>(t)].overlaps(query)) f(t);
        }
        continue;
      }
      EF_CHECK(top + 2 <= static_cast<int>(stack.size()), "BVH deeper than its traversal stack");
      stack[static_cast<std::size_t>(top++)] = node.left;
      stack[static_cast<std::size_t>(top++)] = node.right;
    }
  }

  /// The pairs of triangles that `triangles_intersect` accepts (degenerate triangles skipped),
  /// each pair once: the number, and with `pairs` the list as (i, j) indices into triangles(), i
  /// before j in leaf order. On `threads` threads (0: all cores; contiguous chunks of the leaf
  /// order, joined in chunk order), the same list for any count.
  /// \throws edgefront::InvalidInput for more than kMaxThreads threads (edgefront/parallel.h).
  std::size_t intersecting_pairs(std::vector<std::pair<int, int>>* pairs = nullptr, unsigned threads = 1) const;

  /// Most triangles per leaf.
  static constexpr int kLeafSize = 4;

 private:
  static constexpr std::size_t kMaxDepth = 128;  // traversal stack entries (depth <= log2(n) + 1)
  struct Node {
    AlignedBox box;
    int left = -1, right = -1;  // children; -1 for a leaf
    int begin = 0, end = 0;     // range of order_ below the node
  };
  int build(int begin, int end);

  std::vector<Triangle> tris_;
  std::vector<int> order_;
  std::vector<Vec3> centroids_;
  std::vector<AlignedBox> boxes_;
  std::vector<Node> nodes_;
};

}  // namespace edgefront
