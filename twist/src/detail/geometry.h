#pragma once
// Private helpers of the twist library: face geometry and the face-set surgery (re-adding faces
// reversed, with cut vertices duplicated). The triangle-triangle test is the kernel's
// (edgefront/geometry.h).

#include <array>
#include <cstddef>
#include <memory>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "edgefront/mesh.h"

namespace twist::detail {

using edgefront::FaceHandle;
using edgefront::Mesh;
using edgefront::Vec3;
using edgefront::VertexHandle;

std::array<Vec3, 3> face_points(const Mesh& mesh, FaceHandle f);
/// Unit normal, or zero for a degenerate face.
Vec3 unit_normal(const std::array<Vec3, 3>& p);
double area(const std::array<Vec3, 3>& p);
Vec3 centroid(const std::array<Vec3, 3>& p);

/// The live border halfedges that lie on top of another border halfedge running the same way
/// (their end points coincide within 1e-9 of the bounding-box diagonal): one group per such
/// position, groups in the order of their quantized end points, each group in halfedge order.
/// A reversed seam: a part turned over by hand or wound the other way, split from its neighbours.
std::vector<std::vector<edgefront::HalfedgeHandle>> coincident_border_halfedges(const Mesh& mesh);

/// Does the segment p-q cross the interior of triangle t (not merely touch it: its ends lie more
/// than `eps` off t's plane on opposite sides, and the crossing more than `eps` inside every edge)?
bool segment_crosses(const Vec3& p, const Vec3& q, const std::array<Vec3, 3>& t, double eps);

/// How deeply the two triangles overlap when both are projected along `direction` (unit) onto a
/// plane: the smallest overlap of their projections onto the six in-plane edge normals (the
/// separating axes of two convex polygons). Positive when the projections overlap (the depth of
/// the overlap, a length), zero or negative when they only touch or are apart.
double projected_overlap(const std::array<Vec3, 3>& a, const std::array<Vec3, 3>& b, const Vec3& direction);

/// `LayerRule::Stacked`'s overlap test for two triangles with the same orientation, given their
/// unit normals and longest edges: projected along their mean normal, they overlap by more than
/// 0.1 times the shorter longest edge.
bool stacked_layers(const std::array<Vec3, 3>& a, const Vec3& na, double la, const std::array<Vec3, 3>& b,
                    const Vec3& nb, double lb);

/// The copy journal: when a mesh has this int vertex property (edit records add it), every copy
/// made by `copy_vertex` records 1 + the index of its original (0: not a copy).
inline constexpr const char* kCopyJournal = "twist:copy_of";

/// Appends a copy of `v` (same position) and notes it in the copy journal when the mesh has one.
/// Every vertex copy the surgery makes goes through here.
VertexHandle copy_vertex(Mesh& mesh, VertexHandle v);

/// Removes the faces of `side` from the mesh and adds them again with reversed winding (when
/// `reverse`), giving every vertex where `side` meets other faces one new copy per fan of `side`
/// faces around it, so `side` becomes its own component(s). Faces are re-added in the given
/// order (pass a breadth-first order). Returns the number of vertices duplicated and appends the
/// (duplicate, original) pairs to `duplicates`.
/// \throws edgefront::InternalError if OpenMesh refuses a face.
size_t cut_and_reverse(Mesh& mesh, const std::vector<FaceHandle>& side, bool reverse,
                       std::vector<std::pair<VertexHandle, VertexHandle>>* duplicates);

/// Gives every fan of faces around `v` but the first its own copy of `v` (re-adding those faces),
/// so `v` becomes manifold. Returns the number of copies made.
size_t split_fans(Mesh& mesh, VertexHandle v);

/// Throws InvalidInput when the mesh has no live face or a non-finite coordinate.
void check_mesh(const Mesh& mesh, const char* what);

/// Mean length of the live edges.
double mean_edge_length(const Mesh& mesh);

}  // namespace twist::detail
