#pragma once
// Post-processing of the GCS result: closing false borders (PostProcessOptions::close_false_borders).
//
// On clouds sampled from closed figures the loop can leave a tube (a leg, a tail, an ear) torn open
// lengthwise where it lies within about an edge of another part: a border loop of hundreds of
// vertices whose missing side is still in the cloud. Such a border is false: samples lie beyond it
// that no face of the mesh covers (no face within a distance that faces their way). A true border
// (the rim of an open sheet, a real hole of a scan) has none. Each false loop is closed on a copy
// of the mesh by the least-area triangulation of its vertices, refined to the mesh's edge length
// and pulled onto the uncovered samples (tangentially smoothed, the rim fixed); the copy is kept
// when the patch lies on the samples, does not fold against the faces at its rim and crosses
// nothing. The mesh stays a valid manifold oriented triangle mesh.

#include <cstddef>
#include <vector>

#include "edgefront/mesh.h"

namespace gcs::detail {

struct CloseBordersParams {
  /// The mesh's mean edge length: the scale of every distance below (> 0).
  double mean_edge_length = 0;
  /// Whether the samples' normals are oriented (one side of the surface); unoriented normals
  /// (fitted to the points) serve the planes but not the coverage's facing test.
  bool normals_oriented = true;
  /// A sample is covered when a face lies within this many mean edge lengths of it (and, with
  /// normals, the nearest such face faces the sample's way).
  double covered_edges = 0.5;
  /// ... unless it lies farther than this many mean edge lengths past a border edge (its nearest
  /// point of the mesh on a border edge).
  double beyond_edges = 0.2;
  /// Uncovered samples within this many mean edge lengths of a loop vertex count for the loop.
  double near_edges = 1.5;
  /// A loop is false when it has at least this many uncovered samples near it per loop vertex ...
  double min_uncovered_per_vertex = 1.0;
  /// ... and at least min_deep_per_vertex per loop vertex within wide_edges mean edge lengths of
  /// it that lie farther than deep_edges from the mesh (the cloud goes on past the border; the
  /// cloud of an open sheet ends within about an edge of the mesh's rim: 0.04-0.07 per vertex on
  /// the vaults, 0.16-3 on the torn figures measured).
  double wide_edges = 3.0;
  double deep_edges = 1.0;
  double min_deep_per_vertex = 0.15;
  /// Loops with more vertices are left (the triangulation is cubic in the loop's length).
  std::size_t max_loop_vertices = 800;
  /// A patch with more than this many vertices per loop vertex (plus 16) is refused: the loop
  /// bounds a large missing region, not a tear.
  std::size_t max_patch_vertices_per_loop_vertex = 8;
  /// A loop whose patch is refused is tried again with 1 ... this many rings of faces along it
  /// removed (a curled rim; on a copy, kept when the wider loop's patch passes). 0 = off, the
  /// default: on the closed-model benchmark the retries closed more loops but lost surface (the
  /// patch over the wider loop took a shortcut: bull seed 3 Hausdorff-95 0.60% -> 2.61%).
  std::size_t trim_rings = 0;
  /// Rounds of pulling the patch onto the samples (each: a pull, a tangential smoothing; the
  /// patch is refined again every 8 rounds).
  int rounds = 40;
  /// A patch vertex is pulled toward the uncovered samples within this many mean edge lengths.
  double pull_edges = 4.0;
  /// A patch is kept when its vertices lie within this many mean edge lengths of the samples' planes
  /// on the mean, and each vertex and face centroid within max_sample_edges of a sample.
  double mean_sample_edges = 0.25;
  double max_sample_edges = 1.0;
  /// ... and each patch face at the rim makes a cosine of at least this with the face it borders.
  double min_rim_cos = -0.5;
  /// ... but this share of the rim's sides may fold more (a rim that curls; the crossing test
  /// still applies).
  double max_fold_fraction = 0.1;
};

struct CloseBordersReport {
  std::size_t loops = 0;           ///< border loops on entry
  std::size_t false_loops = 0;     ///< of them judged false (samples beyond them)
  std::size_t closed = 0;          ///< of those closed
  std::size_t vertices_added = 0;  ///< by the patches kept
};

/// Closes the false borders of `mesh` (see the file comment). `samples` are the cloud's points
/// and `normals` their normals (see CloseBordersParams::normals_oriented; empty: none, then
/// coverage is by distance only and the pull takes the samples' centroid; non-finite ones count as
/// none). A mesh without border loops is not changed; a loop whose
/// patch fails a check keeps its border. \throw edgefront::InvalidInput for a mean edge length
/// that is not finite and positive, normals not matching the samples, or non-positive distances.
CloseBordersReport close_false_borders(edgefront::Mesh& mesh, const std::vector<edgefront::Vec3>& samples,
                                       const std::vector<edgefront::Vec3>& normals, const CloseBordersParams& params);

}  // namespace gcs::detail
