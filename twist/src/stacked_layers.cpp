// twist::remove_stacked_layers: border faces stacked on another layer removed, pleats flattened.
#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

#include "detail/geometry.h"
#include "detail/repair_steps.h"
#include "edgefront/error.h"
#include "twist/repair.h"

namespace twist {

using edgefront::FaceHandle;
using edgefront::HalfedgeHandle;
using edgefront::InvalidInput;
using edgefront::Mesh;
using edgefront::Vec3;
using edgefront::VertexHandle;

using detail::folds_around;
using detail::interior_vertices_around;
using detail::MoveTest;
using detail::remove_faces;
using detail::smooth_until;
using detail::straighten_face;

namespace {

/// Flattens a pleat (see `StackedLayerOptions`) of stacked faces f and g. A face of the two with
/// two or three edges folded (n.n < 0) against its neighbours is turned over its own star (the
/// third edge may lie on a crease): it is straightened alone (`straighten_face`), kept when
/// fewer edges around fold than before and the two no longer overlap. Otherwise the interior vertices of f and g and their neighbours are smoothed
/// together, up to 3 rounds, kept when f and g no longer overlap, no face around is degenerate
/// and no more edges around fold than before. Returns whether something was kept (false too
/// when a face is gone, no vertex is interior, or the other wall lies within the pleat's gap
/// behind it).
bool flatten_pleat(Mesh& mesh, FaceHandle f, FaceHandle g) {
  if (!edgefront::is_live(mesh, f) || !edgefront::is_live(mesh, g)) return false;
  auto apart = [&] {
    const FaceGeometry a = face_geometry(mesh, f), b = face_geometry(mesh, g);
    return !detail::stacked_layers(detail::face_points(mesh, f), a.normal, a.longest, detail::face_points(mesh, g), b.normal,
                                   b.longest);
  };
  // A face turned over its own star (vault shell t/R 0.1 at 1500 vertices, seed 1, repair: one
  // face of the outer wall turned over onto the inner one, two edges folded, the third on a
  // crease): moving its own vertices back among its neighbours undoes it and leaves the other
  // layer where it is (at t/R 0.02, 1500 vertices, seed 2, where the walls interleave, the
  // smoothing of both layers' neighbourhoods lost consistency; this does not).
  const MoveTest fewer_folds_apart = [&](const std::vector<VertexHandle>& vs) -> std::function<bool()> {
    const std::optional<size_t> before = folds_around(mesh, vs);
    return [&mesh, &apart, vs, before] {
      const std::optional<size_t> now = folds_around(mesh, vs);
      return before && now && *now < *before && apart();
    };
  };
  for (FaceHandle t : {f, g}) {
    const Vec3 nt = detail::unit_normal(detail::face_points(mesh, t));
    size_t folded = 0;
    for (FaceHandle k : mesh.ff_range(t)) folded += OpenMesh::dot(nt, detail::unit_normal(detail::face_points(mesh, k))) < 0;
    if (folded >= 2 && straighten_face(mesh, t, fewer_folds_apart)) return true;
  }
  const std::vector<VertexHandle> vs = interior_vertices_around(mesh, {f, g});
  if (vs.empty()) return false;
  const std::optional<size_t> before = folds_around(mesh, vs);
  if (!before) return false;
  // A face turned against the pair right behind its lower face, closer than the gap between the
  // two: the stacked faces are the walls of a shell thinner than the mesh resolves, interleaved
  // (+ - + -), not a fold of one wall; smoothing would merge the walls. Left alone.
  const FaceGeometry gf = face_geometry(mesh, f), gg = face_geometry(mesh, g);
  const Vec3 m = (gf.normal + gg.normal).normalized();
  const double gap = OpenMesh::dot(gg.centre - gf.centre, m);
  const FaceHandle low = gap > 0 ? f : g;
  const Vec3 from = gap > 0 ? gf.centre : gg.centre;
  const Vec3 to = from - std::abs(gap) * m;
  const double reach2 = std::pow(std::abs(gap) + std::max(gf.longest, gg.longest), 2);
  for (FaceHandle h : mesh.faces()) {
    if (h == low || (mesh.calc_face_centroid(h) - from).sqrnorm() > reach2) continue;
    const auto p = detail::face_points(mesh, h);
    if (OpenMesh::dot(detail::unit_normal(p), m) < 0 && detail::segment_crosses(from, to, p, 1e-9 * std::abs(gap))) return false;
  }
  return smooth_until(mesh, vs, 3, [&] {
    const std::optional<size_t> now = folds_around(mesh, vs);
    return now && *now <= *before && apart();
  });
}

}  // namespace

StackedLayerReport remove_stacked_layers(Mesh& mesh, const StackedLayerOptions& options) {
  detail::check_mesh(mesh, "twist::remove_stacked_layers");
  if (options.rounds < 1 || options.rounds > 16) throw InvalidInput("twist::remove_stacked_layers: option rounds must lie in [1, 16]");
  if (options.max_group_faces < 1 || options.max_group_faces > 1000) {
    throw InvalidInput("twist::remove_stacked_layers: option max_group_faces must lie in [1, 1000]");
  }
  if (options.min_component_faces < 1) throw InvalidInput("twist::remove_stacked_layers: option min_component_faces must be >= 1");
  DetectOptions d = options.detect;
  d.reference = nullptr;
  d.restrict_to.reset();
  d.face_grid = nullptr;
  d.mean_edge_length = 0;
  validate_detect_options(mesh, d);
  StackedLayerReport report;
  auto has_border = [&] {
    for (HalfedgeHandle h : mesh.halfedges()) {
      if (mesh.is_boundary(h)) return true;
    }
    return false;
  };
  if (!has_border()) return report;  // nothing a removal could take (and no scan)
  for (int round = 0;; ++round) {
    const auto pairs = mesh.faces().begin() == mesh.faces().end()
                           ? std::vector<std::pair<FaceHandle, FaceHandle>>{}
                           : same_orientation_pairs(mesh, d, LayerRule::Stacked);
    if (round == 0) report.pairs_before = pairs.size();
    report.pairs_after = pairs.size();
    if (pairs.empty() || round == options.rounds) break;
    std::unordered_set<int> stacked;
    for (const auto& [f, g] : pairs) {
      stacked.insert(f.idx());
      stacked.insert(g.idx());
    }
    // Is the edge-connected group of stacked faces around f small? (explored with a budget)
    std::unordered_map<int, bool> small;
    auto in_small_group = [&](FaceHandle f) {
      const auto it = small.find(f.idx());
      if (it != small.end()) return it->second;
      std::vector<FaceHandle> group{f};
      std::unordered_set<int> seen{f.idx()};
      for (size_t q = 0; q < group.size() && group.size() <= options.max_group_faces; ++q) {
        for (FaceHandle g : mesh.ff_range(group[q])) {
          if (stacked.count(g.idx()) && seen.insert(g.idx()).second) group.push_back(g);
        }
      }
      const bool is_small = group.size() <= options.max_group_faces;
      if (is_small) {
        for (FaceHandle g : group) small.emplace(g.idx(), true);
      }
      return small.emplace(f.idx(), is_small).first->second;
    };
    // (border edges, border vertices) of a face; (0, 0) away from the border.
    auto border_rank = [&](FaceHandle f) {
      int edges = 0, vertices = 0;
      for (HalfedgeHandle h : mesh.fh_range(f)) edges += mesh.is_boundary(mesh.opposite_halfedge_handle(h));
      for (VertexHandle v : mesh.fv_range(f)) vertices += mesh.is_boundary(v);
      return std::pair<int, int>(edges, vertices);
    };
    std::vector<FaceHandle> doomed;
    std::vector<std::pair<FaceHandle, FaceHandle>> pleats;
    for (const auto& [f, g] : pairs) {
      if (border_rank(f).second == 0 && border_rank(g).second == 0) {
        if (in_small_group(f) && in_small_group(g)) pleats.emplace_back(f, g);
        continue;
      }
      FaceHandle victim;
      std::pair<int, int> best(0, 0);
      double best_area = 0;
      for (FaceHandle x : {f, g}) {
        const std::pair<int, int> rank = border_rank(x);
        if (rank.second == 0 || !in_small_group(x)) continue;
        const double a = mesh.calc_face_area(x);
        if (!victim.is_valid() || rank > best || (rank == best && (a < best_area || (a == best_area && x.idx() > victim.idx())))) {
          victim = x;
          best = rank;
          best_area = a;
        }
      }
      if (victim.is_valid()) doomed.push_back(victim);
    }
    std::sort(doomed.begin(), doomed.end(), [](FaceHandle a, FaceHandle b) { return a.idx() < b.idx(); });
    doomed.erase(std::unique(doomed.begin(), doomed.end()), doomed.end());
    report.faces_removed += remove_faces(mesh, doomed, options.min_component_faces);
    size_t flattened = 0;
    for (const auto& [f, g] : pleats) flattened += flatten_pleat(mesh, f, g);
    report.pleats_flattened += flattened;
    if (doomed.empty() && flattened == 0) break;
    ++report.rounds;
  }
  return report;
}

}  // namespace twist
