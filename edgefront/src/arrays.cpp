// Plain arrays in and out: the views' checks, the conversion (through the mesh builder,
// mesh_builder.cpp), the bounded queries and the GeodesicSolver.

#include "edgefront/arrays.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <limits>
#include <mutex>
#include <string>
#include <unordered_set>

#include "detail/mesh_builder.h"
#include "edgefront/error.h"
#include "edgefront/geodesic_ring_table.h"
#include "edgefront/minimal_edge_front.h"
#include "edgefront/vertex_twins.h"

namespace edgefront {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
/// Larger coordinates make squared lengths overflow.
constexpr double kMaxCoordinate = 1e150;

void check_view_shape(size_t size, size_t cols, const char* what, const char* kind) {
  if (cols != 3) {
    throw InvalidInput(std::string(what) + ": expected " + kind + " x 3 values, got rows of " + std::to_string(cols));
  }
  if (size % 3 != 0) {
    throw InvalidInput(std::string(what) + ": " + std::to_string(size) + " values are not rows of 3 (" + kind +
                       " x 3 expected)");
  }
  if (size == 0) throw InvalidInput(std::string(what) + ": the array is empty");
}

std::string number_text(double x) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

}  // namespace

void VertexArrayView::check_values(const char* what) const {
  check_shape(what);
  for (size_t i = 0; i < rows(); ++i) {
    for (size_t k = 0; k < 3; ++k) {
      const double x = at(i, k);
      if (!(std::abs(x) <= kMaxCoordinate)) {
        throw InvalidInput(std::string(what) + ": row " + std::to_string(i) + ", column " + std::to_string(k) + " is " +
                           number_text(x) + (std::isfinite(x) ? " (beyond 1e150: its square would overflow)" : ""));
      }
    }
  }
}

namespace {

/// The faces as int32 rows, checked: indices in [0, n), three distinct per row. The caller's int32
/// memory is used as it is; int64 is converted once into `storage`.
std::span<const int> checked_triangles(const FaceArrayView& f, size_t n, std::vector<int>& storage) {
  f.check_shape("faces");
  if (n > static_cast<size_t>(std::numeric_limits<int>::max())) {
    throw InvalidInput("vertices: " + std::to_string(n) + " rows are more than an int index can address");
  }
  const std::int64_t limit = static_cast<std::int64_t>(n);
  for (size_t r = 0; r < f.rows(); ++r) {
    const std::int64_t a = f.at(r, 0), b = f.at(r, 1), c = f.at(r, 2);
    for (std::int64_t x : {a, b, c}) {
      if (x < 0 || x >= limit) {
        throw InvalidInput("faces: row " + std::to_string(r) + " has vertex index " + std::to_string(x) + " outside [0, " +
                           std::to_string(n) + ")");
      }
    }
    if (a == b || b == c || a == c) {
      throw InvalidInput("faces: row " + std::to_string(r) + " repeats vertex " + std::to_string(a == b || a == c ? a : b));
    }
  }
  if (f.int32_data()) return {f.int32_data(), f.size()};
  storage.resize(f.size());
  for (size_t r = 0; r < f.rows(); ++r) {
    for (size_t k = 0; k < 3; ++k) storage[3 * r + k] = static_cast<int>(f.at(r, k));
  }
  return storage;
}


}  // namespace

void VertexArrayView::check_shape(const char* what) const { check_view_shape(size_, cols_, what, "n"); }
void FaceArrayView::check_shape(const char* what) const { check_view_shape(size_, cols_, what, "m"); }

// -------------------------------------------------------------------------------------------
// Conversion

ArrayMesh mesh_from_arrays(const VertexArrayView& vertices, const FaceArrayView& faces, const ConversionOptions& options) {
  vertices.check_values("vertices");
  std::vector<int> storage;
  const std::span<const int> tris = checked_triangles(faces, vertices.rows(), storage);
  ArrayMesh out = detail::build_mesh(detail::PointRows{&vertices, nullptr}, tris);
  if (!options.drop_nonmanifold_faces && !out.report.dropped_faces.empty()) {
    const DroppedFace& d = out.report.dropped_faces.front();
    const std::string edge = std::to_string(d.edge[0]) + " -> " + std::to_string(d.edge[1]);
    throw InvalidInput("faces: row " + std::to_string(d.row) + " cannot join a half-edge mesh: " +
                       (d.reason == FaceDropReason::EdgeHasTwoFaces
                            ? "its edge " + edge + " already has two faces (a non-manifold edge)"
                            : "an earlier face uses its edge " + edge +
                                  " in the same direction (wound against it, or repeated)"));
  }
  return out;
}

MeshArrays mesh_to_arrays(const Mesh& mesh) {
  MeshArrays out;
  std::vector<int> row(mesh.n_vertices(), -1);
  out.vertices.reserve(3 * mesh.n_vertices());
  int next = 0;
  for (size_t i = 0; i < mesh.n_vertices(); ++i) {
    const VertexHandle v(static_cast<int>(i));
    if (mesh.status(v).deleted()) continue;
    row[i] = next++;
    const Vec3& p = mesh.point(v);
    out.vertices.insert(out.vertices.end(), {p[0], p[1], p[2]});
  }
  out.faces.reserve(3 * mesh.n_faces());
  for (size_t i = 0; i < mesh.n_faces(); ++i) {
    const FaceHandle f(static_cast<int>(i));
    if (mesh.status(f).deleted()) continue;
    // The to-vertex of the face's halfedge first: add_face(a, b, c) gives a b c.
    HalfedgeHandle h = mesh.halfedge_handle(f);
    for (int k = 0; k < 3; ++k) {
      const int r = row[static_cast<size_t>(mesh.to_vertex_handle(h).idx())];
      EF_CHECK(r >= 0, "mesh_to_arrays: a live face uses a deleted vertex");
      out.faces.push_back(r);
      h = mesh.next_halfedge_handle(h);
    }
    EF_CHECK(h == mesh.halfedge_handle(f), "mesh_to_arrays: a face is not a triangle");
  }
  return out;
}

// -------------------------------------------------------------------------------------------
// Bounded queries on a caller's mesh

namespace {

/// The caller's index of mesh vertex v, each group of twins once (`seen` collects the groups).
int host_index(std::span<const int> host_of_vertex, VertexHandle v) {
  const size_t i = static_cast<size_t>(v.idx());
  return i < host_of_vertex.size() ? host_of_vertex[i] : -1;
}

}  // namespace

SparseDistances distances_within(MinimalDistanceFront& front, const std::vector<VertexHandle>& sources,
                                 double max_distance, DistanceMethod method, std::span<const int> host_of_vertex) {
  if (method != DistanceMethod::Mdf && method != DistanceMethod::Windows) {
    throw InvalidInput(std::string("distances_within: the method must be mdf or windows (stepwise), got ") + to_string(method));
  }
  DistanceOptions o;
  o.max_distance = max_distance;
  o.directions = false;
  o.method = method;
  front.reset(FrontSource::from_vertices(sources), o);
  SparseDistances out;
  std::unordered_set<int> seen;
  front.set_settled_callback([&](VertexHandle v, double d, const Vec3&) {
    const int h = host_index(host_of_vertex, v);
    if (h < 0 || !seen.insert(h).second) return;  // a twin of a vertex listed already
    out.vertex.push_back(h);
    out.distance.push_back(d);
  });
  out.stop = front.run();
  front.set_settled_callback({});
  return out;
}

std::optional<double> distance_between(MinimalDistanceFront& front, VertexHandle from, VertexHandle to,
                                       double max_distance, std::span<const int> host_of_vertex) {
  DistanceOptions o;
  o.max_distance = max_distance;
  o.directions = false;
  o.target = to;
  front.reset(FrontSource::vertex(from), o);
  const int target = host_index(host_of_vertex, to);
  std::optional<double> found;
  front.set_settled_callback([&](VertexHandle v, double d, const Vec3&) {
    if (!found && (v == to || (target >= 0 && host_index(host_of_vertex, v) == target))) found = d;
  });
  front.run();
  front.set_settled_callback({});
  if (found && *found <= max_distance) return found;
  return std::nullopt;
}

// -------------------------------------------------------------------------------------------
// GeodesicSolver

struct GeodesicSolver::Impl {
  ArrayMesh a;
  size_t n_in = 0;  // input vertices
  mutable std::once_flag table_once;
  mutable std::unique_ptr<GeodesicRingTable> table;
  std::unique_ptr<MinimalDistanceFront> front;
  std::unique_ptr<ConnectionPathFinder> finder;

  explicit Impl(ArrayMesh converted) : a(std::move(converted)), n_in(a.report.input_vertices) {
    if (a.vertex_row.size() != a.mesh.n_vertices() || a.face_row.size() != a.mesh.n_faces() || n_in > a.mesh.n_vertices()) {
      throw InvalidInput("GeodesicSolver: the converted mesh's index maps do not match its mesh (use mesh_from_arrays)");
    }
  }

  VertexHandle vertex(int v, const char* what) const {
    if (v < 0 || static_cast<size_t>(v) >= n_in) {
      throw InvalidInput(std::string(what) + ": vertex " + std::to_string(v) + " is outside [0, " + std::to_string(n_in) + ")");
    }
    return VertexHandle(v);
  }
  std::vector<VertexHandle> vertices(std::span<const int> vs, const char* what) const {
    if (vs.empty()) throw InvalidInput(std::string(what) + ": no source vertex given");
    std::vector<VertexHandle> out;
    out.reserve(vs.size());
    for (int v : vs) out.push_back(vertex(v, what));
    return out;
  }
  DistanceOptions options(const ArrayDistanceOptions& o) const {
    DistanceOptions d;
    d.method = o.method;
    d.max_distance = o.max_distance;
    d.directions = o.directions;
    if (o.target >= 0) d.target = vertex(o.target, "distance target");
    if (o.target < -1) throw InvalidInput("distance: target vertex " + std::to_string(o.target) + " is negative (-1: none)");
    return d;
  }
  const GeodesicRingTable& ring_table() const {
    std::call_once(table_once, [&] { table = std::make_unique<GeodesicRingTable>(a.mesh); });
    return *table;
  }
  /// Per input vertex: the copy reached first (smallest distance) stands for a pinched vertex.
  DistanceArrays reduce(const DistanceField& f, bool directions) const {
    DistanceArrays out;
    out.stop = f.stop;
    out.distance.assign(n_in, kInf);
    if (directions) out.direction.assign(3 * n_in, 0.0);
    for (size_t i = 0; i < f.distance.size(); ++i) {
      const size_t r = static_cast<size_t>(a.vertex_row[i]);
      if (r >= n_in || !(f.distance[i] < out.distance[r])) continue;
      out.distance[r] = f.distance[i];
      if (directions && i < f.direction.size()) {
        for (int k = 0; k < 3; ++k) out.direction[3 * r + static_cast<size_t>(k)] = f.direction[i][k];
      }
    }
    return out;
  }
  /// Mesh vertices for a chain of input vertices joined by edges, choosing among the copies of a
  /// pinched vertex the one that shares an edge with its neighbours in the chain.
  std::vector<VertexHandle> chain(std::span<const int> vs, bool closed, const char* what) const {
    std::vector<std::vector<VertexHandle>> options;
    for (int v : vs) {
      std::vector<VertexHandle> o{vertex(v, what)};
      for (VertexHandle t : twins_of(a.mesh, VertexHandle(v))) o.push_back(t);
      options.push_back(std::move(o));
    }
    std::vector<VertexHandle> out;
    for (VertexHandle first : options.empty() ? std::vector<VertexHandle>{} : options[0]) {
      out.assign(1, first);
      for (size_t i = 1; i < options.size(); ++i) {
        VertexHandle pick = options[i][0];
        for (VertexHandle c : options[i]) {
          if (a.mesh.find_halfedge(out.back(), c).is_valid() || a.mesh.find_halfedge(c, out.back()).is_valid()) {
            pick = c;
            break;
          }
        }
        out.push_back(pick);
      }
      const bool closes = !closed || out.size() < 2 || a.mesh.find_halfedge(out.back(), first).is_valid() ||
                          a.mesh.find_halfedge(first, out.back()).is_valid();
      if (closes) break;
    }
    return out;
  }
  PathArrays path_arrays(const std::vector<VertexHandle>& vs, const std::vector<PathPoint>& poly) const {
    PathArrays out;
    for (VertexHandle v : vs) out.vertices.push_back(a.vertex_row[static_cast<size_t>(v.idx())]);
    for (const PathPoint& p : poly) {
      out.points.insert(out.points.end(), {p.position[0], p.position[1], p.position[2]});
      if (p.vertex.is_valid()) {
        const int r = a.vertex_row[static_cast<size_t>(p.vertex.idx())];
        out.edge.insert(out.edge.end(), {r, r});
        out.t.push_back(0.0);
      } else {
        out.edge.push_back(a.vertex_row[static_cast<size_t>(a.mesh.from_vertex_handle(p.halfedge).idx())]);
        out.edge.push_back(a.vertex_row[static_cast<size_t>(a.mesh.to_vertex_handle(p.halfedge).idx())]);
        out.t.push_back(p.t);
      }
      // The mesh face's corners run in the row's order (as `distance_from_points` reads them).
      const bool on_face = p.location.face.is_valid();
      out.face.push_back(on_face ? a.face_row[static_cast<size_t>(p.location.face.idx())] : -1);
      for (const double b : p.location.bary) out.barycentric.push_back(on_face ? b : 0.0);
    }
    return out;
  }
};

GeodesicSolver::GeodesicSolver(const VertexArrayView& vertices, const FaceArrayView& faces, const ConversionOptions& options)
    : impl_(std::make_unique<Impl>(mesh_from_arrays(vertices, faces, options))) {}
GeodesicSolver::GeodesicSolver(ArrayMesh converted) : impl_(std::make_unique<Impl>(std::move(converted))) {}
GeodesicSolver::~GeodesicSolver() = default;
GeodesicSolver::GeodesicSolver(GeodesicSolver&&) noexcept = default;
GeodesicSolver& GeodesicSolver::operator=(GeodesicSolver&&) noexcept = default;

const ArrayMesh& GeodesicSolver::converted() const { return impl_->a; }
size_t GeodesicSolver::n_vertices() const { return impl_->n_in; }
size_t GeodesicSolver::n_faces() const { return impl_->a.face_of_row.size(); }

DistanceArrays GeodesicSolver::distance_from_vertices(std::span<const int> sources, const ArrayDistanceOptions& options) const {
  const Impl& s = *impl_;
  const DistanceOptions o = s.options(options);
  const FrontSource src = FrontSource::from_vertices(s.vertices(sources, "distance"));
  if (o.method == DistanceMethod::Fast) return s.reduce(geodesic_distance(s.a.mesh, s.ring_table(), src, o), o.directions);
  return s.reduce(geodesic_distance(s.a.mesh, src, o), o.directions);
}

DistanceArrays GeodesicSolver::distance_from_points(std::span<const int> faces, std::span<const double> barycentric,
                                                    const ArrayDistanceOptions& options) const {
  const Impl& s = *impl_;
  const DistanceOptions o = s.options(options);
  if (barycentric.size() != 3 * faces.size()) {
    throw InvalidInput("distance: " + std::to_string(faces.size()) + " source faces need " + std::to_string(3 * faces.size()) +
                       " barycentric coordinates (k x 3), got " + std::to_string(barycentric.size()));
  }
  std::vector<SurfacePoint> points;
  points.reserve(faces.size());
  for (size_t i = 0; i < faces.size(); ++i) {
    const int row = faces[i];
    if (row < 0 || static_cast<size_t>(row) >= s.a.face_of_row.size()) {
      throw InvalidInput("distance: source point " + std::to_string(i) + ": face row " + std::to_string(row) +
                         " is outside [0, " + std::to_string(s.a.face_of_row.size()) + ")");
    }
    const int f = s.a.face_of_row[static_cast<size_t>(row)];
    if (f < 0) {
      throw InvalidInput("distance: source point " + std::to_string(i) + ": face row " + std::to_string(row) +
                         " was dropped by the conversion (it does not fit a half-edge mesh)");
    }
    // The mesh face's corners run in the row's order (the builder adds a b c).
    points.push_back(SurfacePoint{FaceHandle(f), {barycentric[3 * i], barycentric[3 * i + 1], barycentric[3 * i + 2]}});
  }
  if (o.method == DistanceMethod::Fast) return s.reduce(geodesic_distance(s.a.mesh, s.ring_table(), points, o), o.directions);
  return s.reduce(geodesic_distance(s.a.mesh, points, o), o.directions);
}

DistanceArrays GeodesicSolver::distance_from_loop(std::span<const int> loop, LoopSide side,
                                                  const ArrayDistanceOptions& options) const {
  const Impl& s = *impl_;
  const DistanceOptions o = s.options(options);
  if (loop.empty()) throw InvalidInput("distance: the loop has no vertices");
  const FrontSource src = loop_from_vertices(s.a.mesh, s.chain(loop, true, "loop source"), side);
  return s.reduce(geodesic_distance(s.a.mesh, src, o), o.directions);
}

SparseDistances GeodesicSolver::distances_within(std::span<const int> sources, double max_distance, DistanceMethod method) {
  Impl& s = *impl_;
  if (!s.front) s.front = std::make_unique<MinimalDistanceFront>(s.a.mesh);
  return edgefront::distances_within(*s.front, s.vertices(sources, "distances_within"), max_distance, method, s.a.vertex_row);
}

std::optional<double> GeodesicSolver::distance_between(int from, int to, double max_distance) {
  Impl& s = *impl_;
  if (!s.front) s.front = std::make_unique<MinimalDistanceFront>(s.a.mesh);
  return edgefront::distance_between(*s.front, s.vertex(from, "distance_between"), s.vertex(to, "distance_between"),
                                     max_distance, s.a.vertex_row);
}

std::vector<int> GeodesicSolver::levels(std::span<const int> sources, int max_levels) const {
  const Impl& s = *impl_;
  const std::vector<int> lv = edge_front_levels(s.a.mesh, FrontSource::from_vertices(s.vertices(sources, "levels")), max_levels);
  std::vector<int> out(s.n_in, -1);
  for (size_t i = 0; i < lv.size(); ++i) {
    const size_t r = static_cast<size_t>(s.a.vertex_row[i]);
    if (lv[i] >= 0 && r < s.n_in && (out[r] < 0 || lv[i] < out[r])) out[r] = lv[i];
  }
  return out;
}

PathArrays GeodesicSolver::connection_path(int from, int to, const ConnectionPathOptions& options) {
  Impl& s = *impl_;
  if (!s.finder) s.finder = std::make_unique<ConnectionPathFinder>(s.a.mesh);
  const ConnectionPath p = s.finder->find(s.vertex(from, "connection_path"), s.vertex(to, "connection_path"), options);
  PathArrays out = s.path_arrays(p.vertices, p.polyline);
  out.status = p.status;
  out.length = p.length;
  return out;
}

PathArrays GeodesicSolver::polyline(std::span<const int> chain, int max_flips) const {
  const Impl& s = *impl_;
  if (chain.empty()) throw InvalidInput("polyline: the chain has no vertices");
  const std::vector<VertexHandle> vs = s.chain(chain, false, "polyline");
  const std::vector<PathPoint> poly = geodesic_polyline(s.a.mesh, vs, max_flips);
  PathArrays out = s.path_arrays(vs, poly);
  out.status = PathStatus::Found;
  out.length = polyline_length(poly);
  return out;
}

DistanceArrays geodesic_distance(const VertexArrayView& vertices, const FaceArrayView& faces, std::span<const int> sources,
                                 const ArrayDistanceOptions& options) {
  return GeodesicSolver(vertices, faces).distance_from_vertices(sources, options);
}

}  // namespace edgefront
