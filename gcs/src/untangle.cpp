#include "detail/untangle.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "detail/self_intersection.h"
#include "edgefront/error.h"
#include "edgefront/mesh_stats.h"

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

Vec3 unit_normal(const Mesh& mesh, FaceHandle f) {
  const Vec3 n = face_normal(mesh, f);
  const double len = n.norm();
  return len > 0 ? n / len : Vec3(0, 0, 0);
}

// The vertices `set` (sorted) were moved from `saved`: put back (there) the moved vertices of both
// faces of every pair that crosses now and is not in `allowed`, and of every face that turned by
// more than acos(min_face_cos) from `entry_normal`, until there is none (at worst every vertex
// goes back). Returns the pairs that cross then.
Pairs settle(Mesh& mesh, const std::vector<VertexHandle>& set, const std::vector<Vec3>& saved, const Pairs& allowed,
             const std::vector<Vec3>& entry_normal, double min_face_cos) {
  const auto put_back = [&](FaceHandle f) {
    bool any = false;
    for (VertexHandle v : mesh.fv_range(f)) {
      const auto it = std::lower_bound(set.begin(), set.end(), v);
      if (it == set.end() || *it != v) continue;
      const Vec3& s = saved[static_cast<std::size_t>(it - set.begin())];
      if (mesh.point(v) != s) {
        mesh.point(v) = s;
        any = true;
      }
    }
    return any;
  };
  for (;;) {
    bool again = false;
    for (VertexHandle v : set) {
      for (FaceHandle f : mesh.vf_range(v)) {
        const Vec3 n = unit_normal(mesh, f);
        if (!(n.sqrnorm() > 0 && (n | entry_normal[static_cast<std::size_t>(f.idx())]) >= min_face_cos))
          again = put_back(f) || again;
      }
    }
    if (again) continue;
    Pairs now = self_intersecting_face_pairs(mesh);
    for (const auto& pair : now) {
      if (std::binary_search(allowed.begin(), allowed.end(), pair)) continue;
      again = put_back(FaceHandle(pair.first)) || again;
      again = put_back(FaceHandle(pair.second)) || again;
    }
    if (!again) return now;
  }
}

// One smoothing round over the vertices of the crossing faces and `rings` rings around them
// (moves that make a new pair cross or turn a face too far are put back). Returns the pairs after.
Pairs relax_round(Mesh& mesh, const Pairs& pairs, int rings, const std::vector<Vec3>& origin,
                  const std::vector<Vec3>& entry_normal, const UntangleParams& p) {
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
  return settle(mesh, set, saved, pairs, entry_normal, p.min_face_cos);
}

// Moves every smoothed vertex halfway back to where it was on entry, `passes` times, as far as
// that makes no pair cross that does not cross now (the smoothing moved more than needed, off the
// samples). Returns the pairs after.
Pairs pull_back(Mesh& mesh, Pairs pairs, const std::vector<Vec3>& origin, const std::vector<Vec3>& entry_normal,
                const UntangleParams& p) {
  for (int pass = 0; pass < p.pull_back_passes; ++pass) {
    std::vector<VertexHandle> set;
    std::vector<Vec3> saved;
    for (VertexHandle v : mesh.vertices()) {
      const Vec3& o = origin[static_cast<std::size_t>(v.idx())];
      if (mesh.point(v) == o) continue;
      set.push_back(v);
      saved.push_back(mesh.point(v));
      mesh.point(v) = 0.5 * (mesh.point(v) + o);
    }
    if (set.empty()) break;
    pairs = settle(mesh, set, saved, pairs, entry_normal, p.min_face_cos);
  }
  return pairs;
}

// A piece a cut separates goes when it has fewer than this share of the largest piece's faces
// (the border creation's BorderParams::min_component_fraction); pieces of fewer than 8 faces go
// in any case (min_component_faces).
constexpr std::size_t kMinPieceFaces = 8;
constexpr double kMinPieceFraction = 0.05;
// A hole the cut left is filled only when its fan agrees with the faces around it (mean cosine of
// their normals at least this), as the topology pass's hole fills (kFillNormalAgreement there).
constexpr double kFillNormalAgreement = 0.5;

// Deletes face f of `trial` and the pieces of fewer than 8 faces that leaves; when f's corners
// end up in several pieces, the largest of those stays and the others go if each is below 5% of
// the largest piece of the mesh. Returns the faces removed, 0 when a larger piece would be cut off.
std::size_t cut_face(Mesh& trial, FaceHandle f) {
  std::vector<VertexHandle> corners;
  for (VertexHandle v : trial.fv_range(f)) corners.push_back(v);
  trial.delete_face(f, true);
  std::size_t removed = 1 + clean_topology(trial, kMinPieceFaces);
  const edgefront::ComponentLabels labels = edgefront::connected_components(trial);
  std::vector<int> pieces;
  for (VertexHandle v : corners)
    if (!trial.status(v).deleted() && !trial.is_isolated(v)) pieces.push_back(labels.vertex_component[static_cast<std::size_t>(v.idx())]);
  std::sort(pieces.begin(), pieces.end());
  pieces.erase(std::unique(pieces.begin(), pieces.end()), pieces.end());
  if (pieces.size() <= 1) return removed;
  std::vector<std::size_t> faces(labels.count, 0);
  for (FaceHandle g : trial.faces()) ++faces[static_cast<std::size_t>(labels.vertex_component[trial.cfv_begin(g)->idx()])];
  const double least = kMinPieceFraction * static_cast<double>(*std::max_element(faces.begin(), faces.end()));
  const int keep = *std::max_element(pieces.begin(), pieces.end(), [&](int x, int y) {
    return faces[static_cast<std::size_t>(x)] < faces[static_cast<std::size_t>(y)];
  });
  for (const int c : pieces)
    if (c != keep && static_cast<double>(faces[static_cast<std::size_t>(c)]) >= least) return 0;
  for (FaceHandle g : trial.faces()) {
    const int c = labels.vertex_component[trial.cfv_begin(g)->idx()];
    if (c != keep && std::binary_search(pieces.begin(), pieces.end(), c)) {
      trial.delete_face(g, true);
      ++removed;
    }
  }
  return removed;
}

// Cuts out one face of `pair` (the one touching a border, else the one farther from the cloud,
// else the other; see cut_face). Returns the faces removed (0: neither face could go).
std::size_t cut_pair(Mesh& mesh, const CloudQuery& cloud, std::pair<int, int> pair) {
  const FaceHandle fa(pair.first), fb(pair.second);
  if (mesh.status(fa).deleted() || mesh.status(fb).deleted()) return 0;
  const bool ba = touches_border(mesh, fa), bb = touches_border(mesh, fb);
  const bool a_first = ba != bb ? ba : cloud(centroid(mesh, fa)).distance >= cloud(centroid(mesh, fb)).distance;
  for (const FaceHandle f : a_first ? std::array{fa, fb} : std::array{fb, fa}) {
    // A face without a border vertex cannot cut its mesh apart (each corner's fan stays a chain
    // joining the other two corners): no trial copy is needed.
    if (!touches_border(mesh, f)) return cut_face(mesh, f);
    Mesh trial = mesh;
    const std::size_t removed = cut_face(trial, f);
    if (removed == 0) continue;
    mesh = std::move(trial);
    return removed;
  }
  return 0;
}

}  // namespace

UntangleReport untangle(Mesh& mesh, const CloudQuery& cloud, const UntangleParams& p) {
  if (!(p.max_move > 0) || !std::isfinite(p.max_move))
    throw edgefront::InvalidInput("gcs untangle: max_move must be finite and > 0");
  if (p.relax_rounds < 0 || p.relax_iterations < 0)
    throw edgefront::InvalidInput("gcs untangle: relax_rounds and relax_iterations must be >= 0");
  if (!(p.relax_rate > 0 && p.relax_rate <= 1)) throw edgefront::InvalidInput("gcs untangle: relax_rate must be in (0, 1]");
  if (!(p.min_face_cos >= -1 && p.min_face_cos <= 1)) throw edgefront::InvalidInput("gcs untangle: min_face_cos must be in [-1, 1]");
  if (p.pull_back_passes < 0) throw edgefront::InvalidInput("gcs untangle: pull_back_passes must be >= 0");
  UntangleReport report;
  Pairs pairs = self_intersecting_face_pairs(mesh);
  report.pairs_before = pairs.size();
  if (pairs.empty()) return report;
  std::vector<Vec3> origin(mesh.n_vertices());
  for (VertexHandle v : mesh.vertices()) origin[static_cast<std::size_t>(v.idx())] = mesh.point(v);
  std::vector<Vec3> entry_normal(mesh.n_faces(), Vec3(0, 0, 0));
  for (FaceHandle f : mesh.faces()) entry_normal[static_cast<std::size_t>(f.idx())] = unit_normal(mesh, f);
  for (int round = 0; round < p.relax_rounds && !pairs.empty(); ++round)
    pairs = relax_round(mesh, pairs, round, origin, entry_normal, p);
  pairs = pull_back(mesh, std::move(pairs), origin, entry_normal, p);
  for (VertexHandle v : mesh.vertices()) report.vertices_moved += mesh.point(v) != origin[static_cast<std::size_t>(v.idx())] ? 1 : 0;

  // Cutting: a pair ends when one of its faces goes.
  if (p.cut && !pairs.empty()) {
    // The corners of the faces that may go: the holes the cut leaves pass through them.
    std::vector<char> cut_corner(mesh.n_vertices(), 0);
    for (const auto& [a, b] : pairs)
      for (const int f : {a, b})
        for (VertexHandle v : mesh.fv_range(FaceHandle(f))) cut_corner[static_cast<std::size_t>(v.idx())] = 1;
    std::size_t removed = 0;
    for (const auto& pair : pairs) removed += cut_pair(mesh, cloud, pair);
    report.faces_removed += removed;
    pairs = self_intersecting_face_pairs(mesh);  // the pairs whose faces could not go
    if (removed > 0 && p.fill_max_vertices >= 3) {
      // One hole at a time, each kept when it makes no pair cross.
      // A fill that crosses a face (the surface the cut face crossed can pass through the hole) is
      // smoothed like the input (no cut) and kept when that leaves no new crossing.
      UntangleParams smooth_only = p;
      smooth_only.cut = false;
      report.holes_filled += fill_small_holes_checked(mesh, cloud, p.fill_max_vertices, p.fill_support, kFillNormalAgreement, cut_corner,
                                                      [&](Mesh& filled) {
                                                        if (self_intersecting_face_pairs(filled) == pairs) return true;
                                                        if (!pairs.empty()) return false;
                                                        const UntangleReport r = untangle(filled, cloud, smooth_only);
                                                        return r.pairs_after == 0;
                                                      });
    }
  }
  report.pairs_after = pairs.size();
  return report;
}

}  // namespace gcs::detail
