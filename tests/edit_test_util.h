#pragma once
// Shared helpers of the edit-record tests: comparing a host's replayed plain arrays with a mesh,
// and turning a patch of a mesh over (a hand-made twist).

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <random>
#include <vector>

#include "edgefront/arrays.h"
#include "edgefront/mesh.h"
#include "edgefront/minimal_edge_front.h"
#include "twist/repair_session.h"

namespace edittest {

using namespace edgefront;

/// Border edges of plain faces (a b c per face; a removed face starts with -1): directed edges
/// whose opposite no face holds.
inline size_t border_edges(const std::vector<int>& F) {
  std::map<std::pair<int, int>, int> directed;
  for (size_t f = 0; 3 * f < F.size(); ++f) {
    if (F[3 * f] < 0) continue;
    for (size_t k = 0; k < 3; ++k) ++directed[{F[3 * f + k], F[3 * f + (k + 1) % 3]}];
  }
  size_t n = 0;
  for (const auto& e : directed) n += directed.count({e.first.second, e.first.first}) == 0;
  return n;
}

/// The mean length of a mesh's edges.
inline double mean_edge_length(const Mesh& mesh) {
  double sum = 0;
  size_t n = 0;
  for (EdgeHandle e : mesh.edges()) {
    sum += mesh.calc_edge_length(e);
    ++n;
  }
  return sum / static_cast<double>(n);
}

/// A face as a rotation starting at its smallest index (orientation kept).
inline std::array<int, 3> canonical(std::array<int, 3> t) {
  const auto it = std::min_element(t.begin(), t.end());
  std::rotate(t.begin(), it, t.end());
  return t;
}

/// Expects the host's arrays (empty slots -1) to hold exactly the live faces of `mesh` under the
/// vertex numbering `host_of` (mesh vertex -> host vertex), each face with its orientation, and
/// the host positions of those vertices to equal the mesh's.
inline void expect_same_mesh(const std::vector<double>& V, const std::vector<int>& F, const Mesh& mesh,
                             const std::vector<int>& host_of) {
  std::vector<std::array<int, 3>> host_faces, mesh_faces;
  for (size_t s = 0; 3 * s < F.size(); ++s) {
    if (F[3 * s] < 0) continue;
    host_faces.push_back(canonical({F[3 * s], F[3 * s + 1], F[3 * s + 2]}));
  }
  for (FaceHandle f : mesh.faces()) {
    std::array<int, 3> t{};
    size_t k = 0;
    for (VertexHandle v : mesh.fv_range(f)) {
      const int h = host_of[static_cast<size_t>(v.idx())];
      ASSERT_GE(h, 0) << "mesh vertex " << v.idx() << " has no host vertex";
      ASSERT_LT(static_cast<size_t>(h), V.size() / 3);
      for (int c = 0; c < 3; ++c) ASSERT_EQ(V[3 * static_cast<size_t>(h) + c], mesh.point(v)[c]) << "vertex " << h;
      t[k++] = h;
    }
    mesh_faces.push_back(canonical(t));
  }
  std::sort(host_faces.begin(), host_faces.end());
  std::sort(mesh_faces.begin(), mesh_faces.end());
  ASSERT_EQ(host_faces.size(), mesh_faces.size());
  EXPECT_EQ(host_faces, mesh_faces);
}

/// Expects a host's replayed arrays to match the session's mirror: the same live faces with their
/// orientation and positions (expect_same_mesh), and slot by slot: the host's face f is the mirror
/// face the session maps it to, an empty slot maps to none.
inline void expect_session_matches(const twist::RepairSession& s, const std::vector<double>& V,
                                   const std::vector<int>& F) {
  ASSERT_EQ(s.vertex_slots(), V.size() / 3);
  ASSERT_EQ(s.face_slots(), F.size() / 3);
  std::vector<int> host_of(s.mirror().n_vertices(), -1);
  for (size_t i = 0; i < host_of.size(); ++i) host_of[i] = s.host_vertex(VertexHandle(static_cast<int>(i)));
  expect_same_mesh(V, F, s.mirror(), host_of);
  for (size_t f = 0; 3 * f < F.size(); ++f) {
    const FaceHandle m = s.mirror_face(static_cast<int>(f));
    if (F[3 * f] < 0) {
      EXPECT_FALSE(m.is_valid()) << "empty slot " << f;
      continue;
    }
    ASSERT_TRUE(m.is_valid() && is_live(s.mirror(), m)) << "slot " << f;
    std::array<int, 3> t{};
    size_t k = 0;
    for (VertexHandle v : s.mirror().fv_range(m)) t[k++] = s.host_vertex(v);
    EXPECT_EQ(canonical(t), canonical({F[3 * f], F[3 * f + 1], F[3 * f + 2]})) << "slot " << f;
  }
}

/// The host numbering of a mirror after a one-shot record: input vertices keep their index, the
/// mirror's live vertices from `first_new` on follow in index order.
inline std::vector<int> appended_numbering(const Mesh& mesh, size_t first_new) {
  std::vector<int> host_of(mesh.n_vertices(), -1);
  int next = static_cast<int>(first_new);
  for (size_t i = 0; i < mesh.n_vertices(); ++i) {
    if (i < first_new) {
      host_of[i] = static_cast<int>(i);
    } else if (!mesh.status(VertexHandle(static_cast<int>(i))).deleted()) {
      host_of[i] = next++;
    }
  }
  return host_of;
}

/// Turns a patch over like a coin: the vertices within `rings - 1` edge rings of `centre` are
/// rotated by pi about the axis through their centroid along a tangent direction; the ring at
/// `rings` stays, so the faces in between fold. Returns the moved vertices.
inline std::vector<VertexHandle> flip_patch(Mesh& mesh, VertexHandle centre, int rings, std::mt19937& rng) {
  const std::vector<int> level = edge_front_levels(mesh, FrontSource::vertex(centre), rings);
  std::vector<VertexHandle> inner;
  Vec3 c(0, 0, 0);
  for (size_t i = 0; i < level.size(); ++i) {
    if (level[i] < 0 || level[i] >= rings) continue;
    inner.push_back(VertexHandle(static_cast<int>(i)));
    c += mesh.point(inner.back());
  }
  c /= static_cast<double>(inner.size());
  const Vec3 n = mesh.calc_vertex_normal(centre).normalized();
  const Vec3 any = std::abs(n[0]) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
  const Vec3 u = OpenMesh::cross(n, any).normalized(), w = OpenMesh::cross(n, u);
  const double a = std::uniform_real_distribution<double>(0, 2 * 3.14159265358979)(rng);
  const Vec3 axis = std::cos(a) * u + std::sin(a) * w;
  for (VertexHandle v : inner) {
    const Vec3 d = mesh.point(v) - c;
    const Vec3 along = OpenMesh::dot(d, axis) * axis;
    mesh.set_point(v, c + along - (d - along));  // rotation by pi about the axis
  }
  mesh.update_face_normals();
  return inner;
}

}  // namespace edittest
