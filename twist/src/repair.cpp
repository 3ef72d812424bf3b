#include "twist/repair.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <functional>
#include <initializer_list>
#include <iterator>
#include <limits>
#include <map>
#include <numbers>
#include <numeric>
#include <optional>
#include <string>
#include <unordered_map>
#include <unordered_set>

#include "detail/geometry.h"
#include "edgefront/error.h"
#include "edgefront/mesh_stats.h"
#include "edgefront/union_find.h"

namespace twist {

using edgefront::EdgeHandle;
using edgefront::FaceHandle;
using edgefront::HalfedgeHandle;
using edgefront::InvalidInput;
using edgefront::Mesh;
using edgefront::Vec3;
using edgefront::VertexHandle;

namespace {

using DupList = std::vector<std::pair<VertexHandle, VertexHandle>>;
/// Decides, for a region about to be repaired, whether it is cut out instead (re-twist guard).
using CutOutRule = std::function<bool(const Mesh&, const TwistRegion&)>;

using edgefront::UnionFind;

bool region_is_live(const Mesh& mesh, const TwistRegion& r) {
  for (FaceHandle f : r.faces) {
    if (!edgefront::is_live(mesh, f)) return false;
  }
  for (const auto& loop : r.border) {
    for (HalfedgeHandle h : loop) {
      if (!edgefront::is_live(mesh, h)) return false;
    }
  }
  return true;
}

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

/// Replaces the faces of `region` by one fan per border loop (a new vertex at the loop's mean
/// position joined to every loop edge), wound like the faces outside: the region is cut out and
/// re-grown as a patch consistent with its surroundings, which the refinement loop then fits to
/// the samples, instead of leaving a hole. Loops entirely on the mesh border stay border; loops
/// that are not simple (a vertex twice, or in two loops) or have fewer than 3 edges make the
/// whole region fall back to plain removal (a hole). Returns the number of fan faces added.
size_t regrow_region(Mesh& mesh, const TwistRegion& region, size_t min_faces) {
  // The loops, split at repeated vertices into simple cycles (a region touching itself at a
  // vertex has a loop through it twice; each cycle gets its own fan, which fills one wedge).
  std::vector<std::vector<HalfedgeHandle>> cycles;
  for (size_t i = 0; i < region.border.size(); ++i) {
    if (region.border_on_mesh_border[i]) continue;
    std::vector<HalfedgeHandle> path;
    std::unordered_map<int, size_t> pos;  // from-vertex -> index in path
    for (HalfedgeHandle h : region.border[i]) {
      const int v = mesh.from_vertex_handle(h).idx();
      const auto it = pos.find(v);
      if (it != pos.end()) {
        const size_t start = it->second;
        cycles.emplace_back(path.begin() + static_cast<std::ptrdiff_t>(start), path.end());
        for (size_t k = start; k < path.size(); ++k) pos.erase(mesh.from_vertex_handle(path[k]).idx());
        path.resize(start);
      }
      pos[v] = path.size();
      path.push_back(h);
    }
    if (!path.empty()) cycles.push_back(std::move(path));
  }
  if (cycles.empty()) {
    remove_faces(mesh, region.faces, min_faces);
    return 0;
  }
  std::vector<VertexHandle> region_vertices;
  for (FaceHandle f : region.faces) {
    for (VertexHandle v : mesh.fv_range(f)) region_vertices.push_back(v);
  }
  std::unordered_set<int> had_face;  // loop halfedges with a face outside the region
  std::vector<VertexHandle> loop_vertices;
  for (const auto& cycle : cycles) {
    for (HalfedgeHandle h : cycle) {
      if (mesh.face_handle(h).is_valid()) had_face.insert(h.idx());
      loop_vertices.push_back(mesh.from_vertex_handle(h));
    }
  }
  for (FaceHandle f : region.faces) {
    if (edgefront::is_live(mesh, f)) mesh.delete_face(f, false);
  }
  // Tiny pieces left outside a loop (an island the region enclosed) go too, and their loop is
  // not closed: a fan over them would make a tiny closed component.
  remove_tiny_pieces(mesh, loop_vertices, min_faces);
  size_t added = 0;
  for (const auto& cycle : cycles) {
    bool outside_left = cycle.size() >= 3;
    for (HalfedgeHandle h : cycle) {
      if (had_face.count(h.idx())) outside_left = outside_left && edgefront::is_live(mesh, h) && mesh.face_handle(h).is_valid();
      outside_left = outside_left && edgefront::is_live(mesh, mesh.from_vertex_handle(h));
    }
    if (!outside_left) continue;  // left as a hole
    std::vector<std::array<VertexHandle, 2>> edges;  // hole edges, wound like the faces outside
    Vec3 centre(0, 0, 0);
    for (HalfedgeHandle h : cycle) {
      edges.push_back({mesh.to_vertex_handle(h), mesh.from_vertex_handle(h)});
      centre += mesh.point(mesh.from_vertex_handle(h));
    }
    centre /= static_cast<double>(cycle.size());
    std::vector<FaceHandle> fan;
    bool refused = false;
    if (edges.size() == 3) {
      const FaceHandle f = mesh.add_face(edges[0][0], edges[2][0], edges[1][0]);
      refused = !f.is_valid();
      if (!refused) fan.push_back(f);
    } else {
      const VertexHandle c = mesh.add_vertex(centre);
      for (const auto& e : edges) {
        const FaceHandle f = mesh.add_face(e[0], e[1], c);
        if (!f.is_valid()) {
          refused = true;
          break;
        }
        fan.push_back(f);
      }
      if (refused || fan.empty()) {
        for (FaceHandle f : fan) mesh.delete_face(f, false);
        if (!mesh.status(c).deleted()) mesh.delete_vertex(c, false);
        fan.clear();
      }
    }
    for (FaceHandle f : fan) mesh.set_normal(f, mesh.calc_face_normal(f));
    added += fan.size();
  }
  // Interior vertices of the region are left without faces now; holes left may meet at a vertex.
  for (VertexHandle v : region_vertices) {
    if (!mesh.status(v).deleted() && mesh.is_isolated(v)) mesh.delete_vertex(v, false);
  }
  for (VertexHandle v : loop_vertices) {
    if (edgefront::is_live(mesh, v)) detail::split_fans(mesh, v);
  }
  return added;
}

/// Cuts `region` off along its border, grows two fronts alternately from both sides of the cut,
/// and flips (or removes, when tiny) the side exhausted first.
RepairRecord repair_region(Mesh& mesh, const TwistRegion& region, const RepairOptions& o, DupList& dups) {
  RepairRecord rec;
  rec.region_faces = region.faces.size();
  std::unordered_set<int> in_region;
  in_region.reserve(region.faces.size() * 2);
  for (FaceHandle f : region.faces) in_region.insert(f.idx());

  std::unordered_set<int> cut_edge;
  std::vector<FaceHandle> seeds_in, seeds_out;
  for (size_t i = 0; i < region.border.size(); ++i) {
    if (region.border_on_mesh_border[i]) continue;
    for (HalfedgeHandle h : region.border[i]) {
      if (mesh.is_boundary(mesh.edge_handle(h))) continue;
      if (!cut_edge.insert(mesh.edge_handle(h).idx()).second) continue;
      const FaceHandle ahead = mesh.face_handle(h);
      const FaceHandle behind = mesh.opposite_face_handle(h);
      if (behind.is_valid() && in_region.count(behind.idx())) seeds_in.push_back(behind);
      if (ahead.is_valid() && !in_region.count(ahead.idx())) seeds_out.push_back(ahead);
    }
  }
  rec.cut_edges = cut_edge.size();
  EF_CHECK(!seeds_in.empty() && !seeds_out.empty(), "twist region border without faces on both sides");

  struct Side {
    std::deque<FaceHandle> queue;
    std::unordered_set<int> visited;
    std::vector<FaceHandle> order;
    bool inside = false;
  };
  Side a, b;
  a.inside = true;
  auto seed = [](Side& s, const std::vector<FaceHandle>& fs) {
    for (FaceHandle f : fs) {
      if (s.visited.insert(f.idx()).second) s.queue.push_back(f);
    }
  };
  seed(a, seeds_in);
  seed(b, seeds_out);
  auto step = [&](Side& s) {
    const FaceHandle f = s.queue.front();
    s.queue.pop_front();
    s.order.push_back(f);
    for (HalfedgeHandle h : mesh.fh_range(f)) {
      if (cut_edge.count(mesh.edge_handle(h).idx())) continue;
      const FaceHandle g = mesh.opposite_face_handle(h);
      if (!g.is_valid() || (in_region.count(g.idx()) > 0) != s.inside) continue;
      if (s.visited.insert(g.idx()).second) s.queue.push_back(g);
    }
  };
  Side* exhausted = nullptr;
  // Take turns; a side is exhausted when its queue is empty on its turn or right after the other
  // side's step, so the fronts never expand more than twice the exhausted side.
  while (!exhausted) {
    if (a.queue.empty()) {
      exhausted = &a;
    } else if (b.queue.empty()) {
      exhausted = &b;
    } else {
      step(a);
      if (b.queue.empty()) {
        exhausted = &b;
      } else if (!a.queue.empty()) {
        step(b);
      }
    }
  }
  // An exhausted side has no queue left, so every face it visited is in `order`.
  Side& other = exhausted == &a ? b : a;
  rec.flipped_region = exhausted == &a;
  rec.other_side_faces = other.order.size();
  rec.faces_visited = a.order.size() + b.order.size();
  if (exhausted->order.size() < o.min_component_faces) {
    if (exhausted == &a && o.regrow_cut_outs) {
      regrow_region(mesh, region, o.min_component_faces);
    } else {
      remove_faces(mesh, exhausted->order, o.min_component_faces);
    }
    rec.removed = true;
    return rec;
  }
  const size_t before = dups.size();
  detail::cut_and_reverse(mesh, exhausted->order, true, &dups);
  rec.vertices_duplicated = dups.size() - before;
  rec.flipped_faces = exhausted->order.size();
  // The cut may also split the other side: pieces of it that hung on the region only by a few
  // edges are now on their own. Tiny ones go (never leave a tiny component); local: each piece
  // at the cut is explored with a budget of min_component_faces.
  std::vector<VertexHandle> at_cut;
  for (size_t i = before; i < dups.size(); ++i) {
    at_cut.push_back(dups[i].first);
    at_cut.push_back(dups[i].second);
  }
  rec.tiny_faces_removed = remove_tiny_pieces(mesh, at_cut, o.min_component_faces);
  return rec;
}

/// Components that contain a vertex of a cut (a copy or its original) and have fewer than
/// max(min_component_faces, min_cut_piece_share x the largest component's faces) faces are
/// removed: pieces the cuts separated that are too small to stand as a part of the surface (a
/// sliver of one wall, a fragment lying over another piece). Components without a cut vertex are
/// the input's and stay. Returns the number of faces removed. O(F).
size_t remove_small_cut_pieces(Mesh& mesh, const RepairOptions& o, const DupList& dups) {
  if (dups.empty()) return 0;
  const edgefront::ComponentLabels labels = edgefront::connected_components(mesh);
  auto label_of = [&](FaceHandle f) { return static_cast<size_t>(labels.vertex_component[(*mesh.fv_begin(f)).idx()]); };
  std::vector<size_t> face_count(labels.count, 0);
  for (FaceHandle f : mesh.faces()) ++face_count[label_of(f)];
  const size_t largest = face_count.empty() ? 0 : *std::max_element(face_count.begin(), face_count.end());
  const double limit = std::max(static_cast<double>(o.min_component_faces), o.min_cut_piece_share * static_cast<double>(largest));
  std::vector<char> doomed(labels.count, 0);
  for (const auto& [copy, original] : dups) {
    for (VertexHandle v : {copy, original}) {
      if (!edgefront::is_live(mesh, v) || mesh.is_isolated(v)) continue;
      const size_t c = static_cast<size_t>(labels.vertex_component[v.idx()]);
      doomed[c] = static_cast<double>(face_count[c]) < limit && face_count[c] != largest;
    }
  }
  size_t removed = 0;
  for (FaceHandle f : mesh.faces()) {
    if (!doomed[label_of(f)]) continue;
    mesh.delete_face(f, true);
    ++removed;
  }
  return removed;
}

/// Removes border flaps (see `RepairOptions::peel_flaps`): faces with a vertex on the border
/// that have a same-orientation partner (`same_orientation_pairs`), in up to `peel_flaps`
/// rounds, and the tiny pieces that leaves. Returns the number of faces removed. Pairs are looked
/// for only around the faces that could be flaps (`same_orientation_pairs` with `restrict_to`).
size_t peel_flaps(Mesh& mesh, const RepairOptions& o, const DupList& dups) {
  size_t removed = 0;
  // With `peel_from_cuts`, only flaps the cuts left: the first round peels faces at a vertex of a cut, each further
  // round faces at a vertex of a face peeled before (a flap of the loop's own border operations
  // is not the repair's business: a run without any cut keeps its mesh as it is).
  std::unordered_set<int> reach;
  for (const auto& [copy, original] : o.peel_from_cuts ? dups : DupList{}) {
    reach.insert(copy.idx());
    reach.insert(original.idx());
  }
  DetectOptions d = o.detect;
  d.restrict_to.reset();
  d.face_grid = nullptr;
  d.mean_edge_length = 0;
  for (int round = 0; round < o.peel_flaps; ++round) {
    if (mesh.faces().begin() == mesh.faces().end()) break;  // nothing left to judge
    std::vector<FaceHandle> flaps;
    auto on_border = [&](FaceHandle f) {
      bool border = false, reached = false;
      for (VertexHandle v : mesh.fv_range(f)) {
        border = border || mesh.is_boundary(v);
        reached = reached || !o.peel_from_cuts || reach.count(v.idx()) > 0;
      }
      return border && reached;
    };
    std::vector<FaceHandle> candidates;  // faces that can be flaps
    if (o.peel_from_cuts) {
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
    d.restrict_to = std::move(candidates);
    for (const auto& [f, g] : same_orientation_pairs(mesh, d)) {
      if (on_border(f)) flaps.push_back(f);
      if (on_border(g)) flaps.push_back(g);
    }
    std::sort(flaps.begin(), flaps.end(), [](FaceHandle a, FaceHandle b) { return a.idx() < b.idx(); });
    flaps.erase(std::unique(flaps.begin(), flaps.end()), flaps.end());
    if (flaps.empty()) break;
    for (FaceHandle f : flaps) {
      for (VertexHandle v : mesh.fv_range(f)) reach.insert(v.idx());
    }
    removed += remove_faces(mesh, flaps, o.min_component_faces);
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

/// Builds, for the vertices about to be moved, the test `smooth_until` applies after a round
/// (it may note what it needs before the move).
using MoveTest = std::function<std::function<bool()>(const std::vector<VertexHandle>&)>;

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

/// Removes or collapses small turned-over patches (see `RepairOptions::drop_turned_patches`).
/// Runs after the global orientation (the reference verdicts are those of the final sides).
/// Pairs are looked for only around the faces the reference rejects (`same_orientation_pairs`
/// with `restrict_to`): the reference's verdict costs a nearest-point query, a pair test a
/// bounded front.
void drop_turned_patches(Mesh& mesh, const RepairOptions& o, RepairReport& report) {
  if (!o.detect.reference || o.drop_turned_patches == 0 || mesh.faces().begin() == mesh.faces().end()) return;
  DetectOptions d = o.detect;
  d.restrict_to.reset();
  d.face_grid = nullptr;
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
    if (vote == 0 && o.detect.reference_side_weight == 0 &&
        std::abs(OpenMesh::dot(n, o.detect.reference->nearest_normal(c))) < -o.detect.reference_cos &&
        !(o.detect.reference->wall_thickness(c) < o.detect.thin_wall * edge)) {
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
  d.restrict_to = std::move(rejected_faces);
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
    for (size_t q = 0; q < group.size() && group.size() <= o.drop_turned_patches; ++q) {
      for (FaceHandle g : mesh.ff_range(group[q])) {
        if (!grouped.count(g.idx()) && rejected(g)) {
          grouped.insert(g.idx());
          group.push_back(g);
        }
      }
    }
    if (group.size() <= o.drop_turned_patches) groups.push_back(std::move(group));
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
  const size_t removed = remove_faces(mesh, flaps, o.min_component_faces);
  report.turned_faces_removed += removed;
  report.faces_removed += removed;
}

/// The winding number of a closed surface given by its faces around p: the sum of the faces'
/// signed solid angles seen from p over 4 pi (Van Oosterom & Strackee's formula), +-1 inside
/// (the sign of the surface's orientation), 0 outside.
double winding_number(const Mesh& mesh, const std::vector<FaceHandle>& faces, const Vec3& p) {
  double sum = 0;
  for (FaceHandle f : faces) {
    const auto q = detail::face_points(mesh, f);
    const Vec3 a = q[0] - p, b = q[1] - p, c = q[2] - p;
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    const double num = OpenMesh::dot(a, OpenMesh::cross(b, c));
    const double den = la * lb * lc + OpenMesh::dot(a, b) * lc + OpenMesh::dot(b, c) * la + OpenMesh::dot(c, a) * lb;
    sum += 2 * std::atan2(num, den);
  }
  return sum / (4 * std::numbers::pi);
}

/// For each closed group (key: group root), how many other closed groups enclose it: a group
/// whose bounding box lies in another's and one of whose vertices that other surrounds (winding
/// number above 1/2 in magnitude). O(faces of the enclosing candidates) per group.
std::unordered_map<size_t, int> nesting_depths(const Mesh& mesh,
                                               const std::unordered_map<size_t, std::vector<FaceHandle>>& closed) {
  struct Box {
    Vec3 lo{std::numeric_limits<double>::infinity()}, hi{-std::numeric_limits<double>::infinity()};
    bool inside(const Box& o) const {
      for (int k = 0; k < 3; ++k)
        if (lo[k] < o.lo[k] || hi[k] > o.hi[k]) return false;
      return true;
    }
  };
  std::unordered_map<size_t, Box> box;
  for (const auto& [g, faces] : closed)
    for (FaceHandle f : faces)
      for (const Vec3& q : detail::face_points(mesh, f)) {
        box[g].lo.minimize(q);
        box[g].hi.maximize(q);
      }
  std::unordered_map<size_t, int> depth;
  for (const auto& [g, faces] : closed) {
    const Vec3 p = mesh.point(*mesh.cfv_begin(faces.front()));
    int d = 0;
    for (const auto& [h, other] : closed)
      if (h != g && box[g].inside(box[h]) && std::abs(winding_number(mesh, other, p)) > 0.5) ++d;
    depth[g] = d;
  }
  return depth;
}

/// The global orientation convention (see repair.h).
void orient_globally(Mesh& mesh, const RepairOptions& o, const DupList& dups, RepairReport& report) {
  const size_t nv = mesh.n_vertices();
  // Groups: components before the cuts (vertex copies joined to their originals).
  UnionFind group(nv);
  UnionFind comp(nv);
  for (FaceHandle f : mesh.faces()) {
    auto it = mesh.fv_begin(f);
    const size_t v0 = static_cast<size_t>((*it).idx());
    ++it;
    for (; it.is_valid(); ++it) {
      group.unite(v0, static_cast<size_t>((*it).idx()));
      comp.unite(v0, static_cast<size_t>((*it).idx()));
    }
  }
  std::unordered_set<int> cut_vertex;
  for (const auto& [copy, original] : dups) {
    if (!edgefront::is_live(mesh, copy) || !edgefront::is_live(mesh, original)) continue;
    group.unite(static_cast<size_t>(copy.idx()), static_cast<size_t>(original.idx()));
    cut_vertex.insert(copy.idx());
    cut_vertex.insert(original.idx());
  }
  struct Acc {
    std::vector<FaceHandle> faces;
    double volume = 0, vote = 0;
    size_t group = 0;
  };
  std::unordered_map<size_t, Acc> comps;
  std::unordered_map<size_t, double> group_volume;
  std::unordered_map<size_t, bool> group_open;
  for (FaceHandle f : mesh.faces()) {
    const auto p = detail::face_points(mesh, f);
    const size_t root = comp.find(static_cast<size_t>((*mesh.fv_begin(f)).idx()));
    Acc& acc = comps[root];
    acc.faces.push_back(f);
    acc.group = group.find(root);
    const double vol = OpenMesh::dot(p[0], OpenMesh::cross(p[1], p[2])) / 6.0;
    acc.volume += vol;
    group_volume[acc.group] += vol;
    if (o.detect.reference) {
      const Vec3 n = detail::unit_normal(p);
      acc.vote += detail::area(p) * reference_vote(*o.detect.reference, o.detect, detail::centroid(p), n);
    }
  }
  for (HalfedgeHandle h : mesh.halfedges()) {
    if (!mesh.is_boundary(h)) continue;
    const bool on_cut = cut_vertex.count(mesh.from_vertex_handle(h).idx()) && cut_vertex.count(mesh.to_vertex_handle(h).idx());
    if (!on_cut) group_open[group.find(static_cast<size_t>(mesh.to_vertex_handle(h).idx()))] = true;
  }
  std::vector<size_t> roots;
  for (const auto& [root, acc] : comps) roots.push_back(root);
  std::sort(roots.begin(), roots.end());
  // Without reference normals, how deep each closed group lies inside others: a closed surface
  // inside an odd number of others bounds a cavity (the inner sphere of a hollow ball) and faces
  // into it (negative volume); the others face outward.
  std::unordered_map<size_t, int> depth;
  if (!o.detect.reference) {
    std::unordered_map<size_t, std::vector<FaceHandle>> closed;
    for (size_t root : roots)
      if (!group_open[comps[root].group]) {
        auto& faces = closed[comps[root].group];
        faces.insert(faces.end(), comps[root].faces.begin(), comps[root].faces.end());
      }
    if (closed.size() > 1) depth = nesting_depths(mesh, closed);
  }
  for (size_t root : roots) {
    Acc& acc = comps[root];
    bool flip = false;
    if (o.detect.reference) {
      flip = acc.vote < 0;
    } else if (!group_open[acc.group]) {
      const bool cavity = depth[acc.group] % 2 == 1;
      flip = cavity ? group_volume[acc.group] > 0 : group_volume[acc.group] < 0;
    }
    if (!flip) continue;
    detail::cut_and_reverse(mesh, acc.faces, true, nullptr);
    ++report.components_flipped;
    report.faces_flipped_globally += acc.faces.size();
  }
}

/// True when the faces connected to `region` number at most twice the region's: cutting it out
/// would take at least half of that surface (a repair costs at most half), so it is repaired by
/// flipping instead. Stops counting at that bound: O(region).
bool region_is_most_of_its_component(const Mesh& mesh, const TwistRegion& region) {
  const size_t limit = 2 * region.faces.size();
  std::unordered_set<int> seen{region.faces.front().idx()};
  std::vector<FaceHandle> stack{region.faces.front()};
  while (!stack.empty()) {
    const FaceHandle f = stack.back();
    stack.pop_back();
    for (FaceHandle g : mesh.ff_range(f)) {
      if (!seen.insert(g.idx()).second) continue;
      if (seen.size() > limit) return false;
      stack.push_back(g);
    }
  }
  return true;
}

void validate_repair_options(const RepairOptions& o) {
  if (o.max_repairs < 1) throw InvalidInput("twist::repair: option max_repairs must be >= 1");
  if (o.min_component_faces < 1) throw InvalidInput("twist::repair: option min_component_faces must be >= 1");
  if (!(o.max_border_ratio >= 0) || !std::isfinite(o.max_border_ratio)) {
    throw InvalidInput("twist::repair: option max_border_ratio must be finite and >= 0");
  }
  if (!(o.retest_turn_degrees >= 0 && o.retest_turn_degrees <= 180)) {
    throw InvalidInput("twist::repair: option retest_turn_degrees must lie in [0, 180]");
  }
  if (!(o.min_cut_piece_share >= 0 && o.min_cut_piece_share <= 1)) {
    throw InvalidInput("twist::repair: option min_cut_piece_share must lie in [0, 1]");
  }
  if (o.peel_flaps < 0 || o.peel_flaps > 16) throw InvalidInput("twist::repair: option peel_flaps must lie in [0, 16]");
  if (o.drop_turned_patches > 64) throw InvalidInput("twist::repair: option drop_turned_patches must lie in [0, 64]");
  if (!(o.retest_move >= 0) || !std::isfinite(o.retest_move)) {
    throw InvalidInput("twist::repair: option retest_move must be finite and >= 0");
  }
  if (!(o.cut_cost >= 0 && o.cut_cost <= 100)) throw InvalidInput("twist::repair: option cut_cost must lie in [0, 100]");
}

RepairReport repair_impl(Mesh& mesh, const RepairOptions& o, const CutOutRule& cut_out, DupList& dups,
                         FaceGrid* grid = nullptr) {
  // Incremental (a face grid and a restricted candidate set): nothing here passes over the mesh.
  const bool incremental = grid && o.detect.restrict_to;
  if (!incremental) detail::check_mesh(mesh, "twist::repair");
  validate_repair_options(o);
  RepairReport report;
  // Reversed seams, except those of our own earlier cuts (a flipped side meets its old
  // neighbours with opposite orientation along the cut: that is the repair, not the input).
  std::unordered_set<int> cut_vertices;
  for (const auto& [copy, original] : dups) {
    cut_vertices.insert(copy.idx());
    cut_vertices.insert(original.idx());
  }
  for (HalfedgeHandle h : incremental ? std::vector<HalfedgeHandle>{} : reversed_seams(mesh)) {
    if (cut_vertices.count(mesh.from_vertex_handle(h).idx()) && cut_vertices.count(mesh.to_vertex_handle(h).idx())) continue;
    ++report.seam_edges;
  }
  report.non_orientable = report.seam_edges > 0;

  DetectOptions dopt = o.detect;
  if (grid) dopt.face_grid = grid;
  bool first = true;
  while (report.repairs < o.max_repairs) {
    const size_t faces_before = mesh.n_faces();
    DetectResult dr = detect_regions(mesh, dopt);
    if (first) report.regions_found = dr.regions.size();
    first = false;
    report.detect_stats.faces_tested += dr.stats.faces_tested;
    report.detect_stats.distance_queries += dr.stats.distance_queries;
    report.detect_stats.vertices_settled += dr.stats.vertices_settled;
    report.detect_stats.flagged_faces += dr.stats.flagged_faces;
    bool did_something = false;
    bool stale = false;
    for (const TwistRegion& region : dr.regions) {
      if (report.repairs >= o.max_repairs) {
        report.capped = true;
        break;
      }
      if (!region_is_live(mesh, region)) {
        stale = true;  // an earlier repair of this pass changed it: detect again
        continue;
      }
      bool has_cut = false;
      for (size_t i = 0; i < region.border.size(); ++i) has_cut = has_cut || !region.border_on_mesh_border[i];
      if (!has_cut) continue;  // a whole component: the global orientation decides its side
      if (o.max_border_ratio > 0) {
        // A twist is a compact region behind a short twist line; a region whose border is far
        // longer than a disk's of its size is scattered evidence (noise, or a wall thinner than
        // the faces), and cutting along it would shred the surface.
        size_t border_edges = 0;
        for (size_t i = 0; i < region.border.size(); ++i) {
          if (!region.border_on_mesh_border[i]) border_edges += region.border[i].size();
        }
        if (static_cast<double>(border_edges) > o.max_border_ratio * std::sqrt(static_cast<double>(region.faces.size())) + 16) {
          ++report.regions_scattered;
          continue;
        }
      }
      if (cut_out && !region_is_most_of_its_component(mesh, region) && cut_out(mesh, region)) {
        if (o.regrow_cut_outs) {
          regrow_region(mesh, region, o.min_component_faces);
        } else {
          remove_faces(mesh, region.faces, o.min_component_faces);
        }
        ++report.regions_cut_out;
        report.faces_removed += region.faces.size();
        ++report.repairs;
        did_something = true;
        continue;
      }
      const RepairRecord rec = repair_region(mesh, region, o, dups);
      report.records.push_back(rec);
      ++report.repairs;
      report.faces_flipped += rec.flipped_faces;
      report.faces_visited += rec.faces_visited;
      report.vertices_duplicated += rec.vertices_duplicated;
      report.cut_edges += rec.cut_edges;
      if (rec.removed) report.faces_removed += rec.faces_visited - rec.other_side_faces;
      report.faces_removed += rec.tiny_faces_removed;
      did_something = true;
    }
    if (!stale || !did_something) break;
    if (incremental) {
      // Re-detect on what is left of the candidates and the faces the repairs created.
      grid->update_new(mesh);
      std::vector<FaceHandle> next;
      for (FaceHandle f : *dopt.restrict_to) {
        if (edgefront::is_live(mesh, f)) next.push_back(f);
      }
      for (size_t i = faces_before; i < mesh.n_faces(); ++i) {
        if (edgefront::is_live(mesh, FaceHandle(static_cast<int>(i)))) next.push_back(FaceHandle(static_cast<int>(i)));
      }
      dopt.restrict_to = std::move(next);
    } else {
      // Re-detect on the whole mesh: handles of the restricted set may be gone.
      dopt.restrict_to.reset();
    }
  }
  if (grid) grid->update_new(mesh);
  if (!incremental && o.min_cut_piece_share > 0) report.faces_removed += remove_small_cut_pieces(mesh, o, dups);
  if (!incremental && o.peel_flaps > 0) {
    const size_t peeled = peel_flaps(mesh, o, dups);
    report.flap_faces_removed += peeled;
    report.faces_removed += peeled;
  }
  if (o.global_orientation) orient_globally(mesh, o, dups, report);
  if (!incremental) drop_turned_patches(mesh, o, report);
  if (o.garbage_collect) {
    const size_t before = mesh.n_vertices();
    mesh.garbage_collection();
    if (mesh.n_vertices() != before) dups.clear();  // vertex handles were renumbered
  }
  return report;
}

/// Pieces that meet another piece along a reversed seam (their border halfedges lie on top of
/// each other running the same way: a region turned over by hand, wound the other way in a file,
/// its vertices split from the rest) are flipped so the seams become compatible: per group of
/// pieces joined by such seams, the pieces get two classes (a piece and a piece it meets along a
/// reversed seam are in different classes) and the class with fewer faces is flipped whole. A
/// seam within one piece (a Moebius band cut open) or a group that cannot be split in two classes
/// is left. The seam vertex pairs join `dups` so the global orientation treats the group as one
/// surface. O(F + border halfedges log).
void flip_seam_pieces(Mesh& mesh, DupList& dups, RepairReport& report) {
  const std::vector<std::vector<HalfedgeHandle>> coincident = detail::coincident_border_halfedges(mesh);
  if (coincident.empty()) return;
  const edgefront::ComponentLabels labels = edgefront::connected_components(mesh);
  auto piece = [&](HalfedgeHandle h) { return labels.vertex_component[static_cast<size_t>(mesh.from_vertex_handle(h).idx())]; };
  std::map<std::pair<int, int>, DupList> seams;  // (piece, piece) -> coincident vertex pairs
  std::map<std::pair<int, int>, std::pair<double, size_t>> turn;  // (piece, piece) -> (sum of n.n' across the seam, edges)
  for (const std::vector<HalfedgeHandle>& hs : coincident) {
    for (size_t i = 0; i < hs.size(); ++i)
      for (size_t j = i + 1; j < hs.size(); ++j) {
        const int a = piece(hs[i]), b = piece(hs[j]);
        if (a == b) continue;
        DupList& pairs = seams[{std::min(a, b), std::max(a, b)}];
        pairs.emplace_back(mesh.from_vertex_handle(hs[j]), mesh.from_vertex_handle(hs[i]));
        pairs.emplace_back(mesh.to_vertex_handle(hs[j]), mesh.to_vertex_handle(hs[i]));
        const FaceHandle fa = mesh.opposite_face_handle(hs[i]), fb = mesh.opposite_face_handle(hs[j]);
        auto& t = turn[{std::min(a, b), std::max(a, b)}];
        t.first += OpenMesh::dot(detail::unit_normal(detail::face_points(mesh, fa)), detail::unit_normal(detail::face_points(mesh, fb)));
        ++t.second;
      }
  }
  // Only seams across which the surface runs on smoothly but turned over (the faces on the two
  // sides face opposite ways: n.n' < -0.5 on average) are flipped; a seam across which they face
  // the same way, or fold, is what a twist repair's cut leaves (the layers cross there) and stays.
  for (auto it = seams.begin(); it != seams.end();) {
    const auto& t = turn[it->first];
    it = t.first < -0.5 * static_cast<double>(t.second) ? std::next(it) : seams.erase(it);
  }
  if (seams.empty()) return;
  std::vector<std::vector<int>> adjacent(labels.count);
  for (const auto& entry : seams) {
    adjacent[static_cast<size_t>(entry.first.first)].push_back(entry.first.second);
    adjacent[static_cast<size_t>(entry.first.second)].push_back(entry.first.first);
  }
  std::vector<std::vector<FaceHandle>> faces(labels.count);
  for (FaceHandle f : mesh.faces()) {
    if (!mesh.status(f).deleted()) faces[static_cast<size_t>(labels.vertex_component[static_cast<size_t>((*mesh.fv_begin(f)).idx())])].push_back(f);
  }
  std::vector<int> colour(labels.count, -1);
  std::vector<FaceHandle> flip;
  std::vector<int> resolved;  // pieces of groups that could be split in two classes
  for (size_t start = 0; start < labels.count; ++start) {
    if (colour[start] >= 0 || adjacent[start].empty()) continue;
    std::vector<int> group{static_cast<int>(start)};
    colour[start] = 0;
    bool two_classes = true;
    size_t class_faces[2] = {0, 0};
    for (size_t k = 0; k < group.size(); ++k) {
      const int c = group[k];
      class_faces[colour[static_cast<size_t>(c)]] += faces[static_cast<size_t>(c)].size();
      for (int d : adjacent[static_cast<size_t>(c)]) {
        if (colour[static_cast<size_t>(d)] < 0) {
          colour[static_cast<size_t>(d)] = 1 - colour[static_cast<size_t>(c)];
          group.push_back(d);
        } else if (colour[static_cast<size_t>(d)] == colour[static_cast<size_t>(c)]) {
          two_classes = false;
        }
      }
    }
    if (!two_classes) continue;
    const int flipped = class_faces[1] <= class_faces[0] ? 1 : 0;
    for (int c : group) {
      resolved.push_back(c);
      if (colour[static_cast<size_t>(c)] != flipped) continue;
      flip.insert(flip.end(), faces[static_cast<size_t>(c)].begin(), faces[static_cast<size_t>(c)].end());
      ++report.seam_pieces_flipped;
    }
  }
  std::sort(resolved.begin(), resolved.end());
  for (const auto& entry : seams) {
    if (std::binary_search(resolved.begin(), resolved.end(), entry.first.first)) dups.insert(dups.end(), entry.second.begin(), entry.second.end());
  }
  if (flip.empty()) return;
  report.seam_faces_flipped += flip.size();
  detail::cut_and_reverse(mesh, flip, true, nullptr);
}

/// `repair` with reference normals by labelling (see `RepairOptions::label_by_reference`).
RepairReport label_repair(Mesh& mesh, const RepairOptions& o, DupList& dups) {
  detail::check_mesh(mesh, "twist::repair");
  validate_repair_options(o);
  RepairReport report;
  const ReferenceLabelling labels = label_by_reference(mesh, o);
  report.regions_found = labels.regions.size() + labels.regions_too_small;
  report.detect_stats.faces_tested = labels.faces_voted;
  std::vector<FaceHandle> side;
  for (size_t r = 0; r < labels.regions.size(); ++r) {
    const auto& region = labels.regions[r];
    RepairRecord rec;
    rec.region_faces = region.size();
    rec.cut_edges = labels.cut_edges[r];
    rec.flipped_faces = region.size();
    rec.faces_visited = region.size();
    rec.flipped_region = true;
    // The vertices on the region's cut (each gets a copy per fan of the region around it: one
    // on a simple cut loop).
    std::unordered_set<int> inside, border;
    for (FaceHandle f : region) inside.insert(f.idx());
    for (FaceHandle f : region) {
      for (HalfedgeHandle h : mesh.fh_range(f)) {
        const FaceHandle g = mesh.opposite_face_handle(h);
        if (!g.is_valid() || inside.count(g.idx())) continue;
        border.insert(mesh.from_vertex_handle(h).idx());
        border.insert(mesh.to_vertex_handle(h).idx());
      }
    }
    rec.vertices_duplicated = border.size();
    report.records.push_back(rec);
    report.cut_edges += rec.cut_edges;
    report.faces_flipped += rec.flipped_faces;
    report.faces_visited += rec.faces_visited;
    ++report.repairs;
    side.insert(side.end(), region.begin(), region.end());
  }
  if (!side.empty()) report.vertices_duplicated = detail::cut_and_reverse(mesh, side, true, &dups);
  // Reversed seams left after the flips, except along our own cuts (a flipped side meets its old
  // neighbours with opposite orientation there: that is the repair): the surface meets itself
  // with opposite orientation (a Moebius band; a region the votes left as it was).
  std::unordered_set<int> cut_vertices;
  for (const auto& [copy, original] : dups) {
    cut_vertices.insert(copy.idx());
    cut_vertices.insert(original.idx());
  }
  for (HalfedgeHandle h : reversed_seams(mesh)) {
    if (cut_vertices.count(mesh.from_vertex_handle(h).idx()) && cut_vertices.count(mesh.to_vertex_handle(h).idx())) continue;
    ++report.seam_edges;
  }
  report.non_orientable = report.seam_edges > 0;
  // No piece the cuts separated is removed (min_cut_piece_share does not apply: the labelling
  // never makes a piece under min_component_faces); border flaps only when asked.
  if (o.peel_flaps > 0) {
    const size_t peeled = peel_flaps(mesh, o, dups);
    report.flap_faces_removed += peeled;
    report.faces_removed += peeled;
  }
  if (o.global_orientation) orient_globally(mesh, o, dups, report);
  drop_turned_patches(mesh, o, report);
  if (o.garbage_collect) mesh.garbage_collection();
  return report;
}

}  // namespace

RepairReport repair(Mesh& mesh, const RepairOptions& options) {
  DupList dups;
  RepairReport seams;
  if (options.flip_seam_pieces) {
    detail::check_mesh(mesh, "twist::repair");
    validate_repair_options(options);
    flip_seam_pieces(mesh, dups, seams);
  }
  RepairReport report = options.detect.reference && options.label_by_reference ? label_repair(mesh, options, dups)
                                                                                : repair_impl(mesh, options, nullptr, dups);
  report.seam_pieces_flipped = seams.seam_pieces_flipped;
  report.seam_faces_flipped = seams.seam_faces_flipped;
  return report;
}

RepairReport orient(Mesh& mesh, const RepairOptions& options) {
  detail::check_mesh(mesh, "twist::orient");
  RepairReport report;
  orient_globally(mesh, options, DupList{}, report);
  if (options.garbage_collect) mesh.garbage_collection();
  return report;
}

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

TwistRepairer::TwistRepairer(RepairOptions options, size_t max_retwists)
    : options_(std::move(options)), max_retwists_(max_retwists) {}

std::vector<FaceHandle> TwistRepairer::retest(const Mesh& mesh, const std::vector<FaceHandle>& changed, double mean_edge_length,
                                              std::vector<std::pair<int, Snapshot>>& current) const {
  current.clear();
  const bool all = options_.retest_turn_degrees == 0 && options_.retest_move == 0;
  const double min_cos = std::cos(options_.retest_turn_degrees * std::numbers::pi / 180.0);
  const double max_move2 = std::pow(options_.retest_move * mean_edge_length, 2);
  std::vector<FaceHandle> out;
  for (FaceHandle f : changed) {
    if (!edgefront::is_live(mesh, f)) continue;
    const FaceGeometry g = face_geometry(mesh, f);
    const Snapshot s{g.normal, g.centre, true};
    const size_t k = static_cast<size_t>(f.idx());
    bool test = all || k >= tested_.size() || !tested_[k].valid;
    if (!test) {
      const Snapshot& t = tested_[k];
      const Vec3 moved = s.centre - t.centre;
      const double across = OpenMesh::dot(t.normal, moved);
      test = OpenMesh::dot(t.normal, s.normal) < min_cos || across * across > max_move2 ||
             moved.sqrnorm() > 16 * max_move2;
    }
    if (!test) continue;
    out.push_back(f);
    current.emplace_back(f.idx(), s);
  }
  return out;
}

RepairReport TwistRepairer::repair_changed(Mesh& mesh, const std::vector<FaceHandle>& changed, double mean_edge_length) {
  ++calls_;
  RepairOptions o = options_;
  std::vector<std::pair<int, Snapshot>> snapshots;
  const bool local = mean_edge_length > 0 && std::isfinite(mean_edge_length);
  o.detect.restrict_to = local ? retest(mesh, changed, mean_edge_length, snapshots) : changed;
  if (local) {
    // Local mode: keep the face grid current (a rebuild only when the edge length drifted by 2x).
    o.detect.mean_edge_length = mean_edge_length;
    const double cell = o.detect.radius > 0 ? o.detect.radius : 2.0 * mean_edge_length;
    if (grid_.cell() == 0 || grid_.cell() > 2 * cell || grid_.cell() < cell / 2) {
      grid_.rebuild(mesh, cell);
    } else {
      grid_.update(mesh, changed);
      grid_.update_new(mesh);
    }
  }
  o.detect.audit_offset = calls_ * 7919;  // a different audit sample every call
  o.global_orientation = false;
  auto rule = [this](const Mesh& m, const TwistRegion& region) {
    Vec3 centre(0, 0, 0);
    for (FaceHandle f : region.faces) centre += detail::centroid(detail::face_points(m, f));
    centre /= static_cast<double>(region.faces.size());
    double radius = 0;
    for (FaceHandle f : region.faces) radius = std::max(radius, (detail::centroid(detail::face_points(m, f)) - centre).norm());
    for (Place& p : places_) {
      // The same place: centres within half the larger radius and radii within a factor 2 (a
      // small region near a large earlier one is a different place).
      const double lo = std::min(p.radius, radius), hi = std::max(p.radius, radius);
      if ((p.centre - centre).norm() <= 0.5 * hi && lo >= 0.5 * hi) {
        ++p.count;
        return p.count > max_retwists_;
      }
    }
    places_.push_back(Place{centre, radius, 1});
    return false;
  };
  RepairReport report = repair_impl(mesh, o, rule, cuts_, grid_.cell() > 0 && o.detect.mean_edge_length > 0 ? &grid_ : nullptr);
  // Remember what the tested faces looked like; when the repairs were capped, regions may be
  // left over: everything is tested again next time.
  if (!report.capped) {
    for (const auto& [idx, snap] : snapshots) {
      if (static_cast<size_t>(idx) >= tested_.size()) tested_.resize(static_cast<size_t>(idx) + 1);
      tested_[static_cast<size_t>(idx)] = snap;
    }
  }
  return report;
}

void TwistRepairer::renumber(const Mesh& mesh, const std::vector<int>& vertex_map, const std::vector<int>& face_map) {
  auto mapped = [&](const std::vector<int>& map, size_t old, size_t live_count, const char* what) {
    if (old >= map.size()) {
      throw InvalidInput(std::string("twist::TwistRepairer::renumber: the ") + what + " map has " + std::to_string(map.size()) +
                         " entries, but the repairer holds " + what + " " + std::to_string(old));
    }
    const int to = map[old];
    if (to >= static_cast<int>(live_count)) {
      throw InvalidInput(std::string("twist::TwistRepairer::renumber: ") + what + " " + std::to_string(old) + " maps to " +
                         std::to_string(to) + ", beyond the renumbered mesh");
    }
    return to;
  };
  std::vector<Snapshot> tested;
  for (size_t i = 0; i < tested_.size(); ++i) {
    if (!tested_[i].valid) continue;
    const int to = mapped(face_map, i, mesh.n_faces(), "face");
    if (to < 0) continue;
    if (static_cast<size_t>(to) >= tested.size()) tested.resize(static_cast<size_t>(to) + 1);
    tested[static_cast<size_t>(to)] = tested_[i];
  }
  DupList cuts;
  for (const auto& [copy, original] : cuts_) {
    const int c = mapped(vertex_map, static_cast<size_t>(copy.idx()), mesh.n_vertices(), "vertex");
    const int o = mapped(vertex_map, static_cast<size_t>(original.idx()), mesh.n_vertices(), "vertex");
    if (c >= 0 && o >= 0) cuts.emplace_back(VertexHandle(c), VertexHandle(o));
  }
  tested_ = std::move(tested);
  cuts_ = std::move(cuts);
  if (grid_.cell() > 0) grid_.rebuild(mesh, grid_.cell());
}

RepairReport TwistRepairer::finish(Mesh& mesh) {
  RepairReport r = repair_impl(mesh, options_, nullptr, cuts_);
  grid_ = FaceGrid();  // the final repair may garbage-collect: handles change
  tested_.clear();
  return r;
}

}  // namespace twist
