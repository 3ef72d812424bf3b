// Plain arrays in and out: the views' checks, the mesh builder shared with the file readers, and
// the GeodesicSolver.

#include "edgefront/arrays.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <limits>
#include <mutex>
#include <numeric>
#include <string>
#include <unordered_map>
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

size_t find_root(std::vector<std::uint32_t>& parent, size_t x) {
  while (parent[x] != x) x = parent[x] = parent[parent[x]];
  return x;
}

}  // namespace

void VertexArrayView::check_shape(const char* what) const { check_view_shape(size_, cols_, what, "n"); }
void FaceArrayView::check_shape(const char* what) const { check_view_shape(size_, cols_, what, "m"); }

// -------------------------------------------------------------------------------------------
// The builder

namespace detail {

ArrayMesh build_mesh(const PointRows& points, std::span<const int> tris) {
  const size_t n = points.size();
  const size_t m = tris.size() / 3;
  ArrayMesh out;
  out.report.input_vertices = n;
  out.report.input_faces = m;

  // Undirected edges: halfedge 3r + k runs tris[3r + k] -> tris[3r + (k + 1) % 3]. Bucketed by the
  // smaller end (a counting sort, stable in row order); equal edges share an id.
  auto next_corner = [](size_t h) { return h % 3 == 2 ? h - 2 : h + 1; };
  auto from = [&](size_t h) { return tris[h]; };
  auto to = [&](size_t h) { return tris[next_corner(h)]; };
  std::vector<std::uint32_t> start(n + 1, 0);
  for (size_t r = 0; r < m; ++r) {
    const int a = tris[3 * r], b = tris[3 * r + 1], c = tris[3 * r + 2];
    ++start[static_cast<size_t>(std::min(a, b)) + 1];
    ++start[static_cast<size_t>(std::min(b, c)) + 1];
    ++start[static_cast<size_t>(std::min(c, a)) + 1];
  }
  std::partial_sum(start.begin(), start.end(), start.begin());
  struct Entry {
    int other;        // the larger end
    std::uint32_t h;  // the halfedge
  };
  std::vector<Entry> bucket(3 * m);
  {
    std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
    auto put = [&](int a, int b, size_t h) {
      bucket[fill[static_cast<size_t>(std::min(a, b))]++] = Entry{std::max(a, b), static_cast<std::uint32_t>(h)};
    };
    for (size_t r = 0; r < m; ++r) {
      const int a = tris[3 * r], b = tris[3 * r + 1], c = tris[3 * r + 2];
      put(a, b, 3 * r);
      put(b, c, 3 * r + 1);
      put(c, a, 3 * r + 2);
    }
  }
  std::vector<std::uint32_t> edge_of(3 * m);
  std::uint32_t edges = 0;
  for (size_t u = 0; u < n; ++u) {
    for (std::uint32_t i = start[u]; i < start[u + 1]; ++i) {
      std::uint32_t id = edges;
      for (std::uint32_t j = start[u]; j < i; ++j) {
        if (bucket[j].other == bucket[i].other) {
          id = edge_of[bucket[j].h];
          break;
        }
      }
      if (id == edges) ++edges;
      edge_of[bucket[i].h] = id;
    }
  }
  std::vector<Entry>().swap(bucket);
  std::vector<std::uint32_t>().swap(start);

  // Rows in order: kept when each edge is free, or has one face running the other way. The two
  // faces of an edge join their corners at both ends (union-find over corners 3r + k).
  constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> first_he(edges, kNone);  // the edge's first kept halfedge
  std::vector<std::uint8_t> count(edges, 0);
  std::vector<std::uint32_t> parent(3 * m);
  std::iota(parent.begin(), parent.end(), 0u);
  std::vector<std::uint8_t> kept(m, 0);
  auto unite = [&](size_t a, size_t b) {
    a = find_root(parent, a);
    b = find_root(parent, b);
    if (a != b) parent[std::max(a, b)] = static_cast<std::uint32_t>(std::min(a, b));
  };
  for (size_t r = 0; r < m; ++r) {
    bool ok = true;
    for (size_t k = 0; k < 3 && ok; ++k) {
      const size_t h = 3 * r + k;
      const std::uint32_t e = edge_of[h];
      if (count[e] == 0) continue;
      DroppedFace d;
      d.row = r;
      d.edge = {from(h), to(h)};
      if (count[e] >= 2) {
        d.reason = FaceDropReason::EdgeHasTwoFaces;
      } else if (from(first_he[e]) == from(h)) {
        d.reason = FaceDropReason::EdgeSameDirection;
      } else {
        continue;
      }
      out.report.dropped_faces.push_back(d);
      ok = false;
    }
    if (!ok) continue;
    kept[r] = 1;
    for (size_t k = 0; k < 3; ++k) {
      const size_t h = 3 * r + k;
      const std::uint32_t e = edge_of[h];
      if (count[e]++ == 0) {
        first_he[e] = static_cast<std::uint32_t>(h);
        continue;
      }
      // h runs a -> b, g runs b -> a: at a, corner k of r and the corner after g's; at b, the reverse.
      const size_t g = first_he[e];
      unite(h, next_corner(g));
      unite(next_corner(h), g);
    }
  }
  std::vector<std::uint32_t>().swap(first_he);
  size_t mesh_edges = 0;  // edges of the kept faces
  for (std::uint8_t c : count) mesh_edges += c > 0 ? 1 : 0;
  std::vector<std::uint8_t>().swap(count);

  // Fans: the corners of a vertex in one class. The class of the lowest row keeps the vertex;
  // every other class gets a copy, numbered by (original, lowest row of the class).
  std::vector<std::uint32_t> first_class(n, kNone);
  struct Extra {
    int vertex;
    size_t row;
    std::uint32_t root;
  };
  std::vector<Extra> extras;
  std::unordered_map<std::uint32_t, int> copy_of_class;
  for (size_t r = 0; r < m; ++r) {
    if (!kept[r]) continue;
    for (size_t k = 0; k < 3; ++k) {
      const int v = tris[3 * r + k];
      const std::uint32_t root = static_cast<std::uint32_t>(find_root(parent, 3 * r + k));
      std::uint32_t& first = first_class[static_cast<size_t>(v)];
      if (first == kNone) {
        first = root;
      } else if (first != root && copy_of_class.emplace(root, -1).second) {
        extras.push_back(Extra{v, r, root});
      }
    }
  }
  std::sort(extras.begin(), extras.end(),
            [](const Extra& a, const Extra& b) { return a.vertex != b.vertex ? a.vertex < b.vertex : a.row < b.row; });
  for (size_t i = 0; i < extras.size(); ++i) copy_of_class[extras[i].root] = static_cast<int>(n + i);

  // The mesh, as OpenMesh's add_face(a, b, c) builds it row by row (the same edge, halfedge and
  // face numbering, next links and outgoing halfedges: tests/arrays_test.cpp compares them), but
  // with the edges known in advance (no halfedge search) and the kernel sized once.
  const size_t nvm = n + extras.size();
  const size_t kept_faces = m - out.report.dropped_faces.size();
  out.vertex_row.resize(nvm);
  for (size_t i = 0; i < n; ++i) out.vertex_row[i] = static_cast<int>(i);
  for (size_t i = 0; i < extras.size(); ++i) out.vertex_row[n + i] = extras[i].vertex;
  out.face_of_row.assign(m, -1);
  out.face_row.reserve(kept_faces);
  Mesh& mesh = out.mesh;
  mesh.resize(nvm, mesh_edges, kept_faces);
  Vec3* const point = nvm ? &mesh.point(VertexHandle(0)) : nullptr;  // the kernel's arrays, written in order
  Vec3* const normal = kept_faces ? &mesh.property(mesh.face_normals_pph(), FaceHandle(0)) : nullptr;
  for (size_t i = 0; i < nvm; ++i) point[i] = points.at(static_cast<size_t>(out.vertex_row[i]));
  std::vector<int> mesh_edge(edges, -1);  // by undirected input edge
  int next_edge = 0, next_face = 0;
  auto boundary = [&](HalfedgeHandle h) { return !mesh.face_handle(h).is_valid(); };
  auto opposite = [](HalfedgeHandle h) { return HalfedgeHandle(h.idx() ^ 1); };
  // OpenMesh's adjust_outgoing_halfedge: the first boundary halfedge, rotating clockwise.
  auto adjust = [&](VertexHandle v) {
    const HalfedgeHandle first = mesh.halfedge_handle(v);
    HalfedgeHandle h = first;
    do {
      if (boundary(h)) {
        mesh.set_halfedge_handle(v, h);
        return;
      }
      h = mesh.next_halfedge_handle(opposite(h));
    } while (h != first && h.is_valid());
  };
  std::array<std::pair<HalfedgeHandle, HalfedgeHandle>, 18> next_cache;  // add_face's, for a triangle
  size_t cached = 0;
  auto cache = [&](HalfedgeHandle a, HalfedgeHandle b) { next_cache[cached++] = {a, b}; };
  for (size_t r = 0; r < m; ++r) {
    if (!kept[r]) continue;
    VertexHandle v[3];
    HalfedgeHandle hh[3];
    bool is_new[3], needs_adjust[3] = {false, false, false};
    for (size_t k = 0; k < 3; ++k) {
      const int input = tris[3 * r + k];
      const std::uint32_t root = static_cast<std::uint32_t>(find_root(parent, 3 * r + k));
      v[k] = VertexHandle(root == first_class[static_cast<size_t>(input)] ? input : copy_of_class.at(root));
    }
    for (size_t i = 0; i < 3; ++i) {
      const int e = mesh_edge[edge_of[3 * r + i]];
      is_new[i] = e < 0;
      if (is_new[i]) continue;
      hh[i] = HalfedgeHandle(mesh.to_vertex_handle(HalfedgeHandle(2 * e)) == v[(i + 1) % 3] ? 2 * e : 2 * e + 1);
      EF_CHECK(boundary(hh[i]), "mesh builder: an edge of row " + std::to_string(r) + " is taken");
    }
    cached = 0;
    // Re-link patches where two old halfedges meet that are not consecutive.
    for (size_t i = 0; i < 3; ++i) {
      const size_t ii = (i + 1) % 3;
      if (is_new[i] || is_new[ii]) continue;
      const HalfedgeHandle inner_prev = hh[i], inner_next = hh[ii];
      if (mesh.next_halfedge_handle(inner_prev) == inner_next) continue;
      HalfedgeHandle boundary_prev = opposite(inner_next);
      do {
        boundary_prev = opposite(mesh.next_halfedge_handle(boundary_prev));
      } while (!boundary(boundary_prev) || boundary_prev == inner_prev);
      const HalfedgeHandle boundary_next = mesh.next_halfedge_handle(boundary_prev);
      EF_CHECK(boundary_next != inner_next, "mesh builder: no gap to re-link a patch at row " + std::to_string(r));
      cache(boundary_prev, mesh.next_halfedge_handle(inner_prev));
      cache(mesh.prev_halfedge_handle(inner_next), boundary_next);
      cache(inner_prev, inner_next);
    }
    for (size_t i = 0; i < 3; ++i) {
      if (!is_new[i]) continue;
      const int e = next_edge++;
      mesh_edge[edge_of[3 * r + i]] = e;
      hh[i] = HalfedgeHandle(2 * e);
      mesh.set_vertex_handle(hh[i], v[(i + 1) % 3]);
      mesh.set_vertex_handle(opposite(hh[i]), v[i]);
    }
    const FaceHandle f(next_face++);
    mesh.set_halfedge_handle(f, hh[2]);
    for (size_t i = 0; i < 3; ++i) {
      const size_t ii = (i + 1) % 3;
      const VertexHandle vh = v[ii];
      const HalfedgeHandle inner_prev = hh[i], inner_next = hh[ii];
      const int id = (is_new[i] ? 1 : 0) | (is_new[ii] ? 2 : 0);
      if (id) {
        const HalfedgeHandle outer_prev = opposite(inner_next), outer_next = opposite(inner_prev);
        if (id == 1) {
          cache(mesh.prev_halfedge_handle(inner_next), outer_next);
          mesh.set_halfedge_handle(vh, outer_next);
        } else if (id == 2) {
          const HalfedgeHandle boundary_next = mesh.next_halfedge_handle(inner_prev);
          cache(outer_prev, boundary_next);
          mesh.set_halfedge_handle(vh, boundary_next);
        } else if (!mesh.halfedge_handle(vh).is_valid()) {
          mesh.set_halfedge_handle(vh, outer_next);
          cache(outer_prev, outer_next);
        } else {
          const HalfedgeHandle boundary_next = mesh.halfedge_handle(vh);
          cache(mesh.prev_halfedge_handle(boundary_next), outer_next);
          cache(outer_prev, boundary_next);
        }
        cache(inner_prev, inner_next);
      } else {
        needs_adjust[ii] = mesh.halfedge_handle(vh) == inner_next;
      }
      mesh.set_face_handle(hh[i], f);
    }
    for (size_t i = 0; i < cached; ++i) mesh.set_next_halfedge_handle(next_cache[i].first, next_cache[i].second);
    for (size_t i = 0; i < 3; ++i) {
      if (needs_adjust[i]) adjust(v[i]);
    }
    // OpenMesh's calc_face_normal of the points in circulation order (a, b, c), operation for operation.
    const Vec3& p0 = point[v[0].idx()];
    const Vec3& p1 = point[v[1].idx()];
    const Vec3& p2 = point[v[2].idx()];
    Vec3 nf = OpenMesh::cross(Vec3(p2 - p1), Vec3(p0 - p1));
    const double length = nf.norm();
    normal[f.idx()] = length != 0.0 ? (nf *= 1.0 / length) : Vec3(0, 0, 0);
    out.face_of_row[r] = f.idx();
    out.face_row.push_back(static_cast<int>(r));
  }
  EF_CHECK(static_cast<size_t>(next_edge) == mesh_edges, "mesh builder: edge count");

  // Twins: each pinched vertex with its copies.
  std::vector<VertexHandle> group;
  for (size_t i = 0; i < extras.size();) {
    const int v = extras[i].vertex;
    group.assign(1, VertexHandle(v));
    for (; i < extras.size() && extras[i].vertex == v; ++i) group.push_back(VertexHandle(static_cast<int>(n + i)));
    link_twins(mesh, group);
    ++out.report.pinched_vertices;
  }
  out.report.vertex_copies = extras.size();
  for (size_t i = 0; i < n; ++i) out.report.isolated_vertices += first_class[i] == kNone ? 1 : 0;
  return out;
}

}  // namespace detail

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
