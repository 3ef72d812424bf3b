#pragma once
/// \file geometry.h
/// The geometry kernel the libraries share: an axis-aligned box, a triangle with its vertex ids,
/// the closest point of a triangle, and the one triangle-triangle intersection test (the twist
/// detector and the gcs evaluation, self-intersection resolution and untangling all call it, so
/// they agree on whether two faces cross). The bounding-volume hierarchy over triangles is in
/// triangle_bvh.h.

#include <array>
#include <limits>

#include "edgefront/mesh.h"

namespace edgefront {

/// An axis-aligned box; the default box is empty (lo = +inf, hi = -inf) and overlaps nothing.
struct AlignedBox {
  Vec3 lo = Vec3(std::numeric_limits<double>::infinity());   ///< smallest coordinates
  Vec3 hi = Vec3(-std::numeric_limits<double>::infinity());  ///< largest coordinates
  /// Grows the box to hold `p`.
  void add(const Vec3& p) {
    lo.minimize(p);
    hi.maximize(p);
  }
  /// Grows the box to hold `b`.
  void add(const AlignedBox& b) {
    lo.minimize(b.lo);
    hi.maximize(b.hi);
  }
  /// Whether the two closed boxes share a point (touching counts).
  bool overlaps(const AlignedBox& b) const {
    return lo[0] <= b.hi[0] && b.lo[0] <= hi[0] && lo[1] <= b.hi[1] && b.lo[1] <= hi[1] && lo[2] <= b.hi[2] &&
           b.lo[2] <= hi[2];
  }
  /// Squared distance from `p` to the box (0 inside).
  double dist2(const Vec3& p) const;
};

/// A triangle of a mesh (or of a soup): its corners, the ids of its vertices, and its unit normal.
/// Two triangles that carry the same non-negative id at a corner share that vertex; a negative id
/// (the default) is shared with nothing, so corners at equal positions without ids do not count as
/// shared.
struct Triangle {
  std::array<Vec3, 3> p;                ///< the corners, in winding order
  std::array<int, 3> v = {-1, -1, -1};  ///< vertex ids of the corners (mesh vertex indices); < 0: none
  Vec3 n = Vec3(0, 0, 0);               ///< unit normal of `p` (right-hand rule); zero when degenerate

  /// A triangle with all corners at the origin and no ids (degenerate); assign it a real one.
  Triangle() = default;
  /// The triangle with corners `corners` and vertex ids `ids`; computes the unit normal.
  explicit Triangle(const std::array<Vec3, 3>& corners, const std::array<int, 3>& ids = {-1, -1, -1});

  /// The unit normal (zero for a degenerate triangle: zero or non-finite area).
  const Vec3& unit_normal() const { return n; }
  /// Whether the triangle has no usable normal (zero or non-finite area).
  bool degenerate() const { return n.sqrnorm() == 0.0; }
  /// The bounding box of the corners.
  AlignedBox box() const;
  /// The bounding box grown by at least this triangle's share of the tolerance of
  /// `triangles_intersect`: kIntersectionTolerance x (D + M) x (1 + D), D the box's diagonal (>=
  /// the longest side), M its largest coordinate magnitude (the test's area tolerance is a length
  /// times a side). Two triangles the test finds intersecting, touching within the tolerance
  /// included, have overlapping contact boxes.
  AlignedBox contact_box() const;
};

/// The live face `f` of `mesh` as a Triangle (corners in `fv_range` order, vertex ids = vertex
/// indices). \throws edgefront::InternalError when `f` is not a triangle.
Triangle face_triangle(const Mesh& mesh, FaceHandle f);

/// Closest point of the triangle abc to `x`, by the Voronoi regions of its corners and sides; for
/// a degenerate (collinear) triangle the nearest point of its three sides.
Vec3 closest_point_on_triangle(const Vec3& x, const Vec3& a, const Vec3& b, const Vec3& c);

/// Whether two triangles intersect beyond the vertices they share (corners with equal
/// non-negative ids, see Triangle): the one test of the libraries. The triangles are closed, so
/// every kind of contact counts:
/// - no shared vertex: they meet anywhere, crossing or only touching (a corner on the other's
///   side or face, a side along the other's side, a coplanar overlap);
/// - one shared vertex: they meet anywhere else (the side opposite the shared corner of one meets
///   the other);
/// - two shared vertices (a shared edge): they are coplanar and folded onto each other (both
///   free corners on the same side of the edge);
/// - three shared vertices: always (the same face twice).
///
/// Tolerance: with L the longest side of the pair and M the largest coordinate magnitude of its
/// corners, distances up to kIntersectionTolerance * (L + M) count as zero (a corner that close
/// to the other's plane lies on it; coplanar within rounding is coplanar), so a near miss must be
/// farther apart than that (about 1e-12 of the pair's size) to count as apart. Degenerate
/// triangles (zero normal) intersect nothing (count them separately).
bool triangles_intersect(const Triangle& a, const Triangle& b);

/// Relative tolerance of `triangles_intersect` (see there): lengths below this times (longest
/// side + largest coordinate magnitude) of the pair are zero.
inline constexpr double kIntersectionTolerance = 1e-12;

/// How two triangles meet, beyond the vertices they share (`triangle_contact`).
enum class TriangleContact {
  Apart,     ///< they do not meet beyond their shared vertices
  Touching,  ///< they meet, but no side of one passes through the other's interior: a corner or a
             ///< side on the other (within the tolerance), or coplanar overlap or folding
  Crossing,  ///< a side of one passes through the interior of the other (a transversal crossing)
};

/// The kind of contact of two triangles, with the tolerance and sharing rules of
/// `triangles_intersect` (which is `triangle_contact(a, b) != TriangleContact::Apart`). A side
/// crosses when its ends lie on opposite sides of the other's plane by more than the tolerance
/// and it meets the plane inside the other triangle by more than the tolerance from every side.
/// The evaluation counts every contact (a touching surface is not embedded); the twist detector
/// counts crossings (touching along an unwelded seam is no twist).
TriangleContact triangle_contact(const Triangle& a, const Triangle& b);

}  // namespace edgefront
