// Self-intersecting face pairs (gcs::count_self_intersections) and the mesh's validity
// (gcs::mesh_validity; also part of gcs::evaluate). Shared parts: detail/evaluation_common.h.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

#include "detail/evaluation_common.h"
#include "detail/self_intersection.h"
#include "edgefront/error.h"
#include "edgefront/mesh_stats.h"
#include "edgefront/parallel.h"
#include "gcs/evaluation.h"

namespace gcs {

using detail::eval::check_mesh_coordinates;
using detail::eval::kInf;
using detail::eval::mesh_triangles;
using detail::eval::Triangle;
using detail::eval::TriangleBvh;
using edgefront::Mesh;
using edgefront::Vec3;

namespace {

// ---------------------------------------------------------------------------------------------
// Self-intersections

// Tolerances of the intersection predicates for a pair of triangles: lengths below `len` and
// (doubled) areas below `area` count as zero. Relative to the size and position of the pair, so
// that exactly planar or rounding-level coplanar configurations are handled as coplanar.
struct Tolerance {
  double len = 0, area = 0;
};

Tolerance tolerance_of(const Triangle& t1, const Triangle& t2) {
  double extent = 0, magnitude = 0;
  for (const Triangle* t : {&t1, &t2}) {
    for (int i = 0; i < 3; ++i) {
      extent = std::max(
          extent, (t->p[static_cast<std::size_t>(i)] - t->p[static_cast<std::size_t>((i + 1) % 3)]).norm());
      magnitude = std::max(magnitude, t->p[static_cast<std::size_t>(i)].max_abs());
    }
  }
  Tolerance tol;
  tol.len = 1e-12 * (extent + magnitude);
  tol.area = tol.len * extent;
  return tol;
}

// 2D helpers on the plane projection that drops axis `drop`.
struct P2 {
  double x, y;
};
P2 project(const Vec3& p, int drop) {
  const int i = drop == 0 ? 1 : 0, j = drop == 2 ? 1 : 2;
  return {p[i], p[j]};
}
double orient2(const P2& a, const P2& b, const P2& c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}
int sign(double v, double tol) { return v > tol ? 1 : (v < -tol ? -1 : 0); }

bool point_in_triangle_2d(const P2& p, const P2& a, const P2& b, const P2& c, double tol) {
  const double area = orient2(a, b, c);
  const double s = area >= 0 ? 1.0 : -1.0;  // make the triangle counter-clockwise
  return s * orient2(a, b, p) >= -tol && s * orient2(b, c, p) >= -tol && s * orient2(c, a, p) >= -tol;
}

bool segments_intersect_2d(const P2& p, const P2& q, const P2& a, const P2& b, double tol) {
  const int o1 = sign(orient2(p, q, a), tol), o2 = sign(orient2(p, q, b), tol);
  const int o3 = sign(orient2(a, b, p), tol), o4 = sign(orient2(a, b, q), tol);
  if (o1 * o2 < 0 && o3 * o4 < 0) return true;
  auto on_segment = [&](const P2& u, const P2& v, const P2& w, int o) {  // w on segment uv (collinear)
    return o == 0 && std::min(u.x, v.x) - tol <= w.x && w.x <= std::max(u.x, v.x) + tol &&
           std::min(u.y, v.y) - tol <= w.y && w.y <= std::max(u.y, v.y) + tol;
  };
  // Touching or collinear overlap: an endpoint on the other segment. `tol` is an area here; the
  // box slack uses it as a length too, which is only more permissive at rounding level.
  return on_segment(p, q, a, o1) || on_segment(p, q, b, o2) || on_segment(a, b, p, o3) ||
         on_segment(a, b, q, o4);
}

int dominant_axis(const Vec3& n) {
  const double ax = std::abs(n[0]), ay = std::abs(n[1]), az = std::abs(n[2]);
  return ax >= ay && ax >= az ? 0 : (ay >= az ? 1 : 2);
}

// Does the closed segment pq meet the closed triangle t?
bool segment_meets_triangle(const Vec3& p, const Vec3& q, const Triangle& t, const Tolerance& tol) {
  const Vec3& n = t.unit_normal();
  if (n.sqrnorm() == 0.0) return false;  // degenerate triangles are not tested
  const double dp = n | (p - t.p[0]), dq = n | (q - t.p[0]);
  const int drop = dominant_axis(n);
  const P2 a = project(t.p[0], drop), b = project(t.p[1], drop), c = project(t.p[2], drop);
  const int sp = sign(dp, tol.len), sq = sign(dq, tol.len);
  if (sp == 0 && sq == 0) {  // coplanar
    const P2 p2 = project(p, drop), q2 = project(q, drop);
    return point_in_triangle_2d(p2, a, b, c, tol.area) || point_in_triangle_2d(q2, a, b, c, tol.area) ||
           segments_intersect_2d(p2, q2, a, b, tol.area) || segments_intersect_2d(p2, q2, b, c, tol.area) ||
           segments_intersect_2d(p2, q2, c, a, tol.area);
  }
  if (sp * sq > 0) return false;  // both strictly on one side
  Vec3 x;
  if (sp == 0) {
    x = p;
  } else if (sq == 0) {
    x = q;
  } else {
    x = p + (dp / (dp - dq)) * (q - p);
  }
  return point_in_triangle_2d(project(x, drop), a, b, c, tol.area);
}

// Do two faces intersect beyond what they share?
bool faces_intersect(const Triangle& t1, const Triangle& t2) {
  const Tolerance tol = tolerance_of(t1, t2);
  std::array<int, 3> pos2 = {-1, -1, -1};  // for each corner of t1: the matching corner of t2
  int shared = 0;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      if (t1.v[static_cast<std::size_t>(i)] == t2.v[static_cast<std::size_t>(j)]) {
        pos2[static_cast<std::size_t>(i)] = j;
        ++shared;
      }
    }
  }
  if (shared == 3) return true;  // the same vertex triple: they overlap completely
  if (shared == 2) {
    // Intersect beyond the shared edge only when coplanar and folded onto each other.
    int i1 = 0;  // t1's corner not shared
    while (pos2[static_cast<std::size_t>(i1)] >= 0) ++i1;
    int i2 = 0;  // t2's corner not shared
    while (i2 == pos2[0] || i2 == pos2[1] || i2 == pos2[2]) ++i2;
    const Vec3& u = t1.p[static_cast<std::size_t>((i1 + 1) % 3)];
    const Vec3& w = t1.p[static_cast<std::size_t>((i1 + 2) % 3)];
    const Vec3& a = t1.p[static_cast<std::size_t>(i1)];
    const Vec3& b = t2.p[static_cast<std::size_t>(i2)];
    const Vec3& n1 = t1.unit_normal();
    if (n1.sqrnorm() == 0.0 || t2.unit_normal().sqrnorm() == 0.0) return false;
    if (std::abs(n1 | (b - u)) > tol.len) return false;  // not coplanar: they meet only on the edge
    return (((w - u) % (a - u)) | ((w - u) % (b - u))) > tol.area * tol.area;
  }
  if (shared == 1) {
    // Both contain the shared corner s; they meet elsewhere iff the side of one opposite s meets
    // the other triangle.
    int i1 = 0;
    while (pos2[static_cast<std::size_t>(i1)] < 0) ++i1;
    const int i2 = pos2[static_cast<std::size_t>(i1)];
    return segment_meets_triangle(t1.p[static_cast<std::size_t>((i1 + 1) % 3)],
                                  t1.p[static_cast<std::size_t>((i1 + 2) % 3)], t2, tol) ||
           segment_meets_triangle(t2.p[static_cast<std::size_t>((i2 + 1) % 3)],
                                  t2.p[static_cast<std::size_t>((i2 + 2) % 3)], t1, tol);
  }
  // No shared vertex: two closed triangles meet iff a side of one meets the other.
  for (int i = 0; i < 3; ++i) {
    if (segment_meets_triangle(t1.p[static_cast<std::size_t>(i)], t1.p[static_cast<std::size_t>((i + 1) % 3)],
                               t2, tol))
      return true;
    if (segment_meets_triangle(t2.p[static_cast<std::size_t>(i)], t2.p[static_cast<std::size_t>((i + 1) % 3)],
                               t1, tol))
      return true;
  }
  return false;
}

// Counts the intersecting pairs; with `pairs`, also lists them (triangle indices, first < second
// in leaf order).
// On `threads` threads (contiguous chunks of the leaf order, the pairs joined in chunk order: the
// same list for any count).
std::size_t count_self_intersections_of(const TriangleBvh& bvh, std::vector<std::pair<int, int>>* pairs = nullptr,
                                        unsigned threads = 1) {
  const std::vector<Triangle>& tris = bvh.triangles();
  const std::size_t n = static_cast<std::size_t>(bvh.size());
  const unsigned chunks = edgefront::threads_for(n, threads);
  std::vector<std::size_t> chunk_count(chunks, 0);
  std::vector<std::vector<std::pair<int, int>>> chunk_pairs(chunks);
  // Each pair once: triangle k (leaf order) against the overlapping ones after it.
  edgefront::parallel_for(n, threads, [&](std::size_t begin, std::size_t end, unsigned chunk) {
    for (int k = static_cast<int>(begin); k < static_cast<int>(end); ++k) {
      const Triangle& a = tris[static_cast<std::size_t>(bvh.in_order(k))];
      if (a.unit_normal().sqrnorm() == 0.0) continue;  // degenerate faces are counted elsewhere
      bvh.for_each_overlapping(bvh.box(bvh.in_order(k)), k + 1, [&](int j) {
        const Triangle& b = tris[static_cast<std::size_t>(j)];
        if (b.unit_normal().sqrnorm() != 0.0 && faces_intersect(a, b)) {
          ++chunk_count[chunk];
          if (pairs) chunk_pairs[chunk].emplace_back(bvh.in_order(k), j);
        }
      });
    }
  });
  std::size_t count = 0;
  for (unsigned c = 0; c < chunks; ++c) {
    count += chunk_count[c];
    if (pairs) pairs->insert(pairs->end(), chunk_pairs[c].begin(), chunk_pairs[c].end());
  }
  return count;
}

double angle_deg(const Vec3& a, const Vec3& b) {
  return std::atan2((a % b).norm(), a | b) * (180.0 / 3.14159265358979323846);
}

}  // namespace

std::size_t count_self_intersections(const Mesh& mesh) {
  check_mesh_coordinates(mesh, "the mesh");
  std::vector<Triangle> tris = mesh_triangles(mesh);
  if (tris.empty()) return 0;
  return count_self_intersections_of(TriangleBvh(std::move(tris)));
}

namespace detail {

std::vector<std::pair<int, int>> self_intersecting_face_pairs(const Mesh& mesh) {
  check_mesh_coordinates(mesh, "the mesh");
  std::vector<int> face_of;
  std::vector<Triangle> tris = mesh_triangles(mesh, &face_of);
  std::vector<std::pair<int, int>> pairs;
  if (tris.empty()) return pairs;
  count_self_intersections_of(TriangleBvh(std::move(tris)), &pairs);
  for (auto& [a, b] : pairs) {
    a = face_of[static_cast<std::size_t>(a)];
    b = face_of[static_cast<std::size_t>(b)];
    if (a > b) std::swap(a, b);
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

}  // namespace detail

namespace detail::eval {

// Validity of `mesh`; `bvh` (over the mesh's live faces) is reused when given.
MeshValidity validity_of(const Mesh& mesh, bool count_self, const TriangleBvh* bvh, unsigned threads) {
  const edgefront::MeshStats st = edgefront::compute_stats(mesh);
  MeshValidity m;
  m.vertices = st.vertices;
  m.edges = st.edges;
  m.faces = st.faces;
  m.nonmanifold_edges = 0;
  m.edge_manifold = true;
  m.nonmanifold_vertices = st.nonmanifold_vertices;
  m.vertex_manifold = st.nonmanifold_vertices == 0;
  m.components = st.components;
  m.border_loops = st.border_loops;
  m.closed = st.border_loops == 0;
  m.euler_characteristic = st.euler_characteristic;
  for (const auto& c : st.per_component) {
    m.component_genus.push_back(c.genus);
    m.genus += c.genus;
  }
  m.isolated_vertices = st.isolated_vertices;
  m.degenerate_faces = st.degenerate_faces;
  m.duplicate_faces = st.duplicate_faces;
  m.valence_histogram = st.valence_histogram;

  std::vector<Triangle> own;
  if (!bvh) own = mesh_triangles(mesh);
  const std::vector<Triangle>& tris = bvh ? bvh->triangles() : own;
  std::vector<double> min_angles;
  min_angles.reserve(tris.size());
  std::size_t below10 = 0, below30 = 0;
  for (const Triangle& t : tris) {
    m.area += 0.5 * ((t.p[1] - t.p[0]) % (t.p[2] - t.p[0])).norm();
    double a = kInf;
    for (int i = 0; i < 3; ++i) {
      const Vec3& p = t.p[static_cast<std::size_t>(i)];
      const Vec3 e1 = t.p[static_cast<std::size_t>((i + 1) % 3)] - p,
                 e2 = t.p[static_cast<std::size_t>((i + 2) % 3)] - p;
      // A zero-length side makes the face degenerate: its smallest angle is 0.
      a = std::min(a, e1.sqrnorm() > 0.0 && e2.sqrnorm() > 0.0 ? angle_deg(e1, e2) : 0.0);
    }
    min_angles.push_back(a);
    below10 += a < 10.0 ? 1 : 0;
    below30 += a < 30.0 ? 1 : 0;
  }
  if (!min_angles.empty()) {
    const double n = static_cast<double>(min_angles.size());
    m.faces_min_angle_below_10 = static_cast<double>(below10) / n;
    m.faces_min_angle_below_30 = static_cast<double>(below30) / n;
    m.min_angle_deg = *std::min_element(min_angles.begin(), min_angles.end());
    std::sort(min_angles.begin(), min_angles.end());
    const std::size_t k = min_angles.size();
    m.median_min_angle_deg = k % 2 ? min_angles[k / 2] : 0.5 * (min_angles[k / 2 - 1] + min_angles[k / 2]);
  }
  if (count_self) {
    if (bvh) {
      m.self_intersecting_pairs = count_self_intersections_of(*bvh, nullptr, threads);
    } else {
      m.self_intersecting_pairs = own.empty() ? 0 : count_self_intersections_of(TriangleBvh(std::move(own)), nullptr, threads);
    }
  }
  return m;
}

}  // namespace detail::eval

using detail::eval::validity_of;

MeshValidity mesh_validity(const Mesh& mesh, bool count_self) {
  check_mesh_coordinates(mesh, "the mesh");
  return validity_of(mesh, count_self, nullptr);
}

}  // namespace gcs
