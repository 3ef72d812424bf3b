// The repair's cleanup: tiny pieces, small cut pieces, border flaps, small turned-over patches, and
// the smoothing moves that straighten faces (also used by the stacked layers). detail/repair_steps.h.
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <initializer_list>
#include <optional>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

#include "detail/geometry.h"
#include "detail/repair_steps.h"
#include "edgefront/mesh_stats.h"
#include "twist/repair.h"

namespace twist {

using edgefront::FaceHandle;
using edgefront::HalfedgeHandle;
using edgefront::Mesh;
using edgefront::Vec3;
using edgefront::VertexHandle;

namespace detail {

/// Pieces (edge-connected face sets) touching these vertices that have fewer than `min_faces`
/// faces are deleted: a cut must never leave a tiny component. Each piece is explored with a
/// budget of `min_faces`, so this is local. Returns the number of faces deleted.
size_t remove_tiny_pieces(Mesh& mesh, const std::vector<VertexHandle>& around, size_t min_faces) {
  size_t removed = 0;
  std::unordered_set<int> big;  // faces known to lie in a piece of at least min_faces
  for (VertexHandle v : around) {
    if (!edgefront::is_live(mesh, v)) continue;
    std::vector<FaceHandle> starts(mesh.vf_range(v).begin(), mesh.vf_range(v).end());
    for (FaceHandle start : starts) {
      if (!edgefront::is_live(mesh, start) || big.count(start.idx())) continue;
      std::vector<FaceHandle> piece{start};
      std::unordered_set<int> seen{start.idx()};
      bool is_big = false;
      for (size_t q = 0; q < piece.size() && !is_big; ++q) {
        for (FaceHandle g : mesh.ff_range(piece[q])) {
          if (big.count(g.idx())) is_big = true;
          if (seen.insert(g.idx()).second) piece.push_back(g);
        }
        is_big = is_big || piece.size() >= min_faces;
      }
      if (is_big) {
        for (FaceHandle f : piece) big.insert(f.idx());
        continue;
      }
      for (FaceHandle f : piece) mesh.delete_face(f, true);
      removed += piece.size();
    }
  }
  return removed;
}

/// Removes faces and any tiny piece the removal leaves; vertices where the rest then meets in
/// several fans get one copy per extra fan (so the mesh stays manifold). Returns the number of
/// faces deleted.
size_t remove_faces(Mesh& mesh, const std::vector<FaceHandle>& faces, size_t min_faces) {
  std::vector<VertexHandle> touched;
  size_t removed = 0;
  for (FaceHandle f : faces) {
    if (!edgefront::is_live(mesh, f)) continue;
    for (VertexHandle v : mesh.fv_range(f)) touched.push_back(v);
  }
  for (FaceHandle f : faces) {
    if (edgefront::is_live(mesh, f)) {
      mesh.delete_face(f, true);
      ++removed;
    }
  }
  std::sort(touched.begin(), touched.end(), [](VertexHandle a, VertexHandle b) { return a.idx() < b.idx(); });
  touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
  removed += remove_tiny_pieces(mesh, touched, min_faces);
  for (VertexHandle v : touched) {
    if (edgefront::is_live(mesh, v)) detail::split_fans(mesh, v);
  }
  return removed;
}

/// Components that contain a vertex of a cut (a copy or its original) and have fewer than
/// max(min_component_faces, min_cut_piece_share x the largest component's faces) faces are
/// removed: pieces the cuts separated that are too small to stand as a part of the surface (a
/// sliver of one wall, a fragment lying over another piece). Components without a cut vertex are
/// the input's and stay. Returns the number of faces removed. O(F).
size_t remove_small_cut_pieces(Mesh& mesh, const RepairOptions& o, const DupList& dups, size_t& spared) {
  if (dups.empty()) return 0;
  const edgefront::ComponentLabels labels = edgefront::connected_components(mesh);
  auto label_of = [&](FaceHandle f) { return static_cast<size_t>(labels.vertex_component[(*mesh.fv_begin(f)).idx()]); };
  std::vector<size_t> face_count(labels.count, 0);
  for (FaceHandle f : mesh.faces()) ++face_count[label_of(f)];
  const size_t largest = face_count.empty() ? 0 : *std::max_element(face_count.begin(), face_count.end());
  const double limit = std::max(static_cast<double>(o.cuts.min_component_faces),
                                o.cuts.min_cut_piece_share * static_cast<double>(largest));
  std::vector<char> doomed(labels.count, 0);
  for (const auto& [copy, original] : dups) {
    for (VertexHandle v : {copy, original}) {
      if (!edgefront::is_live(mesh, v) || mesh.is_isolated(v)) continue;
      const size_t c = static_cast<size_t>(labels.vertex_component[v.idx()]);
      doomed[c] = static_cast<double>(face_count[c]) < limit && face_count[c] != largest;
    }
  }
  // A piece holding a face that alone covers a reference point stays whole (support_radius).
  std::vector<FaceHandle> candidates;
  for (FaceHandle f : mesh.faces()) {
    if (doomed[label_of(f)]) candidates.push_back(f);
  }
  size_t kept_faces = 0;
  const std::vector<FaceHandle> go = without_sole_cover(mesh, candidates, o, kept_faces);
  if (go.size() != candidates.size()) {
    std::unordered_set<int> going;
    for (FaceHandle f : go) going.insert(f.idx());
    std::vector<char> spare(labels.count, 0);
    for (FaceHandle f : candidates) {
      if (!going.count(f.idx())) spare[label_of(f)] = 1;
    }
    // ... unless the reference rejects a face of it: a piece is kept whole or not at all, and a
    // piece turned the wrong way in part would trade orientation for coverage.
    const double edge = detail::mean_edge_length(mesh);
    for (FaceHandle f : candidates) {
      const size_t c = label_of(f);
      if (!spare[c]) continue;
      const std::array<Vec3, 3> p = detail::face_points(mesh, f);
      const Vec3 n = detail::unit_normal(p);
      if (n.sqrnorm() > 0 && reference_vote(*o.detect.reference, o.detect, detail::centroid(p), n, edge) < 0) spare[c] = 0;
    }
    for (size_t c = 0; c < labels.count; ++c) {
      if (spare[c]) doomed[c] = 0;
    }
  }
  size_t removed = 0;
  for (FaceHandle f : candidates) {
    if (doomed[label_of(f)]) {
      mesh.delete_face(f, true);
      ++removed;
    } else {
      ++spared;
    }
  }
  return removed;
}

/// Removes border flaps (see `RepairExperimentalOptions::peel_flaps`): faces with a vertex on the border
/// that have a same-orientation partner (`same_orientation_pairs`), in up to `peel_flaps`
/// rounds, and the tiny pieces that leaves. Returns the number of faces removed. Pairs are looked
/// for only around the faces that could be flaps (`same_orientation_pairs` with `restrict_to`).
size_t peel_flaps(Mesh& mesh, const RepairOptions& o, const DupList& dups, size_t& spared) {
  size_t removed = 0;
  // With `peel_from_cuts`, only flaps the cuts left: the first round peels faces at a vertex of a cut, each further
  // round faces at a vertex of a face peeled before (a flap of the loop's own border operations
  // is not the repair's business: a run without any cut keeps its mesh as it is).
  std::unordered_set<int> reach;
  for (const auto& [copy, original] : o.experimental.peel_from_cuts ? dups : DupList{}) {
    reach.insert(copy.idx());
    reach.insert(original.idx());
  }
  DetectOptions d = o.detect;
  d.incremental.restrict_to.reset();
  d.incremental.face_grid = nullptr;
  d.mean_edge_length = 0;
  for (int round = 0; round < o.experimental.peel_flaps; ++round) {
    if (mesh.faces().begin() == mesh.faces().end()) break;  // nothing left to judge
    std::vector<FaceHandle> flaps;
    auto on_border = [&](FaceHandle f) {
      bool border = false, reached = false;
      for (VertexHandle v : mesh.fv_range(f)) {
        border = border || mesh.is_boundary(v);
        reached = reached || !o.experimental.peel_from_cuts || reach.count(v.idx()) > 0;
      }
      return border && reached;
    };
    std::vector<FaceHandle> candidates;  // faces that can be flaps
    if (o.experimental.peel_from_cuts) {
      for (int v : reach) {
        if (!edgefront::is_live(mesh, VertexHandle(v))) continue;
        for (FaceHandle f : mesh.vf_range(VertexHandle(v))) {
          if (on_border(f)) candidates.push_back(f);
        }
      }
    } else {
      for (FaceHandle f : mesh.faces()) {
        if (on_border(f)) candidates.push_back(f);
      }
    }
    std::sort(candidates.begin(), candidates.end(), [](FaceHandle a, FaceHandle b) { return a.idx() < b.idx(); });
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
    if (candidates.empty()) break;
    d.incremental.restrict_to = std::move(candidates);
    for (const auto& [f, g] : same_orientation_pairs(mesh, d)) {
      if (on_border(f)) flaps.push_back(f);
      if (on_border(g)) flaps.push_back(g);
    }
    std::sort(flaps.begin(), flaps.end(), [](FaceHandle a, FaceHandle b) { return a.idx() < b.idx(); });
    flaps.erase(std::unique(flaps.begin(), flaps.end()), flaps.end());
    flaps = without_sole_cover(mesh, flaps, o, spared);
    if (flaps.empty()) break;
    for (FaceHandle f : flaps) {
      for (VertexHandle v : mesh.fv_range(f)) reach.insert(v.idx());
    }
    removed += remove_faces(mesh, flaps, o.cuts.min_component_faces);
  }
  return removed;
}

/// Moves the vertices `vs` to the centroids of their neighbours, all at once, up to `rounds`
/// times, until `accept()` holds after a round; else puts them back. Returns whether accepted.
bool smooth_until(Mesh& mesh, const std::vector<VertexHandle>& vs, int rounds, const std::function<bool()>& accept) {
  std::vector<Vec3> old, target(vs.size());
  for (VertexHandle v : vs) old.push_back(mesh.point(v));
  for (int round = 0; round < rounds; ++round) {
    for (size_t i = 0; i < vs.size(); ++i) {
      Vec3 sum(0, 0, 0);
      size_t k = 0;
      for (VertexHandle w : mesh.vv_range(vs[i])) {
        sum += mesh.point(w);
        ++k;
      }
      target[i] = k > 0 ? sum / static_cast<double>(k) : mesh.point(vs[i]);
    }
    for (size_t i = 0; i < vs.size(); ++i) mesh.set_point(vs[i], target[i]);
    if (accept()) return true;
  }
  for (size_t i = 0; i < vs.size(); ++i) mesh.set_point(vs[i], old[i]);
  return false;
}

/// Folded edges around the vertices `vs` (n.n < 0 across an edge of a face around them, each
/// counted from both sides), or none when a face there is degenerate.
std::optional<size_t> folds_around(const Mesh& mesh, const std::vector<VertexHandle>& vs) {
  size_t n = 0;
  for (VertexHandle v : vs) {
    for (FaceHandle h : mesh.vf_range(v)) {
      const Vec3 nh = detail::unit_normal(detail::face_points(mesh, h));
      if (nh.sqrnorm() == 0) return std::nullopt;
      for (FaceHandle k : mesh.ff_range(h)) n += OpenMesh::dot(nh, detail::unit_normal(detail::face_points(mesh, k))) < 0;
    }
  }
  return n;
}

/// The vertices of `faces` and their neighbours that are not on the border, by index, once each.
std::vector<VertexHandle> interior_vertices_around(const Mesh& mesh, std::initializer_list<FaceHandle> faces) {
  std::vector<VertexHandle> vs;
  for (FaceHandle x : faces) {
    for (VertexHandle v : mesh.fv_range(x)) {
      vs.push_back(v);
      for (VertexHandle w : mesh.vv_range(v)) vs.push_back(w);
    }
  }
  std::sort(vs.begin(), vs.end(), [](VertexHandle a, VertexHandle b) { return a.idx() < b.idx(); });
  vs.erase(std::unique(vs.begin(), vs.end()), vs.end());
  vs.erase(std::remove_if(vs.begin(), vs.end(), [&](VertexHandle v) { return mesh.is_boundary(v); }), vs.end());
  return vs;
}

/// Straightens turned face f by smoothing (`smooth_until`): one of its interior vertices (tried
/// in circulation order, one round), or else (a tangle: its neighbours are displaced too) its
/// interior vertices and their interior neighbours together (up to 3 rounds), each kept only when
/// `test` (built for the vertices moved) accepts. Returns whether one was kept.
bool straighten_face(Mesh& mesh, FaceHandle f, const MoveTest& test) {
  std::vector<VertexHandle> own(mesh.fv_range(f).begin(), mesh.fv_range(f).end());
  for (VertexHandle v : own) {
    if (mesh.is_boundary(v)) continue;
    const std::vector<VertexHandle> vs{v};
    if (smooth_until(mesh, vs, 1, test(vs))) return true;
  }
  const std::vector<VertexHandle> around = interior_vertices_around(mesh, {f});
  return smooth_until(mesh, around, 3, test(around));
}

/// Removes or collapses small turned-over patches (see `RepairExperimentalOptions::drop_turned_patches`).
/// Runs after the global orientation (the reference verdicts are those of the final sides).
/// Pairs are looked for only around the faces the reference rejects (`same_orientation_pairs`
/// with `restrict_to`): the reference's verdict costs a nearest-point query, a pair test a
/// bounded front.
void drop_turned_patches(Mesh& mesh, const RepairOptions& o, RepairReport& report) {
  if (!o.detect.reference || o.experimental.drop_turned_patches == 0 ||
      mesh.faces().begin() == mesh.faces().end())
    return;
  DetectOptions d = o.detect;
  d.incremental.restrict_to.reset();
  d.incremental.face_grid = nullptr;
  d.mean_edge_length = 0;
  const double edge = detail::mean_edge_length(mesh);
  // The reference's verdict on a triangle: rejected (thin-wall rule on).
  auto rejects = [&](const std::array<Vec3, 3>& p) {
    const Vec3 n = detail::unit_normal(p);
    const Vec3 c = detail::centroid(p);
    int vote = n.sqrnorm() > 0 ? reference_vote(*o.detect.reference, o.detect, c, n, edge) : 1;
    // A face the nearest normal leaves undecided (at a crease or rim its nearest point may lie on
    // the other wall meeting there, at a right angle) is judged by sides (its own wall), unless
    // the wall is thinner than the thin-wall rule allows.
    if (vote == 0 && o.detect.experimental.reference_side_weight == 0 &&
        std::abs(OpenMesh::dot(n, o.detect.reference->nearest_normal(c))) < -o.detect.vote.reference_cos &&
        !(o.detect.reference->wall_thickness(c) < o.detect.vote.thin_wall * edge)) {
      vote = o.detect.reference->judge(c, n);
    }
    return vote < 0;
  };
  std::unordered_map<int, bool> verdict;  // face -> rejected (cached per face)
  auto rejected = [&](FaceHandle f) {
    const auto it = verdict.find(f.idx());
    if (it != verdict.end()) return it->second;
    const bool r = rejects(detail::face_points(mesh, f));
    verdict.emplace(f.idx(), r);
    return r;
  };
  std::vector<FaceHandle> rejected_faces;
  for (FaceHandle f : mesh.faces()) {
    if (rejected(f)) rejected_faces.push_back(f);
  }
  if (rejected_faces.empty()) return;
  d.incremental.restrict_to = std::move(rejected_faces);
  std::vector<FaceHandle> seeds;
  for (const auto& [f, g] : same_orientation_pairs(mesh, d)) {
    if (rejected(f)) seeds.push_back(f);
    if (rejected(g)) seeds.push_back(g);
  }
  std::sort(seeds.begin(), seeds.end(), [](FaceHandle a, FaceHandle b) { return a.idx() < b.idx(); });
  seeds.erase(std::unique(seeds.begin(), seeds.end()), seeds.end());
  std::unordered_set<int> grouped;
  std::vector<std::vector<FaceHandle>> groups;
  for (FaceHandle s : seeds) {
    if (grouped.count(s.idx())) continue;
    // The edge-connected group of rejected faces around s, explored with a budget of one more
    // face than the limit (a bigger group is left to the detector).
    std::vector<FaceHandle> group{s};
    grouped.insert(s.idx());
    for (size_t q = 0; q < group.size() && group.size() <= o.experimental.drop_turned_patches; ++q) {
      for (FaceHandle g : mesh.ff_range(group[q])) {
        if (!grouped.count(g.idx()) && rejected(g)) {
          grouped.insert(g.idx());
          group.push_back(g);
        }
      }
    }
    if (group.size() <= o.experimental.drop_turned_patches) groups.push_back(std::move(group));
  }
  // Straightening turned face f (`straighten_face`) is kept when f is then right, no face around
  // the moved vertices is degenerate and fewer of them are rejected than before (near a rim
  // corner some bevelled faces around may stay rejected); their cached verdicts are then dropped.
  auto right_with_fewer_rejected = [&](FaceHandle f) -> MoveTest {
    return [&, f](const std::vector<VertexHandle>& vs) -> std::function<bool()> {
      size_t before = 0;
      for (VertexHandle v : vs) {
        for (FaceHandle g : mesh.vf_range(v)) before += rejects(detail::face_points(mesh, g));
      }
      return [&, f, vs, before] {
        bool ok = true;
        size_t now = 0;
        for (VertexHandle v : vs) {
          for (FaceHandle g : mesh.vf_range(v)) {
            const auto p = detail::face_points(mesh, g);
            ok = ok && detail::unit_normal(p).sqrnorm() > 0;
            now += rejects(p);
          }
        }
        const bool done = ok && now < before && !rejects(detail::face_points(mesh, f));
        if (done) {
          for (VertexHandle v : vs) {
            for (FaceHandle g : mesh.vf_range(v)) verdict.erase(g.idx());
          }
        }
        return done;
      };
    };
  };
  // A turned face with an edge shorter than half a mean edge is a sliver (inverted by the
  // smoothing among right neighbours, or bevelled over a rim): collapsing that edge removes it
  // and keeps the surface around it closed. Otherwise, a turned face that moving one of its
  // interior vertices to the centroid of its neighbours straightens is straightened. A turned
  // face on the border that is neither is removed (a flap turned over at a rim); an interior
  // one is left (a hole would be worse).
  std::vector<FaceHandle> flaps;
  for (const auto& group : groups) {
    for (FaceHandle f : group) {
      if (!edgefront::is_live(mesh, f)) continue;
      HalfedgeHandle best;
      double best_length = 0.5 * edge;
      for (HalfedgeHandle h : mesh.fh_range(f)) {
        for (HalfedgeHandle c : {h, mesh.opposite_halfedge_handle(h)}) {
          const double length = mesh.calc_edge_length(c);
          if (length <= best_length && mesh.is_collapse_ok(c)) {
            best = c;
            best_length = length;
          }
        }
      }
      if (best.is_valid()) {
        mesh.collapse(best);
        ++report.turned_faces_collapsed;
        continue;
      }
      if (!rejected(f)) continue;  // straightened with a neighbour of its patch
      const bool straightened = straighten_face(mesh, f, right_with_fewer_rejected(f));
      if (straightened) {
        ++report.turned_faces_straightened;
        continue;
      }
      bool border = false;
      for (VertexHandle v : mesh.fv_range(f)) border = border || mesh.is_boundary(v);
      if (border) flaps.push_back(f);
    }
  }
  const size_t removed = remove_faces(mesh, without_sole_cover(mesh, flaps, o, report.supported_faces_spared),
                                      o.cuts.min_component_faces);
  report.turned_faces_removed += removed;
  report.faces_removed += removed;
}

}  // namespace detail
}  // namespace twist
