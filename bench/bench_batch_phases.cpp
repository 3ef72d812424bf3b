// bench_batch_phases: the reconstructor's phases that run in parallel over points, with 1 and
// more threads, on a large cloud.
//
//   bench_batch_phases [--points N] [--threads 1,2] [--repeats R]
//
// The cloud: N points (default 1,000,000) sampled from the bumpy sphere with Gaussian noise of
// 0.002 along the normal (normals dropped for the fits, as for a scan without them). Phases:
// estimate_noise, smooth_noise (64 neighbours), fit_normals (12 neighbours, quadric normals at the
// points), and evaluate (gcs-eval's work: the bumpy sphere's 81,920-face mesh against the cloud as
// ground truth, 100,000 samples, exact surface distances and the self-intersection count). For
// each: best wall time of R runs per thread count, the speed-up against the first thread count
// of the same run, the process CPU time per run (all threads) and its ratio to the wall time; every result is compared byte for byte with the first thread count's (a
// difference is an error, exit 1). Prints a Markdown table.

#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "bench_timing.h"
#include "edgefront/parallel.h"
#include "edgefront/point_index.h"
#include "shapes/shapes.h"
#include "gcs/cloud_noise.h"
#include "gcs/cloud_normals.h"
#include "gcs/evaluation.h"

namespace {

using efbench::load_average;
using efbench::process_cpu_seconds;

template <class T>
std::string bytes_of(const std::vector<T>& v) {
  return std::string(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
}

}  // namespace

int main(int argc, char** argv) {
  std::size_t n = 1000000;
  std::vector<unsigned> thread_counts{1, 2};
  int repeats = 1;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool has_value = i + 1 < argc;
    if (a == "--points" && has_value) {
      n = std::stoul(argv[++i]);
    } else if (a == "--threads" && has_value) {
      thread_counts.clear();
      for (const std::string& t : efbench::split_list(argv[++i])) thread_counts.push_back(static_cast<unsigned>(std::stoul(t)));
    } else if (a == "--repeats" && has_value) {
      repeats = std::stoi(argv[++i]);
    } else {
      std::cerr << "usage: bench_batch_phases [--points N] [--threads 1,2] [--repeats R]\n";
      return 2;
    }
  }
  if (n < 100 || thread_counts.empty() || repeats < 1) {
    std::cerr << "bench_batch_phases: --points >= 100, --threads and --repeats positive\n";
    return 2;
  }
  edgefront::shapes::SampleOptions so;
  so.points = n;
  so.noise_sigma = 0.002;
  edgefront::PointCloud cloud = edgefront::shapes::sample("bumpy-sphere", so);
  edgefront::PointCloud bare;
  bare.points = cloud.points;
  edgefront::shapes::MeshOptions mo;
  mo.resolution = 320;
  const edgefront::Mesh mesh = edgefront::shapes::make("bumpy-sphere", mo);
  const edgefront::PointIndex index(bare.points);
  const gcs::GroundTruth truth = gcs::GroundTruth::from_points(cloud);

  std::printf("cloud: bumpy sphere, %zu points, noise 0.002; mesh for evaluate: %zu faces; best of %d; hardware "
              "threads %u; load before %.2f\n\n",
              n, mesh.n_faces(), repeats, edgefront::default_threads(), load_average());
  std::printf("| phase | threads | best s | speed-up | CPU s per run | CPU / wall |\n|---|---|---|---|---|---|\n");
  int status = 0;
  auto phase = [&](const char* name, auto&& run) {  // run(threads) -> the result's bytes
    std::string reference;
    double base = 0;
    for (const unsigned t : thread_counts) {
      std::string bytes;
      const double cpu0 = process_cpu_seconds();
      const auto w0 = std::chrono::steady_clock::now();
      const double s = efbench::best_seconds(repeats, [&] { bytes = run(t); });
      const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count();
      const double cpu = process_cpu_seconds() - cpu0;
      if (reference.empty() && t == thread_counts.front()) {
        reference = bytes;
        base = s;
      } else if (bytes != reference) {
        std::fprintf(stderr, "bench_batch_phases: %s with %u threads differs from %u threads\n", name, t,
                     thread_counts.front());
        status = 1;
      }
      std::printf("| %s | %u | %.3f | %.2fx | %.3f | %.2f |\n", name, edgefront::resolve_threads(t), s, base / s,
                  cpu / repeats, cpu / wall);
      std::fflush(stdout);
    }
  };
  phase("estimate_noise", [&](unsigned t) {
    gcs::NoiseOptions o;
    o.threads = t;
    const gcs::NoiseEstimate e = gcs::estimate_noise(bare, o);
    return bytes_of(std::vector<double>{e.noise, e.residual, e.wide_residual, e.spacing});
  });
  phase("smooth_noise", [&](unsigned t) {
    edgefront::PointCloud c = bare;
    gcs::SmoothNoiseOptions o;
    o.threads = t;
    gcs::smooth_noise(c, o);
    return bytes_of(c.points);
  });
  phase("fit_normals", [&](unsigned t) {
    gcs::NormalFitOptions o;
    o.threads = t;
    o.quadric_normal = true;
    return bytes_of(gcs::fit_normals(bare.points, index, o));
  });
  phase("evaluate", [&](unsigned t) {
    gcs::EvaluationOptions o;
    o.threads = t;
    return gcs::format_evaluation(gcs::evaluate(mesh, truth, o));
  });
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  std::printf("\nprocess peak RSS %.1f MB; load after %.2f\n", ru.ru_maxrss / 1e3, load_average());
  return status;
}
