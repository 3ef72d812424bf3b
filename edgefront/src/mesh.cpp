#include "edgefront/mesh.h"

#include <string>

#include "edgefront/error.h"

namespace edgefront {

bool has_attributes(const Mesh& mesh) {
  return mesh.has_vertex_status() && mesh.has_edge_status() && mesh.has_halfedge_status() && mesh.has_face_status() &&
         mesh.has_face_normals();
}

void restore_attributes(Mesh& mesh) {
  if (!mesh.has_vertex_status()) mesh.request_vertex_status();
  if (!mesh.has_edge_status()) mesh.request_edge_status();
  if (!mesh.has_halfedge_status()) mesh.request_halfedge_status();
  if (!mesh.has_face_status()) mesh.request_face_status();
  if (!mesh.has_face_normals()) mesh.request_face_normals();
  mesh.update_face_normals();
}

void require_attributes(const Mesh& mesh, const char* what) {
  if (has_attributes(mesh)) return;
  throw InvalidInput(std::string(what) +
                     ": the mesh lacks its status attributes or face normals (Mesh::assign from an OpenMesh mesh of "
                     "other traits drops them): call edgefront::restore_attributes(mesh) after assign, or convert with "
                     "edgefront::mesh_from_openmesh");
}

}  // namespace edgefront
