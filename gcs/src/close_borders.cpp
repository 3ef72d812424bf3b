#include "detail/close_borders.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
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

// The samples no face covers, with their oriented normals (empty without normals).
struct Uncovered {
  std::vector<Vec3> points, normals;
};

// The squared distance from x to the segment ab.
double segment_dist2(const Vec3& x, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double l2 = ab.sqrnorm();
  const double t = l2 > 0 ? std::clamp(((x - a) | ab) / l2, 0.0, 1.0) : 0.0;
  return (x - (a + t * ab)).sqrnorm();
}

// The samples no face covers, their normals turned to the mesh's orientation: farther than
// `covered_distance` from every face, or farther than `beyond_distance` with the nearest point of
// the mesh on a border edge (past the border), or (with normals) whose nearest face faces against
// them (the other side of a thin gap).
Uncovered uncovered_samples(const Mesh& mesh, const std::vector<Vec3>& samples, const std::vector<Vec3>& normals,
                            double covered_distance, double beyond_distance) {
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
  const double sign = agreement < 0 ? -1.0 : 1.0;
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
    if (covered && with_normals && normals[i].sqrnorm() > 0)
      covered = sign * (tris[static_cast<std::size_t>(hit.tri)].n | normals[i]) > 0;
    if (covered) continue;
    u.points.push_back(samples[i]);
    if (with_normals) u.normals.push_back(sign * normals[i]);
  }
  return u;
}

// Uncovered samples within `radius` of the loop's vertices (distinct).
std::size_t uncovered_near(const Mesh& mesh, const Loop& loop, const PointIndex& index, double radius) {
  std::vector<std::size_t> all, found;
  for (auto v : loop.vertices) {
    index.radius_search(mesh.point(v), radius, found);
    all.insert(all.end(), found.begin(), found.end());
  }
  std::sort(all.begin(), all.end());
  return static_cast<std::size_t>(std::unique(all.begin(), all.end()) - all.begin());
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
      if (len > max_len) longest.push_back({-len, e.idx()});
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
void pull_round(Mesh& mesh, const Patch& patch, const Uncovered& unc, const PointIndex& index, double ell,
                double reach) {
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
      if (with_normals && (unc.normals[s.index] | n) < kPullMinCos) continue;
      const double ws = 1.0 / (std::sqrt(s.distance2) + 0.1 * ell);
      c += ws * unc.points[s.index];
      if (with_normals) m += ws * unc.normals[s.index];
      w += ws;
    }
    Vec3 step;
    if (w > 0) {
      c /= w;
      const double lm = m.norm();
      step = lm > 0 ? -((p - c) | m) / (lm * lm) * m : c - p;
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

// The checks a patch must pass (see CloseBordersParams). A vertex's distance to the samples is
// its distance to the tangent plane of its nearest sample (with normals; else to that sample).
bool patch_fits(const Mesh& mesh, const Patch& patch, const Loop& loop, const PointIndex& all,
                const std::vector<Vec3>& normals, const CloseBordersParams& params) {
  const double ell = params.mean_edge_length;
  double sum = 0, dmax = 0;
  std::size_t count = 0, far = 0;
  for (auto v : mesh.vertices()) {
    if (mesh.status(v).deleted() || !patch.is_patch_vertex(v)) continue;
    const Vec3 p = mesh.point(v);
    const PointIndex::Neighbor s = all.nearest(p);
    const double d = std::sqrt(s.distance2);
    if (!(d <= params.max_sample_edges * ell)) ++far;
    const Vec3& n = normals.empty() ? Vec3(0, 0, 0) : normals[s.index];
    const double off = n.sqrnorm() > 0 ? std::abs((p - all.points()[s.index]) | n) / n.norm() : d;
    dmax = std::max(dmax, d);
    sum += off;
    ++count;
  }
  double cmin = 1, csum = 0;
  std::size_t folds = 0;
  bool degenerate = false;
  for (auto f : mesh.faces()) {
    if (!patch.is_patch_face(f)) continue;
    if (!(face_normal(mesh, f).norm() > 1e-12 * ell * ell)) degenerate = true;
  }
  for (auto h : loop.halfedges) {
    const FaceHandle inside = mesh.face_handle(h), outside = mesh.opposite_face_handle(h);
    if (!inside.is_valid() || !outside.is_valid()) return false;
    const Vec3 a = face_normal(mesh, inside), b = face_normal(mesh, outside);
    const double c = (a | b) / (a.norm() * b.norm());
    cmin = std::min(cmin, c);
    csum += c;
    folds += !(c >= params.min_rim_cos);
  }
  if (std::getenv("EF_CLOSE_DEBUG"))
    std::fprintf(stderr, "DBG  verts %zu far %zu max %.2f meanoff %.3f | rim min %.2f mean %.2f folds %zu deg %d\n", count,
                 far, dmax / ell, count ? sum / count / ell : 0.0, cmin, csum / loop.halfedges.size(), folds, degenerate);
  if (degenerate || far > 0 || folds > 0) return false;
  return count == 0 || sum / static_cast<double>(count) <= params.mean_sample_edges * ell;
}

// Closes `loop` on `mesh` by a patch (see the file comment); false when a step or check fails (the
// mesh is then a spoiled copy the caller drops).
bool close_loop(Mesh& mesh, const Loop& loop, const Uncovered& unc, const PointIndex& unc_index,
                const PointIndex& all, const std::vector<Vec3>& normals, const CloseBordersParams& params) {
  std::vector<Vec3> points;
  for (auto v : loop.vertices) points.push_back(mesh.point(v));
  const std::vector<std::array<std::size_t, 3>> tris = least_area_triangulation(points, [&](std::size_t i, std::size_t j) {
    return !mesh.find_halfedge(loop.vertices[i], loop.vertices[j]).is_valid();
  });
  if (tris.empty()) return false;
  const Patch patch{mesh.n_faces(), mesh.n_vertices()};
  std::vector<std::array<VertexHandle, 3>> faces;
  for (const auto& t : tris) faces.push_back({loop.vertices[t[0]], loop.vertices[t[1]], loop.vertices[t[2]]});
  if (!twist::detail::add_all_or_none(mesh, faces)) return false;
  const double ell = params.mean_edge_length;
  for (int round = 0; round < params.rounds; ++round) {
    if (round % kRefineEvery == 0) refine(mesh, patch, ell);
    pull_round(mesh, patch, unc, unc_index, ell, params.pull_edges * ell);
  }
  return patch_fits(mesh, patch, loop, all, normals, params);
}

void check(const CloseBordersParams& p, const std::vector<Vec3>& samples, const std::vector<Vec3>& normals) {
  const auto fail = [](const std::string& what) { throw edgefront::InvalidInput("close_false_borders: " + what); };
  if (!(std::isfinite(p.mean_edge_length) && p.mean_edge_length > 0)) fail("mean_edge_length must be finite and > 0");
  for (double d : {p.covered_edges, p.beyond_edges, p.near_edges, p.pull_edges, p.mean_sample_edges, p.max_sample_edges})
    if (!(std::isfinite(d) && d > 0)) fail("distances must be finite and > 0");
  if (!(p.min_uncovered_per_vertex >= 0) || !std::isfinite(p.min_uncovered_per_vertex))
    fail("min_uncovered_per_vertex must be finite and >= 0");
  if (!(p.min_rim_cos >= -1 && p.min_rim_cos <= 1)) fail("min_rim_cos must be in [-1, 1]");
  if (p.rounds < 0) fail("rounds must be >= 0");
  if (!normals.empty() && normals.size() != samples.size()) fail("normals do not match the samples");
}

}  // namespace

CloseBordersReport close_false_borders(Mesh& mesh, const std::vector<Vec3>& samples, const std::vector<Vec3>& normals,
                                       const CloseBordersParams& params) {
  check(params, samples, normals);
  CloseBordersReport report;
  const std::vector<Loop> loops = twist::detail::border_loops(mesh);
  report.loops = loops.size();
  if (loops.empty() || samples.empty()) return report;
  const double ell = params.mean_edge_length;
  const Uncovered unc = uncovered_samples(mesh, samples, normals, params.covered_edges * ell, params.beyond_edges * ell);
  if (unc.points.empty()) return report;
  const PointIndex unc_index(unc.points);
  const PointIndex all(samples);
  std::size_t crossings = self_intersecting_face_pairs(mesh).size();
  for (const Loop& loop : loops) {
    const std::size_t n = loop.vertices.size();
    if (n < 3 || n > params.max_loop_vertices || !twist::detail::is_simple(loop)) continue;
    const std::size_t near = uncovered_near(mesh, loop, unc_index, params.near_edges * ell);
    if (std::getenv("EF_CLOSE_DEBUG")) std::fprintf(stderr, "DBG loop n=%zu len/ell=%.1f near=%zu unc=%zu\n", n, loop.length / ell, near, unc.points.size());
    if (static_cast<double>(near) < params.min_uncovered_per_vertex * static_cast<double>(n)) continue;
    ++report.false_loops;
    Mesh trial = mesh;
    if (!close_loop(trial, loop, unc, unc_index, all, normals, params)) { if (std::getenv("EF_CLOSE_DEBUG")) std::fprintf(stderr, "DBG  refused\n"); continue; }
    const std::size_t after = self_intersecting_face_pairs(trial).size();
    if (std::getenv("EF_CLOSE_DEBUG")) std::fprintf(stderr, "DBG  crossings %zu -> %zu\n", crossings, after);
    if (after > crossings) continue;
    crossings = after;
    report.vertices_added += trial.n_vertices() - mesh.n_vertices();
    mesh = std::move(trial);
    ++report.closed;
  }
  return report;
}

}  // namespace gcs::detail
