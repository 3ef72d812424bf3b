// geodesic_accuracy: how close the Minimal Distance Front (edgefront::geodesic_distance) comes to
// exact polyhedral geodesics, next to Dijkstra over edges and CGAL's heat method.
//
//   geodesic_accuracy MESH --ref PREFIX [--sources a,b,...] [--name NAME] [--pairs N] [--seed S]
//                          [--worst K] [--windows] [--fast]
//   geodesic_accuracy --synthetic [--ref-dir DIR] [--worst K] [--windows] [--fast]
//   geodesic_accuracy --write-shapes DIR
//
// Mesh mode reads the reference files of bench/cgal_geodesic_reference (PREFIX.exact.<s>.bin,
// optional PREFIX.heat.<s>.bin, timings from PREFIX.log); without --sources every source with an
// exact file is used. For each source it runs the MDF and Dijkstra (timed here) and compares all
// four against the exact distances: relative error |d - d_exact| / d_exact over every vertex except
// those with d_exact = 0 (the source) or unreachable; vertices the exact solver reaches and a
// method does not are counted separately. Then the symmetry statistic |d(a,b) - d(b,a)| / d(a,b)
// of the MDF over N random pairs (each direction a run with `target`).
//
// Synthetic mode needs no CGAL: planar grids (regular, jittered, anisotropic, square and disk
// outlines), where the exact answer is the Euclidean distance, and open cylinders and cones, whose
// polyhedral geodesics are known in closed form (the cylinder is a prism and unrolls into a strip;
// the cone is a pyramid and unrolls into a fan). With --ref-dir, CGAL's exact distances for the
// cylinders and cones (made by cgal_geodesic_reference from the meshes that --write-shapes writes)
// are compared too, and against the closed form.
//
// --fast runs the MDF with DistanceMethod::Fast (the "MDF" columns are then the fast mode);
// --windows with DistanceMethod::Windows.
//
// Output: markdown on stdout. Exit codes: 0 done (targets missed are reported, not fatal),
// 1 error, 2 usage.

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <map>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "edgefront/error.h"
#include "edgefront/front_source.h"
#include "edgefront/mesh.h"
#include "edgefront/mesh_io.h"
#include "edgefront/minimal_distance_front.h"
#include "shapes/shapes.h"

namespace {

namespace fs = std::filesystem;
using edgefront::DistanceField;
using edgefront::DistanceMethod;
using edgefront::DistanceOptions;
using edgefront::FrontSource;
using edgefront::Mesh;
using edgefront::Vec3;
using edgefront::VertexHandle;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kPi = 3.14159265358979323846;

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// ---- small helpers ------------------------------------------------------------------------

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::string pct(double fraction, int precision = 3) {
  if (!std::isfinite(fraction)) return "n/a";
  std::ostringstream os;
  os << std::setprecision(precision) << 100.0 * fraction << "%";
  return os.str();
}

std::string num(double v, int precision = 4) {
  if (std::isnan(v)) return "n/a";
  std::ostringstream os;
  os << std::setprecision(precision) << v;
  return os.str();
}

std::string secs(double s) {
  if (!std::isfinite(s)) return "n/a";
  std::ostringstream os;
  if (s < 0.9995e-3)
    os << std::setprecision(3) << s * 1e6 << " µs";
  else if (s < 0.9995)
    os << std::setprecision(3) << s * 1e3 << " ms";
  else
    os << std::setprecision(3) << s << " s";
  return os.str();
}

std::string join(const std::vector<int>& v, const char* sep = ",") {
  std::string out;
  for (size_t i = 0; i < v.size(); ++i) out += (i ? sep : "") + std::to_string(v[i]);
  return out;
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
      throw UsageError("'" + item + "' is not a vertex index");
    }
    if (used != item.size() || v < 0 || v > std::numeric_limits<int>::max())
      throw UsageError("'" + item + "' is not a vertex index");
    out.push_back(static_cast<int>(v));
  }
  return out;
}

/// `count` distinct non-isolated vertices drawn with std::mt19937_64(seed), not in `taken`
/// (the same rule as cgal_geodesic_reference --random).
std::vector<int> pick_sources(const Mesh& mesh, int count, std::uint64_t seed, const std::vector<int>& taken = {}) {
  std::vector<int> candidates;
  for (const auto v : mesh.vertices())
    if (!mesh.is_isolated(v) && std::find(taken.begin(), taken.end(), v.idx()) == taken.end())
      candidates.push_back(v.idx());
  count = std::min<int>(count, static_cast<int>(candidates.size()));
  std::mt19937_64 rng(seed);
  std::vector<int> out;
  for (int k = 0; k < count; ++k) {
    const size_t remaining = candidates.size() - static_cast<size_t>(k);
    const size_t j = static_cast<size_t>(k) + static_cast<size_t>(rng() % remaining);
    std::swap(candidates[static_cast<size_t>(k)], candidates[j]);
    out.push_back(candidates[static_cast<size_t>(k)]);
  }
  return out;
}

std::vector<double> read_doubles(const fs::path& path, size_t n) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw edgefront::IoError("cannot open " + path.string());
  std::vector<double> d(n);
  in.read(reinterpret_cast<char*>(d.data()), static_cast<std::streamsize>(n * sizeof(double)));
  if (in.gcount() != static_cast<std::streamsize>(n * sizeof(double)) || in.peek() != EOF)
    throw edgefront::IoError(path.string() + " does not hold exactly " + std::to_string(n) +
                             " doubles (wrong mesh or vertex order?)");
  return d;
}

bool file_exists(const fs::path& p) {
  std::error_code ec;
  return fs::is_regular_file(p, ec);
}

// ---- error statistics ---------------------------------------------------------------------

/// Errors of one method against a reference, pooled over sources.
struct ErrorStats {
  std::vector<double> rel;  ///< |d - ref| / ref per compared vertex
  double signed_sum = 0;    ///< sum of (d - ref) / ref
  size_t below = 0;         ///< d < ref (1 - 1e-9): shorter than the exact geodesic
  size_t unreached = 0;     ///< ref finite and > 0, d infinite or NaN
  double time_s = 0;        ///< total time of the runs
  size_t runs = 0;

  void add(double ref, double d) {
    if (!(ref > 0) || !std::isfinite(ref)) return;  // the source itself, or unreachable
    if (!std::isfinite(d)) {
      ++unreached;
      return;
    }
    const double r = (d - ref) / ref;
    rel.push_back(std::abs(r));
    signed_sum += r;
    if (d < ref * (1 - 1e-9)) ++below;
  }
  double mean() const {
    if (rel.empty()) return std::nan("");
    double s = 0;
    for (const double r : rel) s += r;
    return s / static_cast<double>(rel.size());
  }
  double mean_signed() const { return rel.empty() ? std::nan("") : signed_sum / static_cast<double>(rel.size()); }
  double quantile(double q) const {
    if (rel.empty()) return std::nan("");
    std::vector<double> v = rel;
    const size_t k = std::min(v.size() - 1, static_cast<size_t>(std::ceil(q * static_cast<double>(v.size()))) - 1);
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
    return v[k];
  }
  double max() const { return rel.empty() ? std::nan("") : *std::max_element(rel.begin(), rel.end()); }
};

/// One compared vertex, kept to list the worst ones.
struct Sample {
  int source;
  int vertex;
  double exact;
  double ours;
  double dijkstra;
  double rel;
};

void print_worst(std::vector<Sample> samples, size_t k, const char* ours_name) {
  if (samples.empty() || k == 0) return;
  std::vector<Sample> unreached;
  std::vector<Sample> finite;
  for (const Sample& s : samples) (std::isfinite(s.ours) ? finite : unreached).push_back(s);
  if (!unreached.empty()) {
    std::cout << "\n" << unreached.size() << " (source, vertex) pairs reached by the reference are not reached by "
              << ours_name << "; the first " << std::min(k, unreached.size()) << ":\n\n| source | vertex | exact | Dijkstra |\n"
              << "|---|---|---|---|\n";
    for (size_t i = 0; i < std::min(k, unreached.size()); ++i)
      std::cout << "| " << unreached[i].source << " | " << unreached[i].vertex << " | " << std::setprecision(10)
                << unreached[i].exact << " | " << unreached[i].dijkstra << " |\n";
  }
  if (finite.empty()) return;
  k = std::min(k, finite.size());
  std::partial_sort(finite.begin(), finite.begin() + static_cast<std::ptrdiff_t>(k), finite.end(),
                    [](const Sample& a, const Sample& b) { return a.rel > b.rel; });
  std::cout << "\nWorst " << ours_name << " vertices:\n\n| source | vertex | exact | " << ours_name
            << " | Dijkstra | rel. error |\n|---|---|---|---|---|---|\n";
  for (size_t i = 0; i < k; ++i) {
    const Sample& s = finite[i];
    std::cout << "| " << s.source << " | " << s.vertex << " | " << std::setprecision(10) << s.exact << " | "
              << s.ours << " | " << s.dijkstra << " | " << pct(s.rel, 4) << " |\n";
  }
}

// ---- the runs -----------------------------------------------------------------------------

struct Timed {
  DistanceField field;
  double seconds = 0;
};

// --windows: DistanceMethod::Windows; --fast: DistanceMethod::Fast.
bool g_windows = false;
bool g_fast = false;

Timed run_mdf(const Mesh& mesh, int source, const DistanceOptions& options = {}) {
  const auto t0 = std::chrono::steady_clock::now();
  DistanceOptions o = options;
  if (g_windows) o.method = DistanceMethod::Windows;
  if (g_fast) o.method = DistanceMethod::Fast;
  DistanceField f = edgefront::geodesic_distance(mesh, FrontSource::vertex(VertexHandle(source)), o);
  return {std::move(f), seconds_since(t0)};
}

Timed run_dijkstra(const Mesh& mesh, int source, const DistanceOptions& options = {}) {
  const auto t0 = std::chrono::steady_clock::now();
  DistanceField f = edgefront::dijkstra_distance(mesh, FrontSource::vertex(VertexHandle(source)), options);
  return {std::move(f), seconds_since(t0)};
}

struct SymmetryStats {
  ErrorStats stats;  ///< rel holds |d(a,b) - d(b,a)| / d(a,b)
  size_t pairs = 0;
  size_t skipped = 0;
  double seconds = 0;
  std::vector<std::array<double, 4>> worst;  ///< a, b, d(a,b), d(b,a)
};

SymmetryStats symmetry(const Mesh& mesh, int pairs, std::uint64_t seed) {
  SymmetryStats out;
  std::vector<int> usable;
  for (const auto v : mesh.vertices())
    if (!mesh.is_isolated(v)) usable.push_back(v.idx());
  if (usable.size() < 2) return out;
  std::mt19937_64 rng(seed);
  const auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < pairs; ++i) {
    const int a = usable[rng() % usable.size()];
    int b = a;
    while (b == a) b = usable[rng() % usable.size()];
    DistanceOptions o;
    o.directions = false;
    o.method = g_fast ? DistanceMethod::Fast : g_windows ? DistanceMethod::Windows : DistanceMethod::Mdf;
    o.target = VertexHandle(b);
    const double dab = edgefront::geodesic_distance(mesh, FrontSource::vertex(VertexHandle(a)), o)
                           .distance[static_cast<size_t>(b)];
    o.target = VertexHandle(a);
    const double dba = edgefront::geodesic_distance(mesh, FrontSource::vertex(VertexHandle(b)), o)
                           .distance[static_cast<size_t>(a)];
    ++out.pairs;
    if (!std::isfinite(dab) || !std::isfinite(dba) || !(dab > 0)) {
      ++out.skipped;
      continue;
    }
    out.stats.rel.push_back(std::abs(dab - dba) / dab);
    out.worst.push_back({static_cast<double>(a), static_cast<double>(b), dab, dba});
  }
  out.seconds = seconds_since(t0);
  std::sort(out.worst.begin(), out.worst.end(), [](const auto& x, const auto& y) {
    return std::abs(x[2] - x[3]) / x[2] > std::abs(y[2] - y[3]) / y[2];
  });
  if (out.worst.size() > 5) out.worst.resize(5);
  return out;
}

// ---- mesh mode ----------------------------------------------------------------------------

/// Timings that cgal_geodesic_reference appended to PREFIX.log (last line per item wins).
struct RefLog {
  std::map<int, double> exact_s;
  std::map<int, double> heat_s;
  std::optional<double> heat_precompute_s;
  std::vector<std::string> heat_failures;
};

std::map<std::string, std::string> fields(const std::string& line) {
  std::map<std::string, std::string> out;
  std::istringstream in(line);
  std::string tok;
  while (in >> tok) {
    const auto eq = tok.find('=');
    if (eq != std::string::npos) out[tok.substr(0, eq)] = tok.substr(eq + 1);
  }
  return out;
}

RefLog read_ref_log(const fs::path& path) {
  RefLog log;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    auto f = fields(line);
    try {
      if (line.rfind("exact source=", 0) == 0) {
        log.exact_s[std::stoi(f["source"])] = std::stod(f["build_s"]) + std::stod(f["query_s"]);
      } else if (line.rfind("heat precompute_s=", 0) == 0) {
        log.heat_precompute_s = std::stod(f["precompute_s"]);
      } else if (line.rfind("heat source=", 0) == 0) {
        log.heat_s[std::stoi(f["source"])] = std::stod(f["solve_s"]);
      } else if (line.rfind("heat_failed", 0) == 0) {
        log.heat_failures.push_back(line);
      }
    } catch (const std::exception&) {
      // a malformed line is ignored; the timing column then says n/a
    }
  }
  return log;
}

/// Sources with a PREFIX.exact.<s>.bin file, in increasing order.
std::vector<int> discover_sources(const std::string& prefix) {
  const fs::path p(prefix);
  const fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
  const std::string stem = p.filename().string() + ".exact.";
  std::vector<int> out;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (name.rfind(stem, 0) != 0 || name.size() <= stem.size() + 4 || name.substr(name.size() - 4) != ".bin")
      continue;
    const std::string mid = name.substr(stem.size(), name.size() - stem.size() - 4);
    if (!mid.empty() && std::all_of(mid.begin(), mid.end(), [](char c) { return c >= '0' && c <= '9'; }))
      out.push_back(std::stoi(mid));
  }
  std::sort(out.begin(), out.end());
  return out;
}

struct MeshArgs {
  fs::path mesh;
  std::string prefix;
  std::string name;
  std::vector<int> sources;
  int pairs = 1000;
  std::uint64_t seed = 1;
  size_t worst = 10;
};

void row(const std::string& method, const ErrorStats& s, const std::string& time) {
  std::cout << "| " << method << " | " << pct(s.mean()) << " | " << pct(s.quantile(0.99)) << " | " << pct(s.max())
            << " | " << pct(s.mean_signed()) << " | " << s.below << " | " << s.unreached << " | " << time << " |\n";
}

int run_mesh(const MeshArgs& a) {
  const Mesh mesh = edgefront::load_mesh(a.mesh);
  const size_t n = mesh.n_vertices();
  std::vector<int> sources = a.sources.empty() ? discover_sources(a.prefix) : a.sources;
  if (sources.empty()) throw edgefront::InvalidInput("no reference files " + a.prefix + ".exact.<source>.bin found");
  for (const int s : sources)
    if (static_cast<size_t>(s) >= n) throw edgefront::InvalidInput("source " + std::to_string(s) + " is not a vertex");
  const RefLog log = read_ref_log(a.prefix + ".log");
  const std::string name = a.name.empty() ? a.mesh.stem().string() : a.name;

  ErrorStats mdf, dij, heat;
  double exact_time = 0;
  size_t exact_timed = 0, heat_sources = 0;
  double heat_time = 0;
  std::vector<Sample> samples;
  struct PerSource {
    int source;
    double mdf, dij, heat;
  };
  std::vector<PerSource> per_source;
  // Hard bounds every geodesic distance obeys: Euclidean <= d <= Dijkstra; and the MDF settles in
  // non-decreasing distance order.
  size_t below_euclid = 0, above_dijkstra = 0, inversions = 0, settled = 0;
  struct BelowEuclid {
    int source, vertex;
    double euclid, exact, ours;
  };
  std::vector<BelowEuclid> below_list;

  for (const int s : sources) {
    const std::vector<double> exact = read_doubles(a.prefix + ".exact." + std::to_string(s) + ".bin", n);
    std::optional<std::vector<double>> heat_d;
    const fs::path heat_path = a.prefix + ".heat." + std::to_string(s) + ".bin";
    if (file_exists(heat_path)) heat_d = read_doubles(heat_path, n);
    if (log.exact_s.count(s)) {
      exact_time += log.exact_s.at(s);
      ++exact_timed;
    }
    if (heat_d && log.heat_s.count(s)) {
      heat_time += log.heat_s.at(s);
      ++heat_sources;
    }
    const Timed m = run_mdf(mesh, s);
    const Timed d = run_dijkstra(mesh, s);
    mdf.time_s += m.seconds;
    ++mdf.runs;
    dij.time_s += d.seconds;
    ++dij.runs;
    ErrorStats m1, d1, h1;
    for (size_t v = 0; v < n; ++v) {
      const double dm = m.field.distance[v], dd = d.field.distance[v];
      mdf.add(exact[v], dm);
      m1.add(exact[v], dm);
      dij.add(exact[v], dd);
      d1.add(exact[v], dd);
      if (heat_d) {
        heat.add(exact[v], (*heat_d)[v]);
        h1.add(exact[v], (*heat_d)[v]);
      }
      if (exact[v] > 0 && std::isfinite(exact[v]))
        samples.push_back({s, static_cast<int>(v), exact[v], dm, dd,
                           std::isfinite(dm) ? std::abs(dm - exact[v]) / exact[v] : kInf});
    }
    per_source.push_back({s, m1.mean(), d1.mean(), heat_d ? h1.mean() : std::nan("")});
    const Vec3 ps = mesh.point(VertexHandle(s));
    for (const auto v : mesh.vertices()) {
      const double dm = m.field.distance[static_cast<size_t>(v.idx())];
      if (!std::isfinite(dm)) continue;
      const double e = (mesh.point(v) - ps).norm();
      if (dm < e * (1 - 1e-9)) {
        ++below_euclid;
        below_list.push_back({s, v.idx(), e, exact[static_cast<size_t>(v.idx())], dm});
      }
      if (dm > d.field.distance[static_cast<size_t>(v.idx())] * (1 + 1e-9)) ++above_dijkstra;
    }
    double last = 0;
    for (const VertexHandle v : m.field.order) {
      const double dm = m.field.distance[static_cast<size_t>(v.idx())];
      if (dm < last * (1 - 1e-9)) ++inversions;
      last = std::max(last, dm);
    }
    settled += m.field.order.size();
  }

  std::cout << "\n### " << name << " (" << n << " vertices, " << mesh.n_faces() << " faces; sources "
            << join(sources, ", ") << ")\n\n";
  std::cout << "| method | mean rel. error | 99th pct | max | mean signed | below exact | unreached | time per source |\n"
               "|---|---|---|---|---|---|---|---|\n";
  std::cout << "| exact (CGAL Surface_mesh_shortest_path) | 0 | 0 | 0 | 0 | 0 | 0 | "
            << (exact_timed ? secs(exact_time / static_cast<double>(exact_timed)) : "n/a") << " |\n";
  row("**MDF (EdgeFront)**", mdf, secs(mdf.time_s / static_cast<double>(mdf.runs)));
  row("Dijkstra over edges (EdgeFront)", dij, secs(dij.time_s / static_cast<double>(dij.runs)));
  if (!heat.rel.empty()) {
    std::string t = heat_sources ? secs(heat_time / static_cast<double>(heat_sources)) : "n/a";
    if (log.heat_precompute_s) t += " + " + secs(*log.heat_precompute_s) + " precompute";
    row("heat method, iDT (CGAL)", heat, t);
  }
  for (const std::string& f : log.heat_failures) std::cout << "\nheat method: `" << f << "`\n";
  std::cout << "\nMDF bounds over all sources: " << below_euclid << " values below the Euclidean distance, "
            << above_dijkstra << " above Dijkstra (both must be 0); " << inversions << " of " << settled
            << " vertices settled below the largest distance settled before them.\n";
  if (!below_list.empty()) {
    std::sort(below_list.begin(), below_list.end(), [](const BelowEuclid& x, const BelowEuclid& y) {
      return (x.euclid - x.ours) / x.euclid > (y.euclid - y.ours) / y.euclid;
    });
    std::cout << "\nLargest MDF values below the Euclidean distance:\n\n| source | vertex | Euclidean | exact | MDF | "
                 "(Euclidean - MDF) / Euclidean |\n|---|---|---|---|---|---|\n";
    for (size_t i = 0; i < std::min<size_t>(5, below_list.size()); ++i) {
      const BelowEuclid& b = below_list[i];
      std::cout << "| " << b.source << " | " << b.vertex << " | " << std::setprecision(10) << b.euclid << " | "
                << b.exact << " | " << b.ours << " | " << pct((b.euclid - b.ours) / b.euclid, 4) << " |\n";
    }
  }

  std::cout << "\nMean relative error per source:\n\n| source | MDF | Dijkstra | heat (iDT) |\n|---|---|---|---|\n";
  for (const PerSource& p : per_source)
    std::cout << "| " << p.source << " | " << pct(p.mdf) << " | " << pct(p.dij) << " | " << pct(p.heat) << " |\n";

  print_worst(std::move(samples), a.worst, "MDF");

  if (a.pairs > 0) {
    const SymmetryStats sym = symmetry(mesh, a.pairs, a.seed);
    std::cout << "\nSymmetry of the MDF, |d(a,b) - d(b,a)| / d(a,b) over " << sym.stats.rel.size()
              << " random pairs (seed " << a.seed << (sym.skipped ? ", " + std::to_string(sym.skipped) + " skipped" : "")
              << "): mean " << pct(sym.stats.mean(), 3) << ", 99th pct " << pct(sym.stats.quantile(0.99), 3)
              << ", max " << pct(sym.stats.max(), 3) << " (" << secs(sym.seconds) << " for " << 2 * sym.pairs
              << " runs with `target`).";
    if (!sym.worst.empty()) {
      std::cout << " Worst pairs (a, b, d(a,b), d(b,a)):";
      for (const auto& w : sym.worst)
        std::cout << " (" << static_cast<long>(w[0]) << ", " << static_cast<long>(w[1]) << ", "
                  << std::setprecision(10) << w[2] << ", " << w[3] << ")";
    }
    std::cout << "\n";
    std::cout << "\nTargets: MDF mean " << pct(mdf.mean()) << " (<= 0.3%: " << (mdf.mean() <= 0.003 ? "met" : "MISSED")
              << "), 99th pct " << pct(mdf.quantile(0.99))
              << " (<= 2%: " << (mdf.quantile(0.99) <= 0.02 ? "met" : "MISSED") << "), symmetry mean "
              << pct(sym.stats.mean()) << " (<= 0.05%: " << (sym.stats.mean() <= 0.0005 ? "met" : "MISSED") << ")"
              << (mdf.unreached ? ", UNREACHED vertices: " + std::to_string(mdf.unreached) : "") << "\n";
  }
  return 0;
}

// ---- synthetic mode -----------------------------------------------------------------------

/// Closed-form geodesic distances on the prism that `shapes::open_cylinder` builds (columns of
/// vertices at angles 2πi/n): unrolled, it is a strip of width n·c, c = 2R sin(π/n).
std::vector<double> cylinder_reference(const Mesh& mesh, int around, double radius, int source) {
  const double c = 2 * radius * std::sin(kPi / around);
  auto column = [&](const Vec3& p) {
    const double t = std::atan2(p[1], p[0]) / (2 * kPi / around);
    return ((static_cast<long>(std::lround(t)) % around) + around) % around;
  };
  const Vec3 ps = mesh.point(VertexHandle(source));
  const long cs = column(ps);
  std::vector<double> d(mesh.n_vertices());
  for (const auto v : mesh.vertices()) {
    const Vec3 p = mesh.point(v);
    long k = std::labs(column(p) - cs);
    k = std::min<long>(k, around - k);
    const double dx = static_cast<double>(k) * c, dz = p[2] - ps[2];
    d[static_cast<size_t>(v.idx())] = std::sqrt(dx * dx + dz * dz);
  }
  return d;
}

/// Closed-form geodesic distances on the pyramid that `shapes::cone` builds (vertices on the n
/// generators from the apex to the base vertices at angles 2πi/n): unrolled around the apex, each
/// face strip is a sector of angle α = 2 asin(c / 2L), c = 2R sin(π/n), L = sqrt(R² + H²). Two
/// points whose unrolled angle (the shorter way round) is below π see each other; otherwise the path
/// runs through the apex.
std::vector<double> cone_reference(const Mesh& mesh, int around, double radius, double height, int source) {
  const double c = 2 * radius * std::sin(kPi / around);
  const double slant = std::sqrt(radius * radius + height * height);
  const double alpha = 2 * std::asin(c / (2 * slant));
  const Vec3 apex(0, 0, height);
  auto column = [&](const Vec3& p) {
    const double t = std::atan2(p[1], p[0]) / (2 * kPi / around);
    return ((static_cast<long>(std::lround(t)) % around) + around) % around;
  };
  const Vec3 ps = mesh.point(VertexHandle(source));
  const double rs = (ps - apex).norm();
  const long cs = column(ps);
  std::vector<double> d(mesh.n_vertices());
  for (const auto v : mesh.vertices()) {
    const Vec3 p = mesh.point(v);
    const double r = (p - apex).norm();
    long k = std::labs(column(p) - cs);
    k = std::min<long>(k, around - k);
    const double angle = (r == 0 || rs == 0) ? 0.0 : static_cast<double>(k) * alpha;
    d[static_cast<size_t>(v.idx())] =
        angle < kPi ? std::sqrt(std::max(0.0, r * r + rs * rs - 2 * r * rs * std::cos(angle))) : r + rs;
  }
  return d;
}

struct DevelopableShape {
  std::string name;
  bool cone;
  int around;
  int along;
  double radius;
  double height;
};

const std::vector<DevelopableShape>& developable_shapes() {
  static const std::vector<DevelopableShape> shapes = {
      {"cylinder-64x20", false, 64, 20, 1.0, 2.0},
      {"cylinder-24x60", false, 24, 60, 1.0, 2.0},  // thin triangles: 0.26 around, 0.033 along
      {"cone-64x16", true, 64, 16, 1.0, 1.5},
      {"cone-24x48", true, 24, 48, 1.0, 1.5},
  };
  return shapes;
}

Mesh make_shape(const DevelopableShape& s) {
  return s.cone ? edgefront::shapes::cone(s.around, s.along, s.radius, s.height)
                : edgefront::shapes::open_cylinder(s.around, s.along, s.radius, s.height);
}

/// Sources on a developable shape: the cone's apex, then random vertices.
std::vector<int> shape_sources(const DevelopableShape& s, const Mesh& mesh) {
  std::vector<int> out;
  if (s.cone) {
    int apex = 0;
    for (const auto v : mesh.vertices())
      if (mesh.point(v)[2] > mesh.point(VertexHandle(apex))[2]) apex = v.idx();
    out.push_back(apex);
  }
  const std::vector<int> r = pick_sources(mesh, 6, 1, out);
  out.insert(out.end(), r.begin(), r.end());
  return out;
}

int write_shapes(const fs::path& dir) {
  fs::create_directories(dir);
  for (const DevelopableShape& s : developable_shapes()) {
    const Mesh mesh = make_shape(s);
    edgefront::write_mesh(mesh, dir / (s.name + ".off"));
    std::ofstream(dir / (s.name + ".sources")) << join(shape_sources(s, mesh)) << "\n";
    std::cout << (dir / (s.name + ".off")).string() << " " << join(shape_sources(s, mesh)) << "\n";
  }
  return 0;
}

struct PlanarCase {
  std::string name;
  edgefront::shapes::GridOptions options;
};

int run_synthetic(const fs::path& ref_dir, size_t worst) {
  using edgefront::shapes::GridOptions;
  using edgefront::shapes::GridOutline;
  using edgefront::shapes::GridVariant;
  std::vector<PlanarCase> planar;
  {
    GridOptions o;
    o.cells = 32;
    planar.push_back({"square, regular, 32x32", o});
    o.variant = GridVariant::jittered;
    planar.push_back({"square, jittered 0.15, 32x32", o});
    o.jitter = 0.16;
    o.seed = 7;
    planar.push_back({"square, jittered 0.16 (seed 7), 32x32", o});
    o = GridOptions{};
    o.cells = 16;
    o.variant = GridVariant::anisotropic;
    o.anisotropy = 20;
    planar.push_back({"square, anisotropic 1:20, 320x16", o});
    o.cells = 6;
    o.anisotropy = 100;
    planar.push_back({"square, anisotropic 1:100, 600x6", o});
    o = GridOptions{};
    o.cells = 16;
    o.outline = GridOutline::disk;
    planar.push_back({"disk, regular rings, 16 rings", o});
    o.variant = GridVariant::jittered;
    planar.push_back({"disk, jittered rings, 16 rings", o});
  }

  std::cout << "\n### Planar convex regions (reference: Euclidean distance)\n\n"
               "| triangulation | vertices | sources | MDF max rel. error | MDF mean | Dijkstra mean | MDF <= 1e-9 |\n"
               "|---|---|---|---|---|---|---|\n";
  std::vector<Sample> planar_worst;
  for (const PlanarCase& c : planar) {
    const Mesh mesh = edgefront::shapes::grid(c.options);
    // Sources: the vertex nearest the centre, vertex 0 (a corner / the centre of the disk), random.
    int centre = 0;
    for (const auto v : mesh.vertices())
      if (mesh.point(v).norm() < mesh.point(VertexHandle(centre)).norm()) centre = v.idx();
    std::vector<int> sources = {centre};
    if (centre != 0) sources.push_back(0);
    const std::vector<int> r = pick_sources(mesh, 4, 1, sources);
    sources.insert(sources.end(), r.begin(), r.end());
    ErrorStats mdf, dij;
    for (const int s : sources) {
      const Timed m = run_mdf(mesh, s), d = run_dijkstra(mesh, s);
      const Vec3 ps = mesh.point(VertexHandle(s));
      for (const auto v : mesh.vertices()) {
        const size_t i = static_cast<size_t>(v.idx());
        const double e = (mesh.point(v) - ps).norm();
        mdf.add(e, m.field.distance[i]);
        dij.add(e, d.field.distance[i]);
        if (e > 0)
          planar_worst.push_back({s, v.idx(), e, m.field.distance[i], d.field.distance[i],
                                  std::isfinite(m.field.distance[i]) ? std::abs(m.field.distance[i] - e) / e : kInf});
      }
    }
    const bool ok = mdf.max() <= 1e-9 && mdf.unreached == 0;
    std::cout << "| " << c.name << " | " << mesh.n_vertices() << " | " << join(sources, ", ") << " | "
              << num(mdf.max(), 3) << " | " << num(mdf.mean(), 3) << " | " << pct(dij.mean()) << " | "
              << (ok ? "yes" : "**no**") << (mdf.unreached ? " (" + std::to_string(mdf.unreached) + " unreached)" : "")
              << " |\n";
  }
  {
    // Keep only samples above the target for the worst list.
    std::vector<Sample> bad;
    for (const Sample& s : planar_worst)
      if (s.rel > 1e-9) bad.push_back(s);
    if (!bad.empty()) {
      std::cout << "\n" << bad.size() << " planar (source, vertex) pairs exceed 1e-9 (all grids pooled).";
      print_worst(std::move(bad), worst, "MDF");
    }
  }

  std::cout << "\n### Open cylinder and cone (prism and pyramid; reference: closed form"
            << (ref_dir.empty() ? "" : ", and CGAL exact where available") << ")\n\n"
            << "| mesh | vertices | reference | sources | MDF mean | MDF 99th pct | MDF max | MDF unreached | Dijkstra mean | "
               "MDF mean <= 0.1% |\n|---|---|---|---|---|---|---|---|---|---|\n";
  std::vector<std::string> notes;
  std::vector<Sample> dev_worst;
  for (const DevelopableShape& s : developable_shapes()) {
    const Mesh mesh = make_shape(s);
    const std::vector<int> sources = shape_sources(s, mesh);
    ErrorStats mdf_a, dij_a, mdf_c, dij_c;
    size_t cgal_sources = 0;
    double closed_vs_cgal = 0;
    for (const int src : sources) {
      const Timed m = run_mdf(mesh, src), d = run_dijkstra(mesh, src);
      const std::vector<double> ref = s.cone ? cone_reference(mesh, s.around, s.radius, s.height, src)
                                             : cylinder_reference(mesh, s.around, s.radius, src);
      for (size_t v = 0; v < mesh.n_vertices(); ++v) {
        mdf_a.add(ref[v], m.field.distance[v]);
        dij_a.add(ref[v], d.field.distance[v]);
        if (ref[v] > 0)
          dev_worst.push_back({src, static_cast<int>(v), ref[v], m.field.distance[v], d.field.distance[v],
                               std::isfinite(m.field.distance[v]) ? std::abs(m.field.distance[v] - ref[v]) / ref[v] : kInf});
      }
      const fs::path cgal = ref_dir / (s.name + ".exact." + std::to_string(src) + ".bin");
      if (!ref_dir.empty() && file_exists(cgal)) {
        const std::vector<double> ex = read_doubles(cgal, mesh.n_vertices());
        ++cgal_sources;
        for (size_t v = 0; v < mesh.n_vertices(); ++v) {
          mdf_c.add(ex[v], m.field.distance[v]);
          dij_c.add(ex[v], d.field.distance[v]);
          if (ex[v] > 0) closed_vs_cgal = std::max(closed_vs_cgal, std::abs(ref[v] - ex[v]) / ex[v]);
        }
      }
    }
    auto print = [&](const char* ref_name, const ErrorStats& m, const ErrorStats& d) {
      std::cout << "| " << s.name << " | " << mesh.n_vertices() << " | " << ref_name << " | " << join(sources, ", ")
                << " | " << pct(m.mean()) << " | " << pct(m.quantile(0.99)) << " | " << pct(m.max()) << " | "
                << m.unreached << " | " << pct(d.mean()) << " | " << (m.mean() <= 0.001 && m.unreached == 0 ? "yes" : "**no**") << " |\n";
    };
    print("closed form", mdf_a, dij_a);
    if (cgal_sources == sources.size()) {
      print("CGAL exact", mdf_c, dij_c);
      notes.push_back(s.name + ": closed form vs CGAL exact, max rel. difference " + num(closed_vs_cgal, 3));
    } else if (!ref_dir.empty()) {
      notes.push_back(s.name + ": CGAL exact reference missing for " + std::to_string(sources.size() - cgal_sources) +
                      " source(s) in " + ref_dir.string());
    }
  }
  if (!notes.empty()) {
    std::cout << "\n";
    for (const std::string& n : notes) std::cout << "- " << n << "\n";
  }
  print_worst(std::move(dev_worst), worst, "MDF");
  return 0;
}

// ---- command line -------------------------------------------------------------------------

void print_usage(std::ostream& os) {
  os << "usage: geodesic_accuracy MESH --ref PREFIX [--sources a,b,...] [--name NAME] [--pairs N] [--seed S]\n"
        "                         [--worst K] [--windows] [--fast]\n"
        "       geodesic_accuracy --synthetic [--ref-dir DIR] [--worst K] [--windows] [--fast]\n"
        "       geodesic_accuracy --write-shapes DIR\n";
}

int run_cli(int argc, char** argv) {
  MeshArgs m;
  bool synthetic = false;
  fs::path ref_dir, shapes_dir;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw UsageError(arg + " needs a value");
      return argv[++i];
    };
    auto integer = [&](long long lo, long long hi) -> long long {
      const std::string v = value();
      long long x = 0;
      size_t used = 0;
      try {
        x = std::stoll(v, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used == 0 || used != v.size() || x < lo || x > hi) throw UsageError(arg + ": bad value '" + v + "'");
      return x;
    };
    if (arg == "--ref") {
      m.prefix = value();
    } else if (arg == "--sources") {
      m.sources = parse_index_list(value());
    } else if (arg == "--name") {
      m.name = value();
    } else if (arg == "--pairs") {
      m.pairs = static_cast<int>(integer(0, 10000000));
    } else if (arg == "--seed") {
      m.seed = static_cast<std::uint64_t>(integer(0, std::numeric_limits<long long>::max()));
    } else if (arg == "--worst") {
      m.worst = static_cast<size_t>(integer(0, 100000));
    } else if (arg == "--windows") {
      g_windows = true;
    } else if (arg == "--fast") {
      g_fast = true;
    } else if (arg == "--synthetic") {
      synthetic = true;
    } else if (arg == "--ref-dir") {
      ref_dir = value();
    } else if (arg == "--write-shapes") {
      shapes_dir = value();
    } else if (arg == "-h" || arg == "--help") {
      print_usage(std::cout);
      return 0;
    } else if (!arg.empty() && arg[0] == '-') {
      throw UsageError("unknown option " + arg);
    } else if (m.mesh.empty()) {
      m.mesh = arg;
    } else {
      throw UsageError("more than one mesh given: " + arg);
    }
  }
  if (!shapes_dir.empty()) return write_shapes(shapes_dir);
  if (synthetic) return run_synthetic(ref_dir, m.worst);
  if (m.mesh.empty()) throw UsageError("no mesh given");
  if (m.prefix.empty()) throw UsageError("--ref PREFIX is required");
  return run_mesh(m);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run_cli(argc, argv);
  } catch (const UsageError& e) {
    std::cerr << "geodesic_accuracy: " << e.what() << "\n";
    print_usage(std::cerr);
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "geodesic_accuracy: error: " << e.what() << "\n";
    return 1;
  }
}
