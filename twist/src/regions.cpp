// The region steps of a detection (detect.cpp's detect_pass): the flagged faces grown into regions
// behind a Minimal Edge Front, enclosed pieces filled, and a region's border loops.
#include <algorithm>
#include <deque>
#include <unordered_map>
#include <utility>
#include <vector>

#include "detail/detect_steps.h"
#include "detail/geometry.h"
#include "edgefront/minimal_edge_front.h"

namespace twist::detail {

using edgefront::FaceHandle;
using edgefront::HalfedgeHandle;
using edgefront::Mesh;
using edgefront::VertexHandle;

/// The border of a face set as closed loops of halfedges with the set on their right (the face
/// of each halfedge lies outside or is missing), and per loop whether it lies on the mesh border.
std::pair<std::vector<std::vector<HalfedgeHandle>>, std::vector<bool>> border_loops(const Mesh& mesh,
                                                                                   const std::vector<FaceHandle>& faces) {
  std::unordered_map<int, char> in_set;
  for (FaceHandle f : faces) in_set[f.idx()] = 1;
  std::vector<HalfedgeHandle> starts;
  std::unordered_map<int, char> unused;  // border halfedges not yet in a loop
  for (FaceHandle f : faces) {
    for (HalfedgeHandle h : mesh.fh_range(f)) {
      const HalfedgeHandle o = mesh.opposite_halfedge_handle(h);
      const FaceHandle g = mesh.face_handle(o);
      if (g.is_valid() && in_set.count(g.idx())) continue;
      starts.push_back(o);
      unused[o.idx()] = 1;
    }
  }
  std::sort(starts.begin(), starts.end(), [](HalfedgeHandle a, HalfedgeHandle b) { return a.idx() < b.idx(); });
  std::vector<std::vector<HalfedgeHandle>> loops;
  std::vector<bool> on_border;
  for (HalfedgeHandle s0 : starts) {
    if (!unused.count(s0.idx())) continue;
    std::vector<HalfedgeHandle> loop;
    HalfedgeHandle h = s0;
    while (h.is_valid() && unused.erase(h.idx())) {
      loop.push_back(h);
      // The next border halfedge leaves to_vertex(h): turn around it from h's opposite.
      HalfedgeHandle next;
      const HalfedgeHandle back = mesh.opposite_halfedge_handle(h);
      HalfedgeHandle g = back;
      do {
        g = mesh.cw_rotated_halfedge_handle(g);
        if (unused.count(g.idx()) || g == s0) {
          next = g;
          break;
        }
      } while (g != back);
      h = next;
    }
    bool all_border = true;
    for (HalfedgeHandle x : loop) all_border = all_border && mesh.is_boundary(x);
    loops.push_back(std::move(loop));
    on_border.push_back(all_border);
  }
  return {loops, on_border};
}

/// Step 2: grows the flagged faces (`order`) into regions with a Minimal Edge Front from their
/// vertices, `grow_levels` levels; returns the front's loops.
std::vector<edgefront::FrontLoop> grow_front(const Mesh& mesh, const std::vector<FaceHandle>& order, int grow_levels) {
  std::vector<VertexHandle> sources;
  {
    std::unordered_map<int, char> seen;
    for (FaceHandle f : order) {
      for (VertexHandle v : mesh.fv_range(f)) {
        if (seen.emplace(v.idx(), 1).second) sources.push_back(v);
      }
    }
    std::sort(sources.begin(), sources.end(), [](VertexHandle a, VertexHandle b) { return a.idx() < b.idx(); });
  }
  edgefront::MinimalEdgeFront front(mesh);
  front.reset(edgefront::FrontSource::from_vertices(sources));
  front.run(grow_levels);
  return front.loops();
}

/// Step 3: the regions, the surface behind the front (its `loops`) connected without crossing it,
/// seeded at the flagged faces (`order`, evidence in `flagged`); `region_of` maps their faces to
/// their indices.
std::vector<TwistRegion> regions_behind_front(const Mesh& mesh, const std::vector<FaceHandle>& order,
                                             const std::unordered_map<int, Evidence>& flagged,
                                             const std::vector<edgefront::FrontLoop>& loops,
                                             std::unordered_map<int, int>& region_of) {
  std::unordered_map<int, char> front_edge;
  for (const auto& loop : loops) {
    for (HalfedgeHandle h : loop.halfedges) front_edge[mesh.edge_handle(h).idx()] = 1;
  }
  std::vector<FaceHandle> seeds = order;
  std::sort(seeds.begin(), seeds.end(), [](FaceHandle a, FaceHandle b) { return a.idx() < b.idx(); });
  std::vector<TwistRegion> regions;
  for (FaceHandle seed : seeds) {
    if (region_of.count(seed.idx())) continue;
    const int id = static_cast<int>(regions.size());
    regions.emplace_back();
    TwistRegion& r = regions.back();
    std::deque<FaceHandle> queue{seed};
    region_of[seed.idx()] = id;
    while (!queue.empty()) {
      const FaceHandle f = queue.front();
      queue.pop_front();
      r.faces.push_back(f);
      r.area += detail::area(detail::face_points(mesh, f));
      const auto ev = flagged.find(f.idx());
      if (ev != flagged.end()) r.evidence.push_back(ev->second);
      for (HalfedgeHandle h : mesh.fh_range(f)) {
        if (front_edge.count(mesh.edge_handle(h).idx())) continue;
        const FaceHandle g = mesh.opposite_face_handle(h);
        if (!g.is_valid() || region_of.count(g.idx())) continue;
        region_of[g.idx()] = id;
        queue.push_back(g);
      }
    }
    std::sort(r.faces.begin(), r.faces.end(), [](FaceHandle a, FaceHandle b) { return a.idx() < b.idx(); });
    std::sort(r.evidence.begin(), r.evidence.end(),
              [](const Evidence& a, const Evidence& b) { return a.face.idx() < b.face.idx(); });
    r.flagged_faces = r.evidence.size();
  }
  return regions;
}

/// Step 4, fill holes: a piece of the rest enclosed by a region (bounded by one of several border
/// loops of the front, `loops`) and smaller than the region joins it; the largest piece always
/// stays outside. Each piece is explored with a budget of the region's size, so this is
/// semi-local.
void fill_enclosed_pieces(const Mesh& mesh, const std::vector<edgefront::FrontLoop>& loops,
                          std::unordered_map<int, int>& region_of, std::vector<TwistRegion>& regions) {
  std::unordered_map<int, char> filled;
  for (size_t id = 0; id < regions.size(); ++id) {
    TwistRegion& r = regions[id];
    std::vector<std::vector<FaceHandle>> pieces;
    std::unordered_map<int, char> explored;
    bool some_outside = false;
    for (const auto& loop : loops) {
      if (loop.halfedges.empty()) continue;
      const FaceHandle behind = mesh.opposite_face_handle(loop.halfedges.front());
      const auto it = behind.is_valid() ? region_of.find(behind.idx()) : region_of.end();
      if (it == region_of.end() || it->second != static_cast<int>(id)) continue;
      for (HalfedgeHandle h0 : loop.halfedges) {
        const FaceHandle start = mesh.face_handle(h0);
        if (!start.is_valid() || region_of.count(start.idx()) || explored.count(start.idx())) continue;
        std::vector<FaceHandle> piece{start};
        explored[start.idx()] = 1;
        bool fits = true;
        for (size_t q = 0; q < piece.size() && fits; ++q) {
          for (HalfedgeHandle h : mesh.fh_range(piece[q])) {
            const FaceHandle g = mesh.opposite_face_handle(h);
            if (!g.is_valid() || explored.count(g.idx())) continue;
            const auto owner = region_of.find(g.idx());
            if (owner != region_of.end()) {
              if (owner->second != static_cast<int>(id)) fits = false;  // touches another region
              continue;
            }
            explored[g.idx()] = 1;
            piece.push_back(g);
            if (piece.size() >= r.faces.size()) fits = false;
          }
        }
        if (fits) {
          pieces.push_back(std::move(piece));
        } else {
          some_outside = true;
        }
      }
    }
    if (!some_outside && !pieces.empty()) {  // keep the largest piece outside
      const auto largest = std::max_element(pieces.begin(), pieces.end(),
                                            [](const auto& a, const auto& b) { return a.size() < b.size(); });
      pieces.erase(largest);
    }
    for (const auto& piece : pieces) {
      for (FaceHandle f : piece) {
        filled[f.idx()] = 1;
        region_of[f.idx()] = static_cast<int>(id);
        r.faces.push_back(f);
        r.area += detail::area(detail::face_points(mesh, f));
      }
    }
    std::sort(r.faces.begin(), r.faces.end(), [](FaceHandle a, FaceHandle b) { return a.idx() < b.idx(); });
  }
}

}  // namespace twist::detail
