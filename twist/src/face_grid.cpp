// FaceGeometry and FaceGrid: per-face geometry and the incremental spatial index of faces.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "detail/geometry.h"
#include "edgefront/error.h"
#include "twist/detect.h"

namespace twist {

using edgefront::FaceHandle;
using edgefront::InvalidInput;
using edgefront::Mesh;
using edgefront::Vec3;
using edgefront::VertexHandle;

namespace {
// 21 bits per axis: far cells may share a key, which only adds candidates (queries check distances).
std::uint64_t key_of_cell(std::int64_t x, std::int64_t y, std::int64_t z) {
  const auto bits = [](std::int64_t c) { return static_cast<std::uint64_t>(c) & 0x1FFFFFu; };
  return (bits(x) << 42) | (bits(y) << 21) | bits(z);
}
std::uint64_t cell_key(const Vec3& p, double cell) {
  const auto c = [&](int i) { return static_cast<std::int64_t>(std::floor(p[i] / cell)); };
  return key_of_cell(c(0), c(1), c(2));
}
}  // namespace

FaceGeometry face_geometry(const Mesh& mesh, FaceHandle f) {
  if (!edgefront::is_live(mesh, f)) {
    throw InvalidInput("twist::face_geometry: face " + std::to_string(f.idx()) +
                       " is not a live face of the mesh (invalid, out of range or deleted)");
  }
  FaceGeometry g;
  std::array<Vec3, 3> p;
  size_t i = 0;
  for (VertexHandle v : mesh.fv_range(f)) {
    EF_CHECK(i < 3, "face " + std::to_string(f.idx()) + " is not a triangle");
    p[i] = mesh.point(v);
    g.vertices[i++] = v.idx();
  }
  EF_CHECK(i == 3, "face " + std::to_string(f.idx()) + " is not a triangle");
  g.normal = detail::unit_normal(p);
  g.centre = detail::centroid(p);
  for (size_t k = 0; k < 3; ++k) g.longest = std::max(g.longest, (p[k] - p[(k + 1) % 3]).norm());
  return g;
}

void FaceGrid::insert(const Mesh& mesh, FaceHandle f) {
  if (!edgefront::is_live(mesh, f)) return;
  const FaceGeometry g = face_geometry(mesh, f);
  const std::uint64_t key = cell_key(g.centre, cell_);
  const size_t i = static_cast<size_t>(f.idx());
  if (i >= records_.size()) records_.resize(std::max(i + 1, 2 * records_.size()));
  Record& r = records_[i];
  r.geometry = g;
  if (r.key != kNoKey) {
    auto& old = cells_[r.key];
    const auto pos = std::find_if(old.begin(), old.end(), [&](const Entry& e) { return e.face == f.idx(); });
    if (r.key == key && pos != old.end()) {
      pos->centre = g.centre;
      return;
    }
    if (pos != old.end()) {
      *pos = old.back();
      old.pop_back();
      --size_;
    }
  }
  r.key = key;
  cells_[key].push_back(Entry{f.idx(), g.centre});
  ++size_;
}

void FaceGrid::update(const Mesh& mesh, const std::vector<FaceHandle>& faces) {
  EF_CHECK(cell_ > 0, "FaceGrid::update before rebuild");
  for (FaceHandle f : faces) insert(mesh, f);
}

void FaceGrid::update_new(const Mesh& mesh) {
  EF_CHECK(cell_ > 0, "FaceGrid::update_new before rebuild");
  for (size_t i = seen_faces_; i < mesh.n_faces(); ++i) insert(mesh, FaceHandle(static_cast<int>(i)));
  seen_faces_ = mesh.n_faces();
}

void FaceGrid::rebuild(const Mesh& mesh, double cell) {
  if (!(cell > 0) || !std::isfinite(cell)) throw InvalidInput("twist::FaceGrid: the cell size must be finite and > 0");
  cell_ = cell;
  cells_.clear();
  records_.assign(mesh.n_faces(), Record{});
  size_ = 0;
  ++rebuilds_;
  for (FaceHandle f : mesh.faces()) insert(mesh, f);
  seen_faces_ = mesh.n_faces();
}

void FaceGrid::query(const Mesh& mesh, const Vec3& p, double radius, std::vector<FaceHandle>& out) const {
  out.clear();
  if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]) || !std::isfinite(radius) || radius < 0)
    throw InvalidInput("twist::FaceGrid::query: the point and the radius must be finite, the radius >= 0");
  if (!(cell_ > 0)) return;
  const double r2 = radius * radius;
  const auto take = [&](const std::vector<Entry>& entries) {
    for (const Entry& e : entries) {
      if ((e.centre - p).sqrnorm() >= r2) continue;
      const FaceHandle f(e.face);
      if (edgefront::is_live(mesh, f)) out.push_back(f);
    }
  };
  // Cell ranges in doubles first: a query box with more cells than the grid holds (or beyond the
  // integer range) scans the occupied cells instead of the box.
  double lo[3], hi[3], span = 1;
  for (int i = 0; i < 3; ++i) {
    lo[i] = std::floor((p[i] - radius) / cell_);
    hi[i] = std::floor((p[i] + radius) / cell_);
    span *= hi[i] - lo[i] + 1;
  }
  const bool in_range = std::abs(lo[0]) < 1e15 && std::abs(hi[0]) < 1e15 && std::abs(lo[1]) < 1e15 &&
                        std::abs(hi[1]) < 1e15 && std::abs(lo[2]) < 1e15 && std::abs(hi[2]) < 1e15;
  if (!in_range || span > static_cast<double>(cells_.size())) {
    for (const auto& cell : cells_) take(cell.second);
  } else {
    const auto c = [](double v) { return static_cast<std::int64_t>(v); };
    for (std::int64_t x = c(lo[0]); x <= c(hi[0]); ++x) {
      for (std::int64_t y = c(lo[1]); y <= c(hi[1]); ++y) {
        for (std::int64_t z = c(lo[2]); z <= c(hi[2]); ++z) {
          const auto it = cells_.find(key_of_cell(x, y, z));
          if (it != cells_.end()) take(it->second);
        }
      }
    }
  }
  std::sort(out.begin(), out.end(), [](FaceHandle a, FaceHandle b) { return a.idx() < b.idx(); });
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

}  // namespace twist
