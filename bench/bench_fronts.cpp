/// bench_fronts: full sweeps of the Vertex Front and the Minimal Edge Front against a plain
/// breadth-first search, on one mesh, from random source vertices, in one process.
///
///   bench_fronts [--mesh FILE] [--subdiv N] [--sources R] [--seed S] [--reuse]
///
/// Loads FILE (default data/models/armadillo.off, fetched by data/fetch-models.sh), Loop-subdivides
/// it N times (OpenMesh's uniform Loop subdivider), draws R source vertices (std::mt19937_64 with
/// seed S), and for each source times
///   - BFS: a queue array and a visited byte array (both sized by the mesh, allocated per query),
///     neighbours through OpenMesh's vertex-vertex circulator;
///   - VF: `edgefront::VertexFront` run to exhaustion (a new object per source, or with --reuse
///     one object `reset` per source);
///   - MEF: `edgefront::MinimalEdgeFront` with default options run to exhaustion (same).
/// It prints the machine, the sizes and a markdown table per sweep plus the means: time, time
/// ratio to BFS, levels, peak front (vertices for BFS's queue and VF, halfedges for MEF) and peak
/// working memory in bytes (BFS: visited array + queue array), and the ratios of the summed
/// thread CPU times (not counting time spent waiting for a core). Before timing, the levels of all
/// three on the first source are checked against each other (one untimed extra sweep each).
///
/// This is a benchmark, not a test: it takes seconds to minutes on large subdivisions.

#include <sched.h>
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <OpenMesh/Tools/Subdivider/Uniform/LoopT.hh>

#include "edgefront/error.h"
#include "edgefront/front_source.h"
#include "edgefront/mesh.h"
#include "edgefront/mesh_io.h"
#include "edgefront/minimal_edge_front.h"
#include "edgefront/vertex_front.h"

namespace {

using edgefront::Mesh;
using edgefront::VertexHandle;
using Clock = std::chrono::steady_clock;

struct Args {
  std::string mesh = std::string(EDGEFRONT_BENCH_DATA_DIR) + "/models/armadillo.off";
  int subdiv = 0;
  int sources = 10;
  uint64_t seed = 1;
  bool reuse = false;  // one VF and one MEF object for all sources (reset per source)
};

void usage(std::ostream& os) {
  os << "usage: bench_fronts [--mesh FILE] [--subdiv N] [--sources R] [--seed S] [--reuse]\n"
        "  --mesh FILE   triangle mesh (default data/models/armadillo.off)\n"
        "  --subdiv N    Loop-subdivide N times first (default 0; each step multiplies faces by 4)\n"
        "  --sources R   number of random source vertices (default 10)\n"
        "  --seed S      seed of the source choice (default 1)\n"
        "  --reuse       one VF and one MEF object reset per source (default: a new object per source)\n";
}

/// Parses the flags; returns false (after printing why) on a usage error.
bool parse_args(int argc, char** argv, Args& args, bool& help) {
  help = false;
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (flag == "-h" || flag == "--help") {
      help = true;
      return true;
    }
    if (flag == "--reuse") {
      args.reuse = true;
      continue;
    }
    if (i + 1 >= argc) {
      std::cerr << "bench_fronts: error: " << flag << " needs a value or is unknown\n";
      return false;
    }
    const std::string value = argv[++i];
    try {
      size_t used = 0;
      if (flag == "--mesh") {
        args.mesh = value;
        used = value.size();
      } else if (flag == "--subdiv") {
        args.subdiv = std::stoi(value, &used);
      } else if (flag == "--sources") {
        args.sources = std::stoi(value, &used);
      } else if (flag == "--seed") {
        args.seed = std::stoull(value, &used);
      } else {
        std::cerr << "bench_fronts: error: unknown flag " << flag << "\n";
        return false;
      }
      if (used != value.size()) throw std::invalid_argument(value);
    } catch (const std::logic_error&) {
      std::cerr << "bench_fronts: error: bad value '" << value << "' for " << flag << "\n";
      return false;
    }
  }
  if (args.subdiv < 0 || args.subdiv > 6 || args.sources < 1) {
    std::cerr << "bench_fronts: error: need 0 <= --subdiv <= 6 and --sources >= 1\n";
    return false;
  }
  return true;
}

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("model name", 0) == 0) {
      const size_t colon = line.find(':');
      if (colon != std::string::npos) return line.substr(line.find_first_not_of(" \t", colon + 1));
    }
  }
  return "unknown";
}

int available_cpus() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof(set), &set) != 0) return -1;
  return CPU_COUNT(&set);
}

/// The baseline: breadth-first search over the vertex-vertex circulator with a per-query visited
/// array and a flat queue array (both sized by the mesh).
struct BfsResult {
  size_t reached = 0;
  int levels = 0;          // largest hop distance (eccentricity of the source)
  size_t peak_queue = 0;   // largest number of queued, unprocessed vertices
  size_t bytes = 0;        // visited array + queue array
};

BfsResult bfs(const Mesh& mesh, VertexHandle source, std::vector<int>* level_out = nullptr) {
  const size_t n = mesh.n_vertices();
  std::vector<uint8_t> visited(n, 0);
  std::vector<int> queue(n);
  size_t head = 0, tail = 0;
  BfsResult r;
  queue[tail++] = source.idx();
  visited[static_cast<size_t>(source.idx())] = 1;
  if (level_out) (*level_out)[static_cast<size_t>(source.idx())] = 0;
  int depth = 0;
  while (head < tail) {
    // One level: the vertices queued at hop distance `depth`.
    const size_t level_end = tail;
    while (head < level_end) {
      r.peak_queue = std::max(r.peak_queue, tail - head);
      const VertexHandle v(queue[head++]);
      for (const VertexHandle w : mesh.vv_range(v)) {
        uint8_t& seen = visited[static_cast<size_t>(w.idx())];
        if (!seen) {
          seen = 1;
          if (level_out) (*level_out)[static_cast<size_t>(w.idx())] = depth + 1;
          queue[tail++] = w.idx();
        }
      }
    }
    if (tail > level_end) ++depth;
  }
  r.levels = depth;
  r.reached = tail;
  r.bytes = visited.capacity() * sizeof(uint8_t) + queue.capacity() * sizeof(int);
  return r;
}

struct Row {
  int source = 0;
  double t_bfs = 0, t_vf = 0, t_mef = 0;
  double c_bfs = 0, c_vf = 0, c_mef = 0;  // CPU time of this thread (s)
  int levels_bfs = 0, levels_vf = 0, levels_mef = 0;
  size_t reached = 0;
  size_t peak_bfs = 0, peak_vf = 0, peak_mef = 0;
  size_t bytes_bfs = 0, bytes_vf = 0, bytes_mef = 0;
};

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

/// CPU time of the calling thread (s): unlike the wall clock it does not count the time the
/// thread waits for a core, which dominates the noise on a shared machine.
double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

std::string fixed(double x, int digits) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << x;
  return s.str();
}

std::string human_bytes(double b) {
  const char* units[] = {"B", "KB", "MB", "GB"};
  int u = 0;
  while (b >= 1024.0 && u < 3) {
    b /= 1024.0;
    ++u;
  }
  return fixed(b, u == 0 ? 0 : 1) + " " + units[u];
}

/// Checks that BFS, VF and MEF give the same levels from `source` (untimed).
void check_levels(const Mesh& mesh, VertexHandle source) {
  std::vector<int> expected(mesh.n_vertices(), -1);
  bfs(mesh, source, &expected);
  const edgefront::FrontSource src = edgefront::FrontSource::vertex(source);
  const std::vector<int> vf = edgefront::vertex_front_levels(mesh, src);
  const std::vector<int> mef = edgefront::edge_front_levels(mesh, src);
  for (size_t i = 0; i < expected.size(); ++i) {
    if (vf[i] != expected[i] || mef[i] != expected[i]) {
      throw edgefront::InternalError("level mismatch at vertex " + std::to_string(i) + " from source " +
                                     std::to_string(source.idx()) + ": BFS " + std::to_string(expected[i]) +
                                     ", VF " + std::to_string(vf[i]) + ", MEF " + std::to_string(mef[i]));
    }
  }
}

int run(const Args& args) {
  if (!std::filesystem::exists(args.mesh)) {
    std::cerr << "bench_fronts: error: " << args.mesh
              << " not found; fetch the public models with data/fetch-models.sh (or pass --mesh FILE)\n";
    return 1;
  }
  auto t0 = Clock::now();
  Mesh mesh = edgefront::read_mesh(args.mesh).mesh;
  const double t_load = seconds_since(t0);
  const size_t v0 = mesh.n_vertices(), f0 = mesh.n_faces();
  t0 = Clock::now();
  if (args.subdiv > 0) {
    OpenMesh::Subdivider::Uniform::LoopT<Mesh, double> loop;
    loop.attach(mesh);
    loop(static_cast<size_t>(args.subdiv));
    loop.detach();
  }
  const double t_subdiv = seconds_since(t0);

  std::cout << "## bench_fronts\n\n";
  std::cout << "- machine: " << cpu_model() << ", nproc " << available_cpus() << " (one thread used)\n";
  std::cout << "- mesh: " << args.mesh << ": " << v0 << " vertices, " << f0 << " faces (read in " << fixed(t_load, 2)
            << " s)\n";
  std::cout << "- Loop subdivision x" << args.subdiv << ": " << mesh.n_vertices() << " vertices, " << mesh.n_edges()
            << " edges, " << mesh.n_faces() << " faces (" << fixed(t_subdiv, 2) << " s)\n";
  std::cout << "- sources: " << args.sources << " random vertices, seed " << args.seed << "; "
            << (args.reuse ? "one front object of each kind reset per source" : "a new front object per source")
            << " (constructed inside the timed region)\n";
  std::cout.flush();

  std::mt19937_64 rng(args.seed);
  std::uniform_int_distribution<int> pick(0, static_cast<int>(mesh.n_vertices()) - 1);
  std::vector<VertexHandle> sources;
  while (sources.size() < static_cast<size_t>(args.sources)) {
    const VertexHandle v(pick(rng));
    if (mesh.is_isolated(v)) continue;
    sources.push_back(v);
  }

  t0 = Clock::now();
  check_levels(mesh, sources.front());
  std::cout << "- check: BFS, VF and MEF levels agree on every vertex from source " << sources.front().idx() << " ("
            << fixed(seconds_since(t0), 2) << " s, untimed)\n\n";
  std::cout.flush();

  // One object per query unless --reuse (one object of each kind, reset per source: the reuse
  // path the headers advertise).
  std::optional<edgefront::VertexFront> vf;
  std::optional<edgefront::MinimalEdgeFront> mef;
  std::vector<Row> rows;
  for (const VertexHandle s : sources) {
    Row r;
    r.source = s.idx();
    const edgefront::FrontSource src = edgefront::FrontSource::vertex(s);

    double c0 = thread_cpu_seconds();
    t0 = Clock::now();
    const BfsResult b = bfs(mesh, s);
    r.t_bfs = seconds_since(t0);
    r.c_bfs = thread_cpu_seconds() - c0;
    r.levels_bfs = b.levels;
    r.reached = b.reached;
    r.peak_bfs = b.peak_queue;
    r.bytes_bfs = b.bytes;

    c0 = thread_cpu_seconds();
    t0 = Clock::now();
    if (!vf || !args.reuse) vf.emplace(mesh);
    vf->reset(src);
    vf->run(-1);
    r.t_vf = seconds_since(t0);
    r.c_vf = thread_cpu_seconds() - c0;
    r.levels_vf = vf->level();
    r.peak_vf = vf->peak_front_size();
    r.bytes_vf = vf->peak_working_memory_bytes();

    c0 = thread_cpu_seconds();
    t0 = Clock::now();
    if (!mef || !args.reuse) mef.emplace(mesh);
    mef->reset(src);
    mef->run(-1);
    r.t_mef = seconds_since(t0);
    r.c_mef = thread_cpu_seconds() - c0;
    r.levels_mef = mef->level();
    r.peak_mef = mef->peak_front_size();
    r.bytes_mef = mef->peak_working_memory_bytes();
    rows.push_back(r);
  }

  std::cout << "| source | reached | levels | BFS s | VF s | MEF s | VF/BFS | MEF/BFS | BFS peak queue | VF peak front "
               "(vertices) | MEF peak front (edges) | BFS bytes | VF peak bytes | MEF peak bytes |\n";
  std::cout << "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  Row mean;
  double mean_ratio_vf = 0, mean_ratio_mef = 0;
  double peak_bfs = 0, peak_vf = 0, peak_mef = 0, bytes_bfs = 0, bytes_vf = 0, bytes_mef = 0, reached = 0, levels = 0;
  for (const Row& r : rows) {
    std::cout << "| " << r.source << " | " << r.reached << " | " << r.levels_bfs << " | " << fixed(r.t_bfs, 4) << " | "
              << fixed(r.t_vf, 4) << " | " << fixed(r.t_mef, 4) << " | " << fixed(r.t_vf / r.t_bfs, 2) << " | "
              << fixed(r.t_mef / r.t_bfs, 2) << " | " << r.peak_bfs << " | " << r.peak_vf << " | " << r.peak_mef
              << " | " << r.bytes_bfs << " | " << r.bytes_vf << " | " << r.bytes_mef << " |\n";
    mean.t_bfs += r.t_bfs;
    mean.t_vf += r.t_vf;
    mean.t_mef += r.t_mef;
    mean.c_bfs += r.c_bfs;
    mean.c_vf += r.c_vf;
    mean.c_mef += r.c_mef;
    mean_ratio_vf += r.t_vf / r.t_bfs;
    mean_ratio_mef += r.t_mef / r.t_bfs;
    peak_bfs += static_cast<double>(r.peak_bfs);
    peak_vf += static_cast<double>(r.peak_vf);
    peak_mef += static_cast<double>(r.peak_mef);
    bytes_bfs += static_cast<double>(r.bytes_bfs);
    bytes_vf += static_cast<double>(r.bytes_vf);
    bytes_mef += static_cast<double>(r.bytes_mef);
    reached += static_cast<double>(r.reached);
    levels += r.levels_bfs;
  }
  const double k = static_cast<double>(rows.size());
  std::cout << "| **mean** | " << fixed(reached / k, 0) << " | " << fixed(levels / k, 1) << " | "
            << fixed(mean.t_bfs / k, 4) << " | " << fixed(mean.t_vf / k, 4) << " | " << fixed(mean.t_mef / k, 4)
            << " | " << fixed(mean_ratio_vf / k, 2) << " | " << fixed(mean_ratio_mef / k, 2) << " | "
            << fixed(peak_bfs / k, 0) << " | " << fixed(peak_vf / k, 0) << " | " << fixed(peak_mef / k, 0) << " | "
            << fixed(bytes_bfs / k, 0) << " | " << fixed(bytes_vf / k, 0) << " | " << fixed(bytes_mef / k, 0)
            << " |\n\n";
  std::cout << "Means: BFS " << fixed(mean.t_bfs / k * 1e3, 1) << " ms, VF " << fixed(mean.t_vf / k * 1e3, 1)
            << " ms (" << fixed(mean_ratio_vf / k, 2) << "x BFS), MEF " << fixed(mean.t_mef / k * 1e3, 1) << " ms ("
            << fixed(mean_ratio_mef / k, 2) << "x BFS); working memory BFS " << human_bytes(bytes_bfs / k) << ", VF "
            << human_bytes(bytes_vf / k) << ", MEF " << human_bytes(bytes_mef / k) << "\n";
  // Ratios of the summed thread CPU times: the figure to compare on a loaded machine.
  std::cout << "CPU time: BFS " << fixed(mean.c_bfs / k * 1e3, 1) << " ms, VF " << fixed(mean.c_vf / k * 1e3, 1)
            << " ms (" << fixed(mean.c_vf / mean.c_bfs, 2) << "x BFS), MEF " << fixed(mean.c_mef / k * 1e3, 1)
            << " ms (" << fixed(mean.c_mef / mean.c_bfs, 2) << "x BFS)\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Args args;
  bool help = false;
  if (!parse_args(argc, argv, args, help)) {
    usage(std::cerr);
    return 2;
  }
  if (help) {
    usage(std::cout);
    return 0;
  }
  try {
    return run(args);
  } catch (const std::exception& e) {
    std::cerr << "bench_fronts: error: " << e.what() << "\n";
    return 1;
  }
}
