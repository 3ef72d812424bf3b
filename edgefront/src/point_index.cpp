#include "edgefront/point_index.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <nanoflann.hpp>

#include "edgefront/error.h"

namespace edgefront {

namespace {

struct Adaptor {
  const std::vector<Vec3>* pts;
  size_t kdtree_get_point_count() const { return pts->size(); }
  double kdtree_get_pt(size_t i, size_t d) const { return (*pts)[i][static_cast<int>(d)]; }
  template <class BBox>
  bool kdtree_get_bbox(BBox&) const {
    return false;
  }
};
using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Adaptor>, Adaptor, 3, size_t>;

constexpr size_t kLeafSize = 16;

}  // namespace

struct PointIndex::Impl {
  std::vector<Vec3> points;
  Adaptor adaptor{nullptr};
  std::unique_ptr<Tree> tree;
};

PointIndex::PointIndex(std::vector<Vec3> points) : impl_(std::make_unique<Impl>()) {
  for (size_t i = 0; i < points.size(); ++i) {
    const Vec3& p = points[i];
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
      throw InvalidInput("PointIndex: point " + std::to_string(i) + " has a NaN or infinite coordinate");
  }
  impl_->points = std::move(points);
  impl_->adaptor.pts = &impl_->points;
  impl_->tree = std::make_unique<Tree>(3, impl_->adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(kLeafSize));
  impl_->tree->buildIndex();
}
PointIndex::~PointIndex() = default;
PointIndex::PointIndex(PointIndex&&) noexcept = default;
PointIndex& PointIndex::operator=(PointIndex&&) noexcept = default;

PointIndex::Neighbor PointIndex::nearest(const Vec3& p) const {
  if (impl_->points.empty()) throw InvalidInput("PointIndex: nearest point asked of an empty index");
  Neighbor n;
  impl_->tree->knnSearch(&p[0], 1, &n.index, &n.distance2);
  return n;
}

void PointIndex::k_nearest(const Vec3& p, size_t k, std::vector<Neighbor>& out) const {
  out.clear();
  k = std::min(k, impl_->points.size());
  if (k == 0) return;
  // Scratch per thread: const queries may run from several threads at once (edgefront/parallel.h).
  thread_local std::vector<size_t> idx;
  thread_local std::vector<double> d2;
  idx.resize(k);
  d2.resize(k);
  const size_t got = impl_->tree->knnSearch(&p[0], k, idx.data(), d2.data());
  out.reserve(got);
  for (size_t i = 0; i < got; ++i) out.push_back({idx[i], d2[i]});
}

void PointIndex::radius_search(const Vec3& p, double radius, std::vector<size_t>& out) const {
  out.clear();
  if (impl_->points.empty() || !(radius >= 0)) return;
  std::vector<std::pair<size_t, double>> matches;
  nanoflann::SearchParams params;
  params.sorted = false;
  impl_->tree->radiusSearch(&p[0], radius * radius, matches, params);
  out.reserve(matches.size());
  for (const auto& m : matches) out.push_back(m.first);
  std::sort(out.begin(), out.end());
}

const std::vector<Vec3>& PointIndex::points() const { return impl_->points; }
size_t PointIndex::size() const { return impl_->points.size(); }
bool PointIndex::empty() const { return impl_->points.empty(); }

}  // namespace edgefront
