// The faces a clean-up must not remove: those that alone cover a reference point (see
// `CutOptions::support_radius`). detail/repair_steps.h.
#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <unordered_set>
#include <vector>

#include "detail/geometry.h"
#include "detail/repair_steps.h"
#include "edgefront/geometry.h"
#include "edgefront/triangle_bvh.h"

namespace twist::detail {

using edgefront::FaceHandle;
using edgefront::Mesh;
using edgefront::Vec3;

std::vector<FaceHandle> sole_cover(const Mesh& mesh, const std::vector<FaceHandle>& faces, const ReferenceNormals& reference,
                                   double radius) {
  std::vector<FaceHandle> out;
  if (faces.empty() || !(radius > 0)) return out;
  std::unordered_set<int> doomed;
  for (FaceHandle f : faces) {
    if (edgefront::is_live(mesh, f)) doomed.insert(f.idx());
  }
  // The faces that stay, in a hierarchy; the doomed faces' own triangles for the exact test.
  std::vector<edgefront::Triangle> staying;
  for (FaceHandle f : mesh.faces()) {
    if (!doomed.count(f.idx())) staying.emplace_back(face_points(mesh, f));
  }
  const std::vector<Vec3>& samples = reference.cloud().points;
  const double r2 = radius * radius;
  std::unordered_set<size_t> settled;  // samples known to be covered by a staying face
  const std::unique_ptr<const edgefront::TriangleBvh> bvh =
      staying.empty() ? nullptr : std::make_unique<const edgefront::TriangleBvh>(std::move(staying));
  std::vector<size_t> near;
  for (FaceHandle f : faces) {
    if (!doomed.count(f.idx())) continue;
    const std::array<Vec3, 3> p = face_points(mesh, f);
    const Vec3 c = centroid(p);
    double reach = 0;
    for (const Vec3& q : p) reach = std::max(reach, (q - c).norm());
    reference.within(c, reach + radius, near);
    bool alone = false;
    for (size_t k : near) {
      const Vec3& s = samples[k];
      if ((edgefront::closest_point_on_triangle(s, p[0], p[1], p[2]) - s).sqrnorm() > r2) continue;
      if (settled.count(k)) continue;
      if (bvh && bvh->nearest(s).dist2 <= r2) {
        settled.insert(k);
        continue;
      }
      alone = true;
      break;
    }
    if (alone) out.push_back(f);
  }
  return out;
}

std::vector<FaceHandle> without_sole_cover(const Mesh& mesh, const std::vector<FaceHandle>& faces, const RepairOptions& o,
                                           size_t& spared) {
  if (!o.detect.reference || o.cuts.support_radius <= 0 || faces.empty()) return faces;
  const double edge = mean_edge_length(mesh);
  const std::vector<FaceHandle> alone = sole_cover(mesh, faces, *o.detect.reference, o.cuts.support_radius * edge);
  // Only faces the reference confirms are spared: a face turned the wrong way or undecided (on a
  // wall thinner than the thin-wall rule, either way is possible) that alone covers its points
  // still goes (sparing it could trade orientation for coverage).
  std::unordered_set<int> kept;
  for (FaceHandle f : alone) {
    const std::array<Vec3, 3> p = face_points(mesh, f);
    const Vec3 n = unit_normal(p);
    if (n.sqrnorm() > 0 && reference_vote(*o.detect.reference, o.detect, centroid(p), n, edge) > 0) kept.insert(f.idx());
  }
  if (kept.empty()) return faces;
  std::vector<FaceHandle> out;
  for (FaceHandle f : faces) {
    if (!kept.count(f.idx())) out.push_back(f);
  }
  spared += kept.size();
  return out;
}

}  // namespace twist::detail
