#pragma once
// The predicates of the kernel's triangle-triangle test (edgefront/geometry.h), inline so that the
// pair loop of TriangleBvh::intersecting_pairs and the public functions share one definition.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

#include "edgefront/geometry.h"

namespace edgefront::detail {

// Tolerances of the predicates for a pair of triangles: lengths below `len` and (doubled) areas
// below `area` count as zero. Relative to the size and position of the pair, so that exactly
// planar or rounding-level coplanar configurations are handled as coplanar.
struct Tolerance {
  double len = 0, area = 0;
};

inline Tolerance tolerance_of(const Triangle& t1, const Triangle& t2) {
  double extent = 0, magnitude = 0;
  for (const Triangle* t : {&t1, &t2}) {
    for (std::size_t i = 0; i < 3; ++i) {
      extent = std::max(extent, (t->p[i] - t->p[(i + 1) % 3]).norm());
      magnitude = std::max(magnitude, t->p[i].max_abs());
    }
  }
  Tolerance tol;
  tol.len = kIntersectionTolerance * (extent + magnitude);
  tol.area = tol.len * extent;
  return tol;
}

// 2D helpers on the plane projection that drops axis `drop`.
struct P2 {
  double x, y;
};
inline P2 project(const Vec3& p, int drop) {
  const int i = drop == 0 ? 1 : 0, j = drop == 2 ? 1 : 2;
  return {p[i], p[j]};
}
inline double orient2(const P2& a, const P2& b, const P2& c) { return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x); }
inline int sign(double v, double tol) { return v > tol ? 1 : (v < -tol ? -1 : 0); }

inline bool point_in_triangle_2d(const P2& p, const P2& a, const P2& b, const P2& c, double tol) {
  const double area = orient2(a, b, c);
  const double s = area >= 0 ? 1.0 : -1.0;  // make the triangle counter-clockwise
  return s * orient2(a, b, p) >= -tol && s * orient2(b, c, p) >= -tol && s * orient2(c, a, p) >= -tol;
}

inline bool segments_intersect_2d(const P2& p, const P2& q, const P2& a, const P2& b, double tol) {
  const int o1 = sign(orient2(p, q, a), tol), o2 = sign(orient2(p, q, b), tol);
  const int o3 = sign(orient2(a, b, p), tol), o4 = sign(orient2(a, b, q), tol);
  if (o1 * o2 < 0 && o3 * o4 < 0) return true;
  auto on_segment = [&](const P2& u, const P2& v, const P2& w, int o) {  // w on segment uv (collinear)
    return o == 0 && std::min(u.x, v.x) - tol <= w.x && w.x <= std::max(u.x, v.x) + tol &&
           std::min(u.y, v.y) - tol <= w.y && w.y <= std::max(u.y, v.y) + tol;
  };
  // Touching or collinear overlap: an endpoint on the other segment. `tol` is an area here; the
  // box slack uses it as a length too, which is only more permissive at rounding level.
  return on_segment(p, q, a, o1) || on_segment(p, q, b, o2) || on_segment(a, b, p, o3) || on_segment(a, b, q, o4);
}

inline int dominant_axis(const Vec3& n) {
  const double ax = std::abs(n[0]), ay = std::abs(n[1]), az = std::abs(n[2]);
  return ax >= ay && ax >= az ? 0 : (ay >= az ? 1 : 2);
}

// Does the closed segment pq meet the closed triangle t?
inline bool segment_meets_triangle(const Vec3& p, const Vec3& q, const Triangle& t, const Tolerance& tol) {
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

// Does the segment pq pass through the interior of t: its ends strictly on opposite sides of t's
// plane, and the point where it meets the plane strictly inside t (beyond the tolerances)?
inline bool segment_crosses_interior(const Vec3& p, const Vec3& q, const Triangle& t, const Tolerance& tol) {
  const Vec3& n = t.unit_normal();
  if (n.sqrnorm() == 0.0) return false;
  const double dp = n | (p - t.p[0]), dq = n | (q - t.p[0]);
  if (sign(dp, tol.len) * sign(dq, tol.len) >= 0) return false;
  const int drop = dominant_axis(n);
  const P2 a = project(t.p[0], drop), b = project(t.p[1], drop), c = project(t.p[2], drop);
  const P2 x = project(p + (dp / (dp - dq)) * (q - p), drop);
  const double s = orient2(a, b, c) >= 0 ? 1.0 : -1.0;  // make the triangle counter-clockwise
  return s * orient2(a, b, x) > tol.area && s * orient2(b, c, x) > tol.area && s * orient2(c, a, x) > tol.area;
}

// The corners two triangles share: for each corner of t1 the matching corner of t2 (or -1).
struct Sharing {
  std::array<int, 3> pos2 = {-1, -1, -1};
  int shared = 0;
};

inline Sharing sharing_of(const Triangle& t1, const Triangle& t2) {
  Sharing s;
  for (std::size_t i = 0; i < 3; ++i) {
    if (t1.v[i] < 0) continue;  // no id: shared with nothing
    for (std::size_t j = 0; j < 3; ++j) {
      if (t1.v[i] == t2.v[j]) {
        s.pos2[i] = static_cast<int>(j);
        ++s.shared;
        break;
      }
    }
  }
  return s;
}


// Whether two closed triangles meet beyond their shared vertices (triangles_intersect).
inline bool triangles_meet(const Triangle& t1, const Triangle& t2) {
  if (t1.degenerate() || t2.degenerate()) return false;
  const Tolerance tol = tolerance_of(t1, t2);
  const Sharing sh = sharing_of(t1, t2);
  const std::array<int, 3>& pos2 = sh.pos2;  // for each corner of t1: the matching corner of t2
  const int shared = sh.shared;
  if (shared == 3) return true;  // the same vertex triple: they overlap completely
  if (shared == 2) {
    // Intersect beyond the shared edge only when coplanar and folded onto each other.
    std::size_t i1 = 0;  // t1's corner not shared
    while (pos2[i1] >= 0) ++i1;
    int i2 = 0;  // t2's corner not shared
    while (i2 == pos2[0] || i2 == pos2[1] || i2 == pos2[2]) ++i2;
    const Vec3& u = t1.p[(i1 + 1) % 3];
    const Vec3& w = t1.p[(i1 + 2) % 3];
    const Vec3& a = t1.p[i1];
    const Vec3& b = t2.p[static_cast<std::size_t>(i2)];
    if (std::abs(t1.unit_normal() | (b - u)) > tol.len) return false;  // not coplanar: they meet only on the edge
    return (((w - u) % (a - u)) | ((w - u) % (b - u))) > tol.area * tol.area;
  }
  if (shared == 1) {
    // Both contain the shared corner s; they meet elsewhere iff the side of one opposite s meets
    // the other triangle.
    std::size_t i1 = 0;
    while (pos2[i1] < 0) ++i1;
    const std::size_t i2 = static_cast<std::size_t>(pos2[i1]);
    return segment_meets_triangle(t1.p[(i1 + 1) % 3], t1.p[(i1 + 2) % 3], t2, tol) ||
           segment_meets_triangle(t2.p[(i2 + 1) % 3], t2.p[(i2 + 2) % 3], t1, tol);
  }
  // No shared vertex: two closed triangles meet iff a side of one meets the other.
  for (std::size_t i = 0; i < 3; ++i) {
    if (segment_meets_triangle(t1.p[i], t1.p[(i + 1) % 3], t2, tol)) return true;
    if (segment_meets_triangle(t2.p[i], t2.p[(i + 1) % 3], t1, tol)) return true;
  }
  return false;
}

}  // namespace edgefront::detail
