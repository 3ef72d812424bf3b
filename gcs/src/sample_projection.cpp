#include "detail/sample_projection.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

#include "detail/self_intersection.h"
#include "edgefront/error.h"

namespace gcs::detail {

using edgefront::FaceHandle;
using edgefront::Mesh;
using edgefront::Vec3;
using edgefront::VertexHandle;

namespace {

// The (unnormalized) normal of face f with vertex v placed at `at`.
Vec3 moved_face_normal(const Mesh& mesh, FaceHandle f, VertexHandle v, const Vec3& at) {
  Vec3 p[3];
  int k = 0;
  for (auto u : mesh.fv_range(f)) p[k++] = u == v ? at : mesh.point(u);
  return (p[1] - p[0]) % (p[2] - p[0]);
}

double angle_at(const Vec3& apex, const Vec3& a, const Vec3& b) {
  const Vec3 u = a - apex, w = b - apex;
  return std::atan2((u % w).norm(), u | w);
}

Vec3 unit_normal_of(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 n = (b - a) % (c - a);
  const double len = n.norm();
  return len > 0 ? n / len : Vec3(0, 0, 0);
}

// The unordered vertex pair {a, b} as (smaller index, larger index).
std::pair<int, int> pair_key(VertexHandle a, VertexHandle b) {
  return a.idx() < b.idx() ? std::pair<int, int>(a.idx(), b.idx()) : std::pair<int, int>(b.idx(), a.idx());
}

// Whether the vertex pair {a, b} is one of `keys` (sorted pair_keys).
bool listed(const std::vector<std::pair<int, int>>& keys, VertexHandle a, VertexHandle b) {
  return std::binary_search(keys.begin(), keys.end(), pair_key(a, b));
}

// Half-width (radians) of the near-Delaunay band of opposite-angle sums in which the valences
// decide (see delaunay_flips).
constexpr double kValenceSlack = 30.0 * std::numbers::pi / 180.0;

// One run of Delaunay flips (see delaunay_flips), skipping the edges whose end pairs are in
// `frozen`; returns the flipped edges in order and flags (by face index, in `changed`) the faces
// whose triangle a flip replaced (a flip keeps the two face handles of its edge).
std::vector<edgefront::EdgeHandle> flip_pass(Mesh& mesh, double min_dihedral_cos, int max_passes,
                                             const std::vector<std::pair<int, int>>& frozen, std::vector<char>& changed) {
  changed.assign(mesh.n_faces(), 0);
  std::vector<edgefront::EdgeHandle> done;
  for (int pass = 0; pass < max_passes; ++pass) {
    const std::size_t before = done.size();
    for (auto e : mesh.edges()) {
      if (mesh.status(e).deleted() || mesh.is_boundary(e) || !mesh.is_flip_ok(e)) continue;
      const auto h0 = mesh.halfedge_handle(e, 0), h1 = mesh.halfedge_handle(e, 1);
      const VertexHandle p = mesh.from_vertex_handle(h0), q = mesh.to_vertex_handle(h0);
      const VertexHandle r = mesh.to_vertex_handle(mesh.next_halfedge_handle(h0));
      const VertexHandle t = mesh.to_vertex_handle(mesh.next_halfedge_handle(h1));
      const auto too_low = [&](VertexHandle x) { return mesh.valence(x) <= (mesh.is_boundary(x) ? 2u : 3u); };
      if (too_low(p) || too_low(q) || listed(frozen, p, q)) continue;
      const Vec3 &xp = mesh.point(p), &xq = mesh.point(q), &xr = mesh.point(r), &xt = mesh.point(t);
      const double opposite = angle_at(xr, xp, xq) + angle_at(xt, xq, xp);
      if (opposite <= std::numbers::pi - kValenceSlack) continue;
      if (opposite <= std::numbers::pi + kValenceSlack) {
        // Near-Delaunay, the valences decide (sum of the four squared deviations from 6, 4 on a
        // border): a non-Delaunay edge is flipped unless that worsens them, a Delaunay one when it
        // improves them by at least 2. Neither rule flips the new edge back: its opposite angles sum
        // to at most pi + slack, and flipping it back would undo the gain or cross pi the wrong way.
        const auto dev = [&](VertexHandle x, int change) {
          const int d = static_cast<int>(mesh.valence(x)) + change - (mesh.is_boundary(x) ? 4 : 6);
          return d * d;
        };
        const int gain = dev(p, 0) + dev(q, 0) + dev(r, 0) + dev(t, 0) - dev(p, -1) - dev(q, -1) - dev(r, 1) - dev(t, 1);
        if (!(gain >= 2 || (gain >= 0 && opposite > std::numbers::pi + 1e-9))) continue;
      }
      const Vec3 n0 = unit_normal_of(xp, xq, xr), n1 = unit_normal_of(xq, xp, xt);
      if ((n0 | n1) < min_dihedral_cos) continue;
      const Vec3 m0 = unit_normal_of(xp, xt, xr), m1 = unit_normal_of(xt, xq, xr);
      if ((m0 | n0) < min_dihedral_cos || (m0 | n1) < min_dihedral_cos || (m1 | n0) < min_dihedral_cos ||
          (m1 | n1) < min_dihedral_cos)
        continue;
      changed[static_cast<std::size_t>(mesh.face_handle(h0).idx())] = 1;
      changed[static_cast<std::size_t>(mesh.face_handle(h1).idx())] = 1;
      mesh.flip(e);
      done.push_back(e);
    }
    if (done.size() == before) break;
  }
  return done;
}

}  // namespace

std::size_t delaunay_flips(Mesh& mesh, double min_dihedral_cos, int max_passes) {
  if (!(min_dihedral_cos >= -1 && min_dihedral_cos <= 1))
    throw edgefront::InvalidInput("gcs Delaunay flips: min_dihedral_cos must be in [-1, 1]");
  if (max_passes < 0) throw edgefront::InvalidInput("gcs Delaunay flips: max_passes must be >= 0");
  std::vector<std::pair<int, int>> frozen;
  for (int attempt = 0; attempt < 4; ++attempt) {
    std::vector<char> flipped;
    const std::vector<edgefront::EdgeHandle> done = flip_pass(mesh, min_dihedral_cos, max_passes, frozen, flipped);
    if (done.empty()) return 0;
    // Faces no flip touched keep their triangles: a self-intersecting pair is new (or at least
    // involves a new triangle) exactly when one of its faces was flipped.
    std::vector<std::pair<int, int>> fresh;
    for (const auto& pair : self_intersecting_face_pairs(mesh))
      if (flipped[static_cast<std::size_t>(pair.first)] || flipped[static_cast<std::size_t>(pair.second)]) fresh.push_back(pair);
    if (fresh.empty()) {
      mesh.update_face_normals();
      return done.size();
    }
    // A flip made faces intersect: undo every flip (in reverse order: each flip of an edge is
    // undone by flipping it again) and try again without flipping the edges of those faces.
    for (auto it = done.rbegin(); it != done.rend(); ++it) mesh.flip(*it);
    for (const auto& pair : fresh) {
      for (const int f : {pair.first, pair.second}) {
        for (auto h : mesh.fh_range(FaceHandle(f)))
          frozen.push_back(pair_key(mesh.from_vertex_handle(h), mesh.to_vertex_handle(h)));
      }
    }
    std::sort(frozen.begin(), frozen.end());
    frozen.erase(std::unique(frozen.begin(), frozen.end()), frozen.end());
  }
  return 0;
}

std::size_t project_to_samples(Mesh& mesh, const CloudQuery& nearest, double max_move, double min_face_cos) {
  std::vector<Vec3> target(mesh.n_vertices());
  std::vector<char> movable(mesh.n_vertices(), 0);
  for (auto v : mesh.vertices()) {
    if (mesh.is_boundary(v)) continue;
    const Vec3& x = mesh.point(v);
    const CloudHit s = nearest(x);
    const double ln2 = s.normal.sqrnorm();
    if (!std::isfinite(ln2) || !(ln2 > 0)) continue;
    const Vec3 y = x - (((x - s.point) | s.normal) / ln2) * s.normal;
    if (!((y - x).norm() <= max_move)) continue;
    target[v.idx()] = y;
    movable[v.idx()] = 1;
  }
  // Every face may turn by at most acos(min_face_cos) from where it was before any move.
  std::vector<Vec3> before_normal(mesh.n_faces());
  for (auto f : mesh.faces()) before_normal[f.idx()] = mesh.calc_face_normal(f);  // unit, or zero if degenerate
  std::size_t moved = 0;
  for (auto v : mesh.vertices()) {
    if (!movable[v.idx()]) continue;
    bool ok = true;
    for (auto f : mesh.vf_range(v)) {
      const Vec3& before = before_normal[f.idx()];
      const Vec3 after = moved_face_normal(mesh, f, v, target[v.idx()]);
      ok = ok && (before | after) >= min_face_cos * after.norm() && after.norm() > 0;
    }
    if (!ok) continue;
    mesh.point(v) = target[v.idx()];
    ++moved;
  }
  return moved;
}

}  // namespace gcs::detail
