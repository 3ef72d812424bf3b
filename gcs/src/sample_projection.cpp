#include "detail/sample_projection.h"

#include <cmath>
#include <vector>

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

}  // namespace

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
