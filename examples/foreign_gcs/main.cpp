// foreign-gcs: a growing-cell-structures reconstructor that is not EdgeFront's, with its own mesh
// structure, calling EdgeFront's twist repair and bounded geodesic queries through the array /
// session / edit-record API only. See README.md in this folder.
//
//   foreign-gcs POINTS -o MESH [--vertices N] [--seed S] [--no-twist] [--batch SPLITS]
//               [--probes K] [--verbose]
//
// POINTS: text, one point per line, "x y z" or "x y z nx ny nz" (lines starting with # and blank
// lines are skipped). MESH: .off or .ply (ASCII), written to a temporary file and renamed.
// Exit codes: 0 success, 1 error, 2 usage error.

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <unistd.h>

#include "gcs_loop.h"

namespace {

constexpr const char* kUsage =
    "usage: foreign-gcs POINTS -o MESH [--vertices N] [--seed S] [--no-twist] [--batch SPLITS] [--repair-from N] [--probes K] [--heal] [--heal-gap E] [--heal-holes N] [--grow R] [--min-piece S] [--verbose]\n"
    "  POINTS         text file, one point per line: x y z [nx ny nz]\n"
    "  -o MESH        output mesh, .off or .ply (ASCII)\n"
    "  --vertices N   stop at N live vertices (6 to 10000000, default 2000)\n"
    "  --seed S       random seed (0 to 2^63-1, default 1)\n"
    "  --no-twist     no twist repair (the session still mirrors the mesh for the probes)\n"
    "  --batch SPLITS vertex splits between two repair calls (1 to 100000, default 10; 100 basic steps each)\n"
    "  --repair-from N no incremental repair while the mesh has fewer than N vertices (default 200)\n"
    "  --max-retwists R a place the repair turned more often than R times is cut out (default 2)\n"
    "  --probes K     'far along the surface?' MDF probes per batch (0 to 10000, default 16)\n"
    "  --heal         the session re-joins borders after each repair (zips, small holes; needs normals)\n"
    "  --heal-gap E   with --heal: zip border chains closer than E mean edges (0 to 10, default 1)\n"
    "  --heal-holes N with --heal: close holes of at most N border vertices by a fan (0 to 1000, default 8)\n"
    "  --grow R       the heal (implies --heal) also grows up to R rows of faces beyond the borders per repair, on the points (0 to 8, default 0)\n"
"  --min-piece S  with --heal: the finish removes pieces with fewer than S x the largest piece's faces (0 to 0.5, default 0)\n"
    "  --verbose      one line per batch on stderr\n";

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

std::uint64_t parse_count(const std::string& name, const std::string& text, std::uint64_t lo, std::uint64_t hi) {
  if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos)
    throw UsageError(name + ": '" + text + "' is not a non-negative integer");
  errno = 0;
  char* end = nullptr;
  const unsigned long long v = std::strtoull(text.c_str(), &end, 10);
  if (errno == ERANGE || v < lo || v > hi)
    throw UsageError(name + ": " + text + " is out of range [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  return v;
}

double parse_real(const std::string& name, const std::string& text, double lo, double hi) {
  char* end = nullptr;
  errno = 0;
  const double v = text.empty() ? std::nan("") : std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE || !(v >= lo && v <= hi))
    throw UsageError(name + ": '" + text + "' is not a number in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  return v;
}

foreign::Cloud read_points(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw std::runtime_error(path + ": not a regular file");
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open");
  foreign::Cloud c;
  std::string line;
  size_t line_no = 0;
  int columns = -1;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const size_t first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#') continue;
    std::istringstream s(line);
    double v[7];
    int n = 0;
    std::string token;
    while (s >> token) {
      if (n == 6) throw std::runtime_error(path + ":" + std::to_string(line_no) + ": more than 6 values");
      char* end = nullptr;
      v[n] = std::strtod(token.c_str(), &end);
      if (end == token.c_str() || *end != '\0') throw std::runtime_error(path + ":" + std::to_string(line_no) + ": '" + token + "' is not a number");
      if (!std::isfinite(v[n])) throw std::runtime_error(path + ":" + std::to_string(line_no) + ": '" + token + "' is not a finite number");
      if (std::abs(v[n]) > 1e150) throw std::runtime_error(path + ":" + std::to_string(line_no) + ": '" + token + "' is out of range (|x| > 1e150)");
      ++n;
    }
    if (n != 3 && n != 6) throw std::runtime_error(path + ":" + std::to_string(line_no) + ": expected 3 or 6 values, got " + std::to_string(n));
    if (columns >= 0 && n != columns) throw std::runtime_error(path + ":" + std::to_string(line_no) + ": " + std::to_string(n) + " values where earlier lines have " + std::to_string(columns));
    columns = n;
    c.points.push_back({v[0], v[1], v[2]});
    if (n == 6) {
      const double l = std::sqrt(v[3] * v[3] + v[4] * v[4] + v[5] * v[5]);
      if (!(l > 1e-12)) throw std::runtime_error(path + ":" + std::to_string(line_no) + ": zero normal");
      c.normals.push_back({v[3] / l, v[4] / l, v[5] / l});
    }
  }
  if (in.bad()) throw std::runtime_error(path + ": read error");
  if (c.points.size() < 4) throw std::runtime_error(path + ": fewer than 4 points");
  return c;
}

/// Writes to MESH.tmp-PID and renames it over MESH: a failed write leaves no partial file.
void write_mesh(const std::string& path, const std::vector<foreign::Point>& V, const std::vector<foreign::Tri>& F) {
  const std::string ext = std::filesystem::path(path).extension().string();
  const bool ply = ext == ".ply";
  const std::string tmp = path + ".tmp-" + std::to_string(::getpid());
  {
    std::ofstream out(tmp);
    if (!out) throw std::runtime_error(path + ": cannot write (" + std::strerror(errno) + ")");
    out.precision(17);
    if (ply) {
      out << "ply\nformat ascii 1.0\ncomment foreign-gcs\nelement vertex " << V.size()
          << "\nproperty double x\nproperty double y\nproperty double z\nelement face " << F.size()
          << "\nproperty list uchar int vertex_indices\nend_header\n";
    } else {
      out << "OFF\n" << V.size() << ' ' << F.size() << " 0\n";
    }
    for (const foreign::Point& p : V) out << p[0] << ' ' << p[1] << ' ' << p[2] << '\n';
    for (const foreign::Tri& t : F) out << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
    out.flush();
    if (!out) {
      out.close();
      std::remove(tmp.c_str());
      throw std::runtime_error(path + ": write failed");
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::remove(tmp.c_str());
    throw std::runtime_error(path + ": " + ec.message());
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::string points, output;
  foreign::LoopOptions o;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      auto value = [&]() -> std::string {
        if (i + 1 >= argc) throw UsageError(a + " needs a value");
        return argv[++i];
      };
      if (a == "-h" || a == "--help") {
        std::fputs(kUsage, stdout);
        return 0;
      } else if (a == "-o" || a == "--output") {
        output = value();
      } else if (a == "--vertices") {
        o.target_vertices = parse_count(a, value(), 6, 10000000);
      } else if (a == "--seed") {
        o.seed = parse_count(a, value(), 0, (std::uint64_t{1} << 63) - 1);
      } else if (a == "--no-twist") {
        o.twist = false;
      } else if (a == "--batch") {
        o.batch_splits = parse_count(a, value(), 1, 100000);
      } else if (a == "--repair-from") {
        o.min_repair_vertices = parse_count(a, value(), 0, 10000000);
      } else if (a == "--max-retwists") {
        o.max_retwists = parse_count(a, value(), 0, 1000000);
      } else if (a == "--probes") {
        o.probes_per_batch = parse_count(a, value(), 0, 10000);
      } else if (a == "--heal") {
        o.heal = true;
      } else if (a == "--heal-gap") {
        o.heal_gap_edges = parse_real(a, value(), 0, 10);
      } else if (a == "--heal-holes") {
        o.heal_hole_vertices = parse_count(a, value(), 0, 1000);
      } else if (a == "--grow") {
        o.heal_grow_rows = parse_count(a, value(), 0, 8);
        if (o.heal_grow_rows > 0) o.heal = true;
      } else if (a == "--min-piece") {
        o.heal_min_piece_share = parse_real(a, value(), 0, 0.5);
      } else if (a == "--verbose") {
        o.verbose = true;
      } else if (!a.empty() && a[0] == '-') {
        throw UsageError("unknown option " + a);
      } else if (points.empty()) {
        points = a;
      } else {
        throw UsageError("more than one POINTS file");
      }
    }
    if (points.empty()) throw UsageError("POINTS is required");
    if (output.empty()) throw UsageError("-o MESH is required");
    const std::string ext = std::filesystem::path(output).extension().string();
    if (ext != ".off" && ext != ".ply") throw UsageError("-o: " + output + ": the output must end in .off or .ply");
    const std::filesystem::path dir = std::filesystem::path(output).parent_path();
    std::error_code ec;
    if (!dir.empty() && !std::filesystem::is_directory(dir, ec)) throw UsageError("-o: " + dir.string() + " is not a directory");
  } catch (const UsageError& e) {
    std::fprintf(stderr, "foreign-gcs: error: %s\n%s", e.what(), kUsage);
    return 2;
  }
  try {
    const foreign::Cloud cloud = read_points(points);
    std::vector<foreign::Point> V;
    std::vector<foreign::Tri> F;
    const foreign::LoopStats s = foreign::run_gcs(cloud, o, V, F);
    write_mesh(output, V, F);
    std::fprintf(stderr,
                 "foreign-gcs: %zu vertices, %zu faces; %zu basic steps, %zu batches, %zu vertex splits, %zu edge splits, "
                 "%zu collapses%s; twist repair: %zu calls, records: +%zu vertices, %zu faces flipped, %zu removed, %zu "
                 "corners replaced, +%zu faces (heal: %zu strips, %zu holes, %zu grown); far probes %zu of %zu; %.2f s (session %.2f s)\n",
                 V.size(), F.size(), s.basic_steps, s.batches, s.splits, s.edge_splits, s.collapses,
                 s.step_limit ? " (stopped by the step limit)" : "", s.repair_calls, s.record_vertices_added,
                 s.record_faces_flipped, s.record_faces_removed, s.record_corners_replaced, s.record_faces_added,
                 s.heal_strips, s.heal_holes, s.heal_grown, s.probes_far, s.probes,
                 s.seconds_loop, s.seconds_session);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "foreign-gcs: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
