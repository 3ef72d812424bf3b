#pragma once
/// \file detect.h
/// Finding twisted surface regions: parts of a (combinatorially orientable) mesh whose geometric
/// orientation disagrees with the side of the surface they approximate (Annuth & Bohn, VMV 2012,
/// as read in `/work/shared/notes/gcs-and-twist.md` §3; edge-front paper §1, Fig. 1).
///
/// Evidence, per face f (all semi-local):
/// - **Reference**: with reference normals, f's normal disagrees with the nearest oriented point.
/// - **Facing layer**: another face g lies *in front of* f (on the side f's normal points to)
///   within `radius`, roughly parallel (|n_f·n_g| >= `experimental.parallel_cos`), and is *far
///   along the surface*: a Minimal Distance Front from f's centroid, bounded by `max_distance`,
///   does not reach g within `experimental.surface_factor` times their distance. On a correctly
///   oriented thin closed structure every face has the material, not another layer of the same
///   surface, right behind it and empty space in front: layers of one thin wall are back to back. A face whose normal
///   points at another layer is twisted: either both layers face each other (a wall turned inside
///   out: both flagged) or both point the same way (two layers with the same orientation: only
///   the one pointing at the other is flagged). Convention and limit: two distinct surface parts
///   facing each other across a gap narrower than `radius` (a hairpin's arms) look like an
///   inverted wall; pass reference normals for such inputs (they then decide the side, see
///   `RegionOptions::require_orientation_evidence`) or lower `radius`.
/// - **Folded edge**: an edge whose two faces fold onto each other
///   (n_f·n_g <= `experimental.fold_cos`, dihedral angle near 0).
/// - **Self-intersection**: f crosses a face it shares no vertex with: the kernel's
///   edgefront::triangle_contact says `Crossing` (the test gcs::count_self_intersections uses;
///   the evaluation also counts `Touching`, the detector does not: faces touching along an
///   unwelded seam are no twist). Pairs sharing a vertex are not tested here (folded edges cover
///   neighbours), while the evaluation counts them when they meet beyond what they share.
///
/// Flagged faces are grown into regions with a Minimal Edge Front started at their vertices and
/// run `regions.grow_levels` levels (this also closes small gaps between flagged patches); a
/// region is the surface behind the front, its border the front's sealed loops. Pieces of the
/// rest that a region encloses (bounded by one of its several loops) and that are smaller than
/// the region join it (hole filling, explored with a budget of the region's size); the largest piece stays
/// outside.

#include <array>
#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <optional>
#include <utility>
#include <vector>

#include "edgefront/borrowed.h"
#include "edgefront/mesh.h"
#include "twist/reference_normals.h"

namespace twist {

/// What flagged a face.
enum class EvidenceKind {
  Reference,         ///< disagrees with the nearest reference normal
  FacingLayer,       ///< points at a parallel layer that is far along the surface
  FoldedEdge,        ///< has an edge whose faces fold onto each other
  SelfIntersection,  ///< crosses a face it shares no vertex with (edgefront::triangle_contact)
};

/// Short lowercase name of an evidence kind ("reference", "facing-layer", ...).
const char* to_string(EvidenceKind kind);

/// One piece of evidence: `face` is flagged; `partner` is the other face involved (the layer in
/// front, the face across the folded edge, the intersected face), invalid for `Reference`.
struct Evidence {
  EvidenceKind kind = EvidenceKind::Reference;  ///< what was found
  edgefront::FaceHandle face;                   ///< the flagged face
  edgefront::FaceHandle partner;                ///< the other face involved; invalid for `Reference`
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

/// The geometry of a triangle as the detector uses it.
struct FaceGeometry {
  edgefront::Vec3 normal;                  ///< unit normal, zero for a degenerate face
  edgefront::Vec3 centre;                  ///< centroid
  double longest = 0;                      ///< longest edge length
  std::array<int, 3> vertices{-1, -1, -1};  ///< vertex indices in circulation order
};

/// The geometry of a live triangle of the mesh.
/// \throws edgefront::InvalidInput for an invalid, out-of-range or deleted face;
///         edgefront::InternalError when the face is not a triangle.
FaceGeometry face_geometry(const edgefront::Mesh& mesh, edgefront::FaceHandle f);

/// An incremental spatial hash of face centroids, for repeated local detection on a mesh that
/// changes a little at a time (see `IncrementalOptions::face_grid`): updating it costs O(changed
/// faces), a query O(faces in the cells it covers). It holds each face's geometry as of the last
/// `update`/`rebuild` of that face: queries answer for those stored centroids (no mesh access
/// but the deleted flag) and `geometry` returns the stored geometry, so the caller updates every
/// face that moved. The mesh must not be garbage-collected while it is used (rebuild after).
class FaceGrid {
 public:
  /// (Re)inserts these faces at their current centroids; deleted handles are skipped.
  void update(const edgefront::Mesh& mesh, const std::vector<edgefront::FaceHandle>& faces);
  /// Inserts the faces created since the last update (indices from the highest seen on).
  void update_new(const edgefront::Mesh& mesh);
  /// Rebuilds over all live faces with cells of this edge length (> 0, finite): O(F).
  /// \throws edgefront::InvalidInput for a bad cell size.
  void rebuild(const edgefront::Mesh& mesh, double cell);
  /// Live faces whose current centroid lies within `radius` of `p`, in increasing index order.
  void query(const edgefront::Mesh& mesh, const edgefront::Vec3& p, double radius,
             std::vector<edgefront::FaceHandle>& out) const;
  /// The stored geometry of a face, or null when the grid does not hold it.
  const FaceGeometry* geometry(edgefront::FaceHandle f) const {
    const size_t i = static_cast<size_t>(f.idx());
    return f.is_valid() && i < records_.size() && records_[i].key != kNoKey ? &records_[i].geometry : nullptr;
  }
  /// The cell edge length of the last `rebuild` (0 before it), in the mesh's length unit.
  double cell() const { return cell_; }
  /// Number of faces the grid holds.
  size_t size() const { return size_; }
  /// Number of `rebuild` calls so far.
  size_t rebuilds() const { return rebuilds_; }

 private:
  struct Entry {
    int face = -1;
    edgefront::Vec3 centre;
  };
  static constexpr std::uint64_t kNoKey = ~std::uint64_t{0};
  void insert(const edgefront::Mesh& mesh, edgefront::FaceHandle f);
  double cell_ = 0;
  size_t size_ = 0, rebuilds_ = 0, seen_faces_ = 0;
  struct Record {
    FaceGeometry geometry;
    std::uint64_t key = kNoKey;  ///< the cell holding the face, kNoKey when not held
  };
  std::unordered_map<std::uint64_t, std::vector<Entry>> cells_;
  std::vector<Record> records_;  ///< by face index
};

/// How flagged faces become regions, and which regions `detect` keeps (`DetectOptions::regions`).
struct RegionOptions {
  /// Minimal Edge Front levels grown around flagged faces to form regions (this also closes small
  /// gaps between flagged patches). Default 2; in [1, 64].
  int grow_levels = 2;
  /// Regions with fewer flagged faces are dropped (noise). Default 1; >= 1.
  size_t min_flagged_faces = 1;
  /// Regions in which flagged faces are fewer than this share of all faces (after growing,
  /// filling and trimming) are dropped: mostly unflagged regions are grown around stray evidence,
  /// such as a fold band left over right faces after a cut. Default 0.3; in [0, 1].
  double min_flagged_share = 0.3;
  /// Keep only regions with a core of orientation evidence: a face with reference or facing-layer
  /// evidence whose neighbours across all its edges have it too. Folds and self-intersections
  /// alone mark where a twist line runs, not which side is wrong (a correct surface can fold or
  /// intersect itself, e.g. a GCS mesh in transit), and a triangle or two turned over against
  /// right neighbours in a crease is a tangle, not a wrongly oriented patch. With a `reference`,
  /// facing-layer evidence counts for the core only where the side judge abstains
  /// (`DetectExperimentalOptions::reference_side_weight` > 0 and a vote of 0): wherever the
  /// reference decides, a layer in front of a face it confirms is another right part of the
  /// surface across a narrow gap. Default true.
  bool require_orientation_evidence = true;
  /// Field by field.
  bool operator==(const RegionOptions&) const = default;
};

/// How the reference normals judge a face in the default nearest-point mode
/// (`DetectOptions::vote`; used by `reference_vote`, hence by `label_by_reference` too).
struct VoteOptions {
  /// A face disagrees with its nearest reference normal when n·n_ref < this, and agrees when
  /// n·n_ref >= -this; in between it is undecided (normals nearly perpendicular). A cosine;
  /// default -0.2; in [-1, 1].
  double reference_cos = -0.2;
  /// A face the nearest reference normal rejects is left undecided instead when it lies on a wall
  /// thinner than this many mean edge lengths (`ReferenceNormals::wall_thickness` at its
  /// centroid): the mesh does not resolve such a wall (its two layers are closer than a fraction
  /// of an edge and cross each other), so which side is nearest a face, and the verdict, is noise,
  /// and repairing it shreds the wall (thin vault shells: bench/results/twist-vaults.md).
  /// Agreeing verdicts are kept (they start no repair). Nearest-point mode only
  /// (`DetectExperimentalOptions::reference_side_weight` = 0). In mean edge lengths; default
  /// 0.35; in [0, 4]; 0 = off.
  double thin_wall = 0.35;
  /// Field by field.
  bool operator==(const VoteOptions&) const = default;
};

/// Incremental detection, as `TwistRepairer` drives it (`DetectOptions::incremental`): the
/// repairer sets `restrict_to`, `audit_offset` and `face_grid` per call; a one-shot `detect` of a
/// whole mesh leaves them unset.
struct IncrementalOptions {
  /// When set, only these faces plus `audit_faces` evenly spaced faces (from `audit_offset`) are
  /// tested first, then the faces right behind them with the same orientation (they point at a
  /// candidate's back; with a reference only those it leaves undecided); faces within
  /// `RegionOptions::grow_levels` of a flagged face are then tested too, so a twisted region is
  /// found whole. With `RegionOptions::require_orientation_evidence`, self-intersections are
  /// looked for only on those grown faces, not on the candidates (they mark a twist line, never a
  /// region on their own, and the scan is the costliest test). Invalid or deleted handles throw.
  /// Default unset (the whole mesh is tested).
  std::optional<std::vector<edgefront::FaceHandle>> restrict_to = std::nullopt;
  /// With `restrict_to`: evenly spaced faces tested besides it, so that twists away from the
  /// changed faces are found over time. Faces; default 64; >= 0; 0 = none.
  size_t audit_faces = 64;
  /// With `restrict_to`: where the evenly spaced audit starts (a face index, modulo the face
  /// count; the repairer advances it every call so that the audits cover the whole mesh over
  /// time). Default 0; any value.
  size_t audit_offset = 0;
  /// Incremental index of face centroids kept up to date by the caller (borrowed; may be null).
  /// With it and `restrict_to`, a detection touches only the candidates, their neighbourhoods
  /// and the audit: no pass over the whole mesh (pass `DetectOptions::mean_edge_length` too).
  /// Without it, a k-d tree over all face centroids is built per call. Default null.
  edgefront::Borrowed<const FaceGrid> face_grid = nullptr;
};

/// Thresholds of the geometric evidence and the alternative reference judge
/// (`DetectOptions::experimental`). The defaults are what every test, benchmark and the GCS hook
/// use; changing them is rarely useful (the side judge measured worse on the thicker vault shells,
/// bench/results/twist-vaults.md) and they may change or go.
struct DetectExperimentalOptions {
  /// A layer is far along the surface when the geodesic distance exceeds this factor times the
  /// straight distance (plus one mean edge length of slack). Default 2; finite, >= 1.
  double surface_factor = 2.0;
  /// Layers count as parallel when |n_f·n_g| >= this. A cosine; default 0.5; in [0, 1].
  double parallel_cos = 0.5;
  /// g lies in front of f when n_f·(c_g - c_f)/|c_g - c_f| >= this. A cosine; default 0.3; in
  /// (0, 1].
  double facing_cos = 0.3;
  /// An edge is folded when the normals of its faces satisfy n_f·n_g <= this. A cosine; default
  /// -0.9; in [-1, 0].
  double fold_cos = -0.9;
  /// How the reference judges a face: 0 = the nearest point to its centroid (see `VoteOptions`);
  /// >= 1 = by sides (`ReferenceNormals::judge` with this normal weight and `reference_margin`),
  /// which tells the face's own wall on walls thinner than the mesh's edges and abstains between
  /// the walls. Default 0; 0 or in [1, 100].
  double reference_side_weight = 0.0;
  /// Side judge only (`reference_side_weight` >= 1): the margin passed to
  /// `ReferenceNormals::judge`. Default 1.5; in [1, 100].
  double reference_margin = 1.5;
  /// Field by field.
  bool operator==(const DetectExperimentalOptions&) const = default;
};

/// Options of `detect`: the few settings a caller usually sets first, then named groups. Lengths
/// are absolute (the mesh's length unit); 0 means "automatic" where stated.
///
/// \code
///   twist::DetectOptions o;
///   o.reference = &reference;     // oriented points decide which side is right
///   o.radius = 0.01;              // or 0: twice the mean edge length
///   o.regions.grow_levels = 3;    // a group
///   twist::detect(mesh, o);
/// \endcode
struct DetectOptions {
  /// Search radius for layers, or 0: 2 x the mean edge length. Must exceed the thickness of the
  /// thinnest wall to be checked. Length; default 0; finite, >= 0.
  double radius = 0.0;
  /// Oriented reference points (the caller's, borrowed; may be null). When set, reference
  /// evidence is used. Default null.
  edgefront::Borrowed<const ReferenceNormals> reference = nullptr;
  /// Threads for the per-face evidence of a whole-mesh detection (no
  /// `IncrementalOptions::restrict_to`): 0 = all cores. Each thread tests a contiguous range of
  /// faces with its own detector (its own k-d tree over the face centroids), at most one thread
  /// per 1,000 faces; the regions are the same for any count. Incremental detection runs on one
  /// thread. Default 0; >= 0.
  unsigned threads = 0;
  /// Look for self-intersecting face pairs. Default true.
  bool self_intersections = true;
  /// The mesh's mean edge length if the caller knows it, else 0: computed (a pass over the
  /// edges). Length; default 0; finite, >= 0.
  double mean_edge_length = 0;
  RegionOptions regions{};                   ///< growing flagged faces into regions, and which are kept
  VoteOptions vote{};                        ///< how the reference judges a face
  IncrementalOptions incremental{};          ///< detection restricted to changed faces (the repairer's)
  DetectExperimentalOptions experimental{};  ///< evidence thresholds and the side judge; rarely useful
};

/// Statistics of a detection run (for reports and benchmarks).
struct DetectStats {
  size_t faces_tested = 0;       ///< faces whose evidence was evaluated
  size_t distance_queries = 0;   ///< bounded Minimal Distance Front runs
  size_t vertices_settled = 0;   ///< vertices settled by those runs, in total
  size_t flagged_faces = 0;      ///< faces the run found evidence on
};

/// Regions and statistics of one detection run.
struct DetectResult {
  std::vector<TwistRegion> regions;  ///< largest first (ties: lowest face index)
  DetectStats stats;                 ///< counts of the run
};

/// Finds the twisted regions of `mesh`, largest first (ties: lowest face index).
/// \throws edgefront::InvalidInput for an empty mesh (no live face), non-finite coordinates or
///         options out of range (the message names the option).
/// \throws edgefront::TopologyError when the fronts meet a non-manifold vertex.
DetectResult detect_regions(const edgefront::Mesh& mesh, const DetectOptions& options = {});

/// The reference's verdict on a face with this centre and unit normal under `options` (see
/// `DetectExperimentalOptions::reference_side_weight`, `VoteOptions`): +1 agrees, -1 disagrees, 0 undecided.
/// `mean_edge_length` (> 0) turns on `VoteOptions::thin_wall`; 0 leaves it off.
int reference_vote(const ReferenceNormals& reference, const DetectOptions& options, const edgefront::Vec3& centre,
                   const edgefront::Vec3& normal, double mean_edge_length = 0);

/// Which partners make a same-orientation pair (see `same_orientation_pairs`).
enum class LayerRule {
  /// g's centroid lies within `radius` in front of f or behind it: |n_f·d| >=
  /// `DetectExperimentalOptions::facing_cos`·|d|
  /// for d = c_g - c_f (the first rule). It also counts two faces of one wall side by
  /// side across a hole or a border gap, and two faces bevelled over a rim corner (two walls
  /// meeting at a right angle), when their normals tilt enough: both may be oriented right.
  Facing,
  /// As `Facing`, and the two layers are stacked front to back: the two triangles, projected
  /// along their mean normal (n_f + n_g, normalised), overlap by more than 0.1 times the
  /// shorter of their longest edges (the depth of the overlap along the separating
  /// axes of the two projected triangles). Two layers approximating the front and the back of
  /// one wall with the same orientation (the twist the issue rules out) cover each other along
  /// the wall's normal, so every face of them but a few at their borders has such a partner;
  /// faces side by side (one wall across a hole) or meeting at a rim corner do not overlap.
  Stacked,
};

/// Faces that have a partner close in space (centroids within `radius`, in front or behind:
/// |n_f·d| >= `DetectExperimentalOptions::facing_cos`·|d|), far along the surface (as for facing layers) and
/// with the same orientation (n_f·n_g >= `DetectExperimentalOptions::parallel_cos`): the signature of a twist
/// the issue asks to rule out. `rule` sharpens which partners count (see `LayerRule`; the repair's flap
/// peeling and turned patch dropping use `Facing`). Uses the geometry only (`reference` is ignored). With
/// `IncrementalOptions::restrict_to`, only the pairs in which the face or its partner is one of those faces
/// are returned (the same pairs the whole scan gives for them; only those faces and the faces within the
/// layer radius of them are tested, so a small set costs little). Throws as `detect`, and InvalidInput for a
/// `rule` that is no `LayerRule`.
size_t count_same_orientation_layers(const edgefront::Mesh& mesh, const DetectOptions& options = {},
                                     LayerRule rule = LayerRule::Facing);

/// The faces `count_same_orientation_layers` counts, each with its nearest such partner (the one
/// in front when there is one, else behind), in increasing face index order.
std::vector<std::pair<edgefront::FaceHandle, edgefront::FaceHandle>> same_orientation_pairs(
    const edgefront::Mesh& mesh, const DetectOptions& options = {}, LayerRule rule = LayerRule::Facing);

/// Checks `options` as `detect` does before it looks at the faces.
/// \throws edgefront::InvalidInput naming the first option out of range (or a restricted face
///         that is not a live face of `mesh`).
void validate_detect_options(const edgefront::Mesh& mesh, const DetectOptions& options);

/// `detect_regions(mesh, options).regions`.
std::vector<TwistRegion> detect(const edgefront::Mesh& mesh, const DetectOptions& options = {});

/// Border halfedges of `mesh` that lie on top of another border halfedge running the *same* way
/// (the same end positions, within 1e-9 of the bounding-box diagonal): a seam where the surface
/// meets itself with opposite orientation, as on a Möbius strip cut open to fit a half-edge mesh.
/// Gluing such a seam would make the surface non-orientable. Each matched pair is reported once
/// (the halfedge with the lower index).
std::vector<edgefront::HalfedgeHandle> reversed_seams(const edgefront::Mesh& mesh);

}  // namespace twist
