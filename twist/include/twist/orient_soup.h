#pragma once
/// \file orient_soup.h
/// Building a consistently oriented half-edge mesh from a triangle soup whose faces may be wound
/// either way, including non-orientable surfaces (a Möbius band), which a half-edge mesh cannot
/// hold: orientations are propagated breadth-first across shared edges; where two faces meet
/// with incompatible windings after propagation, the edge is cut (its vertices duplicated on one
/// side), and the result is reported as non-orientable.

#include <array>
#include <cstddef>
#include <vector>

#include "edgefront/mesh.h"

namespace twist {

/// What `orient_soup` built and changed.
struct SoupOrientation {
  edgefront::Mesh mesh;            ///< oriented, manifold where the soup is
  bool non_orientable = false;     ///< some edge had to be cut: the surface cannot be oriented
  size_t faces_reversed = 0;       ///< faces whose winding was reversed
  size_t cut_edges = 0;            ///< edges cut open because of orientation conflicts
  size_t vertices_duplicated = 0;  ///< vertex copies made for the cut
  size_t faces_dropped = 0;        ///< faces OpenMesh refused (edges with 3+ faces); 0 for a manifold soup
};

/// Orients a triangle soup into a half-edge mesh (see the file comment).
/// \param points vertex positions (finite)
/// \param triangles vertex indices into `points`, three distinct per face
/// \throws edgefront::InvalidInput for no triangles, indices out of range, a repeated index in a
///         triangle, or non-finite points.
SoupOrientation orient_soup(const std::vector<edgefront::Vec3>& points,
                            const std::vector<std::array<int, 3>>& triangles);

}  // namespace twist
