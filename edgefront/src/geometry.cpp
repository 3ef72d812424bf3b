#include "edgefront/geometry.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>

#include "detail/triangle_predicates.h"
#include "edgefront/error.h"

namespace edgefront {

double AlignedBox::dist2(const Vec3& p) const {
  double d = 0;
  for (int k = 0; k < 3; ++k) {
    const double e = std::max({lo[k] - p[k], 0.0, p[k] - hi[k]});
    d += e * e;
  }
  return d;
}

Triangle::Triangle(const std::array<Vec3, 3>& corners, const std::array<int, 3>& ids) : p(corners), v(ids) {
  const Vec3 c = (p[1] - p[0]) % (p[2] - p[0]);
  const double len = c.norm();
  n = len > 0.0 && std::isfinite(len) ? c / len : Vec3(0, 0, 0);
}

AlignedBox Triangle::box() const {
  AlignedBox b;
  for (const Vec3& q : p) b.add(q);
  return b;
}

AlignedBox Triangle::contact_box() const {
  AlignedBox b = box();
  // Bounds from the box (one square root): the diagonal >= the longest side, and the largest
  // magnitude of its corners >= the largest coordinate magnitude of the triangle's corners.
  const double diagonal = (b.hi - b.lo).norm();
  const double magnitude = std::max(b.lo.max_abs(), b.hi.max_abs());
  const double grow = kIntersectionTolerance * (diagonal + magnitude) * (1.0 + diagonal);
  b.lo -= Vec3(grow);
  b.hi += Vec3(grow);
  return b;
}

Triangle face_triangle(const Mesh& mesh, FaceHandle f) {
  std::array<Vec3, 3> p;
  std::array<int, 3> v = {-1, -1, -1};
  std::size_t k = 0;
  for (const VertexHandle u : mesh.fv_range(f)) {
    if (k < 3) {
      p[k] = mesh.point(u);
      v[k] = u.idx();
    }
    ++k;
  }
  EF_CHECK(k == 3, "face " + std::to_string(f.idx()) + " is not a triangle");
  return Triangle(p, v);
}

namespace {

Vec3 closest_on_segment(const Vec3& x, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double len2 = ab.sqrnorm();
  if (!(len2 > 0.0)) return a;
  const double t = std::clamp(((x - a) | ab) / len2, 0.0, 1.0);
  return a + t * ab;
}

}  // namespace

Vec3 closest_point_on_triangle(const Vec3& x, const Vec3& a, const Vec3& b, const Vec3& c) {
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

// ---------------------------------------------------------------------------------------------
// Triangle-triangle intersection (predicates: detail/triangle_predicates.h)

bool triangles_intersect(const Triangle& t1, const Triangle& t2) { return detail::triangles_meet(t1, t2); }

TriangleContact triangle_contact(const Triangle& t1, const Triangle& t2) {
  using namespace detail;
  if (!triangles_meet(t1, t2)) return TriangleContact::Apart;
  const Tolerance tol = tolerance_of(t1, t2);
  const Sharing sh = sharing_of(t1, t2);
  // Two shared corners or three: coplanar (folded flat, or the same face), so no side crosses.
  if (sh.shared >= 2) return TriangleContact::Touching;
  if (sh.shared == 1) {
    // A side from the shared corner starts on the other's plane: only the opposite sides can cross.
    std::size_t i1 = 0;
    while (sh.pos2[i1] < 0) ++i1;
    const std::size_t i2 = static_cast<std::size_t>(sh.pos2[i1]);
    const bool crossing = segment_crosses_interior(t1.p[(i1 + 1) % 3], t1.p[(i1 + 2) % 3], t2, tol) ||
                          segment_crosses_interior(t2.p[(i2 + 1) % 3], t2.p[(i2 + 2) % 3], t1, tol);
    return crossing ? TriangleContact::Crossing : TriangleContact::Touching;
  }
  for (std::size_t i = 0; i < 3; ++i) {
    if (segment_crosses_interior(t1.p[i], t1.p[(i + 1) % 3], t2, tol) ||
        segment_crosses_interior(t2.p[i], t2.p[(i + 1) % 3], t1, tol)) {
      return TriangleContact::Crossing;
    }
  }
  return TriangleContact::Touching;
}

}  // namespace edgefront
