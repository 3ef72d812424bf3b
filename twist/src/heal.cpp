// The session's border heal (detail/heal.h) on the shared border joins (detail/border_join.h).

#include "detail/heal.h"

#include <algorithm>

#include "detail/border_join.h"
#include "edgefront/mesh_stats.h"

namespace twist::detail {

using edgefront::FaceHandle;
using edgefront::Mesh;
using edgefront::Vec3;

HealCounts heal_borders(Mesh& mesh, const ReferenceNormals& reference, double mean_edge_length,
                        const HealOptions& options, std::vector<FaceHandle>& added) {
  HealCounts counts;
  if (!(mean_edge_length > 0)) return counts;
  const size_t faces_before = mesh.n_faces();
  const std::vector<Vec3>& points = reference.cloud().points;
  const CloudDistance cloud = [&](const Vec3& p) { return (p - points[reference.nearest(p)]).norm(); };
  const double support = options.max_support_edges * mean_edge_length;
  for (size_t row = 0; row < options.grow_rows; ++row) {
    const size_t grown = grow_borders(mesh, reference, mean_edge_length, options.grow_min_support);
    counts.grown += grown;
    if (grown == 0) break;
  }
  if (options.max_gap_edges > 0 && options.max_zips > 0) {
    ZipParams zp;
    zp.mean_edge_length = mean_edge_length;
    zp.max_support_distance = support;
    zp.max_gap_edges = options.max_gap_edges;
    zp.max_zips = options.max_zips;
    zp.min_normal_agreement = options.min_normal_agreement;
    zp.across_loops = true;
    counts.strips = zip_border_slits(mesh, cloud, zp);
  }
  if (options.max_hole_vertices >= 3) {
    for (const BorderLoop& loop : border_loops(mesh)) {
      if (loop.vertices.size() > options.max_hole_vertices) continue;
      if (fill_loop(mesh, cloud, loop, support, options.min_normal_agreement)) ++counts.holes;
    }
  }
  for (size_t i = faces_before; i < mesh.n_faces(); ++i) {
    const FaceHandle f(static_cast<int>(i));
    if (!edgefront::is_live(mesh, f)) continue;
    mesh.set_normal(f, mesh.calc_face_normal(f));  // as the session keeps its faces' normals
    added.push_back(f);
  }
  return counts;
}

size_t remove_small_pieces(Mesh& mesh, double share) {
  if (!(share > 0)) return 0;
  const edgefront::ComponentLabels labels = edgefront::connected_components(mesh);
  if (labels.count < 2) return 0;
  auto label_of = [&](FaceHandle f) { return static_cast<size_t>(labels.vertex_component[(*mesh.fv_begin(f)).idx()]); };
  std::vector<size_t> faces(labels.count, 0);
  for (FaceHandle f : mesh.faces())
    if (edgefront::is_live(mesh, f)) ++faces[label_of(f)];
  const size_t largest = static_cast<size_t>(std::max_element(faces.begin(), faces.end()) - faces.begin());
  const double limit = share * static_cast<double>(faces[largest]);
  size_t removed = 0;
  for (FaceHandle f : mesh.faces()) {
    if (!edgefront::is_live(mesh, f)) continue;
    const size_t c = label_of(f);
    if (c == largest || static_cast<double>(faces[c]) >= limit) continue;
    mesh.delete_face(f, true);
    ++removed;
  }
  return removed;
}

}  // namespace twist::detail
