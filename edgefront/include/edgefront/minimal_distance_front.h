#pragma once
/// \file minimal_distance_front.h
/// The Minimal Distance Front (MDF) of Annuth & Bohn, §2.3, algorithm 3, extended: approximate
/// geodesic distances on a triangle mesh from vertices, a closed edge path or surface points,
/// with memory that follows the front.
///
/// The front is a Minimal Edge Front whose next vertex to expand is the one with the smallest
/// distance (`d_start`) instead of the next one of a level. Every front vertex carries `d_start`
/// and a *virtual source*: the point where the source lies when the surface between it and the
/// vertex is unfolded into the plane of an adjacent face (the paper's `d_start` direction, made
/// exact: its conclusion names the straight-line heuristic as the weak point). When a vertex x
/// settles, each neighbour c takes the smaller of
///   - x's distance plus the edge length, with x as a pseudo source (paths around saddles,
///     borders and re-entrant corners; the Dijkstra bound), and
///   - the distance from x's virtual source, unfolded exactly through the faces around x into a
///     face at the edge x-c, when the straight line from it to c crosses every edge of x in
///     between inside the edge and passes x on c's side.
/// One source per vertex sets its distance (not a window per edge as in exact MMP/ICH); a second
/// one, the best offered from another source position, is propagated too when the first finds
/// no line to a neighbour or the second is straighter (bends later: a path past a pseudo source
/// need not bend there). A value is never below the straight line from the real source, but it
/// can fall slightly below the exact geodesic where a line strays from the faces its source was
/// unfolded along.
/// `DistanceMethod::Windows` keeps windows per edge instead (MMP/ICH carried in the same front
/// order): below 5e-4% mean error on the scanned models, about 3-4x the time of the default.
///
/// Accuracy: exact (to round-off) on regular planar triangulations and on open cylinders and
/// cones; on irregular planar triangulations with obtuse triangles a few vertices come out up to
/// about 2% long (`Windows` is exact there); on CGAL's scanned models a mean relative error of a few tenths of a percent, well
/// below Dijkstra's and CGAL's heat method's (figures per model: bench/results/geodesic-accuracy.md).
///
/// Memory: the loops, the front-vertex table and the priority queue hold O(front) elements; the
/// result arrays (`DistanceField`) are the only per-mesh allocation, and the stepwise class can be
/// used without them (callbacks) for semi-local queries inside `max_distance`.
///
/// Pinched vertices (several fans at one point, split into twins: edgefront/vertex_twins.h) are
/// one point of the surface, in every method: when a twin settles, the others settle at the same
/// distance (equal values) with the same direction (to round-off), each a pseudo source for its own
/// fan at that distance (no straight line or window passes through a point), so distances across
/// a pinch are the sum of the parts. The edge front (`track_front`) continues from each twin as
/// from a source vertex (minimal_edge_front.h). The twins of source vertices are sources; those
/// of a loop source's vertices are at distance 0, pseudo sources for their whole fans. Dijkstra
/// takes a step between twins as an edge of length 0. A vertex that is non-manifold as OpenMesh
/// stores it (several fans, not split) is refused with a `TopologyError` naming
/// `split_pinched_vertices`.

#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "edgefront/front_source.h"
#include "edgefront/mesh.h"
#include "edgefront/surface_point.h"

namespace edgefront {

/// How `geodesic_distance` computes a field: four trade-offs between accuracy and time
/// (README, "Geodesic distances: four modes"; bench/results/geodesic-*.md).
enum class DistanceMethod {
  /// The Minimal Distance Front: one virtual source (and a second, straighter one) per front
  /// vertex, O(front) working memory, stepwise use (`MinimalDistanceFront`), loop sources.
  Mdf,
  /// The MDF carrying windows per edge instead (MMP/ICH in the same front order): near exact,
  /// about 3-4x the MDF's time; vertex and surface-point sources (a loop source runs `Mdf`).
  Windows,
  /// A Dijkstra-like sweep with one straight-line unfolding per edge (see `DistanceOptions`):
  /// whole fields only (`geodesic_distance`, with `max_distance` and `target`), O(mesh) memory;
  /// a loop source runs `Mdf`.
  Fast,
  /// Dijkstra over mesh edges (`dijkstra_distance`): every path runs along edges, so it
  /// overestimates (4-9% on real meshes); the baseline.
  Dijkstra,
};

/// The method's name as the apps and the Python package spell it: "mdf", "windows", "fast",
/// "dijkstra".
const char* to_string(DistanceMethod method);
/// The method named `name` (as `to_string` spells it). \throws InvalidInput for another name.
DistanceMethod parse_distance_method(const std::string& name);

/// Options of the Minimal Distance Front.
struct DistanceOptions {
  /// Stop when the next vertex to settle is farther than this (the paper's d_max). >= 0, not NaN.
  double max_distance = std::numeric_limits<double>::infinity();
  /// Stop as soon as this vertex has settled.
  std::optional<VertexHandle> target = std::nullopt;
  /// Record, per vertex, the unit direction toward the source along the surface.
  bool directions = true;
  /// The method (`geodesic_distance`; the stepwise `MinimalDistanceFront` runs `Mdf` and
  /// `Windows` and refuses the others; `dijkstra_distance` ignores it).
  ///
  /// `DistanceMethod::Windows`, window propagation (as in exact MMP/ICH): every face edge the
  /// front crosses carries the intervals lit straight from a (pseudo) source, with the source unfolded next to it, and they
  /// are carried on face by face in the same distance order as the vertices; saddle and border
  /// vertices become pseudo sources for the directions they shadow. Windows that shorten the
  /// distance by less than 1e-5 (relative) are dropped. Planar and developable meshes come out
  /// exact to round-off (up to ~1e-5 on folded ones); on CGAL's scanned models the mean error is
  /// below 5e-4% (bench/results/geodesic-windows.md). It costs about 3-4x the default (CPU); the
  /// working memory also holds the windows waiting in the queue and the last windows per crossed
  /// edge, and the settled vertices near the front (each is forgotten once the front is past its
  /// distance plus its longest edge): O(front), like the default's. Vertex and surface-point
  /// sources only; a loop source runs `Mdf`.
  ///
  /// `DistanceMethod::Fast`, for `geodesic_distance` only (whole field, `max_distance`,
  /// `target`): a Dijkstra over per-mesh arrays (O(mesh) memory, no edge front) with one straight-line update per
  /// settled vertex x and neighbour c. x's ring is laid out by its corner angles (polar
  /// coordinates) when it settles, or read from a prebuilt `GeodesicRingTable`
  /// (geodesic_ring_table.h) passed to `geodesic_distance(mesh, table, ...)`: the same fields bit
  /// for bit, in less time per query once the table is built (the build costs about as much as
  /// one or two Dijkstras: worth it from the second query on a mesh). x keeps its distance to its virtual
  /// source and the source's ring angle. c takes the distance from the virtual source found, in a
  /// face x-c-y whose corner y is settled too, where the circles of x's and y's source distances
  /// meet (when the line to c crosses x-y); otherwise
  /// from x's source by the law of cosines (when the line crosses x's edges inside them, or x is
  /// intrinsically flat); when it passes an edge of x beyond its far end p, along the path bent
  /// at p (p becomes c's pseudo source); otherwise d + edge length (x a pseudo source: saddles,
  /// borders). Values are clamped between the straight (3D) distance from the source and the
  /// Dijkstra bound, and vertices settle in non-decreasing order: Euclidean <= d <= Dijkstra. Exact
  /// on planar convex regions, open cylinders and cones (vertex or point sources); on scanned
  /// models less accurate than the default mode and far more than Dijkstra, in a small multiple
  /// of `dijkstra_distance`'s time, less than the default's (accuracy:
  /// bench/results/geodesic-accuracy.md; time: bench/results/geodesic-speed.md). Not provided:
  /// the edge front (`peak_front` is 0), the stepwise `MinimalDistanceFront` (its `reset` refuses
  /// the method), loop sources (they run `Mdf`). A vertex nearer the source than all its
  /// neighbours gets its first settled neighbour's distance.
  DistanceMethod method = DistanceMethod::Mdf;
  /// Keep the Minimal Edge Front under the distances: `front_size`, `peak_front` and `validate`
  /// follow it, and its loops count in the working memory. The distances do not need it. Off, the
  /// front is not expanded: somewhat less time for a full field (bench/results/geodesic-speed.md),
  /// the same distances, directions, order and stop; `peak_front` is then 0 for vertex
  /// and point sources, and the working memory counts the distance records and the queue.
  /// Non-manifold vertices (not split into twins) are still refused (when they settle instead of
  /// when they are reached).
  /// `Mdf` only; ignored (kept on) by `Windows`, which expands the front to know where windows start.
  bool track_front = true;
};

/// Why a distance computation stopped.
enum class DistanceStop {
  NotStarted,      ///< no query has run yet
  Exhausted,       ///< every vertex of the source's component (ahead of a loop source) settled
  MaxDistance,     ///< the next vertex would lie beyond `max_distance`
  TargetReached,   ///< `target` settled
};

/// A computed distance field.
struct DistanceField {
  /// Per vertex, the geodesic distance to the source; +infinity where not reached (other
  /// component, behind a loop source, beyond `max_distance`).
  std::vector<double> distance;
  /// Per vertex, the unit vector at the vertex pointing toward the source along the surface
  /// (tangent to the face where the shortest path leaves the vertex); zero at sources and
  /// unreached vertices. Empty when `DistanceOptions::directions` is false.
  std::vector<Vec3> direction;
  /// Vertices in the order they settled (non-decreasing distance up to round-off).
  std::vector<VertexHandle> order;
  DistanceStop stop = DistanceStop::NotStarted;  ///< why the computation stopped
  size_t peak_front = 0;                ///< largest number of front halfedges
  size_t peak_working_memory_bytes = 0; ///< largest working set (loops, tables, queue)
};

/// Stepwise, reusable Minimal Distance Front (a GCS loop or a twist detector may run thousands of
/// small queries: `reset` keeps buffers and touches only what it visits).
class MinimalDistanceFront {
 public:
  /// A front over `mesh` (borrowed: it must outlive the front and not change during a query).
  /// Call `reset` to start a query.
  explicit MinimalDistanceFront(const Mesh& mesh);
  explicit MinimalDistanceFront(const Mesh&& mesh) = delete;  ///< the front reads the mesh: no temporaries
  ~MinimalDistanceFront();
  /// Takes over the moved-from object's state; that object may then only be destroyed or assigned to.
  MinimalDistanceFront(MinimalDistanceFront&&) noexcept;
  /// Takes over the moved-from object's state; that object may then only be destroyed or assigned to.
  MinimalDistanceFront& operator=(MinimalDistanceFront&&) noexcept;

  /// Starts from vertices (distance 0) or a closed edge path (distance to the path, on its ahead
  /// side). \throws InvalidInput for a bad source or options.
  void reset(const FrontSource& source, const DistanceOptions& options = {});
  /// Starts from points on the surface. \throws InvalidInput for an invalid or deleted face, or
  /// barycentric coordinates that are negative, non-finite or do not sum to 1 (within 1e-9).
  void reset(const std::vector<SurfacePoint>& points, const DistanceOptions& options = {});

  /// Settles one vertex (expanding the front around it). Returns false when it stopped.
  bool step();
  /// Runs until a stop condition; returns why.
  DistanceStop run();
  /// Why the current query stopped (`NotStarted` while it runs or before the first `reset`).
  DistanceStop stop_reason() const;

  /// Called when a vertex settles, with its distance and unit direction toward the source.
  void set_settled_callback(std::function<void(VertexHandle, double, const Vec3&)> cb);

  /// Distance of a vertex that is on the front or settled and still remembered, if known.
  std::optional<double> distance(VertexHandle v) const;
  /// Halfedges currently in the edge front (see `DistanceOptions::track_front`).
  size_t front_size() const;
  /// Largest `front_size()` seen since `reset`.
  size_t peak_front_size() const;
  /// Bytes held by the working containers now (capacity, not size).
  size_t working_memory_bytes() const;
  /// Largest `working_memory_bytes()` seen since `reset`.
  size_t peak_working_memory_bytes() const;
  /// Vertices settled since `reset`.
  size_t settled_count() const;

  /// Structural check of the underlying edge front plus the distance invariants (finite,
  /// non-negative distances on the front); throws `InternalError` naming the broken property.
  void validate() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Distance field from vertices or a loop (see `MinimalDistanceFront::reset`).
DistanceField geodesic_distance(const Mesh& mesh, const FrontSource& source, const DistanceOptions& options = {});
/// Distance field from surface points.
DistanceField geodesic_distance(const Mesh& mesh, const std::vector<SurfacePoint>& points,
                                const DistanceOptions& options = {});

/// Baseline: Dijkstra over mesh edges (binary heap, per-mesh arrays), the same sources and
/// options (`method` is ignored). Every path runs along edges, so it overestimates (4-9% on real
/// meshes). `geodesic_distance` with `DistanceMethod::Dijkstra` calls it.
DistanceField dijkstra_distance(const Mesh& mesh, const FrontSource& source, const DistanceOptions& options = {});
/// Dijkstra from surface points: each corner of a point's face starts at its straight distance
/// from the point, then paths run along edges.
DistanceField dijkstra_distance(const Mesh& mesh, const std::vector<SurfacePoint>& points,
                                const DistanceOptions& options = {});

}  // namespace edgefront
