#pragma once
/// \file arrays.h
/// Plain arrays in and out: EdgeFront for a host that keeps its mesh in its own structure.
///
/// A host passes its vertex positions (n x 3, row-major, `double` or `float`) and its triangles
/// (m x 3, row-major, `int32` or `int64`) as views of its own memory; nothing is copied before
/// the conversion reads it, and `int64` indices (numpy's default) are converted to `int` once.
/// Results come back as plain vectors in the host's own indices.
///
/// \code
///   std::vector<double> V = ...;  // 3 n values
///   std::vector<int> F = ...;     // 3 m values
///   edgefront::GeodesicSolver solver(V, F);          // converts once
///   std::vector<double> d = solver.distance_from_vertices(std::vector<int>{0}).distance;
///   auto near = solver.distances_within(std::vector<int>{0}, 0.1);  // O(what it visits)
/// \endcode
///
/// The conversion (`mesh_from_arrays`, also what `read_mesh` builds its meshes with):
/// - vertex i of the input is vertex i of the mesh; isolated vertices are kept;
/// - a face that cannot join a half-edge mesh is dropped and reported with its row (or, with
///   `ConversionOptions::drop_nonmanifold_faces` false, refused): a third face on an edge, or a
///   second face using an edge in the same direction (the two faces are wound against each other,
///   or the face repeats an earlier one). Rows are taken in order: the earlier face stays.
///   Orient a soup first (`twist::orient_arrays`) when its windings disagree;
/// - a *pinched* vertex (several fans of faces meet there only at the vertex) is split: the fan
///   of its lowest face row keeps the vertex, every other fan gets a copy, appended after the
///   input's vertices (in the order of their originals, then of the fans' lowest rows), and the
///   copies are linked as twins of the original (`edgefront/vertex_twins.h`): the distance
///   methods and fronts treat them as one point.
///
/// Per-vertex results of the entry points below have one entry per *input* vertex (a pinched
/// vertex's value is the one of its copies that the method reached first: the smallest distance,
/// the lowest level); the converted mesh (`GeodesicSolver::converted`) lists the input's
/// vertices, then the copies.
///
/// Errors: a wrong shape (not n x 3), empty arrays, NaN, infinite or huge (|x| > 1e150: their
/// squares overflow) coordinates, negative or out-of-range indices, a face with a repeated vertex
/// throw `InvalidInput` naming the row (and, for a coordinate, the column).

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "edgefront/connection_path.h"
#include "edgefront/front_source.h"
#include "edgefront/mesh.h"
#include "edgefront/minimal_distance_front.h"

namespace edgefront {

/// Vertex positions in the caller's memory, read-only and not owned: `size` values, `cols` per
/// row, row-major, `double` or `float`. Functions taking a view read it during the call only.
/// Only n x 3 is accepted; the shape is kept so that a wrong one gets a clear message.
class VertexArrayView {
 public:
  /// An empty view (no rows); the entry points refuse it as a wrong shape.
  VertexArrayView() = default;
  ///@{
  /// `rows` x `cols` values at `data`, row-major (only `cols` = 3 is accepted by the checks).
  VertexArrayView(const double* data, size_t rows, size_t cols = 3) : d_(data), size_(rows * cols), cols_(cols) {}
  VertexArrayView(const float* data, size_t rows, size_t cols = 3) : f_(data), size_(rows * cols), cols_(cols) {}
  ///@}
  ///@{
  /// A flat array (x0 y0 z0 x1 ...); a size that is not a multiple of `cols` is a wrong shape.
  VertexArrayView(std::span<const double> flat, size_t cols = 3) : d_(flat.data()), size_(flat.size()), cols_(cols) {}
  VertexArrayView(std::span<const float> flat, size_t cols = 3) : f_(flat.data()), size_(flat.size()), cols_(cols) {}
  ///@}
  ///@{
  /// A flat vector (x0 y0 z0 x1 ...), 3 values per row; it must outlive the view's use.
  VertexArrayView(const std::vector<double>& flat) : VertexArrayView(std::span<const double>(flat)) {}
  VertexArrayView(const std::vector<float>& flat) : VertexArrayView(std::span<const float>(flat)) {}
  ///@}
  ///@{
  /// One `{x, y, z}` per row.
  VertexArrayView(std::span<const std::array<double, 3>> rows)
      : d_(rows.empty() ? nullptr : rows.data()->data()), size_(3 * rows.size()) {}
  VertexArrayView(const std::vector<std::array<double, 3>>& rows)
      : VertexArrayView(std::span<const std::array<double, 3>>(rows)) {}
  ///@}

  /// Number of rows (`size() / cols()`; 0 when `cols()` is 0).
  size_t rows() const { return cols_ ? size_ / cols_ : 0; }
  /// Values per row (3 for a valid view).
  size_t cols() const { return cols_; }
  /// Number of values.
  size_t size() const { return size_; }
  /// True when the data are `float` (else `double`).
  bool is_float() const { return f_ != nullptr; }
  /// Throws InvalidInput naming `what` unless the view is a non-empty n x 3 array.
  void check_shape(const char* what) const;
  /// `check_shape`, and every value finite and at most 1e150 in magnitude (InvalidInput naming the
  /// row and column).
  void check_values(const char* what) const;
  /// Row i, column k (unchecked).
  double at(size_t i, size_t k) const { return d_ ? d_[i * cols_ + k] : static_cast<double>(f_[i * cols_ + k]); }
  /// Row i as a point (unchecked; needs 3 columns).
  Vec3 point(size_t i) const { return Vec3(at(i, 0), at(i, 1), at(i, 2)); }

 private:
  const double* d_ = nullptr;
  const float* f_ = nullptr;
  size_t size_ = 0;
  size_t cols_ = 3;
};

/// Triangles in the caller's memory, read-only and not owned: `size` vertex indices, `cols` per
/// row, row-major, `int32` or `int64`. Only m x 3 is accepted.
class FaceArrayView {
 public:
  /// An empty view (no rows); the entry points refuse it as a wrong shape.
  FaceArrayView() = default;
  ///@{
  /// `rows` x `cols` vertex indices at `data`, row-major (only `cols` = 3 is accepted).
  FaceArrayView(const std::int32_t* data, size_t rows, size_t cols = 3) : i32_(data), size_(rows * cols), cols_(cols) {}
  FaceArrayView(const std::int64_t* data, size_t rows, size_t cols = 3) : i64_(data), size_(rows * cols), cols_(cols) {}
  ///@}
  ///@{
  /// A flat array (a0 b0 c0 a1 ...); a size that is not a multiple of `cols` is a wrong shape.
  FaceArrayView(std::span<const std::int32_t> flat, size_t cols = 3) : i32_(flat.data()), size_(flat.size()), cols_(cols) {}
  FaceArrayView(std::span<const std::int64_t> flat, size_t cols = 3) : i64_(flat.data()), size_(flat.size()), cols_(cols) {}
  ///@}
  ///@{
  /// A flat vector (a0 b0 c0 a1 ...), 3 indices per row; it must outlive the view's use.
  FaceArrayView(const std::vector<std::int32_t>& flat) : FaceArrayView(std::span<const std::int32_t>(flat)) {}
  FaceArrayView(const std::vector<std::int64_t>& flat) : FaceArrayView(std::span<const std::int64_t>(flat)) {}
  ///@}
  ///@{
  /// One `{a, b, c}` per row.
  FaceArrayView(std::span<const std::array<int, 3>> rows)
      : i32_(rows.empty() ? nullptr : rows.data()->data()), size_(3 * rows.size()) {}
  FaceArrayView(const std::vector<std::array<int, 3>>& rows) : FaceArrayView(std::span<const std::array<int, 3>>(rows)) {}
  ///@}

  /// Number of rows (`size() / cols()`; 0 when `cols()` is 0).
  size_t rows() const { return cols_ ? size_ / cols_ : 0; }
  /// Indices per row (3 for a valid view).
  size_t cols() const { return cols_; }
  /// Number of indices.
  size_t size() const { return size_; }
  /// True when the indices are `int64` (else `int32`).
  bool is_int64() const { return i64_ != nullptr; }
  /// Throws InvalidInput naming `what` unless the view is a non-empty m x 3 array.
  void check_shape(const char* what) const;
  /// Row i, column k (unchecked).
  std::int64_t at(size_t i, size_t k) const { return i32_ ? i32_[i * cols_ + k] : i64_[i * cols_ + k]; }
  /// The int32 data when the view holds int32 (else null).
  const std::int32_t* int32_data() const { return i32_; }

 private:
  const std::int32_t* i32_ = nullptr;
  const std::int64_t* i64_ = nullptr;
  size_t size_ = 0;
  size_t cols_ = 3;
};

/// A triangle mesh as plain arrays (what the entry points return).
struct MeshArrays {
  std::vector<double> vertices;  ///< n x 3, row-major
  std::vector<int> faces;        ///< m x 3, row-major
  /// Number of vertices (rows of `vertices`).
  size_t n_vertices() const { return vertices.size() / 3; }
  /// Number of faces (rows of `faces`).
  size_t n_faces() const { return faces.size() / 3; }
};

/// Options of `mesh_from_arrays`.
struct ConversionOptions {
  /// Faces a half-edge mesh cannot hold (see the file comment) are dropped and reported (true,
  /// the default), or refused: `InvalidInput` naming the row and the edge.
  bool drop_nonmanifold_faces = true;
};

/// Why a face row was dropped.
enum class FaceDropReason {
  EdgeHasTwoFaces,   ///< the edge (`edge`) already has two faces: a third one would make it non-manifold
  EdgeSameDirection, ///< an earlier face uses the edge in the same direction (wound against it, or repeated)
};

/// A face row the conversion dropped, and why.
struct DroppedFace {
  size_t row = 0;                ///< the input row
  FaceDropReason reason = FaceDropReason::EdgeHasTwoFaces;  ///< why it was dropped
  std::array<int, 2> edge{-1, -1};  ///< the input vertices of the edge it conflicted on, in the face's direction
};

/// What the conversion changed.
struct ConversionReport {
  size_t input_vertices = 0;  ///< rows of the vertex array
  size_t input_faces = 0;     ///< rows of the face array
  std::vector<DroppedFace> dropped_faces;  ///< in row order
  size_t pinched_vertices = 0;             ///< input vertices split into several (one per fan)
  size_t vertex_copies = 0;                ///< copies appended for them
  size_t isolated_vertices = 0;            ///< input vertices no kept face uses (kept)
  /// True when the mesh differs from the input as a host sees it (faces dropped or vertices split).
  bool changed() const { return !dropped_faces.empty() || vertex_copies > 0; }
};

/// A converted mesh with its index maps.
struct ArrayMesh {
  Mesh mesh;  ///< face normals up to date; pinched copies linked as twins
  /// Per mesh vertex: the input vertex (row) it stands for. Mesh vertex i < n is input vertex i;
  /// a copy names its original.
  std::vector<int> vertex_row;
  /// Per input face row: the mesh face, or -1 when dropped.
  std::vector<int> face_of_row;
  /// Per mesh face: the input row.
  std::vector<int> face_row;
  ConversionReport report;  ///< what the conversion dropped and split
};

/// Builds a mesh from arrays (see the file comment).
/// \throws InvalidInput for bad arrays (naming the row) or, with `drop_nonmanifold_faces` false,
///         for a face a half-edge mesh cannot hold (naming the row and the edge).
ArrayMesh mesh_from_arrays(const VertexArrayView& vertices, const FaceArrayView& faces,
                           const ConversionOptions& options = {});

/// The live vertices and faces of `mesh` as arrays, renumbered in index order when the mesh has
/// deleted elements. Each face row starts at the vertex it was added with (a face added as
/// `add_face(a, b, c)` gives the row a b c).
MeshArrays mesh_to_arrays(const Mesh& mesh);

/// The live vertices and faces of any OpenMesh mesh (`TriMesh_ArrayKernelT` or
/// `PolyMesh_ArrayKernelT` of any traits: float or double points, with or without status
/// attributes) as arrays: deleted elements (when the mesh has status) are skipped and the rest
/// renumbered in index order, polygons fan-triangulated from their first vertex. What a host with
/// its own OpenMesh type converts with, instead of `Mesh::assign` (which drops the attributes
/// EdgeFront needs: see `has_attributes`).
template <class OtherMesh>
MeshArrays openmesh_to_arrays(const OtherMesh& other) {
  MeshArrays out;
  std::vector<int> row(other.n_vertices(), -1);
  int next = 0;
  for (size_t i = 0; i < other.n_vertices(); ++i) {
    const typename OtherMesh::VertexHandle v(static_cast<int>(i));
    if (other.has_vertex_status() && other.status(v).deleted()) continue;
    row[i] = next++;
    const auto& p = other.point(v);
    out.vertices.insert(out.vertices.end(), {static_cast<double>(p[0]), static_cast<double>(p[1]), static_cast<double>(p[2])});
  }
  std::vector<int> corners;
  for (size_t i = 0; i < other.n_faces(); ++i) {
    const typename OtherMesh::FaceHandle f(static_cast<int>(i));
    if (other.has_face_status() && other.status(f).deleted()) continue;
    corners.clear();
    for (auto v : other.fv_range(f)) corners.push_back(row[static_cast<size_t>(v.idx())]);
    for (size_t k = 1; k + 1 < corners.size(); ++k) out.faces.insert(out.faces.end(), {corners[0], corners[k], corners[k + 1]});
  }
  return out;
}

/// `mesh_from_arrays(openmesh_to_arrays(other))`: an `edgefront::Mesh` (with its attributes) from
/// any OpenMesh mesh; the index maps refer to `other`'s live elements in index order (its own
/// indices when it has no deleted elements and only triangles).
template <class OtherMesh>
ArrayMesh mesh_from_openmesh(const OtherMesh& other, const ConversionOptions& options = {}) {
  const MeshArrays a = openmesh_to_arrays(other);
  return mesh_from_arrays(a.vertices, a.faces, options);
}

/// Options of the distance entry points, in the host's indices.
struct ArrayDistanceOptions {
  DistanceMethod method = DistanceMethod::Mdf;  ///< see `DistanceMethod`
  /// Stop beyond this distance (>= 0, not NaN); vertices farther away stay +infinity.
  double max_distance = std::numeric_limits<double>::infinity();
  int target = -1;          ///< stop once this input vertex has its distance; -1: none
  bool directions = false;  ///< also return, per vertex, the unit direction toward the source
};

/// A distance field in the host's indices.
struct DistanceArrays {
  std::vector<double> distance;   ///< per input vertex; +infinity where not reached
  std::vector<double> direction;  ///< n x 3 when asked for (zero at sources and unreached vertices), else empty
  DistanceStop stop = DistanceStop::NotStarted;  ///< why the query stopped
};

/// The vertices a bounded query settled, in the order they settled (non-decreasing distance):
/// O(what the front visited), nothing per mesh vertex.
struct SparseDistances {
  std::vector<int> vertex;        ///< input vertices (a pinched vertex once)
  std::vector<double> distance;   ///< their distances
  DistanceStop stop = DistanceStop::NotStarted;  ///< why the query stopped
};

/// A connection path in the host's indices (see `ConnectionPath`).
struct PathArrays {
  PathStatus status = PathStatus::NoPath;  ///< Found, or NoPath (different components)
  std::vector<int> vertices;  ///< input vertices from `from` to `to`, each joined to the next by an edge
  double length = 0;          ///< `ConnectionPath::length`
  /// The geodesic polyline when asked for (`ConnectionPathOptions::polyline`): k x 3 positions,
  /// and per point the mesh edge it lies on as k x 2 input vertices (`edge[2i]` at t = 0,
  /// `edge[2i + 1]` at t = 1) with its parameter `t`; a point at a vertex names that vertex twice.
  std::vector<double> points;
  std::vector<int> edge;  ///< k x 2 input vertices per polyline point (see `points`)
  std::vector<double> t;  ///< per polyline point, its parameter in [0, 1] along `edge`
  /// Per polyline point, the same point as a face row and barycentric coordinates (k x 3, in the
  /// row's corner order; `PathPoint::location`): pass both to `distance_from_points` to measure
  /// from points of the polyline. -1 (and zeros) for a point without a face (an isolated vertex).
  std::vector<int> face;
  std::vector<double> barycentric;  ///< k x 3, see `face`
};

/// A reusable solver for many queries on one mesh given as arrays: keeps the converted mesh, the
/// stepwise front of the bounded queries and (built on the first fast-mode query) the
/// `GeodesicRingTable`. Field queries (`distance_from_*`, `levels`, `polyline`) are const and
/// may run from several threads at once; the bounded and path queries reuse buffers (not const).
class GeodesicSolver {
 public:
  /// Converts the arrays (`mesh_from_arrays`). \throws InvalidInput as `mesh_from_arrays`.
  GeodesicSolver(const VertexArrayView& vertices, const FaceArrayView& faces, const ConversionOptions& options = {});
  /// Takes a mesh already converted.
  explicit GeodesicSolver(ArrayMesh converted);
  ~GeodesicSolver();
  /// Takes over the moved-from object's state; that object may then only be destroyed or assigned to.
  GeodesicSolver(GeodesicSolver&&) noexcept;
  /// Takes over the moved-from object's state; that object may then only be destroyed or assigned to.
  GeodesicSolver& operator=(GeodesicSolver&&) noexcept;

  /// The converted mesh and its index maps (see the file comment).
  const ArrayMesh& converted() const;
  /// Input vertices (rows of the vertex array given).
  size_t n_vertices() const;
  /// Input faces (rows of the face array given).
  size_t n_faces() const;

  /// Distance field from input vertices (distance 0). \throws InvalidInput for an empty source,
  /// an index out of range, a repeated vertex, a vertex no face uses, or bad options.
  DistanceArrays distance_from_vertices(std::span<const int> sources, const ArrayDistanceOptions& options = {}) const;
  /// From surface points: per point an input face row and barycentric coordinates (k x 3) with
  /// respect to that row's vertices in the row's order. \throws InvalidInput for a bad or
  /// dropped face, coordinates that are negative, non-finite or do not sum to 1 (within 1e-9),
  /// or arrays of different lengths.
  DistanceArrays distance_from_points(std::span<const int> faces, std::span<const double> barycentric,
                                      const ArrayDistanceOptions& options = {}) const;
  /// From a closed edge loop v0, v1, ..., v(k-1) (input vertices, each joined to the next and the
  /// last to the first by an edge), into the faces on `side` of it (`loop_from_vertices`; the
  /// `Windows` and `Fast` methods run `Mdf` for a loop).
  DistanceArrays distance_from_loop(std::span<const int> loop, LoopSide side = LoopSide::Left,
                                    const ArrayDistanceOptions& options = {}) const;
  /// The vertices within `max_distance` of the sources (the MDF, or `Windows`, stepwise; a
  /// reused front: O(what it visits)). `method` must be `Mdf` or `Windows`.
  SparseDistances distances_within(std::span<const int> sources, double max_distance,
                                   DistanceMethod method = DistanceMethod::Mdf);
  /// The geodesic distance from `from` to `to` when it is at most `max_distance`, else nothing:
  /// "is this point far along the surface?" (stepwise MDF, stops at `to` or beyond the bound).
  std::optional<double> distance_between(int from, int to, double max_distance);

  /// Minimal Edge Front levels (breadth-first hop distance) per input vertex, -1 where not
  /// reached within `max_levels` (all when negative).
  std::vector<int> levels(std::span<const int> sources, int max_levels = -1) const;
  /// A connection path between two input vertices (`ConnectionPathFinder::find`).
  PathArrays connection_path(int from, int to, const ConnectionPathOptions& options = {});
  /// The geodesic polyline along a vertex chain (`geodesic_polyline`).
  PathArrays polyline(std::span<const int> chain, int max_flips = 10000) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// The bounded queries behind `GeodesicSolver::distances_within` and `distance_between`, for a
/// caller that keeps its own mesh, front and index map (`twist::RepairSession` on its mirror):
/// `host_of_vertex` gives per mesh vertex the caller's index (-1: none), which the results use;
/// a group of twins is listed once. \throws InvalidInput for a bad source, bound or method.
SparseDistances distances_within(MinimalDistanceFront& front, const std::vector<VertexHandle>& sources,
                                 double max_distance, DistanceMethod method, std::span<const int> host_of_vertex);
/// The distance from `from` to `to` (or a twin of it) when at most `max_distance`.
std::optional<double> distance_between(MinimalDistanceFront& front, VertexHandle from, VertexHandle to,
                                       double max_distance, std::span<const int> host_of_vertex);

/// One-shot distance field from input vertices: `GeodesicSolver(vertices, faces).distance_from_vertices(...)`.
DistanceArrays geodesic_distance(const VertexArrayView& vertices, const FaceArrayView& faces,
                                 std::span<const int> sources, const ArrayDistanceOptions& options = {});

}  // namespace edgefront
