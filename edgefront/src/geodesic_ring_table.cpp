#include "edgefront/geodesic_ring_table.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "detail/distance_common.h"
#include "edgefront/error.h"

namespace edgefront {

using detail::kFlatDefect;
using detail::kTwoPi;

GeodesicRingTable::GeodesicRingTable(const Mesh& mesh)
    : n_faces_(mesh.n_faces()), n_halfedges_(mesh.n_halfedges()) {
  if (mesh.n_halfedges() >= std::numeric_limits<std::uint32_t>::max()) {
    throw InvalidInput("ring table: the mesh has " + std::to_string(mesh.n_halfedges()) +
                       " halfedges, more than the table's 32-bit offsets hold");
  }
  const size_t n = mesh.n_vertices();
  rings_.resize(n);
  rays_.reserve(mesh.n_halfedges());
  const size_t max_ring = mesh.n_halfedges();
  for (size_t x = 0; x < n; ++x) {
    const VertexHandle vx(static_cast<int>(x));
    Ring& info = rings_[x];
    info.point = mesh.point(vx);
    info.begin = static_cast<std::uint32_t>(rays_.size());
    // The ring, in the walk order of next(opposite(h)).
    size_t gap = 0;
    int gaps = 0;
    const HalfedgeHandle h0 = mesh.halfedge_handle(vx);
    if (h0.is_valid() && !mesh.status(vx).deleted()) {
      HalfedgeHandle h = h0;
      do {
        const VertexHandle y = mesh.to_vertex_handle(h);
        const HalfedgeHandle g = mesh.opposite_halfedge_handle(h);
        Ray ray;
        ray.e = mesh.point(y) - info.point;
        ray.len = ray.e.norm();
        ray.v = y.idx();
        ray.face_after = mesh.face_handle(g).is_valid();
        if (!ray.face_after) {
          gap = rays_.size() - info.begin;
          ++gaps;
        }
        rays_.push_back(ray);
        h = mesh.next_halfedge_handle(g);
        if (rays_.size() - info.begin > max_ring) {
          throw InternalError("ring table: the ring of vertex " + std::to_string(x) + " does not close");
        }
      } while (h != h0);
    }
    const size_t m = rays_.size() - info.begin;
    info.size = static_cast<std::uint32_t>(m);
    info.non_manifold = gaps > 1;
    info.closed = gaps == 0;
    info.first = static_cast<std::uint32_t>(info.closed || m == 0 ? 0 : (gap + 1) % m);
    // The layout: ring angles from the first ray on, and the rotations as running products.
    Ray* ring = rays_.data() + info.begin;
    double total = 0, cos_total = 1, sin_total = 0;
    for (size_t k = 0, i = info.first; k < m; ++k) {
      Ray& ry = ring[i];
      ry.theta = total;
      ry.cos_theta = cos_total;
      ry.sin_theta = sin_total;
      const size_t nx = i + 1 == m ? 0 : i + 1;
      if (ry.face_after) {
        const Vec3& f = ring[nx].e;
        const double sn = OpenMesh::cross(ry.e, f).norm(), cs = OpenMesh::dot(ry.e, f);
        ry.angle_after = std::atan2(sn, cs);
        total += ry.angle_after;
        const double ll = ry.len * ring[nx].len;
        if (ll > 0) {
          ry.cos_after = cs / ll;
          ry.sin_after = sn / ll;
        }
        const double c2 = cos_total * ry.cos_after - sin_total * ry.sin_after;
        sin_total = sin_total * ry.cos_after + cos_total * ry.sin_after;
        cos_total = c2;
      }
      i = nx;
    }
    info.total = total;
    info.cos_total = cos_total;
    info.sin_total = sin_total;
    info.flat = info.closed && std::abs(total - kTwoPi) < kFlatDefect;
  }
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
