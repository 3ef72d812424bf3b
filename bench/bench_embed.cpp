// bench_embed: the cost of embedding EdgeFront in a host (bench/results/embedding.md).
//
//  1. Array conversion of a mesh with about 1.3M faces (icosphere, 8 subdivisions) against one
//     Dijkstra field on it (the issue asks: the conversion must cost less): mesh_from_arrays from
//     double + int32, float + int32, double + int64 arrays; mesh_to_arrays back.
//  2. The incremental twist repair through a RepairSession (host edits, repair, edit record, and
//     the host's replay of the record on its plain arrays) against the same TwistRepairer calls on
//     an edgefront::Mesh, in the same run: a host loop that, per batch, moves a share of the
//     vertices a little (as a GCS loop's smoothing does) and every --flip-every batches turns a
//     patch over (a twist for the repair to find, with the sphere's normals as reference).
// Times are thread CPU seconds, best of --repeats runs; both paths of part 2 give the same mesh
// (checked).
//
//   bench_embed [--subdivisions 8] [--repair-subdivisions 5] [--batches 20] [--move-share 0.2]
//               [--flip-every 2] [--repeats 3] [--seed 1] [--only conversion|direct|session]

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "bench_timing.h"
#include "edgefront/arrays.h"
#include "edgefront/error.h"
#include "edgefront/minimal_distance_front.h"
#include "edgefront/minimal_edge_front.h"
#include "shapes/shapes.h"
#include "twist/repair_session.h"

namespace {

using namespace edgefront;

struct Args {
  int subdivisions = 8;
  int repair_subdivisions = 5;
  int batches = 20;
  double move_share = 0.2;
  int flip_every = 2;  // a patch is turned over every this many batches
  int repeats = 3;
  unsigned seed = 1;
  std::string only;  // "conversion", "direct" or "session": run only that (for callgrind)
};

template <class F>
double best_cpu(int repeats, F&& f) {
  double best = 1e300;
  for (int i = 0; i < repeats; ++i) {
    const double t0 = efbench::cpu_seconds();
    f();
    best = std::min(best, efbench::cpu_seconds() - t0);
  }
  return best;
}

void conversion(const Args& a) {
  const Mesh sphere = shapes::icosphere(a.subdivisions);
  const MeshArrays arrays = mesh_to_arrays(sphere);
  const std::vector<float> vf(arrays.vertices.begin(), arrays.vertices.end());
  const std::vector<std::int64_t> f64(arrays.faces.begin(), arrays.faces.end());
  std::printf("conversion: icosphere(%d), %zu vertices, %zu faces\n", a.subdivisions, arrays.n_vertices(), arrays.n_faces());
  // Each result is kept until the next run has made its own: what is timed is making it (a
  // host keeps the mesh), not freeing the previous one.
  ArrayMesh kept;
  auto convert = [&](const VertexArrayView& v, const FaceArrayView& f) {
    double best = 1e300;
    for (int i = 0; i < a.repeats; ++i) {
      const double t0 = efbench::cpu_seconds();
      ArrayMesh m = mesh_from_arrays(v, f);
      best = std::min(best, efbench::cpu_seconds() - t0);
      kept = std::move(m);
    }
    return best;
  };
  const double t_double = convert(arrays.vertices, arrays.faces);
  const double t_float = convert(vf, arrays.faces);
  const double t_int64 = convert(arrays.vertices, f64);
  const ArrayMesh converted = mesh_from_arrays(arrays.vertices, arrays.faces);
  MeshArrays back;
  const double t_back = best_cpu(a.repeats, [&] {
    MeshArrays b = mesh_to_arrays(converted.mesh);
    back = std::move(b);
  });
  DistanceField field;
  auto dijkstra = [&] {
    double best = 1e300;
    for (int i = 0; i < a.repeats; ++i) {
      const double t0 = efbench::cpu_seconds();
      DistanceField d = dijkstra_distance(converted.mesh, FrontSource::vertex(VertexHandle(0)));
      best = std::min(best, efbench::cpu_seconds() - t0);
      field = std::move(d);
    }
    return best;
  };
  const double t_dijkstra = dijkstra();
  const double t0 = efbench::cpu_seconds();
  const DistanceField mdf = geodesic_distance(converted.mesh, FrontSource::vertex(VertexHandle(0)));
  const double t_mdf = efbench::cpu_seconds() - t0;
  std::printf("  mesh_from_arrays double+int32  %8.3f s  (%.2f x one Dijkstra field)\n", t_double, t_double / t_dijkstra);
  std::printf("  mesh_from_arrays float+int32   %8.3f s  (%.2f x)\n", t_float, t_float / t_dijkstra);
  std::printf("  mesh_from_arrays double+int64  %8.3f s  (%.2f x)\n", t_int64, t_int64 / t_dijkstra);
  std::printf("  mesh_to_arrays                 %8.3f s  (%.2f x)\n", t_back, t_back / t_dijkstra);
  std::printf("  dijkstra_distance, one field   %8.3f s\n", t_dijkstra);
  std::printf("  geodesic_distance (MDF), one   %8.3f s  (for scale)\n", t_mdf);
  if (back.faces != arrays.faces || field.order.size() != mdf.order.size()) std::printf("(unexpected results)\n");
}

/// One host loop's batches: per batch the moved vertices and their new positions.
struct Batch {
  std::vector<int> vertices;
  std::vector<Vec3> positions;
};

/// The batches, made on a copy of the sphere so that both paths replay the same moves.
std::vector<Batch> make_batches(const Mesh& sphere, const Args& a, double mel) {
  Mesh m = sphere;
  std::mt19937 rng(a.seed);
  std::vector<Batch> out;
  std::uniform_real_distribution<double> unit(-1, 1);
  for (int b = 0; b < a.batches; ++b) {
    Batch batch;
    std::vector<char> moved(m.n_vertices(), 0);
    for (VertexHandle v : m.vertices()) {
      if (std::uniform_real_distribution<double>(0, 1)(rng) >= a.move_share) continue;
      moved[static_cast<size_t>(v.idx())] = 1;
      m.set_point(v, m.point(v) + 0.02 * mel * Vec3(unit(rng), unit(rng), unit(rng)));
    }
    if (b % a.flip_every == a.flip_every - 1) {
      // Turn a patch over (2 rings) like a coin, about a tangent axis through its centroid.
      const VertexHandle centre(std::uniform_int_distribution<int>(0, static_cast<int>(m.n_vertices()) - 1)(rng));
      const std::vector<int> level = edge_front_levels(m, FrontSource::vertex(centre), 2);
      Vec3 c(0, 0, 0);
      std::vector<VertexHandle> inner;
      for (size_t i = 0; i < level.size(); ++i) {
        if (level[i] >= 0 && level[i] < 2) {
          inner.emplace_back(static_cast<int>(i));
          c += m.point(inner.back());
        }
      }
      c /= static_cast<double>(inner.size());
      const Vec3 n = m.point(centre).normalized();
      const Vec3 axis = OpenMesh::cross(n, std::abs(n[0]) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0)).normalized();
      for (VertexHandle v : inner) {
        const Vec3 d = m.point(v) - c;
        const Vec3 along = OpenMesh::dot(d, axis) * axis;
        m.set_point(v, c + along - (d - along));
        moved[static_cast<size_t>(v.idx())] = 1;
      }
    }
    for (size_t i = 0; i < moved.size(); ++i) {
      if (!moved[i]) continue;
      batch.vertices.push_back(static_cast<int>(i));
      batch.positions.push_back(m.point(VertexHandle(static_cast<int>(i))));
    }
    out.push_back(std::move(batch));
  }
  return out;
}

void incremental(const Args& a) {
  const Mesh sphere = shapes::icosphere(a.repair_subdivisions);
  const MeshArrays arrays = mesh_to_arrays(sphere);
  double mel = 0;
  for (EdgeHandle e : sphere.edges()) mel += sphere.calc_edge_length(e);
  mel /= static_cast<double>(sphere.n_edges());
  PointCloud truth;
  for (VertexHandle v : sphere.vertices()) {
    truth.points.push_back(sphere.point(v));
    truth.normals.push_back(sphere.point(v).normalized());
  }
  const twist::ReferenceNormals ref(truth);
  twist::RepairOptions options;
  options.detect.reference = &ref;
  options.garbage_collect = false;
  const std::vector<Batch> batches = make_batches(sphere, a, mel);
  size_t moved = 0;
  for (const Batch& b : batches) moved += b.vertices.size();
  std::printf("\nincremental repair: icosphere(%d), %zu vertices, %zu faces, %d batches, %.0f moved vertices per batch\n",
              a.repair_subdivisions, arrays.n_vertices(), arrays.n_faces(), a.batches,
              static_cast<double>(moved) / static_cast<double>(batches.size()));

  MeshArrays direct_result, session_result;
  size_t direct_repairs = 0, session_repairs = 0;
  // On an edgefront::Mesh: positions set, the faces around them handed to the repairer.
  auto direct = [&] {
    ArrayMesh m = mesh_from_arrays(arrays.vertices, arrays.faces);
    twist::TwistRepairer repairer(options);
    direct_repairs = 0;
    const double t0 = efbench::cpu_seconds();
    std::vector<FaceHandle> changed;
    for (const Batch& b : batches) {
      changed.clear();
      for (size_t i = 0; i < b.vertices.size(); ++i) {
        const VertexHandle v(b.vertices[i]);  // originals keep their index: host = mesh index
        if (m.mesh.status(v).deleted()) continue;  // removed by a repair (the host deleted it)
        m.mesh.set_point(v, b.positions[i]);
        for (FaceHandle f : m.mesh.vf_range(v)) changed.push_back(f);
      }
      std::sort(changed.begin(), changed.end());
      changed.erase(std::unique(changed.begin(), changed.end()), changed.end());
      direct_repairs += repairer.repair_changed(m.mesh, changed, mel).repairs;
    }
    const double t = efbench::cpu_seconds() - t0;
    direct_result = mesh_to_arrays(m.mesh);
    return t;
  };
  // Through the session: the host's edits, the repair, the record, and the host's replay.
  double session_only = 0;
  auto session = [&] {
    twist::SessionOptions so;
    so.repair = options;
    twist::RepairSession s(arrays.vertices, arrays.faces, so);
    std::vector<double> V = arrays.vertices;
    std::vector<int> F = arrays.faces;
    session_repairs = 0;
    double replay = 0;
    const double t0 = efbench::cpu_seconds();
    for (const Batch& b : batches) {
      for (size_t i = 0; i < b.vertices.size(); ++i) {
        if (!s.mirror_vertex(b.vertices[i]).is_valid()) continue;  // removed by a record: the host deleted it
        const Vec3& p = b.positions[i];
        s.set_vertex(b.vertices[i], {p[0], p[1], p[2]});
        std::copy(p.data(), p.data() + 3, V.begin() + 3 * b.vertices[i]);
      }
      const twist::EditRecord r = s.repair(mel);
      session_repairs += s.stats().report.repairs;
      const double r0 = efbench::cpu_seconds();
      twist::apply(r, V, F);
      replay += efbench::cpu_seconds() - r0;
    }
    const double t = efbench::cpu_seconds() - t0;
    session_only = t - replay;
    session_result = mesh_to_arrays(s.mirror());
    return t;
  };
  if (a.only == "direct" || a.only == "session") {  // one path, once (instruction counts)
    const double t = a.only == "direct" ? direct() : session();
    std::printf("  %s: %.4f s, %zu repairs\n", a.only.c_str(), t, a.only == "direct" ? direct_repairs : session_repairs);
    return;
  }
  double best_direct = 1e300, best_session = 1e300, best_session_only = 1e300;
  for (int r = 0; r < a.repeats; ++r) {  // alternating, so both see the same machine load
    best_direct = std::min(best_direct, direct());
    best_session = std::min(best_session, session());
    best_session_only = std::min(best_session_only, session_only);
  }
  const bool same = direct_result.faces == session_result.faces && direct_result.vertices == session_result.vertices;
  std::printf("  repairs: %zu (direct), %zu (session); same mesh: %s; a patch turned over every %d batches\n", direct_repairs,
              session_repairs, same ? "yes" : "NO", a.flip_every);
  std::printf("  TwistRepairer on an edgefront::Mesh      %8.4f s\n", best_direct);
  std::printf("  RepairSession (edits, repair, record)    %8.4f s  (%.3f x)\n", best_session_only, best_session_only / best_direct);
  std::printf("  ... and the host's replay of the records %8.4f s  (%.3f x)\n", best_session, best_session / best_direct);
  if (!same) std::exit(1);
}

}  // namespace

int main(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string k = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "bench_embed: %s needs a value\n", k.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (k == "--subdivisions") a.subdivisions = std::stoi(value());
    else if (k == "--repair-subdivisions") a.repair_subdivisions = std::stoi(value());
    else if (k == "--batches") a.batches = std::stoi(value());
    else if (k == "--move-share") a.move_share = std::stod(value());
    else if (k == "--flip-every") a.flip_every = std::max(1, std::stoi(value()));
    else if (k == "--repeats") a.repeats = std::stoi(value());
    else if (k == "--seed") a.seed = static_cast<unsigned>(std::stoul(value()));
    else if (k == "--only") a.only = value();
    else {
      std::fprintf(stderr, "bench_embed: unknown option %s\n", k.c_str());
      return 2;
    }
  }
  try {
    if (a.only.empty() || a.only == "conversion") conversion(a);
    if (a.only != "conversion") incremental(a);
  } catch (const Error& e) {
    std::fprintf(stderr, "bench_embed: %s\n", e.what());
    return 1;
  }
  return 0;
}
