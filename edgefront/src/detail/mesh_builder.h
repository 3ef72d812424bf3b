#pragma once
/// \file mesh_builder.h
/// Private: the one place that turns a vertex list and a triangle list into an `edgefront::Mesh`
/// (the array conversion and the file readers): faces a half-edge mesh cannot hold are dropped
/// (reported), pinched vertices split into one vertex per fan, copies appended and linked as twins.

#include <span>
#include <vector>

#include "edgefront/arrays.h"
#include "edgefront/mesh.h"

namespace edgefront::detail {

/// Vertex positions for the builder: the caller's array view, or points already read.
struct PointRows {
  const VertexArrayView* view = nullptr;
  const std::vector<Vec3>* points = nullptr;
  size_t size() const { return view ? view->rows() : points->size(); }
  Vec3 at(size_t i) const { return view ? view->point(i) : (*points)[i]; }
};

/// Builds the mesh from `triangles` (3 vertex indices per row, each in [0, points.size()), three
/// distinct per row: checked by the caller). Rows are taken in order; a row that would be the
/// third face on an edge, or use an edge in the same direction as an earlier kept row, is
/// dropped (`ArrayMesh::report.dropped_faces`). The rest is added in row order with
/// `add_face(a, b, c)` (corners replaced by copies at pinched vertices), so a manifold input gives
/// the mesh `add_face` gives, and face normals are computed. Never throws for the input's
/// topology; InternalError if OpenMesh refuses a face that passed the checks (a bug).
ArrayMesh build_mesh(const PointRows& points, std::span<const int> triangles);

}  // namespace edgefront::detail
