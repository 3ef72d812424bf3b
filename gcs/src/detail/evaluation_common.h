#pragma once
// What the evaluation's parts share. Internal. The parts:
//   evaluation.cpp          input checks, sampling, the metrics (distances, orientation), evaluate;
//   self_intersections.cpp  self-intersecting face pairs and the mesh's validity;
//   evaluation_output.cpp   the evaluation as text and as JSON.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "detail/triangle_closest.h"
#include "edgefront/error.h"
#include "edgefront/mesh.h"
#include "gcs/evaluation.h"

namespace gcs::detail::eval {

using edgefront::Mesh;
using edgefront::Vec3;

inline constexpr double kInf = std::numeric_limits<double>::infinity();

struct Box {
  Vec3 lo = Vec3(kInf, kInf, kInf);
  Vec3 hi = Vec3(-kInf, -kInf, -kInf);
  void add(const Vec3& p) {
    lo.minimize(p);
    hi.maximize(p);
  }
  void add(const Box& b) {
    lo.minimize(b.lo);
    hi.maximize(b.hi);
  }
  bool overlaps(const Box& b) const {
    return lo[0] <= b.hi[0] && b.lo[0] <= hi[0] && lo[1] <= b.hi[1] && b.lo[1] <= hi[1] && lo[2] <= b.hi[2] &&
           b.lo[2] <= hi[2];
  }
  double dist2(const Vec3& p) const {
    double d = 0;
    for (int k = 0; k < 3; ++k) {
      const double e = std::max({lo[k] - p[k], 0.0, p[k] - hi[k]});
      d += e * e;
    }
    return d;
  }
};

struct Triangle {
  std::array<Vec3, 3> p;
  std::array<int, 3> v = {-1, -1, -1};  // vertex indices (for shared-vertex tests)
  Box box() const {
    Box b;
    for (const Vec3& q : p) b.add(q);
    return b;
  }
  Vec3 n = Vec3(0, 0, 0);  // unit normal; zero for a degenerate triangle (set by finish())
  void finish() {
    const Vec3 c = (p[1] - p[0]) % (p[2] - p[0]);
    const double len = c.norm();
    n = len > 0.0 ? c / len : Vec3(0, 0, 0);
  }
  const Vec3& unit_normal() const { return n; }
};

// ---------------------------------------------------------------------------------------------
// Bounding-volume hierarchy over triangles: nearest-triangle queries and box-overlap queries.

class TriangleBvh {
 public:
  explicit TriangleBvh(std::vector<Triangle> triangles) : tris_(std::move(triangles)) {
    EF_CHECK(!tris_.empty(), "BVH over no triangles");
    order_.resize(tris_.size());
    centroids_.resize(tris_.size());
    boxes_.resize(tris_.size());
    for (std::size_t i = 0; i < tris_.size(); ++i) {
      order_[i] = static_cast<int>(i);
      centroids_[i] = (tris_[i].p[0] + tris_[i].p[1] + tris_[i].p[2]) / 3.0;
      boxes_[i] = tris_[i].box();
    }
    nodes_.reserve(2 * tris_.size() / kLeafSize + 2);
    build(0, static_cast<int>(tris_.size()));
  }

  const std::vector<Triangle>& triangles() const { return tris_; }
  const Box& box(int tri) const { return boxes_[static_cast<std::size_t>(tri)]; }

  struct Hit {
    double dist2 = kInf;
    int tri = -1;
  };

  /// Nearest triangle to `x` (exact point-to-triangle distance).
  Hit nearest(const Vec3& x) const {
    Hit best;
    std::array<std::pair<int, double>, 128> stack;
    int top = 0;
    stack[static_cast<std::size_t>(top++)] = {0, nodes_[0].box.dist2(x)};
    while (top > 0) {
      const auto [id, d2] = stack[static_cast<std::size_t>(--top)];
      if (d2 >= best.dist2) continue;
      const Node& node = nodes_[static_cast<std::size_t>(id)];
      if (node.left < 0) {
        for (int i = node.begin; i < node.end; ++i) {
          const int t = order_[static_cast<std::size_t>(i)];
          const Triangle& tri = tris_[static_cast<std::size_t>(t)];
          const double e2 = (closest_on_triangle(x, tri.p[0], tri.p[1], tri.p[2]) - x).sqrnorm();
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

  /// Number of triangles; `in_order(k)` is the k-th triangle in the hierarchy's leaf order
  /// (spatially coherent).
  int size() const { return static_cast<int>(order_.size()); }
  int in_order(int k) const { return order_[static_cast<std::size_t>(k)]; }

  /// Calls f(tri) for each triangle at leaf-order position >= `first` whose box overlaps `query`.
  template <class F>
  void for_each_overlapping(const Box& query, int first, F&& f) const {
    std::array<int, 128> stack;
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

 private:
  static constexpr int kLeafSize = 4;
  struct Node {
    Box box;
    int left = -1, right = -1;  // children; -1 for a leaf
    int begin = 0, end = 0;     // range of order_ below the node
  };

  // Median split on the longest axis of the centroids' box; depth <= log2(n) + 1.
  int build(int begin, int end) {
    const int id = static_cast<int>(nodes_.size());
    nodes_.emplace_back();
    Box box, cbox;
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
      const double ca = centroids_[static_cast<std::size_t>(a)][axis],
                   cb = centroids_[static_cast<std::size_t>(b)][axis];
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

  std::vector<Triangle> tris_;
  std::vector<int> order_;
  std::vector<Vec3> centroids_;
  std::vector<Box> boxes_;
  std::vector<Node> nodes_;
};

// Live faces of the mesh as triangles; `face_of[i]` is the face index of triangle i.
inline std::vector<Triangle> mesh_triangles(const Mesh& mesh, std::vector<int>* face_of = nullptr) {
  std::vector<Triangle> tris;
  tris.reserve(mesh.n_faces());
  for (const auto f : mesh.faces()) {
    if (mesh.status(f).deleted()) continue;
    Triangle t;
    int k = 0;
    for (const auto v : mesh.fv_range(f)) {
      if (k < 3) {
        t.p[static_cast<std::size_t>(k)] = mesh.point(v);
        t.v[static_cast<std::size_t>(k)] = v.idx();
      }
      ++k;
    }
    EF_CHECK(k == 3, "face " + std::to_string(f.idx()) + " is not a triangle");
    t.finish();
    tris.push_back(t);
    if (face_of) face_of->push_back(f.idx());
  }
  return tris;
}

// \throw InvalidInput when a live vertex of `mesh` has a NaN or infinite coordinate or one beyond
// kMaxCoordinate (`what` names the mesh in the message). In evaluation.cpp.
void check_mesh_coordinates(const Mesh& mesh, const char* what);

// Validity of `mesh`; `bvh` (over the mesh's live faces) is reused when given.
// In self_intersections.cpp.
MeshValidity validity_of(const Mesh& mesh, bool count_self, const TriangleBvh* bvh, unsigned threads = 1);

}  // namespace gcs::detail::eval
