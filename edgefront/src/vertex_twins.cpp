// Vertex twins: a ring per group, stored as an OpenMesh vertex property.

#include "edgefront/vertex_twins.h"

#include <algorithm>
#include <string>

#include "edgefront/error.h"

namespace edgefront {

namespace {

// The property: per vertex, 1 + the index of the next twin; 0 (OpenMesh's default value for a
// new vertex) means "no twins".
constexpr const char* kTwinProperty = "edgefront:twin_next";

bool find_property(const Mesh& mesh, OpenMesh::VPropHandleT<int>& prop) {
  return mesh.get_property_handle(prop, kTwinProperty);
}

}  // namespace

void link_twins(Mesh& mesh, const std::vector<VertexHandle>& group) {
  if (group.size() < 2) throw InvalidInput("link_twins: a group of twins needs at least 2 vertices");
  OpenMesh::VPropHandleT<int> prop;
  const bool had = find_property(mesh, prop);
  for (size_t i = 0; i < group.size(); ++i) {
    const VertexHandle v = group[i];
    if (!is_live(mesh, v)) {
      throw InvalidInput("link_twins: vertex " + std::to_string(v.idx()) + " is not a vertex of the mesh");
    }
    if (std::find(group.begin(), group.begin() + static_cast<std::ptrdiff_t>(i), v) !=
        group.begin() + static_cast<std::ptrdiff_t>(i)) {
      throw InvalidInput("link_twins: vertex " + std::to_string(v.idx()) + " is listed twice");
    }
    if (had && mesh.property(prop, v) != 0) {
      throw InvalidInput("link_twins: vertex " + std::to_string(v.idx()) + " already has twins");
    }
  }
  if (!had) mesh.add_property(prop, kTwinProperty);
  for (size_t i = 0; i < group.size(); ++i) mesh.property(prop, group[i]) = group[(i + 1) % group.size()].idx() + 1;
}

void clear_twins(Mesh& mesh) {
  OpenMesh::VPropHandleT<int> prop;
  if (find_property(mesh, prop)) mesh.remove_property(prop);
}

bool has_twins(const Mesh& mesh) {
  OpenMesh::VPropHandleT<int> prop;
  if (!find_property(mesh, prop)) return false;
  for (const VertexHandle v : mesh.vertices()) {
    if (mesh.property(prop, v) != 0) return true;
  }
  return false;
}

std::vector<VertexHandle> twins_of(const Mesh& mesh, VertexHandle v) {
  std::vector<VertexHandle> out;
  if (!v.is_valid() || static_cast<size_t>(v.idx()) >= mesh.n_vertices()) return out;
  const TwinRing ring(mesh);
  // Bounded: a ring broken by a renumbering (see the header) cannot loop forever.
  for (VertexHandle u = ring.next(v); u != v && out.size() < mesh.n_vertices(); u = ring.next(u)) out.push_back(u);
  return out;
}

TwinRing::TwinRing(const Mesh& mesh) : mesh_(&mesh) { any_ = find_property(mesh, prop_) && has_twins(mesh); }

VertexHandle TwinRing::next(VertexHandle v) const {
  if (!any_) return v;
  const int next = mesh_->property(prop_, v);
  if (next <= 0 || static_cast<size_t>(next - 1) >= mesh_->n_vertices()) return v;
  return VertexHandle(next - 1);
}

}  // namespace edgefront
