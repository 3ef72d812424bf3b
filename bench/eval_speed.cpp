// eval_speed: time of gcs::evaluate on bumpy spheres of growing size (single thread).
//
//   eval_speed [--samples N] [--repeats R]
//
// Result meshes: edgefront::shapes::bumpy_sphere(s) for s = 5, 6, 7 (20K, 82K, 328K faces);
// ground truth: N analytic oriented samples of the same bumpy sphere (default N = 100000, also
// the number of mesh samples). Per size it prints the best of R runs (default 3) of:
//   exact      evaluate() with exact point-to-triangle distances (BVH), no self-intersection count
//   p2p        evaluate() with exact_surface_distance = false (nanoflann over the mesh samples: the
//              common point-to-point method, the baseline)
//   selfint    count_self_intersections() alone
// and the ratio exact / p2p. Exit codes: 0 done, 2 usage.

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>

#include "bench_timing.h"
#include "shapes/shapes.h"
#include "gcs/evaluation.h"

int main(int argc, char** argv) {
  std::size_t samples = 100000;
  int repeats = 3;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if ((arg == "--samples" || arg == "--repeats") && i + 1 < argc) {
      const long long v = std::atoll(argv[++i]);
      if (v < 1) {
        std::cerr << "eval_speed: error: " << arg << " must be >= 1\n";
        return 2;
      }
      if (arg == "--samples") samples = static_cast<std::size_t>(v);
      if (arg == "--repeats") repeats = static_cast<int>(v);
    } else {
      std::cerr << "usage: eval_speed [--samples N] [--repeats R]\n";
      return 2;
    }
  }
  edgefront::shapes::SampleOptions so;
  so.points = samples;
  const gcs::GroundTruth gt = gcs::GroundTruth::from_points(edgefront::shapes::sample("bumpy-sphere", so));
  std::printf("samples %zu (mesh) and %zu (ground truth points), best of %d runs\n", samples, samples,
              repeats);
  std::printf("%10s %10s %10s %10s %12s %14s\n", "faces", "exact_s", "p2p_s", "selfint_s", "exact/p2p",
              "chamfer_%");
  for (const int s : {5, 6, 7}) {
    const edgefront::Mesh mesh = edgefront::shapes::bumpy_sphere(s);
    gcs::EvaluationOptions exact;
    exact.samples = samples;
    exact.self_intersections = false;
    gcs::EvaluationOptions p2p = exact;
    p2p.exact_surface_distance = false;
    gcs::Evaluation e;
    std::size_t pairs = 0;
    const double t_exact = efbench::best_seconds(repeats, [&] { e = gcs::evaluate(mesh, gt, exact); });
    const double t_p2p = efbench::best_seconds(repeats, [&] { gcs::evaluate(mesh, gt, p2p); });
    const double t_self =
        efbench::best_seconds(repeats, [&] { pairs = gcs::count_self_intersections(mesh); });
    std::printf("%10zu %10.3f %10.3f %10.3f %12.2f %14.5f%s\n", mesh.n_faces(), t_exact, t_p2p, t_self,
                t_exact / t_p2p, e.scale(e.chamfer_l1), pairs ? "  (self-intersections found!)" : "");
  }
  return 0;
}
