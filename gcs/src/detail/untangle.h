#pragma once
// Post-processing of the GCS result: resolving self-intersecting face pairs.
//
// On thin shells (walls about one edge apart) the loop's moves drag vertices of one wall through
// the other, and rims curl over the faces next to them: the returned mesh can have face pairs
// that cross. Most crossings are local (the two faces a few edges apart, at a rim): smoothing the
// crossing faces' vertices undoes them. What smoothing cannot undo is cut out, and the small
// holes this leaves are filled again when the fill lies on the samples and crosses nothing.

#include <cstddef>

#include "border_topology.h"
#include "edgefront/mesh.h"

namespace gcs::detail {

struct UntangleParams {
  /// Smoothing rounds: round r smooths the vertices of the crossing faces and r rings around them.
  int relax_rounds = 3;
  /// Jacobi iterations per round: every such vertex moves by `relax_rate` toward the mean of its
  /// neighbours (on a border: of its two border neighbours).
  int relax_iterations = 8;
  double relax_rate = 0.5;
  /// A vertex moves at most this far in all (> 0).
  double max_move = 0;
  /// A move is put back when one of the vertex's faces turns by more than acos(min_face_cos) from
  /// its normal on entry (in [-1, 1]; 0.5 = 60 degrees: smoothing must not fold a face over).
  double min_face_cos = 0.5;
  /// Then, this many times, every moved vertex goes halfway back to its entry position where that
  /// makes nothing cross again (the smoothing moves more than needed, off the samples). >= 0.
  int pull_back_passes = 4;
  /// Cut out one face of every pair that still crosses: the one touching a border (a curled rim),
  /// else the one whose centroid is farther from the cloud, else the other; pieces this cuts off
  /// that the border creation would remove too (fewer than 8 faces or 5% of the largest piece's)
  /// go, and a cut that would cut off a larger piece is not made (the pair is left). Then border
  /// loops of at most `fill_max_vertices` vertices (this includes holes that were there before) are
  /// filled one at a time (detail::fill_small_holes_checked): by the fan of fill_small_holes
  /// (`fill_support`, normal agreement 0.5), or, for a loop through a corner of a face that may
  /// have been cut, by the least-area triangulation of its vertices; a fill is kept when it makes
  /// no pair cross, or when the smoothing above (no cut) undoes every crossing it makes (the
  /// surface the cut face crossed may pass through the hole).
  bool cut = true;
  std::size_t fill_max_vertices = 8;
  double fill_support = 0;
};

struct UntangleReport {
  std::size_t pairs_before = 0;     ///< self-intersecting face pairs on entry
  std::size_t pairs_after = 0;      ///< ... on return (never more than on entry; > 0 when a cut was refused)
  std::size_t vertices_moved = 0;   ///< by the smoothing
  std::size_t faces_removed = 0;    ///< cut out (with the pieces of < 8 faces this cut off)
  std::size_t holes_filled = 0;
};

/// Resolves the self-intersecting face pairs of `mesh` (see the file comment). Every vertex move
/// that makes a pair cross that did not cross before is put back, and a fill that makes one is not
/// kept, so the result never has a crossing the input did not have. The mesh stays a valid
/// manifold oriented mesh (deleted elements not collected; faces are only removed and added when
/// `cut`). A mesh without crossings is not changed. \throw edgefront::InvalidInput for
/// max_move <= 0 or not finite, negative rounds, iterations or passes, relax_rate outside (0, 1],
/// min_face_cos outside [-1, 1].
UntangleReport untangle(edgefront::Mesh& mesh, const CloudQuery& cloud, const UntangleParams& params);

}  // namespace gcs::detail
