#include "detail/surface_fit.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Sparse>

#include "detail/self_intersection.h"
#include "edgefront/error.h"
#include "edgefront/geometry.h"
#include "edgefront/point_index.h"

namespace gcs::detail {

using edgefront::FaceHandle;
using edgefront::Mesh;
using edgefront::PointIndex;
using edgefront::Vec3;
using edgefront::VertexHandle;

namespace {

// Closest mesh point to a sample: its face, the face's vertex ids and the point's barycentric
// coordinates in it.
struct Foot {
  int v[3] = {-1, -1, -1};
  double b[3] = {0, 0, 0};
  Vec3 point{0, 0, 0};
  Vec3 unit_normal{0, 0, 0};
  double distance = 0;
};

void barycentric(const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c, double out[3]) {
  const Vec3 e0 = b - a, e1 = c - a, e2 = q - a;
  const double d00 = e0 | e0, d01 = e0 | e1, d11 = e1 | e1, d20 = e2 | e0, d21 = e2 | e1;
  const double den = d00 * d11 - d01 * d01;
  if (!(std::abs(den) > 0)) {
    out[0] = out[1] = out[2] = 1.0 / 3.0;
    return;
  }
  const double v = std::clamp((d11 * d20 - d01 * d21) / den, 0.0, 1.0);
  const double w = std::clamp((d00 * d21 - d01 * d20) / den, 0.0, 1.0);
  const double u = std::max(0.0, 1.0 - v - w);
  const double s = u + v + w;
  out[0] = u / s;
  out[1] = v / s;
  out[2] = w / s;
}

// Closest points on the mesh, searched among the faces around the kFootVertices nearest live
// vertices (one is not enough: the closest face need not touch the nearest vertex).
constexpr std::size_t kFootVertices = 3;
class FootFinder {
 public:
  explicit FootFinder(const Mesh& mesh) : mesh_(mesh), index_(live_points(mesh, ids_)) {}

  bool find(const Vec3& p, Foot& out) {
    if (index_.empty()) return false;
    index_.k_nearest(p, kFootVertices, hits_);
    double best = -1;
    for (const PointIndex::Neighbor& h : hits_) {
      const VertexHandle v(ids_[h.index]);
      for (FaceHandle f : mesh_.vf_range(v)) {
        Vec3 x[3];
        int id[3];
        int k = 0;
        for (VertexHandle u : mesh_.fv_range(f)) {
          x[k] = mesh_.point(u);
          id[k++] = u.idx();
        }
        const Vec3 q = edgefront::closest_point_on_triangle(p, x[0], x[1], x[2]);
        const double d2 = (q - p).sqrnorm();
        if (best >= 0 && d2 >= best) continue;
        const Vec3 n = (x[1] - x[0]) % (x[2] - x[0]);
        const double len = n.norm();
        if (!(len > 0)) continue;
        best = d2;
        out.point = q;
        out.unit_normal = n / len;
        out.distance = std::sqrt(d2);
        for (int j = 0; j < 3; ++j) out.v[j] = id[j];
        barycentric(q, x[0], x[1], x[2], out.b);
      }
    }
    return best >= 0;
  }

 private:
  static std::vector<Vec3> live_points(const Mesh& mesh, std::vector<int>& ids) {
    std::vector<Vec3> pts;
    for (VertexHandle v : mesh.vertices()) {
      if (mesh.is_isolated(v)) continue;
      pts.push_back(mesh.point(v));
      ids.push_back(v.idx());
    }
    return pts;
  }
  const Mesh& mesh_;
  std::vector<int> ids_;
  PointIndex index_;
  std::vector<PointIndex::Neighbor> hits_;
};

std::vector<Vec3> unit_vertex_normals(const Mesh& mesh) {
  std::vector<Vec3> n(mesh.n_vertices(), Vec3(0, 0, 0));
  for (FaceHandle f : mesh.faces()) {
    Vec3 x[3];
    int k = 0;
    for (VertexHandle u : mesh.fv_range(f)) x[k++] = mesh.point(u);
    const Vec3 c = (x[1] - x[0]) % (x[2] - x[0]);  // area weighted
    for (VertexHandle u : mesh.fv_range(f)) n[u.idx()] += c;
  }
  for (Vec3& v : n) {
    const double len = v.norm();
    v = len > 0 ? v / len : Vec3(0, 0, 0);
  }
  return n;
}

Vec3 unit_face_normal(const Mesh& mesh, FaceHandle f, const std::vector<Vec3>& pos) {
  Vec3 x[3];
  int k = 0;
  for (VertexHandle u : mesh.fv_range(f)) x[k++] = pos[u.idx()];
  const Vec3 c = (x[1] - x[0]) % (x[2] - x[0]);
  const double len = c.norm();
  return len > 0 ? c / len : Vec3(0, 0, 0);
}

void check_params(const SurfaceFitParams& p) {
  auto fail = [](const std::string& m) { throw edgefront::InvalidInput("gcs surface fit: " + m); };
  if (p.rounds < 1 || p.rounds > 20) fail("rounds must be in [1, 20] (got " + std::to_string(p.rounds) + ")");
  if (!(p.smoothness >= 0) || !std::isfinite(p.smoothness)) fail("smoothness must be finite and >= 0");
  if (!(p.max_move > 0) || !std::isfinite(p.max_move)) fail("max_move must be positive and finite");
  if (!(p.max_sample_distance > 0) || !std::isfinite(p.max_sample_distance))
    fail("max_sample_distance must be positive and finite");
  if (!(p.min_face_cos >= -1 && p.min_face_cos <= 1)) fail("min_face_cos must be in [-1, 1]");
}

}  // namespace

double mean_sample_distance(const Mesh& mesh, const std::vector<Vec3>& samples, double max_distance) {
  FootFinder finder(mesh);
  Foot foot;
  double sum = 0;
  std::size_t n = 0;
  for (const Vec3& p : samples) {
    if (!finder.find(p, foot) || !(foot.distance <= max_distance)) continue;
    sum += foot.distance;
    ++n;
  }
  return n ? sum / static_cast<double>(n) : 0.0;
}

SurfaceFitReport fit_to_samples(Mesh& mesh, const std::vector<Vec3>& samples, const std::vector<Vec3>& normals,
                                const SurfaceFitParams& params) {
  check_params(params);
  if (!normals.empty() && normals.size() != samples.size())
    throw edgefront::InvalidInput("gcs surface fit: " + std::to_string(normals.size()) + " normals for " +
                                  std::to_string(samples.size()) + " samples");
  SurfaceFitReport report;
  const std::size_t nv = mesh.n_vertices();
  if (samples.empty() || mesh.n_faces() == 0) return report;
  const std::size_t stride =
      params.max_samples > 0 && samples.size() > params.max_samples ? (samples.size() + params.max_samples - 1) / params.max_samples : 1;

  std::vector<Vec3> start(nv), pos(nv);
  for (VertexHandle v : mesh.vertices()) start[v.idx()] = pos[v.idx()] = mesh.point(v);
  std::vector<Vec3> start_normal(mesh.n_faces(), Vec3(0, 0, 0));
  for (FaceHandle f : mesh.faces()) start_normal[f.idx()] = unit_face_normal(mesh, f, start);
  const std::vector<std::pair<int, int>> pairs_before = self_intersecting_face_pairs(mesh);

  std::vector<Vec3> offset(nv, Vec3(0, 0, 0));  // pos - start
  std::vector<std::size_t> used;       // the samples of the first round
  struct Row {  // one sample's equation: sum_k a[k] t_{v[k]} = r
    int v[3];
    double a[3];
    double r;
  };
  std::vector<Row> rows;
  Foot foot;
  for (int round = 0; round < params.rounds; ++round) {
    const std::vector<Vec3> vn = unit_vertex_normals(mesh);
    FootFinder finder(mesh);
    std::vector<Eigen::Triplet<double>> triplets;
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(nv));
    double dist_sum = 0;
    rows.clear();
    for (std::size_t i = 0; i < samples.size(); i += stride) {
      const Vec3& p = samples[i];
      if (!finder.find(p, foot) || !(foot.distance <= params.max_sample_distance)) continue;
      if (!normals.empty()) {
        const Vec3& sn = normals[i];
        const double len = sn.norm();
        const double c = sn | foot.unit_normal;
        if (len > 0 && std::isfinite(len) && (params.oriented_normals ? c : std::abs(c)) < 0.3 * len) continue;
      }
      if (round == 0) {
        used.push_back(i);
        dist_sum += foot.distance;
      }
      Row row;
      for (int k = 0; k < 3; ++k) {
        row.v[k] = foot.v[k];
        row.a[k] = foot.b[k] * (vn[static_cast<std::size_t>(foot.v[k])] | foot.unit_normal);
      }
      row.r = (p - foot.point) | foot.unit_normal;
      rows.push_back(row);
    }
    // Iteratively reweighted least squares (l1_weights): weights mean|r| / max(|r|, 0.1 mean|r|).
    double mean_abs = 0;
    for (const Row& row : rows) mean_abs += std::abs(row.r);
    mean_abs = rows.empty() ? 0.0 : mean_abs / static_cast<double>(rows.size());
    const bool reweight = params.l1_weights && round > 0 && mean_abs > 0;
    for (const Row& row : rows) {
      const double w = reweight ? mean_abs / std::max(std::abs(row.r), 0.1 * mean_abs) : 1.0;
      for (int k = 0; k < 3; ++k) {
        rhs[row.v[k]] += w * row.a[k] * row.r;
        for (int j = 0; j < 3; ++j) triplets.emplace_back(row.v[k], row.v[j], w * row.a[k] * row.a[j]);
      }
    }
    if (round == 0) {
      report.samples_used = used.size();
      report.mean_distance_before = used.empty() ? 0.0 : dist_sum / static_cast<double>(used.size());
      if (used.empty()) return report;
    }
    for (auto e : mesh.edges()) {
      const int u = mesh.from_vertex_handle(mesh.halfedge_handle(e, 0)).idx();
      const int w = mesh.to_vertex_handle(mesh.halfedge_handle(e, 0)).idx();
      triplets.emplace_back(u, u, params.smoothness);
      triplets.emplace_back(w, w, params.smoothness);
      triplets.emplace_back(u, w, -params.smoothness);
      triplets.emplace_back(w, u, -params.smoothness);
    }
    // A small pull toward t = 0 keeps the system definite (vertices no sample sees, components
    // without samples); vertices without a normal or without faces stay where they are.
    for (std::size_t v = 0; v < nv; ++v) {
      const bool fixed = vn[v].sqrnorm() == 0 || mesh.status(VertexHandle(static_cast<int>(v))).deleted();
      triplets.emplace_back(static_cast<int>(v), static_cast<int>(v), fixed ? 1e6 : 1e-3);
    }
    Eigen::SparseMatrix<double> A(static_cast<Eigen::Index>(nv), static_cast<Eigen::Index>(nv));
    A.setFromTriplets(triplets.begin(), triplets.end());
    Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper> cg;
    cg.setTolerance(1e-6);  // relative residual: far below the samples' spread
    cg.setMaxIterations(500);
    cg.compute(A);
    Eigen::VectorXd t = cg.solve(rhs);
    if (!t.allFinite()) break;

    // Bound the total move, then halve the moves around faces that turn too far.
    std::vector<Vec3> step(nv, Vec3(0, 0, 0));
    for (std::size_t v = 0; v < nv; ++v) {
      const Vec3 want = offset[v] + t[static_cast<Eigen::Index>(v)] * vn[v];
      const double len = want.norm();
      const Vec3 bounded = len > params.max_move ? want * (params.max_move / len) : want;
      step[v] = bounded - offset[v];
    }
    for (int pass = 0; pass <= 8; ++pass) {
      for (std::size_t v = 0; v < nv; ++v) pos[v] = start[v] + offset[v] + step[v];
      std::vector<char> bad(nv, 0);
      bool any = false;
      for (FaceHandle f : mesh.faces()) {
        const Vec3 n = unit_face_normal(mesh, f, pos);
        if (n.sqrnorm() > 0 && (n | start_normal[f.idx()]) >= params.min_face_cos) continue;
        any = true;
        for (VertexHandle u : mesh.fv_range(f)) bad[u.idx()] = 1;
      }
      if (!any) break;
      for (std::size_t v = 0; v < nv; ++v)
        if (bad[v]) step[v] = pass < 8 ? step[v] * 0.5 : Vec3(0, 0, 0);
    }
    for (std::size_t v = 0; v < nv; ++v) offset[v] += step[v];
    for (VertexHandle v : mesh.vertices()) mesh.point(v) = start[v.idx()] + offset[v.idx()];
  }
  // The last pass of the face check zeroed moves without checking again, and new self-
  // intersections may have appeared: put back (to where the fit started) the vertices of every
  // face that turns too far and of both faces of every intersecting pair that was not there
  // before, until nothing changes (each pass only puts vertices back: at worst all of them).
  for (bool again = true; again;) {
    again = false;
    const auto put_back = [&](FaceHandle f) {
      for (VertexHandle u : mesh.fv_range(f)) {
        again = again || mesh.point(u) != start[u.idx()];
        mesh.point(u) = start[u.idx()];
      }
    };
    for (VertexHandle v : mesh.vertices()) pos[v.idx()] = mesh.point(v);
    for (FaceHandle f : mesh.faces()) {
      const Vec3 n = unit_face_normal(mesh, f, pos);
      if (!(n.sqrnorm() > 0 && (n | start_normal[f.idx()]) >= params.min_face_cos)) put_back(f);
    }
    if (again) continue;
    const std::vector<std::pair<int, int>> now = self_intersecting_face_pairs(mesh);
    for (const auto& pair : now) {
      if (std::binary_search(pairs_before.begin(), pairs_before.end(), pair)) continue;
      put_back(FaceHandle(pair.first));
      put_back(FaceHandle(pair.second));
      ++report.intersections_undone;
    }
  }
  for (VertexHandle v : mesh.vertices()) report.vertices_moved += mesh.point(v) != start[v.idx()] ? 1 : 0;
  mesh.update_face_normals();
  if (!params.measure_after) return report;
  std::vector<Vec3> used_samples;
  used_samples.reserve(used.size());
  for (std::size_t i : used) used_samples.push_back(samples[i]);
  report.mean_distance_after = mean_sample_distance(mesh, used_samples, std::numeric_limits<double>::infinity());
  return report;
}

}  // namespace gcs::detail
