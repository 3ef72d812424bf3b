#include "detail/untangle.h"

#include <algorithm>
#include <cmath>
#include <string>
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

using Pairs = std::vector<std::pair<int, int>>;

bool touches_border(const Mesh& mesh, FaceHandle f) {
  for (VertexHandle v : mesh.fv_range(f))
    if (mesh.is_boundary(v)) return true;
  return false;
}

// The mean of v's neighbours; on a border, of its two border neighbours.
Vec3 smoothing_target(const Mesh& mesh, VertexHandle v) {
  Vec3 sum(0, 0, 0);
  double n = 0;
  if (mesh.is_boundary(v)) {
    for (auto h : mesh.voh_range(v)) {
      if (mesh.is_boundary(h)) {
        sum += mesh.point(mesh.to_vertex_handle(h));
        n += 1;
      }
      if (mesh.is_boundary(mesh.opposite_halfedge_handle(h))) {
        sum += mesh.point(mesh.to_vertex_handle(h));
        n += 1;
      }
    }
  } else {
    for (VertexHandle u : mesh.vv_range(v)) {
      sum += mesh.point(u);
      n += 1;
    }
  }
  return n > 0 ? sum / n : mesh.point(v);
}

// One smoothing round over the vertices of the crossing faces and `rings` rings around them;
// moves that make a new pair cross are put back. Returns the pairs after the round.
Pairs relax_round(Mesh& mesh, const Pairs& pairs, int rings, const std::vector<Vec3>& origin, const UntangleParams& p) {
  std::vector<char> in(mesh.n_vertices(), 0);
  std::vector<VertexHandle> set;
  const auto add = [&](VertexHandle v) {
    if (in[static_cast<std::size_t>(v.idx())]) return;
    in[static_cast<std::size_t>(v.idx())] = 1;
    set.push_back(v);
  };
  for (const auto& [a, b] : pairs)
    for (const int f : {a, b})
      for (VertexHandle v : mesh.fv_range(FaceHandle(f))) add(v);
  for (int r = 0; r < rings; ++r) {
    const std::vector<VertexHandle> current = set;
    for (VertexHandle v : current)
      for (VertexHandle u : mesh.vv_range(v)) add(u);
  }
  std::sort(set.begin(), set.end());  // index order: deterministic
  std::vector<Vec3> saved(set.size()), target(set.size());
  for (std::size_t k = 0; k < set.size(); ++k) saved[k] = mesh.point(set[k]);
  for (int it = 0; it < p.relax_iterations; ++it) {
    for (std::size_t k = 0; k < set.size(); ++k) target[k] = smoothing_target(mesh, set[k]);
    for (std::size_t k = 0; k < set.size(); ++k) {
      const Vec3& o = origin[static_cast<std::size_t>(set[k].idx())];
      Vec3 moved = mesh.point(set[k]) + p.relax_rate * (target[k] - mesh.point(set[k])) - o;
      const double len = moved.norm();
      if (len > p.max_move) moved *= p.max_move / len;
      mesh.point(set[k]) = o + moved;
    }
  }
  // Put back (to where the round started) the moved vertices of both faces of every pair that
  // crosses now and did not before, until there is none (at worst every vertex goes back).
  for (;;) {
    Pairs now = self_intersecting_face_pairs(mesh);
    bool put_back = false;
    for (const auto& pair : now) {
      if (std::binary_search(pairs.begin(), pairs.end(), pair)) continue;
      for (const int f : {pair.first, pair.second}) {
        for (VertexHandle v : mesh.fv_range(FaceHandle(f))) {
          if (!in[static_cast<std::size_t>(v.idx())]) continue;
          const std::size_t k = static_cast<std::size_t>(std::lower_bound(set.begin(), set.end(), v) - set.begin());
          if (mesh.point(v) != saved[k]) {
            mesh.point(v) = saved[k];
            put_back = true;
          }
        }
      }
    }
    if (!put_back) return now;
  }
}

}  // namespace

UntangleReport untangle(Mesh& mesh, const CloudQuery& cloud, const UntangleParams& p) {
  if (!(p.max_move > 0) || !std::isfinite(p.max_move))
    throw edgefront::InvalidInput("gcs untangle: max_move must be finite and > 0");
  if (p.relax_rounds < 0 || p.relax_iterations < 0)
    throw edgefront::InvalidInput("gcs untangle: relax_rounds and relax_iterations must be >= 0");
  if (!(p.relax_rate > 0 && p.relax_rate <= 1)) throw edgefront::InvalidInput("gcs untangle: relax_rate must be in (0, 1]");
  UntangleReport report;
  Pairs pairs = self_intersecting_face_pairs(mesh);
  report.pairs_before = pairs.size();
  if (pairs.empty()) return report;
  std::vector<Vec3> origin(mesh.n_vertices());
  for (VertexHandle v : mesh.vertices()) origin[static_cast<std::size_t>(v.idx())] = mesh.point(v);
  for (int round = 0; round < p.relax_rounds && !pairs.empty(); ++round) pairs = relax_round(mesh, pairs, round, origin, p);
  for (VertexHandle v : mesh.vertices()) report.vertices_moved += mesh.point(v) != origin[static_cast<std::size_t>(v.idx())] ? 1 : 0;

  // Cutting: a pair ends when one of its faces goes.
  if (p.cut && !pairs.empty()) {
    std::vector<int> cut;
    for (const auto& [a, b] : pairs) {
      const bool ba = touches_border(mesh, FaceHandle(a)), bb = touches_border(mesh, FaceHandle(b));
      if (ba != bb) {
        cut.push_back(ba ? a : b);
      } else {
        cut.push_back(a);
        cut.push_back(b);
      }
    }
    std::sort(cut.begin(), cut.end());
    cut.erase(std::unique(cut.begin(), cut.end()), cut.end());
    for (const int f : cut) mesh.delete_face(FaceHandle(f), true);
    report.faces_removed += cut.size() + clean_topology(mesh, 8);
    pairs = self_intersecting_face_pairs(mesh);  // none: every pair lost a face
    if (p.fill_max_vertices >= 3) {
      Mesh filled = mesh;
      const std::size_t n = fill_small_holes(filled, cloud, p.fill_max_vertices, p.fill_support, 0.5);
      if (n > 0 && self_intersecting_face_pairs(filled) == pairs) {
        mesh = std::move(filled);
        report.holes_filled += n;
      }
    }
  }
  report.pairs_after = pairs.size();
  return report;
}

}  // namespace gcs::detail
