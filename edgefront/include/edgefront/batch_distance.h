#pragma once
/// \file batch_distance.h
/// Many distance fields on one mesh at once: one field per source vertex (the rows of a matrix
/// over all vertices), or the distances between two vertex sets (sources x targets), computed on
/// several threads.
///
/// \code
///   std::vector<edgefront::VertexHandle> landmarks = ...;
///   edgefront::DistanceMatrix m = edgefront::geodesic_distances(mesh, landmarks, {}, {.threads = 2});
///   double d = m(2, 17);   // from landmarks[2] to vertex 17
///   edgefront::DistanceMatrix between =
///       edgefront::geodesic_distances(mesh, landmarks, landmarks, {.method = edgefront::DistanceMethod::Fast});
/// \endcode
///
/// Each row is the field of `geodesic_distance(mesh, FrontSource::vertex(source), options)` (for
/// `Fast` and `Dijkstra`, of the same on a `GeodesicRingTable`, which gives the same field bit for
/// bit), read at the targets: the same bits for any thread count and any order the rows finish in.
///
/// Threads: one front (or one set of per-mesh arrays, for `Fast` and `Dijkstra`) per thread over
/// the shared const mesh; each thread takes the next source when it is free. For `Fast` and
/// `Dijkstra` with two or more sources a `GeodesicRingTable` is built once (on the calling thread,
/// about 1.5 Dijkstra fields) and read by all threads.
///
/// Memory: the result (rows x columns doubles), plus per thread the working memory of one field
/// (`DistanceMatrix::peak_working_memory_bytes`: for `Mdf` and `Windows` the front's O(front)
/// records; for `Fast` and `Dijkstra` per-mesh arrays and one temporary field), plus the table.
///
/// Cancellation: `BatchOptions::progress` may return false; no new row is started, the rows
/// running finish, and the result is partial (`BatchStatus::Cancelled`, rows not computed are NaN
/// and their `stop` is `DistanceStop::NotStarted`). Nothing is thrown for a cancellation.

#include <cstddef>
#include <functional>
#include <limits>
#include <span>
#include <vector>

#include "edgefront/mesh.h"
#include "edgefront/minimal_distance_front.h"

namespace edgefront {

class GeodesicSolver;

/// How a batch runs.
struct BatchOptions {
  /// Threads to use, >= 0; 0 (the default) = all cores (`std::thread::hardware_concurrency`).
  /// More threads than sources are not started.
  unsigned threads = 0;
  /// Called after each row is finished with the rows finished so far and the total (1 ... total,
  /// increasing by one per call). Calls come from the worker threads, one at a time (serialised
  /// by a lock): keep it short. Return false to cancel (see the file comment). Empty: no calls.
  std::function<bool(std::size_t done, std::size_t total)> progress = nullptr;
};

/// Whether every row was computed.
enum class BatchStatus {
  Complete,   ///< every row computed
  Cancelled,  ///< `BatchOptions::progress` returned false: some rows are missing (NaN)
};

/// The rows of a batch: row i for source i, column j for target j (or vertex j when no targets
/// were given), row-major.
struct DistanceMatrix {
  std::size_t rows = 0;     ///< number of sources
  std::size_t columns = 0;  ///< number of targets, or the mesh's vertex count
  /// rows x columns distances, row-major; +infinity where not reached (another component, beyond
  /// `max_distance`); NaN in rows not computed (cancelled).
  std::vector<double> values;
  /// Per row, why its computation stopped (`DistanceStop::TargetReached` when every target had
  /// settled before the field was complete; `NotStarted` for a row not computed).
  std::vector<DistanceStop> stop;
  /// Per row, 1 when computed.
  std::vector<unsigned char> computed;
  /// Whether every row was computed (`Cancelled`: see `computed`).
  BatchStatus status = BatchStatus::Complete;
  /// Threads that ran.
  unsigned threads = 1;
  /// The sum over the threads of the largest working memory one of their rows needed (bytes,
  /// without the result and the table).
  std::size_t peak_working_memory_bytes = 0;
  /// Bytes of the shared `GeodesicRingTable` (0 when none was built).
  std::size_t table_bytes = 0;

  /// Distance from source `i` to target (or vertex) `j`; unchecked.
  double operator()(std::size_t i, std::size_t j) const { return values[i * columns + j]; }
  /// Row `i` (`columns` values); unchecked.
  std::span<const double> row(std::size_t i) const { return {values.data() + i * columns, columns}; }
};

/// One distance field per source vertex: row i holds the distance from `sources[i]` to every
/// vertex of the mesh (columns = `mesh.n_vertices()`).
/// \param mesh     the mesh (only read; it must not change during the call)
/// \param sources  source vertices, one row each; may repeat (equal rows)
/// \param options  `method`, `max_distance` and `track_front` apply to every row; `directions` is
///                 ignored (no directions are returned); `target` must be empty (give targets)
/// \param batch    threads and progress
/// \throws InvalidInput for no source, an invalid or deleted vertex (naming its position), a
///         target in `options`, a bad `max_distance`; what `geodesic_distance` throws for a source
///         (e.g. TopologyError on a non-manifold vertex), after every thread has stopped.
DistanceMatrix geodesic_distances(const Mesh& mesh, std::span<const VertexHandle> sources,
                                  const DistanceOptions& options = {}, const BatchOptions& batch = {});

/// The distances between two vertex sets: row i, column j is the distance from `sources[i]` to
/// `targets[j]`. With `Mdf` and `Windows` a row stops as soon as every target has settled (the
/// values are those of the full field); `Fast` and `Dijkstra` compute the field (up to
/// `max_distance`). \throws as above, and InvalidInput for no target or an invalid target.
DistanceMatrix geodesic_distances(const Mesh& mesh, std::span<const VertexHandle> sources,
                                  std::span<const VertexHandle> targets, const DistanceOptions& options = {},
                                  const BatchOptions& batch = {});

/// Options of the array entry point, in the host's indices.
struct ArrayBatchOptions {
  DistanceMethod method = DistanceMethod::Mdf;  ///< see `DistanceMethod`
  /// Stop beyond this distance (>= 0, not NaN); farther vertices stay +infinity.
  double max_distance = std::numeric_limits<double>::infinity();
};

/// The array entry point (for the Python package): distances from input vertices `sources` of a
/// `GeodesicSolver`'s mesh to input vertices `targets` (empty: every input vertex, one field per
/// source), in the host's indices. A pinched input vertex (split into copies) takes its copies'
/// smallest distance, as `GeodesicSolver::distance_from_vertices`.
/// \throws InvalidInput for no source, an index outside [0, n_vertices()), a bad max_distance.
DistanceMatrix geodesic_distances(const GeodesicSolver& solver, std::span<const int> sources,
                                  std::span<const int> targets, const ArrayBatchOptions& options = {},
                                  const BatchOptions& batch = {});

}  // namespace edgefront
