// Tests of edgefront/surface_point.h: a vertex and an edge point as face + barycentric, their
// positions, and clear errors for bad handles and parameters.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "edgefront/error.h"
#include "edgefront/surface_point.h"

namespace {

using namespace edgefront;

// Two triangles sharing the edge 0-1: (0, 1, 2) and (1, 0, 3); vertex 4 isolated.
Mesh two_triangles() {
  Mesh m;
  const VertexHandle a = m.add_vertex(Vec3(0, 0, 0)), b = m.add_vertex(Vec3(2, 0, 0)), c = m.add_vertex(Vec3(0, 2, 0)),
                     d = m.add_vertex(Vec3(1, -1, 0));
  m.add_vertex(Vec3(5, 5, 5));
  m.add_face(a, b, c);
  m.add_face(b, a, d);
  return m;
}

TEST(SurfacePoint, AVertexIsCoordinateOneAtItOnAnIncidentFace) {
  const Mesh m = two_triangles();
  for (int v = 0; v < 4; ++v) {
    const SurfacePoint p = surface_point_at_vertex(m, VertexHandle(v));
    ASSERT_TRUE(is_live(m, p.face));
    EXPECT_DOUBLE_EQ(p.bary[0] + p.bary[1] + p.bary[2], 1.0);
    EXPECT_EQ(surface_point_position(m, p), m.point(VertexHandle(v))) << v;
  }
}

TEST(SurfacePoint, AnEdgePointLiesOnAFaceOfTheEdgeEvenFromTheBorderSide) {
  const Mesh m = two_triangles();
  for (const HalfedgeHandle h : m.halfedges()) {
    for (const double t : {0.0, 0.25, 1.0}) {
      const SurfacePoint p = surface_point_on_edge(m, h, t);
      const Vec3 a = m.point(m.from_vertex_handle(h)), b = m.point(m.to_vertex_handle(h));
      EXPECT_LT((surface_point_position(m, p) - (a + t * (b - a))).norm(), 1e-15) << h.idx() << " " << t;
      const bool on_this_side = p.face == m.face_handle(h) || p.face == m.opposite_face_handle(h);
      EXPECT_TRUE(on_this_side) << h.idx();
    }
  }
}

TEST(SurfacePoint, BadHandlesAndParametersThrowNamingThem) {
  const Mesh m = two_triangles();
  EXPECT_THROW(surface_point_at_vertex(m, VertexHandle(4)), InvalidInput);  // isolated: no face
  EXPECT_THROW(surface_point_at_vertex(m, VertexHandle(99)), InvalidInput);
  EXPECT_THROW(surface_point_on_edge(m, HalfedgeHandle(0), 1.5), InvalidInput);
  EXPECT_THROW(surface_point_on_edge(m, HalfedgeHandle(0), std::nan("")), InvalidInput);
  EXPECT_THROW(surface_point_on_edge(m, HalfedgeHandle(), 0.5), InvalidInput);
  EXPECT_THROW(surface_point_position(m, SurfacePoint{FaceHandle(7), {1, 0, 0}}), InvalidInput);
  try {
    surface_point_at_vertex(m, VertexHandle(4));
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("vertex 4 has no face"), std::string::npos) << e.what();
  }
}

}  // namespace
