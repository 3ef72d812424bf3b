#pragma once
/// \file connection_path.h
/// Connection paths between two vertices (Annuth & Bohn, §2.4), with the improvements the paper
/// names but leaves open: a geodesic polyline across faces, a directed search, and many targets
/// from one source.
///
/// The paper's algorithm: two fronts grow alternately from the two vertices; a vertex that lies on
/// both fronts is the middle of the path; the search recurses on both halves until the ends are
/// adjacent. With the Vertex Front or the Minimal Edge Front the path is an edge-wise shortest path
/// (exactly the breadth-first hop count); with the Minimal Distance Front it is the vertex chain of
/// an approximate geodesic, whose length is the sum of the two `d_start` at the top-level meeting
/// vertex; by default its halves are traced down the distances the two MDFs settled instead of
/// recursing (`ConnectionPathOptions::mdf_recursion`). VF/MEF working memory follows the fronts
/// (O(front) per recursion level); the MDF's meeting test and tracing also remember the settled
/// distances (12 bytes per settled vertex, see `ConnectionPath::region_memory_bytes`). The cost
/// depends on the path, not on the mesh: when the vertices are not connected, the smaller
/// component's front dies first and the answer is "no path".
///
/// Pinched vertices (split into twins, edgefront/vertex_twins.h) are one point: a path may pass
/// through one, from a twin to another. Such a step is in the vertex chain (the two twins one
/// after the other) but is not a mesh edge: it counts 0 in `edges` and `edge_length`, and the
/// polyline passes the point exactly (the pieces on either side are straightened each on its own).

#include <cstddef>
#include <memory>
#include <optional>
#include <vector>

#include "edgefront/mesh.h"
#include "edgefront/surface_point.h"

namespace edgefront {

/// Which front finds the path.
enum class PathMethod {
  VertexFront,      ///< edge-wise shortest (hop count), Vertex Front (§2.1)
  MinimalEdgeFront, ///< edge-wise shortest (hop count), Minimal Edge Front (§2.2)
  MinimalDistance,  ///< approximate geodesic, Minimal Distance Front (§2.3)
};

/// Options of a connection path query.
struct ConnectionPathOptions {
  /// The front that finds the path (default: the Minimal Distance Front, a geodesic path).
  PathMethod method = PathMethod::MinimalDistance;
  /// Also compute the geodesic polyline across faces (see `ConnectionPath::polyline`). With the
  /// undirected MDF, the corridor of the shortest edge path (directed search) is straightened too
  /// and the shorter polyline kept; its work counts in `processed`.
  bool polyline = false;
  /// Directed search: instead of two fronts that grow in all directions, a bidirectional A*
  /// search over the mesh edges with the straight-line lower bound (hops: straight-line distance
  /// over the longest edge of the mesh; lengths: straight-line distance), consistent potentials,
  /// one search without recursion (it keeps a predecessor per visited vertex: memory follows the
  /// visited area, not the front). The path metric is that of the method (hops for VF/MEF, edge
  /// lengths for the MDF: with `directed` the MDF vertex chain is a shortest *edge* path and
  /// `length` is its edge length; ask for `polyline` to get the geodesic).
  bool directed = false;
  /// Confinement (paper §3/§4: use the fronts of earlier recursion levels to narrow later ones),
  /// taken to its limit: the two top-level fronts record the levels / distances of what they
  /// process (memory follows the processed area instead of the front), and both halves of the
  /// path are traced inside that region (each step to a neighbour one level lower, or with a
  /// smaller MDF distance), so no recursive searches run. Edge-wise paths keep the exact hop
  /// count. Ignored with `directed`.
  bool confine = false;
  /// MDF only: find the two halves of the path with the paper's recursion (two new fronts per half,
  /// down to adjacent ends; working memory O(front) per level) instead of the default, which traces
  /// them down the distances the two top-level fronts settled (each step to the neighbour with the
  /// smallest distance plus edge length among those with a smaller distance; no further searches).
  /// The length (meeting sum) is the same either way.
  bool mdf_recursion = false;
  /// Polyline: at most this many corridor changes (flips of the path's side around a vertex)
  /// before the straightening stops (status stays Found; `polyline_converged` says whether it
  /// converged). > 0.
  int max_polyline_flips = 10000;
  /// Polyline: after the straightening, the band step (`band_polyline`: shortest path over Steiner
  /// points in a band of faces around the polyline, straightened in its corridor, kept when shorter)
  /// with a band radius of this fraction of the polyline's length; 0 turns it off. Finite, >= 0.
  /// Its band's vertices count in `processed`.
  double polyline_band = 0.3;
  /// Polyline: Steiner points per edge in the band step's search (0..64). More points, a more
  /// accurate polyline at a higher cost (the band step's cost about doubles from 3 to 8); lower it
  /// for speed. Accuracy and time per setting: bench/results/paths.md.
  int polyline_steiner = 8;
};

/// Why a query ended.
enum class PathStatus {
  Found,   ///< a path was found
  NoPath,  ///< the two vertices lie in different components (one front died first)
};

/// A point of a polyline on the surface: on the mesh edge of `halfedge` at parameter `t` from its
/// from-vertex (0) to its to-vertex (1). Points at mesh vertices have `vertex` set (and `t` 0 or 1).
/// `location` is the same point as the library's one surface-location type (surface_point.h), so
/// any point of a polyline is a geodesic source as it is: `geodesic_distance(mesh, {p.location})`.
struct PathPoint {
  HalfedgeHandle halfedge;        ///< the mesh edge the point lies on, as one of its halfedges
  double t = 0.0;                 ///< parameter along `halfedge`, in [0, 1] (0: its from-vertex)
  Vec3 position = Vec3(0, 0, 0);  ///< the point in space (the mesh's length unit)
  VertexHandle vertex;  ///< valid when the point is a mesh vertex
  /// The point as a face and barycentric coordinates: `surface_point_on_edge(mesh, halfedge, t)`
  /// (coordinate 1 at `vertex` for a point at a vertex).
  SurfacePoint location;
};

/// The locations of the points of a polyline (`PathPoint::location` of each, in order): sources
/// for `geodesic_distance` or `MinimalDistanceFront::reset`.
std::vector<SurfacePoint> surface_points(const std::vector<PathPoint>& polyline);

/// The answer of a query.
struct ConnectionPath {
  PathStatus status = PathStatus::NoPath;  ///< Found, or NoPath (different components)
  /// The vertices from `from` to `to`, each joined to the next by a mesh edge or its twin (a pinched
  /// vertex, see above) (empty without a path; one vertex when from == to).
  std::vector<VertexHandle> vertices;
  /// Number of mesh edges of `vertices` (hop count; steps between twins do not count).
  size_t edges = 0;
  /// Sum of the Euclidean lengths of the chain's edges.
  double edge_length = 0.0;
  /// Geometric length: the MDF's geodesic estimate (sum of the two `d_start` at the top-level
  /// meeting vertex) for the undirected MDF, the polyline length when a polyline was computed,
  /// otherwise `edge_length`.
  double length = 0.0;
  /// The geodesic polyline from `from` to `to` when `ConnectionPathOptions::polyline` is set:
  /// first and last points are the end vertices, inner points lie on mesh edges (or at vertices
  /// where the path wraps around one), consecutive points share a face or are twins (the path
  /// passes a pinched vertex).
  std::vector<PathPoint> polyline;
  double polyline_length = 0.0;  ///< length of `polyline` (the mesh's length unit); 0 without one
  bool polyline_converged = false;  ///< the straightening ended because nothing shortened any more
  /// Elements processed: vertices enclosed/settled by all fronts of all recursion levels (or
  /// vertices settled by the directed search).
  size_t processed = 0;
  /// Number of two-front searches (1 + recursive ones).
  size_t searches = 0;
  /// Largest working memory during the query (bytes, capacity): the fronts of one search plus the
  /// per-vertex values kept for the processed area (`region_memory_bytes`).
  size_t peak_working_memory_bytes = 0;
  /// Largest front of one search (front elements: halfedges for MEF/MDF, vertices for the VF).
  /// It follows the front.
  size_t peak_front_size = 0;
  /// Largest working memory of one front (bytes, capacity). It follows the front.
  size_t peak_front_memory_bytes = 0;
  /// Largest memory of the per-vertex values kept for the processed area, in bytes (the MDF's
  /// settled distances of both fronts (meeting test and tracing), the level fronts' values with
  /// `confine`, find_many's source values: 12 bytes per remembered vertex, without the hash table's
  /// spare capacity; the directed search: its tables' capacity). These follow the area.
  size_t region_memory_bytes = 0;
};

/// A reusable path finder: keeps its fronts' buffers across queries. The mesh must outlive it and
/// must not change while it is used.
class ConnectionPathFinder {
 public:
  /// A finder over `mesh` (borrowed: it must outlive the finder and not change while it is used).
  explicit ConnectionPathFinder(const Mesh& mesh);
  explicit ConnectionPathFinder(const Mesh&& mesh) = delete;  ///< the finder reads the mesh: no temporaries
  ~ConnectionPathFinder();
  /// Takes over the moved-from object's buffers; that object may then only be destroyed or assigned to.
  ConnectionPathFinder(ConnectionPathFinder&&) noexcept;
  /// Takes over the moved-from object's buffers; that object may then only be destroyed or assigned to.
  ConnectionPathFinder& operator=(ConnectionPathFinder&&) noexcept;

  /// One path. from == to gives a one-vertex path of length 0; adjacent vertices (or twins) the edge.
  /// \param from, to live vertices of the finder's mesh.
  /// \param options the method and what to compute besides the vertex chain.
  /// \return the path, or `PathStatus::NoPath` (empty `vertices`) when `from` and `to` lie in
  ///         different components.
  /// \throws InvalidInput for an invalid or deleted vertex or bad options (naming it).
  /// \throws TopologyError when a front meets a non-manifold vertex.
  ConnectionPath find(VertexHandle from, VertexHandle to, const ConnectionPathOptions& options = {});

  /// Paths from one source to many targets. One source front serves all targets: it grows only
  /// while the next target is not processed yet and is kept between targets (memory follows the
  /// area it covers: it remembers the levels / distances it processed). Each path is traced from its
  /// target down those values to the source (VF/MEF: one level lower per step, the exact hop
  /// count; MDF: as the default halves of `find`), so no front runs per target. The MDF length is
  /// the source front's distance at the target (one front, not a meeting sum). Results in the
  /// order of `targets`; `processed` of a result counts the source front's growth it caused (plus
  /// its polyline's directed search). `directed`, `confine` and `mdf_recursion` are ignored here.
  /// \throws InvalidInput as `find`.
  std::vector<ConnectionPath> find_many(VertexHandle from, const std::vector<VertexHandle>& targets,
                                        const ConnectionPathOptions& options = {});

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// One connection path: `ConnectionPathFinder(mesh).find(from, to, options)` (see there).
ConnectionPath connection_path(const Mesh& mesh, VertexHandle from, VertexHandle to,
                               const ConnectionPathOptions& options = {});

/// The geodesic polyline along a vertex chain (each vertex joined to the next by an edge, or its
/// twin: a pinched vertex, where the chain is cut into pieces straightened each on its own): the
/// faces around the chain form a corridor that is unfolded into the plane and straightened with
/// the funnel algorithm; wherever the straightened path wraps around a vertex with the corridor on
/// the wrong side (the other side is shorter), the corridor is moved to that side and the path
/// straightened again, until no change shortens it or `max_flips` changes were made.
/// \param mesh the mesh of the chain.
/// \param chain vertices from one end to the other, at least one.
/// \param max_flips at most this many corridor changes tried (<= 0: none, only the first
///        straightening).
/// \param converged when not null, set to true when the straightening stopped because nothing
///        shortened any more, false when it stopped at `max_flips`.
/// \return the points (see `ConnectionPath::polyline`), from the first vertex of `chain` to its last.
/// \throws InvalidInput when the chain is empty, has an invalid vertex or two consecutive
///         vertices that are neither joined by an edge nor twins.
std::vector<PathPoint> geodesic_polyline(const Mesh& mesh, const std::vector<VertexHandle>& chain,
                                         int max_flips = 10000, bool* converged = nullptr);

/// The band step after the straightening (which stops at a *locally* shortest path, possibly on the
/// wrong side of a bump): the faces with a vertex within `band_radius` (edge-path distance) of the
/// polyline form a band; the shortest path over the band's vertices and `steiner_points` points per
/// edge (A*, straight segments inside faces) picks the way through the band, and the corridor of the
/// faces it crosses is straightened as in `geodesic_polyline`. Returns that polyline when it is
/// shorter than `polyline`, otherwise `polyline` itself. Work and memory follow the band, not the
/// mesh; `band_vertices` (optional) receives the number of vertices of the band. A polyline through
/// pinched vertices (consecutive twin points) keeps those points: each piece between them is
/// treated on its own.
/// \throws InvalidInput for a negative or non-finite radius, steiner_points outside 0..64, an empty
///         polyline or one that does not start and end at mesh vertices.
std::vector<PathPoint> band_polyline(const Mesh& mesh, const std::vector<PathPoint>& polyline, double band_radius,
                                     int steiner_points = 8, int max_flips = 10000, bool* converged = nullptr,
                                     size_t* band_vertices = nullptr);

/// Sum of the Euclidean distances between consecutive points' positions (0 for fewer than two).
double polyline_length(const std::vector<PathPoint>& points);

}  // namespace edgefront
