// The mesh builder shared by the array conversion and the file readers (detail/mesh_builder.h).

#include "detail/mesh_builder.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <numeric>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "edgefront/error.h"
#include "edgefront/union_find.h"
#include "edgefront/vertex_twins.h"

namespace edgefront {

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
  // The ids of a bucket's entries are kept next to them (`bucket_id`, read in order) instead of
  // being read back from `edge_of`, whose entries lie all over the mesh (a cache miss each).
  std::vector<std::uint32_t> edge_of(3 * m);
  std::vector<std::uint32_t> bucket_id(3 * m);
  std::uint32_t edges = 0;
  for (size_t u = 0; u < n; ++u) {
    for (std::uint32_t i = start[u]; i < start[u + 1]; ++i) {
      std::uint32_t id = edges;
      for (std::uint32_t j = start[u]; j < i; ++j) {
        if (bucket[j].other == bucket[i].other) {
          id = bucket_id[j];
          break;
        }
      }
      if (id == edges) ++edges;
      bucket_id[i] = id;
      edge_of[bucket[i].h] = id;
    }
  }
  std::vector<std::uint32_t>().swap(bucket_id);
  std::vector<Entry>().swap(bucket);
  std::vector<std::uint32_t>().swap(start);

  // Rows in order: kept when each edge is free, or has one face running the other way. The two
  // faces of an edge join their corners at both ends (union-find over corners 3r + k).
  constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> first_he(edges, kNone);  // the edge's first kept halfedge
  std::vector<std::uint8_t> count(edges, 0);
  BasicUnionFind<std::uint32_t> corner_class(3 * m);
  std::vector<std::uint8_t> kept(m, 0);
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
      corner_class.unite(h, next_corner(g));
      corner_class.unite(next_corner(h), g);
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
  // Per corner: kNone when it belongs to its vertex's first fan (the common case), else the root
  // of its fan, to be mapped to the fan's copy below. The build reads it in order instead of
  // walking the union-find again (whose roots lie all over the mesh: a cache miss each).
  std::vector<std::uint32_t> corner_fan(3 * m, kNone);
  for (size_t r = 0; r < m; ++r) {
    if (!kept[r]) continue;
    for (size_t k = 0; k < 3; ++k) {
      const int v = tris[3 * r + k];
      const std::uint32_t root = static_cast<std::uint32_t>(corner_class.find(3 * r + k));
      std::uint32_t& first = first_class[static_cast<size_t>(v)];
      if (first == kNone) {
        first = root;
      } else if (first != root) {
        corner_fan[3 * r + k] = root;
        if (copy_of_class.emplace(root, -1).second) extras.push_back(Extra{v, r, root});
      }
    }
  }
  corner_class = BasicUnionFind<std::uint32_t>();  // free it
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
      const std::uint32_t fan = corner_fan[3 * r + k];
      v[k] = VertexHandle(fan == kNone ? tris[3 * r + k] : copy_of_class.at(fan));
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

}  // namespace edgefront
