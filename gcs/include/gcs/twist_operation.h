#pragma once
/// \file twist_operation.h
/// The twist repair as a hook of the GCS loop (see `operation.h` and `twist/repair.h`): after
/// each batch, twisted regions are searched near the changed faces that turned or moved across
/// their plane since they were last tested (`twist::RepairExperimentalOptions::retest_turn_degrees`; the
/// smoothing moves almost every face a little in every batch) plus a small audit sample, cut off
/// and flipped; a place that re-twists repeatedly is cut out so the loop re-grows it; the
/// final call repairs the whole mesh and applies the global orientation. When the input points
/// have normals, they decide which side is right.

#include <cstddef>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "edgefront/point_index.h"
#include "gcs/operation.h"
#include "twist/repair.h"

namespace gcs {

/// Options of the `TwistOperation` hook.
struct TwistOperationOptions {
  /// Detection and repair settings (garbage collection is forced off). Default
  /// `default_repair()`, i.e. `twist::RepairOptions::in_loop()`.
  twist::RepairOptions repair = default_repair();
  /// The hook's default repair settings: `twist::RepairOptions::in_loop()`, which differs from
  /// `twist::repair`'s own defaults (`twist::RepairOptions::finished_mesh()`, for a one-shot repair
  /// of a finished mesh) on purpose in four fields: no limit on the border of a region
  /// (`cuts.max_border_ratio` = 0; for a cloud with normals, see
  /// `max_border_ratio_without_normals` for one without): in the loop, cutting scattered regions
  /// too gives higher orientation consistency on the vault shells, at the price of more components
  /// (bench/results/twist-vaults.md has both); and the final call peels border flaps the cuts left
  /// (`experimental.peel_flaps` = 3 with `experimental.peel_from_cuts`: faces at a border lying
  /// over another layer with the same orientation), and, with reference normals, removes or
  /// collapses turned-over patches of up to 4 faces that lie over the other layer
  /// (`experimental.drop_turned_patches` = 4).
  static twist::RepairOptions default_repair() { return twist::RepairOptions::in_loop(); }
  /// `repair.cuts.max_border_ratio` for a cloud without normals. Without normals the detector's
  /// evidence is geometric only (facing layers, folded edges, self-intersections), and on a noisy
  /// cloud whose noise is about an edge length the loop's crumpled surface shows such evidence all
  /// over, and cutting every such region shreds the surface into many pieces with many holes
  /// (CGAL's sphere_20k: bench/results/gcs.md). So without normals a region whose cut border is longer
  /// than this ratio times the square root of its face count (plus 16 edges) is left alone as
  /// scattered evidence (see `twist::CutOptions::max_border_ratio`). 0 = no limit; finite, >= 0.
  double max_border_ratio_without_normals = 4.0;
  std::size_t max_retwists = 2;      ///< a place repaired more often than this is cut out; >= 0
  std::size_t min_vertices = 200;    ///< no repair while the mesh has fewer live vertices (a box has no layers); >= 0
  /// Use the input normals as reference when the cloud has them (for a large cloud the loop
  /// queries through a subsample, that subsample: OperationContext::query_points).
  bool use_point_normals = true;
  /// Local detection after a batch: a face grid kept up to date across calls instead of a k-d
  /// tree over all face centroids per call (see `twist::TwistRepairer::repair_changed`).
  bool local = true;
  /// After a call that cut or removed something, re-join border chains of different loops that
  /// run close and opposite (orientation-compatible) and whole loop pairs, with the loop's border
  /// operations (strips must lie on the input points and agree with the faces on both sides):
  /// pieces a repair separated grow back together where their orientations now agree.
  /// Off by default: on the vault shells it leaves fewer pieces and more surface, but lower
  /// orientation consistency; on CGAL's kitten scan it changes little, as the detector flags
  /// regions there only in a few runs (figures: bench/results/twist-vaults.md).
  /// `gcs-reconstruct --rejoin-borders` turns it on.
  bool rejoin_borders = false;
};

/// Totals over all calls.
struct TwistOperationStats {
  std::size_t calls = 0;            ///< `apply` calls (the final one included)
  std::size_t regions_found = 0;    ///< twisted regions the detector returned
  std::size_t repairs = 0;          ///< regions cut and flipped (or removed)
  std::size_t regions_cut_out = 0;  ///< regions removed because they re-twisted (`max_retwists`)
  std::size_t faces_flipped = 0;    ///< faces flipped by the repairs (not the global orientation)
  std::size_t faces_removed = 0;    ///< faces removed (tiny pieces, cut-outs, flaps)
  std::size_t regions_scattered = 0;   ///< left alone: not compact (`twist::CutOptions::max_border_ratio`)
  std::size_t components_flipped = 0;  ///< by the global orientation of the final call
  bool non_orientable = false;         ///< a repair met a reversed seam (see `twist::RepairReport`)
  double cpu_seconds = 0;              ///< process CPU time spent in `apply` (std::clock; the loop is single-threaded)
  std::size_t faces_tested = 0;        ///< faces whose evidence the detector evaluated, all calls
  std::size_t borders_rejoined = 0;    ///< border strips and loop merges added after repairs
  std::size_t turned_faces_dropped = 0;  ///< turned-over patch faces removed, collapsed or straightened by the final call
};

/// The twist repair as a GCS loop operation (see the file comment). Add one to a
/// `Reconstructor` with `add_operation`; it keeps the repair's state across batches.
class TwistOperation : public Operation {
 public:
  /// A hook with these options; the reference normals and repairer are made at the first call.
  explicit TwistOperation(TwistOperationOptions options = {});
  ~TwistOperation() override;
  std::string name() const override { return "twist-repair"; }
  OperationResult apply(edgefront::Mesh& mesh, const ChangeSet& changed, const OperationContext& context) override;
  /// Always follows the loop's renumbering: the repairer translates its index-keyed state.
  bool can_follow_renumbering() const override;
  void on_renumbered(const edgefront::Mesh& mesh, const MeshRenumbering& map) override;
  /// Totals over all calls so far.
  const TwistOperationStats& stats() const { return stats_; }
  /// What the repairs cut so far: (vertex copy, original) pairs, at the same position, along the
  /// cuts (handles of the current mesh; cleared when the final call garbage-collects). A
  /// reconstructor can use them to re-join borders where orientations are compatible again.
  const std::vector<std::pair<edgefront::VertexHandle, edgefront::VertexHandle>>& cuts() const;

 private:
  TwistOperationOptions options_;
  std::unique_ptr<twist::ReferenceNormals> reference_;
  bool reference_checked_ = false;
  std::unique_ptr<twist::TwistRepairer> repairer_;
  std::unique_ptr<edgefront::PointIndex> cloud_index_;  ///< over the input points, for the border re-join
  TwistOperationStats stats_;
};

}  // namespace gcs
