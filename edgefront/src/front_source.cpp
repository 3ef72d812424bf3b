#include "edgefront/front_source.h"

#include <algorithm>
#include <string>
#include <unordered_set>

#include "edgefront/error.h"

namespace edgefront {

namespace {
std::string vname(VertexHandle v) { return "vertex " + std::to_string(v.idx()); }
}  // namespace

FrontSource loop_from_vertices(const Mesh& mesh, const std::vector<VertexHandle>& path, LoopSide side) {
  require_attributes(mesh, "loop source");
  if (path.size() < 3) {
    throw InvalidInput("loop source: a closed edge path needs at least 3 vertices, got " +
                       std::to_string(path.size()));
  }
  std::unordered_set<int> seen;
  for (VertexHandle v : path) {
    if (!is_live(mesh, v)) throw InvalidInput("loop source: " + vname(v) + " is not a vertex of the mesh");
    if (!seen.insert(v.idx()).second) {
      throw InvalidInput("loop source: " + vname(v) + " is visited twice; the path must not intersect itself");
    }
  }
  std::vector<HalfedgeHandle> hs;
  hs.reserve(path.size());
  for (size_t i = 0; i < path.size(); ++i) {
    const VertexHandle a = path[i];
    const VertexHandle b = path[(i + 1) % path.size()];
    const HalfedgeHandle h = mesh.find_halfedge(a, b);
    if (!h.is_valid()) {
      throw InvalidInput("loop source: " + vname(a) + " and " + vname(b) +
                         " are not joined by an edge, so the path is not closed along mesh edges");
    }
    hs.push_back(h);
  }
  if (side == LoopSide::Right) {
    std::vector<HalfedgeHandle> rev;
    rev.reserve(hs.size());
    for (auto it = hs.rbegin(); it != hs.rend(); ++it) rev.push_back(mesh.opposite_halfedge_handle(*it));
    hs = std::move(rev);
  }
  FrontSource src = FrontSource::from_halfedges(std::move(hs));
  validate_source(mesh, src);
  return src;
}

void validate_source(const Mesh& mesh, const FrontSource& source) {
  require_attributes(mesh, "front source");
  if (source.vertices.empty() && source.loop.empty()) throw InvalidInput("front source is empty");
  if (!source.vertices.empty() && !source.loop.empty()) {
    throw InvalidInput("front source names both vertices and a loop; give one of them");
  }
  if (!source.vertices.empty()) {
    std::unordered_set<int> seen;
    for (VertexHandle v : source.vertices) {
      if (!is_live(mesh, v)) {
        throw InvalidInput("front source: " + vname(v) + " is not a vertex of the mesh (" +
                           std::to_string(mesh.n_vertices()) + " vertices)");
      }
      if (!seen.insert(v.idx()).second) throw InvalidInput("front source: " + vname(v) + " is given twice");
    }
    return;
  }
  const auto& loop = source.loop;
  if (loop.size() < 3) {
    throw InvalidInput("loop source: a closed edge path needs at least 3 halfedges, got " +
                       std::to_string(loop.size()));
  }
  std::unordered_set<int> seen;
  for (size_t i = 0; i < loop.size(); ++i) {
    const HalfedgeHandle h = loop[i];
    if (!is_live(mesh, h)) {
      throw InvalidInput("loop source: halfedge " + std::to_string(h.idx()) + " is not a halfedge of the mesh");
    }
    const HalfedgeHandle n = loop[(i + 1) % loop.size()];
    if (!is_live(mesh, n)) {
      throw InvalidInput("loop source: halfedge " + std::to_string(n.idx()) + " is not a halfedge of the mesh");
    }
    if (mesh.to_vertex_handle(h) != mesh.from_vertex_handle(n)) {
      throw InvalidInput("loop source: halfedge " + std::to_string(i) + " ends at " +
                         vname(mesh.to_vertex_handle(h)) + " but the next one starts at " +
                         vname(mesh.from_vertex_handle(n)) + "; the path is not closed");
    }
    if (!seen.insert(mesh.to_vertex_handle(h).idx()).second) {
      throw InvalidInput("loop source: " + vname(mesh.to_vertex_handle(h)) +
                         " is visited twice; the path must not intersect itself");
    }
    if (mesh.is_boundary(h)) {
      throw InvalidInput("loop source: halfedge " + std::to_string(i) + " (" + vname(mesh.from_vertex_handle(h)) +
                         " -> " + vname(mesh.to_vertex_handle(h)) +
                         ") has no face on its ahead side (it runs along the mesh border)");
    }
  }
}

}  // namespace edgefront
