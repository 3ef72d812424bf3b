#include "edgefront/geodesic_ring_table.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>

#include "detail/distance_common.h"
#include "edgefront/error.h"

namespace edgefront {

using detail::kFlatDefect;
using detail::kTwoPi;

namespace detail {

GeodesicRingTable::Ring layout_ring(const Mesh& mesh, int x, std::vector<GeodesicRingTable::Edge>& edges,
                                    std::vector<GeodesicRingTable::Corner>& corners) {
  using Corner = GeodesicRingTable::Corner;
  const VertexHandle vx(x);
  GeodesicRingTable::Ring info;
  info.point = mesh.point(vx);
  check_finite_vertex(info.point, x);
  info.begin = static_cast<std::uint32_t>(corners.size());
  // The ring, in the walk order of next(opposite(h)).
  size_t gap = 0;
  int gaps = 0;
  const HalfedgeHandle h0 = mesh.halfedge_handle(vx);
  const size_t max_ring = mesh.n_halfedges();
  if (h0.is_valid() && !mesh.status(vx).deleted()) {
    HalfedgeHandle h = h0;
    do {
      const VertexHandle y = mesh.to_vertex_handle(h);
      const HalfedgeHandle g = mesh.opposite_halfedge_handle(h);
      Corner c;
      check_finite_vertex(mesh.point(y), y.idx());
      c.e = mesh.point(y) - info.point;
      c.face_after = mesh.face_handle(g).is_valid();
      if (!c.face_after) {
        gap = corners.size() - info.begin;
        ++gaps;
      }
      edges.push_back(GeodesicRingTable::Edge{c.e.norm(), y.idx(), y.idx()});
      corners.push_back(c);
      h = mesh.next_halfedge_handle(g);
      if (corners.size() - info.begin > max_ring) {
        throw InternalError("distance: the ring of vertex " + std::to_string(x) + " does not close");
      }
    } while (h != h0);
  }
  const size_t m = corners.size() - info.begin;
  info.size = static_cast<std::uint32_t>(m);
  info.non_manifold = gaps > 1;
  info.closed = gaps == 0;
  info.first = static_cast<std::uint32_t>(info.closed || m == 0 ? 0 : (gap + 1) % m);
  // The corners, and the angle sum with its rotation as a running product (in the order a query
  // sums the ring angles, from the first edge on).
  Corner* ring = corners.data() + info.begin;
  const GeodesicRingTable::Edge* edge = edges.data() + info.begin;
  double total = 0, cos_total = 1, sin_total = 0;
  for (size_t k = 0, i = info.first; k < m; ++k) {
    Corner& cy = ring[i];
    const size_t nx = i + 1 == m ? 0 : i + 1;
    if (cy.face_after) {
      const Vec3& f = ring[nx].e;
      const double sn = OpenMesh::cross(cy.e, f).norm(), cs = OpenMesh::dot(cy.e, f);
      cy.angle_after = std::atan2(sn, cs);
      total += cy.angle_after;
      const double ll = edge[i].len * edge[nx].len;
      if (ll > 0) {
        cy.cos_after = cs / ll;
        cy.sin_after = sn / ll;
      }
      const double c2 = cos_total * cy.cos_after - sin_total * cy.sin_after;
      sin_total = sin_total * cy.cos_after + cos_total * cy.sin_after;
      cos_total = c2;
    }
    i = nx;
  }
  info.total = total;
  info.cos_total = cos_total;
  info.sin_total = sin_total;
  info.flat = info.closed && std::abs(total - kTwoPi) < kFlatDefect;
  return info;
}

}  // namespace detail

namespace {

// The position of a point with coordinates x[0..2] (each below 2^bits) along the Hilbert curve
// through the 2^bits-cube (Skilling's transpose form: the coordinates turned into the curve's
// digits in place, then their bits interleaved).
std::uint64_t hilbert_key(std::uint32_t x[3], int bits) {
  for (std::uint32_t q = 1u << (bits - 1); q > 1; q >>= 1) {  // undo the excess rotations
    const std::uint32_t low = q - 1;
    for (int i = 0; i < 3; ++i) {
      if (x[i] & q) {
        x[0] ^= low;
      } else {
        const std::uint32_t t = (x[0] ^ x[i]) & low;
        x[0] ^= t;
        x[i] ^= t;
      }
    }
  }
  x[1] ^= x[0];  // Gray code
  x[2] ^= x[1];
  std::uint32_t t = 0;
  for (std::uint32_t q = 1u << (bits - 1); q > 1; q >>= 1) {
    if (x[2] & q) t ^= q - 1;
  }
  std::uint64_t key = 0;
  for (int b = bits - 1; b >= 0; --b) {
    for (int i = 0; i < 3; ++i) key = key << 1 | (((x[i] ^ t) >> b) & 1u);
  }
  return key;
}

// The mesh's vertices sorted by their position along a Hilbert curve through the bounding cube
// of their points (21 bits per axis; ties, and NaN coordinates, by mesh index).
std::vector<int> locality_order(const Mesh& mesh) {
  constexpr int kBits = 21;
  const size_t n = mesh.n_vertices();
  Vec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (size_t v = 0; v < n; ++v) {
    const Vec3& p = mesh.point(VertexHandle(static_cast<int>(v)));
    for (int a = 0; a < 3; ++a) {
      if (std::isfinite(p[a])) {
        lo[a] = std::min(lo[a], p[a]);
        hi[a] = std::max(hi[a], p[a]);
      }
    }
  }
  double extent = 0;
  for (int a = 0; a < 3; ++a) extent = std::max(extent, hi[a] - lo[a]);
  const double top = static_cast<double>((1u << kBits) - 1);
  const double scale = extent > 0 ? top / extent : 0.0;
  std::vector<std::pair<std::uint64_t, int>> keyed(n);
  for (size_t v = 0; v < n; ++v) {
    const Vec3& p = mesh.point(VertexHandle(static_cast<int>(v)));
    std::uint32_t x[3];
    for (int a = 0; a < 3; ++a) {
      const double q = (p[a] - lo[a]) * scale;  // NaN and infinities go to the cube's faces
      x[a] = q > 0 ? static_cast<std::uint32_t>(std::min(q, top)) : 0u;
    }
    keyed[v] = {hilbert_key(x, kBits), static_cast<int>(v)};
  }
  std::sort(keyed.begin(), keyed.end());
  std::vector<int> order(n);
  for (size_t i = 0; i < n; ++i) order[i] = keyed[i].second;
  return order;
}

}  // namespace

GeodesicRingTable::GeodesicRingTable(const Mesh& mesh)
    : n_faces_(mesh.n_faces()), n_halfedges_(mesh.n_halfedges()) {
  if (mesh.n_halfedges() >= std::numeric_limits<std::uint32_t>::max()) {
    throw InvalidInput("ring table: the mesh has " + std::to_string(mesh.n_halfedges()) +
                       " halfedges, more than the table's 32-bit offsets hold");
  }
  const size_t n = mesh.n_vertices();
  vertex_ = locality_order(mesh);
  index_.resize(n);
  for (size_t i = 0; i < n; ++i) index_[static_cast<size_t>(vertex_[i])] = static_cast<int>(i);
  rings_.resize(n);
  edges_.reserve(mesh.n_halfedges());
  corners_.reserve(mesh.n_halfedges());
  for (size_t i = 0; i < n; ++i) rings_[i] = detail::layout_ring(mesh, vertex_[i], edges_, corners_);
  for (Edge& e : edges_) e.v = index_[static_cast<size_t>(e.vertex)];
}

bool GeodesicRingTable::matches(const Mesh& mesh) const {
  return mesh.n_vertices() == rings_.size() && mesh.n_faces() == n_faces_ && mesh.n_halfedges() == n_halfedges_;
}

void GeodesicRingTable::check(const Mesh& mesh) const {
  if (matches(mesh)) return;
  throw InvalidInput("ring table: built for a mesh with " + std::to_string(rings_.size()) + " vertices, " +
                     std::to_string(n_faces_) + " faces, " + std::to_string(n_halfedges_) +
                     " halfedges, but this mesh has " + std::to_string(mesh.n_vertices()) + ", " +
                     std::to_string(mesh.n_faces()) + ", " + std::to_string(mesh.n_halfedges()) +
                     ": rebuild the table after changing the mesh");
}

}  // namespace edgefront
