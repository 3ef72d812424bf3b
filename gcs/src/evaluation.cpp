#include "gcs/evaluation.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <random>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "detail/evaluation_common.h"
#include "edgefront/coordinate_range.h"
#include "edgefront/error.h"
#include "edgefront/mesh_stats.h"
#include "edgefront/parallel.h"
#include "edgefront/point_index.h"
#include "edgefront/triangle_bvh.h"

namespace gcs {

using detail::eval::Box;
using detail::eval::mesh_triangles;
using detail::eval::Triangle;
using detail::eval::TriangleBvh;
using detail::eval::validity_of;

namespace {

using edgefront::FaceHandle;
using edgefront::InvalidInput;
using edgefront::Mesh;
using edgefront::PointCloud;
using edgefront::PointIndex;
using edgefront::Vec3;

constexpr std::size_t kMaxSamples = 100000000;

bool finite(const Vec3& p) { return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]); }

// ---------------------------------------------------------------------------------------------
// Input checks

void check_options(const EvaluationOptions& o) {
  if (o.samples < 1 || o.samples > kMaxSamples) {
    throw InvalidInput("evaluation: samples must be in [1, 1e8], got " + std::to_string(o.samples));
  }
  for (const double t : o.fscore_thresholds) {
    if (!std::isfinite(t) || !(t > 0.0)) {
      throw InvalidInput(
          "evaluation: F-score thresholds must be finite and > 0 (fractions of the bbox diagonal)");
    }
  }
}

}  // namespace

namespace detail::eval {

void check_mesh_coordinates(const Mesh& mesh, const char* what) {
  for (const auto v : mesh.vertices()) {
    if (mesh.status(v).deleted()) continue;
    if (!finite(mesh.point(v))) {
      throw InvalidInput(std::string("evaluation: ") + what + " has a non-finite coordinate at vertex " +
                         std::to_string(v.idx()));
    }
  }
  edgefront::check_coordinate_range(mesh, std::string("evaluation: ") + what);
}

}  // namespace detail::eval

namespace {

using detail::eval::check_mesh_coordinates;

void check_cloud(const PointCloud& cloud) {
  if (cloud.empty()) throw InvalidInput("evaluation: the ground-truth point set is empty");
  if (!cloud.normals.empty() && cloud.normals.size() != cloud.points.size()) {
    throw InvalidInput("evaluation: the ground truth has " + std::to_string(cloud.normals.size()) +
                       " normals for " + std::to_string(cloud.points.size()) + " points");
  }
  for (std::size_t i = 0; i < cloud.points.size(); ++i) {
    if (!finite(cloud.points[i])) {
      throw InvalidInput("evaluation: the ground truth has a non-finite coordinate at point " +
                         std::to_string(i));
    }
  }
  edgefront::check_coordinate_range(cloud.points, "evaluation: the ground truth");
  for (std::size_t i = 0; i < cloud.normals.size(); ++i) {
    if (!finite(cloud.normals[i]) || !(cloud.normals[i].sqrnorm() > 0.0)) {
      throw InvalidInput("evaluation: the ground truth has a non-finite or zero normal at point " +
                         std::to_string(i));
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Sampling

struct Samples {
  std::vector<Vec3> points;
  std::vector<Vec3> normals;  // unit normal of the sampled triangle
  std::vector<int> tri;       // index into the triangle list
};

double uniform01(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

// Area-uniform samples of the triangles. \throw InvalidInput when the total area is zero.
Samples sample_triangles(const std::vector<Triangle>& tris, std::size_t count, std::uint64_t seed,
                         const char* what) {
  std::vector<double> cumulative(tris.size());
  double total = 0;
  for (std::size_t i = 0; i < tris.size(); ++i) {
    const Triangle& t = tris[i];
    const double area = 0.5 * ((t.p[1] - t.p[0]) % (t.p[2] - t.p[0])).norm();
    total += std::isfinite(area) ? area : 0.0;
    cumulative[i] = total;
  }
  if (!(total > 0.0) || !std::isfinite(total)) {
    throw InvalidInput(std::string("evaluation: ") + what + " has no face of positive area");
  }
  std::mt19937_64 rng(seed);
  Samples s;
  s.points.reserve(count);
  s.normals.reserve(count);
  s.tri.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    const auto it = std::upper_bound(cumulative.begin(), cumulative.end(), uniform01(rng) * total);
    const std::size_t k =
        std::min<std::size_t>(static_cast<std::size_t>(it - cumulative.begin()), tris.size() - 1);
    const Triangle& t = tris[k];
    const double r1 = std::sqrt(uniform01(rng)), r2 = uniform01(rng);
    s.points.push_back((1 - r1) * t.p[0] + r1 * (1 - r2) * t.p[1] + r1 * r2 * t.p[2]);
    s.normals.push_back(t.unit_normal());
    s.tri.push_back(static_cast<int>(k));
  }
  return s;
}

// ---------------------------------------------------------------------------------------------
// Metrics from distances

OneSidedDistance summarize(std::vector<double> d) {
  OneSidedDistance s;
  s.count = d.size();
  if (d.empty()) return s;
  double sum = 0, sum2 = 0;
  for (const double x : d) {
    sum += x;
    sum2 += x * x;
  }
  const double n = static_cast<double>(d.size());
  s.mean = sum / n;
  s.rms = std::sqrt(sum2 / n);
  std::sort(d.begin(), d.end());
  s.median = d.size() % 2 ? d[d.size() / 2] : 0.5 * (d[d.size() / 2 - 1] + d[d.size() / 2]);
  const std::size_t rank = static_cast<std::size_t>(std::ceil(0.95 * n));
  s.p95 = d[std::clamp<std::size_t>(rank, 1, d.size()) - 1];
  s.max = d.back();
  return s;
}

double share_within(const std::vector<double>& d, double threshold) {
  std::size_t k = 0;
  for (const double x : d) k += x <= threshold ? 1 : 0;
  return d.empty() ? 0.0 : static_cast<double>(k) / static_cast<double>(d.size());
}

// Orientation of result samples against the ground-truth normals at their nearest points.
OrientationConsistency orientation_of(const Mesh& mesh, const std::vector<int>& face_of_tri, const Samples& s,
                                      const std::vector<Vec3>& gt_normal) {
  const edgefront::ComponentLabels labels = edgefront::connected_components(mesh);
  std::vector<std::size_t> agree(labels.count, 0), disagree(labels.count, 0);
  OrientationConsistency o;
  o.components.resize(labels.count);
  for (const auto f : mesh.faces()) {
    if (mesh.status(f).deleted()) continue;
    const int c =
        labels
            .vertex_component[static_cast<std::size_t>(mesh.to_vertex_handle(mesh.halfedge_handle(f)).idx())];
    ++o.components[static_cast<std::size_t>(c)].faces;
  }
  double sum_abs = 0;
  std::size_t agree_total = 0;
  for (std::size_t i = 0; i < s.points.size(); ++i) {
    const FaceHandle f(face_of_tri[static_cast<std::size_t>(s.tri[i])]);
    const std::size_t c = static_cast<std::size_t>(labels.vertex_component[static_cast<std::size_t>(
        mesh.to_vertex_handle(mesh.halfedge_handle(f)).idx())]);
    const double dot = s.normals[i] | gt_normal[i];
    sum_abs += std::abs(dot);
    ++o.components[c].samples;
    if (dot > 0) {
      ++agree[c];
      ++agree_total;
    } else if (dot < 0) {
      ++disagree[c];
    }
  }
  const double n = static_cast<double>(s.points.size());
  std::size_t best_total = 0;
  for (std::size_t c = 0; c < labels.count; ++c) {
    ComponentOrientation& co = o.components[c];
    if (co.samples == 0) continue;
    co.area_share = static_cast<double>(co.samples) / n;
    co.agreeing = static_cast<double>(agree[c]) / static_cast<double>(co.samples);
    co.flipped = disagree[c] > agree[c];
    best_total += std::max(agree[c], disagree[c]);
  }
  o.raw = static_cast<double>(agree_total) / n;
  o.per_component = static_cast<double>(best_total) / n;
  o.unsigned_consistency = sum_abs / n;
  return o;
}

Box bbox_of(const std::vector<Vec3>& pts) {
  Box b;
  for (const Vec3& p : pts) b.add(p);
  return b;
}

}  // namespace

// =============================================================================================

GroundTruth GroundTruth::from_points(edgefront::PointCloud cloud) {
  return GroundTruth(std::variant<PointCloud, Mesh>(std::in_place_index<0>, std::move(cloud)));
}

GroundTruth GroundTruth::from_mesh(edgefront::Mesh mesh) {
  return GroundTruth(std::variant<PointCloud, Mesh>(std::in_place_index<1>, std::move(mesh)));
}

bool GroundTruth::has_normals() const { return is_mesh() || points().has_normals(); }

namespace {

// The result's triangles after the checks every entry point shares.
std::vector<Triangle> checked_result_triangles(const Mesh& result, std::vector<int>& face_of) {
  std::size_t live = 0;
  for (const auto v : result.vertices()) live += result.status(v).deleted() ? 0 : 1;
  if (live == 0) throw InvalidInput("evaluation: the result mesh is empty (no vertices)");
  check_mesh_coordinates(result, "the result mesh");
  std::vector<Triangle> tris = mesh_triangles(result, &face_of);
  if (tris.empty()) throw InvalidInput("evaluation: the result mesh has no faces");
  return tris;
}

}  // namespace

OrientationConsistency orientation_consistency(const Mesh& mesh, const PointCloud& oriented_gt,
                                               const EvaluationOptions& options) {
  check_options(options);
  check_cloud(oriented_gt);
  if (!oriented_gt.has_normals()) {
    throw InvalidInput("evaluation: orientation consistency needs a ground truth with normals");
  }
  std::vector<int> face_of;
  const std::vector<Triangle> tris = checked_result_triangles(mesh, face_of);
  const Samples s = sample_triangles(tris, options.samples, options.seed, "the result mesh");
  const PointIndex index(oriented_gt.points);
  std::vector<Vec3> gt_normal(s.points.size());
  edgefront::parallel_for(s.points.size(), options.threads, [&](std::size_t begin, std::size_t end, unsigned) {
    for (std::size_t i = begin; i < end; ++i) {
      gt_normal[i] = oriented_gt.normals[index.nearest(s.points[i]).index].normalized();
    }
  });
  return orientation_of(mesh, face_of, s, gt_normal);
}

Evaluation evaluate(const Mesh& result, const GroundTruth& gt, const EvaluationOptions& options) {
  check_options(options);
  std::vector<int> face_of;
  std::vector<Triangle> result_tris = checked_result_triangles(result, face_of);

  Evaluation e;
  e.ground_truth_is_mesh = gt.is_mesh();
  e.exact_surface_distance = options.exact_surface_distance;
  // Ground truth: its points (or samples), their normals, and its scale.
  std::vector<Vec3> gt_points;
  std::vector<Vec3> gt_point_normals;  // empty without normals
  std::unique_ptr<TriangleBvh> gt_bvh;
  std::unique_ptr<PointIndex> gt_index;
  Box gt_box;
  if (gt.is_mesh()) {
    const Mesh& m = gt.mesh();
    check_mesh_coordinates(m, "the ground-truth mesh");
    std::vector<Triangle> tris = mesh_triangles(m);
    if (tris.empty()) throw InvalidInput("evaluation: the ground-truth mesh has no faces");
    for (const auto v : m.vertices()) {
      if (!m.status(v).deleted() && !m.is_isolated(v)) gt_box.add(m.point(v));
    }
    Samples s = sample_triangles(tris, options.samples, options.seed + 0x9e3779b97f4a7c15ULL,
                                 "the ground-truth mesh");
    gt_points = std::move(s.points);
    gt_point_normals = std::move(s.normals);
    if (options.exact_surface_distance) {
      gt_bvh = std::make_unique<TriangleBvh>(std::move(tris));
    } else {
      gt_index = std::make_unique<PointIndex>(gt_points);
    }
  } else {
    const PointCloud& c = gt.points();
    check_cloud(c);
    gt_points = c.points;
    for (const Vec3& n : c.normals) gt_point_normals.push_back(n.normalized());
    gt_box = bbox_of(gt_points);
    gt_index = std::make_unique<PointIndex>(gt_points);
  }
  e.gt_bbox_diagonal = (gt_box.hi - gt_box.lo).norm();
  if (!(e.gt_bbox_diagonal > 0.0)) {
    throw InvalidInput("evaluation: the ground truth has no extent (all its points coincide)");
  }
  e.ground_truth_points = gt_points.size();

  // Result -> ground truth.
  const Samples rs = sample_triangles(result_tris, options.samples, options.seed, "the result mesh");
  std::vector<double> d_result(rs.points.size());
  std::vector<Vec3> n_gt_at(rs.points.size());
  // The nearest-point queries run on options.threads threads, each sample writing its own slot.
  edgefront::parallel_for(rs.points.size(), options.threads, [&](std::size_t begin, std::size_t end, unsigned) {
    for (std::size_t i = begin; i < end; ++i) {
      if (gt_bvh) {
        const TriangleBvh::Hit h = gt_bvh->nearest(rs.points[i]);
        d_result[i] = std::sqrt(h.dist2);
        n_gt_at[i] = gt_bvh->triangles()[static_cast<std::size_t>(h.tri)].unit_normal();
      } else {
        const PointIndex::Neighbor nb = gt_index->nearest(rs.points[i]);
        d_result[i] = std::sqrt(nb.distance2);
        if (!gt_point_normals.empty()) n_gt_at[i] = gt_point_normals[nb.index];
      }
    }
  });
  // Ground truth -> result.
  std::vector<double> d_gt(gt_points.size());
  const TriangleBvh result_bvh(std::move(result_tris));  // also for the self-intersections
  std::unique_ptr<PointIndex> result_index;
  if (!options.exact_surface_distance) result_index = std::make_unique<PointIndex>(rs.points);
  edgefront::parallel_for(gt_points.size(), options.threads, [&](std::size_t begin, std::size_t end, unsigned) {
    for (std::size_t i = begin; i < end; ++i) {
      d_gt[i] = result_index ? std::sqrt(result_index->nearest(gt_points[i]).distance2)
                             : std::sqrt(result_bvh.nearest(gt_points[i]).dist2);
    }
  });

  for (const double t : options.fscore_thresholds) {
    FScore f;
    f.threshold_fraction = t;
    f.threshold = t * e.gt_bbox_diagonal;
    f.precision = share_within(d_result, f.threshold);
    f.recall = share_within(d_gt, f.threshold);
    f.fscore = f.precision + f.recall > 0 ? 2 * f.precision * f.recall / (f.precision + f.recall) : 0.0;
    e.fscores.push_back(f);
  }
  e.result_to_gt = summarize(std::move(d_result));
  e.gt_to_result = summarize(std::move(d_gt));
  e.chamfer_l1 = 0.5 * (e.result_to_gt.mean + e.gt_to_result.mean);
  e.hausdorff = std::max(e.result_to_gt.max, e.gt_to_result.max);
  e.hausdorff_p95 = std::max(e.result_to_gt.p95, e.gt_to_result.p95);

  if (gt.has_normals()) {
    e.orientation = orientation_of(result, face_of, rs, n_gt_at);
    e.normal_consistency = e.orientation->unsigned_consistency;
  }
  e.validity = validity_of(result, options.self_intersections, &result_bvh, options.threads);
  return e;
}

}  // namespace gcs
