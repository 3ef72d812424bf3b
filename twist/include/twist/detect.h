#pragma once
/// \file detect.h
/// Finding twisted surface regions: parts of a (combinatorially orientable) mesh whose geometric
/// orientation disagrees with the side of the surface they approximate (Annuth & Bohn, VMV 2012,
/// as read in `/work/shared/notes/gcs-and-twist.md` §3; edge-front paper §1, Fig. 1).
///
/// Evidence, per face f (all semi-local):
/// - **Reference**: with reference normals, f's normal disagrees with the nearest oriented point.
/// - **Facing layer**: another face g lies *in front of* f (on the side f's normal points to)
///   within `radius`, roughly parallel (|n_f·n_g| >= `parallel_cos`), and is *far along the
///   surface*: a Minimal Distance Front from f's centroid, bounded by `max_distance`, does not
///   reach g within `surface_factor` times their distance. On a correctly oriented thin closed
///   structure every face has the material, not another layer of the same surface, right behind
///   it and empty space in front: layers of one thin wall are back to back. A face whose normal
///   points at another layer is twisted: either both layers face each other (a wall turned inside
///   out: both flagged) or both point the same way (two layers with the same orientation: only
///   the one pointing at the other is flagged). Convention and limit: two distinct surface parts
///   facing each other across a gap narrower than `radius` (a hairpin's arms) look like an
///   inverted wall; pass reference normals for such inputs or lower `radius`.
/// - **Folded edge**: an edge whose two faces fold onto each other (n_f·n_g <= `fold_cos`,
///   dihedral angle near 0).
/// - **Self-intersection**: f intersects a face it shares no vertex with.
///
/// Flagged faces are grown into regions with a Minimal Edge Front started at their vertices and
/// run `grow_levels` levels (this also closes small gaps between flagged patches); a region is
/// the surface behind the front, its border the front's sealed loops. Pieces of the rest that a
/// region encloses (bounded by one of its several loops) and that are smaller than the region
/// join it (hole filling, explored with a budget of the region's size); the largest piece stays
/// outside.

#include <cstddef>
#include <optional>
#include <vector>

#include "edgefront/mesh.h"
#include "twist/reference_normals.h"

namespace twist {

/// What flagged a face.
enum class EvidenceKind {
  Reference,         ///< disagrees with the nearest reference normal
  FacingLayer,       ///< points at a parallel layer that is far along the surface
  FoldedEdge,        ///< has an edge whose faces fold onto each other
  SelfIntersection,  ///< intersects a face it shares no vertex with
};

/// Short lowercase name of an evidence kind ("reference", "facing-layer", ...).
const char* to_string(EvidenceKind kind);

/// One piece of evidence: `face` is flagged; `partner` is the other face involved (the layer in
/// front, the face across the folded edge, the intersected face), invalid for `Reference`.
struct Evidence {
  EvidenceKind kind = EvidenceKind::Reference;
  edgefront::FaceHandle face;
  edgefront::FaceHandle partner;
};

/// A connected twisted region.
struct TwistRegion {
  std::vector<edgefront::FaceHandle> faces;  ///< sorted by index
  /// The sealed border: closed loops of halfedges with the region on their right (the Minimal
  /// Edge Front's convention: the face of each halfedge lies outside). Loops on the mesh border
  /// are included and marked by `border_on_mesh_border`.
  std::vector<std::vector<edgefront::HalfedgeHandle>> border;
  std::vector<bool> border_on_mesh_border;  ///< per loop of `border`: all its halfedges are on the mesh border
  std::vector<Evidence> evidence;           ///< one entry per flagged face of the region (first evidence found)
  size_t flagged_faces = 0;                 ///< faces with evidence (the rest was added by growing)
  double area = 0;                          ///< total area of `faces`
};

/// Options of `detect`. Lengths are absolute; 0 means "automatic" where stated.
struct DetectOptions {
  /// Search radius for layers, > 0, or 0: 2 x the mean edge length. Must exceed the thickness of
  /// the thinnest wall to be checked.
  double radius = 0.0;
  /// A layer is far along the surface when the geodesic distance exceeds this factor times the
  /// straight distance (plus one mean edge length of slack). >= 1.
  double surface_factor = 2.0;
  /// Layers count as parallel when |n_f·n_g| >= this. In [0, 1].
  double parallel_cos = 0.5;
  /// g lies in front of f when n_f·(c_g - c_f)/|c_g - c_f| >= this. In (0, 1].
  double facing_cos = 0.3;
  /// An edge is folded when the normals of its faces satisfy n_f·n_g <= this. In [-1, 0].
  double fold_cos = -0.9;
  /// Look for self-intersecting face pairs.
  bool self_intersections = true;
  /// Minimal Edge Front levels grown around flagged faces to form regions. In [1, 64].
  int grow_levels = 2;
  /// Regions with fewer flagged faces are dropped (noise). >= 1.
  size_t min_flagged_faces = 1;
  /// Regions in which flagged faces are fewer than this share of all faces (after growing,
  /// filling and trimming) are dropped: mostly unflagged regions are grown around stray evidence,
  /// such as a fold band left over right faces after a cut. In [0, 1].
  double min_flagged_share = 0.3;
  /// Keep only regions with at least one face of orientation evidence (reference or facing
  /// layer). Folds and self-intersections alone mark where a twist line runs, not which side is
  /// wrong (a correct surface can fold or intersect itself, e.g. a GCS mesh in transit).
  bool require_orientation_evidence = true;
  /// Oriented reference points (not owned; may be null). When set, reference evidence is used.
  const ReferenceNormals* reference = nullptr;
  /// A face disagrees with its reference normal when n·n_ref < this. In [-1, 1].
  double reference_cos = -0.2;
  /// Which reference point speaks for a face: 0 = the nearest to its centroid; >= 1 = the one of
  /// the face's own side (`ReferenceNormals::side_normal` with this normal weight), which matters
  /// on walls thinner than the mesh's edges. 0 or in [1, 100].
  double reference_side_weight = 4.0;
  /// Incremental mode: when set, only these faces plus `audit_faces` evenly spaced faces (from
  /// `audit_offset`) are tested first; faces within `grow_levels` of a flagged face are then
  /// tested too, so a twisted region is found whole. Invalid or deleted handles throw.
  std::optional<std::vector<edgefront::FaceHandle>> restrict_to = std::nullopt;
  size_t audit_faces = 64;
  size_t audit_offset = 0;
};

/// Statistics of a detection run (for reports and benchmarks).
struct DetectStats {
  size_t faces_tested = 0;       ///< faces whose evidence was evaluated
  size_t distance_queries = 0;   ///< bounded Minimal Distance Front runs
  size_t vertices_settled = 0;   ///< vertices settled by those runs, in total
  size_t flagged_faces = 0;
};

/// Regions and statistics of one detection run.
struct DetectResult {
  std::vector<TwistRegion> regions;
  DetectStats stats;
};

/// Finds the twisted regions of `mesh`, largest first (ties: lowest face index).
/// \throws edgefront::InvalidInput for an empty mesh (no live face), non-finite coordinates or
///         options out of range (the message names the option).
/// \throws edgefront::TopologyError when the fronts meet a non-manifold vertex.
DetectResult detect_regions(const edgefront::Mesh& mesh, const DetectOptions& options = {});

/// The reference normal that speaks for a face with this centre and unit normal under `options`
/// (see `DetectOptions::reference_side_weight`).
edgefront::Vec3 reference_normal(const ReferenceNormals& reference, const DetectOptions& options,
                                 const edgefront::Vec3& centre, const edgefront::Vec3& normal);

/// Faces that have a partner close in space (centroids within `radius`, in front or behind:
/// |n_f·d| >= `facing_cos`·|d|), far along the surface (as for facing layers) and with the same
/// orientation (n_f·n_g >= `parallel_cos`): the signature of a twist the issue asks to rule out.
/// Uses the geometry only (`reference`, `restrict_to` are ignored). Throws as `detect`.
size_t count_same_orientation_layers(const edgefront::Mesh& mesh, const DetectOptions& options = {});

/// `detect_regions(mesh, options).regions`.
std::vector<TwistRegion> detect(const edgefront::Mesh& mesh, const DetectOptions& options = {});

/// Border halfedges of `mesh` that lie on top of another border halfedge running the *same* way
/// (the same end positions, within 1e-9 of the bounding-box diagonal): a seam where the surface
/// meets itself with opposite orientation, as on a Möbius strip cut open to fit a half-edge mesh.
/// Gluing such a seam would make the surface non-orientable. Each matched pair is reported once
/// (the halfedge with the lower index).
std::vector<edgefront::HalfedgeHandle> reversed_seams(const edgefront::Mesh& mesh);

}  // namespace twist
