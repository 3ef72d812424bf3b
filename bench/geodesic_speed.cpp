// geodesic_speed: speed and memory of the Minimal Distance Front.
//
//   geodesic_speed [--model PATH] [--subdiv K] [--sources N] [--reps R] [--seed S]
//                  [--small CELLS] [--large CELLS] [--cell H] [--dmax D] [--queries Q]
//                  [--skip-full] [--skip-dmax] [--windows] [--fast-only]
//
// 1. Full field: the model (default data/models/armadillo.off) Loop-subdivided K times (default 2:
//    the armadillo's 52K triangles become 832K) with OpenMesh's LoopT; from N random sources
//    (default 5), edgefront::geodesic_distance against edgefront::dijkstra_distance (binary heap,
//    same mesh) in the same run, each timed R times (default 3) alternately, the median taken. Both
//    with default options (directions on) and with directions off, and with the edge front not
//    tracked (DistanceOptions::track_front off, directions on). Also a sanity check of the
//    MDF's values: Euclidean <= MDF <= Dijkstra (up to 1e-9 relative). And the fast mode
//    (DistanceMethod::Fast, directions on): time, ratio to Dijkstra, the same bounds, and its mean
//    relative difference from the default MDF.
// 2. d_max queries: the same query (source at the centre vertex, d_max D, default 0.5) on a
//    planar grid of SMALL x SMALL cells (default 100) and one of LARGE x LARGE cells (default
//    2000), both with cell size H (default 0.02), so the local triangulation is the same. With the
//    reusable MinimalDistanceFront: vertices settled, peak front, the MDF's own peak working
//    memory, the heap growth measured here (every operator new / delete of the process is
//    counted), time of the first query and mean time of Q repeated queries (default 200). For
//    contrast, the free functions geodesic_distance and dijkstra_distance with max_distance.
//
// --windows: the MDF runs with DistanceMethod::Windows (windows per edge).
// --fast-only: part 1 times only the fast mode and Dijkstra (directions on), by thread CPU time
//    (medians of 2R runs each per source, the order rotated every repetition): Dijkstra over the
//    mesh's halfedges, the GeodesicRingTable's build, the fast mode on the table, Dijkstra on the
//    table, and the per-call fast mode (build + query); ratios, the same bounds check, whether the
//    query equals the per-call field, the table's and the query's memory.
//
// Output: markdown on stdout, progress on stderr. Exit codes: 0 done, 1 error, 2 usage.

#include <malloc.h>
#include <time.h>

#include <OpenMesh/Tools/Subdivider/Uniform/LoopT.hh>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <limits>
#include <new>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "edgefront/error.h"
#include "edgefront/front_source.h"
#include "edgefront/geodesic_ring_table.h"
#include "edgefront/mesh.h"
#include "edgefront/mesh_io.h"
#include "edgefront/minimal_distance_front.h"
#include "shapes/shapes.h"

// ---- heap accounting: every allocation of the process through operator new --------------------

namespace heap {
std::atomic<long long> current{0};
std::atomic<long long> peak{0};

inline void note_alloc(void* p) {
  const long long n = static_cast<long long>(malloc_usable_size(p));
  const long long now = current.fetch_add(n, std::memory_order_relaxed) + n;
  long long old = peak.load(std::memory_order_relaxed);
  while (now > old && !peak.compare_exchange_weak(old, now, std::memory_order_relaxed)) {
  }
}
inline void note_free(void* p) { current.fetch_sub(static_cast<long long>(malloc_usable_size(p)), std::memory_order_relaxed); }

inline void* allocate(std::size_t n) {
  void* p = std::malloc(n ? n : 1);
  if (p) note_alloc(p);
  return p;
}
inline void* allocate_aligned(std::size_t n, std::size_t align) {
  void* p = nullptr;
  if (posix_memalign(&p, std::max(align, sizeof(void*)), n ? n : 1) != 0) return nullptr;
  note_alloc(p);
  return p;
}
inline void release(void* p) noexcept {
  if (!p) return;
  note_free(p);
  std::free(p);
}

/// Peak heap use above the level at the time of the last `reset_peak`.
struct Region {
  long long start;
  Region() : start(current.load()) { peak.store(start); }
  long long peak_growth() const { return peak.load() - start; }
  long long growth() const { return current.load() - start; }
};
}  // namespace heap

void* operator new(std::size_t n) {
  if (void* p = heap::allocate(n)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t n) {
  if (void* p = heap::allocate(n)) return p;
  throw std::bad_alloc();
}
void* operator new(std::size_t n, const std::nothrow_t&) noexcept { return heap::allocate(n); }
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept { return heap::allocate(n); }
void* operator new(std::size_t n, std::align_val_t a) {
  if (void* p = heap::allocate_aligned(n, static_cast<std::size_t>(a))) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t n, std::align_val_t a) {
  if (void* p = heap::allocate_aligned(n, static_cast<std::size_t>(a))) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { heap::release(p); }
void operator delete[](void* p) noexcept { heap::release(p); }
void operator delete(void* p, std::size_t) noexcept { heap::release(p); }
void operator delete[](void* p, std::size_t) noexcept { heap::release(p); }
void operator delete(void* p, std::align_val_t) noexcept { heap::release(p); }
void operator delete[](void* p, std::align_val_t) noexcept { heap::release(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { heap::release(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { heap::release(p); }

namespace {

namespace fs = std::filesystem;
using edgefront::DistanceField;
using edgefront::DistanceOptions;
using edgefront::DistanceStop;
using edgefront::FrontSource;
using edgefront::Mesh;
using edgefront::Vec3;
using edgefront::VertexHandle;

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// CPU time of the calling thread (s): unlike the wall clock it does not count the time spent
// waiting for a core, the main noise on a shared machine.
double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

std::string secs(double s) {
  std::ostringstream os;
  if (!std::isfinite(s))
    os << "n/a";
  else if (s < 0.9995e-3)
    os << std::setprecision(3) << s * 1e6 << " µs";
  else if (s < 0.9995)
    os << std::setprecision(3) << s * 1e3 << " ms";
  else
    os << std::setprecision(3) << s << " s";
  return os.str();
}

std::string bytes(long long b) {
  std::ostringstream os;
  const double x = static_cast<double>(b);
  if (std::llabs(b) < 10 * 1024)
    os << b << " B";
  else if (std::llabs(b) < 10LL * 1024 * 1024)
    os << std::setprecision(4) << x / 1024.0 << " KiB";
  else
    os << std::setprecision(4) << x / (1024.0 * 1024.0) << " MiB";
  return os.str();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

struct Args {
  fs::path model;
  int subdiv = 2;
  int sources = 5;
  int reps = 3;
  std::uint64_t seed = 1;
  int small = 100;
  int large = 2000;
  double cell = 0.02;
  double dmax = 0.5;
  int queries = 200;
  bool full = true;
  bool dmax_part = true;
  bool windows = false;  // --windows: DistanceMethod::Windows
  bool fast_only = false;  // --fast-only: part 1 times only Dijkstra and the fast mode
};

void fast_only(const Mesh& mesh, const std::vector<int>& sources, const Args& a);

// ---- part 1: full field --------------------------------------------------------------------

void full_field(const Args& a) {
  std::cerr << "geodesic_speed: reading " << a.model << "\n";
  Mesh mesh = edgefront::load_mesh(a.model);
  const size_t faces0 = mesh.n_faces();
  const auto t0 = Clock::now();
  if (a.subdiv > 0) {
    OpenMesh::Subdivider::Uniform::LoopT<Mesh, double> loop;
    loop.attach(mesh);
    loop(static_cast<size_t>(a.subdiv));
    loop.detach();
  }
  const double subdiv_s = seconds_since(t0);
  mesh.update_face_normals();
  const size_t n = mesh.n_vertices();

  std::vector<int> usable;
  for (const auto v : mesh.vertices())
    if (!mesh.is_isolated(v)) usable.push_back(v.idx());
  std::mt19937_64 rng(a.seed);
  std::vector<int> sources;
  while (static_cast<int>(sources.size()) < a.sources && sources.size() < usable.size()) {
    const int s = usable[rng() % usable.size()];
    if (std::find(sources.begin(), sources.end(), s) == sources.end()) sources.push_back(s);
  }

  std::cout << "\n### Full field: " << a.model.stem().string() << ", Loop-subdivided " << a.subdiv << "x ("
            << faces0 << " -> " << mesh.n_faces() << " triangles, " << n << " vertices; subdivision "
            << secs(subdiv_s) << ")\n\n";
  if (a.fast_only) {
    fast_only(mesh, sources, a);
    return;
  }
  std::cout << "Median of " << a.reps << " alternating runs per source and configuration.\n\n"
            << "| source | Dijkstra | MDF | **MDF / Dijkstra** | Dijkstra, no directions | MDF, no directions | ratio, no "
               "directions | MDF, front not tracked | ratio, front not tracked | MDF peak front | MDF peak working memory | "
               "Dijkstra / MDF distance (mean) | MDF below Euclidean / above Dijkstra | fast | **fast / Dijkstra** | fast: "
               "below Euclidean / above Dijkstra | fast vs MDF: mean, max relative difference |\n"
               "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  std::vector<double> ratios, ratios_nodir, ratios_untracked, ratios_fast;
  bool untracked_same = true;  // DistanceOptions::track_front off gave the same distances
  double cpu_dij = 0, cpu_mdf = 0;  // summed thread CPU time of the runs with directions
  double min_cpu_dij = 0, min_cpu_mdf = 0;  // summed over sources: the fastest run's CPU time
  for (const int s : sources) {
    std::cerr << "geodesic_speed: full field from " << s << "\n";
    const FrontSource src = FrontSource::vertex(VertexHandle(s));
    DistanceOptions with_dir, no_dir;
    no_dir.directions = false;
    with_dir.method = no_dir.method = a.windows ? edgefront::DistanceMethod::Windows : edgefront::DistanceMethod::Mdf;
    DistanceOptions untracked = with_dir;
    untracked.track_front = false;
    DistanceOptions fast = with_dir;
    fast.method = edgefront::DistanceMethod::Fast;
    std::vector<double> td, tm, tdn, tmn, tmu, tf, cd, cm;
    DistanceField mdf, dij, fst;
    for (int r = 0; r < a.reps; ++r) {
      double c = thread_cpu_seconds();
      auto t = Clock::now();
      dij = edgefront::dijkstra_distance(mesh, src, with_dir);
      td.push_back(seconds_since(t));
      cd.push_back(thread_cpu_seconds() - c);
      cpu_dij += cd.back();
      c = thread_cpu_seconds();
      t = Clock::now();
      mdf = edgefront::geodesic_distance(mesh, src, with_dir);
      tm.push_back(seconds_since(t));
      cm.push_back(thread_cpu_seconds() - c);
      cpu_mdf += cm.back();
      t = Clock::now();
      (void)edgefront::dijkstra_distance(mesh, src, no_dir);
      tdn.push_back(seconds_since(t));
      t = Clock::now();
      (void)edgefront::geodesic_distance(mesh, src, no_dir);
      tmn.push_back(seconds_since(t));
      t = Clock::now();
      const DistanceField mu = edgefront::geodesic_distance(mesh, src, untracked);
      tmu.push_back(seconds_since(t));
      untracked_same = untracked_same && mu.distance == mdf.distance;
      t = Clock::now();
      fst = edgefront::geodesic_distance(mesh, src, fast);
      tf.push_back(seconds_since(t));
    }
    size_t fast_below = 0, fast_above = 0;
    double fast_diff_sum = 0, fast_diff_max = 0;
    size_t fast_compared = 0;
    for (size_t v = 0; v < n; ++v) {
      const double df = fst.distance[v], dm = mdf.distance[v], dd = dij.distance[v];
      if (std::isfinite(dd) != std::isfinite(df)) ++fast_above;  // reached by one and not the other
      if (!std::isfinite(df) || !std::isfinite(dd)) continue;
      const double e = (mesh.point(VertexHandle(static_cast<int>(v))) - mesh.point(VertexHandle(s))).norm();
      if (df < e * (1 - 1e-9)) ++fast_below;
      if (df > dd * (1 + 1e-9)) ++fast_above;
      if (std::isfinite(dm) && dm > 0) {
        const double r = std::abs(df - dm) / dm;
        fast_diff_sum += r;
        fast_diff_max = std::max(fast_diff_max, r);
        ++fast_compared;
      }
    }
    // Sanity: Euclidean <= MDF <= Dijkstra.
    const Vec3 ps = mesh.point(VertexHandle(s));
    size_t below_euclid = 0, above_dijkstra = 0, compared = 0, unreached = 0;
    double ratio_sum = 0, worst_below = 0;
    int worst_vertex = -1;
    for (size_t v = 0; v < n; ++v) {
      const double dm = mdf.distance[v], dd = dij.distance[v];
      if (!std::isfinite(dd)) continue;
      if (!std::isfinite(dm)) {
        ++unreached;
        continue;
      }
      const double e = (mesh.point(VertexHandle(static_cast<int>(v))) - ps).norm();
      if (dm < e * (1 - 1e-9)) {
        ++below_euclid;
        if ((e - dm) / e > worst_below) {
          worst_below = (e - dm) / e;
          worst_vertex = static_cast<int>(v);
        }
      }
      if (dm > dd * (1 + 1e-9)) ++above_dijkstra;
      if (dm > 0) {
        ratio_sum += dd / dm;
        ++compared;
      }
    }
    std::ostringstream bounds;
    bounds << below_euclid << " / " << above_dijkstra;
    if (worst_vertex >= 0)
      bounds << " (worst: vertex " << worst_vertex << ", MDF " << std::setprecision(8) << mdf.distance[static_cast<size_t>(worst_vertex)]
             << " < Euclidean " << (mesh.point(VertexHandle(worst_vertex)) - ps).norm() << ")";
    if (unreached) bounds << "; " << unreached << " unreached by the MDF";
    const double md = median(td), mm = median(tm), mdn = median(tdn), mmn = median(tmn), mmu = median(tmu);
    min_cpu_dij += *std::min_element(cd.begin(), cd.end());
    min_cpu_mdf += *std::min_element(cm.begin(), cm.end());
    ratios.push_back(mm / md);
    ratios_nodir.push_back(mmn / mdn);
    ratios_untracked.push_back(mmu / md);
    const double mf = median(tf);
    ratios_fast.push_back(mf / md);
    std::ostringstream fast_text;
    fast_text << secs(mf) << " | **" << std::setprecision(3) << mf / md << "** | " << fast_below << " / " << fast_above
              << " | " << std::setprecision(3) << 100 * fast_diff_sum / static_cast<double>(std::max<size_t>(fast_compared, 1))
              << "%, " << 100 * fast_diff_max << "%";
    std::ostringstream ratio_text;
    ratio_text << std::setprecision(4) << (compared ? ratio_sum / static_cast<double>(compared) : std::nan(""));
    std::cout << "| " << s << " | " << secs(md) << " | " << secs(mm) << " | **" << std::setprecision(3) << mm / md
              << "** | " << secs(mdn) << " | " << secs(mmn) << " | " << std::setprecision(3) << mmn / mdn << " | "
              << secs(mmu) << " | " << std::setprecision(3) << mmu / md << " | " << mdf.peak_front << " | " << bytes(static_cast<long long>(mdf.peak_working_memory_bytes)) << " | "
              << ratio_text.str() << " | " << bounds.str() << " | " << fast_text.str() << " |\n";
  }
  double mean = 0, mean_nodir = 0, mean_untracked = 0, mean_fast = 0;
  for (size_t i = 0; i < ratios.size(); ++i) {
    mean += ratios[i] / static_cast<double>(ratios.size());
    mean_nodir += ratios_nodir[i] / static_cast<double>(ratios.size());
    mean_untracked += ratios_untracked[i] / static_cast<double>(ratios.size());
    mean_fast += ratios_fast[i] / static_cast<double>(ratios.size());
  }
  std::cout << "\nMean MDF / Dijkstra time: **" << std::setprecision(3) << mean << "** with directions (target <= 1.5: "
            << (mean <= 1.5 ? "met" : "MISSED") << "), " << mean_nodir << " without.\n"
            << "Ratio of the summed thread CPU times (with directions, all runs; not counting time spent waiting for a "
               "core): "
            << std::setprecision(3) << cpu_mdf / cpu_dij << "; of the fastest run's CPU time per source: "
            << min_cpu_mdf / min_cpu_dij << ".\n"
            << "With the edge front not tracked (`DistanceOptions::track_front = false`, directions on): "
            << std::setprecision(3) << mean_untracked << "; the same distances: " << (untracked_same ? "yes" : "**NO**")
            << ".\nFast mode (`DistanceMethod::Fast`, directions on) / Dijkstra: **" << std::setprecision(3) << mean_fast
            << "**.\n";
}

// Dijkstra and the fast mode only, by thread CPU time: the five runs of each source rotate their
// order every repetition (2R repetitions); medians.
void fast_only(const Mesh& mesh, const std::vector<int>& sources, const Args& a) {
  const size_t n = mesh.n_vertices();
  DistanceOptions dij_opt, fast_opt;
  fast_opt.method = edgefront::DistanceMethod::Fast;
  // The five runs: Dijkstra over the mesh's halfedges, the ring table's build, the fast mode on it,
  // Dijkstra on it, and the per-call fast mode (build + query).
  enum { kDij, kBuild, kQuery, kTableDij, kPerCall, kRuns };
  std::cout << "Thread CPU time, median of " << 2 * a.reps
            << " runs each, their order rotated every repetition. Dijkstra: binary heap over the mesh's "
               "halfedges (`dijkstra_distance`); table: `GeodesicRingTable` build; query: the fast mode on the "
               "table; table Dijkstra: `dijkstra_distance(mesh, table, ...)`; per call: `geodesic_distance(mesh, "
               "source, {.method = DistanceMethod::Fast})` (build + query).\n\n"
            << "| source | Dijkstra | table build | query | table Dijkstra | per call | build / Dijkstra | **query / "
               "table Dijkstra** | query / Dijkstra | table Dijkstra / Dijkstra | per call / Dijkstra | fast: below "
               "Euclidean / above Dijkstra | query = per call |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  std::vector<std::vector<double>> ratio(5);
  size_t table_bytes = 0, query_bytes = 0;
  for (const int s : sources) {
    std::cerr << "geodesic_speed: fast mode from " << s << "\n";
    const FrontSource src = FrontSource::vertex(VertexHandle(s));
    std::vector<std::vector<double>> cpu(kRuns);
    DistanceField dij, query, per_call, tdij;
    std::optional<edgefront::GeodesicRingTable> table;
    for (int r = 0; r < 2 * a.reps; ++r) {
      for (int k = 0; k < kRuns; ++k) {
        const int run = (k + r) % kRuns;
        if (run != kBuild && !table) table.emplace(mesh);  // the first repetition may start with a query
        const double c = thread_cpu_seconds();
        switch (run) {
          case kDij: dij = edgefront::dijkstra_distance(mesh, src, dij_opt); break;
          case kBuild: table.emplace(mesh); break;
          case kQuery: query = edgefront::geodesic_distance(mesh, *table, src, fast_opt); break;
          case kTableDij: tdij = edgefront::dijkstra_distance(mesh, *table, src, dij_opt); break;
          default: per_call = edgefront::geodesic_distance(mesh, src, fast_opt); break;
        }
        cpu[run].push_back(thread_cpu_seconds() - c);
      }
    }
    table_bytes = table->memory_bytes();
    query_bytes = query.peak_working_memory_bytes;
    size_t below = 0, above = 0;
    const Vec3 ps = mesh.point(VertexHandle(s));
    for (size_t v = 0; v < n; ++v) {
      const double df = query.distance[v], dd = dij.distance[v];
      if (std::isfinite(dd) != std::isfinite(df)) ++above;
      if (!std::isfinite(df) || !std::isfinite(dd)) continue;
      if (df < (mesh.point(VertexHandle(static_cast<int>(v))) - ps).norm() * (1 - 1e-9)) ++below;
      if (df > dd * (1 + 1e-9)) ++above;
    }
    const bool same = query.distance == per_call.distance && query.direction == per_call.direction &&
                      query.order == per_call.order && tdij.distance == dij.distance && tdij.order == dij.order;
    double med[kRuns];
    for (int k = 0; k < kRuns; ++k) med[k] = median(cpu[k]);
    const double rs[5] = {med[kBuild] / med[kDij], med[kQuery] / med[kTableDij], med[kQuery] / med[kDij],
                          med[kTableDij] / med[kDij], med[kPerCall] / med[kDij]};
    std::cout << "| " << s;
    for (int k = 0; k < kRuns; ++k) std::cout << " | " << secs(med[k]);
    std::cout << std::setprecision(3);
    for (int k = 0; k < 5; ++k) {
      ratio[k].push_back(rs[k]);
      std::cout << (k == 1 ? " | **" : " | ") << rs[k] << (k == 1 ? "**" : "");
    }
    std::cout << " | " << below << " / " << above << " | " << (same ? "yes" : "NO") << " |\n";
  }
  std::cout << std::setprecision(3) << "\nMedians over the sources: table build / Dijkstra " << median(ratio[0])
            << ", **query / table Dijkstra " << median(ratio[1]) << "**, query / Dijkstra " << median(ratio[2])
            << ", table Dijkstra / Dijkstra " << median(ratio[3]) << ", per call / Dijkstra " << median(ratio[4])
            << ".\nMemory: the table " << bytes(static_cast<long long>(table_bytes)) << " ("
            << static_cast<double>(table_bytes) / static_cast<double>(n) << " B per vertex); a query's working memory "
            << bytes(static_cast<long long>(query_bytes)) << " ("
            << static_cast<double>(query_bytes) / static_cast<double>(n) << " B per vertex, the output arrays not counted).\n";
}

// ---- part 2: d_max queries -----------------------------------------------------------------

struct GridRun {
  int cells = 0;
  size_t vertices = 0;
  double build_s = 0;
  long long construct_heap = 0;  // heap kept by MinimalDistanceFront(mesh)
  double construct_s = 0;
  size_t settled = 0;
  size_t peak_front = 0;
  size_t peak_working = 0;
  long long first_peak_heap = 0;   // peak heap growth of the first query
  long long repeat_peak_heap = 0;  // largest peak heap growth of a repeated query
  size_t repeat_settled_min = std::numeric_limits<size_t>::max();  // settled counts of the repeated queries
  size_t repeat_settled_max = 0;
  double first_s = 0;
  std::vector<double> query_s;  // mean per query, per round
  double max_rel_err = 0;       // settled vertices vs Euclidean
  double max_settled_d = 0;
  DistanceStop stop = DistanceStop::NotStarted;
  // Free functions with max_distance, for contrast.
  double free_mdf_s = 0, free_dij_s = 0;
  long long free_mdf_heap = 0, free_dij_heap = 0;
  size_t free_mdf_reached = 0, free_dij_reached = 0;
};

const char* stop_name(DistanceStop s) {
  switch (s) {
    case DistanceStop::NotStarted: return "not started";
    case DistanceStop::Exhausted: return "exhausted";
    case DistanceStop::MaxDistance: return "max distance";
    case DistanceStop::TargetReached: return "target";
  }
  return "?";
}

void dmax_queries(const Args& a) {
  std::vector<GridRun> runs;
  std::vector<Mesh> meshes;
  for (const int cells : {a.small, a.large}) {
    std::cerr << "geodesic_speed: building a " << cells << "x" << cells << " grid\n";
    GridRun g;
    g.cells = cells;
    edgefront::shapes::GridOptions o;
    o.cells = cells;
    o.half_size = 0.5 * a.cell * cells;
    auto t = Clock::now();
    meshes.push_back(edgefront::shapes::grid(o));
    g.build_s = seconds_since(t);
    g.vertices = meshes.back().n_vertices();
    runs.push_back(g);
  }
  // The centre vertex of each grid (cells even: exactly at the origin).
  std::vector<VertexHandle> centre;
  for (const Mesh& m : meshes) {
    VertexHandle best(0);
    for (const auto v : m.vertices())
      if (m.point(v).sqrnorm() < m.point(best).sqrnorm()) best = v;
    centre.push_back(best);
  }

  std::vector<edgefront::MinimalDistanceFront> fronts;
  fronts.reserve(meshes.size());
  for (size_t i = 0; i < meshes.size(); ++i) {
    heap::Region region;
    const auto t = Clock::now();
    fronts.emplace_back(meshes[i]);
    runs[i].construct_s = seconds_since(t);
    runs[i].construct_heap = region.growth();
  }

  DistanceOptions opt;
  opt.max_distance = a.dmax;
  if (a.windows) opt.method = edgefront::DistanceMethod::Windows;
  // First query on each grid, with a callback that checks distances against the Euclidean ones.
  for (size_t i = 0; i < meshes.size(); ++i) {
    const Mesh& m = meshes[i];
    GridRun& g = runs[i];
    const Vec3 ps = m.point(centre[i]);
    fronts[i].set_settled_callback([&](VertexHandle v, double d, const Vec3&) {
      const double e = (m.point(v) - ps).norm();
      if (e > 0) g.max_rel_err = std::max(g.max_rel_err, std::abs(d - e) / e);
      g.max_settled_d = std::max(g.max_settled_d, d);
    });
    heap::Region region;
    const auto t = Clock::now();
    fronts[i].reset(FrontSource::vertex(centre[i]), opt);
    g.stop = fronts[i].run();
    g.first_s = seconds_since(t);
    g.first_peak_heap = region.peak_growth();
    g.settled = fronts[i].settled_count();
    g.peak_front = fronts[i].peak_front_size();
    g.peak_working = fronts[i].peak_working_memory_bytes();
    fronts[i].set_settled_callback([](VertexHandle, double, const Vec3&) {});
  }
  // Repeated queries, rounds alternating between the grids.
  for (int round = 0; round < 3; ++round)
    for (size_t i = 0; i < meshes.size(); ++i) {
      const auto t = Clock::now();
      for (int q = 0; q < a.queries; ++q) {
        heap::Region region;
        fronts[i].reset(FrontSource::vertex(centre[i]), opt);
        fronts[i].run();
        runs[i].repeat_peak_heap = std::max(runs[i].repeat_peak_heap, region.peak_growth());
        runs[i].repeat_settled_min = std::min(runs[i].repeat_settled_min, fronts[i].settled_count());
        runs[i].repeat_settled_max = std::max(runs[i].repeat_settled_max, fronts[i].settled_count());
      }
      runs[i].query_s.push_back(seconds_since(t) / a.queries);
    }
  // The free functions (per-mesh result arrays), for contrast.
  for (size_t i = 0; i < meshes.size(); ++i) {
    const int reps = 5;
    std::vector<double> tm, td;
    for (int r = 0; r < reps; ++r) {
      {
        heap::Region region;
        const auto t = Clock::now();
        const DistanceField f = edgefront::geodesic_distance(meshes[i], FrontSource::vertex(centre[i]), opt);
        tm.push_back(seconds_since(t));
        runs[i].free_mdf_heap = region.peak_growth();
        runs[i].free_mdf_reached = f.order.size();
      }
      {
        heap::Region region;
        const auto t = Clock::now();
        const DistanceField f = edgefront::dijkstra_distance(meshes[i], FrontSource::vertex(centre[i]), opt);
        td.push_back(seconds_since(t));
        runs[i].free_dij_heap = region.peak_growth();
        runs[i].free_dij_reached = f.order.size();
      }
    }
    runs[i].free_mdf_s = median(tm);
    runs[i].free_dij_s = median(td);
  }

  std::cout << "\n### d_max queries: the same query on a " << a.small << "x" << a.small << " and a " << a.large << "x"
            << a.large << " grid\n\nCell size " << a.cell << ", source at the centre vertex, d_max = " << a.dmax
            << " (" << a.dmax / a.cell << " cells). Reusable `MinimalDistanceFront` (constructed once per mesh); "
            << "heap growth is measured by counting every operator new/delete of the process.\n\n"
            << "| grid | vertices | stop | settled | peak front | peak working memory (MDF's count) | heap peak, first "
               "query | heap peak, repeated queries | first query | per query (median of 3 rounds of "
            << a.queries << ") | max rel. error vs Euclidean |\n|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const GridRun& g : runs)
    std::cout << "| " << g.cells << "x" << g.cells << " | " << g.vertices << " | " << stop_name(g.stop) << " | "
              << g.settled << " | " << g.peak_front << " | " << bytes(static_cast<long long>(g.peak_working)) << " | "
              << bytes(g.first_peak_heap) << " | " << bytes(g.repeat_peak_heap) << " | " << secs(g.first_s) << " | "
              << secs(median(g.query_s)) << " | " << std::setprecision(3) << g.max_rel_err << " |\n";
  std::cout << "\n| grid | grid build | MinimalDistanceFront(mesh): time, heap kept | geodesic_distance(d_max): "
               "time, heap peak, reached | dijkstra_distance(d_max): time, heap peak, reached |\n|---|---|---|---|---|\n";
  for (const GridRun& g : runs)
    std::cout << "| " << g.cells << "x" << g.cells << " | " << secs(g.build_s) << " | " << secs(g.construct_s) << ", "
              << bytes(g.construct_heap) << " | " << secs(g.free_mdf_s) << ", " << bytes(g.free_mdf_heap) << ", "
              << g.free_mdf_reached << " | " << secs(g.free_dij_s) << ", " << bytes(g.free_dij_heap) << ", "
              << g.free_dij_reached << " |\n";
  const GridRun &s = runs[0], &l = runs[1];
  const double time_ratio = median(l.query_s) / median(s.query_s);
  std::cout << "\nSame vertices settled: " << (s.settled == l.settled ? "yes" : "**NO**") << " (" << s.settled << " vs "
            << l.settled << "); same peak front: " << (s.peak_front == l.peak_front ? "yes" : "**NO**")
            << "; same peak working memory: " << (s.peak_working == l.peak_working ? "yes" : "**NO**") << " ("
            << s.peak_working << " vs " << l.peak_working << " B); heap peak of a repeated query: "
            << bytes(s.repeat_peak_heap) << " vs " << bytes(l.repeat_peak_heap) << "; time per query large/small: "
            << std::setprecision(3) << time_ratio << ".\n";
  for (const GridRun& g : runs)
    if (g.repeat_settled_min != g.settled || g.repeat_settled_max != g.settled)
      std::cout << "\n**The reused front settled " << g.repeat_settled_min << " to " << g.repeat_settled_max
                << " vertices in repeated queries on the " << g.cells << "x" << g.cells << " grid, not " << g.settled
                << " as in the first query.**\n";
  std::cout << "\nRepeated queries settled the same number of vertices as the first one: "
            << (std::all_of(runs.begin(), runs.end(),
                            [](const GridRun& g) {
                              return g.repeat_settled_min == g.settled && g.repeat_settled_max == g.settled;
                            })
                    ? "yes"
                    : "**no**")
            << ".\n";
}

Args parse(int argc, char** argv) {
  Args a;
#ifdef EDGEFRONT_BENCH_DATA_DIR
  a.model = fs::path(EDGEFRONT_BENCH_DATA_DIR) / "models" / "armadillo.off";
#else
  a.model = "data/models/armadillo.off";
#endif
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw UsageError(arg + " needs a value");
      return argv[++i];
    };
    auto number = [&](double lo, double hi) -> double {
      const std::string v = value();
      double x = 0;
      size_t used = 0;
      try {
        x = std::stod(v, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used == 0 || used != v.size() || !(x >= lo && x <= hi)) throw UsageError(arg + ": bad value '" + v + "'");
      return x;
    };
    if (arg == "--model")
      a.model = value();
    else if (arg == "--subdiv")
      a.subdiv = static_cast<int>(number(0, 5));
    else if (arg == "--sources")
      a.sources = static_cast<int>(number(1, 1000));
    else if (arg == "--reps")
      a.reps = static_cast<int>(number(1, 1000));
    else if (arg == "--seed")
      a.seed = static_cast<std::uint64_t>(number(0, 1e18));
    else if (arg == "--small")
      a.small = static_cast<int>(number(2, 4096));
    else if (arg == "--large")
      a.large = static_cast<int>(number(2, 4096));
    else if (arg == "--cell")
      a.cell = number(1e-9, 1e9);
    else if (arg == "--dmax")
      a.dmax = number(0, 1e18);
    else if (arg == "--queries")
      a.queries = static_cast<int>(number(1, 1e7));
    else if (arg == "--skip-full")
      a.full = false;
    else if (arg == "--skip-dmax")
      a.dmax_part = false;
    else if (arg == "--fast-only")
      a.fast_only = true;
    else if (arg == "--windows")
      a.windows = true;
    else if (arg == "-h" || arg == "--help") {
      std::cout << "usage: geodesic_speed [--model PATH] [--subdiv K] [--sources N] [--reps R] [--seed S]\n"
                   "                      [--small CELLS] [--large CELLS] [--cell H] [--dmax D] [--queries Q]\n"
                   "                      [--skip-full] [--skip-dmax] [--windows] [--fast-only]\n";
      std::exit(0);
    } else
      throw UsageError("unknown argument " + arg);
  }
  if (a.dmax_part && (a.small % 2 || a.large % 2)) throw UsageError("--small and --large must be even (centre vertex)");
  if (a.dmax_part && a.dmax >= 0.5 * a.cell * a.small)
    throw UsageError("--dmax must stay inside the small grid (< cell * small / 2)");
  return a;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Args a = parse(argc, argv);
    if (a.full) full_field(a);
    if (a.dmax_part) dmax_queries(a);
    return 0;
  } catch (const UsageError& e) {
    std::cerr << "geodesic_speed: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "geodesic_speed: error: " << e.what() << "\n";
    return 1;
  }
}
