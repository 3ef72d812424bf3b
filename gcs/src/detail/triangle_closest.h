#pragma once
// The closest point of a triangle to a point (used by the evaluation's distances and the result's
// surface fit).

#include <algorithm>
#include <array>

#include "edgefront/mesh.h"

namespace gcs::detail {

inline edgefront::Vec3 closest_on_segment(const edgefront::Vec3& x, const edgefront::Vec3& a,
                                          const edgefront::Vec3& b) {
  const edgefront::Vec3 ab = b - a;
  const double len2 = ab.sqrnorm();
  if (!(len2 > 0.0)) return a;
  const double t = std::clamp(((x - a) | ab) / len2, 0.0, 1.0);
  return a + t * ab;
}

/// Closest point of triangle abc to x, by the Voronoi regions of its vertices and edges; for a
/// degenerate (collinear) triangle the nearest point of its three sides.
inline edgefront::Vec3 closest_on_triangle(const edgefront::Vec3& x, const edgefront::Vec3& a,
                                           const edgefront::Vec3& b, const edgefront::Vec3& c) {
  using edgefront::Vec3;
  const Vec3 ab = b - a, ac = c - a, ax = x - a;
  const double d1 = ab | ax, d2 = ac | ax;
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec3 bx = x - b;
  const double d3 = ab | bx, d4 = ac | bx;
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + (d1 / (d1 - d3)) * ab;
  const Vec3 cx = x - c;
  const double d5 = ab | cx, d6 = ac | cx;
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + (d2 / (d2 - d6)) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  const double sum = va + vb + vc;
  if (!(sum > 0.0)) {
    const std::array<Vec3, 3> q = {closest_on_segment(x, a, b), closest_on_segment(x, b, c),
                                   closest_on_segment(x, c, a)};
    return *std::min_element(q.begin(), q.end(), [&](const Vec3& u, const Vec3& w) {
      return (u - x).sqrnorm() < (w - x).sqrnorm();
    });
  }
  return a + (vb / sum) * ab + (vc / sum) * ac;
}

}  // namespace gcs::detail
