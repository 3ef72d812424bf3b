#include "edgefront/coordinate_range.h"

#include <algorithm>
#include <cmath>

#include "edgefront/error.h"

namespace edgefront {

namespace {

/// The check over points given by `point(i)` for i in [0, n) where `live(i)`; `noun` names them.
template <class Point, class Live>
std::string problem(size_t n, const Point& point, const Live& live, const char* noun) {
  Vec3 lo(0, 0, 0), hi(0, 0, 0);
  bool any = false;
  for (size_t i = 0; i < n; ++i) {
    if (!live(i)) continue;
    const Vec3& p = point(i);
    for (int k = 0; k < 3; ++k) {
      if (!std::isfinite(p[k])) {
        return std::string(noun) + " " + std::to_string(i) + " has a non-finite coordinate (" +
               number_for_message(p[k]) + ")";
      }
      if (std::abs(p[k]) > kMaxCoordinate) {
        return std::string(noun) + " " + std::to_string(i) + " has the coordinate " + number_for_message(p[k]) +
               ", beyond +-" + number_for_message(kMaxCoordinate) +
               ": squared lengths and areas would overflow (scale the data down)";
      }
    }
    if (!any) {
      lo = hi = p;
      any = true;
    } else {
      lo.minimize(p);
      hi.maximize(p);
    }
  }
  const double extent = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  if (extent > 0 && extent < kMinExtent) {
    return "the points span only " + number_for_message(extent) + ", less than " +
           number_for_message(kMinExtent) + ": squared lengths and areas would underflow to zero (scale the data up)";
  }
  return {};
}

}  // namespace

std::string coordinate_range_problem(const std::vector<Vec3>& points, const char* noun) {
  return problem(
      points.size(), [&](size_t i) -> const Vec3& { return points[i]; }, [](size_t) { return true; }, noun);
}

std::string coordinate_range_problem(const Mesh& mesh) {
  return problem(
      mesh.n_vertices(), [&](size_t i) -> const Vec3& { return mesh.point(VertexHandle(static_cast<int>(i))); },
      [&](size_t i) { return !mesh.status(VertexHandle(static_cast<int>(i))).deleted(); }, "vertex");
}

void check_coordinate_range(const std::vector<Vec3>& points, const std::string& what) {
  if (std::string why = coordinate_range_problem(points); !why.empty()) throw InvalidInput(what + ": " + why);
}

void check_coordinate_range(const Mesh& mesh, const std::string& what) {
  if (std::string why = coordinate_range_problem(mesh); !why.empty()) throw InvalidInput(what + ": " + why);
}

}  // namespace edgefront
