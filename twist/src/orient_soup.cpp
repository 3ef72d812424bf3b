#include "twist/orient_soup.h"

#include <cmath>
#include <cstdint>
#include <deque>
#include <map>
#include <numeric>
#include <string>
#include <utility>

#include "edgefront/error.h"
#include "edgefront/union_find.h"

namespace twist {

using edgefront::InvalidInput;
using edgefront::Mesh;
using edgefront::Vec3;
using edgefront::VertexHandle;

namespace {

struct Incidence {
  size_t face = 0;
  int local = 0;  ///< edge (local, local+1) of the face
  int dir = 0;    ///< +1 when the face runs lo -> hi along this edge
};


}  // namespace

SoupOrientation orient_soup(const std::vector<Vec3>& points, const std::vector<std::array<int, 3>>& triangles) {
  if (triangles.empty()) throw InvalidInput("twist::orient_soup: the soup has no triangles");
  for (size_t i = 0; i < points.size(); ++i) {
    const Vec3& p = points[i];
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
      throw InvalidInput("twist::orient_soup: point " + std::to_string(i) + " is not finite");
    }
  }
  const int np = static_cast<int>(points.size());
  for (size_t f = 0; f < triangles.size(); ++f) {
    const auto& t = triangles[f];
    for (int k = 0; k < 3; ++k) {
      if (t[static_cast<size_t>(k)] < 0 || t[static_cast<size_t>(k)] >= np) {
        throw InvalidInput("twist::orient_soup: triangle " + std::to_string(f) + " has index " +
                           std::to_string(t[static_cast<size_t>(k)]) + " outside [0, " + std::to_string(np) + ")");
      }
    }
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
      throw InvalidInput("twist::orient_soup: triangle " + std::to_string(f) + " repeats a vertex index");
    }
  }

  const size_t nf = triangles.size();
  std::map<std::pair<int, int>, std::vector<Incidence>> edges;
  for (size_t f = 0; f < nf; ++f) {
    for (int k = 0; k < 3; ++k) {
      const int a = triangles[f][static_cast<size_t>(k)];
      const int b = triangles[f][static_cast<size_t>((k + 1) % 3)];
      edges[{std::min(a, b), std::max(a, b)}].push_back(Incidence{f, k, a < b ? 1 : -1});
    }
  }

  // Breadth-first propagation of orientations across manifold edges; conflicts are cut.
  SoupOrientation out;
  std::vector<int> orient(nf, 0);
  std::map<std::pair<int, int>, bool> cut;
  for (size_t start = 0; start < nf; ++start) {
    if (orient[start] != 0) continue;
    orient[start] = 1;
    std::deque<size_t> queue{start};
    while (!queue.empty()) {
      const size_t f = queue.front();
      queue.pop_front();
      for (int k = 0; k < 3; ++k) {
        const int a = triangles[f][static_cast<size_t>(k)];
        const int b = triangles[f][static_cast<size_t>((k + 1) % 3)];
        const auto key = std::make_pair(std::min(a, b), std::max(a, b));
        const auto& inc = edges[key];
        if (inc.size() != 2) continue;
        const Incidence& mine = inc[0].face == f && inc[0].local == k ? inc[0] : inc[1];
        const Incidence& other = &mine == &inc[0] ? inc[1] : inc[0];
        const int want = -mine.dir * orient[f] * other.dir;  // opposite traversal of the shared edge
        if (orient[other.face] == 0) {
          orient[other.face] = want;
          queue.push_back(other.face);
        } else if (orient[other.face] != want) {
          cut[key] = true;
        }
      }
    }
  }
  out.cut_edges = cut.size();
  out.non_orientable = !cut.empty();

  // Vertex copies: corners (face, k) joined across uncut manifold edges.
  edgefront::UnionFind corner_class(nf * 3);
  for (const auto& [key, inc] : edges) {
    if (inc.size() != 2 || cut.count(key)) continue;
    for (int end = 0; end < 2; ++end) {
      const int v = end == 0 ? key.first : key.second;
      size_t corners[2];
      for (int s = 0; s < 2; ++s) {
        const auto& t = triangles[inc[static_cast<size_t>(s)].face];
        const int k = inc[static_cast<size_t>(s)].local;
        const int c = t[static_cast<size_t>(k)] == v ? k : (k + 1) % 3;
        corners[s] = inc[static_cast<size_t>(s)].face * 3 + static_cast<size_t>(c);
      }
      corner_class.unite(corners[0], corners[1]);
    }
  }
  std::map<size_t, VertexHandle> vertex_of_class;
  std::vector<int> copies_of(points.size(), 0);
  for (size_t f = 0; f < nf; ++f) {
    for (int k = 0; k < 3; ++k) {
      const size_t root = corner_class.find(f * 3 + static_cast<size_t>(k));
      if (vertex_of_class.count(root)) continue;
      const int v = triangles[root / 3][root % 3];
      vertex_of_class[root] = out.mesh.add_vertex(points[static_cast<size_t>(v)]);
      if (copies_of[static_cast<size_t>(v)]++ > 0) ++out.vertices_duplicated;
    }
  }
  for (size_t f = 0; f < nf; ++f) {
    std::array<VertexHandle, 3> vh;
    for (int k = 0; k < 3; ++k) vh[static_cast<size_t>(k)] = vertex_of_class[corner_class.find(f * 3 + static_cast<size_t>(k))];
    if (orient[f] < 0) {
      std::swap(vh[1], vh[2]);
      ++out.faces_reversed;
    }
    if (!out.mesh.add_face(vh[0], vh[1], vh[2]).is_valid()) ++out.faces_dropped;
  }
  out.mesh.update_face_normals();
  return out;
}

}  // namespace twist
