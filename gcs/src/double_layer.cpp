#include "detail/double_layer.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>
#include <queue>
#include <tuple>
#include <vector>

#include <Eigen/Dense>

#include "edgefront/error.h"
#include "edgefront/mesh_stats.h"
#include "edgefront/union_find.h"

namespace gcs::detail {

using edgefront::FaceHandle;
using edgefront::Mesh;
using edgefront::Vec3;
using edgefront::VertexHandle;

Vec3 vertex_normal_sum(const Mesh& mesh, VertexHandle v) {
  Vec3 n(0, 0, 0);
  const Vec3& x = mesh.point(v);
  for (auto h : mesh.voh_range(v)) {
    if (!mesh.face_handle(h).is_valid()) continue;
    const Vec3& a = mesh.point(mesh.to_vertex_handle(h));
    const Vec3& b = mesh.point(mesh.to_vertex_handle(mesh.next_halfedge_handle(h)));
    n += (a - x) % (b - x);
  }
  return n;
}

int oriented_nearest(const Mesh& mesh, VertexGrid& grid, const Vec3& sample, const Vec3& normal,
                     int max_candidates, double max_extra_distance) {
  const int first = grid.nearest(sample);
  if (first < 0) return first;
  if ((vertex_normal_sum(mesh, VertexHandle(first)) | normal) > 0) return first;
  return oriented_nearest_after(mesh, grid, sample, normal, first, max_candidates, max_extra_distance);
}

int oriented_nearest_after(const Mesh& mesh, VertexGrid& grid, const Vec3& sample, const Vec3& normal, int first,
                           int max_candidates, double max_extra_distance) {
  const auto agrees = [&](int id) { return (vertex_normal_sum(mesh, VertexHandle(id)) | normal) > 0; };
  const double limit = (grid.position(first) - sample).norm() + max_extra_distance;
  // Take disagreeing candidates out of the grid until an agreeing one is nearest, then put them
  // back at their stored positions (the grid's answers do not depend on insertion order).
  std::vector<std::pair<int, Vec3>> taken;
  taken.reserve(static_cast<size_t>(max_candidates));
  taken.emplace_back(first, grid.position(first));
  grid.remove(first);
  int found = -1;
  while (static_cast<int>(taken.size()) < max_candidates) {
    const int id = grid.nearest(sample);
    if (id < 0 || (grid.position(id) - sample).norm() > limit) break;
    if (agrees(id)) {
      found = id;
      break;
    }
    taken.emplace_back(id, grid.position(id));
    grid.remove(id);
  }
  for (const auto& [id, p] : taken) grid.insert(id, p);
  return found >= 0 ? found : first;
}

std::size_t remove_opposed_faces(Mesh& mesh, const FaceNearest& nearest, const OpposedParams& params) {
  EF_CHECK(nearest.size() >= mesh.n_faces(), "remove_opposed_faces: a nearest sample per face is needed");
  std::vector<FaceHandle> doomed;
  size_t live_faces = 0;
  for (auto f : mesh.faces()) {
    ++live_faces;
    auto it = mesh.cfv_iter(f);
    const Vec3 a = mesh.point(*it), b = mesh.point(*++it), c = mesh.point(*++it);
    const CloudHit& hit = nearest[static_cast<size_t>(f.idx())];
    if (!(hit.distance <= params.max_distance) || !std::isfinite(hit.normal[0])) continue;
    const Vec3 n = (b - a) % (c - a);
    const double ln = n.norm(), lh = hit.normal.norm();
    if (ln > 0 && lh > 0 && (n | hit.normal) < -params.min_cos * ln * lh) doomed.push_back(f);
  }
  if (doomed.empty() || doomed.size() * 10 >= live_faces * 9) return 0;  // never wipe out the mesh
  std::vector<VertexHandle> touched;
  for (auto f : doomed)
    for (auto v : mesh.fv_range(f)) touched.push_back(v);
  for (auto f : doomed) mesh.delete_face(f, true);
  size_t removed = doomed.size() + clean_topology(mesh, params.min_component_faces, params.min_component_fraction,
                                                  {&nearest, params.sample_part});
  // Pieces of the kept layer that hung on the removed one only: components that lost faces here
  // and have less than split_fraction of the largest component's faces go too (the loop regrows
  // the sheet over their samples; left alone they stay apart, since loop merging joins only loops
  // of similar length).
  const edgefront::ComponentLabels labels = edgefront::connected_components(mesh);
  if (labels.count > 1 && params.split_fraction > 0) {
    std::vector<size_t> faces(labels.count, 0);
    for (auto f : mesh.faces()) ++faces[static_cast<size_t>(labels.vertex_component[mesh.fv_begin(f)->idx()])];
    const double largest = static_cast<double>(*std::max_element(faces.begin(), faces.end()));
    std::vector<char> split(labels.count, 0);
    bool any = false;
    for (auto v : touched) {
      if (mesh.status(v).deleted()) continue;
      const int c = labels.vertex_component[static_cast<size_t>(v.idx())];
      if (c >= 0 && static_cast<double>(faces[static_cast<size_t>(c)]) < params.split_fraction * largest) {
        split[static_cast<size_t>(c)] = 1;
        any = true;
      }
    }
    if (any && params.sample_part) {
      const std::vector<char> separate = separate_surfaces(mesh, labels, faces, {&nearest, params.sample_part});
      for (size_t c = 0; c < labels.count; ++c) split[c] = split[c] && !separate[c];
    }
    for (auto f : mesh.faces()) {
      if (!split[static_cast<size_t>(labels.vertex_component[mesh.fv_begin(f)->idx()])]) continue;
      mesh.delete_face(f, true);
      ++removed;
    }
  }
  return removed;
}

std::vector<int> cloud_parts(const std::vector<Vec3>& points, const edgefront::PointIndex& index, std::size_t k) {
  EF_CHECK(index.size() == points.size(), "cloud_parts: sizes differ");
  const std::size_t n = points.size();
  edgefront::UnionFind parts_of(n);
  std::vector<edgefront::PointIndex::Neighbor> knn;
  for (std::size_t i = 0; i < n; ++i) {
    index.k_nearest(points[i], k + 1, knn);
    for (const auto& nb : knn) {
      parts_of.unite(i, nb.index);
    }
  }
  // Roots are the smallest index of their set, so labels go in the order of first points.
  std::vector<int> label(n, -1);
  int parts = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t r = parts_of.find(i);
    label[i] = r == i ? parts++ : label[r];
  }
  return label;
}

double normal_flux(const std::vector<Vec3>& points, const std::vector<Vec3>& normals) {
  EF_CHECK(normals.size() == points.size(), "normal_flux: sizes differ");
  if (points.empty()) return 0;
  Vec3 c(0, 0, 0);
  for (const Vec3& p : points) c += p;
  c /= static_cast<double>(points.size());
  double flux = 0, extent = 0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vec3 d = points[i] - c;
    extent = std::max(extent, d.norm());
    const double ln = normals[i].norm();
    if (!std::isfinite(ln) || !(ln > 0)) continue;
    flux += (normals[i] | d) / ln;
    ++count;
  }
  return count && extent > 0 ? flux / (extent * static_cast<double>(count)) : 0.0;
}

bool orient_normals(const std::vector<Vec3>& points, const edgefront::PointIndex& index, std::vector<Vec3>& normals,
                    std::size_t k, const std::vector<double>* noise, bool refined) {
  const std::size_t n = points.size();
  EF_CHECK(normals.size() == n && index.size() == n, "orient_normals: sizes differ");
  EF_CHECK(!noise || noise->size() == n, "orient_normals: noise and points differ in size");
  const auto noise2 = [&](std::size_t i) {
    const double s = noise ? (*noise)[i] : 0.0;
    return std::isfinite(s) ? s * s : 0.0;
  };
  const auto usable = [&](std::size_t i) { return std::isfinite(normals[i][0]) && normals[i].sqrnorm() > 0; };
  // The k-nearest-neighbour graph made symmetric (CSR): a point that is among another's k nearest
  // is linked both ways, so one far from everybody's list is still reached.
  std::vector<edgefront::PointIndex::Neighbor> knn;
  std::vector<std::vector<std::size_t>> adj(n);
  std::size_t total = 0;
  std::vector<double> reach2(n, 0);  // squared distance from a usable point to its k-th neighbour
  for (std::size_t i = 0; i < n; ++i) {
    if (!usable(i)) continue;
    ++total;
    index.k_nearest(points[i], k + 1, knn);
    reach2[i] = knn.empty() ? 0.0 : knn.back().distance2;
    for (const auto& nb : knn) {
      if (nb.index == i || !usable(nb.index)) continue;
      adj[i].push_back(nb.index);
      adj[nb.index].push_back(i);
    }
  }
  std::size_t seed = 0;
  while (seed < n && !usable(seed)) ++seed;
  if (seed == n) return false;
  // How well normal j, carried to point i, agrees with normal i: n_i . R n_j with R the reflection
  // in the plane that bisects the chord from p_i to p_j. On a surface that bends evenly between
  // the two points (an arc, a crease, the two walls of a thin shell) the reflection takes the one
  // consistently oriented normal into the other, so agree() is near +1 for a consistent pair and
  // near -1 for an inconsistent one, however far the normals turn; along a flat surface (chord in
  // the tangent plane) it is n_i . n_j (Hoppe's criterion). Noise: two points a little apart along
  // the normal are not two walls, so the reflection term is damped by the points' noise (the chord
  // counts as kNoiseChord noise deviations longer); coincident points: n_i . n_j.
  constexpr double kNoiseChord = 3;
  const auto agree = [&](std::size_t i, std::size_t j) {
    const Vec3 d = points[j] - points[i];
    const double l2 = d.sqrnorm() + kNoiseChord * kNoiseChord * (noise2(i) + noise2(j));
    const double c = normals[i] | normals[j];
    return refined && l2 > 0 ? c - 2 * (normals[i] | d) * (normals[j] | d) / l2 : c;
  };
  // Prim's spanning tree, cheapest edge = best agreement either way; each point takes the sign
  // that agrees with the point it was reached from. Ties by index.
  using Item = std::tuple<double, std::size_t, std::size_t>;  // (1 - |agree|, to, from)
  std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
  std::vector<char> done(n, 0);
  std::size_t reached = 0;
  queue.emplace(0.0, seed, seed);
  // Usable points that the graph leaves apart (islands that undefined normals cut off, a small
  // densely sampled detail whose k nearest are all its own) are linked to reached points among
  // their 4(k + 1) nearest, then 8(k + 1), then 16(k + 1), by links at most kLinkReach times as
  // long as the reached point's distance to its k-th neighbour: a part of the cloud that lies
  // farther apart (the inner sphere of nested spheres) stays apart.
  constexpr double kLinkReach = 4;
  for (std::size_t wide = 4 * (k + 1);; wide *= 2) {
    while (!queue.empty()) {
      const auto [cost, i, from] = queue.top();
      queue.pop();
      if (done[i]) continue;
      done[i] = 1;
      ++reached;
      if (agree(i, from) < 0) normals[i] = -normals[i];
      for (const std::size_t j : adj[i])
        if (!done[j]) queue.emplace(1.0 - std::abs(agree(i, j)), j, i);
    }
    if (!refined || reached == total || wide > 16 * (k + 1) || wide / 2 >= n) break;
    for (std::size_t i = 0; i < n; ++i) {
      if (done[i] || !usable(i)) continue;
      index.k_nearest(points[i], wide, knn);
      for (const auto& nb : knn)
        if (done[nb.index] && usable(nb.index) && nb.distance2 <= kLinkReach * kLinkReach * reach2[nb.index])
          queue.emplace(1.0 - std::abs(agree(i, nb.index)), i, nb.index);
    }
  }
  if (reached != total) return false;  // parts lying apart: no one orientation
  // Global sign: outward (sum of n.(p - c) > 0, which is 3 x the volume for a closed surface);
  // when that sum is small (an open, nearly flat sheet) the normals point along the positive side
  // of the cloud's thinnest principal axis (its largest coordinate positive).
  Vec3 c(0, 0, 0);
  for (const Vec3& p : points) c += p;
  c /= static_cast<double>(n);
  const double flux = normal_flux(points, normals);
  double sign = flux;
  if (!(std::abs(flux) > 0.05)) {
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3 d = points[i] - c;
      const Eigen::Vector3d q(d[0], d[1], d[2]);
      cov += q * q.transpose();
    }
    const Eigen::Vector3d e = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(cov).eigenvectors().col(0);
    int big = 0;
    for (int a = 1; a < 3; ++a)
      if (std::abs(e[a]) > std::abs(e[big])) big = a;
    const Vec3 axis = Vec3(e[0], e[1], e[2]) * (e[big] < 0 ? -1.0 : 1.0);
    sign = 0;
    for (std::size_t i = 0; i < n; ++i)
      if (usable(i)) sign += normals[i] | axis;
  }
  if (sign < 0)
    for (Vec3& m : normals)
      if (std::isfinite(m[0])) m = -m;
  return true;
}

}  // namespace gcs::detail
