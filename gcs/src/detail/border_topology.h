#pragma once
// The built-in topology changes of the GCS loop (neural-mesh style): removing triangles that no
// sample supports and overlong edges (borders appear), cleaning what that leaves (non-manifold
// vertices, tiny components), and joining two border loops by a strip of triangles (handles).
// Every function leaves a valid manifold oriented triangle mesh (deleted elements not collected).

#include <array>
#include <cstddef>
#include <functional>
#include <limits>
#include <vector>

#include "../../../twist/src/detail/border_join.h"  // the border joins the twist layer shares
#include "edgefront/mesh.h"
#include "edgefront/mesh_stats.h"

namespace gcs::detail {

/// The input sample nearest to a point: its distance and its (unoriented) unit normal, NaN when
/// unknown.
struct CloudHit {
  double distance = 0;
  edgefront::Vec3 normal{0, 0, 0};
  edgefront::Vec3 point{0, 0, 0};  ///< the sample (filled by CloudNeighbors; CloudQuery may leave it)
  /// the sample's index in the searched points (kNoSample when the query does not say)
  std::size_t index = kNoSample;
  static constexpr std::size_t kNoSample = std::numeric_limits<std::size_t>::max();
};
using CloudQuery = std::function<CloudHit(const edgefront::Vec3&)>;
/// The (up to) k input samples nearest to a point, nearest first, written into `out`.
using CloudNeighbors = std::function<void(const edgefront::Vec3&, std::size_t k, std::vector<CloudHit>& out)>;

/// The centroid of face f (a triangle).
edgefront::Vec3 centroid(const edgefront::Mesh& mesh, edgefront::FaceHandle f);
/// The (unnormalized) normal of face f: twice its area along its unit normal.
edgefront::Vec3 face_normal(const edgefront::Mesh& mesh, edgefront::FaceHandle f);

struct BorderParams {
  double max_support_distance = 0;  ///< faces whose centroid is farther from the cloud are removed
  double max_edge_length = 0;       ///< faces with a longer edge are removed
  /// faces whose normal makes |cos| below this with the nearest sample's normal are removed
  double min_normal_cos = 0.35;
  /// ... when the centroid is at least this far from the nearest sample
  double normal_check_distance = 0;
  /// Film test (needs a CloudNeighbors with oriented normals): a face is removed when every one of
  /// the `film_samples` samples nearest to its centroid that lie within max_support_distance faces
  /// sideways to it (|cos| of the normals below film_min_cos) and has the centroid in front of it
  /// (on its normal's side): a film spanning a tunnel or gap outside the object (e.g. the one
  /// across kitten.xyz's tail tunnel), which no sample facing like it supports. A sample without a
  /// normal (NaN) keeps the face. 0 = off.
  std::size_t film_samples = 0;
  double film_min_cos = 0.5;

  std::size_t min_component_faces = 8;  ///< components with fewer faces are removed
  double min_component_fraction = 0.05;  ///< ... or with fewer than this share of the largest's faces
  /// ... unless they lie on a part of the cloud of their own (see clean_topology; empty: no
  /// component is spared): the part of the cloud of a sample index.
  std::function<int(std::size_t)> sample_part;
};

/// The sample nearest to each face's centroid, indexed by face index (entries of faces that are
/// deleted or were added later are meaningless). remove_unsupported_faces hands the nearest samples
/// it found to remove_opposed_faces (double_layer.h) this way, so the second test needs no search.
using FaceNearest = std::vector<CloudHit>;

/// Removes unsupported faces (and vertices left without faces), then non-manifold fans and tiny
/// components. Returns the number of faces removed. Never empties the mesh: when every face
/// would go, nothing is removed.
/// `neighbors` (may be empty: no film test) serves BorderParams::film_samples; with the film test
/// on, one search per face serves both tests: the nearest sample is the first of `neighbors`'
/// answer (`cloud` is then not called). When `nearest` is given, it receives the nearest sample of
/// every face the mesh had on entry (the faces still there after the call included), as found.
std::size_t remove_unsupported_faces(edgefront::Mesh& mesh, const CloudQuery& cloud,
                                     const BorderParams& params, const CloudNeighbors& neighbors = {},
                                     FaceNearest* nearest = nullptr);

/// The sample nearest to every face's centroid by `cloud` (a FaceNearest for a mesh whose support
/// test did not run, e.g. in tests).
FaceNearest face_nearest(const edgefront::Mesh& mesh, const CloudQuery& cloud);

/// Where the faces' nearest samples lie in the cloud: `nearest` by face index (FaceNearest) and
/// the part of the cloud (double_layer.h: cloud_parts) of a sample index. Empty (no nearest or no
/// sample_part): nothing is known, no piece is spared.
struct SeparateParts {
  const FaceNearest* nearest = nullptr;
  std::function<int(std::size_t)> sample_part;
  explicit operator bool() const { return nearest && sample_part; }
};

/// For each component of `labels` (face counts `faces`), whether it is a separate surface: the
/// largest of the components whose faces' nearest samples lie mostly on one part of the cloud,
/// for every part but the one most of the largest component's faces lie on (nested spheres' inner
/// sphere, a leg of a one-sided scan seen apart from the body). Other pieces, fragments of some
/// surface, are judged as before by the rules that remove small pieces.
std::vector<char> separate_surfaces(const edgefront::Mesh& mesh, const edgefront::ComponentLabels& labels,
                                    const std::vector<std::size_t>& faces, const SeparateParts& parts);

/// Deletes faces until no vertex has more than one fan (keeps each vertex's largest fan) and
/// removes components other than the largest with fewer than max(min_faces, min_fraction x the
/// largest's face count) faces, but the separate surfaces (with `parts`: separate_surfaces).
/// Returns the number of faces removed.
std::size_t clean_topology(edgefront::Mesh& mesh, std::size_t min_faces, double min_fraction = 0,
                           const SeparateParts& parts = {});

struct MergeParams {
  double mean_edge_length = 0;
  double max_support_distance = 0;   ///< strip face centroids must be this close to the cloud
  double max_gap_edges = 4.0;        ///< mean distance between matched loop vertices, in mean edge lengths
  double max_gap_fraction = 0.1;     ///< ... or this fraction of the shorter loop's length
  double max_length_ratio = 1.6;     ///< longer loop length / shorter loop length
  double min_normal_agreement = 0.2; ///< mean cosine between strip faces and the faces they border
  /// A close, similar, orientation-compatible pair whose strip is refused (the rims curl away from
  /// the gap or slid past each other) is tried again with 1 ... this many rings of faces removed
  /// along both loops (on a copy; kept only when the strip is then added). 0 = off.
  std::size_t max_trim_rings = 0;
};

/// Joins pairs of border loops that are close, of similar length and orientation-compatible
/// (their boundary halfedges run opposite) with a strip of triangles. Returns the number of
/// pairs joined (each loop in at most one pair per call).
std::size_t merge_border_loops(edgefront::Mesh& mesh, const CloudQuery& cloud, const MergeParams& params);

/// Parameters of zip_border_slits (shared with the twist layer's heal).
using ZipParams = twist::detail::ZipParams;

/// Closes slits: where two border chains (of the same loop or of two loops) run close to each other
/// (within max_gap_edges mean edge lengths) in opposite directions, the gap between them is closed
/// by a strip of triangles, seeded at the closest pair and extended both ways while the chains stay
/// within max_gap_edges. A slit within one loop splits it in two; between two loops it joins
/// them. Strips must lie on the cloud and agree with the faces they border (as in
/// merge_border_loops). This is how a torn handle closes into a tube (the kitten's tail). Returns
/// the number of strips added.
std::size_t zip_border_slits(edgefront::Mesh& mesh, const CloudQuery& cloud, const ZipParams& params);

/// Retrying a refused hole fill after removing rings of faces along the loop (a curled rim).
struct TrimParams {
  std::size_t rings = 0;         ///< 1 ... this many rings are tried; 0 = off
  double max_loop_length = 0;    ///< only for loops at most this long
};

/// A hole whose closing was refused (its rim curls): on a copy, removes 1 ... `rings` rings of
/// faces along the loop and tries `close` on the wider loop; keeps the copy when that succeeds and
/// the mesh keeps its number of components. Returns whether the mesh was changed.
bool trim_and_close(edgefront::Mesh& mesh, const twist::detail::BorderLoop& loop, std::size_t rings,
                    const std::function<bool(edgefront::Mesh&, const twist::detail::BorderLoop&)>& close);

/// Closes small holes: a border loop of at most `max_vertices` vertices whose fan of triangles
/// around the loop's centroid lies within `max_support_distance` of the cloud and agrees with the
/// neighbouring faces (mean cosine >= min_normal_agreement) is filled by that fan (one new vertex;
/// a loop of 3 vertices by its own triangle, which only needs a mean cosine above
/// min(0, min_normal_agreement): it must not fold back).
/// With `trim` on, a loop of at most trim.max_loop_length whose fill is refused is tried again on a
/// copy with 1 ... trim.rings rings of faces along it removed, filled by a fan of any size; the
/// copy is kept when that fan is added and the number of components stays (the call then stops).
/// Returns the number of loops filled.
std::size_t fill_small_holes(edgefront::Mesh& mesh, const CloudQuery& cloud, std::size_t max_vertices,
                             double max_support_distance, double min_normal_agreement, const TrimParams& trim = {});

/// The triangulation of least total area of the polygon `points` (a closed loop, in order): an
/// O(n^3) dynamic programme over the sub-polygons p_i ... p_j, using the chord p_i p_j (i < j, not
/// a side of the polygon) only where `usable(i, j)` says so, and no zero-area triangle. Triangles
/// as (i, k, j) with i < k < j (the loop's winding); empty when there is none (or n < 3).
/// With `rim_normals` (one per side p_k p_k+1, k taken cyclically: the normal of the face beyond
/// it), the triangulation whose largest fold between neighbouring triangles (and against those
/// faces at the sides) is least is chosen first, the area deciding between equals (Liepa 2003).
std::vector<std::array<std::size_t, 3>> least_area_triangulation(
    const std::vector<edgefront::Vec3>& points, const std::function<bool(std::size_t, std::size_t)>& usable,
    const std::vector<edgefront::Vec3>& rim_normals = {});

/// Closes small holes one at a time, each on a copy of the mesh that is kept only when `accept`
/// (called with the copy, which it may change) returns true, e.g. when the fill crosses nothing.
/// A border loop of 3 ... max_vertices distinct vertices is first tried with the fan of fill_small_holes (same checks);
/// when that is refused or not accepted and the loop passes through a vertex flagged in
/// `triangulate_at` (indexed by vertex index; may be shorter than the vertex array: unflagged),
/// it is tried with the triangulation of least area over its own vertices (no new vertex, no
/// diagonal that is an edge already): every face's centroid within max_support_distance of the
/// cloud, and the faces along the loop, on the mean, not folded back over the faces they border
/// (mean cosine > 0). The loops are the mesh's on entry, in border_loops order; filling one does
/// not change the others. Returns the number of loops filled.
std::size_t fill_small_holes_checked(edgefront::Mesh& mesh, const CloudQuery& cloud, std::size_t max_vertices,
                                     double max_support_distance, double min_normal_agreement,
                                     const std::vector<char>& triangulate_at,
                                     const std::function<bool(edgefront::Mesh&)>& accept);

/// Closes elongated holes (slits in a closed surface: a sparsely sampled stretch whose faces were
/// removed): a border loop of min_vertices ... max_vertices distinct vertices is filled by one
/// strip of triangles zipping its two halves together, from the tip pair farthest apart (up to 3
/// tip pairs are tried). The strip must lie on the cloud and agree with the faces it borders (as in
/// merge_border_loops). With trim_rings > 0, a loop whose strip is refused (curled rims) is tried
/// again on a copy with 1 ... trim_rings rings of faces along it removed (the wider loop may have
/// more than max_vertices vertices); the copy is kept when the strip is added and the number of
/// components stays (the call then stops). Returns the number of loops filled.
std::size_t fill_slit_holes(edgefront::Mesh& mesh, const CloudQuery& cloud, std::size_t min_vertices,
                            std::size_t max_vertices, double max_support_distance, double min_normal_agreement,
                            std::size_t trim_rings = 0);

}  // namespace gcs::detail
