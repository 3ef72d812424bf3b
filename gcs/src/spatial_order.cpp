#include "detail/spatial_order.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <tuple>
#include <utility>

#include "edgefront/error.h"

namespace gcs::detail {

using edgefront::EdgeHandle;
using edgefront::FaceHandle;
using edgefront::HalfedgeHandle;
using edgefront::Mesh;
using edgefront::Vec3;
using edgefront::VertexHandle;

namespace {

// Spreads the low 21 bits of x so that bit i lands on bit 3 i.
std::uint64_t spread3(std::uint64_t x) {
  x &= 0x1fffff;
  x = (x | x << 32) & 0x1f00000000ffffULL;
  x = (x | x << 16) & 0x1f0000ff0000ffULL;
  x = (x | x << 8) & 0x100f00f00f00f00fULL;
  x = (x | x << 4) & 0x10c30c30c30c30c3ULL;
  x = (x | x << 2) & 0x1249249249249249ULL;
  return x;
}

// Morton codes of points over their bounding box, `bits` (<= 21) per axis.
struct MortonCoder {
  Vec3 lo, scale;
  double max;
  MortonCoder(const std::vector<Vec3>& points, int bits) : max(static_cast<double>((1u << bits) - 1)) {
    Vec3 hi = points[0];
    lo = points[0];
    for (const Vec3& p : points) {
      lo.minimize(p);
      hi.maximize(p);
    }
    for (int a = 0; a < 3; ++a) {
      const double ext = hi[a] - lo[a];
      scale[a] = ext > 0 ? max / ext : 0.0;
    }
  }
  std::uint64_t operator()(const Vec3& p) const {
    std::uint64_t c[3];
    for (int a = 0; a < 3; ++a) {
      const double q = (p[a] - lo[a]) * scale[a];
      // NaN and out-of-box coordinates go to the box's faces (only the order is affected).
      c[a] = q > 0 ? static_cast<std::uint64_t>(std::min(q, max)) : 0;
    }
    return spread3(c[0]) | spread3(c[1]) << 1 | spread3(c[2]) << 2;
  }
};

// Sorts (code, index) pairs that are in increasing index order by their code_bits-bit codes, ties
// keeping the index order: the same result as std::sort of the pairs. An LSD radix sort (11-bit
// digits; digits every key shares are skipped): linear in n, where the comparison sort of a large
// cloud was most of the set-up's sorting time.
template <class Code, class Index>
void sort_by_code(std::vector<std::pair<Code, Index>>& keyed, int code_bits) {
  constexpr int kBits = 11;
  constexpr std::size_t kBuckets = std::size_t(1) << kBits;
  if (keyed.size() < 4096) {
    std::sort(keyed.begin(), keyed.end());
    return;
  }
  const int passes = (code_bits + kBits - 1) / kBits;
  std::vector<std::array<std::size_t, kBuckets>> count(static_cast<std::size_t>(passes));
  for (auto& c : count) c.fill(0);
  for (const auto& e : keyed)
    for (int p = 0; p < passes; ++p) ++count[p][(e.first >> (p * kBits)) & (kBuckets - 1)];
  std::vector<std::pair<Code, Index>> other(keyed.size());
  for (int p = 0; p < passes; ++p) {
    std::array<std::size_t, kBuckets>& c = count[p];
    if (std::find(c.begin(), c.end(), keyed.size()) != c.end()) continue;  // one digit for all
    std::size_t sum = 0;
    for (std::size_t& x : c) sum += std::exchange(x, sum);  // bucket starts
    for (const auto& e : keyed) other[c[(e.first >> (p * kBits)) & (kBuckets - 1)]++] = e;
    keyed.swap(other);
  }
}

}  // namespace

std::vector<std::size_t> morton_order(const std::vector<Vec3>& points) {
  std::vector<std::size_t> order(points.size());
  if (points.empty()) return order;
  constexpr int kBitsPerAxis = 21;  // 3 x 21 = 63 bits: the finest code in a 64-bit key
  const MortonCoder code(points, kBitsPerAxis);
  std::vector<std::pair<std::uint64_t, std::size_t>> keyed(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) keyed[i] = {code(points[i]), i};
  sort_by_code(keyed, 3 * kBitsPerAxis);
  for (std::size_t i = 0; i < keyed.size(); ++i) order[i] = keyed[i].second;
  return order;
}

std::vector<std::size_t> coarse_morton_order(const std::vector<Vec3>& points) {
  EF_CHECK(points.size() < (std::size_t(1) << 32), "coarse_morton_order: more than 2^32 points");
  std::vector<std::size_t> order(points.size());
  if (points.empty()) return order;
  // 8-byte pairs and three radix passes instead of morton_order's 16 bytes and six.
  constexpr int kBitsPerAxis = 10;  // 3 x 10 = 30 bits: the code fits a 32-bit key
  const MortonCoder code(points, kBitsPerAxis);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> keyed(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    keyed[i] = {static_cast<std::uint32_t>(code(points[i])), static_cast<std::uint32_t>(i)};
  sort_by_code(keyed, 3 * kBitsPerAxis);
  for (std::size_t i = 0; i < keyed.size(); ++i) order[i] = keyed[i].second;
  return order;
}

std::vector<std::size_t> stride_subsample(std::size_t n, std::size_t max_points, std::uint64_t seed) {
  EF_CHECK(max_points >= 1, "stride_subsample: max_points must be at least 1");
  const std::size_t k = n <= max_points ? 1 : (n + max_points - 1) / max_points;
  // The run position from the seed (splitmix64 finalizer: nearby seeds give unrelated positions).
  std::uint64_t z = seed + 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  z ^= z >> 31;
  std::vector<std::size_t> out;
  out.reserve(n / k + 1);
  for (std::size_t i = static_cast<std::size_t>(z % k); i < n; i += k) out.push_back(i);
  return out;
}

MeshRenumbering renumber_spatially(Mesh& mesh) {
  MeshRenumbering map;
  map.vertex.assign(mesh.n_vertices(), -1);
  map.edge.assign(mesh.n_edges(), -1);
  map.face.assign(mesh.n_faces(), -1);

  // Vertices by Morton code of their position.
  std::vector<Vec3> pos;
  std::vector<VertexHandle> live;
  for (auto v : mesh.vertices()) {
    live.push_back(v);
    pos.push_back(mesh.point(v));
  }
  const std::vector<std::size_t> vorder = morton_order(pos);
  for (std::size_t k = 0; k < vorder.size(); ++k) map.vertex[live[vorder[k]].idx()] = static_cast<int>(k);
  const auto vnew = [&](VertexHandle v) {
    const int n = map.vertex[v.idx()];
    EF_CHECK(n >= 0, "renumber: a live element uses a deleted vertex");
    return n;
  };

  // Edges by their (smaller, larger) new vertex index, faces by their sorted new vertex indices.
  std::vector<std::pair<std::uint64_t, int>> edges;
  for (auto e : mesh.edges()) {
    const HalfedgeHandle h = mesh.halfedge_handle(e, 0);
    const auto a = static_cast<std::uint64_t>(vnew(mesh.from_vertex_handle(h)));
    const auto b = static_cast<std::uint64_t>(vnew(mesh.to_vertex_handle(h)));
    edges.emplace_back(std::min(a, b) << 32 | std::max(a, b), e.idx());
  }
  std::sort(edges.begin(), edges.end());
  std::vector<std::pair<std::array<int, 3>, int>> faces;
  for (auto f : mesh.faces()) {
    std::array<int, 3> key{};
    int k = 0;
    for (auto v : mesh.fv_range(f)) {
      EF_CHECK(k < 3, "renumber: the mesh has a face that is not a triangle");
      key[k++] = vnew(v);
    }
    std::sort(key.begin(), key.end());
    faces.emplace_back(key, f.idx());
  }
  std::sort(faces.begin(), faces.end());

  Mesh out;
  out.reserve(live.size(), edges.size(), faces.size());
  for (const std::size_t i : vorder) out.new_vertex(pos[i]);
  std::vector<HalfedgeHandle> hnew(mesh.n_halfedges());
  for (const auto& [key, e] : edges) {
    const HalfedgeHandle h0 = mesh.halfedge_handle(EdgeHandle(e), 0);
    map.edge[static_cast<std::size_t>(e)] = static_cast<int>(out.n_edges());
    const HalfedgeHandle n0 =
        out.new_edge(VertexHandle(vnew(mesh.from_vertex_handle(h0))), VertexHandle(vnew(mesh.to_vertex_handle(h0))));
    hnew[h0.idx()] = n0;
    hnew[mesh.opposite_halfedge_handle(h0).idx()] = out.opposite_halfedge_handle(n0);
  }
  for (std::size_t k = 0; k < faces.size(); ++k) {
    const FaceHandle f(faces[k].second);
    map.face[f.idx()] = static_cast<int>(k);
    const FaceHandle nf = out.new_face();
    out.set_halfedge_handle(nf, hnew[mesh.halfedge_handle(f).idx()]);
    out.set_normal(nf, mesh.normal(f));
  }
  for (const auto& [key, e] : edges) {
    for (int side = 0; side < 2; ++side) {
      const HalfedgeHandle h = mesh.halfedge_handle(EdgeHandle(e), side);
      const HalfedgeHandle next = mesh.next_halfedge_handle(h);
      EF_CHECK(next.is_valid() && hnew[next.idx()].is_valid(), "renumber: a halfedge has no live successor");
      out.set_next_halfedge_handle(hnew[h.idx()], hnew[next.idx()]);
      const FaceHandle f = mesh.face_handle(h);
      out.set_face_handle(hnew[h.idx()], f.is_valid() ? FaceHandle(map.face[f.idx()]) : FaceHandle());
    }
  }
  for (std::size_t k = 0; k < vorder.size(); ++k) {
    const HalfedgeHandle h = mesh.halfedge_handle(live[vorder[k]]);
    out.set_halfedge_handle(VertexHandle(static_cast<int>(k)), h.is_valid() ? hnew[h.idx()] : HalfedgeHandle());
  }
  mesh = std::move(out);
  return map;
}

}  // namespace gcs::detail
