#pragma once
/// \file repair.h
/// Repairing twisted regions: cut the region off along its sealed border (duplicating the border
/// vertices on one side, so the mesh stays manifold), grow two face fronts alternately from both
/// sides of the cut and flip the side that is exhausted first (so the work is at most twice the
/// flipped side, and the flipped side is at most half of what the two fronts can reach), then
/// fix the global orientation.
///
/// Global orientation convention, per group of components that were one component before the
/// cuts: with reference normals, each component is flipped when its area-weighted vote against
/// the nearest reference normals is negative; without them, a closed group gets positive signed
/// volume (outward normals), unless it lies inside an odd number of other closed groups: then it
/// bounds a cavity (the inner sphere of a hollow ball) and gets negative volume (normals into the
/// cavity); an open group keeps the orientation of its larger side (the smaller side was the one
/// flipped).
///
/// Face handles change (faces of the flipped side are re-added); vertex handles of untouched
/// vertices stay valid unless `garbage_collect` removes deleted vertices (only those of removed
/// tiny pieces or cut-out regions); cut vertices get new copies appended at the end.

#include <array>
#include <cstddef>
#include <utility>
#include <vector>

#include "edgefront/mesh.h"
#include "twist/detect.h"

namespace twist {

/// Where the repair may cut and what it leaves standing (`RepairOptions::cuts`).
struct CutOptions {
  /// Labelling only (`RepairOptions::label_by_reference`): the price of cutting the mesh along an
  /// edge, per unit of edge length, in units of the mean edge length (an area, comparable with
  /// the area of the faces the reference rejects): a region is flipped only when the area it puts
  /// right exceeds the area it puts wrong plus cut_cost x mean edge x the length of the cut around
  /// it. A disk of wrongly oriented faces is flipped from a radius of about 2 x cut_cost mean
  /// edges on (and never below `min_component_faces`). The default 0.5 flips more of the wrong
  /// flaps of a finished torn reconstruction than 1 did, at about one extra piece per twist line
  /// cut as before (each flipped region is its own piece); 0.25 flips more still but cuts up a
  /// surface whose reference rejects scattered faces (bench/results/twist-finished.md). Mean edge
  /// lengths; default 0.5; in [0, 100].
  double cut_cost = 0.5;
  /// Detector path only: regions whose cut border has more than max_border_ratio * sqrt(faces) +
  /// 16 edges are not repaired (counted in `RepairReport::regions_scattered`): a twist is a
  /// compact region behind a short twist line, while scattered evidence (noise, a wall thinner
  /// than the faces) joined into one region has a border snaking through the surface, and cutting
  /// along it shreds it. A disk of n faces has a border of about 3.5 sqrt(n) edges. Edges per
  /// square root of a face count; default 6; finite, >= 0; 0 = no limit.
  double max_border_ratio = 6.0;
  /// A side smaller than this is never left as its own component: it is removed instead of
  /// flipped (and the labelling leaves flip regions this small that would need a cut). Faces;
  /// default 8; >= 1.
  size_t min_component_faces = 8;
  /// At the end of a full repair (`repair`, `TwistRepairer::finish`; not the incremental calls,
  /// which stay local), a component that the cuts separated (it holds a vertex of a cut) and that
  /// has fewer than max(min_component_faces, this share x the largest component's faces) faces is
  /// removed: a sliver or fragment too small to stand as a part of the surface, often lying over
  /// another piece with the same orientation. Components the input had stay. Not applied when
  /// labelling by a reference (it removes nothing). A share of faces; default 0.02; in [0, 1];
  /// 0 = only `min_component_faces` at each cut.
  double min_cut_piece_share = 0.02;
  /// At the end of a full repair, with reference normals (`DetectOptions::reference`): the
  /// clean-ups that remove faces (the small cut pieces of `min_cut_piece_share`, the border flaps
  /// of `RepairExperimentalOptions::peel_flaps`, the turned border patches of
  /// `RepairExperimentalOptions::drop_turned_patches`) spare the faces that alone cover a
  /// reference point (a point within this distance of such a face and farther than it from every
  /// face that stays) and that the reference confirms (`reference_vote` > 0). Removing them
  /// would lose area the samples support (a hole where the surface was); a double layer (another
  /// face over the same points) and a face turned the wrong way or undecided still go. A small cut
  /// piece holding such a face is kept whole, unless the reference rejects one of its faces.
  /// Mean edge lengths; default 0 (off, also in `in_loop()`: in the GCS loop at 0.5 it changed
  /// coverage by -2.4 to +1.3 points, mean -0.02 over 60 runs, and lowered the consistency of some
  /// runs, bench/results/twist-coverage.md); finite, in [0, 4].
  double support_radius = 0.0;
  /// Field by field.
  bool operator==(const CutOptions&) const = default;
};

/// Clean-ups and filters that are off (or neutral) in a one-shot repair of a finished mesh
/// (`RepairOptions::experimental`). The GCS hook turns the first three on
/// (`RepairOptions::in_loop()`); the rest measured no clear gain (bench/results/twist-vaults.md)
/// and may change or go.
struct RepairExperimentalOptions {
  /// At the end of a full repair: rounds of removing border flaps, faces with a vertex on the
  /// mesh border that have a partner close in space, far along the surface and with the same
  /// orientation (`same_orientation_pairs`). Such a face is not a twist (the orientation of both
  /// may be right) but a double layer: a flap of one piece lying over another piece or over the
  /// same piece further along (left by a cut, a re-join or the loop's border operations). Each
  /// round peels one ring; the tiny pieces it leaves go too. Faces away from a border are left to
  /// the detector. Off by default: on a mesh that no refinement loop will fit again, the faces of
  /// a twist line cut through but not moved count as flaps. Rounds; default 0; in [0, 16]; 0 = off.
  int peel_flaps = 0;
  /// Peel only flaps the cuts left: the first round only faces at a vertex of a cut (of this call,
  /// or for `TwistRepairer::finish` of the whole run), each further round faces at a vertex of a
  /// face peeled before. A run that cut nothing then keeps its mesh as it is (in a loop, the
  /// loop's own border flaps are the loop's business). Default false.
  bool peel_from_cuts = false;
  /// At the end of a full repair, after the global orientation, with reference normals only:
  /// small turned-over patches the detector leaves alone (no core of orientation evidence, see
  /// `RegionOptions::require_orientation_evidence`) but that lie over another layer with their
  /// orientation. A patch is an edge-connected group of at most this many faces the reference
  /// rejects (`reference_vote` with the thin-wall rule: faces on a wall thinner than the edges
  /// stay undecided and are never touched), at least one of which has a same-orientation partner
  /// (`same_orientation_pairs`). Each face of such a patch with an edge shorter than half the
  /// mean edge (a sliver inverted by the smoothing among right neighbours, or bevelled over a
  /// rim) is collapsed by its shortest collapsible edge, which keeps the surface around it
  /// closed; a longer one is straightened: one of its interior vertices (tried in circulation
  /// order) moved to the centroid of its neighbours, or else (a tangle: neighbours displaced too)
  /// its interior vertices and their interior neighbours smoothed together that way, up to 3
  /// rounds, kept when the face is then right, no face around the moved vertices is degenerate
  /// and fewer of them are rejected than before (at a rim corner some bevelled faces may stay
  /// rejected); else a longer one on the border is removed (a flap turned over at a rim, and the
  /// tiny pieces that leaves) and a longer interior one is left (a hole would be worse). The
  /// smoothing of a tangle straightens a face folded by a vertex of low valence, which no single
  /// move straightens. Rim slivers are collapsed, not removed: removing one widens the border gap,
  /// and faces of the same wall across it then count as pairs (bench/results/twist-vaults.md).
  /// Each such face makes every face of the other layer within the radius a same-orientation
  /// pair (tens of pairs from one face of a few thousandths of the area). Bigger groups are the
  /// detector's business. Faces; default 0; in [0, 64]; 0 = off.
  size_t drop_turned_patches = 0;
  /// A region cut out (re-twist guard) or a region side too small to stand alone is replaced by
  /// a fan per border loop wound like its surroundings (re-grown in place) instead of leaving a
  /// hole; falls back to a hole when a loop is not simple. Default false (no clear gain in the
  /// loop: bench/results/twist-vaults.md).
  bool regrow_cut_outs = false;
  /// `repair` only (not `TwistRepairer`), first of all: pieces that meet another piece along a
  /// reversed seam (border halfedges on top of each other running the same way, see
  /// `reversed_seams`: a patch turned over by hand or wound the other way in a file, which a
  /// half-edge mesh holds as a separate piece in its hole) are flipped whole, the smaller class
  /// of each group of pieces so joined, so the seams become compatible; the global orientation
  /// then treats each group as one surface. Needs no reference. A seam within one piece (a Moebius
  /// band) is left and reported (`RepairReport::non_orientable`). Only seams across which the
  /// faces face opposite ways (n.n' < -0.5 on average) count. Off by default: the cut of a twist
  /// repair leaves the same signature (the flipped side meets the rest along a reversed seam), so
  /// on a mesh that was repaired before this would undo the repair; turn it on for meshes with
  /// patches wound the other way (with a reference the labelling flips such pieces anyway).
  /// Default false.
  bool flip_seam_pieces = false;
  /// `TwistRepairer::repair_changed` only: a changed face is tested again only when it is new,
  /// its normal turned by more than `retest_turn_degrees`, or one of its corners moved by more
  /// than `retest_move` mean edge lengths since it was last tested (a corner replaced by another
  /// vertex counts as moved to that vertex's position). In a GCS loop the smoothing moves almost
  /// every vertex a little in every batch, so without this every face would be tested after
  /// every batch (the whole mesh per call, and the same stable folds found again and again).
  /// Faces a tested face points at from behind are tested too (see
  /// `IncrementalOptions::restrict_to`), and the audit still samples the rest. Both 0: every
  /// changed face is tested. Degrees; default 10; in [0, 180].
  double retest_turn_degrees = 10.0;
  /// See `retest_turn_degrees`: corner movement. Mean edge lengths; default 0.25; finite, >= 0.
  double retest_move = 0.25;
  /// Field by field.
  bool operator==(const RepairExperimentalOptions&) const = default;
};

/// Options of `repair`, `orient` and `TwistRepairer` (and, through `SessionOptions`, of a
/// `RepairSession`): the few settings a caller usually sets first (the detection with its search
/// radius, reference and threads; what to repair), then named groups. The defaults suit a
/// one-shot repair of a finished mesh; `in_loop()` is what the GCS hook uses inside a refinement
/// loop.
///
/// \code
///   twist::RepairOptions o;                 // or twist::RepairOptions::in_loop()
///   o.detect.reference = &reference;        // oriented points decide which side is right
///   o.detect.radius = 0.01;                 // layer search radius (0: twice the mean edge)
///   o.cuts.cut_cost = 2;                    // a group
///   twist::repair(mesh, o);
/// \endcode
struct RepairOptions {
  /// How regions are found: search radius, reference normals, threads (see `DetectOptions`).
  DetectOptions detect;
  /// `repair` with reference normals (`detect.reference`): label every face keep or flip by the
  /// reference (`label_by_reference`: a minimum cut between the faces' votes and the price of
  /// cutting, `CutOptions::cut_cost`), cut along the borders between the labels and flip the
  /// flip-labelled regions, instead of detecting twisted regions and flipping the smaller side of
  /// each. The detector needs a core of evidence, a compact region and a short border; a finished
  /// mesh whose orientation disagrees with the reference in large irregular patches (a
  /// reconstruction twisted along its whole length) has none of these. `TwistRepairer` (the
  /// refinement loop) never labels. Default true; false = the detector's regions, as without a
  /// reference.
  bool label_by_reference = true;
  /// `repair` by labelling only, at the end: the geometry of small patches the reference still
  /// rejects is mended (edge-connected groups of at most this many faces whose `reference_vote`
  /// is -1, thin-wall rule on; bigger groups were the labelling's to flip). Such patches are folds
  /// and flaps turned over at a border, which a flip cannot fix without leaving a tiny piece. Per
  /// rejected face, in this order, each change kept only when it lowers the area the reference
  /// rejects, makes no degenerate face (area under 1e-4 mean edge^2) and no more folded edges
  /// (n.n' < 0) around: (1) an edge of the face swapped for the other diagonal of its quad;
  /// (2) a corner moved: turned about the opposite edge of a rejected face around it (a page
  /// folded over its hinge, turned back flat; border corners too), or an interior corner to the
  /// centroid of its neighbours, no farther from the reference than max(its distance, half a mean
  /// edge); (3) a patch of 2 or more faces away from the border, all still rejected, whose rim is
  /// one simple loop of 4 or more edges: cut out (counted in `RepairReport::faces_removed` and
  /// `mend_faces_cut_out`) and re-grown as a fan around the rim's centroid (within a mean edge of
  /// the reference), wound like the faces around. Up to 3 rounds. Nothing is removed without
  /// being re-grown, and no piece is added; the area shrinks where folds are undone (figures:
  /// bench/results/twist-finished.md). Faces; default 8; in [0, 64]; 0 = off.
  size_t mend_patches = 8;
  /// At most this many detected regions are repaired per call. Regions; default 16; >= 1.
  size_t max_repairs = 16;
  /// Apply the global orientation convention at the end (see the file comment). Default true.
  bool global_orientation = true;
  /// Compact the mesh at the end (deleted faces, edges and vertices). Default true.
  bool garbage_collect = true;
  CutOptions cuts{};                         ///< where to cut, and which pieces may stand alone
  RepairExperimentalOptions experimental{};  ///< clean-ups and filters, off in a one-shot repair

  /// The defaults: a one-shot repair of a finished mesh (`repair`, `ef-twist`).
  static RepairOptions finished_mesh();
  /// Inside a refinement loop (`gcs::TwistOperationOptions::default_repair()`): the defaults with
  /// `cuts.max_border_ratio` 0 (no limit: in the loop, cutting scattered regions too gives higher
  /// orientation consistency on the vault shells, at the price of more components), and at the
  /// final call `experimental.peel_flaps` 3 with `experimental.peel_from_cuts` (border flaps the
  /// cuts left) and `experimental.drop_turned_patches` 4 (turned-over slivers and rim flaps of 1-4
  /// faces over the other layer, with a reference). Figures: bench/results/twist-vaults.md.
  static RepairOptions in_loop();
};

/// What one repair did.
struct RepairRecord {
  size_t region_faces = 0;       ///< faces of the detected region
  size_t cut_edges = 0;          ///< interior edges cut along the region's border
  size_t vertices_duplicated = 0; ///< vertex copies made for the cut
  size_t flipped_faces = 0;      ///< faces of the side flipped (0 when removed)
  size_t other_side_faces = 0;   ///< faces the other front had expanded when the first was exhausted
  /// Faces expanded by both fronts together (at most twice the exhausted side: the fronts take
  /// turns); faces only queued at the other front's rim are not counted.
  size_t faces_visited = 0;
  bool flipped_region = false;   ///< the region side was the one flipped (else the other side)
  bool removed = false;          ///< the exhausted side was smaller than min_component_faces, or cut out
  size_t tiny_faces_removed = 0; ///< faces of pieces under min_component_faces that the cut split off the other side
};

/// What a `repair`, `orient` or `TwistRepairer` call found and did, in total.
struct RepairReport {
  size_t regions_found = 0;            ///< twisted regions the detector returned
  size_t repairs = 0;                  ///< regions cut and flipped (or removed)
  bool capped = false;                 ///< more regions than max_repairs were found
  size_t faces_flipped = 0;            ///< by the repairs (not counting the global orientation)
  size_t faces_visited = 0;            ///< by the alternating fronts, all repairs together
  size_t faces_removed = 0;             ///< all removals (tiny pieces, cut-outs, flaps)
  size_t flap_faces_removed =
      0;  ///< border flaps peeled at the end (see `RepairExperimentalOptions::peel_flaps`)
  size_t turned_faces_removed = 0;      ///< faces of turned-over border patches removed (`drop_turned_patches`)
  size_t turned_faces_collapsed = 0;    ///< faces of turned-over interior patches collapsed (`drop_turned_patches`)
  size_t turned_faces_straightened = 0; ///< turned-over faces straightened by moving vertices (`drop_turned_patches`)
  size_t supported_faces_spared = 0;   ///< faces the clean-ups kept: alone covering a reference point (`CutOptions::support_radius`)
  size_t vertices_duplicated = 0;      ///< vertex copies made by the cuts, all repairs together
  size_t cut_edges = 0;                ///< edges cut, all repairs together
  /// Repair by labelling: the twist lines cut, groups of cut edges that meet at vertices (a
  /// region flipped off the middle of a surface has one closed line, a band around a tube two).
  size_t cut_lines = 0;
  size_t regions_cut_out = 0;          ///< regions removed because they re-twisted (TwistRepairer)
  size_t regions_scattered = 0;        ///< regions left alone: not compact (see max_border_ratio)
  size_t seam_pieces_flipped = 0;      ///< pieces flipped whole to make reversed seams compatible (`flip_seam_pieces`)
  size_t seam_faces_flipped = 0;       ///< their faces
  size_t components_flipped = 0;       ///< by the global orientation
  size_t faces_flipped_globally = 0;   ///< faces of the components the global orientation flipped
  bool non_orientable = false;         ///< the surface meets itself with opposite orientation
  size_t seam_edges = 0;               ///< border edges along such seams (left cut open)
  size_t mend_edges_flipped = 0;       ///< edges swapped for the other diagonal (`mend_patches`)
  size_t mend_vertices_moved = 0;      ///< vertices moved to unfold rejected faces (`mend_patches`)
  size_t mend_faces_cut_out = 0;       ///< faces of rejected patches cut out and re-grown (`mend_patches`; also in faces_removed)
  size_t mend_faces_added = 0;         ///< faces of the fans that re-grew them (`mend_patches`)
  DetectStats detect_stats;            ///< the detector's counts
  std::vector<RepairRecord> records;   ///< one per repair, in the order they were made
};

/// The keep/flip labelling of `label_by_reference`.
struct ReferenceLabelling {
  /// The regions to flip: edge-connected sets of flip-labelled faces (breadth-first order from
  /// the lowest face index), lowest first face first.
  std::vector<std::vector<edgefront::FaceHandle>> regions;
  std::vector<size_t> cut_edges;  ///< per region: its interior edges shared with kept faces (the cut)
  std::vector<double> votes;      ///< per region: the area its faces' votes add up to (< 0: rejected)
  size_t regions_too_small = 0;   ///< flip regions left as they are: they need a cut and have < min_component_faces faces
  size_t faces_voted = 0;         ///< live faces judged
  double total_area = 0;          ///< of the live faces
  double wrong_area_before = 0;   ///< area of the faces the reference rejects
  double wrong_area_after = 0;    ///< area the reference rejects once the regions are flipped
  double undecided_area = 0;      ///< area of the faces the reference leaves undecided (vote 0)
};

/// Labels every face keep or flip so that the orientation agrees with the reference normals
/// wherever that is worth a cut: each face votes with its area (`reference_vote` under
/// `options.detect`: +1 agrees, -1 disagrees, 0 undecided, e.g. on a wall thinner than
/// `VoteOptions::thin_wall` mean edges), each interior edge costs `options.cuts.cut_cost` x mean
/// edge x its length when its two faces get different labels, and a minimum s-t cut (exact,
/// max-flow) picks the labelling of least total cost. Regions of consistently oriented faces are
/// thus flipped whole by their area-weighted vote, and the cut runs only where two regions that
/// disagree must meet: the twist line. Flip regions of fewer than `options.cuts.min_component_faces`
/// faces that need a cut stay (`regions_too_small`). Does not change the mesh. Cost: one
/// nearest-point query per face (two on thin walls), then the max-flow over the face graph.
/// 	hrows edgefront::InvalidInput without `options.detect.reference`, for an empty mesh,
///         non-finite coordinates or options out of range (`cuts.cut_cost`, `cuts.min_component_faces`, the
///         detection options).
ReferenceLabelling label_by_reference(const edgefront::Mesh& mesh, const RepairOptions& options);

/// Detects and repairs the twisted regions of `mesh` (see the file comment). With reference
/// normals and `RepairOptions::label_by_reference` (the default), the regions are those of
/// `label_by_reference`: they are cut off along the label border and flipped (nothing removed),
/// then the global orientation applies; the detector is not run (`regions_found` counts the
/// labelled regions, `records` has one entry per region).
/// A non-orientable surface (a reversed seam, see `reversed_seams`) cannot be oriented: the seam is
/// left open, `non_orientable` is set, and the rest is repaired.
/// \throws edgefront::InvalidInput as `detect`, or for options out of range.
/// \throws edgefront::InternalError if OpenMesh refuses a re-added face (a bug; the mesh may then
///         be partly modified).
RepairReport repair(edgefront::Mesh& mesh, const RepairOptions& options = {});

/// Only the global orientation convention (see the file comment): no detection, no cut; each
/// component is flipped as the convention says (`components_flipped`, `faces_flipped_globally`).
/// A flipped component's faces are re-added (new face handles); the old ones are garbage-collected
/// when `options.garbage_collect`.
/// \throws edgefront::InvalidInput for an empty mesh or non-finite coordinates.
RepairReport orient(edgefront::Mesh& mesh, const RepairOptions& options = {});

/// Options of `remove_stacked_layers`.
struct StackedLayerOptions {
  /// How pairs are found (`same_orientation_pairs` with `LayerRule::Stacked`; `reference`,
  /// `incremental` and `mean_edge_length` are ignored).
  DetectOptions detect;
  /// Rounds; each round finds the pairs again, removes at most one face per pair (a face removed
  /// can leave its neighbour stacked on the same layer) and flattens pleats. In [1, 16].
  int rounds = 3;
  /// A face is removed only when the edge-connected group of faces that have or are a stacked
  /// partner around it has at most this many faces: a small double layer at a rim or hole, not
  /// one layer of a wall twisted front to back (every face of such a layer is stacked, so its
  /// group is large; that is the repair's business, `repair`). In [1, 1000].
  size_t max_group_faces = 8;
  /// Pieces smaller than this (in faces) that a removal cuts off go too (no tiny components). >= 1.
  size_t min_component_faces = 8;
};

/// What `remove_stacked_layers` did.
struct StackedLayerReport {
  size_t pairs_before = 0;   ///< faces with a stacked same-orientation partner before
  size_t pairs_after = 0;    ///< and after
  size_t faces_removed = 0;  ///< border faces of stacked pairs, and the tiny pieces they left
  size_t pleats_flattened = 0;  ///< pairs with no face on the border smoothed apart
  size_t rounds = 0;         ///< rounds that removed or flattened something
};

/// Removes small double layers at borders: faces that have a same-orientation partner stacked
/// on them (`same_orientation_pairs`, `LayerRule::Stacked`: close in space, far along the
/// surface, covering each other along their mean normal) where one of the two faces touches the
/// mesh border. Of such a pair the face on the border goes (when both are: the one with more
/// border edges, then more border vertices, then the smaller, then the higher index), so the
/// other layer keeps covering the place and no hole opens where the layers overlapped; the
/// tiny pieces that leaves go too, and a vertex where the rest meets in several fans is split
/// (the mesh stays manifold). Such pairs are not twists (both faces usually agree with the
/// surface) but overlaps of one wall's faces where a rim or a hole's border curls over the
/// surface next to it, as a reconstructor's border operations and its post-processing
/// (projection onto the samples, flips, surface fit) leave them. A pair with no face on a border
/// is a pleat (a Z fold inside the surface: the layer between the two faces is turned over), or a
/// face turned over its own star onto another layer. A face of the pair with two or three edges
/// folded (n.n < 0) against its neighbours is straightened alone: one of its interior vertices moved
/// to the centroid of its neighbours, or else its interior vertices and their interior neighbours
/// smoothed together (up to 3 times), kept when fewer edges around fold than before and the two
/// faces no longer overlap (the other layer is not moved: e.g. one face of a shell's outer wall
/// turned over onto the inner one). Otherwise the interior
/// vertices of the two faces and their neighbours are smoothed together (moved to the centroids
/// of their neighbours, up to 3 times) and kept so when the two faces then no longer overlap, no
/// face around is degenerate and no more edges around fold than before; else put back. That
/// smoothing is not tried when a face turned against the pair lies right behind its lower face,
/// closer than the gap between the two: the walls of a shell thinner than the mesh resolves,
/// interleaved, not a fold of one wall (smoothing would merge the walls and lower the orientation
/// consistency: bench/results/twist-vaults.md). Pairs in larger
/// groups (`max_group_faces`) are left. A mesh without a border is not scanned (nothing to
/// remove; its pleats stay). Does not garbage-collect.
/// \throws edgefront::InvalidInput for an empty mesh, non-finite coordinates or options out of
///         range (as `detect`, and `rounds`, `max_group_faces`, `min_component_faces`).
StackedLayerReport remove_stacked_layers(edgefront::Mesh& mesh, const StackedLayerOptions& options = {});

/// Incremental repair for a refinement loop: detection restricted to the faces a batch changed
/// (plus the audit of `DetectOptions`), repairs as `repair`, and a memory of repaired places: a
/// region whose centre lies within its own radius of an earlier repair more than `max_retwists`
/// times is cut out (its faces removed) instead of flipped, so the loop can re-grow it.
class TwistRepairer {
 public:
  /// \param options the repair's options (`repair_changed` replaces `detect.incremental` (`restrict_to`,
  ///        `audit_offset`, `face_grid`) per call and applies no global orientation).
  /// \param max_retwists how often one place may twist again before it is cut out (>= 0).
  explicit TwistRepairer(RepairOptions options = {}, size_t max_retwists = 2);

  /// Repairs the twists near what changed (see the class comment).
  /// \param mesh the mesh the repairer works on (the same one at every call).
  /// \param changed faces created or moved since the last call (handles of the current mesh).
  /// \param mean_edge_length the mesh's mean edge length when the caller knows it (> 0): then
  ///        the call is local (a face grid kept up to date across calls, no pass over the mesh
  ///        but a grid rebuild when the edge length drifted by a factor 2); 0: a k-d tree over
  ///        all face centroids per call. The mesh must not be garbage-collected between calls.
  /// Global orientation is not applied here (call `finish`).
  RepairReport repair_changed(edgefront::Mesh& mesh, const std::vector<edgefront::FaceHandle>& changed,
                              double mean_edge_length = 0);
  /// The face grid of the local mode (for statistics).
  const FaceGrid& face_grid() const { return grid_; }
  /// A full `repair` with the global orientation (at the end of a reconstruction).
  RepairReport finish(edgefront::Mesh& mesh);

  /// Follows a renumbering of the mesh's elements between two calls (a refinement loop that
  /// reorders its mesh for memory locality, see `gcs::MeshRenumbering`): `vertex_map` and
  /// `face_map` give each old index its new one, -1 for an element that is gone. The face
  /// snapshots and the cut pairs are translated (pairs with a vertex gone are dropped), the face
  /// grid is rebuilt over the renumbered mesh with the same cell, and the places of earlier
  /// repairs (positions) are kept, so the next call repairs as it would have without the
  /// renumbering. \throws edgefront::InvalidInput when a map is shorter than the indices this
  /// repairer holds or maps to an index that is not a live element of `mesh`.
  void renumber(const edgefront::Mesh& mesh, const std::vector<int>& vertex_map, const std::vector<int>& face_map);
  /// Number of `repair_changed` calls so far.
  size_t calls() const { return calls_; }
  /// (vertex copy, original) pairs made by the cuts so far (see `cuts_`).
  const std::vector<std::pair<edgefront::VertexHandle, edgefront::VertexHandle>>& cuts() const { return cuts_; }

 private:
  struct Place {
    edgefront::Vec3 centre;
    double radius = 0;
    size_t count = 0;
  };
  /// A face as it was when last tested (see `RepairExperimentalOptions::retest_turn_degrees`).
  struct Snapshot {
    edgefront::Vec3 normal;
    edgefront::Vec3 centre;
    bool valid = false;
  };
  /// The changed faces worth testing again; fills `current` with their snapshots.
  std::vector<edgefront::FaceHandle> retest(const edgefront::Mesh& mesh, const std::vector<edgefront::FaceHandle>& changed,
                                            double mean_edge_length, std::vector<std::pair<int, Snapshot>>& current) const;
  RepairOptions options_;
  size_t max_retwists_;
  std::vector<Snapshot> tested_;  ///< by face index
  size_t calls_ = 0;
  std::vector<Place> places_;
  FaceGrid grid_;
  /// Vertex copies made by the cuts so far, with their originals: the global orientation treats
  /// pieces cut apart as one group. Forgotten when garbage collection renumbers vertices.
  std::vector<std::pair<edgefront::VertexHandle, edgefront::VertexHandle>> cuts_;
};

}  // namespace twist
