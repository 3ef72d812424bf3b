/// bench_paths: connection paths (paper §2.4) on real meshes: time per query against a
/// bidirectional Dijkstra written here, path length error against CGAL's exact geodesics, elements
/// processed with and without the directed search, many targets from one source; and a locality
/// check on two grids of equal local triangulation.
///
///   bench_paths --mesh FILE [--subdiv N] [--reference PREFIX] [--sources a,b,...]
///               [--random-sources K] [--targets T] [--seed S] [--only NAME,NAME,...] [--no-many]
///               [--band R] [--steiner K]
///   bench_paths --grid-check [--large CELLS]
///
/// Pairs: for each source vertex, T random target vertices (std::mt19937_64(S)). With --reference,
/// the sources are those with a PREFIX.exact.<s>.bin file of bench/cgal_geodesic_reference (exact
/// distances from s to every vertex, CGAL Surface_mesh_shortest_path), and every pair is compared
/// with the exact distance. Without it, K random sources (no accuracy columns).
///
/// Per pair, in this order, each timed separately (steady_clock):
///   bidirectional Dijkstra over edge lengths (per-mesh arrays allocated once, reset by a touched
///   list; binary heap; stops when the two smallest keys add up to the best meeting),
///   VF, MEF, MDF connection paths, undirected, directed and confined, MDF with a polyline, all
///   through one reused edgefront::ConnectionPathFinder.
/// The hop counts of every VF/MEF variant must agree (the run aborts otherwise).
/// Then per source: find_many over its T targets against the sum of the single queries (skipped with
/// --no-many). --only runs just the named variants (names as in the table's first column).
///
/// --grid-check: the same 5 queries on a 100x100 grid and a LARGExLARGE grid (default 2000) with
/// cell size 0.02, elements processed per method (must be equal), and a 10-triangle island query.
///
/// Prints markdown. A measurement, not a test.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <limits>
#include <map>
#include <queue>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "edgefront/connection_path.h"
#include "edgefront/error.h"
#include "edgefront/mesh.h"
#include "edgefront/mesh_io.h"
#include "shapes/shapes.h"

// After mesh.h: OpenMesh's subdivider headers rely on what the mesh headers include.
#include <OpenMesh/Tools/Subdivider/Uniform/LoopT.hh>

namespace {

namespace fs = std::filesystem;
using namespace edgefront;
using Clock = std::chrono::steady_clock;

double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

std::string fixed(double x, int digits) {
  std::ostringstream os;
  os << std::fixed << std::setprecision(digits) << x;
  return os.str();
}
std::string pct(double x) { return fixed(100 * x, 3) + "%"; }

// ---- bidirectional Dijkstra (the baseline) --------------------------------------------------

class BidirectionalDijkstra {
 public:
  explicit BidirectionalDijkstra(const Mesh& mesh) : mesh_(mesh) {
    for (auto& d : dist_) d.assign(mesh.n_vertices(), kInf);
    for (auto& c : closed_) c.assign(mesh.n_vertices(), 0);
  }
  // Shortest edge-path length, +inf when not connected. `settled` counts closed vertices. With
  // `one_sided`, only the front from s grows, until t settles (plain Dijkstra with a target).
  double run(VertexHandle s, VertexHandle t, size_t& settled, bool one_sided = false) {
    for (int side = 0; side < 2; ++side) {
      for (int v : touched_[side]) {
        dist_[side][v] = kInf;
        closed_[side][v] = 0;
      }
      touched_[side].clear();
    }
    using Entry = std::pair<double, int>;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> q[2];
    auto label = [&](int side, int v, double d) {
      if (dist_[side][v] == kInf) touched_[side].push_back(v);
      dist_[side][v] = d;
      q[side].push({d, v});
    };
    auto top = [&](int side) {
      while (!q[side].empty() && closed_[side][q[side].top().second]) q[side].pop();
      return q[side].empty() ? kInf : q[side].top().first;
    };
    label(0, s.idx(), 0);
    if (!one_sided) label(1, t.idx(), 0);
    double best = s == t ? 0 : kInf;
    settled = 0;
    auto settle = [&](int side) {  // the top of `side` (after `top`)
      const int x = q[side].top().second;
      q[side].pop();
      closed_[side][x] = 1;
      ++settled;
      const Vec3& px = mesh_.point(VertexHandle(x));
      for (VertexHandle y : mesh_.vv_range(VertexHandle(x))) {
        const double d = dist_[side][x] + (mesh_.point(y) - px).norm();
        if (d < dist_[side][y.idx()]) label(side, y.idx(), d);
        best = std::min(best, d + dist_[1 - side][y.idx()]);
      }
    };
    if (one_sided) {
      while (top(0) < kInf && !closed_[0][t.idx()]) settle(0);
      return dist_[0][t.idx()];
    }
    while (true) {
      const double k0 = top(0), k1 = top(1);
      if (k0 == kInf || k1 == kInf || k0 + k1 >= best) break;
      settle(k0 <= k1 ? 0 : 1);
    }
    return best;
  }

 private:
  static constexpr double kInf = std::numeric_limits<double>::infinity();
  const Mesh& mesh_;
  std::vector<double> dist_[2];
  std::vector<uint8_t> closed_[2];
  std::vector<int> touched_[2];
};

// ---- statistics ------------------------------------------------------------------------------

struct Series {
  std::vector<double> time, processed, rel_error;
  std::vector<double> front, front_bytes, region_bytes;  // peak front size, its bytes, area values' bytes
  void add(double t, double p) {
    time.push_back(t);
    processed.push_back(static_cast<double>(p));
  }
};
double mean(const std::vector<double>& v) {
  if (v.empty()) return std::nan("");
  double s = 0;
  for (double x : v) s += x;
  return s / static_cast<double>(v.size());
}
double quantile(std::vector<double> v, double q) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(q * static_cast<double>(v.size())))];
}

std::vector<double> read_doubles(const fs::path& path, size_t n) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError("cannot open " + path.string());
  std::vector<double> d(n);
  in.read(reinterpret_cast<char*>(d.data()), static_cast<std::streamsize>(n * sizeof(double)));
  if (in.gcount() != static_cast<std::streamsize>(n * sizeof(double)) || in.peek() != EOF) {
    throw IoError(path.string() + " does not hold exactly " + std::to_string(n) + " doubles");
  }
  return d;
}

// Sources with a PREFIX.exact.<s>.bin file.
std::vector<int> reference_sources(const std::string& prefix) {
  const fs::path p(prefix);
  const std::string stem = p.filename().string() + ".exact.";
  std::vector<int> out;
  for (const auto& e : fs::directory_iterator(p.parent_path().empty() ? fs::path(".") : p.parent_path())) {
    const std::string name = e.path().filename().string();
    if (name.rfind(stem, 0) != 0 || name.size() <= stem.size() + 4 || name.substr(name.size() - 4) != ".bin") continue;
    out.push_back(std::stoi(name.substr(stem.size(), name.size() - stem.size() - 4)));
  }
  std::sort(out.begin(), out.end());
  return out;
}

struct Args {
  std::string mesh;
  int subdiv = 0;
  std::string reference;
  std::vector<int> sources;
  int random_sources = 5;
  int targets = 200;
  uint64_t seed = 1;
  bool grid_check = false;
  int large = 2000;
  std::vector<std::string> only;  // --only: variant names to run (default: all)
  bool many = true;               // --no-many: skip the find_many comparison
  double band = -1;               // --band R: polyline band radius / path length (default: the option's)
  int steiner = -1;               // --steiner K: Steiner points per edge of the band step
};

Args parse(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string f = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw InvalidInput(f + " needs a value");
      return argv[++i];
    };
    if (f == "--mesh") a.mesh = value();
    else if (f == "--subdiv") a.subdiv = std::stoi(value());
    else if (f == "--reference") a.reference = value();
    else if (f == "--sources") {
      std::stringstream ss(value());
      for (std::string tok; std::getline(ss, tok, ',');) a.sources.push_back(std::stoi(tok));
    } else if (f == "--random-sources") a.random_sources = std::stoi(value());
    else if (f == "--targets") a.targets = std::stoi(value());
    else if (f == "--seed") a.seed = std::stoull(value());
    else if (f == "--grid-check") a.grid_check = true;
    else if (f == "--large") a.large = std::stoi(value());
    else if (f == "--only") {
      std::stringstream ss(value());
      for (std::string tok; std::getline(ss, tok, ',');) a.only.push_back(tok);
    } else if (f == "--no-many") a.many = false;
    else if (f == "--band") a.band = std::stod(value());
    else if (f == "--steiner") a.steiner = std::stoi(value());
    else throw InvalidInput("unknown flag " + f + " (see the comment at the top of bench/bench_paths.cpp)");
  }
  if (!a.grid_check && a.mesh.empty()) throw InvalidInput("--mesh FILE or --grid-check is required");
  if (a.targets < 1 || a.subdiv < 0 || a.subdiv > 4 || a.large < 100) throw InvalidInput("bad option values");
  return a;
}

// ---- the mesh benchmark ----------------------------------------------------------------------

struct Variant {
  std::string name;
  ConnectionPathOptions options;
};

int run_mesh(const Args& a) {
  Mesh mesh = read_mesh(a.mesh).mesh;
  const size_t v0 = mesh.n_vertices();
  if (a.subdiv > 0) {
    OpenMesh::Subdivider::Uniform::LoopT<Mesh, double> loop;
    loop.attach(mesh);
    loop(static_cast<size_t>(a.subdiv));
    loop.detach();
  }
  const size_t n = mesh.n_vertices();
  std::vector<int> sources = a.sources;
  if (!a.reference.empty() && sources.empty()) sources = reference_sources(a.reference);
  std::mt19937_64 rng(a.seed);
  std::uniform_int_distribution<int> pick(0, static_cast<int>(n) - 1);
  if (sources.empty()) {
    for (int i = 0; i < a.random_sources; ++i) sources.push_back(pick(rng));
  }
  std::cout << "### " << fs::path(a.mesh).stem().string() << (a.subdiv ? " Loop x" + std::to_string(a.subdiv) : "")
            << " (" << n << " vertices, " << mesh.n_faces() << " faces; " << sources.size() << " sources x "
            << a.targets << " random targets, seed " << a.seed << (a.reference.empty() ? "" : ", exact reference")
            << ")\n\n";
  (void)v0;

  std::vector<Variant> variants = {
      {"VF", {.method = PathMethod::VertexFront}},
      {"VF directed", {.method = PathMethod::VertexFront, .directed = true}},
      {"MEF", {.method = PathMethod::MinimalEdgeFront}},
      {"MEF directed", {.method = PathMethod::MinimalEdgeFront, .directed = true}},
      {"MDF (vertex path; length = meeting sum)", {.method = PathMethod::MinimalDistance}},
      {"MDF directed (A* edge path)", {.method = PathMethod::MinimalDistance, .directed = true}},
      {"MDF + polyline", {.method = PathMethod::MinimalDistance, .polyline = true}},
      {"MDF directed + polyline", {.method = PathMethod::MinimalDistance, .polyline = true, .directed = true}},
      {"MDF + polyline without band step", {.method = PathMethod::MinimalDistance, .polyline = true, .polyline_band = 0}},
      {"MDF directed + polyline without band step",
       {.method = PathMethod::MinimalDistance, .polyline = true, .directed = true, .polyline_band = 0}},
      {"VF confined", {.method = PathMethod::VertexFront, .confine = true}},
      {"MEF confined", {.method = PathMethod::MinimalEdgeFront, .confine = true}},
      {"MDF recursive (paper's halves)", {.method = PathMethod::MinimalDistance, .mdf_recursion = true}},
  };
  if (!a.only.empty()) {
    std::erase_if(variants, [&](const Variant& v) {
      return std::find(a.only.begin(), a.only.end(), v.name) == a.only.end();
    });
    EF_CHECK(!variants.empty(), "--only names no variant");
  }
  for (Variant& v : variants) {
    if (!v.options.polyline || v.options.polyline_band == 0) continue;
    if (a.band >= 0) v.options.polyline_band = a.band;
    if (a.steiner >= 0) v.options.polyline_steiner = a.steiner;
  }
  std::vector<Series> series(variants.size());
  Series dijkstra, one_sided;
  ConnectionPathFinder finder(mesh);
  BidirectionalDijkstra bd(mesh);
  size_t pairs = 0, no_path = 0, unconverged = 0;
  double many_time[2] = {0, 0}, single_time[2] = {0, 0};
  size_t many_work[2] = {0, 0}, single_work[2] = {0, 0};
  std::vector<double> many_error[2];  // MDF lengths vs exact: find_many, single queries
  for (int s : sources) {
    std::vector<double> exact;
    if (!a.reference.empty()) exact = read_doubles(a.reference + ".exact." + std::to_string(s) + ".bin", n);
    std::vector<VertexHandle> targets;
    while (static_cast<int>(targets.size()) < a.targets) {
      const int t = pick(rng);
      if (t != s) targets.emplace_back(t);
    }
    const VertexHandle vs(s);
    for (VertexHandle vt : targets) {
      ++pairs;
      size_t settled = 0;
      auto t0 = Clock::now();
      const double dij = bd.run(vs, vt, settled);
      const double t_dij = since(t0);
      if (!std::isfinite(dij)) {
        ++no_path;
        continue;
      }
      const double ref = exact.empty() ? std::nan("") : exact[vt.idx()];
      dijkstra.add(t_dij, static_cast<double>(settled));
      t0 = Clock::now();
      const double one = bd.run(vs, vt, settled, true);
      one_sided.add(since(t0), static_cast<double>(settled));
      EF_CHECK(std::abs(one - dij) <= 1e-9 * dij, "one- and two-sided Dijkstra disagree");
      if (std::isfinite(ref) && ref > 0) dijkstra.rel_error.push_back(std::abs(dij - ref) / ref);
      long hops = -1;
      for (size_t i = 0; i < variants.size(); ++i) {
        t0 = Clock::now();
        const ConnectionPath p = finder.find(vs, vt, variants[i].options);
        const double t = since(t0);
        EF_CHECK(p.status == PathStatus::Found, "Dijkstra found a path, " + variants[i].name + " did not");
        series[i].add(t, static_cast<double>(p.processed));
        series[i].front.push_back(static_cast<double>(p.peak_front_size));
        series[i].front_bytes.push_back(static_cast<double>(p.peak_front_memory_bytes));
        series[i].region_bytes.push_back(static_cast<double>(p.region_memory_bytes));
        if (variants[i].options.method != PathMethod::MinimalDistance) {
          if (hops < 0) hops = static_cast<long>(p.edges);
          EF_CHECK(hops == static_cast<long>(p.edges), variants[i].name + " hop count differs");
        }
        if (variants[i].options.polyline && !p.polyline_converged) ++unconverged;
        if (std::isfinite(ref) && ref > 0) series[i].rel_error.push_back(std::abs(p.length - ref) / ref);
      }
    }
    // Many targets from one source vs the same queries one by one.
    int k = 0;
    if (!a.many) continue;
    for (PathMethod m : {PathMethod::MinimalEdgeFront, PathMethod::MinimalDistance}) {
      auto t0 = Clock::now();
      const auto many = finder.find_many(vs, targets, {.method = m});
      many_time[k] += since(t0);
      std::vector<ConnectionPath> single;
      t0 = Clock::now();
      for (VertexHandle vt : targets) single.push_back(finder.find(vs, vt, {.method = m}));
      single_time[k] += since(t0);
      for (size_t i = 0; i < targets.size(); ++i) {
        many_work[k] += many[i].processed;
        single_work[k] += single[i].processed;
        EF_CHECK(many[i].status == single[i].status, "find_many and find disagree on a path's existence");
        if (m != PathMethod::MinimalDistance) {
          EF_CHECK(many[i].edges == single[i].edges, "find_many's hop count differs from find's");
          continue;
        }
        const double ref = exact.empty() ? std::nan("") : exact[targets[i].idx()];
        if (!(std::isfinite(ref) && ref > 0) || many[i].status != PathStatus::Found) continue;
        many_error[0].push_back(std::abs(many[i].length - ref) / ref);
        many_error[1].push_back(std::abs(single[i].length - ref) / ref);
      }
      ++k;
    }
  }
  const double t_ref = mean(dijkstra.time);
  std::cout << "| method | time per query | / bidir. Dijkstra | elements processed | mean rel. error | 99th pct | max "
               "| within 0.5% |\n|---|---:|---:|---:|---:|---:|---:|---:|\n";
  auto row = [&](const std::string& name, const Series& s) {
    std::cout << "| " << name << " | " << fixed(mean(s.time) * 1e3, 3) << " ms | " << fixed(mean(s.time) / t_ref, 2)
              << " | " << fixed(mean(s.processed), 0) << " | ";
    if (s.rel_error.empty()) {
      std::cout << "- | - | - | - |\n";
      return;
    }
    const double within = static_cast<double>(std::count_if(s.rel_error.begin(), s.rel_error.end(),
                                                            [](double e) { return e <= 0.005; })) /
                          static_cast<double>(s.rel_error.size());
    std::cout << pct(mean(s.rel_error)) << " | " << pct(quantile(s.rel_error, 0.99)) << " | "
              << pct(*std::max_element(s.rel_error.begin(), s.rel_error.end())) << " | " << pct(within) << " |\n";
  };
  row("bidirectional Dijkstra (edge lengths)", dijkstra);
  row("Dijkstra, one front to the target", one_sided);
  for (size_t i = 0; i < variants.size(); ++i) {
    const bool hop = variants[i].options.method != PathMethod::MinimalDistance;
    Series s = series[i];
    if (hop) s.rel_error.clear();  // hop paths: no geodesic length to compare
    row(variants[i].name, s);
  }
  std::cout << "\nWorking memory per query (means): the fronts follow the front; the per-vertex values of "
               "the processed area (MDF: both fronts' settled distances, for the meeting test and the traced "
               "halves; confine; the directed search's tables) follow the area.\n\n| method | elements processed "
               "| largest front (elements) | its memory | area values' memory |\n|---|---:|---:|---:|---:|\n";
  for (size_t i = 0; i < variants.size(); ++i) {
    const Series& x = series[i];
    std::cout << "| " << variants[i].name << " | " << fixed(mean(x.processed), 0) << " | " << fixed(mean(x.front), 0)
              << " | " << fixed(mean(x.front_bytes) / 1024, 1) << " KiB | " << fixed(mean(x.region_bytes) / 1024, 1)
              << " KiB |\n";
  }
  std::cout << "\n" << pairs << " pairs, " << no_path << " without a path (skipped); polylines not converged: "
            << unconverged << ". Errors are |length - exact| / exact (VF/MEF are hop-count paths: no error column).\n\n";
  const char* names[2] = {"MEF", "MDF"};
  if (!a.many) return 0;
  std::cout << "Many targets from one source (find_many over each source's " << a.targets << " targets vs the same "
            << "queries one by one):\n\n| method | find_many time | single queries time | elements processed "
               "(many / single) |\n|---|---:|---:|---:|\n";
  for (int k = 0; k < 2; ++k) {
    std::cout << "| " << names[k] << " | " << fixed(many_time[k], 3) << " s | " << fixed(single_time[k], 3) << " s | "
              << many_work[k] << " / " << single_work[k] << " (" << fixed(100.0 * many_work[k] / single_work[k], 1)
              << "%) |\n";
  }
  if (!many_error[0].empty()) {
    auto within = [](const std::vector<double>& e) {
      return static_cast<double>(std::count_if(e.begin(), e.end(), [](double x) { return x <= 0.005; })) /
             static_cast<double>(e.size());
    };
    std::cout << "\nMDF lengths vs exact (MEF hop counts are checked equal): find_many (source front's distance) "
              << pct(mean(many_error[0])) << " mean, " << pct(within(many_error[0])) << " within 0.5%; single queries "
              << "(meeting sum) " << pct(mean(many_error[1])) << " mean, " << pct(within(many_error[1]))
              << " within 0.5%.\n";
  }
  std::cout << "\n";
  return 0;
}

// ---- locality on grids -------------------------------------------------------------------------

VertexHandle nearest(const Mesh& mesh, const Vec3& p) {
  VertexHandle best;
  double bd = std::numeric_limits<double>::infinity();
  for (VertexHandle v : mesh.vertices()) {
    const double d = (mesh.point(v) - p).sqrnorm();
    if (d < bd) {
      bd = d;
      best = v;
    }
  }
  return best;
}

int run_grid_check(const Args& a) {
  const std::vector<std::pair<Vec3, Vec3>> queries = {
      {{-0.2, 0.06, 0}, {0.24, -0.1, 0}}, {{0, 0, 0}, {0.5, 0.5, 0}}, {{-0.3, 0.2, 0}, {0.3, 0.25, 0}},
      {{0.1, -0.4, 0}, {0.1, 0.4, 0}},    {{-0.05, -0.05, 0}, {0.05, 0.07, 0}}};
  const std::vector<std::pair<std::string, ConnectionPathOptions>> methods = {
      {"VF", {.method = PathMethod::VertexFront}},
      {"MEF", {.method = PathMethod::MinimalEdgeFront}},
      {"MDF", {.method = PathMethod::MinimalDistance}},
      {"MDF + polyline", {.method = PathMethod::MinimalDistance, .polyline = true}},
      {"MEF confined", {.method = PathMethod::MinimalEdgeFront, .confine = true}},
      {"MDF confined", {.method = PathMethod::MinimalDistance, .confine = true}},
      {"MEF directed", {.method = PathMethod::MinimalEdgeFront, .directed = true}},
      {"MDF directed", {.method = PathMethod::MinimalDistance, .directed = true}}};
  std::map<std::pair<size_t, size_t>, std::vector<size_t>> work;  // (query, method) -> per grid
  std::map<std::pair<size_t, size_t>, std::vector<double>> time;
  std::vector<size_t> island_work;
  for (int cells : {100, a.large}) {
    auto t0 = Clock::now();
    Mesh mesh = shapes::grid({.cells = cells, .half_size = cells / 100.0});
    const std::vector<VertexHandle> island_vertices = shapes::add_island(mesh);  // 10 triangles above the grid
    std::cerr << "grid " << cells << "x" << cells << ": " << mesh.n_faces() << " faces in " << fixed(since(t0), 1)
              << " s\n";
    ConnectionPathFinder finder(mesh);
    for (size_t q = 0; q < queries.size(); ++q) {
      const VertexHandle s = nearest(mesh, queries[q].first), t = nearest(mesh, queries[q].second);
      for (size_t m = 0; m < methods.size(); ++m) {
        t0 = Clock::now();
        const ConnectionPath p = finder.find(s, t, methods[m].second);
        time[{q, m}].push_back(since(t0));
        work[{q, m}].push_back(p.processed);
      }
    }
    const VertexHandle g = nearest(mesh, Vec3(0, 0, 0)), island = island_vertices[4];  // upper row, third vertex
    for (size_t m = 0; m < 3; ++m) {
      const ConnectionPath p = finder.find(g, island, methods[m].second);
      EF_CHECK(p.status == PathStatus::NoPath, "the island is connected?");
      island_work.push_back(p.processed);
    }
  }
  std::cout << "### Locality: the same queries on a 100x100 and a " << a.large << "x" << a.large
            << " grid (cell size 0.02, 2 triangles per cell)\n\n| query | method | elements processed (100 / "
            << a.large << ") | time ms (100 / " << a.large << ") |\n|---|---|---:|---:|\n";
  bool equal = true;
  for (const auto& [key, w] : work) {
    const auto& t = time[key];
    equal = equal && w[0] == w[1];
    std::cout << "| " << key.first << " | " << methods[key.second].first << " | " << w[0] << " / " << w[1] << " | "
              << fixed(t[0] * 1e3, 3) << " / " << fixed(t[1] * 1e3, 3) << " |\n";
  }
  std::cout << "\nNo path from the grid centre to a 10-triangle island (VF, MEF, MDF): elements processed "
            << island_work[0] << ", " << island_work[1] << ", " << island_work[2] << " beside the 100x100 grid; "
            << island_work[3] << ", " << island_work[4] << ", " << island_work[5] << " beside the " << a.large << "x"
            << a.large << " grid.\n\nAll processed counts equal: " << (equal ? "yes" : "NO") << "\n\n";
  return equal ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Args a = parse(argc, argv);
    return a.grid_check ? run_grid_check(a) : run_mesh(a);
  } catch (const std::exception& e) {
    std::cerr << "bench_paths: error: " << e.what() << "\n";
    return 1;
  }
}
