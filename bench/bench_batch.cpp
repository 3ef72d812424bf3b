// bench_batch: batch geodesics (edgefront/batch_distance.h) with 1 and more threads.
//
//   bench_batch [MESH] [--sources K] [--threads 1,2] [--methods mdf,fast,...] [--repeats R]
//
// MESH defaults to the bumpy sphere at resolution 320 (an icosphere of 81,920 faces). For each method and thread
// count: the best wall time of R batches of K full fields (sources evenly strided over the
// vertex indices), fields per second, the speed-up against the first thread count of the same
// run, the CPU time of the process per batch (all threads) and its ratio to the wall time (how
// many cores the batch really had: the machine may be shared), and the memory the batch accounts for (the sum over
// the threads of one field's working memory, the result, the shared table). Every batch's result
// is compared byte for byte with the first thread count's: a difference is an error (exit 1).
// Prints a Markdown table.

#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "bench_timing.h"
#include "edgefront/batch_distance.h"
#include "edgefront/mesh_io.h"
#include "edgefront/parallel.h"
#include "shapes/shapes.h"

namespace {

using efbench::load_average;
using efbench::process_cpu_seconds;

}  // namespace

int main(int argc, char** argv) {
  std::string mesh_path;
  std::size_t k = 16;
  std::vector<unsigned> thread_counts{1, 2};
  std::vector<std::string> methods{"mdf", "fast", "dijkstra"};
  int repeats = 3;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool has_value = i + 1 < argc;
    if (a == "--sources" && has_value) {
      k = std::stoul(argv[++i]);
    } else if (a == "--threads" && has_value) {
      thread_counts.clear();
      for (const std::string& t : efbench::split_list(argv[++i])) thread_counts.push_back(static_cast<unsigned>(std::stoul(t)));
    } else if (a == "--methods" && has_value) {
      methods = efbench::split_list(argv[++i]);
    } else if (a == "--repeats" && has_value) {
      repeats = std::stoi(argv[++i]);
    } else if (!a.empty() && a[0] != '-' && mesh_path.empty()) {
      mesh_path = a;
    } else {
      std::cerr << "usage: bench_batch [MESH] [--sources K] [--threads 1,2] [--methods mdf,fast] [--repeats R]\n";
      return 2;
    }
  }
  if (k == 0 || thread_counts.empty() || repeats < 1) {
    std::cerr << "bench_batch: --sources, --threads and --repeats need positive values\n";
    return 2;
  }
  edgefront::Mesh mesh;
  std::string name;
  if (mesh_path.empty()) {
    edgefront::shapes::MeshOptions mo;
    mo.resolution = 320;
    mesh = edgefront::shapes::make("bumpy-sphere", mo);
    name = "bumpy-sphere (resolution 320)";
  } else {
    mesh = edgefront::read_mesh(mesh_path).mesh;
    name = mesh_path;
  }
  std::vector<edgefront::VertexHandle> sources;
  for (std::size_t i = 0; i < k; ++i) sources.emplace_back(static_cast<int>(i * mesh.n_vertices() / k));

  std::printf("mesh: %s, %zu vertices, %zu faces; %zu sources; best of %d; hardware threads %u; load before %.2f\n\n",
              name.c_str(), mesh.n_vertices(), mesh.n_faces(), k, repeats, edgefront::default_threads(), load_average());
  std::printf("| method | threads | best s | fields/s | speed-up | CPU s per batch | CPU / wall | working memory (all threads) | result | table |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|\n");
  int status = 0;
  for (const std::string& method : methods) {
    edgefront::DistanceOptions o;
    o.method = edgefront::parse_distance_method(method);
    std::vector<double> reference;
    double base = 0;
    for (const unsigned t : thread_counts) {
      edgefront::DistanceMatrix m;
      const double cpu0 = process_cpu_seconds();
      const auto w0 = std::chrono::steady_clock::now();
      const double s = efbench::best_seconds(repeats, [&] { m = edgefront::geodesic_distances(mesh, sources, o, {.threads = t}); });
      const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count();
      const double cpu = (process_cpu_seconds() - cpu0) / repeats;
      if (reference.empty()) {
        reference = m.values;
        base = s;
      } else if (reference.size() != m.values.size() ||
                 std::memcmp(reference.data(), m.values.data(), reference.size() * sizeof(double)) != 0) {
        std::fprintf(stderr, "bench_batch: %s with %u threads differs from %u threads\n", method.c_str(), t,
                     thread_counts.front());
        status = 1;
      }
      std::printf("| %s | %u | %.3f | %.2f | %.2fx | %.3f | %.2f | %.1f MB | %.1f MB | %.1f MB |\n", method.c_str(), m.threads,
                  s, static_cast<double>(k) / s, base / s, cpu, cpu * repeats / wall, m.peak_working_memory_bytes / 1e6,
                  m.values.size() * sizeof(double) / 1e6, m.table_bytes / 1e6);
      std::fflush(stdout);
    }
  }
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  std::printf("\nprocess peak RSS %.1f MB; load after %.2f\n", ru.ru_maxrss / 1e3, load_average());
  return status;
}
