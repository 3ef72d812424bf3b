#pragma once
/// \file mesh_stats.h
/// Counts and measures of a mesh: elements, components, border loops, Euler characteristic and
/// genus per component, non-manifold vertices, degenerate and duplicate faces, bounding box, edge
/// lengths, valences. Also the connected-component labelling other modules reuse.

#include <cstddef>
#include <string>
#include <vector>

#include "edgefront/mesh.h"

namespace edgefront {

/// A triangle counts as degenerate when its area is <= kDegenerateAreaFactor * d^2, d the
/// diagonal of the mesh's bounding box (so exactly zero-area triangles always count). Used by
/// compute_stats and by read_mesh's report.
inline constexpr double kDegenerateAreaFactor = 1e-12;

/// Counts and measures of the live elements of a mesh (compute_stats). Lengths are in the mesh's
/// length unit.
struct MeshStats {
  size_t vertices = 0;              ///< live (non-deleted) vertices, isolated ones included
  size_t faces = 0;                 ///< live faces
  size_t edges = 0;                 ///< live edges
  size_t isolated_vertices = 0;     ///< live vertices without an incident edge
  size_t components = 0;            ///< connected components; an isolated vertex is one
  size_t border_loops = 0;          ///< cycles of boundary halfedges
  size_t nonmanifold_vertices = 0;  ///< vertices whose faces form more than one fan (> 1 boundary gap)
  size_t degenerate_faces = 0;      ///< see kDegenerateAreaFactor
  size_t duplicate_faces = 0;       ///< faces with the vertex set of a face with a lower index
  long euler_characteristic = 0;    ///< V - E + F over live elements

  /// The counts of one connected component.
  struct Component {
    size_t vertices = 0;      ///< live vertices of the component
    size_t faces = 0;         ///< live faces of the component
    size_t border_loops = 0;  ///< cycles of boundary halfedges of the component
    long euler = 0;    ///< V - E + F of the component
    double genus = 0;  ///< (2 - euler - border_loops) / 2; meaningful for orientable manifold surfaces
                       ///< (a half-integer hints at a non-orientable or non-manifold one, and an
                       ///< isolated vertex gives 0.5)
  };
  /// In the order of components' lowest vertex index (the labels of connected_components).
  std::vector<Component> per_component;

  Vec3 bbox_min = Vec3(0, 0, 0);  ///< of the live vertices; zero for an empty mesh
  Vec3 bbox_max = Vec3(0, 0, 0);  ///< of the live vertices; zero for an empty mesh
  double bbox_diagonal = 0;       ///< |bbox_max - bbox_min|; 0 for an empty mesh or a single point
  double mean_edge_length = 0;    ///< over live edges; 0 without edges
  double min_edge_length = 0;     ///< shortest live edge; 0 without edges
  double max_edge_length = 0;     ///< longest live edge; 0 without edges
  /// valence_histogram[k] = number of live vertices with k incident edges (size: max valence + 1;
  /// empty for a mesh without vertices).
  std::vector<size_t> valence_histogram;
};

/// Statistics of the live (non-deleted) elements of `mesh`. Linear time.
/// \return counts, measures (in the mesh's length unit) and per-component figures.
/// \throw InternalError if the halfedge structure is inconsistent (a boundary cycle that does
///        not close).
MeshStats compute_stats(const Mesh& mesh);

/// Readable multi-line text of `stats` (ends with a newline).
std::string format_stats(const MeshStats& stats);

/// Connected components over the live edges.
struct ComponentLabels {
  /// Per vertex index: the component (0-based) of the vertex, -1 for deleted vertices. Components
  /// are numbered in the order of their lowest vertex index; an isolated vertex is its own
  /// component.
  std::vector<int> vertex_component;
  size_t count = 0;  ///< number of components
};

/// Labels the connected components of `mesh` (deterministic; linear time).
ComponentLabels connected_components(const Mesh& mesh);

}  // namespace edgefront
