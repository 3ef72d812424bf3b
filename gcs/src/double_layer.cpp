#include "detail/double_layer.h"

#include <cmath>
#include <vector>

namespace gcs::detail {

using edgefront::FaceHandle;
using edgefront::Mesh;
using edgefront::Vec3;
using edgefront::VertexHandle;

Vec3 vertex_normal_sum(const Mesh& mesh, VertexHandle v) {
  Vec3 n(0, 0, 0);
  const Vec3& x = mesh.point(v);
  for (auto h : mesh.voh_range(v)) {
    if (!mesh.face_handle(h).is_valid()) continue;
    const Vec3& a = mesh.point(mesh.to_vertex_handle(h));
    const Vec3& b = mesh.point(mesh.to_vertex_handle(mesh.next_halfedge_handle(h)));
    n += (a - x) % (b - x);
  }
  return n;
}

int oriented_nearest(const Mesh& mesh, VertexGrid& grid, const Vec3& sample, const Vec3& normal,
                     int max_candidates, double max_extra_distance) {
  const int first = grid.nearest(sample);
  if (first < 0) return first;
  const auto agrees = [&](int id) { return (vertex_normal_sum(mesh, VertexHandle(id)) | normal) > 0; };
  if (agrees(first)) return first;
  const double limit = (grid.position(first) - sample).norm() + max_extra_distance;
  // Take disagreeing candidates out of the grid until an agreeing one is nearest, then put them
  // back at their stored positions (the grid's answers do not depend on insertion order).
  std::vector<std::pair<int, Vec3>> taken;
  taken.reserve(static_cast<size_t>(max_candidates));
  taken.emplace_back(first, grid.position(first));
  grid.remove(first);
  int found = -1;
  while (static_cast<int>(taken.size()) < max_candidates) {
    const int id = grid.nearest(sample);
    if (id < 0 || (grid.position(id) - sample).norm() > limit) break;
    if (agrees(id)) {
      found = id;
      break;
    }
    taken.emplace_back(id, grid.position(id));
    grid.remove(id);
  }
  for (const auto& [id, p] : taken) grid.insert(id, p);
  return found >= 0 ? found : first;
}

std::size_t remove_opposed_faces(Mesh& mesh, const CloudQuery& cloud, const OpposedParams& params) {
  std::vector<FaceHandle> doomed;
  size_t live_faces = 0;
  for (auto f : mesh.faces()) {
    ++live_faces;
    auto it = mesh.cfv_iter(f);
    const Vec3 a = mesh.point(*it), b = mesh.point(*++it), c = mesh.point(*++it);
    const CloudHit hit = cloud((a + b + c) / 3.0);
    if (!(hit.distance <= params.max_distance) || !std::isfinite(hit.normal[0])) continue;
    const Vec3 n = (b - a) % (c - a);
    const double ln = n.norm(), lh = hit.normal.norm();
    if (ln > 0 && lh > 0 && (n | hit.normal) < -params.min_cos * ln * lh) doomed.push_back(f);
  }
  if (doomed.empty() || doomed.size() * 10 >= live_faces * 9) return 0;  // never wipe out the mesh
  for (auto f : doomed) mesh.delete_face(f, true);
  return doomed.size() + clean_topology(mesh, params.min_component_faces, params.min_component_fraction);
}

}  // namespace gcs::detail
