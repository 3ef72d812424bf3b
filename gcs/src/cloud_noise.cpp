#include "gcs/cloud_noise.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cmath>
#include <string>
#include <unordered_map>
#include <vector>

#include <Eigen/Dense>

#include "edgefront/error.h"
#include "edgefront/parallel.h"
#include "edgefront/point_index.h"
#include "detail/local_quadric.h"

namespace gcs {

using edgefront::InvalidInput;
using edgefront::PointCloud;
using edgefront::PointIndex;
using edgefront::Vec3;

using detail::LocalQuadric;
using detail::QuadricFitter;

namespace {

constexpr std::size_t kMinNeighbours = 8;
constexpr std::size_t kMaxNeighbours = 256;
// estimate_noise looks at a cloud of more than this many times max_points in patches.
constexpr std::size_t kPatchesAbove = 4;
// The quadric's misfit to a clean surface grows with the neighbourhood: with twice the neighbours
// its square is at least this many times larger (8 for a smooth surface evenly sampled; 4.2-12 on
// CGAL's scanned models' vertex sets, median residuals at 10 and 20 neighbours), while noise stays.
constexpr double kMisfitGrowth = 4;

Eigen::Vector3d eig(const Vec3& p) { return {p[0], p[1], p[2]}; }

void check_cloud(const PointCloud& cloud, const char* who) {
  if (cloud.size() < kMinNeighbours)
    throw InvalidInput(std::string(who) + ": at least " + std::to_string(kMinNeighbours) + " points are needed (got " +
                       std::to_string(cloud.size()) + ")");
  if (!cloud.normals.empty() && cloud.normals.size() != cloud.points.size())
    throw InvalidInput(std::string(who) + ": the cloud has " + std::to_string(cloud.normals.size()) + " normals for " +
                       std::to_string(cloud.points.size()) + " points");
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const Vec3& p = cloud.points[i];
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
      throw InvalidInput(std::string(who) + ": point " + std::to_string(i) + " has a NaN or infinite coordinate");
  }
}

void check_neighbours(std::size_t k, const char* who) {
  if (k < kMinNeighbours || k > kMaxNeighbours)
    throw InvalidInput(std::string(who) + ": neighbours must be in [" + std::to_string(kMinNeighbours) + ", " +
                       std::to_string(kMaxNeighbours) + "] (got " + std::to_string(k) + ")");
}

double median(std::vector<double>& v) {
  if (v.empty()) return 0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

// `count` indices evenly strided over [0, n).
std::vector<std::size_t> strided(std::size_t n, std::size_t count) {
  const std::size_t m = std::min(n, count);
  std::vector<std::size_t> out(m);
  for (std::size_t s = 0; s < m; ++s) out[s] = s * n / m;
  return out;
}

// Median distance from the listed points to their nearest other point.
// (On `threads` threads, each over a contiguous chunk of `points`; the gaps are joined in chunk
// order, so the median is the same for any thread count.)
double median_gap(const PointCloud& cloud, const PointIndex& index, const std::vector<std::size_t>& points,
                  unsigned threads) {
  std::vector<std::vector<double>> chunk_gaps(edgefront::threads_for(points.size(), threads));
  edgefront::parallel_for(points.size(), threads, [&](std::size_t begin, std::size_t end, unsigned chunk) {
    std::vector<double>& gaps = chunk_gaps[chunk];
    gaps.reserve(end - begin);
    std::vector<PointIndex::Neighbor> near;
    for (std::size_t s = begin; s < end; ++s) {
      index.k_nearest(cloud.points[points[s]], kMinNeighbours, near);
      for (const PointIndex::Neighbor& h : near) {
        if (h.distance2 > 0) {
          gaps.push_back(std::sqrt(h.distance2));
          break;
        }
      }
    }
  });
  std::vector<double> gaps;
  gaps.reserve(points.size());
  for (const std::vector<double>& g : chunk_gaps) gaps.insert(gaps.end(), g.begin(), g.end());
  return median(gaps);
}

// The estimate over the listed points of `cloud`: the quadric fits' residuals at k and at 2k
// neighbours, the surface's own misfit taken out (see NoiseEstimate::noise).
// (Parallel over contiguous chunks of `points`, the residuals joined in chunk order.)
NoiseEstimate estimate_at(const PointCloud& cloud, const std::vector<std::size_t>& points, std::size_t neighbours,
                          unsigned threads) {
  QuadricFitter fitter(cloud);
  const unsigned chunks = edgefront::threads_for(points.size(), threads);
  std::vector<std::vector<double>> chunk_narrow(chunks), chunk_wide(chunks);
  edgefront::parallel_for(points.size(), threads, [&](std::size_t begin, std::size_t end, unsigned chunk) {
    QuadricFitter local(cloud, fitter.index());
    LocalQuadric q, q2;
    for (std::size_t s = begin; s < end; ++s) {
      const std::size_t i = points[s];
      if (local.fit(i, neighbours, q) && local.fit(i, 2 * neighbours, q2)) {
        chunk_narrow[chunk].push_back(q.residual);
        chunk_wide[chunk].push_back(q2.residual);
      }
    }
  });
  std::vector<double> narrow, wide;
  narrow.reserve(points.size());
  wide.reserve(points.size());
  for (unsigned c = 0; c < chunks; ++c) {
    narrow.insert(narrow.end(), chunk_narrow[c].begin(), chunk_narrow[c].end());
    wide.insert(wide.end(), chunk_wide[c].begin(), chunk_wide[c].end());
  }
  NoiseEstimate e;
  e.points_used = narrow.size();
  e.residual = median(narrow);
  e.wide_residual = median(wide);
  e.noise = std::sqrt(std::max(0.0, (kMisfitGrowth * e.residual * e.residual - e.wide_residual * e.wide_residual) /
                                        (kMisfitGrowth - 1)));
  e.spacing = median_gap(cloud, fitter.index(), points, threads);
  return e;
}

// A large cloud is looked at in patches, so that no k-d tree over all of it is needed (building
// one is most of the estimate's cost: 1.6 s for 1M points): cubes around 16 evenly strided
// points, sized to hold about `want` points in all, and the points of the cubes grown to twice
// their side, which hold the complete neighbourhoods of the points inside. Returns that sub-cloud
// and, in `inner`, its points inside the cubes.
PointCloud patches(const PointCloud& cloud, std::size_t want, std::vector<std::size_t>& inner) {
  constexpr std::size_t kPatches = 16;
  constexpr std::size_t kCountStride = 8;  // the sizing pass counts every 8th point
  Vec3 lo = cloud.points[0], hi = cloud.points[0];
  for (const Vec3& p : cloud.points) {
    lo.minimize(p);
    hi.maximize(p);
  }
  const double diagonal = (hi - lo).norm();
  const std::vector<std::size_t> centres = strided(cloud.size(), kPatches);
  auto in_cube = [&](const Vec3& p, const Vec3& c, double half) {
    return std::abs(p[0] - c[0]) <= half && std::abs(p[1] - c[1]) <= half && std::abs(p[2] - c[2]) <= half;
  };
  // The side that holds want / kPatches points, from the counts in cubes of a 32nd of the
  // diagonal (a surface: the count grows with the square of the side).
  const double side0 = diagonal / 32;
  std::vector<double> counts(centres.size(), 0);
  for (std::size_t i = 0; i < cloud.size(); i += kCountStride) {
    for (std::size_t b = 0; b < centres.size(); ++b) counts[b] += in_cube(cloud.points[i], cloud.points[centres[b]], side0 / 2);
  }
  const double per_patch = static_cast<double>(want) / static_cast<double>(centres.size());
  const double side =
      std::min(diagonal, side0 * std::sqrt(per_patch / (kCountStride * std::max(1.0, median(counts)))));
  PointCloud sub;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const Vec3& p = cloud.points[i];
    bool outer = false, inside = false;
    for (std::size_t c : centres) {
      if (in_cube(p, cloud.points[c], side)) {
        outer = true;
        if (in_cube(p, cloud.points[c], side / 2)) {
          inside = true;
          break;
        }
      }
    }
    if (!outer) continue;
    if (inside) inner.push_back(sub.points.size());
    sub.points.push_back(p);
    if (cloud.has_normals()) sub.normals.push_back(cloud.normals[i]);
  }
  return sub;
}

}  // namespace

NoiseEstimate estimate_noise(const PointCloud& cloud, const NoiseOptions& options) {
  check_neighbours(options.neighbours, "estimate_noise");
  if (options.max_points < 1) throw InvalidInput("estimate_noise: max_points must be >= 1");
  check_cloud(cloud, "estimate_noise");
  if (cloud.size() <= kPatchesAbove * options.max_points)
    return estimate_at(cloud, strided(cloud.size(), options.max_points), options.neighbours, options.threads);
  std::vector<std::size_t> inner;
  const PointCloud sub = patches(cloud, options.max_points, inner);
  std::vector<std::size_t> points;
  for (std::size_t s : strided(inner.size(), options.max_points)) points.push_back(inner[s]);
  return estimate_at(sub, points, options.neighbours, options.threads);
}

std::size_t smooth_noise(PointCloud& cloud, const SmoothNoiseOptions& options) {
  check_neighbours(options.neighbours, "smooth_noise");
  check_cloud(cloud, "smooth_noise");
  QuadricFitter fitter(cloud);
  // The k-d tree queries dominate the cost, so points share them: the cloud is binned into cells of
  // 4 nearest-point gaps (a few points each); the point nearest a cell's middle is queried for 2k + 16 neighbours, and every point of the cell
  // takes its k nearest among those (a point's k nearest lie within them unless the cell is
  // much denser than the median).
  std::vector<std::vector<std::size_t>> cells;
  const double cell = 4 * median_gap(cloud, fitter.index(), strided(cloud.size(), 20000), options.threads);
  if (cell > 0) {
    struct KeyHash {
      std::size_t operator()(const std::array<std::int64_t, 3>& k) const {
        return static_cast<std::size_t>(k[0] * 73856093LL ^ k[1] * 19349663LL ^ k[2] * 83492791LL);
      }
    };
    std::unordered_map<std::array<std::int64_t, 3>, std::size_t, KeyHash> slot;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
      const Vec3& p = cloud.points[i];
      const std::array<std::int64_t, 3> key = {static_cast<std::int64_t>(std::floor(p[0] / cell)),
                                               static_cast<std::int64_t>(std::floor(p[1] / cell)),
                                               static_cast<std::int64_t>(std::floor(p[2] / cell))};
      const auto [it, fresh] = slot.try_emplace(key, cells.size());
      if (fresh) cells.emplace_back();
      cells[it->second].push_back(i);
    }
  } else {  // most points coincide
    for (std::size_t i = 0; i < cloud.size(); ++i) cells.push_back({i});
  }
  const std::size_t query = std::min(cloud.size(), 2 * options.neighbours + 16);
  std::vector<Vec3> moved = cloud.points;
  // Parallel over contiguous chunks of cells: a point is moved by its own cell's work only, which
  // reads the original cloud, so the result is the same for any thread count.
  std::vector<std::size_t> chunk_count(edgefront::threads_for(cells.size(), options.threads), 0);
  edgefront::parallel_for(cells.size(), options.threads, [&](std::size_t first, std::size_t last, unsigned chunk) {
    QuadricFitter local(cloud, fitter.index());
    std::vector<PointIndex::Neighbor> candidates;
    std::size_t& count = chunk_count[chunk];
    LocalQuadric q;
    for (std::size_t c = first; c < last; ++c) {
      const std::vector<std::size_t>& members = cells[c];
      Vec3 middle(0, 0, 0);
      for (std::size_t i : members) middle += cloud.points[i];
      middle /= static_cast<double>(members.size());
      const std::size_t centre = *std::min_element(members.begin(), members.end(), [&](std::size_t a, std::size_t b) {
        const double da = (cloud.points[a] - middle).sqrnorm(), db = (cloud.points[b] - middle).sqrnorm();
        return da != db ? da < db : a < b;
      });
      local.index().k_nearest(cloud.points[centre], query, candidates);
      for (std::size_t i : members) {
        if (!local.fit_from(i, options.neighbours, candidates, q)) continue;
        const Eigen::Vector3d p = eig(cloud.points[i]);
        const Eigen::Vector3d d = p - q.origin;
        const double lift = q.height(d.dot(q.u), d.dot(q.v)) - d.dot(q.n);
        if (lift == 0) continue;
        const Eigen::Vector3d to = p + lift * q.n;
        moved[i] = Vec3(to[0], to[1], to[2]);
        ++count;
      }
    }
  });
  cloud.points = std::move(moved);
  std::size_t count = 0;
  for (const std::size_t k : chunk_count) count += k;
  return count;
}

}  // namespace gcs
