#include "detail/close_borders.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "detail/border_topology.h"
#include "detail/self_intersection.h"
#include "edgefront/error.h"
#include "edgefront/geometry.h"
#include "edgefront/point_index.h"
#include "edgefront/triangle_bvh.h"

namespace gcs::detail {

using edgefront::EdgeHandle;
using edgefront::FaceHandle;
using edgefront::HalfedgeHandle;
using edgefront::Mesh;
using edgefront::PointIndex;
using edgefront::Vec3;
using edgefront::VertexHandle;

namespace {

using Loop = twist::detail::BorderLoop;

// Patch edges longer than this many mean edge lengths are split (refinement to the mesh's scale).
constexpr double kSplitEdges = 4.0 / 3.0;
// Passes of splits and of Delaunay flips per refinement.
constexpr int kRefinePasses = 12;
constexpr int kFlipPasses = 20;
// Every this many pull rounds the patch is refined again (it grows as it bulges onto the samples).
constexpr int kRefineEvery = 8;
// A pull moves a vertex at most this many mean edge lengths per round; the smoothing moves it by
// this share of its tangential Laplacian.
constexpr double kStepEdges = 0.25;
constexpr double kSmoothRate = 0.5;
// Samples pulling a patch vertex: the nearest uncovered ones (at most this many), facing the
// vertex's way (cosine above kPullMinCos) when the cloud has normals.
constexpr std::size_t kPullSamples = 8;
constexpr double kPullMinCos = 0.2;
// The share of the way toward the pulling samples' centroid along their plane a pull goes.
constexpr double kPullTangential = 0.25;

// The samples no face covers, with their normals (turned to face the mesh's way when oriented;
// empty without normals) and their distances to the mesh.
struct Uncovered {
  std::vector<Vec3> points, normals;
  std::vector<double> distance;  // to the mesh
  double sign = 1;  // the samples' normals times this face the mesh's way
};

// The squared distance from x to the segment ab.
double segment_dist2(const Vec3& x, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double l2 = ab.sqrnorm();
  const double t = l2 > 0 ? std::clamp(((x - a) | ab) / l2, 0.0, 1.0) : 0.0;
  return (x - (a + t * ab)).sqrnorm();
}

// A sample's normal `sn` as it faces a patch vertex of normal n: as it is when the normals are
// oriented, else turned to n's side.
Vec3 facing(const Vec3& sn, const Vec3& n, bool oriented) { return oriented || (sn | n) >= 0 ? sn : -sn; }

// The samples no face covers, their normals turned to the mesh's orientation: farther than
// `covered_distance` from every face, or farther than `beyond_distance` with the nearest point of
// the mesh on a border edge (past the border), or (with normals) whose nearest face faces against
// them (the other side of a thin gap).
Uncovered uncovered_samples(const Mesh& mesh, const std::vector<Vec3>& samples, const std::vector<Vec3>& normals,
                            bool oriented, double covered_distance, double beyond_distance) {
  Uncovered u;
  std::vector<edgefront::Triangle> tris;
  std::vector<std::array<bool, 3>> border_side;  // side k: corners k, k + 1
  for (auto f : mesh.faces()) {
    tris.push_back(edgefront::face_triangle(mesh, f));
    std::array<bool, 3> side{};
    for (int k = 0; k < 3; ++k) {
      const HalfedgeHandle h =
          mesh.find_halfedge(VertexHandle(tris.back().v[static_cast<std::size_t>(k)]),
                             VertexHandle(tris.back().v[static_cast<std::size_t>((k + 1) % 3)]));
      side[static_cast<std::size_t>(k)] = h.is_valid() && mesh.is_boundary(mesh.edge_handle(h));
    }
    border_side.push_back(side);
  }
  if (tris.empty()) return u;
  const edgefront::TriangleBvh bvh(tris);
  const bool with_normals = !normals.empty();
  // The orientation of the mesh against the normals: the sign of the summed agreement of the
  // samples' nearest faces.
  std::vector<edgefront::TriangleBvh::Hit> hits(samples.size());
  double agreement = 0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    hits[i] = bvh.nearest(samples[i]);
    if (with_normals && hits[i].tri >= 0) agreement += tris[static_cast<std::size_t>(hits[i].tri)].n | normals[i];
  }
  const double sign = oriented && agreement < 0 ? -1.0 : 1.0;
  u.sign = sign;
  const double c2 = covered_distance * covered_distance, b2 = beyond_distance * beyond_distance;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const edgefront::TriangleBvh::Hit& hit = hits[i];
    bool covered = hit.tri >= 0 && hit.dist2 <= c2;
    if (covered && hit.dist2 > b2) {  // past a border edge?
      const std::size_t t = static_cast<std::size_t>(hit.tri);
      for (std::size_t k = 0; k < 3 && covered; ++k) {
        if (!border_side[t][k]) continue;
        const double d2 = segment_dist2(samples[i], tris[t].p[k], tris[t].p[(k + 1) % 3]);
        covered = d2 > hit.dist2 * (1 + 1e-9);
      }
    }
    if (covered && with_normals && oriented && normals[i].sqrnorm() > 0)
      covered = sign * (tris[static_cast<std::size_t>(hit.tri)].n | normals[i]) > 0;
    if (covered) continue;
    u.points.push_back(samples[i]);
    u.distance.push_back(std::sqrt(hit.dist2));
    if (with_normals) u.normals.push_back(sign * normals[i]);
  }
  return u;
}

// Uncovered samples within `radius` of the loop's vertices (distinct indices).
std::vector<std::size_t> uncovered_near(const Mesh& mesh, const Loop& loop, const PointIndex& index, double radius) {
  std::vector<std::size_t> all, found;
  for (auto v : loop.vertices) {
    index.radius_search(mesh.point(v), radius, found);
    all.insert(all.end(), found.begin(), found.end());
  }
  std::sort(all.begin(), all.end());
  all.erase(std::unique(all.begin(), all.end()), all.end());
  return all;
}

// A patch: the faces and vertices added to the mesh after it had f0 faces and v0 vertices.
struct Patch {
  std::size_t f0 = 0, v0 = 0;
  bool is_patch_face(FaceHandle f) const { return f.is_valid() && static_cast<std::size_t>(f.idx()) >= f0; }
  bool is_patch_vertex(VertexHandle v) const { return static_cast<std::size_t>(v.idx()) >= v0; }
  // An edge with patch faces on both sides (the rim's edges have an old face on one side).
  bool inner(const Mesh& mesh, EdgeHandle e) const {
    return is_patch_face(mesh.face_handle(mesh.halfedge_handle(e, 0))) &&
           is_patch_face(mesh.face_handle(mesh.halfedge_handle(e, 1)));
  }
};

// The angle at the vertex opposite halfedge h in its face.
double opposite_angle(const Mesh& mesh, HalfedgeHandle h) {
  const Vec3 a = mesh.point(mesh.from_vertex_handle(h)), b = mesh.point(mesh.to_vertex_handle(h));
  const Vec3 c = mesh.point(mesh.to_vertex_handle(mesh.next_halfedge_handle(h)));
  const Vec3 u = a - c, w = b - c;
  const double nu = u.norm(), nw = w.norm();
  if (!(nu > 0 && nw > 0)) return std::numbers::pi;
  return std::acos(std::clamp((u | w) / (nu * nw), -1.0, 1.0));
}

// Splits the patch's inner edges longer than kSplitEdges mean edge lengths (longest first) and
// flips its inner edges toward a Delaunay triangulation.
void refine(Mesh& mesh, const Patch& patch, double ell) {
  const double max_len = kSplitEdges * ell;
  for (int pass = 0; pass < kRefinePasses; ++pass) {
    std::vector<std::pair<double, int>> longest;
    for (auto e : mesh.edges()) {
      if (mesh.status(e).deleted() || !patch.inner(mesh, e)) continue;
      const double len = mesh.calc_edge_length(e);
      // A chord between two rim vertices is split whatever its length: a face with three rim
      // vertices (an ear) could not move onto the samples.
      const HalfedgeHandle h = mesh.halfedge_handle(e, 0);
      const bool chord = !patch.is_patch_vertex(mesh.from_vertex_handle(h)) && !patch.is_patch_vertex(mesh.to_vertex_handle(h));
      if (len > max_len || chord) longest.push_back({-len, e.idx()});
    }
    if (longest.empty()) break;
    std::sort(longest.begin(), longest.end());
    for (const auto& [neg_len, idx] : longest) {
      const EdgeHandle e(idx);
      const HalfedgeHandle h = mesh.halfedge_handle(e, 0);
      const Vec3 mid = 0.5 * (mesh.point(mesh.from_vertex_handle(h)) + mesh.point(mesh.to_vertex_handle(h)));
      mesh.split(e, mid);
    }
    for (int flips = 0; flips < kFlipPasses; ++flips) {
      bool any = false;
      for (auto e : mesh.edges()) {
        if (mesh.status(e).deleted() || !patch.inner(mesh, e) || !mesh.is_flip_ok(e)) continue;
        const HalfedgeHandle h0 = mesh.halfedge_handle(e, 0), h1 = mesh.halfedge_handle(e, 1);
        if (!patch.is_patch_vertex(mesh.to_vertex_handle(mesh.next_halfedge_handle(h0))) &&
            !patch.is_patch_vertex(mesh.to_vertex_handle(mesh.next_halfedge_handle(h1))))
          continue;  // the flip would make a chord between rim vertices
        if (opposite_angle(mesh, h0) + opposite_angle(mesh, h1) <= std::numbers::pi + 1e-9) continue;
        mesh.flip(e);
        any = true;
      }
      if (!any) break;
    }
  }
}

// The area-weighted normal of vertex v (unit; zero when undefined).
Vec3 vertex_normal(const Mesh& mesh, VertexHandle v) {
  Vec3 n(0, 0, 0);
  for (auto f : mesh.vf_range(v)) n += face_normal(mesh, f);
  const double len = n.norm();
  return len > 0 ? n / len : Vec3(0, 0, 0);
}

Vec3 neighbour_mean(const Mesh& mesh, VertexHandle v) {
  Vec3 sum(0, 0, 0);
  int k = 0;
  for (auto u : mesh.vv_range(v)) {
    sum += mesh.point(u);
    ++k;
  }
  return k > 0 ? sum / static_cast<double>(k) : mesh.point(v);
}

// One round: every patch vertex is pulled toward the plane of the uncovered samples nearest to it
// (or, with none within reach, toward its neighbours' mean), then smoothed tangentially.
void pull_round(Mesh& mesh, const Patch& patch, const Uncovered& unc, bool oriented, const PointIndex& index,
                double ell, double reach) {
  std::vector<VertexHandle> verts;
  for (auto v : mesh.vertices())
    if (!mesh.status(v).deleted() && patch.is_patch_vertex(v)) verts.push_back(v);
  const bool with_normals = !unc.normals.empty();
  const double max_step = kStepEdges * ell;
  std::vector<PointIndex::Neighbor> near;
  std::vector<Vec3> moved(verts.size());
  for (std::size_t k = 0; k < verts.size(); ++k) {
    const VertexHandle v = verts[k];
    const Vec3 p = mesh.point(v);
    const Vec3 n = vertex_normal(mesh, v);
    index.k_nearest(p, kPullSamples, near);
    Vec3 c(0, 0, 0), m(0, 0, 0);
    double w = 0;
    for (const PointIndex::Neighbor& s : near) {
      if (s.distance2 > reach * reach) break;
      const Vec3 sn = with_normals ? facing(unc.normals[s.index], n, oriented) : Vec3(0, 0, 0);
      if (with_normals && (sn | n) < kPullMinCos) continue;
      const double ws = 1.0 / (std::sqrt(s.distance2) + 0.1 * ell);
      c += ws * unc.points[s.index];
      m += ws * sn;
      w += ws;
    }
    Vec3 step;
    if (w > 0) {
      c /= w;
      const double lm = m.norm();
      // Onto the samples' plane, and a part of the way toward them along it (past a rim the patch
      // must turn onto the missing surface; all the way, the vertices would clump on the samples).
      step = c - p;
      if (lm > 0) {
        const Vec3 normal_part = ((c - p) | m) / (lm * lm) * m;
        step = normal_part + kPullTangential * (step - normal_part);
      }
    } else {
      step = 0.5 * (neighbour_mean(mesh, v) - p);
    }
    const double len = step.norm();
    if (len > max_step) step *= max_step / len;
    moved[k] = p + step;
  }
  for (std::size_t k = 0; k < verts.size(); ++k) mesh.point(verts[k]) = moved[k];
  for (std::size_t k = 0; k < verts.size(); ++k) {
    const VertexHandle v = verts[k];
    const Vec3 n = vertex_normal(mesh, v);
    Vec3 l = neighbour_mean(mesh, v) - mesh.point(v);
    l -= (l | n) * n;
    moved[k] = mesh.point(v) + kSmoothRate * l;
  }
  for (std::size_t k = 0; k < verts.size(); ++k) mesh.point(verts[k]) = moved[k];
}

// One fairing round: every patch vertex moves by kSmoothRate of its Laplacian (which unfolds
// folds the pull left), then onto the tangent plane of its nearest sample that faces its way (with
// normals; else toward that sample), at most kStepEdges mean edge lengths in all.
void fair_round(Mesh& mesh, const Patch& patch, const PointIndex& all, const std::vector<Vec3>& normals,
                bool oriented, double sign, double ell) {
  std::vector<VertexHandle> verts;
  for (auto v : mesh.vertices())
    if (!mesh.status(v).deleted() && patch.is_patch_vertex(v)) verts.push_back(v);
  std::vector<Vec3> moved(verts.size());
  for (std::size_t k = 0; k < verts.size(); ++k) {
    const VertexHandle v = verts[k];
    moved[k] = mesh.point(v) + kSmoothRate * (neighbour_mean(mesh, v) - mesh.point(v));
  }
  for (std::size_t k = 0; k < verts.size(); ++k) mesh.point(verts[k]) = moved[k];
  std::vector<PointIndex::Neighbor> near;
  const double max_step = kStepEdges * ell;
  for (std::size_t k = 0; k < verts.size(); ++k) {
    const VertexHandle v = verts[k];
    const Vec3 p = mesh.point(v);
    const Vec3 n = vertex_normal(mesh, v);
    all.k_nearest(p, kPullSamples, near);
    Vec3 step(0, 0, 0);
    for (const PointIndex::Neighbor& s : near) {
      const Vec3& q = all.points()[s.index];
      if (normals.empty()) {
        step = q - p;
        break;
      }
      const Vec3 sn = facing(sign * normals[s.index], n, oriented);
      if ((sn | n) < kPullMinCos) continue;
      step = -((p - q) | sn) / sn.sqrnorm() * sn;
      break;
    }
    const double len = step.norm();
    if (len > max_step) step *= max_step / len;
    moved[k] = p + step;
  }
  for (std::size_t k = 0; k < verts.size(); ++k) mesh.point(verts[k]) = moved[k];
}

// The rim sides whose patch face folds against the face beyond (cosine below `min_cos`).
std::size_t rim_folds(const Mesh& mesh, const Loop& loop, double min_cos) {
  std::size_t folds = 0;
  for (auto h : loop.halfedges) {
    const FaceHandle inside = mesh.face_handle(h), outside = mesh.opposite_face_handle(h);
    if (!inside.is_valid() || !outside.is_valid()) continue;
    const Vec3 a = face_normal(mesh, inside), b = face_normal(mesh, outside);
    folds += !((a | b) >= min_cos * a.norm() * b.norm());
  }
  return folds;
}

// Unfolds the rim: the patch vertex of a patch face that folds against the face beyond its rim
// side (a, b) is moved to a + b - q, q the third corner of that face (the old surface continued
// across the side), averaged over its folded sides.
void unfold_rim(Mesh& mesh, const Patch& patch, const Loop& loop) {
  std::vector<std::pair<int, Vec3>> targets;
  for (auto h : loop.halfedges) {
    const FaceHandle inside = mesh.face_handle(h), outside = mesh.opposite_face_handle(h);
    if (!inside.is_valid() || !outside.is_valid()) continue;
    const Vec3 na = face_normal(mesh, inside), nb = face_normal(mesh, outside);
    if ((na | nb) >= 0) continue;
    const VertexHandle p = mesh.to_vertex_handle(mesh.next_halfedge_handle(h));
    if (!patch.is_patch_vertex(p)) continue;
    const VertexHandle q = mesh.to_vertex_handle(mesh.next_halfedge_handle(mesh.opposite_halfedge_handle(h)));
    targets.push_back({p.idx(), mesh.point(mesh.from_vertex_handle(h)) + mesh.point(mesh.to_vertex_handle(h)) - mesh.point(q)});
  }
  std::sort(targets.begin(), targets.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  for (std::size_t i = 0; i < targets.size();) {
    std::size_t j = i;
    Vec3 sum(0, 0, 0);
    for (; j < targets.size() && targets[j].first == targets[i].first; ++j) sum += targets[j].second;
    mesh.point(VertexHandle(targets[i].first)) = sum / static_cast<double>(j - i);
    i = j;
  }
}

double square(double x) { return x * x; }

// The checks a patch must pass (see CloseBordersParams). A vertex's distance to the samples is
// its distance to the tangent plane of its nearest sample (with a normal; else to that sample).
bool patch_fits(const Mesh& mesh, const Patch& patch, const Loop& loop, const PointIndex& all,
                const std::vector<Vec3>& normals, const CloseBordersParams& params) {
  const double ell = params.mean_edge_length;
  for (auto h : loop.halfedges)
    if (!mesh.face_handle(h).is_valid() || !mesh.opposite_face_handle(h).is_valid()) return false;
  if (static_cast<double>(rim_folds(mesh, loop, params.min_rim_cos)) >
      params.max_fold_fraction * static_cast<double>(loop.halfedges.size()))
    return false;
  // No degenerate face, and no face spanning a gap between samples (its vertices on two parts).
  for (auto f : mesh.faces()) {
    if (!patch.is_patch_face(f)) continue;
    if (!(face_normal(mesh, f).norm() > 1e-12 * ell * ell)) return false;
    if (!(all.nearest(centroid(mesh, f)).distance2 <= square(params.max_sample_edges * ell))) return false;
  }
  double sum = 0;
  std::size_t count = 0;
  for (auto v : mesh.vertices()) {
    if (mesh.status(v).deleted() || !patch.is_patch_vertex(v)) continue;
    const Vec3 p = mesh.point(v);
    const PointIndex::Neighbor s = all.nearest(p);
    const double d = std::sqrt(s.distance2);
    if (!(d <= params.max_sample_edges * ell)) return false;
    const Vec3& n = normals.empty() ? Vec3(0, 0, 0) : normals[s.index];
    sum += n.sqrnorm() > 0 ? std::abs((p - all.points()[s.index]) | n) / n.norm() : d;
    ++count;
  }
  return count == 0 || sum / static_cast<double>(count) <= params.mean_sample_edges * ell;
}

// What every loop's closing reads: the cloud, its index and normals, the parameters.
struct Context {
  const std::vector<Vec3>& samples;
  const std::vector<Vec3>& normals;
  const PointIndex& all;
  const CloseBordersParams& params;
};

// The samples no face of `mesh` covers (uncovered_samples under the parameters), with their index.
struct UncoveredSet {
  Uncovered samples;
  PointIndex index;
  UncoveredSet(const Mesh& mesh, const Context& ctx)
      : samples(uncovered_samples(mesh, ctx.samples, ctx.normals, ctx.params.normals_oriented,
                                  ctx.params.covered_edges * ctx.params.mean_edge_length,
                                  ctx.params.beyond_edges * ctx.params.mean_edge_length)),
        index(samples.points) {}
};

// Closes `loop` on `mesh` by a patch (see the file comment) pulled onto `uncovered` (the samples
// `mesh` leaves uncovered) when the patch fits and makes no more than `crossings` self-intersecting
// face pairs in all; then `crossings` is the count after it. False when a step or check fails
// (the mesh is then a spoiled copy the caller drops).
bool close_loop(Mesh& mesh, const Loop& loop, const Context& ctx, const UncoveredSet& uncovered, std::size_t& crossings) {
  const CloseBordersParams& params = ctx.params;
  const double ell = params.mean_edge_length;
  const Uncovered& unc = uncovered.samples;
  const PointIndex& unc_index = uncovered.index;
  if (unc.points.empty()) return false;
  std::vector<Vec3> points, rim_normals;
  for (auto v : loop.vertices) points.push_back(mesh.point(v));
  for (auto h : loop.halfedges) {
    const FaceHandle f = mesh.opposite_face_handle(h);
    rim_normals.push_back(f.is_valid() ? face_normal(mesh, f) : Vec3(0, 0, 0));
  }
  const std::vector<std::array<std::size_t, 3>> tris = least_area_triangulation(
      points, [&](std::size_t i, std::size_t j) { return !mesh.find_halfedge(loop.vertices[i], loop.vertices[j]).is_valid(); },
      rim_normals);
  if (tris.empty()) return false;
  const Patch patch{mesh.n_faces(), mesh.n_vertices()};
  std::vector<std::array<VertexHandle, 3>> faces;
  for (const auto& t : tris) faces.push_back({loop.vertices[t[0]], loop.vertices[t[1]], loop.vertices[t[2]]});
  if (!twist::detail::add_all_or_none(mesh, faces)) return false;
  const std::size_t max_vertices = params.max_patch_vertices_per_loop_vertex * loop.vertices.size() + 16;
  for (int round = 0; round < params.rounds; ++round) {
    if (round % kRefineEvery == 0) {
      refine(mesh, patch, ell);
      if (mesh.n_vertices() - patch.v0 > max_vertices) return false;  // a balloon, not a tear
    }
    if (round < params.rounds / 2) {
      pull_round(mesh, patch, unc, params.normals_oriented, unc_index, ell, params.pull_edges * ell);
    } else {
      unfold_rim(mesh, patch, loop);
      fair_round(mesh, patch, ctx.all, ctx.normals, params.normals_oriented, unc.sign, ell);
    }
  }
  if (!patch_fits(mesh, patch, loop, ctx.all, ctx.normals, params)) return false;
  const std::size_t after = self_intersecting_face_pairs(mesh).size();
  if (after > crossings) return false;
  crossings = after;
  return true;
}

// Whether the loop's halfedges are all still live border halfedges (a trim for another loop may
// have taken faces along it).
bool still_border(const Mesh& mesh, const Loop& loop) {
  for (auto h : loop.halfedges)
    if (mesh.status(h).deleted() || !mesh.is_boundary(h)) return false;
  return true;
}

void check(const CloseBordersParams& p, const std::vector<Vec3>& samples, const std::vector<Vec3>& normals) {
  const auto fail = [](const std::string& what) { throw edgefront::InvalidInput("close_false_borders: " + what); };
  if (!(std::isfinite(p.mean_edge_length) && p.mean_edge_length > 0)) fail("mean_edge_length must be finite and > 0");
  for (double d : {p.covered_edges, p.beyond_edges, p.near_edges, p.wide_edges, p.deep_edges, p.pull_edges,
                   p.mean_sample_edges, p.max_sample_edges})
    if (!(std::isfinite(d) && d > 0)) fail("distances must be finite and > 0");
  if (!(p.min_uncovered_per_vertex >= 0) || !std::isfinite(p.min_uncovered_per_vertex) ||
      !(p.min_deep_per_vertex >= 0) || !std::isfinite(p.min_deep_per_vertex))
    fail("min_uncovered_per_vertex and min_deep_per_vertex must be finite and >= 0");
  if (!(p.min_rim_cos >= -1 && p.min_rim_cos <= 1)) fail("min_rim_cos must be in [-1, 1]");
  if (!(p.max_fold_fraction >= 0 && p.max_fold_fraction <= 1)) fail("max_fold_fraction must be in [0, 1]");
  if (p.rounds < 0) fail("rounds must be >= 0");
  if (!normals.empty() && normals.size() != samples.size()) fail("normals do not match the samples");
}

}  // namespace

CloseBordersReport close_false_borders(Mesh& mesh, const std::vector<Vec3>& samples,
                                       const std::vector<Vec3>& sample_normals, const CloseBordersParams& params) {
  check(params, samples, sample_normals);
  // Unusable normals (not finite) are taken as none (zero).
  std::vector<Vec3> normals = sample_normals;
  for (Vec3& n : normals)
    if (!std::isfinite(n.sqrnorm())) n = Vec3(0, 0, 0);
  CloseBordersReport report;
  const std::vector<Loop> loops = twist::detail::border_loops(mesh);
  report.loops = loops.size();
  if (loops.empty() || samples.empty()) return report;
  const double ell = params.mean_edge_length;
  const PointIndex all(samples);
  const Context ctx{samples, normals, all, params};
  // The samples the mesh leaves uncovered: computed again only when a loop was closed.
  std::optional<UncoveredSet> uncovered(std::in_place, mesh, ctx);
  if (uncovered->samples.points.empty()) return report;
  std::size_t crossings = self_intersecting_face_pairs(mesh).size();
  for (const Loop& loop : loops) {
    const std::size_t n = loop.vertices.size();
    if (n < 3 || n > params.max_loop_vertices || !twist::detail::is_simple(loop) || !still_border(mesh, loop)) continue;
    // False: uncovered samples near it, and some of them farther than an edge or so from the
    // mesh (the cloud goes on past the border; an open sheet's cloud ends within about an edge).
    if (!uncovered) uncovered.emplace(mesh, ctx);
    const std::size_t near = uncovered_near(mesh, loop, uncovered->index, params.near_edges * ell).size();
    std::size_t deep = 0;
    for (std::size_t i : uncovered_near(mesh, loop, uncovered->index, params.wide_edges * ell))
      deep += uncovered->samples.distance[i] > params.deep_edges * ell;
    if (static_cast<double>(near) < params.min_uncovered_per_vertex * static_cast<double>(n) ||
        static_cast<double>(deep) < params.min_deep_per_vertex * static_cast<double>(n))
      continue;
    ++report.false_loops;
    const std::size_t before = mesh.n_vertices();
    Mesh trial = mesh;
    if (close_loop(trial, loop, ctx, *uncovered, crossings)) {
      mesh = std::move(trial);
    } else if (params.trim_rings == 0 ||
               !trim_and_close(mesh, loop, params.trim_rings, [&](Mesh& m, const Loop& l) {
                 return close_loop(m, l, ctx, UncoveredSet(m, ctx), crossings);  // the trim uncovered more
               })) {
      continue;
    }
    uncovered.reset();  // the patch covers samples now
    report.vertices_added += mesh.n_vertices() - before;
    ++report.closed;
  }
  return report;
}

}  // namespace gcs::detail
