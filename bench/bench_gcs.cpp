// bench_gcs: the GCS reconstructor on real and synthetic clouds (not a test; prints a report).
//
//   bench_gcs [--quick] [--data DIR]
//
// 1. kitten.xyz (CGAL sample, 5210 points) at 5K vertices: time, closed?, genus, valences.
// 2. sphere_20k.xyz at 10K vertices: valence-6 share, valence 5-7 share, median minimum angle.
// 3. 100K vertices from a 1M-point synthetic cloud (shapes::sample "bumpy-sphere"): time.
// 4. Runtime at a fixed target (20K vertices) for 100K-point vs 1M-point clouds of the same shape.
// --quick divides the synthetic targets by 10 (for a smoke run). Single thread.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "edgefront/mesh_stats.h"
#include "edgefront/point_cloud_io.h"
#include "edgefront/shapes.h"
#include "gcs/reconstructor.h"

namespace {

using edgefront::Mesh;
using edgefront::Vec3;

double median_min_angle_deg(const Mesh& mesh) {
  std::vector<double> a;
  for (auto f : mesh.faces()) {
    auto it = mesh.cfv_iter(f);
    const Vec3 p = mesh.point(*it), q = mesh.point(*++it), r = mesh.point(*++it);
    const auto ang = [](const Vec3& x, const Vec3& y, const Vec3& z) {
      const Vec3 u = (y - x).normalized(), v = (z - x).normalized();
      return std::acos(std::clamp(u | v, -1.0, 1.0));
    };
    a.push_back(std::min({ang(p, q, r), ang(q, r, p), ang(r, p, q)}) * 180.0 / M_PI);
  }
  std::sort(a.begin(), a.end());
  return a.empty() ? 0 : a[a.size() / 2];
}

void print_mesh(const char* label, const gcs::ReconstructResult& r) {
  const edgefront::MeshStats s = edgefront::compute_stats(r.mesh);
  std::printf("%s: %zu vertices, %zu faces, %zu component(s), %zu border loop(s), non-manifold %zu, stop: %s\n", label,
              s.vertices, s.faces, s.components, s.border_loops, s.nonmanifold_vertices,
              gcs::to_string(r.stop_reason).c_str());
  std::printf("  time %.2f s (topology %.2f s), %llu basic steps (%.2f us/step), %zu splits, %zu collapses, "
              "%zu faces removed, %zu loops merged, %zu holes filled\n",
              r.seconds_total, r.seconds_topology, static_cast<unsigned long long>(r.basic_steps),
              1e6 * r.seconds_total / std::max<double>(1, static_cast<double>(r.basic_steps)), r.splits, r.collapses,
              r.faces_removed, r.loops_merged, r.holes_filled);
  for (size_t c = 0; c < s.per_component.size() && c < 4; ++c)
    std::printf("  component %zu: %zu faces, %zu border loops, genus %g\n", c, s.per_component[c].faces,
                s.per_component[c].border_loops, s.per_component[c].genus);
  size_t v6 = 0, v57 = 0, total = 0;
  std::printf("  valences:");
  for (size_t k = 0; k < s.valence_histogram.size(); ++k) {
    if (!s.valence_histogram[k]) continue;
    std::printf(" %zu:%zu", k, s.valence_histogram[k]);
    total += s.valence_histogram[k];
    if (k == 6) v6 += s.valence_histogram[k];
    if (k >= 5 && k <= 7) v57 += s.valence_histogram[k];
  }
  std::printf("\n  valence 6: %.1f%%, valence 5-7: %.1f%%, median minimum angle %.1f deg\n",
              100.0 * static_cast<double>(v6) / static_cast<double>(std::max<size_t>(total, 1)),
              100.0 * static_cast<double>(v57) / static_cast<double>(std::max<size_t>(total, 1)),
              median_min_angle_deg(r.mesh));
  std::fflush(stdout);
}

gcs::ReconstructResult run(const edgefront::PointCloud& cloud, size_t target) {
  gcs::ReconstructOptions o;
  o.target_vertices = target;
  return gcs::reconstruct(cloud, o);
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false;
  std::filesystem::path data = EDGEFRONT_BENCH_DATA_DIR;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--quick")) quick = true;
    else if (!std::strcmp(argv[i], "--data") && i + 1 < argc) data = argv[++i];
    else {
      std::fprintf(stderr, "usage: bench_gcs [--quick] [--data DIR]\n");
      return 2;
    }
  }
  const size_t div = quick ? 10 : 1;
  try {
    const auto models = data / "models";
    if (std::filesystem::exists(models / "kitten.xyz")) {
      print_mesh("kitten.xyz at 5K", run(edgefront::read_points(models / "kitten.xyz"), 5000));
    } else {
      std::printf("kitten.xyz: missing (run data/fetch-models.sh)\n");
    }
    if (std::filesystem::exists(models / "sphere_20k.xyz")) {
      print_mesh("sphere_20k.xyz at 10K", run(edgefront::read_points(models / "sphere_20k.xyz"), 10000));
    } else {
      std::printf("sphere_20k.xyz: missing (run data/fetch-models.sh)\n");
    }
    edgefront::shapes::SampleOptions so;
    so.points = 1'000'000;
    const edgefront::PointCloud big = edgefront::shapes::sample("bumpy-sphere", so);
    so.points = 100'000;
    const edgefront::PointCloud small_cloud = edgefront::shapes::sample("bumpy-sphere", so);
    const size_t fixed = 20000 / div;
    const gcs::ReconstructResult a = run(small_cloud, fixed);
    const gcs::ReconstructResult b = run(big, fixed);
    std::printf("fixed target %zu: 100K points %.2f s, 1M points %.2f s, ratio 1M/100K %.3f\n", fixed, a.seconds_total,
                b.seconds_total, b.seconds_total / a.seconds_total);
    print_mesh("bumpy-sphere 1M points at the 100K target", run(big, 100000 / div));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_gcs: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
