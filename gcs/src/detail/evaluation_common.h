#pragma once
// What the evaluation's parts share. Internal. The parts:
//   evaluation.cpp          input checks, sampling, the metrics (distances, orientation), evaluate;
//   self_intersections.cpp  self-intersecting face pairs and the mesh's validity;
//   evaluation_output.cpp   the evaluation as text and as JSON.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "edgefront/error.h"
#include "edgefront/geometry.h"
#include "edgefront/mesh.h"
#include "edgefront/triangle_bvh.h"
#include "gcs/evaluation.h"

namespace gcs::detail::eval {

using edgefront::Mesh;
using edgefront::Vec3;

inline constexpr double kInf = std::numeric_limits<double>::infinity();

// The geometry is the shared kernel's (edgefront/geometry.h, edgefront/triangle_bvh.h).
using Box = edgefront::AlignedBox;
using edgefront::Triangle;
using edgefront::TriangleBvh;

// Live faces of the mesh as triangles; `face_of[i]` is the face index of triangle i.
inline std::vector<Triangle> mesh_triangles(const Mesh& mesh, std::vector<int>* face_of = nullptr) {
  std::vector<Triangle> tris;
  tris.reserve(mesh.n_faces());
  for (const auto f : mesh.faces()) {
    if (mesh.status(f).deleted()) continue;
    tris.push_back(edgefront::face_triangle(mesh, f));
    if (face_of) face_of->push_back(f.idx());
  }
  return tris;
}

// \throw InvalidInput when a live vertex of `mesh` has a NaN or infinite coordinate or one beyond
// kMaxCoordinate (`what` names the mesh in the message). In evaluation.cpp.
void check_mesh_coordinates(const Mesh& mesh, const char* what);

// Validity of `mesh`; `bvh` (over the mesh's live faces) is reused when given.
// In self_intersections.cpp.
MeshValidity validity_of(const Mesh& mesh, bool count_self, const TriangleBvh* bvh, unsigned threads = 1);

}  // namespace gcs::detail::eval
