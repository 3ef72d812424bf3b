// twist::repair: the detect-and-repair loop, cut and flip. The other steps: detail/repair_steps.h.
#include "twist/repair.h"

#include <array>
#include <cmath>
#include <cstddef>
#include <deque>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

#include "detail/geometry.h"
#include "detail/repair_steps.h"
#include "edgefront/error.h"
#include "edgefront/union_find.h"

namespace twist {

using edgefront::FaceHandle;
using edgefront::HalfedgeHandle;
using edgefront::InvalidInput;
using edgefront::Mesh;
using edgefront::Vec3;
using edgefront::VertexHandle;

using detail::CutOutRule;
using detail::drop_turned_patches;
using detail::DupList;
using detail::orient_globally;
using detail::peel_flaps;
using detail::remove_faces;
using detail::remove_small_cut_pieces;
using detail::remove_tiny_pieces;

namespace {

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
  if (exhausted->order.size() < o.cuts.min_component_faces) {
    if (exhausted == &a && o.experimental.regrow_cut_outs) {
      regrow_region(mesh, region, o.cuts.min_component_faces);
    } else {
      remove_faces(mesh, exhausted->order, o.cuts.min_component_faces);
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
  rec.tiny_faces_removed = remove_tiny_pieces(mesh, at_cut, o.cuts.min_component_faces);
  return rec;
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
  if (o.cuts.min_component_faces < 1)
    throw InvalidInput("twist::repair: option cuts.min_component_faces must be >= 1");
  if (!(o.cuts.max_border_ratio >= 0) || !std::isfinite(o.cuts.max_border_ratio)) {
    throw InvalidInput("twist::repair: option cuts.max_border_ratio must be finite and >= 0");
  }
  if (!(o.experimental.retest_turn_degrees >= 0 && o.experimental.retest_turn_degrees <= 180)) {
    throw InvalidInput("twist::repair: option experimental.retest_turn_degrees must lie in [0, 180]");
  }
  if (!(o.cuts.min_cut_piece_share >= 0 && o.cuts.min_cut_piece_share <= 1)) {
    throw InvalidInput("twist::repair: option cuts.min_cut_piece_share must lie in [0, 1]");
  }
  if (o.experimental.peel_flaps < 0 || o.experimental.peel_flaps > 16)
    throw InvalidInput("twist::repair: option experimental.peel_flaps must lie in [0, 16]");
  if (o.mend_patches > 64) throw InvalidInput("twist::repair: option mend_patches must lie in [0, 64]");
  if (o.experimental.drop_turned_patches > 64)
    throw InvalidInput("twist::repair: option experimental.drop_turned_patches must lie in [0, 64]");
  if (!(o.experimental.retest_move >= 0) || !std::isfinite(o.experimental.retest_move)) {
    throw InvalidInput("twist::repair: option experimental.retest_move must be finite and >= 0");
  }
  if (!(o.cuts.cut_cost >= 0 && o.cuts.cut_cost <= 100))
    throw InvalidInput("twist::repair: option cuts.cut_cost must lie in [0, 100]");
  if (!(o.cuts.support_radius >= 0 && o.cuts.support_radius <= 4))
    throw InvalidInput("twist::repair: option cuts.support_radius must lie in [0, 4] (mean edge lengths), got " +
                       std::to_string(o.cuts.support_radius));
}

}  // namespace

namespace detail {

RepairReport repair_impl(Mesh& mesh, const RepairOptions& o, const CutOutRule& cut_out, DupList& dups,
                         FaceGrid* grid) {
  // Incremental (a face grid and a restricted candidate set): nothing here passes over the mesh.
  const bool incremental = grid && o.detect.incremental.restrict_to;
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
  if (grid) dopt.incremental.face_grid = grid;
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
      if (o.cuts.max_border_ratio > 0) {
        // A twist is a compact region behind a short twist line; a region whose border is far
        // longer than a disk's of its size is scattered evidence (noise, or a wall thinner than
        // the faces), and cutting along it would shred the surface.
        size_t border_edges = 0;
        for (size_t i = 0; i < region.border.size(); ++i) {
          if (!region.border_on_mesh_border[i]) border_edges += region.border[i].size();
        }
        if (static_cast<double>(border_edges) >
            o.cuts.max_border_ratio * std::sqrt(static_cast<double>(region.faces.size())) + 16) {
          ++report.regions_scattered;
          continue;
        }
      }
      if (cut_out && !region_is_most_of_its_component(mesh, region) && cut_out(mesh, region)) {
        if (o.experimental.regrow_cut_outs) {
          regrow_region(mesh, region, o.cuts.min_component_faces);
        } else {
          remove_faces(mesh, region.faces, o.cuts.min_component_faces);
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
      for (FaceHandle f : *dopt.incremental.restrict_to) {
        if (edgefront::is_live(mesh, f)) next.push_back(f);
      }
      for (size_t i = faces_before; i < mesh.n_faces(); ++i) {
        if (edgefront::is_live(mesh, FaceHandle(static_cast<int>(i)))) next.push_back(FaceHandle(static_cast<int>(i)));
      }
      dopt.incremental.restrict_to = std::move(next);
    } else {
      // Re-detect on the whole mesh: handles of the restricted set may be gone.
      dopt.incremental.restrict_to.reset();
    }
  }
  if (grid) grid->update_new(mesh);
  if (!incremental && o.cuts.min_cut_piece_share > 0)
    report.faces_removed += remove_small_cut_pieces(mesh, o, dups, report.supported_faces_spared);
  if (!incremental && o.experimental.peel_flaps > 0) {
    const size_t peeled = peel_flaps(mesh, o, dups, report.supported_faces_spared);
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

}  // namespace detail

namespace {

/// The twist lines a labelled repair cuts along: the groups of cut edges (between a face of `side`
/// and a face outside it) that meet at vertices.
size_t cut_lines(const Mesh& mesh, const std::vector<FaceHandle>& side) {
  std::unordered_set<int> inside;
  for (FaceHandle f : side) inside.insert(f.idx());
  edgefront::UnionFind lines(mesh.n_vertices());
  std::vector<size_t> ends;
  for (FaceHandle f : side) {
    for (HalfedgeHandle h : mesh.fh_range(f)) {
      const FaceHandle g = mesh.opposite_face_handle(h);
      if (!g.is_valid() || inside.count(g.idx())) continue;
      const size_t a = static_cast<size_t>(mesh.from_vertex_handle(h).idx()), b = static_cast<size_t>(mesh.to_vertex_handle(h).idx());
      lines.unite(a, b);
      ends.push_back(a);
    }
  }
  std::unordered_set<size_t> roots;
  for (size_t v : ends) roots.insert(lines.find(v));
  return roots.size();
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
  report.cut_lines = cut_lines(mesh, side);
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
  if (o.experimental.peel_flaps > 0) {
    const size_t peeled = peel_flaps(mesh, o, dups, report.supported_faces_spared);
    report.flap_faces_removed += peeled;
    report.faces_removed += peeled;
  }
  if (o.global_orientation) orient_globally(mesh, o, dups, report);
  drop_turned_patches(mesh, o, report);
  detail::mend_patches(mesh, o, report);
  if (o.garbage_collect) mesh.garbage_collection();
  return report;
}

}  // namespace

using detail::flip_seam_pieces;
using detail::repair_impl;

RepairReport repair(Mesh& mesh, const RepairOptions& options) {
  DupList dups;
  RepairReport seams;
  if (options.experimental.flip_seam_pieces) {
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

RepairOptions RepairOptions::finished_mesh() { return RepairOptions{}; }

RepairOptions RepairOptions::in_loop() {
  // Rounds of border-flap peeling at the final call (one ring each). The value the GCS hook was
  // measured with on the vault shells (bench/results/twist-vaults.md, which reports no other count).
  constexpr int kLoopPeelRounds = 3;
  // Largest turned-over patch the final call drops: slivers and rim flaps of 1-4 faces, each of
  // which makes every face of the other layer within the radius a same-orientation pair; bigger
  // groups are the detector's business (bench/results/twist-vaults.md).
  constexpr size_t kLoopTurnedPatchFaces = 4;
  RepairOptions o;
  o.cuts.max_border_ratio = 0;  // no limit: in the loop, scattered regions are cut too
  o.experimental.peel_flaps = kLoopPeelRounds;
  o.experimental.peel_from_cuts = true;  // only flaps the cuts left (a run without a cut keeps its mesh)
  o.experimental.drop_turned_patches = kLoopTurnedPatchFaces;
  return o;
}

}  // namespace twist
