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

OpenMesh::VPropHandleT<int> property_of(Mesh& mesh) {
  OpenMesh::VPropHandleT<int> prop;
  if (!find_property(mesh, prop)) mesh.add_property(prop, kTwinProperty);
  return prop;
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
  prop = property_of(mesh);
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

std::vector<VertexHandle> split_pinched_vertices(Mesh& mesh) {
  std::vector<VertexHandle> origin;  // per copy, the vertex it was split from
  const size_t n0 = mesh.n_vertices();
  std::vector<std::vector<HalfedgeHandle>> fans;
  for (size_t i = 0; i < n0; ++i) {
    const VertexHandle v(static_cast<int>(i));
    if (mesh.status(v).deleted() || mesh.is_manifold(v)) continue;
    // The fans, each as its outgoing halfedges in the walk order next(opposite(h)): from the
    // fan's outgoing border halfedge to the halfedge whose opposite is its incoming border
    // halfedge. The border loop goes on from there into the next fan's outgoing border halfedge.
    HalfedgeHandle start;
    for (HalfedgeHandle h : mesh.voh_range(v)) {
      if (mesh.is_boundary(h)) {
        start = h;
        break;
      }
    }
    EF_CHECK(start.is_valid(), "a non-manifold vertex without a border halfedge");
    fans.clear();
    const size_t guard = 2 * mesh.n_halfedges() + 2;
    HalfedgeHandle h = start;
    size_t steps = 0;
    do {
      fans.emplace_back();
      while (true) {
        EF_CHECK(++steps <= guard, "the fans of vertex " + std::to_string(i) + " do not close");
        fans.back().push_back(h);
        const HalfedgeHandle in = mesh.opposite_halfedge_handle(h);
        h = mesh.next_halfedge_handle(in);
        if (mesh.is_boundary(in)) break;  // the fan's incoming border halfedge: the next fan follows
      }
    } while (h != start);
    if (fans.size() < 2) continue;
    std::vector<VertexHandle> group{v};
    const Vec3 at = mesh.point(v);  // (a copy: adding vertices moves the points)
    for (size_t f = 0; f < fans.size(); ++f) {
      VertexHandle owner = v;
      if (f > 0) {
        owner = mesh.add_vertex(at);
        group.push_back(owner);
        origin.push_back(v);
        for (HalfedgeHandle g : fans[f]) mesh.set_vertex_handle(mesh.opposite_halfedge_handle(g), owner);
      }
      // Each fan's border closes on itself: its incoming border halfedge continues with its
      // outgoing one.
      mesh.set_next_halfedge_handle(mesh.opposite_halfedge_handle(fans[f].back()), fans[f].front());
      mesh.set_halfedge_handle(owner, fans[f].front());
    }
    // The copies join v's group (v's existing twins stay in it): v -> copies -> v's old next.
    const OpenMesh::VPropHandleT<int> prop = property_of(mesh);
    const int old_next = mesh.property(prop, v);
    for (size_t k = 0; k + 1 < group.size(); ++k) mesh.property(prop, group[k]) = group[k + 1].idx() + 1;
    mesh.property(prop, group.back()) = old_next != 0 ? old_next : v.idx() + 1;
  }
  return origin;
}

TwinRing::TwinRing(const Mesh& mesh) {
  OpenMesh::VPropHandleT<int> prop;
  if (!find_property(mesh, prop) || mesh.n_vertices() == 0) return;
  next_ = mesh.property(prop).data_vector().data();
  n_ = static_cast<int>(mesh.n_vertices());
}

}  // namespace edgefront
