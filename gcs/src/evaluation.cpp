#include "gcs/evaluation.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <limits>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "detail/self_intersection.h"
#include "edgefront/coordinate_range.h"
#include "edgefront/error.h"
#include "edgefront/geometry.h"
#include "edgefront/parallel.h"
#include "edgefront/mesh_stats.h"
#include "edgefront/point_index.h"
#include "edgefront/triangle_bvh.h"

namespace gcs {
namespace {

using edgefront::FaceHandle;
using edgefront::InvalidInput;
using edgefront::Mesh;
using edgefront::PointCloud;
using edgefront::PointIndex;
using edgefront::Vec3;

constexpr std::size_t kMaxSamples = 100000000;
constexpr double kInf = std::numeric_limits<double>::infinity();

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
// Geometry: the shared kernel (edgefront/geometry.h, edgefront/triangle_bvh.h)

using Box = edgefront::AlignedBox;
using edgefront::Triangle;
using edgefront::TriangleBvh;

// Live faces of the mesh as triangles; `face_of[i]` is the face index of triangle i.
std::vector<Triangle> mesh_triangles(const Mesh& mesh, std::vector<int>* face_of = nullptr) {
  std::vector<Triangle> tris;
  tris.reserve(mesh.n_faces());
  for (const auto f : mesh.faces()) {
    if (mesh.status(f).deleted()) continue;
    tris.push_back(edgefront::face_triangle(mesh, f));
    if (face_of) face_of->push_back(f.idx());
  }
  return tris;
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

// ---------------------------------------------------------------------------------------------
// Self-intersections

// Counts the intersecting pairs; with `pairs`, also lists them (triangle indices, first < second
// in leaf order).
// On `threads` threads (contiguous chunks of the leaf order, the pairs joined in chunk order: the
// same list for any count).
std::size_t count_self_intersections_of(const TriangleBvh& bvh, std::vector<std::pair<int, int>>* pairs = nullptr,
                                        unsigned threads = 1) {
  return bvh.intersecting_pairs(pairs, threads);
}

// ---------------------------------------------------------------------------------------------

double angle_deg(const Vec3& a, const Vec3& b) {
  return std::atan2((a % b).norm(), a | b) * (180.0 / 3.14159265358979323846);
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

namespace {

// Validity of `mesh`; `bvh` (over the mesh's live faces) is reused when given.
MeshValidity validity_of(const Mesh& mesh, bool count_self, const TriangleBvh* bvh, unsigned threads = 1) {
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

}  // namespace

MeshValidity mesh_validity(const Mesh& mesh, bool count_self) {
  check_mesh_coordinates(mesh, "the mesh");
  return validity_of(mesh, count_self, nullptr);
}

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

// ---------------------------------------------------------------------------------------------
// Output

namespace {

std::string num(double v) {
  if (!std::isfinite(v)) return "null";
  std::array<char, 64> buf{};
  const auto r = std::to_chars(buf.data(), buf.data() + buf.size(), v);
  return std::string(buf.data(), r.ptr);
}

std::string fixed(double v, int digits) {
  std::ostringstream os;
  os << std::fixed << std::setprecision(digits) << v;
  return os.str();
}

std::string distance_json(const OneSidedDistance& d, double diag) {
  std::ostringstream os;
  os << "{\"count\": " << d.count << ", \"mean\": " << num(d.mean) << ", \"rms\": " << num(d.rms)
     << ", \"median\": " << num(d.median) << ", \"p95\": " << num(d.p95) << ", \"max\": " << num(d.max)
     << ", \"mean_percent\": " << num(100 * d.mean / diag) << ", \"p95_percent\": " << num(100 * d.p95 / diag)
     << ", \"max_percent\": " << num(100 * d.max / diag) << "}";
  return os.str();
}

}  // namespace

std::string format_evaluation(const Evaluation& e) {
  std::ostringstream os;
  auto dist = [&](const char* label, double v) {
    os << label << fixed(v, 6) << "  (" << fixed(e.scale(v), 4) << "% of bbox diagonal)\n";
  };
  os << "ground truth:            " << (e.ground_truth_is_mesh ? "mesh, " : "point set, ")
     << e.ground_truth_points << (e.ground_truth_is_mesh ? " samples" : " points") << ", bbox diagonal "
     << fixed(e.gt_bbox_diagonal, 6) << "\n";
  os << "result samples:          " << e.result_to_gt.count << "; distance to a mesh: "
     << (e.exact_surface_distance ? "exact, to its surface" : "to its nearest sample") << "\n";
  dist("chamfer-L1:              ", e.chamfer_l1);
  dist("  result -> gt mean:     ", e.result_to_gt.mean);
  dist("  gt -> result mean:     ", e.gt_to_result.mean);
  dist("hausdorff:               ", e.hausdorff);
  dist("  result -> gt max:      ", e.result_to_gt.max);
  dist("  gt -> result max:      ", e.gt_to_result.max);
  dist("hausdorff 95%:           ", e.hausdorff_p95);
  for (const FScore& f : e.fscores) {
    os << "F-score @ " << fixed(100 * f.threshold_fraction, 2) << "%:          " << fixed(f.fscore, 4)
       << "  (precision " << fixed(f.precision, 4) << ", recall " << fixed(f.recall, 4) << ", threshold "
       << fixed(f.threshold, 6) << ")\n";
  }
  if (e.normal_consistency) {
    os << "normal consistency:      " << fixed(*e.normal_consistency, 4) << "  (mean |n.n_gt|)\n";
  } else {
    os << "normal consistency:      n/a (ground truth without normals)\n";
  }
  if (e.orientation) {
    std::size_t with_samples = 0, flipped = 0;
    for (const auto& c : e.orientation->components) {
      with_samples += c.samples > 0 ? 1 : 0;
      flipped += c.samples > 0 && c.flipped ? 1 : 0;
    }
    os << "orientation consistency: " << fixed(e.orientation->raw, 4) << " as is, "
       << fixed(e.orientation->per_component, 4) << " with the better sign per component (" << flipped
       << " of " << with_samples << " components better flipped)\n";
  } else {
    os << "orientation consistency: n/a (ground truth without normals)\n";
  }
  const MeshValidity& m = e.validity;
  os << "mesh:                    " << m.vertices << " vertices, " << m.edges << " edges, " << m.faces
     << " faces, area " << fixed(m.area, 6) << "\n";
  os << "manifold:                edges " << (m.edge_manifold ? "yes" : "no") << ", vertices "
     << (m.vertex_manifold ? "yes" : "no") << " (" << m.nonmanifold_vertices << " non-manifold)";
  if (m.faces_dropped_when_read > 0) {
    os << "; but the file had " << m.faces_dropped_when_read
       << " more faces that made it non-manifold (dropped on reading)";
  }
  os << "\n";
  os << "components:              " << m.components << ", border loops " << m.border_loops
     << (m.closed ? " (closed)" : "") << ", isolated vertices " << m.isolated_vertices << "\n";
  os << "euler / genus:           " << m.euler_characteristic << " / " << m.genus;
  if (m.component_genus.size() > 1) {
    os << "  (per component:";
    for (std::size_t i = 0; i < m.component_genus.size() && i < 10; ++i) os << " " << m.component_genus[i];
    if (m.component_genus.size() > 10) os << " ...";
    os << ")";
  }
  os << "\n";
  os << "self-intersecting pairs: "
     << (m.self_intersecting_pairs ? std::to_string(*m.self_intersecting_pairs) : std::string("not computed"))
     << "\n";
  os << "degenerate / duplicate:  " << m.degenerate_faces << " / " << m.duplicate_faces << " faces\n";
  os << "min angle:               " << fixed(m.min_angle_deg, 2) << " deg, median of per-face minimum "
     << fixed(m.median_min_angle_deg, 2) << " deg; " << fixed(100 * m.faces_min_angle_below_10, 2)
     << "% of faces < 10 deg, " << fixed(100 * m.faces_min_angle_below_30, 2) << "% < 30 deg\n";
  os << "valence histogram:      ";
  std::size_t total = 0;
  for (const std::size_t c : m.valence_histogram) total += c;
  for (std::size_t k = 0; k < m.valence_histogram.size(); ++k) {
    if (m.valence_histogram[k] == 0) continue;
    os << " " << k << ":" << m.valence_histogram[k] << " ("
       << fixed(100.0 * static_cast<double>(m.valence_histogram[k]) / static_cast<double>(total), 1) << "%)";
  }
  os << "\n";
  return os.str();
}

std::string evaluation_to_json(const Evaluation& e) {
  std::ostringstream os;
  const double diag = e.gt_bbox_diagonal;
  os << "{\"ground_truth\": {\"kind\": \"" << (e.ground_truth_is_mesh ? "mesh" : "points")
     << "\", \"points\": " << e.ground_truth_points << ", \"bbox_diagonal\": " << num(diag) << "},\n";
  os << " \"result_samples\": " << e.result_to_gt.count << ", \"distance_to_mesh\": \""
     << (e.exact_surface_distance ? "surface" : "nearest_sample") << "\",\n";
  os << " \"chamfer_l1\": " << num(e.chamfer_l1) << ", \"chamfer_l1_percent\": " << num(e.scale(e.chamfer_l1))
     << ",\n";
  os << " \"hausdorff\": " << num(e.hausdorff) << ", \"hausdorff_percent\": " << num(e.scale(e.hausdorff))
     << ",\n";
  os << " \"hausdorff_p95\": " << num(e.hausdorff_p95)
     << ", \"hausdorff_p95_percent\": " << num(e.scale(e.hausdorff_p95)) << ",\n";
  os << " \"result_to_gt\": " << distance_json(e.result_to_gt, diag) << ",\n";
  os << " \"gt_to_result\": " << distance_json(e.gt_to_result, diag) << ",\n";
  os << " \"fscores\": [";
  for (std::size_t i = 0; i < e.fscores.size(); ++i) {
    const FScore& f = e.fscores[i];
    os << (i ? ", " : "") << "{\"threshold_fraction\": " << num(f.threshold_fraction)
       << ", \"threshold\": " << num(f.threshold) << ", \"precision\": " << num(f.precision)
       << ", \"recall\": " << num(f.recall) << ", \"fscore\": " << num(f.fscore) << "}";
  }
  os << "],\n";
  os << " \"normal_consistency\": " << (e.normal_consistency ? num(*e.normal_consistency) : "null") << ",\n";
  os << " \"orientation_consistency\": ";
  if (e.orientation) {
    os << "{\"raw\": " << num(e.orientation->raw)
       << ", \"per_component\": " << num(e.orientation->per_component) << ", \"components\": [";
    bool first = true;
    for (std::size_t c = 0; c < e.orientation->components.size(); ++c) {
      const ComponentOrientation& co = e.orientation->components[c];
      if (co.faces == 0) continue;
      os << (first ? "" : ", ") << "{\"component\": " << c << ", \"faces\": " << co.faces
         << ", \"samples\": " << co.samples << ", \"area_share\": " << num(co.area_share)
         << ", \"agreeing\": " << num(co.agreeing) << ", \"flipped\": " << (co.flipped ? "true" : "false")
         << "}";
      first = false;
    }
    os << "]}";
  } else {
    os << "null";
  }
  os << ",\n";
  const MeshValidity& m = e.validity;
  os << " \"mesh\": {\"vertices\": " << m.vertices << ", \"edges\": " << m.edges << ", \"faces\": " << m.faces
     << ", \"area\": " << num(m.area) << ", \"edge_manifold\": " << (m.edge_manifold ? "true" : "false")
     << ", \"nonmanifold_edges\": " << m.nonmanifold_edges
     << ", \"vertex_manifold\": " << (m.vertex_manifold ? "true" : "false")
     << ", \"nonmanifold_vertices\": " << m.nonmanifold_vertices
     << ", \"faces_dropped_when_read\": " << m.faces_dropped_when_read
     << ",\n  \"components\": " << m.components << ", \"border_loops\": " << m.border_loops
     << ", \"closed\": " << (m.closed ? "true" : "false")
     << ", \"euler_characteristic\": " << m.euler_characteristic << ", \"genus\": " << num(m.genus)
     << ", \"component_genus\": [";
  for (std::size_t i = 0; i < m.component_genus.size(); ++i)
    os << (i ? ", " : "") << num(m.component_genus[i]);
  os << "],\n  \"isolated_vertices\": " << m.isolated_vertices
     << ", \"degenerate_faces\": " << m.degenerate_faces << ", \"duplicate_faces\": " << m.duplicate_faces
     << ", \"self_intersecting_pairs\": "
     << (m.self_intersecting_pairs ? std::to_string(*m.self_intersecting_pairs) : std::string("null"))
     << ",\n  \"min_angle_deg\": " << num(m.min_angle_deg)
     << ", \"median_min_angle_deg\": " << num(m.median_min_angle_deg)
     << ", \"faces_min_angle_below_10\": " << num(m.faces_min_angle_below_10)
     << ", \"faces_min_angle_below_30\": " << num(m.faces_min_angle_below_30) << ", \"valence_histogram\": [";
  for (std::size_t k = 0; k < m.valence_histogram.size(); ++k)
    os << (k ? ", " : "") << m.valence_histogram[k];
  os << "]}}\n";
  return os.str();
}

}  // namespace gcs
