// Directed connection path search: bidirectional A* (see detail/directed_path.h).

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <utility>

#include "detail/directed_path.h"
#include "edgefront/error.h"
#include "edgefront/vertex_twins.h"

namespace edgefront::detail {

DirectedPathResult DirectedPathSearch::find(VertexHandle s, VertexHandle t, bool hops) {
  if (hops && longest_edge_ < 0) {
    longest_edge_ = 0.0;
    for (EdgeHandle e : mesh_.edges()) longest_edge_ = std::max(longest_edge_, mesh_.calc_edge_length(e));
  }
  // Slightly shrunk so that round-off never makes a reduced edge cost negative.
  const double scale = hops ? (longest_edge_ > 0 ? (1.0 - 1e-9) / longest_edge_ : 0.0) : 1.0 - 1e-9;
  const Vec3 ps = mesh_.point(s), pt = mesh_.point(t);
  auto pot = [&](VertexHandle v) {  // forward potential; the backward one is its negative
    const Vec3& p = mesh_.point(v);
    return 0.5 * scale * ((p - pt).norm() - (p - ps).norm());
  };
  using Entry = std::pair<double, int>;
  using Queue = std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>>;
  Queue q[2];
  DirectedPathResult out;
  for (auto& l : labels_) l.clear();
  labels_[0].insert(static_cast<uint32_t>(s.idx()), Label{0.0, -1, false});
  labels_[1].insert(static_cast<uint32_t>(t.idx()), Label{0.0, -1, false});
  q[0].push({pot(s), s.idx()});
  q[1].push({-pot(t), t.idx()});
  double best = std::numeric_limits<double>::infinity();
  int meet = -1;
  size_t peak_q = 0;
  const TwinRing twins(mesh_);  // a step between twins (one point: a pinched vertex) costs nothing
  auto top_key = [&](int side) {
    // Drops stale entries; +inf when empty.
    while (!q[side].empty()) {
      const Label* l = labels_[side].find(static_cast<uint32_t>(q[side].top().second));
      if (l && !l->closed) return q[side].top().first;
      q[side].pop();
    }
    return std::numeric_limits<double>::infinity();
  };
  while (true) {
    const double k0 = top_key(0), k1 = top_key(1);
    if (!std::isfinite(k0) || !std::isfinite(k1)) break;  // a side is exhausted
    if (k0 + k1 >= best) break;
    const int side = q[0].size() <= q[1].size() ? 0 : 1;
    const int x = q[side].top().second;
    q[side].pop();
    Label* lx = labels_[side].find(static_cast<uint32_t>(x));
    lx->closed = true;
    const double gx = lx->g;
    ++out.processed;
    const VertexHandle vx(x);
    auto relax = [&](VertexHandle y, double w) {
      const double g = gx + w;
      auto [ly, inserted] = labels_[side].insert(static_cast<uint32_t>(y.idx()), Label{g, x, false});
      if (!inserted) {
        if (ly->closed || !(g < ly->g)) return;
        ly->g = g;
        ly->pred = x;
      }
      q[side].push({g + (side == 0 ? pot(y) : -pot(y)), y.idx()});
      if (const Label* other = labels_[1 - side].find(static_cast<uint32_t>(y.idx()))) {
        if (g + other->g < best) {
          best = g + other->g;
          meet = y.idx();
        }
      }
    };
    for (VertexHandle y : mesh_.vv_range(vx)) relax(y, hops ? 1.0 : (mesh_.point(y) - mesh_.point(vx)).norm());
    if (twins.any()) twins.for_each_twin(x, [&](int twin) { relax(VertexHandle(twin), 0.0); });
    peak_q = std::max(peak_q, q[0].size() + q[1].size());
  }
  out.memory_bytes = labels_[0].memory_bytes() + labels_[1].memory_bytes() + peak_q * sizeof(Entry);
  if (meet < 0) return out;
  std::vector<VertexHandle> half;
  for (int v = meet; v >= 0; v = labels_[0].find(static_cast<uint32_t>(v))->pred) half.emplace_back(v);
  std::reverse(half.begin(), half.end());
  const Label* l = labels_[1].find(static_cast<uint32_t>(meet));
  for (int v = l->pred; v >= 0; v = labels_[1].find(static_cast<uint32_t>(v))->pred) half.emplace_back(v);
  EF_CHECK(half.front() == s && half.back() == t, "directed path reconstruction");
  out.vertices = std::move(half);
  return out;
}

}  // namespace edgefront::detail
