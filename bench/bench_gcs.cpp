// bench_gcs: the GCS reconstructor on real and synthetic clouds (not a test; prints a report).
//
//   bench_gcs [--quick] [--eval] [--twist] [--repeat R] [--data DIR] [--case kitten|sphere|fixed|big|step|nested|fit] [--vertices N] [--smoothing K]
//             [--seeds N] [--step-factor F] [--points P] [--reference DIR]
//
// 1. kitten.xyz (CGAL sample, 5210 points) at 5K vertices: time, closed?, genus, valences; with
//    --seeds N also one line per seed 1..N (border loops, genus) and how many ended closed genus 1.
//    (--case sphere --seeds N: the sphere case with seeds 1..N.)
// 6. (--case nested only) nested spheres (shapes::sample "nested-spheres", 20K points) at 4K
//    vertices: components, border loops, genus per component (target: two closed spheres); with
//    --seeds N also one line per seed 1..N and how many ended as two closed spheres oriented as
//    the samples (outer outward, inner into the cavity), with the cloud's normals and without
//    them (the orientation without normals comes from the twist repair's global orientation:
//    add --twist).
// 2. sphere_20k.xyz at 10K vertices: valence-6 share, valence 5-7 share, median minimum angle.
// 3. 100K vertices from a 1M-point synthetic cloud (shapes::sample "bumpy-sphere"): time.
// 4. Runtime at a fixed target (20K vertices) for 100K-point vs 1M-point clouds of the same shape,
//    with both meshes' figures; with --eval also gcs::evaluate of both against the 100K points;
//    with --repeat R, R pairs run alternately, then the CPU ratio of the fastest runs and the
//    median pair ratio.
// 5. (--case step only) time per basic step at --vertices N (default 10000) on the 1M-point cloud:
//    grows to N, then times F * N further basic steps at that size (no splits, no collapses;
//    F = --step-factor, default 100).
// 7. (--case fit only) kitten.xyz at 5K vertices, seeds 1..N (default 8), the result with and
//    without the surface fit (PostProcessOptions::fit_surface), judged by gcs::evaluate against the
//    5,210 points (as gcs-eval: exact distances, 100K samples, seed 1); with --reference DIR also
//    DIR/kitten-advancing-front.off and DIR/kitten-poisson.off (bench/cgal_reconstruct_reference).
// --quadric-normals sets InputOptions::quadric_normals (clouds without normals: the nested
// spheres' second block). --twist registers the twist repair (gcs::TwistOperation, default options) as gcs-reconstruct
// does without --no-twist (the cases above run without it), and prints the time spent in it.
// --quick divides the synthetic targets by 10 (for a smoke run); --case runs one case; --points P
// replaces the 1M-point cloud of cases 3 and 5 by a P-point one. Single thread. Case 3 also prints
// the CPU time of the set-up (Reconstructor constructor: sorting, kd-tree) apart.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <time.h>

#include "edgefront/mesh_io.h"
#include "edgefront/mesh_stats.h"
#include "edgefront/point_cloud_io.h"
#include "shapes/shapes.h"
#include "gcs/evaluation.h"
#include "gcs/reconstructor.h"
#include "gcs/twist_operation.h"
#include "bench_timing.h"

namespace {

using edgefront::Mesh;
using edgefront::Vec3;

using efbench::cpu_seconds;

double g_last_cpu = 0;  // CPU seconds of the last run()
int g_smoothing = -1;   // --smoothing K: smoothing passes per basic step (-1: the default)
std::uint64_t g_seed = 1;

double load_average() {
  double l = -1;
  if (FILE* f = std::fopen("/proc/loadavg", "r")) {
    if (std::fscanf(f, "%lf", &l) != 1) l = -1;
    std::fclose(f);
  }
  return l;
}

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
  std::printf("  time %.2f s wall, %.2f s CPU (load average %.1f) (topology %.2f s wall, surface fit %.2f s wall), %llu basic steps (%.2f us/step wall), %zu splits, %zu collapses, "
              "%zu faces removed, %zu loops merged, %zu slits zipped, %zu holes filled\n",
              r.seconds_total, g_last_cpu, load_average(), r.seconds_topology, r.seconds_fit, static_cast<unsigned long long>(r.basic_steps),
              1e6 * r.seconds_total / std::max<double>(1, static_cast<double>(r.basic_steps)), r.splits, r.collapses,
              r.faces_removed, r.loops_merged, r.slits_zipped, r.holes_filled);
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

bool g_fit = true;  // PostProcessOptions::fit_surface
bool g_twist = false;  // --twist: the twist repair registered as in gcs-reconstruct
bool g_quadric = false;  // --quadric-normals: InputOptions::quadric_normals

gcs::ReconstructResult run(const edgefront::PointCloud& cloud, size_t target) {
  gcs::ReconstructOptions o;
  o.post.fit_surface = g_fit;
  o.input.quadric_normals = g_quadric;
  o.target_vertices = target;
  if (g_smoothing >= 0) o.growth.smoothing_iterations = g_smoothing;
  o.seed = g_seed;
  const double c0 = cpu_seconds();
  gcs::Reconstructor rec(cloud, o);
  if (g_twist) rec.add_operation(std::make_shared<gcs::TwistOperation>(gcs::TwistOperationOptions{}));
  gcs::ReconstructResult r = rec.run();
  g_last_cpu = cpu_seconds() - c0;
  if (g_twist) std::printf("  (twist repair: %.2f s wall in the operation)\n", r.seconds_operations);
  return r;
}

// One line of the fit case: the figures gcs-eval prints, in % of the bounding-box diagonal.
void print_evaluation(const std::string& label, const Mesh& mesh, const gcs::GroundTruth& gt, double cpu) {
  const gcs::Evaluation e = gcs::evaluate(mesh, gt);
  const gcs::MeshValidity& v = e.validity;
  std::printf("  %-24s chamfer %.4f%% (gt->result %.4f%%, result->gt %.4f%%), H95 %.4f%%, normal cons. %.4f, %s, "
              "genus %g, %zu self-intersecting pairs, median min angle %.1f deg, %.2f%% < 30 deg",
              label.c_str(), e.scale(e.chamfer_l1), e.scale(e.gt_to_result.mean), e.scale(e.result_to_gt.mean),
              e.scale(e.hausdorff_p95), e.normal_consistency.value_or(-1),
              v.closed && v.components == 1 && v.edge_manifold && v.vertex_manifold ? "closed manifold" : "NOT closed/manifold",
              v.genus, v.self_intersecting_pairs.value_or(0), v.median_min_angle_deg, 100 * v.faces_min_angle_below_30);
  if (cpu >= 0) std::printf(", %.2f s CPU", cpu);
  std::printf("\n");
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false;
  bool eval = false;
  size_t repeat = 1;
  std::string only;
  size_t vertices = 0;
  size_t seeds = 0;
  size_t step_factor = 100;
  size_t big_points = 1'000'000;
  std::filesystem::path reference;
  std::filesystem::path data = EDGEFRONT_BENCH_DATA_DIR;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--quick")) quick = true;
    else if (!std::strcmp(argv[i], "--eval")) eval = true;
    else if (!std::strcmp(argv[i], "--twist")) g_twist = true;
    else if (!std::strcmp(argv[i], "--quadric-normals")) g_quadric = true;
    else if (!std::strcmp(argv[i], "--repeat") && i + 1 < argc) repeat = std::stoul(argv[++i]);
    else if (!std::strcmp(argv[i], "--data") && i + 1 < argc) data = argv[++i];
    else if (!std::strcmp(argv[i], "--case") && i + 1 < argc) only = argv[++i];
    else if (!std::strcmp(argv[i], "--vertices") && i + 1 < argc) vertices = std::stoul(argv[++i]);
    else if (!std::strcmp(argv[i], "--smoothing") && i + 1 < argc) g_smoothing = std::stoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--seeds") && i + 1 < argc) seeds = std::stoul(argv[++i]);
    else if (!std::strcmp(argv[i], "--step-factor") && i + 1 < argc) step_factor = std::stoul(argv[++i]);
    else if (!std::strcmp(argv[i], "--points") && i + 1 < argc) big_points = std::stoul(argv[++i]);
    else if (!std::strcmp(argv[i], "--reference") && i + 1 < argc) reference = argv[++i];
    else {
      std::fprintf(stderr, "usage: bench_gcs [--quick] [--eval] [--twist] [--repeat R] [--data DIR] [--case kitten|sphere|fixed|big|step|nested|fit] [--vertices N] [--smoothing K] [--seeds N] [--step-factor F] [--points P] [--reference DIR]\n");
      return 2;
    }
  }
  const size_t div = quick ? 10 : 1;
  const auto want = [&](const char* name) { return only.empty() || only == name; };
  try {
    const auto models = data / "models";
    if (!want("kitten")) {
    } else if (std::filesystem::exists(models / "kitten.xyz")) {
      const edgefront::PointCloud kitten = edgefront::read_points(models / "kitten.xyz");
      print_mesh("kitten.xyz at 5K", run(kitten, 5000));
      size_t closed_genus1 = 0;
      for (size_t seed = 1; seed <= seeds; ++seed) {
        g_seed = seed;
        const gcs::ReconstructResult r = run(kitten, 5000);
        const edgefront::MeshStats s = edgefront::compute_stats(r.mesh);
        const double genus = s.per_component.empty() ? 0.0 : s.per_component[0].genus;
        const bool ok = s.components == 1 && s.border_loops == 0 && s.nonmanifold_vertices == 0 && genus == 1;
        closed_genus1 += ok;
        std::printf("  seed %zu: %zu component(s), %zu border loop(s), genus %g, %.2f s CPU%s\n", seed, s.components,
                    s.border_loops, genus, g_last_cpu, ok ? "  closed genus 1" : "");
      }
      g_seed = 1;
      if (seeds) std::printf("  closed, manifold, genus 1 on %zu of %zu seeds\n", closed_genus1, seeds);
    } else {
      std::printf("kitten.xyz: missing (run data/fetch-models.sh)\n");
    }
    if (only == "fit") {
      const edgefront::PointCloud kitten = edgefront::read_points(models / "kitten.xyz");
      const gcs::GroundTruth gt = gcs::GroundTruth::from_points(kitten);
      std::printf("kitten.xyz at 5K vertices, surface fit off / on (load average %.1f):\n", load_average());
      for (const char* name : {"advancing-front", "poisson"}) {
        const auto path = reference / ("kitten-" + std::string(name) + ".off");
        if (!reference.empty() && std::filesystem::exists(path))
          print_evaluation(std::string("CGAL ") + name, edgefront::load_mesh(path.string()), gt, -1);
      }
      for (size_t seed = 1; seed <= (seeds ? seeds : 8); ++seed) {
        g_seed = seed;
        for (const bool fit : {false, true}) {
          g_fit = fit;
          const gcs::ReconstructResult r = run(kitten, 5000);
          print_evaluation("seed " + std::to_string(seed) + (fit ? " fit" : " no fit"), r.mesh, gt, g_last_cpu);
        }
      }
      g_seed = 1;
      g_fit = true;
    }
    if (only == "nested") {
      edgefront::shapes::SampleOptions so;
      so.points = 20000;
      const edgefront::PointCloud nested = edgefront::shapes::sample("nested-spheres", so);
      print_mesh("nested spheres (20K points) at 4K", run(nested, 4000));
      // --seeds N: how many of seeds 1..N end as two closed spheres oriented as the samples, from
      // the oriented cloud and from its points alone (normals fitted; the orientation is judged
      // against the true normals).
      const edgefront::PointCloud bare = [&] {
        edgefront::PointCloud c = nested;
        c.normals.clear();
        return c;
      }();
      for (const edgefront::PointCloud* input : {&nested, &bare}) {
        if (seeds <= 1) break;
        std::printf("  %s:\n", input == &nested ? "with normals" : "without normals");
        size_t two_closed = 0;
        for (size_t seed = 1; seed <= seeds; ++seed) {
          g_seed = seed;
          const Mesh mesh = run(*input, 4000).mesh;
          const edgefront::MeshStats s = edgefront::compute_stats(mesh);
          // Which spheres: vertices within r < 0.75 are on the inner one (radius 0.5), the others
          // on the outer (radius 1); the orientation against the samples' (outward / inward) normals.
          size_t inner = 0;
          for (auto v : mesh.vertices()) inner += mesh.point(v).norm() < 0.75;
          const double oriented = gcs::orientation_consistency(mesh, nested).raw;
          const bool ok = s.components == 2 && s.border_loops == 0 && s.nonmanifold_vertices == 0 && inner > 0 &&
                          inner < mesh.n_vertices() && oriented > 0.99;
          two_closed += ok;
          std::printf("  seed %zu: %zu component(s), %zu border loop(s), %zu of %zu vertices on the inner sphere, "
                      "orientation consistency %.4f%s\n",
                      seed, s.components, s.border_loops, inner, mesh.n_vertices(), oriented,
                      ok ? "  two closed spheres" : "");
        }
        g_seed = 1;
        std::printf("  two closed spheres on %zu of %zu seeds\n", two_closed, seeds);
      }
    }
    if (!want("sphere")) {
    } else if (std::filesystem::exists(models / "sphere_20k.xyz")) {
      const edgefront::PointCloud sphere = edgefront::read_points(models / "sphere_20k.xyz");
      print_mesh("sphere_20k.xyz at 10K", run(sphere, 10000));
      for (size_t seed = 2; seed <= seeds; ++seed) {  // --seeds N: also seeds 2..N
        g_seed = seed;
        print_mesh(("sphere_20k.xyz at 10K, seed " + std::to_string(seed)).c_str(), run(sphere, 10000));
      }
      g_seed = 1;
    } else {
      std::printf("sphere_20k.xyz: missing (run data/fetch-models.sh)\n");
    }
    if (!want("fixed") && !want("big") && !want("step")) return 0;
    edgefront::shapes::SampleOptions so;
    so.points = want("fixed") ? 1'000'000 : big_points;
    const edgefront::PointCloud big = edgefront::shapes::sample("bumpy-sphere", so);
    if (want("fixed")) {
      so.points = 100'000;
      const edgefront::PointCloud small_cloud = edgefront::shapes::sample("bumpy-sphere", so);
      const size_t fixed = vertices ? vertices : 20000 / div;
      // --repeat R: R pairs, the two clouds alternately (the machine's load drifts).
      gcs::ReconstructResult a, b;
      double cpu_a = 0, cpu_b = 0;
      std::vector<double> all_a, all_b, ratios;
      for (size_t k = 0; k < std::max<size_t>(1, repeat); ++k) {
        a = run(small_cloud, fixed);
        cpu_a = g_last_cpu;
        b = run(big, fixed);
        cpu_b = g_last_cpu;
        all_a.push_back(cpu_a);
        all_b.push_back(cpu_b);
        ratios.push_back(cpu_b / cpu_a);
        std::printf("fixed target %zu: 100K points %.2f s wall / %.2f s CPU, 1M points %.2f s wall / %.2f s CPU, "
                    "ratio 1M/100K %.3f (CPU %.3f), load average %.1f\n",
                    fixed, a.seconds_total, cpu_a, b.seconds_total, cpu_b, b.seconds_total / a.seconds_total,
                    cpu_b / cpu_a, load_average());
      }
      if (ratios.size() > 1) {
        const size_t within = static_cast<size_t>(
            std::count_if(ratios.begin(), ratios.end(), [](double r) { return r >= 0.8 && r <= 1.2; }));
        std::sort(ratios.begin(), ratios.end());
        std::printf("  %zu pairs: CPU ratio of the fastest runs %.3f (%.2f / %.2f s), median pair ratio %.3f, "
                    "pairs within +-20%%: %zu\n",
                    ratios.size(), *std::min_element(all_b.begin(), all_b.end()) / *std::min_element(all_a.begin(), all_a.end()),
                    *std::min_element(all_b.begin(), all_b.end()), *std::min_element(all_a.begin(), all_a.end()),
                    ratios[ratios.size() / 2], within);
      }
      // Where the difference goes: the set-up alone (Reconstructor constructor) and the topology passes.
      double setup[2];
      for (int k = 0; k < 2; ++k) {
        gcs::ReconstructOptions o;
        o.target_vertices = fixed;
        const double c0 = cpu_seconds();
        gcs::Reconstructor r(k == 0 ? small_cloud : big, o);
        setup[k] = cpu_seconds() - c0;
      }
      std::printf("  set-up CPU: 100K %.2f s, 1M %.2f s; topology wall: 100K %.2f s, 1M %.2f s\n", setup[0], setup[1],
                  a.seconds_topology, b.seconds_topology);
      g_last_cpu = cpu_a;
      print_mesh("  100K points", a);
      g_last_cpu = cpu_b;
      print_mesh("  1M points", b);
      if (eval) {  // both against the 100K-point cloud (the same shape)
        const gcs::GroundTruth gt = gcs::GroundTruth::from_points(small_cloud);
        print_evaluation("100K points", a.mesh, gt, cpu_a);
        print_evaluation("1M points", b.mesh, gt, cpu_b);
      }
    }
    if (want("big")) {
      const size_t n = vertices ? vertices : 100000 / div;
      {  // the set-up alone (the run below includes it)
        gcs::ReconstructOptions o;
        o.target_vertices = n;
        const double c0 = cpu_seconds();
        gcs::Reconstructor setup(big, o);
        std::printf("set-up (%zu points): %.2f s CPU\n", big.size(), cpu_seconds() - c0);
      }
      print_mesh(("bumpy-sphere " + std::to_string(big.size()) + " points at the " + std::to_string(n) + " target").c_str(),
                 run(big, n));
    }
    if (only == "step") {
      const size_t n = vertices ? vertices : 10000;
      gcs::ReconstructOptions o;
      o.target_vertices = n;
      if (g_smoothing >= 0) o.growth.smoothing_iterations = g_smoothing;
      gcs::Reconstructor rec(big, o);
      rec.run();
      const std::uint64_t steps = std::max<std::uint64_t>(1, step_factor) * static_cast<std::uint64_t>(n);
      const auto t0 = std::chrono::steady_clock::now();
      const double c0 = cpu_seconds();
      rec.run_basic_steps(steps);
      const double cpu = cpu_seconds() - c0;
      const double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      std::printf("basic step at %zu vertices (%zu-point cloud): %.3f us CPU, %.3f us wall (%llu steps, load "
                  "average %.1f)\n",
                  n, big.size(), 1e6 * cpu / static_cast<double>(steps), 1e6 * dt / static_cast<double>(steps),
                  static_cast<unsigned long long>(steps), load_average());
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_gcs: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
