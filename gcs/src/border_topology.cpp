#include "detail/border_topology.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <vector>

#include "edgefront/error.h"
#include "edgefront/mesh_stats.h"
#include "edgefront/point_index.h"

namespace gcs::detail {

using edgefront::FaceHandle;
using edgefront::HalfedgeHandle;
using edgefront::Mesh;
using edgefront::Vec3;
using edgefront::VertexHandle;

Vec3 centroid(const Mesh& mesh, FaceHandle f) {
  Vec3 c(0, 0, 0);
  for (auto v : mesh.fv_range(f)) c += mesh.point(v);
  return c / 3.0;
}

Vec3 face_normal(const Mesh& mesh, FaceHandle f) {
  auto it = mesh.cfv_iter(f);
  const Vec3 a = mesh.point(*it), b = mesh.point(*++it), c = mesh.point(*++it);
  return (b - a) % (c - a);
}

namespace {

Vec3 tri_normal(const Vec3& a, const Vec3& b, const Vec3& c) { return (b - a) % (c - a); }

// The border joins the twist layer shares (twist/src/detail/border_join.h), on this loop's cloud.
using Loop = twist::detail::BorderLoop;
using twist::detail::add_all_or_none;
using twist::detail::border_loops;
using twist::detail::is_simple;
using twist::detail::loop_halfedge;
using twist::detail::loop_vertex;
using twist::detail::Strip;

twist::detail::CloudDistance distance_of(const CloudQuery& cloud) {
  return [&cloud](const Vec3& p) { return cloud(p).distance; };
}

bool zip_strip(Mesh& mesh, const CloudQuery& cloud, const Strip& st, double max_support_distance,
               double min_normal_agreement) {
  return twist::detail::zip_strip(mesh, distance_of(cloud), st, max_support_distance, min_normal_agreement);
}

bool fill_loop(Mesh& mesh, const CloudQuery& cloud, const Loop& loop, double max_support_distance,
               double min_normal_agreement) {
  return twist::detail::fill_loop(mesh, distance_of(cloud), loop, max_support_distance, min_normal_agreement);
}

// Deletes the faces of every fan but the largest at non-manifold vertices; true if any was deleted.
size_t fix_nonmanifold_vertices(Mesh& mesh) {
  size_t removed = 0;
  for (bool again = true; again;) {
    again = false;
    for (auto v : mesh.vertices()) {
      if (mesh.status(v).deleted() || mesh.is_manifold(v)) continue;
      // Outgoing halfedges in circulator order, cut into fans at the boundary ones.
      std::vector<std::vector<FaceHandle>> fans;
      std::vector<HalfedgeHandle> out;
      for (auto h : mesh.voh_range(v)) out.push_back(h);
      size_t start = 0;
      while (start < out.size() && mesh.face_handle(out[start]).is_valid()) ++start;
      if (start == out.size()) continue;  // no boundary: cannot be non-manifold
      std::vector<FaceHandle> cur;
      for (size_t k = 1; k <= out.size(); ++k) {
        const HalfedgeHandle h = out[(start + k) % out.size()];
        const FaceHandle f = mesh.face_handle(h);
        if (f.is_valid()) {
          cur.push_back(f);
        } else if (!cur.empty()) {
          fans.push_back(cur);
          cur.clear();
        }
      }
      if (!cur.empty()) fans.push_back(cur);
      if (fans.size() < 2) continue;
      size_t keep = 0;
      for (size_t k = 1; k < fans.size(); ++k) {
        const auto min_idx = [](const std::vector<FaceHandle>& fs) {
          int m = std::numeric_limits<int>::max();
          for (auto f : fs) m = std::min(m, f.idx());
          return m;
        };
        if (fans[k].size() > fans[keep].size() ||
            (fans[k].size() == fans[keep].size() && min_idx(fans[k]) < min_idx(fans[keep])))
          keep = k;
      }
      for (size_t k = 0; k < fans.size(); ++k) {
        if (k == keep) continue;
        for (auto f : fans[k]) {
          if (mesh.status(f).deleted()) continue;
          mesh.delete_face(f, true);
          ++removed;
        }
      }
      again = true;
    }
  }
  return removed;
}

}  // namespace

std::vector<char> separate_surfaces(const Mesh& mesh, const edgefront::ComponentLabels& labels,
                                    const std::vector<size_t>& faces, const SeparateParts& parts) {
  // (component, part) -> faces; each component's part is the one most of its faces lie on.
  std::map<std::pair<int, int>, size_t> count;
  for (auto f : mesh.faces()) {
    const size_t sample = (*parts.nearest)[static_cast<size_t>(f.idx())].index;
    if (sample != CloudHit::kNoSample)
      ++count[{labels.vertex_component[mesh.cfv_begin(f)->idx()], parts.sample_part(sample)}];
  }
  std::vector<std::pair<size_t, int>> dominant(labels.count, {0, -1});  // (faces, part)
  for (const auto& [key, n] : count) {
    auto& d = dominant[static_cast<size_t>(key.first)];
    if (n > d.first) d = {n, key.second};
  }
  const size_t largest = static_cast<size_t>(std::max_element(faces.begin(), faces.end()) - faces.begin());
  std::map<int, size_t> lead;  // part -> its largest component (the first of equals)
  for (size_t c = 0; c < labels.count; ++c) {
    const int part = dominant[c].second;
    if (part < 0) continue;
    const auto it = lead.find(part);
    if (it == lead.end() || faces[c] > faces[it->second]) lead[part] = c;
  }
  std::vector<char> separate(labels.count, 0);
  for (const auto& [part, c] : lead)
    if (part != dominant[largest].second) separate[c] = 1;
  return separate;
}

size_t clean_topology(Mesh& mesh, size_t min_faces, double min_fraction, const SeparateParts& parts) {
  size_t removed = fix_nonmanifold_vertices(mesh);
  const edgefront::ComponentLabels labels = edgefront::connected_components(mesh);
  if (labels.count > 1) {
    std::vector<size_t> faces(labels.count, 0);
    for (auto f : mesh.faces()) ++faces[labels.vertex_component[mesh.fv_begin(f)->idx()]];
    const size_t largest = static_cast<size_t>(std::max_element(faces.begin(), faces.end()) - faces.begin());
    min_faces = std::max(min_faces, static_cast<size_t>(min_fraction * static_cast<double>(faces[largest])));
    std::vector<char> doomed(labels.count, 0);
    bool any = false;
    for (size_t c = 0; c < labels.count; ++c) {
      doomed[c] = c != largest && faces[c] < min_faces;
      any = any || doomed[c];
    }
    if (any && parts) {
      const std::vector<char> separate = separate_surfaces(mesh, labels, faces, parts);
      for (size_t c = 0; c < labels.count; ++c) doomed[c] = doomed[c] && !separate[c];
    }
    for (auto f : mesh.faces()) {
      if (!doomed[static_cast<size_t>(labels.vertex_component[mesh.fv_begin(f)->idx()])]) continue;
      mesh.delete_face(f, true);
      ++removed;
    }
  }
  // Vertices left without faces (possible when a deleted component had isolated vertices).
  for (auto v : mesh.vertices())
    if (mesh.is_isolated(v)) mesh.delete_vertex(v);
  return removed;
}

FaceNearest face_nearest(const Mesh& mesh, const CloudQuery& cloud) {
  FaceNearest nearest(mesh.n_faces());
  for (auto f : mesh.faces()) nearest[static_cast<size_t>(f.idx())] = cloud(centroid(mesh, f));
  return nearest;
}

size_t remove_unsupported_faces(Mesh& mesh, const CloudQuery& cloud, const BorderParams& params,
                                const CloudNeighbors& neighbors, FaceNearest* nearest) {
  std::vector<FaceHandle> doomed;
  std::vector<CloudHit> near;
  const bool film_test = params.film_samples > 0 && neighbors;
  size_t live_faces = 0;
  const double max_edge2 = params.max_edge_length * params.max_edge_length;
  // The nearest samples are kept for the caller, and for clean_topology's sparing of separate parts.
  FaceNearest own;
  FaceNearest* const record = nearest ? nearest : params.sample_part ? &own : nullptr;
  if (record) record->assign(mesh.n_faces(), CloudHit{});
  for (auto f : mesh.faces()) {
    ++live_faces;
    const Vec3 c = centroid(mesh, f);
    // With the film test on, its k nearest samples (nearest first) give the nearest one too.
    if (film_test) neighbors(c, params.film_samples, near);
    const CloudHit hit =
        !film_test ? cloud(c) : near.empty() ? CloudHit{std::numeric_limits<double>::infinity(), {}, {}} : near.front();
    if (record) (*record)[static_cast<size_t>(f.idx())] = hit;
    bool remove = hit.distance > params.max_support_distance;
    if (!remove && hit.distance >= params.normal_check_distance && std::isfinite(hit.normal[0])) {
      const Vec3 n = face_normal(mesh, f);
      const double ln = n.norm();
      remove = ln > 0 && std::abs(n | hit.normal) < params.min_normal_cos * ln;
    }
    if (!remove) {
      for (auto h : mesh.fh_range(f)) remove = remove || mesh.calc_edge_sqr_length(h) > max_edge2;
    }
    if (!remove && film_test) {
      const Vec3 n = face_normal(mesh, f);
      bool supported = !(n.norm() > 0);
      for (const CloudHit& s : near) {
        if (supported || s.distance > params.max_support_distance) break;
        supported = !std::isfinite(s.normal[0]) ||
                    std::abs(n | s.normal) >= params.film_min_cos * n.norm() * s.normal.norm() ||
                    ((c - s.point) | s.normal) <= 0;
      }
      remove = !supported;
    }
    if (remove) doomed.push_back(f);
  }
  if (doomed.empty() || doomed.size() * 10 >= live_faces * 9) return 0;  // never wipe out the mesh
  for (auto f : doomed) mesh.delete_face(f, true);
  return doomed.size() + clean_topology(mesh, params.min_component_faces, params.min_component_fraction,
                                        {record, params.sample_part});
}

namespace {

enum class PairMerge { not_candidate, refused, merged };

// Joins loops A and B by a strip when they are simple, disjoint, not joined by an edge, of similar
// length, close (mean gap within the limit plus `extra_gap`) and run opposite at their closest
// pair: `refused` when such a candidate pair's strip fails zip_strip's checks.
PairMerge merge_pair(Mesh& mesh, const CloudQuery& cloud, const Loop& A, const Loop& B, const MergeParams& params,
                     double extra_gap) {
  const size_t nA = A.vertices.size(), nB = B.vertices.size();
  if (nA < 3 || nB < 3 || nA * nB > 4'000'000) return PairMerge::not_candidate;
  const double lmin = std::min(A.length, B.length), lmax = std::max(A.length, B.length);
  if (!(lmin > 0) || lmax > params.max_length_ratio * lmin) return PairMerge::not_candidate;
  // Simple, disjoint loops without an edge between them.
  std::set<int> in_b;
  for (auto v : B.vertices) in_b.insert(v.idx());
  std::set<int> in_a;
  for (auto v : A.vertices) in_a.insert(v.idx());
  if (in_a.size() != nA || in_b.size() != nB) return PairMerge::not_candidate;
  for (auto v : A.vertices) {
    for (auto u : mesh.vv_range(v))
      if (in_b.count(u.idx()) > 0) return PairMerge::not_candidate;
  }
  // Gap: mean distance from A's vertices to B's; the start pair is the closest one.
  double gap = 0, best = std::numeric_limits<double>::infinity();
  size_t i0 = 0, k0 = 0;
  for (size_t i = 0; i < nA; ++i) {
    double d_min = std::numeric_limits<double>::infinity();
    size_t k_min = 0;
    for (size_t k = 0; k < nB; ++k) {
      const double d = (mesh.point(A.vertices[i]) - mesh.point(B.vertices[k])).norm();
      if (d < d_min) {
        d_min = d;
        k_min = k;
      }
    }
    gap += d_min;
    if (d_min < best) {
      best = d_min;
      i0 = i;
      k0 = k_min;
    }
  }
  gap /= static_cast<double>(nA);
  if (gap > std::max(params.max_gap_edges * params.mean_edge_length, params.max_gap_fraction * lmin) + extra_gap)
    return PairMerge::not_candidate;
  // Orientation: A's and B's boundary halfedges must run opposite at the start pair.
  const Vec3 tA = mesh.point(loop_vertex(A, long(i0) + 1)) - mesh.point(loop_vertex(A, long(i0) - 1));
  const Vec3 tB = mesh.point(loop_vertex(B, long(k0) + 1)) - mesh.point(loop_vertex(B, long(k0) - 1));
  if ((tA | tB) >= 0) return PairMerge::not_candidate;
  const Strip strip{[&](size_t i) { return loop_vertex(A, long(i0 + i)); },
                    [&](size_t j) { return loop_vertex(B, long(k0) - long(j)); },
                    [&](size_t i) { return loop_halfedge(A, long(i0 + i)); },
                    [&](size_t j) { return loop_halfedge(B, long(k0) - long(j) - 1); }, nA, nB};
  return zip_strip(mesh, cloud, strip, params.max_support_distance, params.min_normal_agreement) ? PairMerge::merged
                                                                                                  : PairMerge::refused;
}

// Deletes the faces around `front` (vertices) and returns the vertices of those faces that are
// left: the next ring. Vertices left without faces are deleted with their faces.
std::vector<VertexHandle> trim_ring(Mesh& mesh, const std::vector<VertexHandle>& front) {
  std::vector<FaceHandle> faces;
  for (auto v : front) {
    if (mesh.status(v).deleted()) continue;
    for (auto f : mesh.vf_range(v)) faces.push_back(f);
  }
  std::vector<int> corner;
  for (auto f : faces) {
    if (mesh.status(f).deleted()) continue;
    for (auto u : mesh.fv_range(f)) corner.push_back(u.idx());
    mesh.delete_face(f, true);
  }
  std::sort(corner.begin(), corner.end());
  corner.erase(std::unique(corner.begin(), corner.end()), corner.end());
  std::vector<VertexHandle> next;
  for (int k : corner) {
    const VertexHandle u(k);
    if (!mesh.status(u).deleted()) next.push_back(u);
  }
  return next;
}

// The loop with the most vertices in `marked` (a per-vertex flag), or loops.size() when none has any.
size_t loop_with_most(const std::vector<Loop>& loops, const std::vector<char>& marked) {
  size_t best = loops.size(), best_count = 0;
  for (size_t l = 0; l < loops.size(); ++l) {
    size_t count = 0;
    for (auto v : loops[l].vertices) count += marked[static_cast<size_t>(v.idx())] != 0;
    if (count > best_count) {
      best_count = count;
      best = l;
    }
  }
  return best;
}

// A copy of the mesh with `rings` rings of faces removed along each rim (vertex lists; the rims
// are trimmed ring by ring in turn) and its non-manifold vertices repaired, with its border loops
// and, per rim, the loop holding most of that rim's new border (loops.size() when none). Empty
// when the trimming changed the number of components (`components`: the mesh's).
struct Trimmed {
  Mesh mesh;
  std::vector<Loop> loops;
  std::vector<size_t> rim_loop;
};
std::optional<Trimmed> trimmed_copy(const Mesh& mesh, std::vector<std::vector<VertexHandle>> rims, size_t rings,
                                    size_t components) {
  Trimmed t{mesh, {}, {}};
  for (size_t r = 0; r < rings; ++r) {
    for (auto& rim : rims) rim = trim_ring(t.mesh, rim);
  }
  fix_nonmanifold_vertices(t.mesh);
  if (edgefront::connected_components(t.mesh).count != components) return std::nullopt;
  t.loops = border_loops(t.mesh);
  for (const auto& rim : rims) {
    std::vector<char> marked(t.mesh.n_vertices(), 0);
    for (auto v : rim) marked[static_cast<size_t>(v.idx())] = 1;
    t.rim_loop.push_back(loop_with_most(t.loops, marked));
  }
  return t;
}

// A candidate pair whose strip was refused: on a copy of the mesh, removes `rings` rings of faces
// along both loops (curled or overlapping rims: the two borders slid past each other, or bent
// away from the gap) and tries the strip between the new borders (the gap limit grows by two mean
// edge lengths per ring). Keeps the copy when the strip is added without splitting the mesh into
// more components.
bool trim_and_merge(Mesh& mesh, const CloudQuery& cloud, const Loop& A, const Loop& B, const MergeParams& params) {
  const size_t components = edgefront::connected_components(mesh).count;
  for (size_t rings = 1; rings <= params.max_trim_rings; ++rings) {
    std::optional<Trimmed> t = trimmed_copy(mesh, {A.vertices, B.vertices}, rings, components);
    if (!t) continue;
    const size_t la = t->rim_loop[0], lb = t->rim_loop[1];
    if (la == t->loops.size() || lb == t->loops.size() || la == lb) continue;
    const double extra_gap = 2.0 * static_cast<double>(rings) * params.mean_edge_length;
    if (merge_pair(t->mesh, cloud, t->loops[la], t->loops[lb], params, extra_gap) == PairMerge::merged) {
      mesh = std::move(t->mesh);
      return true;
    }
  }
  return false;
}

}  // namespace

size_t merge_border_loops(Mesh& mesh, const CloudQuery& cloud, const MergeParams& params) {
  std::vector<Loop> loops = border_loops(mesh);
  if (loops.size() < 2) return 0;
  std::vector<char> used(loops.size(), 0);
  size_t merged = 0;
  for (size_t ia = 0; ia < loops.size(); ++ia) {
    for (size_t ib = ia + 1; ib < loops.size() && !used[ia]; ++ib) {
      if (used[ib]) continue;
      const PairMerge m = merge_pair(mesh, cloud, loops[ia], loops[ib], params, 0.0);
      if (m == PairMerge::merged) {
        used[ia] = used[ib] = 1;
        ++merged;
      } else if (m == PairMerge::refused && params.max_trim_rings > 0 &&
                 trim_and_merge(mesh, cloud, loops[ia], loops[ib], params)) {
        return merged + 1;  // the trimming changed other loops' halfedges: the next pass sees them anew
      }
    }
  }
  return merged;
}

bool trim_and_close(Mesh& mesh, const Loop& loop, size_t rings, const std::function<bool(Mesh&, const Loop&)>& close) {
  const size_t components = edgefront::connected_components(mesh).count;
  for (size_t r = 1; r <= rings; ++r) {
    std::optional<Trimmed> t = trimmed_copy(mesh, {loop.vertices}, r, components);
    if (!t || t->rim_loop[0] == t->loops.size()) continue;
    if (close(t->mesh, t->loops[t->rim_loop[0]])) {
      mesh = std::move(t->mesh);
      return true;
    }
  }
  return false;
}

size_t fill_small_holes(Mesh& mesh, const CloudQuery& cloud, size_t max_vertices, double max_support_distance,
                        double min_normal_agreement, const TrimParams& trim) {
  size_t filled = 0;
  for (const Loop& loop : border_loops(mesh)) {
    const size_t n = loop.vertices.size();
    if (n < 3) continue;
    if (n <= max_vertices && fill_loop(mesh, cloud, loop, max_support_distance, min_normal_agreement)) {
      ++filled;
    } else if (trim.rings > 0 && loop.length <= trim.max_loop_length &&
               trim_and_close(mesh, loop, trim.rings, [&](Mesh& m, const Loop& wider) {
                 return fill_loop(m, cloud, wider, max_support_distance, min_normal_agreement);
               })) {
      return filled + 1;  // the trimming may have changed other loops' halfedges
    }
  }
  return filled;
}

std::vector<std::array<size_t, 3>> least_area_triangulation(const std::vector<Vec3>& points,
                                                           const std::function<bool(size_t, size_t)>& usable,
                                                           const std::vector<Vec3>& rim_normals) {
  const size_t n = points.size();
  if (n < 3) return {};
  const bool dihedral = rim_normals.size() == n;
  const auto chord_ok = [&](size_t i, size_t j) {  // the chord v_i v_j, i < j
    return j == i + 1 || (i == 0 && j == n - 1) || usable(i, j);
  };
  // The cost of a sub-polygon: (largest fold, area), compared in that order; without rim normals
  // the fold is 0 throughout and the area alone decides.
  using Cost = std::pair<double, double>;
  constexpr double kNone = std::numeric_limits<double>::infinity();
  std::vector<Cost> cost(n * n, {kNone, kNone});
  std::vector<size_t> split(n * n, 0);
  for (size_t i = 0; i + 1 < n; ++i) cost[i * n + i + 1] = {0, 0};
  // The fold between triangle normal `nt` and the face across its side (i, j): the rim face for a
  // loop side, else the sub-polygon's triangle on that side; 1 - cosine, in [0, 2].
  const auto fold = [&](const Vec3& nt, size_t i, size_t j) {
    Vec3 other;
    if (j == i + 1) {
      other = rim_normals[i];
    } else {
      const size_t k = split[i * n + j];
      other = tri_normal(points[i], points[k], points[j]);
    }
    const double l = nt.norm() * other.norm();
    return l > 0 ? 1.0 - (nt | other) / l : 2.0;
  };
  for (size_t len = 2; len < n; ++len) {
    for (size_t i = 0; i + len < n; ++i) {
      const size_t j = i + len;
      if (!chord_ok(i, j)) continue;
      for (size_t k = i + 1; k < j; ++k) {
        const Cost& a = cost[i * n + k];
        const Cost& b = cost[k * n + j];
        if (!(a.second < kNone) || !(b.second < kNone)) continue;
        const Vec3 nt = tri_normal(points[i], points[k], points[j]);
        const double area = nt.norm();
        if (!(area > 0)) continue;
        double worst = std::max(a.first, b.first);
        if (dihedral) {
          worst = std::max({worst, fold(nt, i, k), fold(nt, k, j)});
          if (i == 0 && j == n - 1) worst = std::max(worst, fold(nt, n - 1, n));  // the loop side v_n-1 v_0
        }
        const Cost c{worst, a.second + b.second + area};
        if (c < cost[i * n + j]) {
          cost[i * n + j] = c;
          split[i * n + j] = k;
        }
      }
    }
  }
  if (!(cost[n - 1].second < kNone)) return {};
  std::vector<std::array<size_t, 3>> tris;
  std::vector<std::pair<size_t, size_t>> todo{{0, n - 1}};
  while (!todo.empty()) {
    const auto [i, j] = todo.back();
    todo.pop_back();
    if (j < i + 2) continue;
    const size_t k = split[i * n + j];
    tris.push_back({i, k, j});
    todo.push_back({i, k});
    todo.push_back({k, j});
  }
  return tris;
}

namespace {

// Closes the simple loop `loop` by the triangulation of least total area over its vertices (see
// fill_small_holes_checked; least_area_triangulation), where a diagonal that is an edge of the
// mesh already cannot be used. Leaves the mesh unchanged and returns false when no triangulation
// passes the checks or OpenMesh refuses a face.
bool fill_loop_least_area(Mesh& mesh, const CloudQuery& cloud, const Loop& loop, double max_support_distance) {
  const size_t n = loop.vertices.size();
  if (n < 3 || !is_simple(loop)) return false;
  const auto p = [&](size_t k) { return mesh.point(loop.vertices[k]); };
  std::vector<Vec3> points;
  for (size_t k = 0; k < n; ++k) points.push_back(p(k));
  const std::vector<std::array<size_t, 3>> tris = least_area_triangulation(points, [&](size_t i, size_t j) {
    return !mesh.find_halfedge(loop.vertices[i], loop.vertices[j]).is_valid();
  });
  if (tris.empty()) return false;
  // Checks: on the cloud; along the loop, not folded back on the mean.
  double agreement = 0;
  for (const auto& t : tris) {
    const Vec3 nf = tri_normal(p(t[0]), p(t[1]), p(t[2]));
    if (cloud((p(t[0]) + p(t[1]) + p(t[2])) / 3.0).distance > max_support_distance) return false;
    for (size_t e = 0; e < 3; ++e) {
      const size_t a = t[e], b = t[(e + 1) % 3];
      if (!(b == a + 1 || (a == n - 1 && b == 0))) continue;  // a loop edge v_a -> v_a+1
      const FaceHandle adj = mesh.opposite_face_handle(loop.halfedges[a]);
      const Vec3 na = adj.is_valid() ? face_normal(mesh, adj) : Vec3(0, 0, 0);
      if (!(na.norm() > 0)) return false;
      agreement += (nf | na) / (nf.norm() * na.norm());
    }
  }
  if (!(agreement > 0)) return false;
  std::vector<std::array<VertexHandle, 3>> faces;
  for (const auto& t : tris) faces.push_back({loop.vertices[t[0]], loop.vertices[t[1]], loop.vertices[t[2]]});
  return add_all_or_none(mesh, faces);
}

}  // namespace

size_t fill_small_holes_checked(Mesh& mesh, const CloudQuery& cloud, size_t max_vertices, double max_support_distance,
                                double min_normal_agreement, const std::vector<char>& triangulate_at,
                                const std::function<bool(Mesh&)>& accept) {
  size_t filled = 0;
  for (const Loop& loop : border_loops(mesh)) {
    const size_t n = loop.vertices.size();
    if (n < 3 || n > max_vertices) continue;
    Mesh trial = mesh;
    if (fill_loop(trial, cloud, loop, max_support_distance, min_normal_agreement) && accept(trial)) {
      mesh = std::move(trial);
      ++filled;
      continue;
    }
    bool flagged = false;
    for (auto v : loop.vertices) {
      const size_t i = static_cast<size_t>(v.idx());
      flagged = flagged || (i < triangulate_at.size() && triangulate_at[i] != 0);
    }
    if (!flagged) continue;
    trial = mesh;
    if (fill_loop_least_area(trial, cloud, loop, max_support_distance) && accept(trial)) {
      mesh = std::move(trial);
      ++filled;
    }
  }
  return filled;
}

namespace {

// Zips the two halves of one simple loop of at least 6 vertices together (see fill_slit_holes).
bool fill_slit_loop(Mesh& mesh, const CloudQuery& cloud, const Loop& L, double max_support_distance,
                    double min_normal_agreement) {
  const size_t n = L.vertices.size();
  if (n < 6 || !is_simple(L)) return false;
  // Tips: the pairs of loop vertices half a loop apart, farthest apart first; the strip runs from
  // tip i along both sides of the loop to tip i + n/2.
  std::vector<std::pair<double, size_t>> tips;
  const size_t half = n / 2;
  for (size_t i = 0; i < half; ++i)
    tips.push_back({-(mesh.point(L.vertices[i]) - mesh.point(L.vertices[i + half])).norm(), i});
  std::sort(tips.begin(), tips.end());
  for (size_t t = 0; t < tips.size() && t < 3; ++t) {
    const long i0 = static_cast<long>(tips[t].second);
    const Strip strip{[&](size_t k) { return loop_vertex(L, i0 + long(k)); },
                      [&](size_t k) { return loop_vertex(L, i0 - 1 - long(k)); },
                      [&](size_t k) { return loop_halfedge(L, i0 + long(k)); },
                      [&](size_t k) { return loop_halfedge(L, i0 - 2 - long(k)); }, half, n - half - 2};
    if (zip_strip(mesh, cloud, strip, max_support_distance, min_normal_agreement)) return true;
  }
  return false;
}

}  // namespace

size_t fill_slit_holes(Mesh& mesh, const CloudQuery& cloud, size_t min_vertices, size_t max_vertices,
                       double max_support_distance, double min_normal_agreement, std::size_t trim_rings) {
  size_t filled = 0;
  for (const Loop& L : border_loops(mesh)) {
    const size_t n = L.vertices.size();
    if (n < std::max<size_t>(min_vertices, 6) || n > max_vertices) continue;
    if (fill_slit_loop(mesh, cloud, L, max_support_distance, min_normal_agreement)) {
      ++filled;
    } else if (trim_rings > 0 && trim_and_close(mesh, L, trim_rings, [&](Mesh& m, const Loop& wider) {
                 return fill_slit_loop(m, cloud, wider, max_support_distance, min_normal_agreement);
               })) {
      return filled + 1;  // the trimming may have changed other loops' halfedges
    }
  }
  return filled;
}

size_t zip_border_slits(Mesh& mesh, const CloudQuery& cloud, const ZipParams& params) {
  return twist::detail::zip_border_slits(mesh, distance_of(cloud), params);
}

}  // namespace gcs::detail
