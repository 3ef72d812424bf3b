#include "gcs/cloud_normals.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "detail/local_quadric.h"
#include "edgefront/error.h"
#include "edgefront/parallel.h"

namespace gcs {

using edgefront::InvalidInput;
using edgefront::PointIndex;
using edgefront::Vec3;

namespace {

constexpr std::size_t kMinNeighbours = 8, kMaxNeighbours = 256;

Eigen::Vector3d eig(const Vec3& p) { return {p[0], p[1], p[2]}; }

// A neighbour's fit "passes through" a point when the point's height off its quadric is within
// this many times the fit's residual (plus a small share of the extent, for a noise-free fit).
constexpr double kThroughResiduals = 2.0, kThroughSpread = 0.02;

}  // namespace

std::vector<Vec3> fit_normals(const std::vector<Vec3>& points, const PointIndex& index, const NormalFitOptions& o,
                              std::vector<double>* residuals) {
  if (o.neighbours < kMinNeighbours || o.neighbours > kMaxNeighbours)
    throw InvalidInput("fit_normals: neighbours must be in [8, 256] (got " + std::to_string(o.neighbours) + ")");
  if (!(o.max_residual > 0)) throw InvalidInput("fit_normals: max_residual must be > 0");
  if (index.size() != points.size()) throw InvalidInput("fit_normals: the index is not over the points");
  const std::size_t n = points.size();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<Vec3> out(n, Vec3(nan, nan, nan));
  if (residuals) residuals->assign(n, nan);
  if (n < kMinNeighbours) return out;
  const std::size_t k = std::min(o.neighbours, n);
  std::vector<detail::LocalQuadric> fits(n);
  std::vector<double> ratio(n, std::numeric_limits<double>::infinity());
  std::vector<double> reach2(n, 0);  // squared distance to the k-th neighbour
  // The fits run in parallel (contiguous chunks of points, one fitter each over the shared tree);
  // with best_neighbourhood each keeps its neighbours (k per point, `hit_count` of them used),
  // and the lists of who is in whose neighbourhood are built afterwards in point order, as one
  // thread would: the normals are the same for any thread count.
  std::vector<std::uint32_t> hit_index;
  std::vector<std::uint32_t> hit_count;
  if (o.best_neighbourhood) {
    hit_index.assign(n * k, 0);
    hit_count.assign(n, 0);
  }
  edgefront::parallel_for(n, o.threads, [&](std::size_t begin, std::size_t end, unsigned) {
    detail::QuadricFitter fitter(points, index);
    for (std::size_t i = begin; i < end; ++i) {
      detail::LocalQuadric& q = fits[i];
      if (!fitter.fit(i, k, q) || !(q.spread > 0)) continue;
      ratio[i] = q.residual / q.spread;
      const auto& hits = fitter.last_hits();
      reach2[i] = hits.back().distance2;
      if (o.best_neighbourhood) {
        EF_CHECK(hits.size() <= k, "fit_normals: more neighbours than asked for");
        for (std::size_t j = 0; j < hits.size(); ++j) hit_index[i * k + j] = static_cast<std::uint32_t>(hits[j].index);
        hit_count[i] = static_cast<std::uint32_t>(hits.size());
      }
    }
  });
  std::vector<std::vector<std::uint32_t>> members;  // who is in whose neighbourhood (best_neighbourhood)
  if (o.best_neighbourhood) {
    members.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t j = 0; j < hit_count[i]; ++j) {
        const std::uint32_t h = hit_index[i * k + j];
        if (h != i) members[h].push_back(static_cast<std::uint32_t>(i));
      }
    }
  }
  edgefront::parallel_for(n, o.threads, [&](std::size_t begin, std::size_t end, unsigned) {
    for (std::size_t i = begin; i < end; ++i) {
      const Eigen::Vector3d p = eig(points[i]);
      std::size_t best = i;
      double best_ratio = ratio[i];
      if (o.best_neighbourhood && !(ratio[i] <= o.max_residual)) {
        for (const std::uint32_t j : members[i]) {
          if (!(ratio[j] < best_ratio)) continue;
          const detail::LocalQuadric& q = fits[j];
          const Eigen::Vector3d d = p - q.origin;
          const double off = std::abs(q.height(d.dot(q.u), d.dot(q.v)) - d.dot(q.n));
          if (off > kThroughResiduals * q.residual + kThroughSpread * q.spread) continue;
          best = j;
          best_ratio = ratio[j];
        }
      }
      if (!(best_ratio <= o.max_residual)) continue;
      const detail::LocalQuadric& q = fits[best];
      const Eigen::Vector3d m = o.quadric_normal ? q.normal_at(p) : q.n;
      if (!m.allFinite()) continue;
      out[i] = Vec3(m[0], m[1], m[2]);
      if (residuals) (*residuals)[i] = q.residual;
    }
  });
  return out;
}

}  // namespace gcs
