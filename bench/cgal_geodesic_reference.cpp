// cgal_geodesic_reference: reference geodesic distances from CGAL for bench/geodesic_accuracy.
//
//   cgal_geodesic_reference MESH --sources v1,v2,... -o OUT_PREFIX [--heat] [--no-exact]
//                           [--skip-existing]
//   cgal_geodesic_reference MESH --random K [--seed S] (-o OUT_PREFIX ... | --print-sources)
//
// `--random K` picks K distinct non-isolated vertices with std::mt19937_64(S) (default S = 1),
// appended to `--sources`; `--print-sources` prints the list (comma-separated) and exits, so a
// script can hand the same sources to bench/geodesic_accuracy.
//
// The mesh is read with edgefront::read_mesh (the reader every EdgeFront tool uses) and copied
// into a CGAL::Surface_mesh with the same vertex indices and the same triangles, so index i here
// is VertexHandle(i) there. For OFF files the mesh is also read with CGAL's own OFF reader and
// compared with that copy (vertex count, every coordinate bit for bit, the faces as vertex
// triples); the verdict goes to the log.
//
// Per source vertex s it writes raw little-endian doubles, one per vertex in index order, +inf
// where the source is not reachable:
//   <prefix>.exact.<s>.bin   CGAL::Surface_mesh_shortest_path (exact polyhedral geodesics, Chen-Han
//                            / Xin-Wang window propagation, Epick kernel)
//   <prefix>.heat.<s>.bin    CGAL::Heat_method_3, intrinsic Delaunay variant (with --heat)
// and appends one line per event to <prefix>.log (`key=value` fields; the accuracy benchmark reads
// the last line per method and source):
//   exact source=s build_s=.. query_s=.. reached=.. peak_rss_mb=..
//   heat precompute_s=.. peak_rss_mb=..
//   heat source=s solve_s=..
//   heat_failed stage=precompute|solve source=s message="..."
// With --skip-existing a source whose .bin file already exists with the right size is not
// recomputed (the heat precomputation is skipped too when every heat file exists).
//
// Exit codes: 0 done (a heat-method failure is recorded, not fatal), 1 error, 2 usage.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Heat_method_3/Surface_mesh_geodesic_distances_3.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_shortest_path.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "edgefront/atomic_write.h"
#include "edgefront/error.h"
#include "edgefront/mesh.h"
#include "edgefront/mesh_io.h"

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point3 = Kernel::Point_3;
using SurfaceMesh = CGAL::Surface_mesh<Point3>;
using SmVertex = SurfaceMesh::Vertex_index;
using ShortestPathTraits = CGAL::Surface_mesh_shortest_path_traits<Kernel, SurfaceMesh>;
using ShortestPath = CGAL::Surface_mesh_shortest_path<ShortestPathTraits>;
using HeatIdt =
    CGAL::Heat_method_3::Surface_mesh_geodesic_distances_3<SurfaceMesh, CGAL::Heat_method_3::Intrinsic_Delaunay>;

constexpr double kInf = std::numeric_limits<double>::infinity();

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Args {
  std::filesystem::path mesh;
  std::vector<int> sources;
  std::string prefix;
  bool heat = false;
  bool exact = true;
  bool skip_existing = false;
  int random = 0;
  std::uint64_t seed = 1;
  bool print_sources = false;
};

void print_usage(std::ostream& os) {
  os << "usage: cgal_geodesic_reference MESH --sources v1,v2,... -o OUT_PREFIX [--heat] [--no-exact]\n"
        "                               [--skip-existing] [--random K [--seed S]] [--print-sources]\n"
        "Writes OUT_PREFIX.exact.<v>.bin (Surface_mesh_shortest_path) and, with --heat,\n"
        "OUT_PREFIX.heat.<v>.bin (Heat_method_3, intrinsic Delaunay): one double per vertex in the\n"
        "mesh's vertex order (+inf: unreachable). Timings are appended to OUT_PREFIX.log.\n";
}

std::vector<int> parse_index_list(const std::string& text) {
  std::vector<int> out;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    if (item.empty()) continue;
    size_t used = 0;
    long long v = -1;
    try {
      v = std::stoll(item, &used);
    } catch (const std::exception&) {
      throw UsageError("--sources: '" + item + "' is not a vertex index");
    }
    if (used != item.size() || v < 0 || v > std::numeric_limits<int>::max())
      throw UsageError("--sources: '" + item + "' is not a vertex index");
    out.push_back(static_cast<int>(v));
  }
  if (out.empty()) throw UsageError("--sources: no vertex index given");
  return out;
}

Args parse_args(int argc, char** argv) {
  Args a;
  bool have_sources = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&](const char* name) -> std::string {
      if (i + 1 >= argc) throw UsageError(std::string(name) + " needs a value");
      return argv[++i];
    };
    if (arg == "--sources") {
      a.sources = parse_index_list(value("--sources"));
      have_sources = true;
    } else if (arg == "-o" || arg == "--output") {
      a.prefix = value("-o");
    } else if (arg == "--heat") {
      a.heat = true;
    } else if (arg == "--no-exact") {
      a.exact = false;
    } else if (arg == "--skip-existing") {
      a.skip_existing = true;
    } else if (arg == "--random") {
      const std::string v = value("--random");
      try {
        a.random = std::stoi(v);
      } catch (const std::exception&) {
        a.random = -1;
      }
      if (a.random < 1) throw UsageError("--random needs a positive count, got '" + v + "'");
    } else if (arg == "--seed") {
      const std::string v = value("--seed");
      try {
        a.seed = std::stoull(v);
      } catch (const std::exception&) {
        throw UsageError("--seed needs a non-negative integer, got '" + v + "'");
      }
    } else if (arg == "--print-sources") {
      a.print_sources = true;
    } else if (arg == "-h" || arg == "--help") {
      print_usage(std::cout);
      std::exit(0);
    } else if (!arg.empty() && arg[0] == '-') {
      throw UsageError("unknown option " + arg);
    } else if (a.mesh.empty()) {
      a.mesh = arg;
    } else {
      throw UsageError("more than one mesh given: " + arg);
    }
  }
  if (a.mesh.empty()) throw UsageError("no mesh given");
  if (!have_sources && a.random == 0) throw UsageError("--sources or --random is required");
  if (a.prefix.empty() && !a.print_sources) throw UsageError("-o OUT_PREFIX is required");
  if (!a.exact && !a.heat) throw UsageError("--no-exact without --heat computes nothing");
  return a;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// Peak resident set size of this process in MiB (Linux VmHWM), or -1 when unknown.
double peak_rss_mb() {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;
  return -1.0;
}

/// Resets the peak RSS counter so that the next reading covers only what follows (Linux >= 4.0;
/// silently ignored elsewhere).
void reset_peak_rss() {
  std::ofstream out("/proc/self/clear_refs");
  if (out) out << "5";
}

class Log {
 public:
  explicit Log(const std::filesystem::path& path) : out_(path, std::ios::app) {
    if (!out_) throw edgefront::IoError("cannot append to log " + path.string());
  }
  void line(const std::string& text) {
    out_ << text << '\n';
    out_.flush();
    std::cout << text << '\n' << std::flush;
  }

 private:
  std::ofstream out_;
};

std::string quote(std::string s) {
  std::replace(s.begin(), s.end(), '"', '\'');
  std::replace(s.begin(), s.end(), '\n', ' ');
  return "\"" + s + "\"";
}

std::string fmt(double v, int precision = 4) {
  std::ostringstream os;
  os.precision(precision);
  os << v;
  return os.str();
}

/// The CGAL copy of an EdgeFront mesh: vertex i is vertex i, faces in the same order and orientation.
SurfaceMesh to_cgal(const edgefront::Mesh& mesh) {
  SurfaceMesh sm;
  sm.reserve(static_cast<SurfaceMesh::size_type>(mesh.n_vertices()),
             static_cast<SurfaceMesh::size_type>(mesh.n_edges()),
             static_cast<SurfaceMesh::size_type>(mesh.n_faces()));
  for (const auto v : mesh.all_vertices()) {
    if (mesh.status(v).deleted()) throw edgefront::InvalidInput("mesh has deleted vertices");
    const edgefront::Vec3& p = mesh.point(v);
    const SmVertex added = sm.add_vertex(Point3(p[0], p[1], p[2]));
    if (static_cast<int>(added.idx()) != v.idx()) throw edgefront::InternalError("CGAL vertex index differs");
  }
  for (const auto f : mesh.faces()) {
    std::array<SmVertex, 3> tri{};
    int k = 0;
    for (const auto v : mesh.fv_range(f)) {
      if (k == 3) throw edgefront::InvalidInput("mesh has a face with more than 3 vertices");
      tri[static_cast<size_t>(k++)] = SmVertex(static_cast<SurfaceMesh::size_type>(v.idx()));
    }
    if (k != 3) throw edgefront::InvalidInput("mesh has a face with fewer than 3 vertices");
    if (sm.add_face(tri[0], tri[1], tri[2]) == SurfaceMesh::null_face())
      throw edgefront::InternalError("CGAL refused face " + std::to_string(f.idx()) + " that OpenMesh accepted");
  }
  return sm;
}

/// Reads an OFF file with CGAL's own reader and compares it with the copy made from EdgeFront's
/// reader. Returns "ok ..." or a description of the first difference.
std::string check_against_cgal_reader(const std::filesystem::path& path, const SurfaceMesh& ours) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext != ".off") return "skipped (not an OFF file)";
  SurfaceMesh theirs;
  std::ifstream in(path);
  if (!in || !CGAL::IO::read_OFF(in, theirs))
    return "mismatch: CGAL's OFF reader refused the file (EdgeFront's copy is used)";
  if (theirs.number_of_vertices() != ours.number_of_vertices())
    return "mismatch: CGAL read " + std::to_string(theirs.number_of_vertices()) + " vertices, EdgeFront " +
           std::to_string(ours.number_of_vertices());
  for (const SmVertex v : ours.vertices()) {
    const Point3& a = ours.point(v);
    const Point3& b = theirs.point(v);
    if (a != b) {
      std::ostringstream os;
      os.precision(17);
      os << "mismatch: vertex " << v.idx() << " is (" << a << ") for EdgeFront, (" << b << ") for CGAL";
      return os.str();
    }
  }
  if (theirs.number_of_faces() != ours.number_of_faces())
    return "mismatch: CGAL read " + std::to_string(theirs.number_of_faces()) + " faces, EdgeFront " +
           std::to_string(ours.number_of_faces());
  auto triples = [](const SurfaceMesh& sm) {
    std::vector<std::array<std::uint32_t, 3>> out;
    out.reserve(sm.number_of_faces());
    for (const auto f : sm.faces()) {
      std::array<std::uint32_t, 3> t{};
      size_t k = 0;
      for (const SmVertex v : CGAL::vertices_around_face(sm.halfedge(f), sm)) {
        if (k < 3) t[k] = static_cast<std::uint32_t>(v.idx());
        ++k;
      }
      // Rotate so that the smallest index comes first (keeps the orientation).
      std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
      out.push_back(t);
    }
    std::sort(out.begin(), out.end());
    return out;
  };
  if (triples(theirs) != triples(ours)) return "mismatch: same vertices, different faces";
  return "ok (" + std::to_string(ours.number_of_vertices()) + " vertices bit-identical, " +
         std::to_string(ours.number_of_faces()) + " faces identical)";
}

std::filesystem::path output_path(const std::string& prefix, const char* method, int source) {
  return prefix + "." + method + "." + std::to_string(source) + ".bin";
}

bool have_file(const std::filesystem::path& path, size_t n) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  return !ec && size == n * sizeof(double);
}

void write_doubles(const std::filesystem::path& path, const std::vector<double>& values) {
  edgefront::write_file_atomically(
      path,
      [&](std::ostream& os) {
        os.write(reinterpret_cast<const char*>(values.data()),
                 static_cast<std::streamsize>(values.size() * sizeof(double)));
      },
      true);
}

/// `count` distinct non-isolated vertices drawn with std::mt19937_64(seed), not already in `taken`.
std::vector<int> pick_sources(const edgefront::Mesh& mesh, int count, std::uint64_t seed, const std::vector<int>& taken) {
  std::vector<int> candidates;
  for (const auto v : mesh.vertices())
    if (!mesh.is_isolated(v) && std::find(taken.begin(), taken.end(), v.idx()) == taken.end())
      candidates.push_back(v.idx());
  if (static_cast<size_t>(count) > candidates.size())
    throw edgefront::InvalidInput("--random " + std::to_string(count) + ": the mesh has only " +
                                  std::to_string(candidates.size()) + " usable vertices");
  std::mt19937_64 rng(seed);
  std::vector<int> out;
  for (int k = 0; k < count; ++k) {
    const size_t remaining = candidates.size() - static_cast<size_t>(k);
    const size_t j = static_cast<size_t>(k) + static_cast<size_t>(rng() % remaining);  // partial Fisher-Yates
    std::swap(candidates[static_cast<size_t>(k)], candidates[j]);
    out.push_back(candidates[static_cast<size_t>(k)]);
  }
  return out;
}

int run(Args args) {
  const edgefront::MeshReadResult read = edgefront::read_mesh(args.mesh);
  const edgefront::Mesh& mesh = read.mesh;
  const size_t n = mesh.n_vertices();
  if (args.random > 0) {
    const std::vector<int> picked = pick_sources(mesh, args.random, args.seed, args.sources);
    args.sources.insert(args.sources.end(), picked.begin(), picked.end());
  }
  if (args.print_sources) {
    for (size_t i = 0; i < args.sources.size(); ++i) std::cout << (i ? "," : "") << args.sources[i];
    std::cout << "\n";
    return 0;
  }
  for (const int s : args.sources) {
    if (static_cast<size_t>(s) >= n)
      throw edgefront::InvalidInput("source " + std::to_string(s) + " is not a vertex (the mesh has " +
                                    std::to_string(n) + ")");
    if (mesh.is_isolated(edgefront::VertexHandle(s)))
      throw edgefront::InvalidInput("source " + std::to_string(s) + " is an isolated vertex");
  }
  const std::filesystem::path prefix_dir = std::filesystem::path(args.prefix).parent_path();
  if (!prefix_dir.empty()) std::filesystem::create_directories(prefix_dir);

  const SurfaceMesh sm = to_cgal(mesh);
  Log log(args.prefix + ".log");
  {
    const std::time_t now = std::time(nullptr);
    char stamp[32];
    std::strftime(stamp, sizeof stamp, "%Y-%m-%dT%H:%M:%S", std::localtime(&now));
    log.line(std::string("# run ") + stamp + " mesh=" + args.mesh.string() + " vertices=" + std::to_string(n) +
             " faces=" + std::to_string(mesh.n_faces()));
  }
  log.line("order_check " + check_against_cgal_reader(args.mesh, sm));

  if (args.exact) {
    for (const int s : args.sources) {
      const auto path = output_path(args.prefix, "exact", s);
      if (args.skip_existing && have_file(path, n)) {
        log.line("# exact source=" + std::to_string(s) + " cached in " + path.string());
        continue;
      }
      reset_peak_rss();
      std::vector<double> d(n, kInf);
      size_t reached = 0;
      double build_s = 0, query_s = 0;
      {
        ShortestPath sp(sm);
        sp.add_source_point(SmVertex(static_cast<SurfaceMesh::size_type>(s)));
        const auto t0 = std::chrono::steady_clock::now();
        sp.build_sequence_tree();
        build_s = seconds_since(t0);
        const auto t1 = std::chrono::steady_clock::now();
        for (const SmVertex v : sm.vertices()) {
          const double dv = sp.shortest_distance_to_source_points(v).first;
          if (dv >= 0) {
            d[v.idx()] = dv;
            ++reached;
          }
        }
        query_s = seconds_since(t1);
      }
      write_doubles(path, d);
      log.line("exact source=" + std::to_string(s) + " build_s=" + fmt(build_s) + " query_s=" + fmt(query_s) +
               " reached=" + std::to_string(reached) + " peak_rss_mb=" + fmt(peak_rss_mb(), 5));
    }
  }

  if (args.heat) {
    bool all_cached = args.skip_existing;
    for (const int s : args.sources) all_cached = all_cached && have_file(output_path(args.prefix, "heat", s), n);
    if (all_cached) {
      log.line("# heat: every source cached");
      return 0;
    }
    SurfaceMesh hm_mesh = sm;  // the distance property map lives on this copy
    auto dmap = hm_mesh.add_property_map<SmVertex, double>("v:heat_distance", 0.0).first;
    reset_peak_rss();
    std::unique_ptr<HeatIdt> hm;
    try {
      const auto t0 = std::chrono::steady_clock::now();
      hm = std::make_unique<HeatIdt>(hm_mesh);
      log.line("heat precompute_s=" + fmt(seconds_since(t0)) + " peak_rss_mb=" + fmt(peak_rss_mb(), 5));
    } catch (const std::exception& e) {
      log.line("heat_failed stage=precompute message=" + quote(e.what()));
      return 0;
    }
    for (const int s : args.sources) {
      const auto path = output_path(args.prefix, "heat", s);
      if (args.skip_existing && have_file(path, n)) {
        log.line("# heat source=" + std::to_string(s) + " cached in " + path.string());
        continue;
      }
      try {
        hm->clear_sources();
        hm->add_source(SmVertex(static_cast<SurfaceMesh::size_type>(s)));
        const auto t0 = std::chrono::steady_clock::now();
        hm->estimate_geodesic_distances(dmap);
        const double solve_s = seconds_since(t0);
        std::vector<double> d(n, kInf);
        for (const SmVertex v : hm_mesh.vertices()) d[v.idx()] = dmap[v];
        write_doubles(path, d);
        log.line("heat source=" + std::to_string(s) + " solve_s=" + fmt(solve_s));
      } catch (const std::exception& e) {
        log.line("heat_failed stage=solve source=" + std::to_string(s) + " message=" + quote(e.what()));
      }
    }
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(parse_args(argc, argv));
  } catch (const UsageError& e) {
    std::cerr << "cgal_geodesic_reference: " << e.what() << "\n";
    print_usage(std::cerr);
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "cgal_geodesic_reference: error: " << e.what() << "\n";
    return 1;
  }
}
