#include "edgefront/surface_point.h"

#include <cmath>
#include <string>

#include "edgefront/error.h"

namespace edgefront {

namespace {

// `p`'s barycentric coordinates with `wa` at vertex a, `wb` at vertex b, 0 elsewhere (fv order).
SurfacePoint on_face(const Mesh& mesh, FaceHandle f, VertexHandle a, double wa, VertexHandle b, double wb) {
  SurfacePoint p;
  p.face = f;
  std::size_t k = 0;
  for (const VertexHandle u : mesh.fv_range(f)) {
    if (k < 3) p.bary[k] = u == a ? wa : (u == b ? wb : 0.0);
    ++k;
  }
  EF_CHECK(k == 3, "face " + std::to_string(f.idx()) + " is not a triangle");
  return p;
}

}  // namespace

SurfacePoint surface_point_at_vertex(const Mesh& mesh, VertexHandle v) {
  if (!is_live(mesh, v)) {
    throw InvalidInput("surface point: vertex " + std::to_string(v.idx()) + " is not a vertex of the mesh");
  }
  for (const FaceHandle f : mesh.vf_range(v)) {
    if (is_live(mesh, f)) return on_face(mesh, f, v, 1.0, VertexHandle(), 0.0);
  }
  throw InvalidInput("surface point: vertex " + std::to_string(v.idx()) + " has no face");
}

SurfacePoint surface_point_on_edge(const Mesh& mesh, HalfedgeHandle h, double t) {
  if (!is_live(mesh, h)) {
    throw InvalidInput("surface point: halfedge " + std::to_string(h.idx()) + " is not a halfedge of the mesh");
  }
  if (!(t >= 0.0 && t <= 1.0)) {
    throw InvalidInput("surface point: the edge parameter must be in [0, 1], got " + std::to_string(t));
  }
  FaceHandle f = mesh.face_handle(h);
  if (!is_live(mesh, f)) f = mesh.face_handle(mesh.opposite_halfedge_handle(h));
  if (!is_live(mesh, f)) {
    throw InvalidInput("surface point: the edge of halfedge " + std::to_string(h.idx()) + " has no face");
  }
  return on_face(mesh, f, mesh.from_vertex_handle(h), 1.0 - t, mesh.to_vertex_handle(h), t);
}

Vec3 surface_point_position(const Mesh& mesh, const SurfacePoint& p) {
  if (!is_live(mesh, p.face)) {
    throw InvalidInput("surface point: face " + std::to_string(p.face.idx()) + " is not a face of the mesh");
  }
  Vec3 x(0, 0, 0);
  std::size_t k = 0;
  for (const VertexHandle v : mesh.fv_range(p.face)) {
    if (k < 3) x += mesh.point(v) * p.bary[k];
    ++k;
  }
  return x;
}

}  // namespace edgefront
