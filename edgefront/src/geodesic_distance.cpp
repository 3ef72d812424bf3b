// The one-off distance queries (geodesic_distance: a MinimalDistanceFront run to the end, or the
// fast and Dijkstra modes) and the distance methods' names.
#include <cmath>
#include <limits>
#include <string>

#include "detail/distance_common.h"
#include "edgefront/error.h"
#include "edgefront/minimal_distance_front.h"

namespace edgefront {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();

DistanceField collect(const Mesh& mesh, MinimalDistanceFront& front, const DistanceOptions& options) {
  DistanceField out;
  out.distance.assign(mesh.n_vertices(), kInf);
  if (options.directions) out.direction.assign(mesh.n_vertices(), Vec3(0, 0, 0));
  front.set_settled_callback([&](VertexHandle v, double d, const Vec3& dir) {
    if (out.distance[v.idx()] != kInf) return;  // a loop vertex reached again from behind
    out.distance[v.idx()] = d;
    if (options.directions) out.direction[v.idx()] = dir;
    out.order.push_back(v);
  });
  out.stop = front.run();
  out.peak_front = front.peak_front_size();
  out.peak_working_memory_bytes = front.peak_working_memory_bytes();
  return out;
}
}  // namespace

const char* to_string(DistanceMethod method) {
  switch (method) {
    case DistanceMethod::Mdf: return "mdf";
    case DistanceMethod::Windows: return "windows";
    case DistanceMethod::Fast: return "fast";
    case DistanceMethod::Dijkstra: return "dijkstra";
  }
  return "unknown";
}

DistanceMethod parse_distance_method(const std::string& name) {
  for (DistanceMethod m : {DistanceMethod::Mdf, DistanceMethod::Windows, DistanceMethod::Fast, DistanceMethod::Dijkstra}) {
    if (name == to_string(m)) return m;
  }
  throw InvalidInput("distance: unknown method \"" + name + "\" (one of mdf, windows, fast, dijkstra)");
}

DistanceField geodesic_distance(const Mesh& mesh, const FrontSource& source, const DistanceOptions& options) {
  if (options.method == DistanceMethod::Dijkstra) return dijkstra_distance(mesh, source, options);
  if (options.method == DistanceMethod::Fast && !source.is_loop()) return detail::fast_distance(mesh, source, options);
  DistanceOptions o = options;
  if (o.method == DistanceMethod::Fast) o.method = DistanceMethod::Mdf;  // a loop source runs the MDF
  MinimalDistanceFront front(mesh);
  front.reset(source, o);
  return collect(mesh, front, o);
}

DistanceField geodesic_distance(const Mesh& mesh, const std::vector<SurfacePoint>& points,
                                const DistanceOptions& options) {
  if (options.method == DistanceMethod::Dijkstra) return dijkstra_distance(mesh, points, options);
  if (options.method == DistanceMethod::Fast) return detail::fast_distance(mesh, points, options);
  MinimalDistanceFront front(mesh);
  front.reset(points, options);
  return collect(mesh, front, options);
}

}  // namespace edgefront
