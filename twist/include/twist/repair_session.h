#pragma once
/// \file repair_session.h
/// A session that mirrors a host's mesh: created once from
/// the host's arrays, told what the host changed (in the host's own vertex and face indices),
/// asked to repair; each answer is an `EditRecord` the host replays on its own structure. The
/// session keeps an `edgefront::Mesh` mirror, index maps both ways and a `TwistRepairer`: applying
/// the edits and the repair cost about what changed, as `TwistRepairer::repair_changed` does on a
/// mesh; an answer whose repair changed the mirror adds one pass over the host's slots to write
/// the record (a status and corner check per face, a position check per vertex: no geometry).
/// What a refinement loop (GCS) needs after every batch (bench/results/embedding.md: within a
/// few percent of the same repair on an `edgefront::Mesh`). It also answers bounded geodesic
/// queries on the mirror.
///
/// \code
///   twist::RepairSession session(V, F);            // the host's arrays
///   host.apply(session.initial_record());          // pinched vertices split, if any
///   for (;;) {
///     // ... the host's batch: it moves vertices, splits, collapses ...
///     session.set_vertex(v, x, y, z);              // moved or added
///     session.set_face(f, a, b, c);                // added or re-connected
///     session.remove_face(g);
///     host.apply(session.repair());                // the twists near what changed, repaired
///     if (session.distance_between(u, w, 0.1))     // near along the surface?
///       ...
///   }
///   host.apply(session.finish());                  // a full repair and the global orientation
/// \endcode
///
/// Indices: the host's. A vertex or face index the host names for the first time is added; the
/// session's own new vertices and faces (cuts) get the indices after the largest the host has
/// used (`EditRecord`: appended, never compacted). The host replays every record before its next
/// edit (the record's new indices are the next free ones at that moment).
///
/// Edits are buffered and applied at the next answer (`sync`, `repair`, `finish`), all at once:
/// removals first, then faces added or re-connected, then positions. Edits that a half-edge mesh
/// cannot hold (a third face on an edge, a face wound against a neighbour, a face at a vertex
/// whose fan is closed) are refused with `edgefront::InvalidInput` naming the host's face; then
/// nothing of the batch is applied (the session is as before the batch, the buffer cleared).
/// Vertices left pinched by removed faces (two fans meeting at one vertex) are split by the
/// session, as in the conversion: the answer's record adds the copy and re-connects the faces.
///
/// Not thread-safe. Deterministic: the same edits give the same records.

#include <array>
#include <cstddef>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "edgefront/arrays.h"
#include "twist/edit_record.h"
#include "twist/repair.h"

namespace twist {

/// Border heal after every repair (`SessionOptions::heal`): the border operations a host's loop
/// may lack, done on the mirror and returned in the same record. A repair cuts a closed mesh along
/// a twist line and flips a side; along that cut both sides then run the same way and cannot be
/// glued back, but as the host's loop moves on, other borders come to run opposite and close
/// (the pieces now facing the same way across a seam). The heal zips such chains with a strip of
/// triangles (joining two loops, or closing a slit of one) and closes small holes with a fan
/// around their centroid (one new vertex, `VertexAdded::original` -1; a triangle for a hole of 3).
/// A strip or fan is added only when every face lies on the reference cloud and the new faces
/// agree with the faces they border (mean cosine of the normals), so it never joins two sides
/// that run the same way. The record reports the new faces in `faces_added` and the fan centres
/// in `vertices_added`; the next `repair` looks at the healed faces too.
struct HealOptions {
  bool enabled = false;              ///< off: no heal (the default)
  double max_gap_edges = 1.0;        ///< chains closer than this many mean edge lengths are zipped; 0: no zips
  double max_support_edges = 0.5;    ///< new faces' centroids within this many mean edges of the reference points
  double min_normal_agreement = 0.2; ///< mean cosine between new faces and the faces they border
  size_t max_zips = 32;              ///< strips per answer
  size_t max_hole_vertices = 8;      ///< holes of at most this many border vertices are closed (< 3: none)
  /// Border growth, before the zips: rows of faces grown beyond the borders per answer (0: none,
  /// the default; at most 8). A border edge gets a triangle with a new vertex (`VertexAdded::original`
  /// -1) about one mean edge beyond it where reference points facing like the edge's face lie there
  /// (at least `grow_min_support` within 0.6 mean edges; the new vertex is their mean) and no face
  /// facing that way does (within 0.45 mean edges); the wedges between two new triangles are
  /// closed. So each side of a cut grows on along its own wall, across the fold the cut left,
  /// until borders that run opposite meet and the zips join them.
  size_t grow_rows = 0;
  size_t grow_min_support = 3;       ///< reference points a grown vertex needs (>= 1)
  /// At the end of `finish` (after its full repair), components with fewer than this share of the
  /// largest component's faces are removed: debris the joins could not attach (a sliver on a
  /// rim, a scrap of film). A share of faces in [0, 1); 0 (the default): nothing is removed.
  double min_piece_share = 0;
};

/// What the heal did in the last answer.
struct HealReport {
  size_t strips = 0;       ///< strips zipped between border chains
  size_t holes = 0;        ///< small holes closed
  size_t grown = 0;        ///< faces the border growth added
  size_t piece_faces_removed = 0;  ///< faces of small pieces `finish` removed (`HealOptions::min_piece_share`)
  size_t faces_added = 0;  ///< faces the strips, fans and growth added
};

/// Options of a `RepairSession`.
struct SessionOptions {
  /// The repair (`garbage_collect` is ignored: the mirror keeps its indices while the host does).
  RepairOptions repair = {};
  size_t max_retwists = 2;  ///< see `TwistRepairer`; >= 0
  edgefront::ConversionOptions conversion = {};  ///< how the host's arrays are converted (`mesh_from_arrays`)
  /// Border heal after every `repair` and before the full repair of `finish` (see `HealOptions`);
  /// needs `repair.detect.reference` (the cloud the new faces must lie on).
  HealOptions heal = {};
};

/// What the last answer did besides its record.
struct SessionStats {
  size_t calls = 0;              ///< answers so far
  size_t faces_changed = 0;      ///< faces the last batch added, re-connected or moved
  size_t pinched_split = 0;      ///< vertices the last batch left pinched, split
  RepairReport report;           ///< of the last repair
  HealReport heal;               ///< of the last answer's heal (zero when off, and after `sync`)
};

/// A mirror of a host's mesh with incremental twist repair (see the file comment). Not copyable;
/// one thread at a time.
class RepairSession {
 public:
  /// Converts the host's arrays (`edgefront::mesh_from_arrays`).
  /// \throws edgefront::InvalidInput as `mesh_from_arrays`, or for options out of range (a heal
  ///         without a reference cloud, a negative or non-finite heal distance).
  RepairSession(const edgefront::VertexArrayView& vertices, const edgefront::FaceArrayView& faces,
                SessionOptions options = {});
  ~RepairSession();
  /// Takes over the moved-from object's mirror and buffers; that object may then only be destroyed or assigned to.
  RepairSession(RepairSession&&) noexcept;
  /// Takes over the moved-from object's mirror and buffers; that object may then only be destroyed or assigned to.
  RepairSession& operator=(RepairSession&&) noexcept;

  /// What the conversion changed (faces dropped, pinched vertices split) as a record on the
  /// host's arrays: the host applies it before its first edit. Empty for a manifold mesh.
  const EditRecord& initial_record() const;
  /// What the conversion of the host's arrays found and changed.
  const edgefront::ConversionReport& conversion() const;

  // -- The host's edits (buffered; see the file comment) ----------------------------------------
  /// Moves vertex `v` there, or adds it when `v` is not a vertex yet (>= 0). Finite coordinates.
  void set_vertex(int v, const std::array<double, 3>& position);
  /// `set_vertex` for many: `ids[i]` to row i of `positions` (k x 3).
  void set_vertices(std::span<const int> ids, const edgefront::VertexArrayView& positions);
  /// Face `f` becomes a b c: added when `f` is not a face yet (>= 0), else re-connected.
  void set_face(int f, const std::array<int, 3>& corners);
  /// Removes face `f`.
  void remove_face(int f);
  /// Removes vertex `v` (no face may use it once the batch is applied).
  void remove_vertex(int v);
  /// True when edits wait for the next answer.
  bool pending() const;

  // -- Answers ---------------------------------------------------------------------------------
  /// Applies the buffered edits, repairs nothing: the record holds the splits of pinched vertices
  /// the batch left (usually empty).
  /// \throws edgefront::InvalidInput for edits that do not fit (naming the host's index).
  EditRecord sync();
  /// Applies the edits and repairs the twists near what changed (`TwistRepairer::repair_changed`
  /// in its local mode), then heals the borders when `SessionOptions::heal` is on. `mean_edge_length` > 0: the host's value; 0: the session's estimate
  /// (recomputed when the live edge count changed by more than 10% since the last time).
  EditRecord repair(double mean_edge_length = 0);
  /// Applies the edits, heals the borders when `SessionOptions::heal` is on, and repairs the
  /// whole mesh with the global orientation (`TwistRepairer::finish`).
  EditRecord finish();
  /// Per host face index (the host's face index space): the twisted region it lies in (0 = the
  /// largest), -1 for none or an empty slot. Detection only (`RepairOptions::detect`); no edits
  /// may be pending (else `InvalidInput`: call `sync` first).
  std::vector<int> detect();

  // -- Bounded geodesic queries on the mirror (no edits pending: else InvalidInput) -------------
  /// The distance along the surface from `from` to `to` when at most `max_distance`, else nothing.
  std::optional<double> distance_between(int from, int to, double max_distance);
  /// The vertices within `max_distance` of the sources, in settling order.
  edgefront::SparseDistances distances_within(std::span<const int> sources, double max_distance);

  // -- State -----------------------------------------------------------------------------------
  size_t vertex_slots() const;  ///< the host's vertex index space (largest index + 1)
  size_t face_slots() const;    ///< the host's face index space
  /// What the last answer did besides its record.
  const SessionStats& stats() const;
  /// The mirror (read-only: for tests, benchmarks and rendering; indices are the session's).
  const edgefront::Mesh& mirror() const;
  /// The mirror vertex of host vertex `v` (invalid for none), and the host vertex of a mirror vertex (-1).
  edgefront::VertexHandle mirror_vertex(int v) const;
  /// The host vertex of mirror vertex `v` (-1 for none).
  int host_vertex(edgefront::VertexHandle v) const;
  /// The mirror face of host face `f` (invalid for none or an empty slot).
  edgefront::FaceHandle mirror_face(int f) const;
  /// The host face of mirror face `f` (-1 for none).
  int host_face(edgefront::FaceHandle f) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace twist
