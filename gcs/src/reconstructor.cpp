#include "gcs/reconstructor.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <new>
#include <type_traits>
#include <limits>
#include <numbers>
#include <random>
#include <utility>

#include <Eigen/Dense>

#if defined(__linux__)
#include <sys/mman.h>
#endif

#include "detail/border_topology.h"
#include "detail/counter_heap.h"
#include "detail/double_layer.h"
#include "detail/neighbor_cache.h"
#include "detail/sample_projection.h"
#include "detail/spatial_order.h"
#include "detail/surface_fit.h"
#include "detail/untangle.h"
#include "detail/vertex_grid.h"
#include "edgefront/coordinate_range.h"
#include "edgefront/error.h"
#include "edgefront/mesh_stats.h"
#include "edgefront/point_index.h"
#include "gcs/cloud_noise.h"
#include "gcs/cloud_normals.h"
#include "twist/repair.h"

namespace gcs {

using edgefront::EdgeHandle;
using edgefront::FaceHandle;
using edgefront::HalfedgeHandle;
using edgefront::InvalidInput;
using edgefront::Mesh;
using edgefront::PointIndex;
using edgefront::Vec3;
using edgefront::VertexHandle;

std::string to_string(Phase phase) {
  switch (phase) {
    case Phase::noise_estimate:
      return "noise estimate";
    case Phase::normal_fitting:
      return "normal fitting";
    case Phase::growth:
      return "growth";
    case Phase::post_processing:
      return "post-processing";
  }
  return "unknown phase";
}

std::string to_string(StopReason reason) {
  switch (reason) {
    case StopReason::target_reached:
      return "target reached";
    case StopReason::cancelled:
      return "cancelled";
    case StopReason::step_limit:
      return "step limit";
    case StopReason::shrunk_by_operations:
      return "below the target: the operations removed parts again after regrowing";
  }
  return "unknown";
}

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

Vec3 face_normal_of(const Vec3& a, const Vec3& b, const Vec3& c) { return (b - a) % (c - a); }

// Sample indices are drawn as one 64-bit draw modulo n (portable, unlike
// std::uniform_int_distribution; the modulo bias is below n / 2^64).
// x % n for a fixed n without a 64-bit division (tens of cycles, on the basic step's critical
// path): q = floor(x * floor((2^64 - 1) / n) / 2^64) is at most 2 below floor(x / n), so the
// remainder x - q n is corrected by at most two subtractions. Exactly x % n.
class FixedModulo {
 public:
  explicit FixedModulo(std::uint64_t n = 1) : n_(n), m_(~std::uint64_t(0) / n) {}
  std::uint64_t operator()(std::uint64_t x) const {
    __extension__ using Wide = unsigned __int128;
    const std::uint64_t q = static_cast<std::uint64_t>((static_cast<Wide>(x) * m_) >> 64);
    std::uint64_t r = x - q * n_;
    while (r >= n_) r -= n_;
    return r;
  }

 private:
  std::uint64_t n_, m_;
};

// What the basic step reads of a sample: the point and its oriented normal, side by side (one or
// two cache lines per draw instead of two far apart). Large arrays are advised for transparent
// huge pages (Linux): a uniform draw over a large cloud otherwise misses the TLB on most steps.
struct DrawSample {
  Vec3 point;
  Vec3 normal;  // oriented normal, zero when the loop does not orient the winners
};
class DrawSamples {
 public:
  void assign(const std::vector<Vec3>& points, const std::vector<Vec3>* normals) {
    constexpr size_t kHuge = size_t(2) << 20;
    const size_t n = points.size(), bytes = std::max<size_t>(n, 1) * sizeof(DrawSample);
    const size_t align = bytes >= 2 * kHuge ? kHuge : 64;
    void* mem = std::aligned_alloc(align, (bytes + align - 1) / align * align);
    if (!mem) throw std::bad_alloc();
    data_.reset(static_cast<DrawSample*>(mem));
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    if (align == kHuge) (void)madvise(mem, (bytes + align - 1) / align * align, MADV_HUGEPAGE);  // advice only
#endif
    for (size_t i = 0; i < n; ++i)
      new (data_.get() + i) DrawSample{points[i], normals ? (*normals)[i] : Vec3(0, 0, 0)};
  }
  const DrawSample& operator[](size_t i) const { return data_.get()[i]; }

 private:
  struct Free {
    void operator()(DrawSample* p) const { std::free(p); }
  };
  std::unique_ptr<DrawSample, Free> data_;
};
static_assert(std::is_trivially_destructible_v<DrawSample>, "DrawSamples frees without destructors");

// Drops the points that repeat an earlier one exactly (with their normals); the others keep their
// input order. Returns how many were dropped. Sorts a copy: O(n log n).
size_t drop_repeated_points(edgefront::PointCloud& c) {
  const std::vector<Vec3>& p = c.points;
  struct Key {
    double x, y, z;
    size_t i;
  };
  std::vector<Key> keys(p.size());
  for (size_t i = 0; i < p.size(); ++i) keys[i] = {p[i][0], p[i][1], p[i][2], i};
  std::sort(keys.begin(), keys.end(), [](const Key& a, const Key& b) {
    if (a.x != b.x) return a.x < b.x;
    if (a.y != b.y) return a.y < b.y;
    if (a.z != b.z) return a.z < b.z;
    return a.i < b.i;
  });
  std::vector<uint8_t> repeated(p.size(), 0);
  size_t dropped = 0;
  for (size_t k = 1; k < keys.size(); ++k) {
    const Key &a = keys[k - 1], &b = keys[k];
    if (a.x == b.x && a.y == b.y && a.z == b.z) {
      repeated[b.i] = 1;
      ++dropped;
    }
  }
  if (dropped == 0) return 0;
  size_t out = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    if (repeated[i]) continue;
    c.points[out] = c.points[i];
    if (!c.normals.empty()) c.normals[out] = c.normals[i];
    ++out;
  }
  c.points.resize(out);
  if (!c.normals.empty()) c.normals.resize(out);
  return dropped;
}

// A normal that is not a usable direction: non-finite or zero (edgefront::read_points with
// tolerate_invalid_normals stores dropped normals as NaN).
bool missing_normal(const Vec3& n) {
  return !(std::isfinite(n[0]) && std::isfinite(n[1]) && std::isfinite(n[2])) || !(n.sqrnorm() > 0);
}

// The scatter matrix (sum of outer products) of the neighbours' positions about their centroid:
// its eigenvector of the smallest eigenvalue is the normal of their least-squares plane.
Eigen::Matrix3d neighbour_scatter(const std::vector<Vec3>& points, const std::vector<PointIndex::Neighbor>& knn) {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const PointIndex::Neighbor& nb : knn) centre += Eigen::Vector3d(points[nb.index][0], points[nb.index][1], points[nb.index][2]);
  centre /= static_cast<double>(knn.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const PointIndex::Neighbor& nb : knn) {
    const Eigen::Vector3d q = Eigen::Vector3d(points[nb.index][0], points[nb.index][1], points[nb.index][2]) - centre;
    cov += q * q.transpose();
  }
  return cov;
}

// Replaces the missing normals of `c` (missing_normal) by the normal of the plane through the
// point's 16 nearest points, oriented like the sum of the 8 nearest given normals, and normalizes
// the given ones that are not unit. Returns how many were filled; clears the normals when none is
// given (then returns 0 and sets `unusable`). Deterministic.
size_t fill_missing_normals(edgefront::PointCloud& c, bool& unusable) {
  unusable = false;
  if (c.normals.empty()) return 0;
  std::vector<Vec3> given_points, given_normals;
  std::vector<size_t> missing;
  for (size_t i = 0; i < c.size(); ++i) {
    if (missing_normal(c.normals[i])) {
      missing.push_back(i);
    } else {
      given_points.push_back(c.points[i]);
      given_normals.push_back(c.normals[i]);
    }
  }
  if (missing.empty()) return 0;
  if (given_points.empty()) {
    c.normals.clear();
    unusable = true;
    return 0;
  }
  const PointIndex all(c.points);
  const PointIndex given(std::move(given_points));
  std::vector<PointIndex::Neighbor> knn;
  for (const size_t i : missing) {
    const Vec3& p = c.points[i];
    all.k_nearest(p, 16, knn);
    const Eigen::Matrix3d cov = neighbour_scatter(c.points, knn);
    given.k_nearest(p, 8, knn);
    Vec3 side(0, 0, 0);
    for (const PointIndex::Neighbor& nb : knn) side += given_normals[nb.index];
    Vec3 n = side;  // degenerate neighbourhood (fewer than 3 points, a line): the neighbours' mean
    if (cov.trace() > 0) {
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
      const Eigen::Vector3d e = eig.eigenvectors().col(0);
      if (eig.eigenvalues()[1] > 0) n = Vec3(e[0], e[1], e[2]);
    }
    if ((n | side) < 0) n = -n;
    if (!(n.sqrnorm() > 0)) n = given_normals[knn.front().index];
    c.normals[i] = n.normalized();
  }
  return missing.size();
}

// The options' ranges; the target against the number of points is checked in init, after the
// repeated points are dropped.
void check_options(const ReconstructOptions& o) {
  auto fail = [](const std::string& m) { throw InvalidInput("gcs: " + m); };
  if (o.target_vertices < 4) fail("target_vertices must be at least 4 (got " + std::to_string(o.target_vertices) + ")");
  if (o.target_vertices > 50'000'000) fail("target_vertices above 50,000,000 is not supported");
  if (o.steps_per_split < 1) fail("steps_per_split must be >= 1");
  if (!(o.winner_rate > 0 && o.winner_rate <= 1)) fail("winner_rate must be in (0, 1]");
  if (!(o.neighbor_rate >= 0 && o.neighbor_rate <= 1)) fail("neighbor_rate must be in [0, 1]");
  if (o.smoothing_iterations < 0 || o.smoothing_iterations > 100) fail("smoothing_iterations must be in [0, 100]");
  if (!(o.decay_half_life > 0) || !std::isfinite(o.decay_half_life)) fail("decay_half_life must be positive");
  if (!(o.inactivity_window >= 0) || !std::isfinite(o.inactivity_window)) fail("inactivity_window must be >= 0");
  if (o.batch_splits < 1) fail("batch_splits must be >= 1");
  if (!(o.unsupported_distance > 0) || !std::isfinite(o.unsupported_distance)) fail("unsupported_distance must be positive");
  if (!(o.long_edge_factor > 1) || !std::isfinite(o.long_edge_factor)) fail("long_edge_factor must be > 1");
  if (o.progress_interval < 1) fail("progress_interval must be >= 1");
  if (o.film_samples > 64) fail("film_samples must be at most 64");
  if (o.border_trim_rings > 8) fail("border_trim_rings must be at most 8");
  if (o.max_query_points != 0 && o.max_query_points < o.target_vertices)
    fail("max_query_points " + std::to_string(o.max_query_points) + " is below target_vertices " +
         std::to_string(o.target_vertices) + ": a subsample sparser than the mesh cannot support its faces (0 = automatic)");
  if (o.fit_rounds < 1 || o.fit_rounds > 20) fail("fit_rounds must be in [1, 20] (got " + std::to_string(o.fit_rounds) + ")");
  if (!(o.fit_smoothness >= 0) || !std::isfinite(o.fit_smoothness)) fail("fit_smoothness must be finite and >= 0");
  if (!(o.smooth_noise_ratio >= 0)) fail("smooth_noise_ratio must be >= 0 (infinity turns the smoothing off)");
  if (o.stacked_layer_rounds < 0 || o.stacked_layer_rounds > 16)
    fail("stacked_layer_rounds must be in [0, 16] (got " + std::to_string(o.stacked_layer_rounds) + ")");
}

}  // namespace

// The film test of the border creation runs only for clouds whose oriented normals point away
// from their centroid at least this much (detail::normal_flux: a sphere 1, a flat sheet 0): a film
// across a tunnel needs a surface around a volume; on flat sheets it curled the borders.
constexpr double kEnclosingFlux = 0.2;
// Holes whose fan fill is refused are retried with rings trimmed only when their border is at most
// this many mean edge lengths long (ReconstructOptions::border_trim_rings).
constexpr double kTrimHoleEdges = 10.0;
// Border loops of at most this many vertices are small holes, closed by a fan around their centroid
// (a loop one vertex longer is a slit, zipped by fill_slit_holes up to fill_slits_max_vertices).
constexpr std::size_t kSmallHoleVertices = 8;
// A hole's fan or a slit's strip must agree with the faces it borders: mean cosine of their normals.
constexpr double kFillNormalAgreement = 0.5;
// The Delaunay flips before the fit flip only edges between nearly coplanar faces (cosine of the
// dihedral angle at least this: about 26 degrees), in at most this many passes over the edges.
constexpr double kFlipMinDihedralCos = 0.9;
constexpr int kFlipMaxPasses = 10;

struct Reconstructor::Impl {
  ReconstructOptions opt;
  edgefront::PointCloud cloud;  // centred
  Vec3 offset{0, 0, 0};
  double bbox_diagonal = 0;
  double noise_ratio = 0;  // estimated noise / spacing of the input (ReconstructOptions::smooth_noise_ratio)
  bool cloud_smoothed = false;
  size_t normals_filled = 0;     // missing input normals fitted (fill_missing_normals)
  bool normals_unusable = false;  // the cloud had normals, none usable
  double sample_spacing = 0;
  // The nearest-sample queries (topology passes, projection, normal fits): a k-d tree over the
  // whole (static, centred) cloud, or for a large cloud with normals over a spatially even
  // subsample of it (ReconstructOptions::max_query_points), whose points and normals are then
  // kept side by side in tree order (query_points, subsample.normals: no scattered reads in the
  // cloud).
  std::unique_ptr<PointIndex> tree;
  // Subsampled: the tree's points and their input normals (OperationContext::query_points); else
  // empty.
  edgefront::PointCloud subsample;
  const std::vector<Vec3>* query_points = nullptr;  // the tree's points: the cloud's or the subsample's
  std::vector<PointIndex::Neighbor> knn;  // query scratch
  // Faces whose centroid is at least this many mean edge lengths from the nearest sample are
  // also removed when their normal is far from that sample's (|cos| < 0.35, BorderParams).
  double normal_gate = 0.3;
  std::vector<Vec3> fitted_normal;  // lazily fitted normals (inputs without normals)
  std::vector<double> fitted_residual;  // with quadric_normals: their fits' residuals (orient_normals' noise)
  bool oriented = false;  // orient_winners with input normals or orientable fitted ones (double_layer.h)
  bool encloses = false;  // oriented, and the oriented normals point outward as around a volume
  std::vector<Vec3> oriented_fitted;  // without input normals: the fitted normals, oriented

  Mesh mesh;
  detail::VertexGrid grid;
  std::vector<double> tau;  // scaled counters: true counter = tau * scale
  double scale = 1.0;
  double decay = 1.0;
  detail::CounterHeap order;  // the scaled counters of the live vertices, most active on top
  std::vector<std::uint64_t> last_win;
  std::vector<std::uint64_t> vstamp, fstamp;
  std::uint64_t clock = 1;
  size_t live = 0;
  // The mesh is renumbered in spatial order (memory locality of the basic step) when the live
  // vertex count reaches this; then at 1.5 times that count, and so on (reorder_if_due).
  size_t next_reorder_live = 2048;  // smaller meshes fit in the caches

  std::mt19937_64 rng;
  static constexpr size_t kNoSample = std::numeric_limits<size_t>::max();
  size_t next_sample = kNoSample;  // the sample of the next basic step, drawn ahead (basic_step)
  DrawSamples draw;  // the cloud's points with their oriented normals, for the basic step
  FixedModulo draw_mod;  // % cloud.size()
  std::uint64_t steps = 0;
  std::uint64_t next_collapse_scan = 0;
  size_t splits = 0, collapses = 0, faces_removed = 0, loops_merged = 0, slits_zipped = 0, holes_filled = 0, batches = 0;
  size_t splits_in_batch = 0;
  size_t topology_last_live = 0;
  double seconds_ops = 0, seconds_topology = 0;
  bool finished = false;
  StopReason finished_reason = StopReason::target_reached;

  struct Registered {
    std::shared_ptr<Operation> op;
    std::uint64_t last = 0;
    OperationReport report;
  };
  std::vector<Registered> ops;

  // Snapshot of face vertex triples for detecting what an operation re-connected.
  std::vector<std::array<int, 3>> face_snapshot;


  // ---------------------------------------------------------------- setup
  void init(edgefront::PointCloud points, const ReconstructOptions& options, const ProgressCallback& progress) {
    opt = options;
    const auto t_init = Clock::now();
    // The set-up phases report their start and end (Progress::phase); cancelling is not possible.
    auto report = [&](Phase phase, double fraction) {
      if (!progress) return;
      Progress p;
      p.phase = phase;
      p.phase_fraction = fraction;
      p.target_vertices = opt.target_vertices;
      p.seconds = seconds_since(t_init);
      (void)progress(p);
    };
    if (points.size() < 4)
      throw InvalidInput("gcs: at least 4 points are needed (got " + std::to_string(points.size()) + ")");
    for (size_t i = 0; i < points.size(); ++i) {
      const Vec3& p = points.points[i];
      if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
        throw InvalidInput("gcs: point " + std::to_string(i) + " has a NaN or infinite coordinate");
    }
    edgefront::check_coordinate_range(points.points, "gcs");
    if (!points.normals.empty() && points.normals.size() != points.points.size())
      throw InvalidInput("gcs: the cloud has " + std::to_string(points.normals.size()) + " normals for " +
                         std::to_string(points.points.size()) + " points");
    check_options(opt);
    Vec3 lo = points.points[0], hi = points.points[0];
    for (const Vec3& p : points.points) {
      lo.minimize(p);
      hi.maximize(p);
    }
    offset = (lo + hi) * 0.5;
    bbox_diagonal = (hi - lo).norm();
    if (!(bbox_diagonal > 1e-12 * std::max(1.0, offset.norm())))
      throw InvalidInput("gcs: all points coincide: there is no surface to reconstruct");
    // Repeated points would weigh their place several times in every k-nearest query (a plane whose
    // points were each written 3 times came out in 12 pieces): they are dropped. Each vertex needs
    // samples that it wins: above one vertex per distinct point the loop cannot hold the vertices
    // it adds (it collapses them as inactive) and runs into the step limit.
    if (const size_t repeated = drop_repeated_points(points); opt.target_vertices > points.size()) {
      const std::string count = repeated == 0 ? "number of points (" + std::to_string(points.size()) + ")"
                                              : "number of distinct points (" + std::to_string(points.size()) + "; " +
                                                    std::to_string(repeated) + " repeat an earlier one)";
      throw InvalidInput("gcs: target_vertices " + std::to_string(opt.target_vertices) + " is more than the " + count +
                         ": the samples cannot place that many vertices");
    }
    cloud = std::move(points);
    for (Vec3& p : cloud.points) p -= offset;
    if (!cloud.normals.empty() && std::any_of(cloud.normals.begin(), cloud.normals.end(), missing_normal)) {
      report(Phase::normal_fitting, 0);
      normals_filled = fill_missing_normals(cloud, normals_unusable);
      if (!normals_unusable) report(Phase::normal_fitting, 1);
    }
    if (std::isfinite(opt.smooth_noise_ratio) && cloud.size() >= 8) {
      report(Phase::noise_estimate, 0);
      const NoiseEstimate noise = estimate_noise(cloud, {.threads = opt.threads});
      noise_ratio = noise.ratio();
      report(Phase::noise_estimate, 0.5);
      if (noise_ratio > opt.smooth_noise_ratio) cloud_smoothed = smooth_noise(cloud, {.threads = opt.threads}) > 0;
      report(Phase::noise_estimate, 1);
    }
    // Collinear: the second principal extent vanishes.
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (const Vec3& p : cloud.points) {
      const Eigen::Vector3d q(p[0], p[1], p[2]);
      cov += q * q.transpose();
    }
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
    const Eigen::Vector3d ev = eig.eigenvalues();  // ascending
    if (!(ev[1] > 1e-14 * ev[2]))
      throw InvalidInput("gcs: all points lie on one line: there is no surface to reconstruct");

    // A large cloud with normals is queried through a subsample (max_query_points): then the
    // support distance of the topology is measured to the subsample, and the spacing (below) is
    // the subsample's. (Without normals, the normals are fitted to and oriented over all points.)
    const size_t query_limit =
        opt.max_query_points ? opt.max_query_points
                             : std::max<size_t>(kAutoQueryPoints, kAutoQueryPerVertex * opt.target_vertices);
    if (cloud.has_normals() && cloud.size() > query_limit) {
      build_subsampled_tree(query_limit);
    } else {
      if (cloud.size() >= kSpatialSortMinPoints) sort_cloud_spatially();
      tree = std::make_unique<PointIndex>(cloud.points);
      query_points = &cloud.points;
    }
    // Sample spacing: mean distance to the nearest other (distinct) point over up to 1000 points.
    {
      const std::vector<Vec3>& tp = *query_points;
      const size_t n = tp.size(), m = std::min<size_t>(n, 1000);
      double sum = 0;
      size_t cnt = 0;
      for (size_t k = 0; k < m; ++k) {
        const size_t i = k * n / m;
        tree->k_nearest(tp[i], 8, knn);
        for (const PointIndex::Neighbor& nb : knn) {
          if (nb.distance2 > 0) {
            sum += std::sqrt(nb.distance2);
            ++cnt;
            break;
          }
        }
      }
      sample_spacing = cnt ? sum / static_cast<double>(cnt) : bbox_diagonal * 1e-3;
    }

    oriented = opt.orient_winners && cloud.has_normals();
    if (opt.orient_winners && !cloud.has_normals()) {
      report(Phase::normal_fitting, 0);
      constexpr size_t kSteps = 20;  // progress reports while fitting
      for (size_t s = 0; s < kSteps; ++s) {
        for (size_t i = s * cloud.size() / kSteps; i < (s + 1) * cloud.size() / kSteps; ++i) point_normal(i);
        report(Phase::normal_fitting, 0.8 * static_cast<double>(s + 1) / kSteps);
      }
      oriented_fitted = fitted_normal;
      oriented = detail::orient_normals(cloud.points, *tree, oriented_fitted, 8,
                                        opt.quadric_normals ? &fitted_residual : nullptr, opt.quadric_normals);
      report(Phase::normal_fitting, 1);
    }
    if (oriented) {
      encloses = detail::normal_flux(cloud.points, cloud.has_normals() ? cloud.normals : oriented_fitted) > kEnclosingFlux;
    }
    draw_mod = FixedModulo(cloud.size());
    draw.assign(cloud.points, oriented ? (cloud.has_normals() ? &cloud.normals : &oriented_fitted) : nullptr);
    rng.seed(opt.seed);
    build_start_mesh(lo - offset, hi - offset);
    live = mesh.n_vertices();
    ensure_sizes();
    grid.reset(mean_edge_length());
    grid.resize(mesh.n_vertices());
    for (auto v : mesh.vertices()) {
      grid.insert(v.idx(), mesh.point(v));
      set_tau(v.idx(), 0.0);
      last_win[v.idx()] = 0;
    }
    update_decay();
    next_collapse_scan = collapse_window();
    opt.topology_min_vertices = std::min(opt.topology_min_vertices, opt.target_vertices / 2);
  }

  // A large cloud queried whole is put in spatial (Morton) order once: the kd-tree's leaves and
  // the nearest-sample queries of the topology passes (over faces that are in spatial order too,
  // see reorder_if_due) then touch far fewer cache lines. The samples are drawn uniformly by index,
  // so the draws keep their distribution. Small clouds fit in the cache and keep their order.
  static constexpr size_t kSpatialSortMinPoints = 65536;
  // ReconstructOptions::max_query_points = 0: max(kAutoQueryPoints, kAutoQueryPerVertex * target).
  static constexpr size_t kAutoQueryPoints = 100000, kAutoQueryPerVertex = 5;
  // The tree over a spatially even subsample of at most `limit` points: the cloud in a coarse
  // Morton order (cheaper than sort_cloud_spatially's, as good for the surface fit's walk over
  // the samples), then one point out of every run (detail::stride_subsample).
  void build_subsampled_tree(size_t limit) {
    permute_cloud(detail::coarse_morton_order(cloud.points));
    const std::vector<size_t> ids = detail::stride_subsample(cloud.size(), limit, opt.seed);
    subsample.points.resize(ids.size());
    subsample.normals.resize(ids.size());
    for (size_t k = 0; k < ids.size(); ++k) {
      subsample.points[k] = cloud.points[ids[k]];
      subsample.normals[k] = cloud.normals[ids[k]];
    }
    tree = std::make_unique<PointIndex>(subsample.points);
    query_points = &tree->points();
  }

  void sort_cloud_spatially() { permute_cloud(detail::morton_order(cloud.points)); }
  void permute_cloud(const std::vector<size_t>& perm) {
    std::vector<Vec3> sorted(cloud.size());
    for (size_t k = 0; k < perm.size(); ++k) sorted[k] = cloud.points[perm[k]];
    cloud.points.swap(sorted);
    if (cloud.has_normals()) {
      for (size_t k = 0; k < perm.size(); ++k) sorted[k] = cloud.normals[perm[k]];
      cloud.normals.swap(sorted);
    }
  }

  void build_start_mesh(Vec3 lo, Vec3 hi) {
    // Pad thin directions (a planar cloud still gets a solid start) and grow by 2%.
    const double min_extent = 0.05 * bbox_diagonal;
    for (int a = 0; a < 3; ++a) {
      const double ext = hi[a] - lo[a];
      const double pad = 0.02 * ext + 0.5 * std::max(0.0, min_extent - ext);
      lo[a] -= pad;
      hi[a] += pad;
    }
    std::vector<VertexHandle> vh;
    if (opt.start == StartShape::box) {
      for (int i = 0; i < 8; ++i)
        vh.push_back(mesh.add_vertex(Vec3(i & 1 ? hi[0] : lo[0], i & 2 ? hi[1] : lo[1], i & 4 ? hi[2] : lo[2])));
      const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
      for (const auto& q : quads) {
        mesh.add_face(vh[q[0]], vh[q[1]], vh[q[2]]);
        mesh.add_face(vh[q[0]], vh[q[2]], vh[q[3]]);
      }
    } else {
      const Vec3 c = (lo + hi) * 0.5, e = (hi - lo) * 0.5 * 1.8;  // the tetrahedron contains the box
      const int s[4][3] = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
      for (const auto& k : s) vh.push_back(mesh.add_vertex(c + Vec3(k[0] * e[0], k[1] * e[1], k[2] * e[2])));
      // Orientation fixed below by the signed volume.
      mesh.add_face(vh[0], vh[1], vh[2]);
      mesh.add_face(vh[0], vh[3], vh[1]);
      mesh.add_face(vh[0], vh[2], vh[3]);
      mesh.add_face(vh[1], vh[3], vh[2]);
    }
    double vol = 0;
    for (auto f : mesh.faces()) {
      auto it = mesh.cfv_iter(f);
      const Vec3 a = mesh.point(*it), b = mesh.point(*++it), c = mesh.point(*++it);
      vol += (a | (b % c));
    }
    EF_CHECK(mesh.n_faces() > 0 && vol > 0, "start mesh is not outward oriented");
  }

  // ---------------------------------------------------------------- bookkeeping
  void ensure_sizes() {
    const size_t nv = mesh.n_vertices(), nf = mesh.n_faces();
    if (tau.size() < nv) {
      tau.resize(nv, -1.0);  // -1: not in `order`
      last_win.resize(nv, steps);
      vstamp.resize(nv, clock);
      grid.resize(nv);
      neighbors.resize(nv);
    }
    if (fstamp.size() < nf) fstamp.resize(nf, clock);
  }

  void set_tau(int v, double true_value) {
    tau[v] = true_value / scale;
    order.set(v, tau[v]);
  }
  double true_tau(int v) const { return tau[v] * scale; }
  void drop_tau(int v) {
    order.erase(v);
    tau[v] = -1.0;
  }
  void update_decay() {
    decay = std::pow(0.5, 1.0 / (opt.decay_half_life * static_cast<double>(std::max<size_t>(live, 1))));
  }
  std::uint64_t collapse_window() const {
    return static_cast<std::uint64_t>(std::ceil(opt.inactivity_window * static_cast<double>(live)));
  }
  void renormalize() {
    for (size_t v = 0; v < tau.size(); ++v)
      if (tau[v] >= 0) tau[v] *= scale;
    order.scale_all(scale);
    scale = 1.0;
  }
  void stamp(VertexHandle v) { vstamp[v.idx()] = clock; }
  void stamp_ring(VertexHandle v) {
    stamp(v);
    for (auto u : mesh.vv_range(v)) stamp(u);
  }

  double mean_edge_length() const {
    double sum = 0;
    size_t n = 0;
    for (auto e : mesh.edges()) {
      sum += mesh.calc_edge_length(e);
      ++n;
    }
    return n ? sum / static_cast<double>(n) : bbox_diagonal * 0.1;
  }

  // The input normal of point i, or (without input normals) its fitted normal: with
  // quadric_normals fit_normals' (cloud_normals.h), all fitted on first use; else the normal of a
  // plane fitted to its 20 nearest points, computed once on first use, NaN where the neighbourhood
  // is not flat. Either is unsigned, NaN where undefined. (A cloud without normals is never
  // subsampled: the tree indices are cloud indices here.)
  const Vec3& point_normal(size_t i) {
    if (cloud.has_normals()) return cloud.normals[i];
    if (opt.quadric_normals) {
      if (fitted_normal.empty()) fitted_normal = fit_normals(cloud.points, *tree, {.threads = opt.threads}, &fitted_residual);
      return fitted_normal[i];
    }
    if (fitted_normal.empty()) fitted_normal.assign(cloud.size(), Vec3(0, 0, 0));
    Vec3& n = fitted_normal[i];
    if (n.sqrnorm() > 0 || std::isnan(n[0])) return n;
    tree->k_nearest(cloud.points[i], 20, knn);
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(neighbour_scatter(cloud.points, knn));
    const Eigen::Vector3d e = eig.eigenvectors().col(0);
    const Eigen::Vector3d ev = eig.eigenvalues();
    // Not flat enough (noise comparable to the spacing): no usable normal (marked by a NaN).
    if (!(ev[0] < 0.05 * ev[1])) {
      n = Vec3(std::numeric_limits<double>::quiet_NaN(), 0, 0);
      return n;
    }
    n = Vec3(e[0], e[1], e[2]);
    if (!(n.sqrnorm() > 0.5)) n = Vec3(std::numeric_limits<double>::quiet_NaN(), 0, 0);
    return n;
  }

  const Vec3& oriented_normal(size_t i) const { return cloud.has_normals() ? cloud.normals[i] : oriented_fitted[i]; }

  // The normal of tree point k: point_normal (the input or the fitted one) for cloud_query,
  // oriented_normal for the others; both are the input normal in a subsample.
  const Vec3& query_point_normal(size_t k) {
    return subsample.empty() ? point_normal(k) : subsample.normals[k];
  }
  const Vec3& query_oriented_normal(size_t k) const {
    return subsample.empty() ? oriented_normal(k) : subsample.normals[k];
  }

  // The part of the searched cloud (detail::cloud_parts) that tree point k lies on; the parts
  // are found on the first call (only a pass that would remove a piece asks).
  std::vector<int> query_parts;
  int query_point_part(size_t k) {
    if (query_parts.empty()) query_parts = detail::cloud_parts(*query_points, *tree);
    return query_parts[k];
  }

  detail::CloudHit cloud_query(const Vec3& p) {
    const PointIndex::Neighbor nb = tree->nearest(p);
    return {std::sqrt(nb.distance2), query_point_normal(nb.index), (*query_points)[nb.index], nb.index};
  }

  // The k samples nearest to p with their oriented normals (the film test of the border creation).
  std::vector<PointIndex::Neighbor> knn_oriented;  // its scratch (point_normal uses knn)
  void oriented_neighbors(const Vec3& p, size_t k, std::vector<detail::CloudHit>& out) {
    tree->k_nearest(p, k, knn_oriented);
    out.clear();
    for (const PointIndex::Neighbor& nb : knn_oriented)
      out.push_back({std::sqrt(nb.distance2), query_oriented_normal(nb.index), (*query_points)[nb.index], nb.index});
  }

  // ---------------------------------------------------------------- geometry helpers
  double mean_adjacent_edge_length(VertexHandle v) const {
    double s = 0;
    int k = 0;
    for (auto h : mesh.voh_range(v)) {
      s += mesh.calc_edge_length(h);
      ++k;
    }
    return k ? s / k : 0.0;
  }

  // ---------------------------------------------------------------- the basic step
  void basic_step() {
    // The samples are drawn one step ahead (the same sequence) so that the next one's point and
    // normal can be fetched from memory while this step runs (a large cloud is far bigger than
    // the caches).
    if (next_sample == kNoSample) next_sample = static_cast<size_t>(draw_mod(rng()));
    const size_t si = next_sample;
    next_sample = static_cast<size_t>(draw_mod(rng()));
    __builtin_prefetch(&draw[next_sample]);
    __builtin_prefetch(reinterpret_cast<const char*>(&draw[next_sample]) + sizeof(DrawSample) - 1);
    const Vec3& s = draw[si].point;
    int wi = grid.nearest(s);
    EF_CHECK(wi >= 0, "the mesh has no vertex");
    const bool smooth = opt.neighbor_rate > 0 && opt.smoothing_iterations > 0;
    // Facing the sample's side once the mesh hugs the cloud (detail/double_layer.h): the nearest
    // vertex wins when its normal agrees with the sample's (the normal summed over the ring just
    // gathered, as detail::vertex_normal_sum would), otherwise detail::oriented_nearest_after picks.
    const bool facing = oriented && live >= opt.topology_min_vertices;
    if (smooth || facing) gather_ring(VertexHandle(wi));
    if (facing && !((ring_normal_sum(wi) | draw[si].normal) > 0)) {
      // Skipping unfaced samples (ReconstructOptions::skip_unfaced_samples), the search goes wider:
      // the missing layer's border vertices must be found to grow it back.
      const bool skip = opt.skip_unfaced_samples && cloud.has_normals();
      const int other = detail::oriented_nearest_after(mesh, grid, s, draw[si].normal, wi, skip ? 32 : 8,
                                                       (skip ? 4 : 2) * grid.cell_size());
      if (other == wi && skip) {  // no vertex nearby faces the sample's side
        end_step();
        return;
      }
      if (other != wi) {
        wi = other;
        gather_ring(VertexHandle(wi));
      }
    }
    const VertexHandle w(wi);
    mesh.point(w) += opt.winner_rate * (s - mesh.point(w));
    grid.move(wi, mesh.point(w));
    stamp(w);
    if (smooth) {
      // The passes update the mesh positions in place (member by member, as in the paper's loop).
      Vec3* const pos = &mesh.point(VertexHandle(0));
      for (int it = 0; it < opt.smoothing_iterations; ++it) {
        if (it == 0) {
          for (RingCache::Member& m : ring.members) smooth_member_first(pos, m);
        } else {
          for (const RingCache::Member& m : ring.members) smooth_member(pos, m);
        }
      }
      for (const RingCache::Member& m : ring.members) {
        grid.move(m.vid, pos[m.vid]);
        vstamp[static_cast<size_t>(m.vid)] = clock;
      }
    }
    tau[wi] += 1.0 / scale;
    order.set(wi, tau[wi]);
    last_win[wi] = steps;
    end_step();
  }
  // The global decay of every basic step (with or without a winner).
  void end_step() {
    scale *= decay;
    if (scale < 1e-150) renormalize();
    ++steps;
  }

  // The winner's 1-ring (the members) with the ring of each member, gathered once per basic step
  // as vertex ids, so that the smoothing passes run over two small arrays instead of re-walking
  // the halfedge structure. The rings are read from the neighbour cache (one line per vertex).
  struct RingCache {
    struct Member {
      int vid;               // the member's vertex id
      int begin, end;        // its neighbours: entries [begin, end)
      int border_a = -1;     // border members: the two border neighbours (vertex ids)
      int border_b = -1;
      bool winner_face = false;  // the winner's outgoing halfedge to this member has a face
      double inv_k = 0;      // 1 / (end - begin)
      double n0 = 0, n1 = 0, n2 = 0;  // its normal for this basic step (smooth_member_first)
      double inv_nn = 0;              // 1 / |n|^2, 0 without a usable normal
    };
    struct Entry {
      int a;  // neighbour, in outgoing-halfedge order
      int b;  // the next vertex of the face of that halfedge, -1 at a border
    };
    std::vector<Member> members;
    std::vector<Entry> entries;
  } ring;
  detail::NeighborCache neighbors;
  // Rings longer than the cache holds, walked (neighbour ids and face flags in voh order).
  struct WalkedRing {
    std::vector<int> nb;
    std::vector<char> face;
  } walked_winner, walked_member;

  // v's neighbours in the order of mesh.voh_range(v) and whether each outgoing halfedge has a
  // face: from the neighbour cache, or walked into `scratch` for rings it does not hold.
  template <class F>
  void with_ring(VertexHandle v, WalkedRing& scratch, F&& f) {
    if (const detail::NeighborCache::Line* l = neighbors.get(mesh, v)) {
      f(static_cast<int>(l->count), l->nb, [l](int e) { return l->has_face(e); });
      return;
    }
    scratch.nb.clear();
    scratch.face.clear();
    for (auto h : mesh.voh_range(v)) {
      scratch.nb.push_back(mesh.to_vertex_handle(h).idx());
      scratch.face.push_back(mesh.face_handle(h).is_valid() ? 1 : 0);
    }
    const char* face = scratch.face.data();
    f(static_cast<int>(scratch.nb.size()), scratch.nb.data(), [face](int e) { return face[e] != 0; });
  }

  void gather_ring(VertexHandle w) {
    ring.members.clear();
    with_ring(w, walked_winner, [&](int count, const int* wnb, auto winner_face) {
      // The members' lines and positions are fetched together (independent misses overlap).
      for (int i = 0; i < count; ++i) {
        neighbors.prefetch(wnb[i]);
        __builtin_prefetch(&mesh.point(VertexHandle(wnb[i])));
      }
      int n = 0;  // entries used
      for (int i = 0; i < count; ++i) {
        RingCache::Member m{wnb[i], n, 0};
        m.winner_face = winner_face(i);
        // Around v, the face of outgoing halfedge e (v, a_e, b_e) is the face on the far side of
        // halfedge e - 1 in this clockwise order, so b_e = a_(e-1) (cyclically: the first entry's
        // is the last neighbour). At a border halfedge (no face) b_e = -1, and the border
        // neighbours are a_e and a_(e-1) (the end of the incoming border halfedge); with several
        // border halfedges, the last one counts.
        with_ring(VertexHandle(m.vid), walked_member, [&](int k, const int* nb, auto has_face) {
          if (static_cast<size_t>(n + k) > ring.entries.size()) ring.entries.resize(2 * ring.entries.size() + static_cast<size_t>(k) + 64);
          RingCache::Entry* const out = ring.entries.data() + n;
          int border_e = -1;
          for (int e = 0; e < k; ++e) {
            __builtin_prefetch(&mesh.point(VertexHandle(nb[e])));
            const bool f = has_face(e);
            if (!f) border_e = e;
            out[e] = {nb[e], f ? nb[e == 0 ? k - 1 : e - 1] : -1};
          }
          n += k;
          m.end = n;
          if (k > 0) m.inv_k = 1.0 / static_cast<double>(k);
          if (border_e >= 0) {
            m.border_a = nb[border_e];
            m.border_b = nb[border_e == 0 ? k - 1 : border_e - 1];
          }
        });
        ring.members.push_back(m);
      }
    });
  }

  // The winner's area-weighted normal (detail::vertex_normal_sum: the same sum in the same order)
  // from the ring gathered for it, at the current positions.
  Vec3 ring_normal_sum(int wi) const {
    Vec3 n(0, 0, 0);
    const Vec3& x = mesh.point(VertexHandle(wi));
    const size_t k = ring.members.size();
    for (size_t i = 0; i < k; ++i) {
      if (!ring.members[i].winner_face) continue;
      const Vec3& a = mesh.point(VertexHandle(ring.members[i].vid));
      const Vec3& b = mesh.point(VertexHandle(ring.members[i == 0 ? k - 1 : i - 1].vid));
      n += (a - x) % (b - x);
    }
    return n;
  }

  // The tangential Laplacian update of ring member m (border vertices: along the border only):
  // the ring mean minus the vertex, without its component along the member's area-weighted
  // normal n: L_t = L - (L.n / n.n) n (no square root). The normal is computed in the first pass
  // of a basic step (smooth_member_first) and kept for the other passes: a pass moves the members
  // by 5% of their Laplacian, which turns the normal by a small fraction of a degree, so the
  // recomputation bought nothing measurable (bench/results/gcs.md, session 6) at about half of the
  // smoothing's cost. On scalars so that the compiler keeps the values in registers; `pos` is the
  // mesh's position array.
  void smooth_member(Vec3* pos, const RingCache::Member& m) const {
    if (m.end <= m.begin) return;
    Vec3& x = pos[m.vid];
    const double x0 = x[0], x1 = x[1], x2 = x[2];
    double l0, l1, l2;
    if (m.border_a >= 0) {
      const Vec3& a = pos[m.border_a];
      const Vec3& b = pos[m.border_b];
      l0 = (a[0] + b[0]) * 0.5 - x0;
      l1 = (a[1] + b[1]) * 0.5 - x1;
      l2 = (a[2] + b[2]) * 0.5 - x2;
    } else {
      double s0 = 0, s1 = 0, s2 = 0;
      const RingCache::Entry* const entries = ring.entries.data();
      for (int e = m.begin; e < m.end; ++e) {
        const Vec3& a = pos[entries[e].a];
        s0 += a[0];
        s1 += a[1];
        s2 += a[2];
      }
      l0 = s0 * m.inv_k - x0;
      l1 = s1 * m.inv_k - x1;
      l2 = s2 * m.inv_k - x2;
    }
    const double d = (l0 * m.n0 + l1 * m.n1 + l2 * m.n2) * m.inv_nn;
    x[0] = x0 + opt.neighbor_rate * (l0 - d * m.n0);
    x[1] = x1 + opt.neighbor_rate * (l1 - d * m.n1);
    x[2] = x2 + opt.neighbor_rate * (l2 - d * m.n2);
  }

  // The first pass: computes and keeps m's normal (sum over its faces of the cross products, taken
  // relative to the member), then updates it as above.
  void smooth_member_first(Vec3* pos, RingCache::Member& m) const {
    if (m.end <= m.begin) return;
    const double x0 = pos[m.vid][0], x1 = pos[m.vid][1], x2 = pos[m.vid][2];
    double n0 = 0, n1 = 0, n2 = 0;
    const RingCache::Entry* const entries = ring.entries.data();
    for (int e = m.begin; e < m.end; ++e) {
      const RingCache::Entry en = entries[e];
      if (en.b < 0) continue;
      const double u0 = pos[en.a][0] - x0, u1 = pos[en.a][1] - x1, u2 = pos[en.a][2] - x2;
      const double v0 = pos[en.b][0] - x0, v1 = pos[en.b][1] - x1, v2 = pos[en.b][2] - x2;
      n0 += u1 * v2 - u2 * v1;
      n1 += u2 * v0 - u0 * v2;
      n2 += u0 * v1 - u1 * v0;
    }
    const double nn = n0 * n0 + n1 * n1 + n2 * n2;
    const double inv_nn = nn > 0 ? 1.0 / nn : 0.0;
    // No usable normal (degenerate faces, or a square that overflows): the plain Laplacian.
    const bool usable = std::isfinite(inv_nn) && std::isfinite(nn);
    m.n0 = usable ? n0 : 0.0;
    m.n1 = usable ? n1 : 0.0;
    m.n2 = usable ? n2 : 0.0;
    m.inv_nn = usable ? inv_nn : 0.0;
    smooth_member(pos, m);
  }

  // ---------------------------------------------------------------- vertex split
  // mesh.valence(x) and mesh.is_boundary(x) (whether x's outgoing halfedge has no face) from the
  // neighbour cache.
  unsigned valence_of(VertexHandle x) {
    const detail::NeighborCache::Line* l = neighbors.get(mesh, x);
    return l ? l->count : static_cast<unsigned>(mesh.valence(x));
  }
  bool border_of(VertexHandle x) {
    const detail::NeighborCache::Line* l = neighbors.get(mesh, x);
    return l ? !(l->count > 0 && l->has_face(0)) : mesh.is_boundary(x);
  }

  bool flip_geometry_ok(EdgeHandle e) const {
    const HalfedgeHandle h0 = mesh.halfedge_handle(e, 0), h1 = mesh.halfedge_handle(e, 1);
    const Vec3& p = mesh.point(mesh.from_vertex_handle(h0));
    const Vec3& q = mesh.point(mesh.to_vertex_handle(h0));
    const Vec3& r = mesh.point(mesh.to_vertex_handle(mesh.next_halfedge_handle(h0)));
    const Vec3& s = mesh.point(mesh.to_vertex_handle(mesh.next_halfedge_handle(h1)));
    const Vec3 n_old = face_normal_of(p, q, r).normalized() + face_normal_of(q, p, s).normalized();
    const Vec3 n1 = face_normal_of(p, s, r), n2 = face_normal_of(s, q, r);
    return (n1 | n_old) > 0 && (n2 | n_old) > 0 && n1.norm() > 0 && n2.norm() > 0;
  }

  // Flips the edge of `h` (which runs between v and a neighbour) so that m gains a neighbour.
  bool try_flip(HalfedgeHandle h) {
    const EdgeHandle e = mesh.edge_handle(h);
    if (mesh.is_boundary(e) || !mesh.is_flip_ok(e)) return false;
    const VertexHandle a = mesh.from_vertex_handle(h) , b = mesh.to_vertex_handle(h);
    // Neither end may drop below valence 3 (interior) / 2 (border).
    for (const VertexHandle x : {a, b}) {
      if (valence_of(x) <= (border_of(x) ? 2u : 3u)) return false;
    }
    if (!flip_geometry_ok(e)) return false;
    const VertexHandle r = mesh.to_vertex_handle(mesh.next_halfedge_handle(mesh.halfedge_handle(e, 0)));
    const VertexHandle s = mesh.to_vertex_handle(mesh.next_halfedge_handle(mesh.halfedge_handle(e, 1)));
    mesh.flip(e);
    for (const VertexHandle x : {a, b, r, s}) {
      stamp(x);
      neighbors.invalidate(x.idx());
    }
    return true;
  }

  // Valence-driven edge flips on the edges at v and m (a design addition to the paper's split,
  // which alone leaves about a quarter of the vertices at valence 6 on a sphere): an edge is
  // flipped when that lowers the squared deviation of its four vertices from the ideal valence
  // (6 inside, 4 on a border), the two triangles are nearly coplanar and none folds.
  void improve_valences(VertexHandle v, VertexHandle m) {
    const auto dev = [&](VertexHandle x, int delta) {
      const int ideal = border_of(x) ? 4 : 6;
      const int d = static_cast<int>(valence_of(x)) + delta - ideal;
      return d * d;
    };
    std::vector<EdgeHandle> edges;
    for (int pass = 0; pass < 3; ++pass) {
      edges.clear();
      for (const VertexHandle c : {v, m}) {
        for (auto h : mesh.voh_range(c)) {
          for (auto g : mesh.voh_range(mesh.to_vertex_handle(h))) edges.push_back(mesh.edge_handle(g));
        }
      }
      std::sort(edges.begin(), edges.end());
      edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
      bool flipped = false;
      for (const EdgeHandle e : edges) {
        if (mesh.status(e).deleted() || mesh.is_boundary(e)) continue;
        const HalfedgeHandle h0 = mesh.halfedge_handle(e, 0), h1 = mesh.halfedge_handle(e, 1);
        const VertexHandle p = mesh.from_vertex_handle(h0), q = mesh.to_vertex_handle(h0);
        const VertexHandle r = mesh.to_vertex_handle(mesh.next_halfedge_handle(h0));
        const VertexHandle s = mesh.to_vertex_handle(mesh.next_halfedge_handle(h1));
        const int before = dev(p, 0) + dev(q, 0) + dev(r, 0) + dev(s, 0);
        const int after = dev(p, -1) + dev(q, -1) + dev(r, 1) + dev(s, 1);
        if (after >= before) continue;
        const Vec3 n0 = face_normal_of(mesh.point(p), mesh.point(q), mesh.point(r)).normalized();
        const Vec3 n1 = face_normal_of(mesh.point(q), mesh.point(p), mesh.point(s)).normalized();
        if ((n0 | n1) < 0.8) continue;  // keep creases
        if (try_flip(h0)) flipped = true;
      }
      if (!flipped) break;
    }
  }

  void split_most_active() {
    EF_CHECK(!order.empty(), "no vertex to split");
    const VertexHandle v(order.top());
    HalfedgeHandle longest;
    double best = -1;
    int best_to = std::numeric_limits<int>::max();
    for (auto h : mesh.voh_range(v)) {
      const double l = mesh.calc_edge_sqr_length(h);
      const int to = mesh.to_vertex_handle(h).idx();
      if (l > best || (l == best && to < best_to)) {
        best = l;
        best_to = to;
        longest = h;
      }
    }
    EF_CHECK(longest.is_valid(), "the most active vertex has no edge");
    const VertexHandle u = mesh.to_vertex_handle(longest);
    const Vec3 mid = (mesh.point(v) + mesh.point(u)) * 0.5;
    const VertexHandle m = mesh.split(mesh.edge_handle(longest), mid);
    ensure_sizes();
    neighbors.invalidate(m.idx());  // and its ring: v, u and the two opposite corners
    for (auto x : mesh.vv_range(m)) neighbors.invalidate(x.idx());
    // Walk equally both ways from the split edge: each flip moves one neighbour of v to m.
    bool left_ok = true, right_ok = true;
    for (bool left = true; (left_ok || right_ok) && valence_of(v) > valence_of(m) + 1; left = !left) {
      if (left && left_ok) {
        const HalfedgeHandle h = mesh.find_halfedge(v, m);
        left_ok = mesh.face_handle(h).is_valid() &&
                  try_flip(mesh.prev_halfedge_handle(h));  // edge (a, v) of face (v, m, a)
      } else if (!left && right_ok) {
        const HalfedgeHandle h = mesh.find_halfedge(m, v);
        right_ok = mesh.face_handle(h).is_valid() &&
                   try_flip(mesh.next_halfedge_handle(h));  // edge (v, b) of face (m, v, b)
      }
    }
    improve_valences(v, m);
    stamp_ring(v);
    stamp_ring(m);
    // Share v's counter in proportion to the vertices' areas.
    const double av = std::pow(mean_adjacent_edge_length(v), 2), am = std::pow(mean_adjacent_edge_length(m), 2);
    const double t = true_tau(v.idx());
    const double share = (av + am) > 0 ? av / (av + am) : 0.5;
    set_tau(v.idx(), t * share);
    set_tau(m.idx(), t * (1 - share));
    last_win[m.idx()] = steps;
    grid.insert(m.idx(), mesh.point(m));
    ++live;
    ++splits;
    update_decay();
    reorder_if_due();
  }

  // Splits append vertices, edges and faces at the ends of the mesh's arrays, so a vertex's ring
  // spreads over memory as the mesh grows; renumbering the mesh in spatial order (Morton) brings
  // it back together (fewer cache misses per basic step on large meshes). Registered operations
  // may keep handles between their calls: only when all of them can follow (operation.h), and they
  // get the maps. Also drops the deleted elements.
  void reorder_if_due() {
    if (live < next_reorder_live) return;
    for (const Registered& r : ops)
      if (!r.op->can_follow_renumbering()) return;  // asked again at the next split
    next_reorder_live = live + live / 2;
    const MeshRenumbering map = detail::renumber_spatially(mesh);
    const size_t nv = mesh.n_vertices(), nf = mesh.n_faces();
    std::vector<double> new_tau(nv, -1.0);
    std::vector<std::uint64_t> new_last_win(nv, steps), new_vstamp(nv, clock), new_fstamp(nf, clock);
    for (size_t i = 0; i < map.vertex.size(); ++i) {
      const int n = map.vertex[i];
      if (n < 0) continue;
      new_tau[n] = tau[i];
      new_last_win[n] = last_win[i];
      new_vstamp[n] = vstamp[i];
    }
    std::vector<std::array<int, 3>> new_snapshot(nf, {-1, -1, -1});
    for (size_t i = 0; i < map.face.size(); ++i) {
      const int n = map.face[i];
      if (n < 0) continue;
      new_fstamp[n] = fstamp[i];
      if (i < face_snapshot.size() && face_snapshot[i][0] >= 0)
        for (int k = 0; k < 3; ++k) new_snapshot[n][k] = map.vertex[face_snapshot[i][k]];
    }
    tau = std::move(new_tau);
    last_win = std::move(new_last_win);
    vstamp = std::move(new_vstamp);
    fstamp = std::move(new_fstamp);
    face_snapshot = std::move(new_snapshot);
    neighbors.invalidate_all();
    neighbors.resize(nv);
    order.clear();
    grid.reset(grid.cell_size());
    grid.resize(nv);
    for (size_t i = 0; i < nv; ++i) {
      EF_CHECK(tau[i] >= 0, "reorder: a live vertex had no counter");
      order.set(static_cast<int>(i), tau[i]);
      grid.insert(static_cast<int>(i), mesh.point(VertexHandle(static_cast<int>(i))));
    }
    for (Registered& r : ops) r.op->on_renumbered(mesh, map);
  }

  // ---------------------------------------------------------------- collapses
  double collapse_cost(HalfedgeHandle h) {
    const double a = valence_of(mesh.from_vertex_handle(h)), b = valence_of(mesh.to_vertex_handle(h));
    double sum = (a + b - 10) * (a + b - 10);
    for (const HalfedgeHandle g : std::array<HalfedgeHandle, 2>{h, mesh.opposite_halfedge_handle(h)}) {
      if (!mesh.face_handle(g).is_valid()) continue;
      const double c = valence_of(mesh.to_vertex_handle(mesh.next_halfedge_handle(g)));
      sum += (c - 7) * (c - 7);
    }
    return std::sqrt(sum) / 3.0;
  }

  bool collapse_geometry_ok(HalfedgeHandle h) const {
    const VertexHandle v0 = mesh.from_vertex_handle(h), v1 = mesh.to_vertex_handle(h);
    const Vec3& x0 = mesh.point(v0);
    const Vec3& x1 = mesh.point(v1);
    for (auto g : mesh.voh_range(v0)) {
      if (!mesh.face_handle(g).is_valid()) continue;
      const VertexHandle a = mesh.to_vertex_handle(g), b = mesh.to_vertex_handle(mesh.next_halfedge_handle(g));
      if (a == v1 || b == v1) continue;
      const Vec3 n_old = face_normal_of(x0, mesh.point(a), mesh.point(b));
      const Vec3 n_new = face_normal_of(x1, mesh.point(a), mesh.point(b));
      const double ln = n_new.norm(), lo = n_old.norm();
      if (!(ln > 1e-14 * bbox_diagonal * bbox_diagonal) || lo == 0) return false;
      if ((n_new | n_old) < 0.2 * ln * lo) return false;
    }
    return true;
  }

  bool try_collapse(VertexHandle v) {
    if (live <= 8) return false;
    const bool border = mesh.is_boundary(v);
    HalfedgeHandle best;
    double best_cost = std::numeric_limits<double>::infinity();
    for (auto h : mesh.voh_range(v)) {
      if (border && !mesh.is_boundary(mesh.edge_handle(h))) continue;
      const VertexHandle u = mesh.to_vertex_handle(h);
      if (valence_of(v) + valence_of(u) < 7) continue;  // would leave a valence-2 vertex
      bool opp_ok = true;
      for (const HalfedgeHandle g : std::array<HalfedgeHandle, 2>{h, mesh.opposite_halfedge_handle(h)}) {
        if (!mesh.face_handle(g).is_valid()) continue;
        const VertexHandle c = mesh.to_vertex_handle(mesh.next_halfedge_handle(g));
        if (valence_of(c) <= (border_of(c) ? 2u : 3u)) opp_ok = false;
      }
      if (!opp_ok) continue;
      const double cost = collapse_cost(h);
      if (cost < best_cost && mesh.is_collapse_ok(h) && collapse_geometry_ok(h)) {
        best_cost = cost;
        best = h;
      }
    }
    if (!best.is_valid()) return false;
    const VertexHandle u = mesh.to_vertex_handle(best);
    const double t = true_tau(v.idx());
    for (auto x : mesh.vv_range(v)) neighbors.invalidate(x.idx());  // u and v's other neighbours
    neighbors.invalidate(v.idx());
    mesh.collapse(best);
    drop_tau(v.idx());
    grid.remove(v.idx());
    set_tau(u.idx(), true_tau(u.idx()) + t);
    stamp_ring(u);
    --live;
    ++collapses;
    return true;
  }

  void collapse_inactive() {
    const std::uint64_t window = collapse_window();
    const size_t nv = mesh.n_vertices();
    for (size_t i = 0; i < nv; ++i) {
      const VertexHandle v(static_cast<int>(i));
      if (mesh.status(v).deleted() || tau[i] < 0) continue;
      if (last_win[i] + window >= steps) continue;
      try_collapse(v);
    }
    update_decay();
  }

  // ---------------------------------------------------------------- resync after foreign changes
  void snapshot_faces() {
    face_snapshot.assign(mesh.n_faces(), {-1, -1, -1});
    for (auto f : mesh.faces()) {
      auto it = mesh.cfv_iter(f);
      face_snapshot[f.idx()] = {it->idx(), (++it)->idx(), (++it)->idx()};
    }
  }

  // Brings counters, grid and stamps in line with a mesh changed by someone else.
  void resync() {
    // Keep the mesh manifold without isolated vertices (an operation may leave a bow tie).
    detail::clean_topology(mesh, 0);
    if (mesh.n_vertices() < tau.size() || mesh.n_faces() < fstamp.size()) {
      full_rebuild();
      return;
    }
    ensure_sizes();
    size_t n_live = 0;
    for (size_t i = 0; i < mesh.n_vertices(); ++i) {
      const VertexHandle v(static_cast<int>(i));
      const bool is_live = !mesh.status(v).deleted();
      if (!is_live) {
        if (grid.contains(static_cast<int>(i))) grid.remove(static_cast<int>(i));
        drop_tau(static_cast<int>(i));
        continue;
      }
      ++n_live;
      if (!grid.contains(static_cast<int>(i))) {
        grid.insert(static_cast<int>(i), mesh.point(v));
        set_tau(static_cast<int>(i), 0.0);
        last_win[i] = steps;
        stamp(v);
      } else if (grid.position(static_cast<int>(i)) != mesh.point(v)) {
        grid.move(static_cast<int>(i), mesh.point(v));
        stamp(v);
      }
    }
    for (size_t i = 0; i < mesh.n_faces(); ++i) {
      const FaceHandle f(static_cast<int>(i));
      const bool was = i < face_snapshot.size() && face_snapshot[i][0] >= 0;
      if (mesh.status(f).deleted()) {
        if (was)
          for (int k : face_snapshot[i]) {
            neighbors.invalidate(k);
            if (!mesh.status(VertexHandle(k)).deleted()) vstamp[k] = clock;
          }
        continue;
      }
      auto it = mesh.cfv_iter(f);
      const std::array<int, 3> now = {it->idx(), (++it)->idx(), (++it)->idx()};
      if (!was || now != face_snapshot[i]) {
        fstamp[i] = clock;
        for (int k : now) {
          vstamp[k] = clock;
          neighbors.invalidate(k);
        }
        if (was)
          for (int k : face_snapshot[i]) {
            neighbors.invalidate(k);
            if (!mesh.status(VertexHandle(k)).deleted()) vstamp[k] = clock;
          }
      }
    }
    live = n_live;
    update_decay();
    snapshot_faces();
  }

  void full_rebuild() {
    neighbors.invalidate_all();
    tau.assign(mesh.n_vertices(), -1.0);
    order.clear();
    scale = 1.0;
    last_win.assign(mesh.n_vertices(), steps);
    vstamp.assign(mesh.n_vertices(), clock);
    fstamp.assign(mesh.n_faces(), clock);
    grid.reset(grid.cell_size());
    grid.resize(mesh.n_vertices());
    live = 0;
    for (auto v : mesh.vertices()) {
      grid.insert(v.idx(), mesh.point(v));
      set_tau(v.idx(), 0.0);
      ++live;
    }
    update_decay();
    snapshot_faces();
  }

  // `target`: mean_edge_length() of the mesh as it is.
  void rebuild_grid_if_needed(double target) {
    if (target <= 0) return;
    const double ratio = grid.cell_size() / target;
    if (ratio > 0.5 && ratio < 2.0) return;
    grid.reset(target);
    for (auto v : mesh.vertices()) grid.insert(v.idx(), mesh.point(v));
  }

  // ---------------------------------------------------------------- batches
  ChangeSet changes_since(std::uint64_t last) const {
    ChangeSet cs;
    for (auto v : mesh.vertices())
      if (vstamp[v.idx()] > last) cs.vertices.push_back(v);
    for (auto f : mesh.faces()) {
      bool changed = fstamp[f.idx()] > last;
      for (auto v : mesh.fv_range(f)) changed = changed || vstamp[v.idx()] > last;
      if (changed) cs.faces.push_back(f);
    }
    return cs;
  }

  // A face farther than this from every sample is unsupported (ell: the mean edge length).
  double support_distance(double ell) const { return opt.unsupported_distance * std::max(ell, sample_spacing); }
  // Faces added across a border (loop merges, slit zips, hole fills) may lie up to 1.5 times as
  // far from the samples as a face may before it is removed: a hysteresis, so that the strip
  // across a sparsely sampled stretch is not refused by the test that tore it open.
  double bridge_distance(double ell) const { return 1.5 * support_distance(ell); }

  // `ell`: mean_edge_length() of the mesh as it is. Returns false when the pass was not due (the
  // mesh is then unchanged).
  bool topology_pass(bool force, double ell) {
    if (!opt.create_borders && !opt.merge_borders) return false;
    if (live < opt.topology_min_vertices) return false;
    if (!force && topology_last_live > 0 && static_cast<double>(live) < 1.1 * static_cast<double>(topology_last_live))
      return false;
    const auto t0 = Clock::now();
    topology_last_live = live;
    const double support = support_distance(ell);
    const double bridge = bridge_distance(ell);
    const detail::CloudQuery dist = [this](const Vec3& p) { return cloud_query(p); };
    const size_t trim_rings = opt.border_trim_rings;
    bool changed = false;
    const auto tally = [&changed](size_t& total, size_t n) {
      total += n;
      changed = changed || n > 0;
    };
    if (opt.create_borders) {
      detail::BorderParams bp;
      bp.max_support_distance = support;
      bp.max_edge_length = opt.long_edge_factor * ell;
      bp.min_component_faces = 8;
      bp.normal_check_distance = normal_gate * ell;
      bp.film_samples = encloses ? opt.film_samples : 0;
      // Both removals spare a piece lying on a part of the cloud of its own (a separate surface).
      const auto sample_part = [this](size_t k) { return query_point_part(k); };
      bp.sample_part = sample_part;
      // The support test's nearest sample per face goes on to the opposed-face test (same
      // centroids: nothing moves in between), with the sample's oriented normal.
      detail::FaceNearest nearest;
      tally(faces_removed, detail::remove_unsupported_faces(
                               mesh, dist, bp,
                               [this](const Vec3& p, size_t k, std::vector<detail::CloudHit>& out) {
                                 oriented_neighbors(p, k, out);
                               },
                               oriented ? &nearest : nullptr));
      if (oriented) {
        for (auto f : mesh.faces()) {
          detail::CloudHit& hit = nearest[static_cast<size_t>(f.idx())];
          if (hit.index != detail::CloudHit::kNoSample) hit.normal = query_oriented_normal(hit.index);
        }
        tally(faces_removed,
              detail::remove_opposed_faces(mesh, nearest, {.max_distance = support, .sample_part = sample_part}));
      }
    }
    if (opt.merge_borders) {
      detail::MergeParams mp;
      mp.mean_edge_length = ell;
      mp.max_support_distance = bridge;
      mp.max_trim_rings = trim_rings;
      tally(loops_merged, detail::merge_border_loops(mesh, dist, mp));
      // zip_slits zips within and across loops; otherwise torn-off pieces of an open sheet are
      // joined back (join_components: only across components).
      const bool join = !opt.zip_slits && opt.join_components && !encloses &&
                        edgefront::connected_components(mesh).count > 1;
      if (opt.zip_slits || join) {
        detail::ZipParams zp;
        zp.mean_edge_length = ell;
        zp.max_support_distance = bridge;
        zp.across_loops = join;
        zp.only_across_components = join;
        tally(slits_zipped, detail::zip_border_slits(mesh, dist, zp));
      }
    }
    if (opt.create_borders) {
      tally(holes_filled, detail::fill_small_holes(mesh, dist, kSmallHoleVertices, bridge, kFillNormalAgreement, {.rings = trim_rings, .max_loop_length = kTrimHoleEdges * ell}));
      if (opt.fill_slits_max_vertices > kSmallHoleVertices)
        tally(holes_filled, detail::fill_slit_holes(mesh, dist, kSmallHoleVertices + 1, opt.fill_slits_max_vertices,
                                                       bridge, kFillNormalAgreement,
                                                       trim_rings));
    }
    if (changed) resync();
    seconds_topology += seconds_since(t0);
    return true;
  }

  // Splits per batch at the current size (ReconstructOptions::batch_growth_vertices).
  size_t batch_size() const {
    const size_t g = opt.batch_growth_vertices;
    if (g == 0 || live <= g) return opt.batch_splits;
    return static_cast<size_t>(std::ceil(static_cast<double>(opt.batch_splits) * static_cast<double>(live) /
                                         static_cast<double>(g)));
  }

  void end_batch(bool final_call) {
    ++batches;
    splits_in_batch = 0;
    // The mean edge length (a pass over all edges) is computed again only where the mesh may
    // have changed.
    double ell = mean_edge_length();
    rebuild_grid_if_needed(ell);
    snapshot_faces();
    if (topology_pass(final_call, ell)) ell = mean_edge_length();
    ell = run_operations(final_call, ell);
    // The topology pass and the operations may change the mean edge length: with or without
    // operations registered, the grid is checked at the same point (an operation that changes
    // nothing leaves the run as it is without it).
    rebuild_grid_if_needed(ell);
  }

  // `ell`: mean_edge_length() of the mesh as it is; returns it after the operations.
  double run_operations(bool final_call, double ell) {
    if (ops.empty()) return ell;
    OperationContext ctx{cloud};
    ctx.query_points = subsample.empty() ? nullptr : &subsample;
    ctx.mean_edge_length = ell;
    ctx.bbox_diagonal = bbox_diagonal;
    ctx.target_vertices = opt.target_vertices;
    ctx.basic_steps = steps;
    ctx.batch = batches;
    ctx.final_call = final_call;
    for (Registered& r : ops) {
      ctx.live_vertices = live;
      const ChangeSet cs = changes_since(r.last);
      ++clock;
      const auto t0 = Clock::now();
      const OperationResult res = r.op->apply(mesh, cs, ctx);
      const double dt = seconds_since(t0);
      r.report.seconds += dt;
      seconds_ops += dt;
      ++r.report.calls;
      if (!res.summary.empty()) r.report.last_summary = res.summary;
      if (res.mesh_changed) {
        ++r.report.changes;
        resync();
        ctx.mean_edge_length = mean_edge_length();
      }
      r.last = clock;
      ++clock;
    }
    return ctx.mean_edge_length;
  }

  // `step(fraction)` is called before each post-processing step and at the end (may be empty).
  ReconstructResult make_result(double seconds, const std::function<void(double)>& step = {}) {
    ReconstructResult r;
    r.noise_ratio = noise_ratio;
    r.cloud_smoothed = cloud_smoothed;
    r.normals_filled = normals_filled;
    r.normals_unusable = normals_unusable;
    r.mesh = mesh;
    r.mesh.garbage_collection();
    auto report = [&](double fraction) {
      if (step) step(fraction);
    };
    // Post-processing of the copy only (the loop's own mesh stays as it is).
    const double ell = mean_edge_length();
    report(0);
    if (opt.project_to_samples) {
      detail::project_to_samples(r.mesh, [this](const Vec3& p) { return cloud_query(p); }, 0.5 * ell);
    }
    report(0.1);
    if (opt.delaunay_flips) {
      const auto t_flips = Clock::now();
      detail::delaunay_flips(r.mesh, kFlipMinDihedralCos, kFlipMaxPasses);
      r.seconds_fit += seconds_since(t_flips);
    }
    report(0.2);
    if (opt.fit_surface) {
      const auto t_fit = Clock::now();
      detail::SurfaceFitParams fp;
      fp.rounds = opt.fit_rounds;
      fp.smoothness = opt.fit_smoothness;
      fp.max_move = 0.5 * ell;
      fp.max_sample_distance = ell;
      fp.min_face_cos = std::cos(45.0 * std::numbers::pi / 180.0);
      fp.max_samples = 2 * r.mesh.n_vertices();  // cost: the big clouds (1M points) use an even stride
      // The samples' normals (input, or fitted and oriented) when the loop uses them: a sample is
      // fitted only by a face that faces its way (not by the other layer of a thin shell).
      fp.oriented_normals = true;
      fp.measure_after = false;
      const std::vector<Vec3> none;
      detail::fit_to_samples(r.mesh, cloud.points, !oriented ? none : cloud.has_normals() ? cloud.normals : oriented_fitted, fp);
      r.seconds_fit += seconds_since(t_fit);
    }
    report(0.6);
    if (opt.stacked_layer_rounds > 0 && r.mesh.n_faces() > 0) {
      const auto t_layers = Clock::now();
      twist::StackedLayerOptions so;
      so.rounds = opt.stacked_layer_rounds;
      const twist::StackedLayerReport layers = twist::remove_stacked_layers(r.mesh, so);
      r.stacked_faces_found = layers.pairs_before;
      r.stacked_faces_removed = layers.faces_removed;
      r.stacked_pleats_flattened = layers.pleats_flattened;
      if (r.stacked_faces_removed > 0) r.mesh.garbage_collection();
      r.seconds_fit += seconds_since(t_layers);
    }
    report(0.7);
    if (opt.resolve_self_intersections && r.mesh.n_faces() > 0) {
      const auto t_untangle = Clock::now();
      detail::UntangleParams up;
      up.max_move = 0.5 * ell;
      up.fill_support = bridge_distance(ell);  // as the topology pass's hole fills
      const detail::UntangleReport u = detail::untangle(r.mesh, [this](const Vec3& p) { return cloud_query(p); }, up);
      r.crossing_pairs_found = u.pairs_before;
      r.crossing_pairs_left = u.pairs_after;
      r.crossing_vertices_moved = u.vertices_moved;
      r.crossing_faces_removed = u.faces_removed;
      r.crossing_holes_filled = u.holes_filled;
      if (u.faces_removed > 0) r.mesh.garbage_collection();
      r.seconds_crossings = seconds_since(t_untangle);
      r.seconds_fit += r.seconds_crossings;
    }
    for (auto v : r.mesh.vertices()) r.mesh.point(v) += offset;
    r.mesh.update_face_normals();
    report(1);
    r.stop_reason = finished_reason;
    r.basic_steps = steps;
    r.splits = splits;
    r.collapses = collapses;
    r.faces_removed = faces_removed;
    r.loops_merged = loops_merged;
    r.slits_zipped = slits_zipped;
    r.holes_filled = holes_filled;
    r.batches = batches;
    r.seconds_total = seconds + r.seconds_fit;  // the flips and the fit run after the loop's clock stopped
    r.seconds_operations = seconds_ops;
    r.seconds_topology = seconds_topology;
    for (const Registered& reg : ops) r.operations.push_back(reg.report);
    return r;
  }

  ReconstructResult run(const ProgressCallback& progress) {
    const auto t0 = Clock::now();
    auto post = [&](double fraction) {
      if (!progress) return;
      Progress p;
      p.phase = Phase::post_processing;
      p.phase_fraction = fraction;
      p.vertices = live;
      p.target_vertices = opt.target_vertices;
      p.basic_steps = steps;
      p.seconds = seconds_since(t0);
      (void)progress(p);
    };
    if (finished) return make_result(0.0, post);
    const std::uint64_t step_limit =
        opt.max_steps_per_vertex == 0 ? std::numeric_limits<std::uint64_t>::max()
                                      : opt.max_steps_per_vertex * static_cast<std::uint64_t>(opt.target_vertices);
    size_t splits_since_progress = 0;
    auto report = [&]() {
      if (!progress) return true;
      Progress p;
      p.phase = Phase::growth;
      p.phase_fraction = opt.target_vertices ? std::min(1.0, static_cast<double>(live) / static_cast<double>(opt.target_vertices)) : 1.0;
      p.vertices = live;
      p.target_vertices = opt.target_vertices;
      p.basic_steps = steps;
      p.seconds = seconds_since(t0);
      return progress(p);
    };
    StopReason reason = StopReason::target_reached;
    // Operations on the final call (e.g. the twist repair cutting out a region) can shrink the
    // mesh below the target: then the loop grows it back and calls them again, a few times.
    // (The final border pass trims a few unsupported triangles: that much is not shrinking.)
    constexpr int kRegrowRounds = 3;
    auto shrunk = [&] { return static_cast<double>(live) < 0.9 * static_cast<double>(opt.target_vertices); };
    for (int round = 0;; ++round) {
    while (live < opt.target_vertices) {
      if (steps >= step_limit) {
        reason = StopReason::step_limit;
        break;
      }
      for (int i = 0; i < opt.steps_per_split; ++i) {
        basic_step();
        if (opt.inactivity_window > 0 && steps >= next_collapse_scan) {
          collapse_inactive();
          next_collapse_scan = steps + std::max<std::uint64_t>(1, collapse_window());
        }
      }
      split_most_active();
      if (++splits_in_batch >= batch_size()) end_batch(false);
      if (++splits_since_progress >= opt.progress_interval) {
        splits_since_progress = 0;
        if (!report()) {
          reason = StopReason::cancelled;
          break;
        }
      }
    }
    if (reason == StopReason::cancelled) break;
    end_batch(true);
    if (reason != StopReason::target_reached || !shrunk() || round + 1 >= kRegrowRounds) break;
    }
    if (reason == StopReason::target_reached && shrunk()) reason = StopReason::shrunk_by_operations;
    if (reason != StopReason::cancelled) {
      finished = true;
      finished_reason = reason;
      report();
    }
    // After a cancel the callback is not called again (the post-processing still runs, unreported).
    ReconstructResult r = make_result(seconds_since(t0), reason == StopReason::cancelled ? std::function<void(double)>() : post);
    r.stop_reason = reason;
    return r;
  }

  // ---------------------------------------------------------------- validation
  void validate() const {
    auto fail = [](const std::string& m) { throw edgefront::InternalError("gcs validate: " + m); };
    const size_t nv = mesh.n_vertices();
    if (tau.size() < nv || last_win.size() < nv || vstamp.size() < nv || grid.capacity() < nv)
      fail("per-vertex state is smaller than the mesh's vertex array");
    if (fstamp.size() < mesh.n_faces()) fail("per-face state is smaller than the mesh's face array");
    size_t n_live = 0;
    for (size_t i = 0; i < nv; ++i) {
      const VertexHandle v(static_cast<int>(i));
      const int id = static_cast<int>(i);
      if (mesh.status(v).deleted()) {
        if (grid.contains(id)) fail("deleted vertex " + std::to_string(i) + " is in the spatial grid");
        if (tau[i] >= 0) fail("deleted vertex " + std::to_string(i) + " has a signal counter");
        continue;
      }
      ++n_live;
      grid.check(id, mesh.point(v));
      if (!(tau[i] >= 0) || !std::isfinite(tau[i])) fail("vertex " + std::to_string(i) + " has no valid counter");
      if (!order.contains(id) || order.value(id) != tau[i])
        fail("vertex " + std::to_string(i) + " is missing from the counter order");
      if (!mesh.is_manifold(v)) fail("vertex " + std::to_string(i) + " is not manifold");
      if (mesh.valence(v) < 2) fail("vertex " + std::to_string(i) + " has valence " + std::to_string(mesh.valence(v)));
      const Vec3& p = mesh.point(v);
      if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
        fail("vertex " + std::to_string(i) + " has a non-finite position");
      std::vector<int> nb;
      for (auto u : mesh.vv_range(v)) {
        if (mesh.status(u).deleted()) fail("vertex " + std::to_string(i) + " has a deleted neighbour");
        nb.push_back(u.idx());
      }
      std::sort(nb.begin(), nb.end());
      if (std::adjacent_find(nb.begin(), nb.end()) != nb.end())
        fail("vertex " + std::to_string(i) + " has two edges to the same neighbour");
    }
    try {
      neighbors.check(mesh);
    } catch (const std::exception& e) {
      fail(e.what());
    }
    if (n_live != live) fail("live vertex count " + std::to_string(live) + " != mesh " + std::to_string(n_live));
    if (grid.size() != n_live) fail("spatial grid holds " + std::to_string(grid.size()) + " vertices, mesh has " + std::to_string(n_live));
    try {
      order.check();
    } catch (const std::exception& e) {
      fail(e.what());
    }
    if (order.size() != n_live) fail("counter order holds " + std::to_string(order.size()) + " vertices, mesh has " + std::to_string(n_live));
    for (auto f : mesh.faces()) {
      int k = 0;
      std::array<int, 3> vs{};
      for (auto h : mesh.fh_range(f)) {
        if (k == 3) fail("face " + std::to_string(f.idx()) + " is not a triangle");
        if (mesh.status(h).deleted()) fail("face " + std::to_string(f.idx()) + " has a deleted halfedge");
        if (mesh.face_handle(h) != f) fail("face " + std::to_string(f.idx()) + ": halfedge does not point back");
        if (mesh.next_halfedge_handle(mesh.prev_halfedge_handle(h)) != h) fail("face " + std::to_string(f.idx()) + ": prev/next links disagree");
        const VertexHandle v = mesh.to_vertex_handle(h);
        if (mesh.status(v).deleted()) fail("face " + std::to_string(f.idx()) + " uses a deleted vertex");
        vs[k++] = v.idx();
      }
      if (k != 3) fail("face " + std::to_string(f.idx()) + " is not a triangle");
      if (vs[0] == vs[1] || vs[1] == vs[2] || vs[0] == vs[2]) fail("face " + std::to_string(f.idx()) + " repeats a vertex");
    }
    for (auto h : mesh.halfedges()) {
      if (mesh.opposite_halfedge_handle(mesh.opposite_halfedge_handle(h)) != h) fail("halfedge opposite link broken");
      if (mesh.to_vertex_handle(mesh.opposite_halfedge_handle(h)) != mesh.from_vertex_handle(h)) fail("halfedge vertex link broken");
      if (mesh.is_boundary(h) && mesh.is_boundary(mesh.opposite_halfedge_handle(h))) fail("edge without faces");
    }
  }
};

Reconstructor::Reconstructor(edgefront::PointCloud points, const ReconstructOptions& options,
                             const ProgressCallback& progress)
    : impl_(std::make_unique<Impl>()) {
  impl_->init(std::move(points), options, progress);
}
Reconstructor::~Reconstructor() = default;

void Reconstructor::add_operation(std::shared_ptr<Operation> operation) {
  if (!operation) throw InvalidInput("gcs: add_operation needs an operation (got a null pointer)");
  Impl::Registered r;
  r.report.name = operation->name();
  r.op = std::move(operation);
  r.last = 0;
  impl_->ops.push_back(std::move(r));
}

ReconstructResult Reconstructor::run(const ProgressCallback& progress) { return impl_->run(progress); }
const Mesh& Reconstructor::mesh() const { return impl_->mesh; }
Vec3 Reconstructor::offset() const { return impl_->offset; }
void Reconstructor::validate() const { impl_->validate(); }
void Reconstructor::run_basic_steps(std::uint64_t n) {
  for (std::uint64_t i = 0; i < n; ++i) impl_->basic_step();
}

ReconstructResult reconstruct(edgefront::PointCloud points, const ReconstructOptions& options,
                              const ProgressCallback& progress) {
  Reconstructor r(std::move(points), options, progress);
  return r.run(progress);
}

size_t max_target_vertices(const edgefront::PointCloud& points) {
  edgefront::PointCloud copy;
  copy.points = points.points;
  drop_repeated_points(copy);
  return std::min<size_t>(copy.size(), 50'000'000);
}

}  // namespace gcs
