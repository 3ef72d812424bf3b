// Tests of edgefront/geometry.h (the one triangle-triangle test, its tolerance and contact kinds,
// the closest point of a triangle) and that its two users, the twist detector and
// gcs::count_self_intersections, agree on a set of cases.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "edgefront/error.h"
#include "edgefront/geometry.h"
#include "gcs/evaluation.h"
#include "twist/detect.h"

namespace {

using edgefront::Mesh;
using edgefront::Triangle;
using edgefront::triangle_contact;
using edgefront::TriangleContact;
using edgefront::triangles_intersect;
using edgefront::Vec3;

using Corners = std::array<Vec3, 3>;
using Ids = std::array<int, 3>;

// One case: two triangles with their vertex ids (equal ids are a shared vertex).
struct Case {
  std::string name;
  Corners a, b;
  Ids ia, ib;
  TriangleContact contact;  // the expected verdict
};

// The reference triangle in the plane z = 0: (0,0,0), (2,0,0), (0,2,0); ids 0, 1, 2.
const Corners kBase = {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 2, 0)};
const Ids kBaseIds = {0, 1, 2};

std::vector<Case> cases() {
  std::vector<Case> c;
  // A vertical triangle whose lower side pierces the base's interior.
  c.push_back({"crossing", kBase, {Vec3(0.5, 0.5, -1), Vec3(0.5, 0.5, 1), Vec3(0.5, 1.5, 0.5)}, kBaseIds, {3, 4, 5},
               TriangleContact::Crossing});
  // A vertical triangle standing on the base: its lowest corner touches the base's interior.
  c.push_back({"touching at a vertex", kBase, {Vec3(0.5, 0.5, 0), Vec3(0.5, 0.0, 1), Vec3(0.5, 1.0, 1)}, kBaseIds,
               {3, 4, 5}, TriangleContact::Touching});
  // The same, lifted a little: a near miss by 1e-6 (far above the tolerance of about 1e-12).
  c.push_back({"near miss", kBase, {Vec3(0.5, 0.5, 1e-6), Vec3(0.5, 0.0, 1), Vec3(0.5, 1.0, 1)}, kBaseIds, {3, 4, 5},
               TriangleContact::Apart});
  // Lowered by 1e-11 (above the tolerance of about 5e-12 here): a shallow crossing, still one.
  c.push_back({"shallow crossing", kBase, {Vec3(0.5, 0.5, -1e-11), Vec3(0.5, 0.0, 1), Vec3(0.5, 1.0, 1)}, kBaseIds,
               {3, 4, 5}, TriangleContact::Crossing});
  // Lifted by less than the tolerance (1e-12 of the pair's size): touching within rounding.
  c.push_back({"within the tolerance", kBase, {Vec3(0.5, 0.5, 1e-14), Vec3(0.5, 0.0, 1), Vec3(0.5, 1.0, 1)}, kBaseIds,
               {3, 4, 5}, TriangleContact::Touching});
  // A second sheet's corner touching the base's corner, not shared (different vertices).
  c.push_back({"touching corners, not shared", kBase, {Vec3(0, 0, 0), Vec3(-1, 0, 1), Vec3(0, -1, 1)}, kBaseIds,
               {3, 4, 5}, TriangleContact::Touching});
  // The same corner as a shared vertex: they meet only there.
  c.push_back({"sharing a vertex only", kBase, {Vec3(0, 0, 0), Vec3(-1, 0, 1), Vec3(0, -1, 1)}, kBaseIds, {0, 4, 5},
               TriangleContact::Apart});
  // Sharing a vertex, and the side opposite it crosses the base's interior.
  c.push_back({"sharing a vertex, crossing", kBase, {Vec3(0, 0, 0), Vec3(1, 1, -1), Vec3(1, 0.2, 1)}, kBaseIds,
               {0, 4, 5}, TriangleContact::Crossing});
  // Sharing an edge at a right angle (a crease).
  c.push_back({"sharing an edge, creased", kBase, {Vec3(2, 0, 0), Vec3(0, 0, 0), Vec3(1, 0, 1)}, kBaseIds, {1, 0, 5},
               TriangleContact::Apart});
  // Sharing an edge, coplanar, on opposite sides (a flat pair of neighbours).
  c.push_back({"sharing an edge, flat", kBase, {Vec3(2, 0, 0), Vec3(0, 0, 0), Vec3(1, -1, 0)}, kBaseIds, {1, 0, 5},
               TriangleContact::Apart});
  // Sharing an edge, coplanar, folded onto each other (the free corners on the same side).
  c.push_back({"sharing an edge, folded flat", kBase, {Vec3(2, 0, 0), Vec3(0, 0, 0), Vec3(1, 0.5, 0)}, kBaseIds,
               {1, 0, 5}, TriangleContact::Touching});
  // Coplanar, overlapping, no shared vertex.
  c.push_back({"coplanar overlap", kBase, {Vec3(0.5, 0.5, 0), Vec3(3, 0.5, 0), Vec3(0.5, 3, 0)}, kBaseIds, {3, 4, 5},
               TriangleContact::Touching});
  // Coplanar, apart.
  c.push_back({"coplanar apart", kBase, {Vec3(3, 3, 0), Vec3(5, 3, 0), Vec3(3, 5, 0)}, kBaseIds, {3, 4, 5}, TriangleContact::Apart});
  // Parallel planes, one above the other.
  c.push_back({"parallel apart", kBase, {Vec3(0, 0, 1), Vec3(2, 0, 1), Vec3(0, 2, 1)}, kBaseIds, {3, 4, 5}, TriangleContact::Apart});
  // The same vertex triple twice.
  c.push_back({"the same face twice", kBase, kBase, kBaseIds, kBaseIds, TriangleContact::Touching});
  return c;
}

TEST(Geometry, TriangleContactGivesTheExpectedVerdictInBothArgumentOrders) {
  for (const Case& c : cases()) {
    const Triangle a(c.a, c.ia), b(c.b, c.ib);
    EXPECT_EQ(triangle_contact(a, b), c.contact) << c.name;
    EXPECT_EQ(triangle_contact(b, a), c.contact) << c.name << " (swapped)";
    EXPECT_EQ(triangles_intersect(a, b), c.contact != TriangleContact::Apart) << c.name;
    EXPECT_EQ(triangles_intersect(b, a), c.contact != TriangleContact::Apart) << c.name << " (swapped)";
  }
}

TEST(Geometry, VerdictsDoNotDependOnScaleOrPosition) {
  // The tolerance is relative to the pair's size and position: scaled by 1e3 and moved far away,
  // every case keeps its verdict (the two cases at the tolerance's scale excepted: the offset
  // from the origin grows the tolerance past them, as it should: coordinates carry less precision).
  for (const Case& c : cases()) {
    if (c.name == "within the tolerance" || c.name == "shallow crossing") continue;
    Corners a = c.a, b = c.b;
    for (Vec3* p : {&a[0], &a[1], &a[2], &b[0], &b[1], &b[2]}) *p = *p * 1e3 + Vec3(1e4, -2e4, 5e3);
    EXPECT_EQ(triangle_contact(Triangle(a, c.ia), Triangle(b, c.ib)), c.contact) << c.name;
  }
}

TEST(Geometry, CornersWithoutIdsAreSharedWithNothing) {
  // Equal positions but no ids: the touching corner counts as contact.
  const Corners b = {Vec3(0, 0, 0), Vec3(-1, 0, 1), Vec3(0, -1, 1)};
  EXPECT_TRUE(triangles_intersect(Triangle(kBase), Triangle(b)));
  // Negative ids never match each other.
  EXPECT_TRUE(triangles_intersect(Triangle(kBase, {-1, -1, -1}), Triangle(b, {-1, -2, -3})));
}

TEST(Geometry, DegenerateTrianglesIntersectNothing) {
  const Corners line = {Vec3(0.5, 0.5, -1), Vec3(0.5, 0.5, 1), Vec3(0.5, 0.5, 0)};  // collinear, pierces the base
  const Triangle d(line, {3, 4, 5});
  EXPECT_TRUE(d.degenerate());
  EXPECT_FALSE(triangles_intersect(Triangle(kBase, kBaseIds), d));
  EXPECT_FALSE(triangles_intersect(d, Triangle(kBase, kBaseIds)));
}

TEST(Geometry, TriangleHasItsUnitNormalAndBox) {
  const Triangle t(kBase, kBaseIds);
  EXPECT_DOUBLE_EQ(t.unit_normal()[2], 1.0);
  EXPECT_FALSE(t.degenerate());
  const edgefront::AlignedBox box = t.box();
  EXPECT_EQ(box.lo, Vec3(0, 0, 0));
  EXPECT_EQ(box.hi, Vec3(2, 2, 0));
  EXPECT_DOUBLE_EQ(box.dist2(Vec3(3, 1, 0)), 1.0);
  EXPECT_DOUBLE_EQ(box.dist2(Vec3(1, 1, 0)), 0.0);
  EXPECT_FALSE(edgefront::AlignedBox().overlaps(box));  // the empty box overlaps nothing
}

TEST(Geometry, ClosestPointOnTriangleIsTheNearestOfDenseSamples) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-3, 3);
  const Corners t = {Vec3(0, 0, 0), Vec3(2, 0.3, 0.1), Vec3(0.4, 1.7, -0.5)};
  for (int trial = 0; trial < 50; ++trial) {
    const Vec3 x(u(rng), u(rng), u(rng));
    const Vec3 q = edgefront::closest_point_on_triangle(x, t[0], t[1], t[2]);
    const double d = (q - x).norm();
    // No point of a fine barycentric grid is nearer (up to the grid's resolution).
    constexpr int kSteps = 60;
    double best = std::numeric_limits<double>::infinity();
    for (int i = 0; i <= kSteps; ++i) {
      for (int j = 0; i + j <= kSteps; ++j) {
        const double s = static_cast<double>(i) / kSteps, r = static_cast<double>(j) / kSteps;
        best = std::min(best, ((1 - s - r) * t[0] + s * t[1] + r * t[2] - x).norm());
      }
    }
    EXPECT_LE(d, best + 1e-12) << trial;
    EXPECT_GE(d, best - 0.05) << trial;  // and q is no farther than the grid's nearest by more than its spacing
  }
}

TEST(Geometry, FaceTriangleCarriesTheVertexIndices) {
  Mesh m;
  std::vector<edgefront::VertexHandle> v;
  for (const Vec3& p : kBase) v.push_back(m.add_vertex(p));
  const edgefront::FaceHandle f = m.add_face(v[0], v[1], v[2]);
  const Triangle t = edgefront::face_triangle(m, f);
  EXPECT_EQ(t.v, (Ids{0, 1, 2}));
  EXPECT_EQ(t.p[1], kBase[1]);
}

// ---------------------------------------------------------------------------------------------
// The two users agree: each case as a two-face mesh, judged by gcs::count_self_intersections and
// by the twist detector's self-intersection evidence.

Mesh two_face_mesh(const Case& c) {
  Mesh m;
  std::vector<edgefront::VertexHandle> vh;
  std::vector<Vec3> pos;
  auto vertex = [&](int id, const Vec3& p) {
    while (static_cast<int>(vh.size()) <= id) {
      vh.push_back(m.add_vertex(p));
      pos.push_back(p);
    }
    return vh[static_cast<std::size_t>(id)];
  };
  std::array<edgefront::VertexHandle, 3> fa, fb;
  for (std::size_t k = 0; k < 3; ++k) fa[k] = vertex(c.ia[k], c.a[k]);
  for (std::size_t k = 0; k < 3; ++k) fb[k] = vertex(c.ib[k], c.b[k]);
  EF_CHECK(m.add_face(fa[0], fa[1], fa[2]).is_valid(), c.name + ": face a refused");
  EF_CHECK(m.add_face(fb[0], fb[1], fb[2]).is_valid(), c.name + ": face b refused");
  if (c.ib[0] == c.ia[0] && c.ib[1] != c.ia[1] && c.ib[1] != c.ia[2]) {
    // Sharing only the first corner: a pinched vertex, which the detector's fronts refuse. A
    // bridge face (shared corner, a's last, b's second) makes it one fan; it meets a and b only
    // along their shared edges, never coplanar in these cases, so it adds no pair.
    EF_CHECK(m.add_face(fa[0], fa[2], fb[1]).is_valid(), c.name + ": bridge face refused");
  }
  return m;
}

bool twist_finds_self_intersection(const Mesh& m) {
  twist::DetectOptions o;
  o.self_intersections = true;
  o.regions.require_orientation_evidence = false;  // report the pair's faces as they are
  o.regions.min_flagged_share = 0.0;
  o.regions.min_flagged_faces = 1;
  // Only the self-intersection evidence: a face keeps the first evidence found, so layers and
  // folds (tested before it) are narrowed to exactly parallel and exactly folded faces.
  o.experimental.parallel_cos = 1.0;
  o.experimental.fold_cos = -1.0;
  const twist::DetectResult r = twist::detect_regions(m, o);
  for (const twist::TwistRegion& region : r.regions) {
    for (const twist::Evidence& e : region.evidence) {
      if (e.kind == twist::EvidenceKind::SelfIntersection) return true;
    }
  }
  return false;
}

bool share_a_vertex(const Case& c) {
  for (const int a : c.ia) {
    for (const int b : c.ib) {
      if (a == b) return true;
    }
  }
  return false;
}

TEST(Geometry, TheTwistDetectorAndTheEvaluationAgreeOnPairsSharingNoVertex) {
  int compared = 0;
  for (const Case& c : cases()) {
    if (share_a_vertex(c)) continue;  // the detector asks only about pairs sharing no vertex
    const Mesh m = two_face_mesh(c);
    // The evaluation counts every contact, the detector the crossings: one test, one verdict.
    EXPECT_EQ(gcs::count_self_intersections(m) > 0, c.contact != TriangleContact::Apart) << c.name;
    EXPECT_EQ(twist_finds_self_intersection(m), c.contact == TriangleContact::Crossing) << c.name;
    ++compared;
  }
  EXPECT_EQ(compared, 9);  // crossing (2), touching (2) and within the tolerance, near miss, coplanar (2), parallel
}

TEST(Geometry, TheEvaluationJudgesPairsSharingAVertexOrAnEdgeByTheKernel) {
  for (const Case& c : cases()) {
    // The same face twice is no mesh (OpenMesh refuses it): kernel level only (test above).
    if (!share_a_vertex(c) || c.name == "the same face twice") continue;
    EXPECT_EQ(gcs::count_self_intersections(two_face_mesh(c)) > 0, c.contact != TriangleContact::Apart) << c.name;
  }
}

}  // namespace
