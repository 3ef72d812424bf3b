// Border growth (detail/heal.h: grow_borders, HealOptions::grow_rows): each border edge gets a
// triangle beyond it where the reference cloud continues the surface on the edge's own side and
// no face covers it yet; the wedges between neighbouring new triangles are closed. After a twist
// cut, both sides are right but meet at a fold (the surface came along one wall and turned back
// along the other); growing each side on along the points that face like it carries it across the
// fold on its own wall, until borders that run opposite meet and the zips join them.

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "detail/border_join.h"
#include "detail/geometry.h"
#include "detail/heal.h"
#include "edgefront/geometry.h"
#include "edgefront/mesh_stats.h"
#include "edgefront/triangle_bvh.h"

namespace twist::detail {

using edgefront::FaceHandle;
using edgefront::HalfedgeHandle;
using edgefront::Mesh;
using edgefront::Vec3;
using edgefront::VertexHandle;

namespace {

// In mean edge lengths.
constexpr double kReach = 0.866;         // a new vertex this far beyond its edge (equilateral height)
constexpr double kSupportRadius = 0.6;   // reference points this close to that spot support it
constexpr double kMinBeyond = 0.5;       // ... and their mean must lie at least this far beyond
constexpr double kCoverRadius = 0.45;    // a face facing the same way this close covers the spot
constexpr double kBlockRadius = 0.3;     // any face this close blocks it (a new face would cross it)
constexpr double kReuseRadius = 0.6;     // the neighbouring edge's new vertex this close is shared
constexpr double kSnapRadius = 0.6;      // another border's vertex this close is used instead of a new one
// Cosines.
// A supporting point's normal against the edge's face: sideways ones count, so that a row turns
// round a crease (a shell's rim between its two walls); the other wall's (opposite) do not.
constexpr double kSupportCos = -0.3;
constexpr double kFoldCos = 0.0;         // a new face against the face it borders: not folded back
constexpr double kAgreeCos = 0.3;        // a new face against its supporting points' mean normal
constexpr double kEarCos = 0.26;         // a wedge narrower than about 75 degrees is closed

Vec3 unit(const Vec3& v) {
  const double n = v.norm();
  return n > 0 ? v / n : Vec3(0, 0, 0);
}

Vec3 face_unit_normal(const Mesh& mesh, FaceHandle f) { return unit_normal(face_points(mesh, f)); }

/// The live faces on entry, for the coverage test.
class Coverage {
 public:
  explicit Coverage(const Mesh& mesh) {
    std::vector<edgefront::Triangle> tris;
    for (FaceHandle f : mesh.faces()) {
      if (!edgefront::is_live(mesh, f)) continue;
      edgefront::Triangle t = edgefront::face_triangle(mesh, f);
      if (!t.degenerate()) tris.push_back(t);
    }
    if (!tris.empty()) bvh_ = std::make_unique<edgefront::TriangleBvh>(std::move(tris));
  }
  /// True when a face whose normal agrees with `normal` lies within `radius` of `p`, or any face
  /// within `block`.
  bool covered(const Vec3& p, const Vec3& normal, double radius, double block) const {
    if (!bvh_) return false;
    edgefront::AlignedBox box;
    box.add(p - Vec3(radius));
    box.add(p + Vec3(radius));
    bool hit = false;
    bvh_->for_each_overlapping(box, 0, [&](int i) {
      if (hit) return;
      const edgefront::Triangle& t = bvh_->triangles()[static_cast<size_t>(i)];
      const double r = (t.n | normal) > 0 ? radius : block;
      hit = (edgefront::closest_point_on_triangle(p, t.p[0], t.p[1], t.p[2]) - p).sqrnorm() < r * r;
    });
    return hit;
  }

 private:
  std::unique_ptr<edgefront::TriangleBvh> bvh_;
};

struct Grower {
  Mesh& mesh;
  const ReferenceNormals& reference;
  double unit_length;
  size_t min_support;
  Coverage coverage;
  std::vector<VertexHandle> fresh;  // vertices added in this row
  std::vector<VertexHandle> border; // the border vertices at the start of the row, then the fresh ones
  std::vector<char> is_fresh;       // by vertex index
  std::vector<size_t> near;

  Grower(Mesh& m, const ReferenceNormals& r, double l, size_t s) : mesh(m), reference(r), unit_length(l), min_support(s), coverage(m) {}

  bool fresh_vertex(VertexHandle v) const { return static_cast<size_t>(v.idx()) < is_fresh.size() && is_fresh[static_cast<size_t>(v.idx())]; }

  bool near_fresh(const Vec3& p, double radius) const {
    for (VertexHandle v : fresh)
      if ((mesh.point(v) - p).sqrnorm() < radius * radius) return true;
    return false;
  }

  /// The mean of the reference points near `spot` facing like `normal` (and their mean normal);
  /// false when fewer than min_support.
  bool support(const Vec3& spot, const Vec3& normal, Vec3& mean, Vec3& mean_normal) {
    reference.within(spot, kSupportRadius * unit_length, near);
    const auto& cloud = reference.cloud();
    size_t count = 0;
    mean = Vec3(0, 0, 0);
    mean_normal = Vec3(0, 0, 0);
    for (size_t i : near) {
      if ((cloud.normals[i] | normal) < kSupportCos) continue;
      mean += cloud.points[i];
      mean_normal += cloud.normals[i];
      ++count;
    }
    if (count < min_support) return false;
    mean /= static_cast<double>(count);
    mean_normal = unit(mean_normal);
    return true;
  }

  /// True when at most one border gap meets at v (one fan, not pinched).
  bool one_fan(VertexHandle v) const {
    size_t gaps = 0;
    for (auto h = mesh.cvoh_iter(v); h.is_valid(); ++h) gaps += mesh.is_boundary(*h) ? 1 : 0;
    return gaps <= 1;
  }

  /// Adds face (a, b, c) unless OpenMesh refuses it or it would pinch a corner (two fans meeting
  /// at one vertex: then it is removed again); true when added.
  bool add(VertexHandle a, VertexHandle b, VertexHandle c) {
    const MuteOpenMeshErrors mute;
    const FaceHandle f = mesh.add_face(a, b, c);
    if (!f.is_valid()) return false;
    if (one_fan(a) && one_fan(b) && one_fan(c)) return true;
    mesh.delete_face(f, false);
    return false;
  }

  /// The border vertex (not a or b) nearest to q within kSnapRadius whose faces face like
  /// `normal` (mean cosine >= kAgreeCos); invalid for none.
  VertexHandle nearest_border_vertex(const Vec3& q, VertexHandle a, VertexHandle b, const Vec3& normal) const {
    VertexHandle best;
    double best_d2 = kSnapRadius * kSnapRadius * unit_length * unit_length;
    for (VertexHandle w : border) {
      if (w == a || w == b || mesh.status(w).deleted() || !mesh.is_boundary(w)) continue;
      const double d2 = (mesh.point(w) - q).sqrnorm();
      if (d2 >= best_d2) continue;
      Vec3 m(0, 0, 0);
      for (auto fit = mesh.cvf_iter(w); fit.is_valid(); ++fit) m += face_unit_normal(mesh, *fit);
      if ((unit(m) | normal) < kAgreeCos) continue;
      best = w;
      best_d2 = d2;
    }
    return best;
  }

  /// One triangle beyond the boundary halfedge h; `previous` is the vertex the previous edge of
  /// the loop grew to (invalid for none), updated.
  bool grow_edge(HalfedgeHandle h, VertexHandle& previous) {
    const VertexHandle a = mesh.from_vertex_handle(h), b = mesh.to_vertex_handle(h);
    const HalfedgeHandle inner = mesh.opposite_halfedge_handle(h);
    const FaceHandle f = mesh.face_handle(inner);
    const VertexHandle c = mesh.to_vertex_handle(mesh.next_halfedge_handle(inner));
    const Vec3 pa = mesh.point(a), pb = mesh.point(b), mid = 0.5 * (pa + pb);
    const Vec3 n = face_unit_normal(mesh, f);
    Vec3 out = unit(n % (pb - pa));
    if ((out | (mesh.point(c) - mid)) > 0) out = -out;
    if (out.sqrnorm() == 0 || n.sqrnorm() == 0) return false;
    // Only a side the reference agrees with grows: a wrong one would grow on along the other wall.
    if (reference.judge((pa + pb + mesh.point(c)) / 3.0, n) <= 0) return false;
    Vec3 q, nq;
    if (!support(mid + kReach * unit_length * out, n, q, nq)) return false;
    if (((q - mid) | out) < kMinBeyond * unit_length) return false;
    VertexHandle r;
    if (previous.is_valid() && (mesh.point(previous) - q).sqrnorm() < kReuseRadius * kReuseRadius * unit_length * unit_length) {
      r = previous;
    } else if ((r = nearest_border_vertex(q, a, b, nq)).is_valid()) {
      // Another border runs there (the other side of a slit, a front grown from elsewhere): the
      // triangle closes on its vertex instead of a new one next to it.
    } else if (coverage.covered(q, nq, kCoverRadius * unit_length, kBlockRadius * unit_length) ||
               near_fresh(q, kReuseRadius * unit_length)) {
      return false;
    }
    if (r.is_valid()) q = mesh.point(r);
    const Vec3 t = unit((pb - pa) % (q - pa));
    if ((t | n) < kFoldCos || (t | nq) < kAgreeCos) return false;
    const bool made = !r.is_valid();
    if (made) r = mesh.add_vertex(q);
    if (!add(a, b, r)) {
      if (made) mesh.delete_vertex(r, false);
      return false;
    }
    if (made) {
      fresh.push_back(r);
      border.push_back(r);
      if (is_fresh.size() <= static_cast<size_t>(r.idx())) is_fresh.resize(static_cast<size_t>(r.idx()) + 1, 0);
      is_fresh[static_cast<size_t>(r.idx())] = 1;
    }
    previous = r;
    return true;
  }

  /// Closes the narrow wedge at border vertex v between its border neighbours u (before) and w
  /// (after) when one of them is new: face (u, v, w).
  bool close_wedge(VertexHandle u, VertexHandle v, VertexHandle w, HalfedgeHandle in, HalfedgeHandle out) {
    if (u == w || (!fresh_vertex(u) && !fresh_vertex(w))) return false;
    const Vec3 pu = mesh.point(u), pv = mesh.point(v), pw = mesh.point(w);
    if ((unit(pu - pv) | unit(pw - pv)) < kEarCos) return false;
    const Vec3 t = unit((pv - pu) % (pw - pu));
    const Vec3 n1 = face_unit_normal(mesh, mesh.face_handle(mesh.opposite_halfedge_handle(in)));
    const Vec3 n2 = face_unit_normal(mesh, mesh.face_handle(mesh.opposite_halfedge_handle(out)));
    if ((t | n1) < kAgreeCos || (t | n2) < kAgreeCos) return false;
    const Vec3 centre = (pu + pv + pw) / 3.0;
    const auto& cloud = reference.cloud();
    if ((cloud.points[reference.nearest(centre)] - centre).norm() > kCoverRadius * unit_length) return false;
    return add(u, v, w);
  }
};

}  // namespace

size_t grow_borders(Mesh& mesh, const ReferenceNormals& reference, double mean_edge_length, size_t min_support) {
  if (!(mean_edge_length > 0)) return 0;
  Grower g(mesh, reference, mean_edge_length, std::max<size_t>(min_support, 1));
  const std::vector<BorderLoop> loops = border_loops(mesh);
  for (const BorderLoop& loop : loops) g.border.insert(g.border.end(), loop.vertices.begin(), loop.vertices.end());
  size_t faces = 0;
  for (const BorderLoop& loop : loops) {
    VertexHandle previous;
    for (HalfedgeHandle h : loop.halfedges) {
      if (!mesh.is_boundary(h) || !mesh.face_handle(mesh.opposite_halfedge_handle(h)).is_valid()) {
        previous.reset();
        continue;
      }
      if (g.grow_edge(h, previous)) {
        ++faces;
      } else {
        previous.reset();
      }
    }
  }
  if (g.fresh.empty()) return faces;
  for (const BorderLoop& loop : border_loops(mesh)) {
    const long n = static_cast<long>(loop.vertices.size());
    if (n < 4) continue;  // a hole of 3 is the heal's
    for (long k = 0; k < n; ++k) {
      const HalfedgeHandle in = loop_halfedge(loop, k - 1), out = loop_halfedge(loop, k);
      if (!mesh.is_boundary(in) || !mesh.is_boundary(out) || mesh.next_halfedge_handle(in) != out) continue;
      if (g.close_wedge(loop_vertex(loop, k - 1), loop_vertex(loop, k), loop_vertex(loop, k + 1), in, out)) {
        ++faces;
        ++k;  // the next vertex's wedge changed
      }
    }
  }
  return faces;
}

}  // namespace twist::detail
