#pragma once
/// \file geodesic_ring_table.h
/// A per-mesh table of vertex rings for many fast distance queries (`DistanceMethod::Fast`).
///
/// The fast mode settles vertices in distance order and, for each settled vertex x, lays x's ring
/// out in the plane by its corner angles (polar coordinates around x). `GeodesicRingTable` does
/// that layout once per mesh: per vertex, its neighbours in ring order (compressed sparse rows,
/// two arrays: neighbour with edge length, corner), each corner with the edge vector and the corner
/// angle to the next neighbour with its cosine and sine; per vertex its position, the angle sum
/// (with cosine and sine), whether the ring is closed, intrinsically flat or non-manifold. A query
/// then does no halfedge walk and no `atan2` or `acos` per corner: when a vertex settles, its ring
/// angles are the corner angles summed and their cosines and sines the corners' rotations
/// multiplied (4 multiplications per neighbour).
///
///     edgefront::GeodesicRingTable table(mesh);      // once per mesh
///     auto f = edgefront::geodesic_distance(mesh, table, edgefront::FrontSource::vertex(v));
///     auto g = edgefront::geodesic_distance(mesh, table, points, {.max_distance = 0.1});
///
/// The table stores the vertices in a locality order, not the mesh's: sorted along a Hilbert curve
/// through their positions (ties by mesh index), so that the rings and per-vertex records a query
/// touches around its front lie close in memory (the effect on query time:
/// bench/results/geodesic-speed.md).
/// `index(v)` is the table index of mesh vertex v, `vertex(i)` the mesh vertex at table index i;
/// `ring`, `edges` and `corners` take table indices, and `Edge::v` is a table index (`Edge::vertex`
/// the mesh's). Queries take and return mesh indices as always.
///
/// The table is a snapshot of the mesh's connectivity and positions: rebuild it whenever the mesh
/// changes (points moved, elements added or deleted, garbage collected). A query compares the
/// mesh's vertex, face and halfedge counts with the table's and throws `InvalidInput` when they
/// differ; moved points or a different mesh with the same counts are not detected. Queries only
/// read the table: several threads may query one table at once.
///
/// Memory: `memory_bytes()`, 72 bytes per halfedge (16 + 56) plus 72 per vertex (64 + the two
/// 4-byte index maps): about 500 bytes per vertex of a closed triangle mesh. Built in O(halfedges)
/// plus a sort of the vertices by their curve keys, one `atan2` per corner.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "edgefront/front_source.h"
#include "edgefront/mesh.h"
#include "edgefront/minimal_distance_front.h"

namespace edgefront {

/// Per-mesh ring layout for fast distance queries (see the file comment). Immutable after
/// construction; several threads may query one table at once.
class GeodesicRingTable {
 public:
  /// One edge x -> v: the neighbour and the edge length (what a walk over edges reads).
  struct Edge {
    double len = 0;   ///< the edge length |v - x| (the mesh's length unit)
    int v = -1;       ///< the neighbour's table index
    int vertex = -1;  ///< the neighbour's mesh index (in the padding: no extra memory)
  };
  /// The corner after one neighbour v of a vertex x, in the ring walk order next(opposite(h))
  /// (the same sense of rotation at every vertex of an oriented mesh).
  struct Corner {
    Vec3 e;                       ///< the edge vector x -> v
    ///@{
    /// Cosine and sine of the corner angle between this edge and the next one.
    double cos_after = 1, sin_after = 0;
    ///@}
    double angle_after = 0;       ///< that corner angle (0 when there is no face after this edge)
    bool face_after = false;      ///< a face lies between this edge and the next one in the walk
  };
  /// Per vertex: where its ring lies and its shape.
  struct Ring {
    Vec3 point;                   ///< the vertex's position
    double total = 0;             ///< the angle sum (sum of corner angles)
    ///@{
    /// Cosine and sine of `total`, as the product of the corners' rotations.
    double cos_total = 1, sin_total = 0;
    ///@}
    std::uint32_t begin = 0;      ///< the ring's first entry in the per-edge arrays
    std::uint32_t size = 0;       ///< the number of neighbours
    std::uint32_t first = 0;      ///< where the ring angle is 0: 0 on a closed ring, the edge after the border gap otherwise
    bool closed = true;           ///< no border gap (isolated vertices too)
    bool flat = false;            ///< closed and the angle sum is 2 pi within 1e-10
    bool non_manifold = false;    ///< several fans meet at the vertex (a query refuses to settle it)
  };

  /// Builds the table. \throws InvalidInput for a mesh with more than 2^32 - 1 halfedges, and
  /// InternalError when a vertex's ring does not close (corrupt connectivity).
  explicit GeodesicRingTable(const Mesh& mesh);

  /// Vertices of the mesh the table was built from (deleted ones included).
  size_t n_vertices() const { return rings_.size(); }
  /// Faces of that mesh (`mesh.n_faces()` at build time).
  size_t n_faces() const { return n_faces_; }
  /// Halfedges of that mesh (`mesh.n_halfedges()` at build time).
  size_t n_halfedges() const { return n_halfedges_; }
  /// The table index of mesh vertex v (0 <= v.idx() < n_vertices(), unchecked).
  int index(VertexHandle v) const { return index_[static_cast<size_t>(v.idx())]; }
  /// The mesh vertex at table index i (0 <= i < n_vertices(), unchecked).
  VertexHandle vertex(int i) const { return VertexHandle(vertex_[static_cast<size_t>(i)]); }
  /// The ring of the vertex at table index i.
  const Ring& ring(int i) const { return rings_[static_cast<size_t>(i)]; }
  /// Its edges in walk order (`ring(i).size` of them) and their corners; two arrays, so that a
  /// walk over edges reads 16 bytes per edge.
  std::span<const Edge> edges(int i) const { return span_of(edges_, i); }
  /// The corners of the vertex at table index i, parallel to `edges(i)`.
  std::span<const Corner> corners(int i) const { return span_of(corners_, i); }
  /// Bytes held by the table.
  size_t memory_bytes() const {
    return rings_.capacity() * sizeof(Ring) + edges_.capacity() * sizeof(Edge) + corners_.capacity() * sizeof(Corner) +
           (index_.capacity() + vertex_.capacity()) * sizeof(int);
  }

  /// Whether the mesh has the vertex, face and halfedge counts the table was built with.
  bool matches(const Mesh& mesh) const;
  /// \throws InvalidInput naming the counts when `matches(mesh)` is false (rebuild the table).
  void check(const Mesh& mesh) const;

 private:
  template <class T>
  std::span<const T> span_of(const std::vector<T>& a, int v) const {
    const Ring& r = rings_[static_cast<size_t>(v)];
    return {a.data() + r.begin, r.size};
  }
  std::vector<Ring> rings_;
  std::vector<Edge> edges_;
  std::vector<Corner> corners_;
  std::vector<int> index_;   // mesh index -> table index
  std::vector<int> vertex_;  // table index -> mesh index
  size_t n_faces_ = 0, n_halfedges_ = 0;
};

/// The fast mode (`DistanceMethod::Fast`, documented there) on a prebuilt table: the same field
/// as `geodesic_distance(mesh, source, {.method = DistanceMethod::Fast})` (which lays out each
/// ring when its vertex settles, with the same code), bit for bit.
/// `options.method` is taken as `Fast` and `track_front` is ignored; a loop source runs the
/// default mode (the table is not used). \throws InvalidInput for a bad source or options, or a
/// table that does not match the mesh (`GeodesicRingTable::check`); TopologyError when a
/// non-manifold vertex settles (one not split into twins; twins, read from the mesh at each query,
/// are one point as in every method: see minimal_distance_front.h).
DistanceField geodesic_distance(const Mesh& mesh, const GeodesicRingTable& table, const FrontSource& source,
                                const DistanceOptions& options = {});
/// The same from surface points (see `MinimalDistanceFront::reset` for their checks).
DistanceField geodesic_distance(const Mesh& mesh, const GeodesicRingTable& table,
                                const std::vector<SurfacePoint>& points, const DistanceOptions& options = {});

/// `dijkstra_distance` (binary heap over mesh edges) reading the edges from the table instead of
/// the mesh's halfedges: the same distances, order and stop (directions to round-off). A loop
/// source runs `dijkstra_distance(mesh, ...)`. \throws as `dijkstra_distance`, and InvalidInput for
/// a table that does not match the mesh.
DistanceField dijkstra_distance(const Mesh& mesh, const GeodesicRingTable& table, const FrontSource& source,
                                const DistanceOptions& options = {});

}  // namespace edgefront
