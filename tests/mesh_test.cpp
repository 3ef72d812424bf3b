// edgefront/mesh.h: a Mesh assigned from an OpenMesh mesh of other traits (floats, no status)
// lacks its attributes; every entry point refuses it with InvalidInput instead of crashing, and
// restore_attributes (or mesh_from_openmesh) makes it usable.

#include "edgefront/mesh.h"

#include <gtest/gtest.h>

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include "edgefront/arrays.h"
#include "edgefront/connection_path.h"
#include "edgefront/error.h"
#include "edgefront/minimal_distance_front.h"
#include "edgefront/minimal_edge_front.h"
#include "shapes/shapes.h"
#include "twist/detect.h"
#include "twist/repair.h"

namespace {

using namespace edgefront;

/// A host's OpenMesh type: float points, no status, no normals.
struct FloatTraits : OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3f;
};
using FloatMesh = OpenMesh::TriMesh_ArrayKernelT<FloatTraits>;

FloatMesh float_sphere() {
  const Mesh sphere = shapes::icosphere(2);
  FloatMesh out;
  for (VertexHandle v : sphere.vertices()) {
    const Vec3& p = sphere.point(v);
    out.add_vertex(OpenMesh::Vec3f(static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2])));
  }
  for (FaceHandle f : sphere.faces()) {
    std::vector<FloatMesh::VertexHandle> c;
    for (VertexHandle v : sphere.fv_range(f)) c.emplace_back(v.idx());
    out.add_face(c);
  }
  return out;
}

TEST(Mesh, AssignFromAnotherTraitsIsRefusedNotACrash) {
  const FloatMesh host = float_sphere();
  Mesh m;
  m.assign(host);
  ASSERT_EQ(m.n_faces(), host.n_faces());
  EXPECT_FALSE(has_attributes(m));
  auto refused = [](const std::function<void()>& f) {
    try {
      f();
    } catch (const InvalidInput& e) {
      return std::string(e.what()).find("restore_attributes") != std::string::npos;
    }
    return false;
  };
  EXPECT_TRUE(refused([&] { geodesic_distance(m, FrontSource::vertex(VertexHandle(0))); }));
  EXPECT_TRUE(refused([&] { geodesic_distance(m, FrontSource::vertex(VertexHandle(0)), {.method = DistanceMethod::Fast}); }));
  EXPECT_TRUE(refused([&] { dijkstra_distance(m, FrontSource::vertex(VertexHandle(0))); }));
  EXPECT_TRUE(refused([&] { geodesic_distance(m, std::vector<SurfacePoint>{{FaceHandle(0)}}); }));
  EXPECT_TRUE(refused([&] { edge_front_levels(m, FrontSource::vertex(VertexHandle(0))); }));
  EXPECT_TRUE(refused([&] { connection_path(m, VertexHandle(0), VertexHandle(5)); }));
  EXPECT_TRUE(refused([&] { twist::detect(m); }));
  EXPECT_TRUE(refused([&] { twist::repair(m); }));

  restore_attributes(m);
  EXPECT_TRUE(has_attributes(m));
  EXPECT_TRUE(twist::detect(m).empty());
  const DistanceField d = geodesic_distance(m, FrontSource::vertex(VertexHandle(0)));
  EXPECT_NEAR(*std::max_element(d.distance.begin(), d.distance.end()), 3.1, 0.1);
}

TEST(Mesh, AnyOpenMeshConvertsThroughArrays) {
  FloatMesh host = float_sphere();
  host.request_face_status();
  host.request_vertex_status();
  host.request_edge_status();
  host.request_halfedge_status();
  host.delete_face(FloatMesh::FaceHandle(3), false);  // a hole; indices of the rest stay in order
  const ArrayMesh m = mesh_from_openmesh(host);
  EXPECT_TRUE(has_attributes(m.mesh));
  EXPECT_EQ(m.mesh.n_faces(), host.n_faces() - 1);
  EXPECT_EQ(m.mesh.n_vertices(), host.n_vertices());
  for (VertexHandle v : m.mesh.vertices()) {
    for (int k = 0; k < 3; ++k) EXPECT_EQ(m.mesh.point(v)[k], static_cast<double>(host.point(FloatMesh::VertexHandle(v.idx()))[k]));
  }
  EXPECT_EQ(m.face_of_row[3], 3);  // rows after the deleted face move up by one
  const MeshArrays a = openmesh_to_arrays(float_sphere());
  EXPECT_EQ(a.n_faces(), host.n_faces());
}

}  // namespace
