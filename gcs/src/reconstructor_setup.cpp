// gcs::Reconstructor, set-up and sampling: the input checks, repeated points, missing normals,
// noise smoothing, the nearest-sample query tree, the samples the basic step draws from, the start
// mesh, and the normals of the samples.
#include <algorithm>
#include <new>
#include <string>
#include <utility>

#include <Eigen/Dense>

#if defined(__linux__)
#include <sys/mman.h>
#endif

#include "detail/double_layer.h"
#include "detail/reconstructor_impl.h"
#include "detail/spatial_order.h"
#include "edgefront/coordinate_range.h"
#include "edgefront/error.h"
#include "gcs/cloud_noise.h"
#include "gcs/cloud_normals.h"

namespace gcs {

namespace {

// A missing input normal is the normal of the plane through its point's this many nearest points,
// oriented like the sum of the this many nearest given normals (fill_missing_normals): enough
// points for a stable plane at the sampling scale, few enough to stay local.
constexpr std::size_t kFillPlaneNeighbours = 16;
constexpr std::size_t kFillOrientNeighbours = 8;
// Without input normals (and without quadric_normals) a point's normal is the plane through its this
// many nearest points, undefined unless the plane's smallest eigenvalue is below this share of the
// middle one (not flat: noise comparable to the spacing, or two walls in one neighbourhood).
constexpr std::size_t kPlaneFitNeighbours = 20;
constexpr double kPlaneFitFlatness = 0.05;
// The sample spacing is the mean distance to the nearest other point over at most this many points.
constexpr std::size_t kSpacingProbes = 1000;
// The fitted normals are oriented over the graph of each point's this many nearest
// (detail::orient_normals).
constexpr std::size_t kOrientNeighbours = 8;
// The start mesh: directions thinner than this share of the bounding-box diagonal are padded to it
// (a planar cloud still gets a solid start), and every direction grows by this share of its extent.
constexpr double kStartMinExtent = 0.05;
constexpr double kStartPadding = 0.02;
// The start tetrahedron's half-extents are this many times the box's (it then contains the box).
constexpr double kTetrahedronScale = 1.8;

}  // namespace

namespace detail {

void DrawSamples::assign(const std::vector<Vec3>& points, const std::vector<Vec3>* normals) {
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

std::size_t drop_repeated_points(edgefront::PointCloud& c) {
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


}  // namespace detail

namespace {

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
    all.k_nearest(p, kFillPlaneNeighbours, knn);
    const Eigen::Matrix3d cov = neighbour_scatter(c.points, knn);
    given.k_nearest(p, kFillOrientNeighbours, knn);
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
  if (o.growth.steps_per_split < 1) fail("growth.steps_per_split must be >= 1");
  if (!(o.growth.winner_rate > 0 && o.growth.winner_rate <= 1)) fail("growth.winner_rate must be in (0, 1]");
  if (!(o.growth.neighbor_rate >= 0 && o.growth.neighbor_rate <= 1)) fail("growth.neighbor_rate must be in [0, 1]");
  if (o.growth.smoothing_iterations < 0 || o.growth.smoothing_iterations > 100) fail("growth.smoothing_iterations must be in [0, 100]");
  if (!(o.growth.decay_half_life > 0) || !std::isfinite(o.growth.decay_half_life)) fail("growth.decay_half_life must be positive");
  if (!(o.growth.inactivity_window >= 0) || !std::isfinite(o.growth.inactivity_window)) fail("growth.inactivity_window must be >= 0");
  if (o.growth.batch_splits < 1) fail("growth.batch_splits must be >= 1");
  if (!(o.topology.unsupported_distance > 0) || !std::isfinite(o.topology.unsupported_distance)) fail("topology.unsupported_distance must be positive");
  if (!(o.topology.long_edge_factor > 1) || !std::isfinite(o.topology.long_edge_factor)) fail("topology.long_edge_factor must be > 1");
  if (o.progress_interval < 1) fail("progress_interval must be >= 1");
  if (o.topology.film_samples > 64) fail("topology.film_samples must be at most 64");
  if (o.topology.border_trim_rings > 8) fail("topology.border_trim_rings must be at most 8");
  if (o.input.max_query_points != 0 && o.input.max_query_points < o.target_vertices)
    fail("input.max_query_points " + std::to_string(o.input.max_query_points) + " is below target_vertices " +
         std::to_string(o.target_vertices) + ": a subsample sparser than the mesh cannot support its faces (0 = automatic)");
  if (o.post.fit_rounds < 1 || o.post.fit_rounds > 20) fail("post.fit_rounds must be in [1, 20] (got " + std::to_string(o.post.fit_rounds) + ")");
  if (!(o.post.fit_smoothness >= 0) || !std::isfinite(o.post.fit_smoothness)) fail("post.fit_smoothness must be finite and >= 0");
  if (!(o.input.smooth_noise_ratio >= 0)) fail("input.smooth_noise_ratio must be >= 0 (infinity turns the smoothing off)");
  if (o.post.stacked_layer_rounds < 0 || o.post.stacked_layer_rounds > 16)
    fail("post.stacked_layer_rounds must be in [0, 16] (got " + std::to_string(o.post.stacked_layer_rounds) + ")");
  if (o.post.close_borders_max_vertices < 3 || o.post.close_borders_max_vertices > 4000)
    fail("post.close_borders_max_vertices must be in [3, 4000] (got " + std::to_string(o.post.close_borders_max_vertices) + ")");
}

}  // namespace

// The film test of the border creation runs only for clouds whose oriented normals point away
// from their centroid at least this much (detail::normal_flux: a sphere 1, a flat sheet 0): a film
// across a tunnel needs a surface around a volume; on flat sheets it curled the borders.
constexpr double kEnclosingFlux = 0.2;

void Reconstructor::Impl::init(edgefront::PointCloud points, const ReconstructOptions& options, const ProgressCallback& progress) {
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
  if (const size_t repeated = detail::drop_repeated_points(points); opt.target_vertices > points.size()) {
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
  if (std::isfinite(opt.input.smooth_noise_ratio) && cloud.size() >= 8) {
    report(Phase::noise_estimate, 0);
    const NoiseEstimate noise = estimate_noise(cloud, {.threads = opt.threads});
    noise_ratio = noise.ratio();
    report(Phase::noise_estimate, 0.5);
    if (noise_ratio > opt.input.smooth_noise_ratio) cloud_smoothed = smooth_noise(cloud, {.threads = opt.threads}) > 0;
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
      opt.input.max_query_points ? opt.input.max_query_points
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
    const size_t n = tp.size(), m = std::min<size_t>(n, kSpacingProbes);
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

  oriented = opt.input.orient_winners && cloud.has_normals();
  if (opt.input.orient_winners && !cloud.has_normals()) {
    report(Phase::normal_fitting, 0);
    constexpr size_t kSteps = 20;  // progress reports while fitting
    for (size_t s = 0; s < kSteps; ++s) {
      for (size_t i = s * cloud.size() / kSteps; i < (s + 1) * cloud.size() / kSteps; ++i) point_normal(i);
      report(Phase::normal_fitting, 0.8 * static_cast<double>(s + 1) / kSteps);
    }
    oriented_fitted = fitted_normal;
    oriented = detail::orient_normals(cloud.points, *tree, oriented_fitted, kOrientNeighbours,
                                      opt.input.quadric_normals ? &fitted_residual : nullptr, opt.input.quadric_normals);
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
  opt.topology.min_vertices = std::min(opt.topology.min_vertices, opt.target_vertices / 2);
}

void Reconstructor::Impl::build_subsampled_tree(size_t limit) {
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

void Reconstructor::Impl::permute_cloud(const std::vector<size_t>& perm) {
  std::vector<Vec3> sorted(cloud.size());
  for (size_t k = 0; k < perm.size(); ++k) sorted[k] = cloud.points[perm[k]];
  cloud.points.swap(sorted);
  if (cloud.has_normals()) {
    for (size_t k = 0; k < perm.size(); ++k) sorted[k] = cloud.normals[perm[k]];
    cloud.normals.swap(sorted);
  }
}

void Reconstructor::Impl::build_start_mesh(Vec3 lo, Vec3 hi) {
  // Pad thin directions (a planar cloud still gets a solid start) and grow by 2%.
  const double min_extent = kStartMinExtent * bbox_diagonal;
  for (int a = 0; a < 3; ++a) {
    const double ext = hi[a] - lo[a];
    const double pad = kStartPadding * ext + 0.5 * std::max(0.0, min_extent - ext);
    lo[a] -= pad;
    hi[a] += pad;
  }
  std::vector<VertexHandle> vh;
  if (opt.growth.start == StartShape::box) {
    for (int i = 0; i < 8; ++i)
      vh.push_back(mesh.add_vertex(Vec3(i & 1 ? hi[0] : lo[0], i & 2 ? hi[1] : lo[1], i & 4 ? hi[2] : lo[2])));
    const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& q : quads) {
      mesh.add_face(vh[q[0]], vh[q[1]], vh[q[2]]);
      mesh.add_face(vh[q[0]], vh[q[2]], vh[q[3]]);
    }
  } else {
    const Vec3 c = (lo + hi) * 0.5, e = (hi - lo) * 0.5 * kTetrahedronScale;  // the tetrahedron contains the box
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

double Reconstructor::Impl::mean_edge_length() const {
  double sum = 0;
  size_t n = 0;
  for (auto e : mesh.edges()) {
    sum += mesh.calc_edge_length(e);
    ++n;
  }
  return n ? sum / static_cast<double>(n) : bbox_diagonal * 0.1;
}

const Vec3& Reconstructor::Impl::point_normal(size_t i) {
  if (cloud.has_normals()) return cloud.normals[i];
  if (opt.input.quadric_normals) {
    if (fitted_normal.empty()) fitted_normal = fit_normals(cloud.points, *tree, {.threads = opt.threads}, &fitted_residual);
    return fitted_normal[i];
  }
  if (fitted_normal.empty()) fitted_normal.assign(cloud.size(), Vec3(0, 0, 0));
  Vec3& n = fitted_normal[i];
  if (n.sqrnorm() > 0 || std::isnan(n[0])) return n;
  tree->k_nearest(cloud.points[i], kPlaneFitNeighbours, knn);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(neighbour_scatter(cloud.points, knn));
  const Eigen::Vector3d e = eig.eigenvectors().col(0);
  const Eigen::Vector3d ev = eig.eigenvalues();
  // Not flat enough (noise comparable to the spacing): no usable normal (marked by a NaN).
  if (!(ev[0] < kPlaneFitFlatness * ev[1])) {
    n = Vec3(std::numeric_limits<double>::quiet_NaN(), 0, 0);
    return n;
  }
  n = Vec3(e[0], e[1], e[2]);
  if (!(n.sqrnorm() > 0.5)) n = Vec3(std::numeric_limits<double>::quiet_NaN(), 0, 0);
  return n;
}

const Vec3& Reconstructor::Impl::query_point_normal(size_t k) {
  return subsample.empty() ? point_normal(k) : subsample.normals[k];
}

int Reconstructor::Impl::query_point_part(size_t k) {
  if (query_parts.empty()) query_parts = detail::cloud_parts(*query_points, *tree);
  return query_parts[k];
}

detail::CloudHit Reconstructor::Impl::cloud_query(const Vec3& p) {
  const PointIndex::Neighbor nb = tree->nearest(p);
  return {std::sqrt(nb.distance2), query_point_normal(nb.index), (*query_points)[nb.index], nb.index};
}

void Reconstructor::Impl::oriented_neighbors(const Vec3& p, size_t k, std::vector<detail::CloudHit>& out) {
  tree->k_nearest(p, k, knn_oriented);
  out.clear();
  for (const PointIndex::Neighbor& nb : knn_oriented)
    out.push_back({std::sqrt(nb.distance2), query_oriented_normal(nb.index), (*query_points)[nb.index], nb.index});
}

}  // namespace gcs
