#include "render/scene.h"

#include <string>

#include "edgefront/error.h"

namespace edgefront::render {

Polyline polyline_from_vertices(const Mesh& mesh, const std::vector<VertexHandle>& vertices, bool closed,
                                const Rgb& color) {
  Polyline line;
  line.closed = closed;
  line.color = color;
  line.points.reserve(vertices.size());
  for (const VertexHandle v : vertices) {
    if (!is_live(mesh, v)) {
      throw InvalidInput("polyline_from_vertices: vertex " + std::to_string(v.idx()) + " is not a vertex of the mesh");
    }
    line.points.push_back(mesh.point(v));
  }
  return line;
}

Polyline polyline_from_halfedges(const Mesh& mesh, const std::vector<HalfedgeHandle>& halfedges, const Rgb& color) {
  Polyline line;
  line.color = color;
  line.points.reserve(halfedges.size() + 1);
  for (const HalfedgeHandle h : halfedges) {
    if (!is_live(mesh, h)) {
      throw InvalidInput("polyline_from_halfedges: halfedge " + std::to_string(h.idx()) +
                         " is not a halfedge of the mesh");
    }
    line.points.push_back(mesh.point(mesh.from_vertex_handle(h)));
  }
  if (!halfedges.empty()) {
    const VertexHandle end = mesh.to_vertex_handle(halfedges.back());
    if (end == mesh.from_vertex_handle(halfedges.front())) {
      line.closed = true;
    } else {
      line.points.push_back(mesh.point(end));
    }
  }
  return line;
}

std::vector<Polyline> border_polylines(const Mesh& mesh, const Rgb& color, double width_px) {
  std::vector<Polyline> out;
  std::vector<bool> seen(mesh.n_halfedges(), false);
  for (const auto h : mesh.halfedges()) {
    if (seen[static_cast<size_t>(h.idx())] || !mesh.is_boundary(h)) continue;
    Polyline line;
    line.closed = true;
    line.color = color;
    line.width_px = width_px;
    HalfedgeHandle cur = h;
    // A boundary cycle is at most as long as the number of halfedges; the bound guards against
    // a broken structure.
    for (size_t guard = 0; guard <= mesh.n_halfedges(); ++guard) {
      seen[static_cast<size_t>(cur.idx())] = true;
      line.points.push_back(mesh.point(mesh.from_vertex_handle(cur)));
      cur = mesh.next_halfedge_handle(cur);
      if (cur == h) break;
    }
    EF_CHECK(cur == h, "a boundary cycle of the mesh does not close");
    out.push_back(std::move(line));
  }
  return out;
}

}  // namespace edgefront::render
