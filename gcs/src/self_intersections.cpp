// Self-intersecting face pairs (gcs::count_self_intersections) and the mesh's validity
// (gcs::mesh_validity; also part of gcs::evaluate). Shared parts: detail/evaluation_common.h.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

#include "detail/evaluation_common.h"
#include "detail/self_intersection.h"
#include "edgefront/error.h"
#include "edgefront/mesh_stats.h"
#include "edgefront/parallel.h"
#include "gcs/evaluation.h"

namespace gcs {

using detail::eval::check_mesh_coordinates;
using detail::eval::kInf;
using detail::eval::mesh_triangles;
using detail::eval::Triangle;
using detail::eval::TriangleBvh;
using edgefront::Mesh;
using edgefront::Vec3;

namespace {

// ---------------------------------------------------------------------------------------------
// Self-intersections: the kernel's pair loop and test (TriangleBvh::intersecting_pairs,
// edgefront::triangles_intersect).

// Counts the intersecting pairs; with `pairs`, also lists them (triangle indices, first < second
// in leaf order), on `threads` threads (the same list for any count).
std::size_t count_self_intersections_of(const TriangleBvh& bvh, std::vector<std::pair<int, int>>* pairs = nullptr,
                                        unsigned threads = 1) {
  return bvh.intersecting_pairs(pairs, threads);
}

double angle_deg(const Vec3& a, const Vec3& b) {
  return std::atan2((a % b).norm(), a | b) * (180.0 / 3.14159265358979323846);
}

}  // namespace

std::size_t count_self_intersections(const Mesh& mesh) {
  check_mesh_coordinates(mesh, "the mesh");
  std::vector<Triangle> tris = mesh_triangles(mesh);
  if (tris.empty()) return 0;
  return count_self_intersections_of(TriangleBvh(std::move(tris)));
}

namespace detail {

std::vector<std::pair<int, int>> self_intersecting_face_pairs(const Mesh& mesh) {
  check_mesh_coordinates(mesh, "the mesh");
  std::vector<int> face_of;
  std::vector<Triangle> tris = mesh_triangles(mesh, &face_of);
  std::vector<std::pair<int, int>> pairs;
  if (tris.empty()) return pairs;
  count_self_intersections_of(TriangleBvh(std::move(tris)), &pairs);
  for (auto& [a, b] : pairs) {
    a = face_of[static_cast<std::size_t>(a)];
    b = face_of[static_cast<std::size_t>(b)];
    if (a > b) std::swap(a, b);
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

}  // namespace detail

namespace detail::eval {

// Validity of `mesh`; `bvh` (over the mesh's live faces) is reused when given.
MeshValidity validity_of(const Mesh& mesh, bool count_self, const TriangleBvh* bvh, unsigned threads) {
  const edgefront::MeshStats st = edgefront::compute_stats(mesh);
  MeshValidity m;
  m.vertices = st.vertices;
  m.edges = st.edges;
  m.faces = st.faces;
  m.nonmanifold_edges = 0;
  m.edge_manifold = true;
  m.nonmanifold_vertices = st.nonmanifold_vertices;
  m.vertex_manifold = st.nonmanifold_vertices == 0;
  m.components = st.components;
  m.border_loops = st.border_loops;
  m.closed = st.border_loops == 0;
  m.euler_characteristic = st.euler_characteristic;
  for (const auto& c : st.per_component) {
    m.component_genus.push_back(c.genus);
    m.genus += c.genus;
  }
  m.isolated_vertices = st.isolated_vertices;
  m.degenerate_faces = st.degenerate_faces;
  m.duplicate_faces = st.duplicate_faces;
  m.valence_histogram = st.valence_histogram;

  std::vector<Triangle> own;
  if (!bvh) own = mesh_triangles(mesh);
  const std::vector<Triangle>& tris = bvh ? bvh->triangles() : own;
  std::vector<double> min_angles;
  min_angles.reserve(tris.size());
  std::size_t below10 = 0, below30 = 0;
  for (const Triangle& t : tris) {
    m.area += 0.5 * ((t.p[1] - t.p[0]) % (t.p[2] - t.p[0])).norm();
    double a = kInf;
    for (int i = 0; i < 3; ++i) {
      const Vec3& p = t.p[static_cast<std::size_t>(i)];
      const Vec3 e1 = t.p[static_cast<std::size_t>((i + 1) % 3)] - p,
                 e2 = t.p[static_cast<std::size_t>((i + 2) % 3)] - p;
      // A zero-length side makes the face degenerate: its smallest angle is 0.
      a = std::min(a, e1.sqrnorm() > 0.0 && e2.sqrnorm() > 0.0 ? angle_deg(e1, e2) : 0.0);
    }
    min_angles.push_back(a);
    below10 += a < 10.0 ? 1 : 0;
    below30 += a < 30.0 ? 1 : 0;
  }
  if (!min_angles.empty()) {
    const double n = static_cast<double>(min_angles.size());
    m.faces_min_angle_below_10 = static_cast<double>(below10) / n;
    m.faces_min_angle_below_30 = static_cast<double>(below30) / n;
    m.min_angle_deg = *std::min_element(min_angles.begin(), min_angles.end());
    std::sort(min_angles.begin(), min_angles.end());
    const std::size_t k = min_angles.size();
    m.median_min_angle_deg = k % 2 ? min_angles[k / 2] : 0.5 * (min_angles[k / 2 - 1] + min_angles[k / 2]);
  }
  if (count_self) {
    if (bvh) {
      m.self_intersecting_pairs = count_self_intersections_of(*bvh, nullptr, threads);
    } else {
      m.self_intersecting_pairs = own.empty() ? 0 : count_self_intersections_of(TriangleBvh(std::move(own)), nullptr, threads);
    }
  }
  return m;
}

}  // namespace detail::eval

using detail::eval::validity_of;

MeshValidity mesh_validity(const Mesh& mesh, bool count_self) {
  check_mesh_coordinates(mesh, "the mesh");
  return validity_of(mesh, count_self, nullptr);
}

}  // namespace gcs
