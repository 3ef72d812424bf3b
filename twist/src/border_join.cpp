// Border chains joined by strips, small holes closed by fans (see detail/border_join.h). The GCS
// loop's border topology builds on these; the session's heal (heal.cpp) calls them on its mirror.

#include "detail/border_join.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <set>
#include <utility>

#include "edgefront/error.h"
#include "edgefront/mesh_stats.h"
#include "edgefront/point_index.h"

namespace twist::detail {

using edgefront::FaceHandle;
using edgefront::HalfedgeHandle;
using edgefront::Mesh;
using edgefront::Vec3;
using edgefront::VertexHandle;

namespace {

Vec3 tri_normal(const Vec3& a, const Vec3& b, const Vec3& c) { return (b - a) % (c - a); }

/// Twice the area along the unit normal of face f.
Vec3 face_normal(const Mesh& mesh, FaceHandle f) {
  auto it = mesh.cfv_iter(f);
  const Vec3 a = mesh.point(*it), b = mesh.point(*++it), c = mesh.point(*++it);
  return (b - a) % (c - a);
}

}  // namespace

std::vector<BorderLoop> border_loops(const Mesh& mesh) {
  std::vector<BorderLoop> loops;
  std::vector<char> seen(mesh.n_halfedges(), 0);
  for (auto h : mesh.halfedges()) {
    if (seen[h.idx()] || !mesh.is_boundary(h)) continue;
    BorderLoop loop;
    HalfedgeHandle g = h;
    do {
      seen[g.idx()] = 1;
      loop.halfedges.push_back(g);
      loop.vertices.push_back(mesh.from_vertex_handle(g));
      loop.length += mesh.calc_edge_length(g);
      g = mesh.next_halfedge_handle(g);
      EF_CHECK(loop.halfedges.size() <= mesh.n_halfedges(), "a border loop does not close");
    } while (g != h);
    loops.push_back(std::move(loop));
  }
  return loops;
}

// True when no vertex occurs twice on the loop.
bool is_simple(const BorderLoop& L) {
  std::set<int> distinct;
  for (auto v : L.vertices) distinct.insert(v.idx());
  return distinct.size() == L.vertices.size();
}

// Vertex k of a loop, k taken cyclically (may be negative).
VertexHandle loop_vertex(const BorderLoop& L, long k) {
  const long n = static_cast<long>(L.vertices.size());
  return L.vertices[static_cast<size_t>(((k % n) + n) % n)];
}

// Boundary halfedge k of a loop (from vertex k to vertex k + 1), k taken cyclically.
HalfedgeHandle loop_halfedge(const BorderLoop& L, long k) {
  const long n = static_cast<long>(L.halfedges.size());
  return L.halfedges[static_cast<size_t>(((k % n) + n) % n)];
}

// Adds the faces in order; when OpenMesh refuses one, removes those added and returns false (the
// mesh is then as before, up to the deleted faces' garbage).
bool add_all_or_none(Mesh& mesh, const std::vector<std::array<VertexHandle, 3>>& faces) {
  std::vector<FaceHandle> added;
  const MuteOpenMeshErrors mute;  // a refused face is handled here, not printed
  for (const auto& t : faces) {
    const FaceHandle f = mesh.add_face(t[0], t[1], t[2]);
    if (!f.is_valid()) {
      for (auto g : added) mesh.delete_face(g, false);
      return false;
    }
    added.push_back(f);
  }
  return true;
}

// Plans the zipper triangles of a strip (advancing on the side whose next diagonal is shorter),
// checks that every triangle is non-degenerate, lies within `max_support_distance` of the cloud and
// that the triangles agree with the faces they border (mean cosine >= min_normal_agreement), then
// adds them. Leaves the mesh unchanged and returns false when a check fails or OpenMesh refuses a
// face (a non-manifold result).
bool zip_strip(Mesh& mesh, const CloudDistance& cloud, const Strip& st, double max_support_distance,
               double min_normal_agreement) {
  struct Tri {
    VertexHandle a, b, c;
    HalfedgeHandle border;  // the loop halfedge the face closes
  };
  std::vector<Tri> plan;
  size_t i = 0, j = 0;
  while (i < st.nA || j < st.nB) {
    bool advance_a;
    if (i == st.nA) advance_a = false;
    else if (j == st.nB) advance_a = true;
    else
      advance_a = (mesh.point(st.a(i + 1)) - mesh.point(st.b(j))).sqrnorm() <=
                  (mesh.point(st.a(i)) - mesh.point(st.b(j + 1))).sqrnorm();
    if (advance_a) {
      plan.push_back({st.a(i), st.a(i + 1), st.b(j), st.ha(i)});
      ++i;
    } else {
      plan.push_back({st.b(j + 1), st.b(j), st.a(i), st.hb(j)});
      ++j;
    }
  }
  if (plan.empty()) return false;
  double agreement = 0;
  for (const Tri& t : plan) {
    if (t.a == t.c || t.b == t.c) return false;
    const Vec3 n = tri_normal(mesh.point(t.a), mesh.point(t.b), mesh.point(t.c));
    const FaceHandle adj = mesh.opposite_face_handle(t.border);
    const Vec3 m = adj.is_valid() ? face_normal(mesh, adj) : Vec3(0, 0, 0);
    const double ln = n.norm(), lm = m.norm();
    if (!(ln > 0) || !(lm > 0)) return false;
    agreement += (n | m) / (ln * lm);
    const Vec3 c = (mesh.point(t.a) + mesh.point(t.b) + mesh.point(t.c)) / 3.0;
    if (cloud(c) > max_support_distance) return false;
  }
  if (agreement / static_cast<double>(plan.size()) < min_normal_agreement) return false;
  std::vector<std::array<VertexHandle, 3>> faces;
  for (const Tri& t : plan) faces.push_back({t.a, t.b, t.c});
  return add_all_or_none(mesh, faces);
}

// True when the fan around the centroid of the simple loop `loop` (its own triangle for 3
// vertices) would close it: the centroid (written to `center`) lies within max_support_distance of
// the cloud and the fan agrees with the faces around (mean cosine >= min_normal_agreement; for 3
// vertices > min(0, min_normal_agreement)). See fill_small_holes.
bool fan_fits(const Mesh& mesh, const CloudDistance& cloud, const BorderLoop& loop, double max_support_distance,
              double min_normal_agreement, Vec3& center) {
  const size_t n = loop.vertices.size();
  if (n < 3 || !is_simple(loop)) return false;
  Vec3 c(0, 0, 0);
  for (auto v : loop.vertices) c += mesh.point(v);
  c /= static_cast<double>(n);
  center = c;
  if (cloud(c) > max_support_distance) return false;
  double agreement = 0;
  for (size_t k = 0; k < n; ++k) {
    const Vec3 nf = tri_normal(mesh.point(loop.vertices[k]), mesh.point(loop.vertices[(k + 1) % n]), c);
    const FaceHandle adj = mesh.opposite_face_handle(loop.halfedges[k]);
    const Vec3 na = adj.is_valid() ? face_normal(mesh, adj) : Vec3(0, 0, 0);
    if (!(nf.norm() > 0) || !(na.norm() > 0)) return false;
    agreement += (nf | na) / (nf.norm() * na.norm());
  }
  // A triangular hole (left where a thin neck was cut, e.g. between nested spheres) is closed by
  // its own triangle whenever that does not fold back over its neighbours (mean cosine > 0).
  return agreement / static_cast<double>(n) >= (n == 3 ? std::min(0.0, min_normal_agreement) : min_normal_agreement);
}

// Fills one simple border loop by a fan around its centroid (a triangle for 3 vertices) when the
// centroid lies on the cloud and the fan agrees with the faces around (see fill_small_holes).
bool fill_loop(Mesh& mesh, const CloudDistance& cloud, const BorderLoop& loop, double max_support_distance,
               double min_normal_agreement) {
  Vec3 c;
  if (!fan_fits(mesh, cloud, loop, max_support_distance, min_normal_agreement, c)) return false;
  const size_t n = loop.vertices.size();
  const MuteOpenMeshErrors mute;
  if (n == 3) return mesh.add_face(loop.vertices[0], loop.vertices[1], loop.vertices[2]).is_valid();
  const VertexHandle center = mesh.add_vertex(c);
  std::vector<FaceHandle> added;
  for (size_t k = 0; k < n; ++k) {
    const FaceHandle f = mesh.add_face(loop.vertices[k], loop.vertices[(k + 1) % n], center);
    if (!f.is_valid()) {
      for (auto g : added) mesh.delete_face(g, false);
      mesh.delete_vertex(center, false);
      return false;
    }
    added.push_back(f);
  }
  return true;
}

size_t zip_border_slits(Mesh& mesh, const CloudDistance& cloud, const ZipParams& params) {
  const double gap = params.max_gap_edges * params.mean_edge_length;
  if (!(gap > 0)) return 0;
  size_t zipped = 0;
  size_t attempts = 0;
  std::set<std::pair<int, int>> failed;  // seed vertex pairs whose strip was refused
  while (zipped < params.max_zips && attempts < 8 * params.max_zips) {
    const std::vector<BorderLoop> loops = border_loops(mesh);
    // Boundary vertex -> (loop, position); a vertex on two loops is skipped (not simple).
    std::vector<std::pair<int, long>> where;
    std::vector<Vec3> pts;
    std::vector<char> simple;
    for (size_t l = 0; l < loops.size(); ++l) {
      for (size_t k = 0; k < loops[l].vertices.size(); ++k) {
        where.push_back({static_cast<int>(l), static_cast<long>(k)});
        pts.push_back(mesh.point(loops[l].vertices[k]));
      }
    }
    if (pts.size() < 6) break;
    {
      std::vector<int> count(mesh.n_vertices(), 0);
      for (const auto& [l, k] : where) ++count[loop_vertex(loops[l], k).idx()];
      for (const auto& [l, k] : where) simple.push_back(count[loop_vertex(loops[l], k).idx()] == 1);
    }
    const edgefront::PointIndex index(pts);
    std::vector<int> component;
    if (params.only_across_components) component = edgefront::connected_components(mesh).vertex_component;
    const auto vertex_of = [&](size_t p) { return loop_vertex(loops[static_cast<size_t>(where[p].first)], where[p].second); };
    // Candidate seeds: close pairs of boundary vertices whose loops run opposite there.
    struct Seed {
      double d;
      size_t p, q;
    };
    std::vector<Seed> seeds;
    std::vector<size_t> near;
    const auto tangent = [&](size_t p) {
      const BorderLoop& L = loops[static_cast<size_t>(where[p].first)];
      return mesh.point(loop_vertex(L, where[p].second + 1)) - mesh.point(loop_vertex(L, where[p].second - 1));
    };
    for (size_t p = 0; p < pts.size(); ++p) {
      if (!simple[p]) continue;
      index.radius_search(pts[p], gap, near);
      for (const size_t q : near) {
        if (q <= p || !simple[q]) continue;
        const auto [lp, kp] = where[p];
        const auto [lq, kq] = where[q];
        if (lp != lq && !params.across_loops) continue;
        if (params.only_across_components && component[vertex_of(p).idx()] == component[vertex_of(q).idx()]) continue;
        if (lp == lq) {
          const long n = static_cast<long>(loops[static_cast<size_t>(lp)].vertices.size());
          const long d = std::abs(kp - kq);
          if (std::min(d, n - d) < static_cast<long>(params.min_loop_separation)) continue;
        }
        const VertexHandle vp = loop_vertex(loops[static_cast<size_t>(lp)], kp);
        const VertexHandle vq = loop_vertex(loops[static_cast<size_t>(lq)], kq);
        if (mesh.find_halfedge(vp, vq).is_valid() || failed.count({vp.idx(), vq.idx()})) continue;
        const Vec3 tp = tangent(p), tq = tangent(q);
        const double lt = tp.norm() * tq.norm();
        if (!(lt > 0) || (tp | tq) > -params.min_opposite_cos * lt) continue;
        seeds.push_back({(pts[p] - pts[q]).norm(), p, q});
      }
    }
    if (seeds.empty()) break;
    std::sort(seeds.begin(), seeds.end(), [](const Seed& x, const Seed& y) {
      return x.d < y.d || (x.d == y.d && (x.p < y.p || (x.p == y.p && x.q < y.q)));
    });
    bool done = false;
    for (const Seed& sd : seeds) {
      if (attempts >= 8 * params.max_zips) break;
      ++attempts;
      const BorderLoop& A = loops[static_cast<size_t>(where[sd.p].first)];
      const BorderLoop& B = loops[static_cast<size_t>(where[sd.q].first)];
      const long i0 = where[sd.p].second, j0 = where[sd.q].second;
      const bool same = &A == &B;
      const long n = static_cast<long>(A.vertices.size());
      // Extend the matched run both ways while the pairs stay within the gap and (same loop) the
      // two chains keep at least two loop vertices between them.
      const auto close = [&](long ia, long jb) {
        return (mesh.point(loop_vertex(A, ia)) - mesh.point(loop_vertex(B, jb))).norm() <= gap;
      };
      const auto apart = [&](long ia, long jb) {
        if (!same) return true;
        const long d = ((jb - ia) % n + n) % n;  // from a forward to b
        return d >= 2 && n - d >= 2;
      };
      const long limit = static_cast<long>(std::min(A.vertices.size(), B.vertices.size())) / 2;
      long back = 0, fwd = 0;
      while (back < limit && close(i0 - back - 1, j0 + back + 1) && apart(i0 - back - 1, j0 + back + 1) &&
             apart(i0 + fwd, j0 - fwd))
        ++back;
      while (fwd + back < limit && close(i0 + fwd + 1, j0 - fwd - 1) && apart(i0 + fwd + 1, j0 - fwd - 1)) ++fwd;
      if (same && !(apart(i0 - back, j0 + back) && apart(i0 + fwd, j0 - fwd))) {
        failed.insert({loop_vertex(A, i0).idx(), loop_vertex(B, j0).idx()});
        continue;
      }
      const long ia = i0 - back, jb = j0 + back;
      const size_t m = static_cast<size_t>(back + fwd);
      if (m == 0) {
        failed.insert({loop_vertex(A, i0).idx(), loop_vertex(B, j0).idx()});
        continue;
      }
      const Strip strip{[&](size_t i) { return loop_vertex(A, ia + long(i)); },
                        [&](size_t j) { return loop_vertex(B, jb - long(j)); },
                        [&](size_t i) { return loop_halfedge(A, ia + long(i)); },
                        [&](size_t j) { return loop_halfedge(B, jb - long(j) - 1); }, m, m};
      if (!zip_strip(mesh, cloud, strip, params.max_support_distance, params.min_normal_agreement)) {
        failed.insert({loop_vertex(A, i0).idx(), loop_vertex(B, j0).idx()});
        continue;
      }
      ++zipped;
      done = true;
      break;
    }
    if (!done) break;
  }
  return zipped;
}

}  // namespace twist::detail
