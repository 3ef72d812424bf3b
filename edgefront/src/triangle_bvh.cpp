#include "edgefront/triangle_bvh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>

#include "detail/triangle_predicates.h"
#include "edgefront/parallel.h"

namespace edgefront {

TriangleBvh::TriangleBvh(std::vector<Triangle> triangles) : tris_(std::move(triangles)) {
  if (tris_.empty()) throw InvalidInput("TriangleBvh: no triangles to build a hierarchy over");
  // A NaN corner would break the median splits' ordering (and every box test after them).
  for (std::size_t i = 0; i < tris_.size(); ++i) {
    for (const Vec3& c : tris_[i].p) {
      if (!std::isfinite(c[0]) || !std::isfinite(c[1]) || !std::isfinite(c[2])) {
        throw InvalidInput("TriangleBvh: triangle " + std::to_string(i) + " has a non-finite corner");
      }
    }
  }
  order_.resize(tris_.size());
  centroids_.resize(tris_.size());
  boxes_.resize(tris_.size());
  for (std::size_t i = 0; i < tris_.size(); ++i) {
    order_[i] = static_cast<int>(i);
    centroids_[i] = (tris_[i].p[0] + tris_[i].p[1] + tris_[i].p[2]) / 3.0;
    boxes_[i] = tris_[i].contact_box();
  }
  nodes_.reserve(2 * tris_.size() / kLeafSize + 2);
  build(0, static_cast<int>(tris_.size()));
}

TriangleBvh::Hit TriangleBvh::nearest(const Vec3& x) const {
  Hit best;
  std::array<std::pair<int, double>, kMaxDepth> stack;
  int top = 0;
  stack[static_cast<std::size_t>(top++)] = {0, nodes_[0].box.dist2(x)};
  while (top > 0) {
    const std::pair<int, double> entry = stack[static_cast<std::size_t>(--top)];
    if (entry.second >= best.dist2) continue;
    const Node& node = nodes_[static_cast<std::size_t>(entry.first)];
    if (node.left < 0) {
      for (int i = node.begin; i < node.end; ++i) {
        const int t = order_[static_cast<std::size_t>(i)];
        const Triangle& tri = tris_[static_cast<std::size_t>(t)];
        const double e2 = (closest_point_on_triangle(x, tri.p[0], tri.p[1], tri.p[2]) - x).sqrnorm();
        if (e2 < best.dist2 || (e2 == best.dist2 && t < best.tri)) best = {e2, t};
      }
      continue;
    }
    const double dl = nodes_[static_cast<std::size_t>(node.left)].box.dist2(x);
    const double dr = nodes_[static_cast<std::size_t>(node.right)].box.dist2(x);
    EF_CHECK(top + 2 <= static_cast<int>(stack.size()), "BVH deeper than its traversal stack");
    if (dl <= dr) {
      stack[static_cast<std::size_t>(top++)] = {node.right, dr};
      stack[static_cast<std::size_t>(top++)] = {node.left, dl};
    } else {
      stack[static_cast<std::size_t>(top++)] = {node.left, dl};
      stack[static_cast<std::size_t>(top++)] = {node.right, dr};
    }
  }
  return best;
}

std::size_t TriangleBvh::intersecting_pairs(std::vector<std::pair<int, int>>* pairs, unsigned threads) const {
  const std::size_t n = order_.size();
  const unsigned chunks = threads_for(n, threads);
  std::vector<std::size_t> chunk_count(chunks, 0);
  std::vector<std::vector<std::pair<int, int>>> chunk_pairs(chunks);
  // Each pair once: triangle k (leaf order) against the overlapping ones after it.
  parallel_for(n, threads, [&](std::size_t begin, std::size_t end, unsigned chunk) {
    for (int k = static_cast<int>(begin); k < static_cast<int>(end); ++k) {
      const int ia = in_order(k);
      const Triangle& a = tris_[static_cast<std::size_t>(ia)];
      if (a.degenerate()) continue;
      for_each_overlapping(box(ia), k + 1, [&](int j) {
        const Triangle& b = tris_[static_cast<std::size_t>(j)];
        if (!b.degenerate() && detail::triangles_meet(a, b)) {
          ++chunk_count[chunk];
          if (pairs) chunk_pairs[chunk].emplace_back(ia, j);
        }
      });
    }
  });
  std::size_t count = 0;
  for (unsigned c = 0; c < chunks; ++c) {
    count += chunk_count[c];
    if (pairs) pairs->insert(pairs->end(), chunk_pairs[c].begin(), chunk_pairs[c].end());
  }
  return count;
}

int TriangleBvh::build(int begin, int end) {
  const int id = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  AlignedBox box, cbox;
  for (int i = begin; i < end; ++i) {
    const int t = order_[static_cast<std::size_t>(i)];
    box.add(boxes_[static_cast<std::size_t>(t)]);
    cbox.add(centroids_[static_cast<std::size_t>(t)]);
  }
  nodes_[static_cast<std::size_t>(id)].box = box;
  if (end - begin <= kLeafSize) {
    nodes_[static_cast<std::size_t>(id)].begin = begin;
    nodes_[static_cast<std::size_t>(id)].end = end;
    return id;
  }
  const Vec3 ext = cbox.hi - cbox.lo;
  const int axis = ext[0] >= ext[1] && ext[0] >= ext[2] ? 0 : (ext[1] >= ext[2] ? 1 : 2);
  const int mid = begin + (end - begin) / 2;
  std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end, [&](int a, int b) {
    const double ca = centroids_[static_cast<std::size_t>(a)][axis], cb = centroids_[static_cast<std::size_t>(b)][axis];
    return ca < cb || (ca == cb && a < b);
  });
  const int left = build(begin, mid);
  const int right = build(mid, end);
  Node& node = nodes_[static_cast<std::size_t>(id)];
  node.left = left;
  node.right = right;
  node.begin = begin;
  node.end = end;
  return id;
}

}  // namespace edgefront
