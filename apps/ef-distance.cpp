/// ef-distance: approximate geodesic distances on a mesh with the Minimal Distance Front (or, as
/// the baseline, Dijkstra over the mesh edges), from vertices, a closed vertex loop or points on
/// faces.
///
///   ef-distance MESH (--source V[,V...] | --loop V,V,V... | --point F:b0,b1,b2 ...)
///               [--side left|right] [--max-distance D] [--method mdf|windows|fast|dijkstra]
///               [-o FILE.txt | -o FILE.ply] [--png FILE.png [--azimuth A] [--elevation E] [--size WxH]]
///   ef-distance MESH (--sources V[,V...] | --sources-file F) [--targets V[,V...] | --targets-file F]
///               [--max-distance D] [--method ...] [--threads N] [-q] [-o FILE.csv | -o FILE.txt]
///
/// Batch mode (--sources, --sources-file: one field per source, edgefront/batch_distance.h), on
/// --threads threads (default: all cores; the numbers are the same for any count). Output, CSV
/// (comma-separated, one header line, numbers as below, "inf" where not reached): without targets
/// a header "vertex,S1,S2,..." (the source indices) and one line per vertex "v,d(S1,v),d(S2,v),...";
/// with targets a header "source,T1,T2,..." and one line per source "S,d(S,T1),d(S,T2),...". A
/// sources or targets file holds vertex indices separated by blanks, commas or line breaks; '#'
/// starts a comment to the end of its line. A progress bar goes to stderr when it is a terminal
/// (not with -q).
///
/// Output: one distance per line in input vertex order, then the copies of pinched vertices the
/// reader appended (each with its original's distance) ("inf" where not reached: another
/// component, behind a loop, beyond --max-distance), written with the fewest digits that read
/// back to the same double, on stdout or into FILE.txt. FILE.ply gets the mesh with a per-vertex
/// scalar "distance", the same as "quality" (what MeshLab reads as per-vertex quality; -1 where not
/// reached) and colors: a colormap over [0, largest finite distance] with dark isoline
/// bands every 1/20 of that range, grey where not reached (for MeshLab and similar viewers). A
/// one-line summary (method, time, reached vertices, peak front, stop reason) goes to stderr.
/// --method windows is the MDF with per-edge windows (DistanceMethod::Windows): near-exact
/// distances from vertices and points at about 3-4x the time of the default. --method fast is
/// the MDF's fast mode (DistanceMethod::Fast): about 2x the time of --method dijkstra, errors a
/// few times those of the default (vertices and points only). --point takes every method;
/// --loop only mdf and dijkstra.
/// --max-distance takes a non-negative number or "inf" (the default).
/// --png renders the field (colormap, isolines at a nice step, grey where not reached) with the
/// sources (points or the loop) into a picture (apps/common/app_render.h).
///
/// Exit codes: 0 ok, 1 error (one line "ef-distance: error: ..." on stderr), 2 usage error.

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include <CLI/CLI.hpp>

#include "app_options.h"
#include "app_output.h"
#include "app_parse.h"
#include "app_render.h"
#include "app_util.h"
#include "edgefront/batch_distance.h"
#include "edgefront/error.h"
#include "edgefront/front_source.h"
#include "edgefront/mesh.h"
#include "edgefront/mesh_io.h"
#include "edgefront/minimal_distance_front.h"
#include "render/color.h"
#include "render/scene.h"

namespace {

using edgefront::render::colormap;
using edgefront::apps::lower_extension;
using edgefront::apps::parse_index;
using edgefront::apps::parse_vertex_list;
using edgefront::apps::split_list;

using edgefront::VertexHandle;

constexpr const char* kAppName = "ef-distance";

/// Parses "F:b0,b1,b2". The library checks the barycentric coordinates themselves.
edgefront::SurfacePoint parse_point(const std::string& text, size_t n_faces) {
  const std::string option = "--point '" + text + "'";
  const size_t colon = text.find(':');
  if (colon == std::string::npos) throw edgefront::InvalidInput(option + ": expected F:b0,b1,b2");
  // Splitting at ':' (absent before the colon) only trims the face token.
  const std::string face_token = split_list(text.substr(0, colon), ':').front();
  edgefront::SurfacePoint p;
  p.face = edgefront::FaceHandle(static_cast<int>(parse_index(face_token, n_faces, option, "face", "faces")));
  const std::vector<std::string> coords = split_list(text.substr(colon + 1), ',');
  if (coords.size() != 3) {
    throw edgefront::InvalidInput(option + ": expected 3 barycentric coordinates after ':', got " +
                                  std::to_string(coords.size()));
  }
  for (size_t i = 0; i < 3; ++i) {
    const std::string& c = coords[i];
    const char* end = c.data() + c.size();
    const auto [ptr, ec] = std::from_chars(c.data(), end, p.bary[i]);
    if (c.empty() || ec != std::errc() || ptr != end) {
      throw edgefront::InvalidInput(option + ": '" + c + "' is not a number");
    }
  }
  return p;
}

/// Colors with isolines: the colormap over [0, max_finite], darkened in a thin band at every
/// 1/20 of the range; grey where the distance is infinite.
std::vector<std::array<uint8_t, 3>> isoline_colors(const std::vector<double>& distance, double max_finite) {
  constexpr int kBands = 20;
  constexpr double kLineWidth = 0.15;  // share of a band drawn dark
  std::vector<std::array<uint8_t, 3>> colors(distance.size(), std::array<uint8_t, 3>{128, 128, 128});
  for (size_t i = 0; i < distance.size(); ++i) {
    if (!std::isfinite(distance[i])) continue;
    const double t = max_finite > 0 ? distance[i] / max_finite : 0.0;
    std::array<uint8_t, 3> c = colormap(t);
    const double band = t * kBands;
    if (max_finite > 0 && band - std::floor(band) < kLineWidth) {
      for (uint8_t& channel : c) channel = static_cast<uint8_t>(channel * 0.3);
    }
    colors[i] = c;
  }
  return colors;
}

/// Shortest text that reads back to the same double; "inf" for +infinity.
void append_number(std::string& text, double x) {
  if (std::isinf(x)) {
    text.append(x > 0 ? "inf" : "-inf");
    return;
  }
  char buf[64];
  const auto [ptr, ec] = std::to_chars(buf, buf + sizeof(buf), x);
  EF_CHECK(ec == std::errc(), "formatting a distance failed");
  text.append(buf, ptr);
}

/// Vertex indices from a file: separated by blanks, commas or line breaks, '#' to the end of a
/// line is a comment. \throws IoError when the file cannot be read, InvalidInput / AppUsageError
/// naming the file, line and token for a bad index, InvalidInput for a file without any index.
std::vector<VertexHandle> read_vertex_file(const std::string& path, size_t n_vertices, const std::string& option) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw edgefront::IoError(option + ": '" + path + "' is not a readable regular file");
  }
  std::ifstream in(path);
  if (!in) throw edgefront::IoError(option + ": cannot open '" + path + "'");
  std::vector<VertexHandle> out;
  std::string line;
  for (size_t number = 1; std::getline(in, line); ++number) {
    line = line.substr(0, line.find('#'));
    for (char& c : line) {
      if (c == ',' || c == '\t' || c == '\r') c = ' ';
    }
    std::istringstream tokens(line);
    std::string token;
    while (tokens >> token) {
      out.push_back(edgefront::apps::parse_vertex(token, n_vertices, option + " '" + path + "' line " + std::to_string(number)));
    }
  }
  if (in.bad()) throw edgefront::IoError(option + ": reading '" + path + "' failed");
  if (out.empty()) throw edgefront::InvalidInput(option + ": '" + path + "' holds no vertex index");
  return out;
}

std::string stop_name(edgefront::DistanceStop stop) {
  switch (stop) {
    case edgefront::DistanceStop::NotStarted: return "not started";
    case edgefront::DistanceStop::Exhausted: return "exhausted";
    case edgefront::DistanceStop::MaxDistance: return "max distance";
    case edgefront::DistanceStop::TargetReached: return "target reached";
  }
  return "unknown";
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Approximate geodesic distances (Minimal Distance Front, or Dijkstra over edges) from vertices, a "
               "closed vertex loop or surface points; one distance per vertex (inf when not reached).",
               kAppName};
  std::string input;
  std::string source_text;
  std::string loop_text;
  std::vector<std::string> point_texts;
  std::string side = "left";
  double max_distance = std::numeric_limits<double>::infinity();
  std::string method = "mdf";
  std::string output;
  app.add_option("MESH", input, "mesh file (.off, .obj, .ply, .stl)")->required();
  CLI::Option* source_opt = app.add_option("--source", source_text, "source vertices: V[,V...] (0-based indices)")
                                ->check(edgefront::apps::index_list());
  CLI::Option* loop_opt =
      app.add_option("--loop", loop_text, "source loop: closed vertex path V,V,V... joined by mesh edges")
          ->check(edgefront::apps::index_list());
  CLI::Option* point_opt = app.add_option(
      "--point", point_texts, "source point F:b0,b1,b2 (face index, barycentric coordinates in the face's vertex "
                              "order); may be repeated")
                              ->check(edgefront::apps::surface_point());
  source_opt->excludes(loop_opt)->excludes(point_opt);
  loop_opt->excludes(source_opt)->excludes(point_opt);
  point_opt->excludes(source_opt)->excludes(loop_opt);
  CLI::Option* side_opt = app.add_option("--side", side, "side of the loop to measure on: left (default) or right")
                              ->check(CLI::IsMember({"left", "right"}));
  app.add_option("--max-distance", max_distance, "stop beyond this distance, >= 0 (default: inf, no limit)")
      ->check(edgefront::apps::real_range(0.0, std::numeric_limits<double>::infinity()));
  app.add_option("--method", method,
                 "mdf (Minimal Distance Front, default), windows (MDF with per-edge windows: near-exact, "
                 "3-4x slower; vertices and points only), fast (one update per neighbour: about 2x a Dijkstra, "
                 "less accurate than mdf; vertices and points only) or dijkstra (over edges)")
      ->check(CLI::IsMember({"mdf", "windows", "fast", "dijkstra"}));
  app.add_option("-o,--output", output, "write the distances to FILE.txt, or a PLY with distance and colors to FILE.ply; "
                                        "batch: the CSV table to FILE.csv or FILE.txt")
      ->check(edgefront::apps::output_file({".txt", ".ply", ".csv"}));
  edgefront::apps::PngOutput png(app);
  std::string sources_text, sources_file, targets_text, targets_file;
  unsigned threads = 0;
  bool quiet = false;
  CLI::Option* sources_opt =
      app.add_option("--sources", sources_text, "batch: one distance field per source vertex, V[,V...] (CSV output)")
          ->check(edgefront::apps::index_list());
  CLI::Option* sources_file_opt =
      app.add_option("--sources-file", sources_file, "batch: the source vertices from a file (indices separated by "
                                                     "blanks, commas or lines; '#' comments)");
  CLI::Option* targets_opt =
      app.add_option("--targets", targets_text, "batch: only the distances to these vertices, V[,V...]: a sources x "
                                                "targets matrix")
          ->check(edgefront::apps::index_list());
  CLI::Option* targets_file_opt =
      app.add_option("--targets-file", targets_file, "batch: the target vertices from a file (as --sources-file)");
  for (CLI::Option* batch_opt : {sources_opt, sources_file_opt}) {
    batch_opt->excludes(source_opt)->excludes(loop_opt)->excludes(point_opt);
  }
  sources_opt->excludes(sources_file_opt);
  targets_opt->excludes(targets_file_opt);
  edgefront::apps::add_threads_option(app, threads);
  app.add_flag("-q,--quiet", quiet, "batch: no progress bar");
  app.footer("Batch output (--sources, --sources-file): CSV with one header line. Without targets: "
             "\"vertex,S1,S2,...\" then one line per vertex \"v,d(S1,v),d(S2,v),...\"; with targets: "
             "\"source,T1,T2,...\" then one line per source \"S,d(S,T1),...\". \"inf\" where not reached; numbers "
             "read back to the same double. The numbers do not depend on --threads.");

  return edgefront::apps::run_app(app, argc, argv, [&] {
    const bool batch = sources_opt->count() > 0 || sources_file_opt->count() > 0;
    if (!batch && (targets_opt->count() > 0 || targets_file_opt->count() > 0)) {
      throw edgefront::apps::AppUsageError("--targets and --targets-file need --sources or --sources-file");
    }
    if (batch) {
      const std::string ext = output.empty() ? std::string() : lower_extension(output);
      if (ext == ".ply") throw edgefront::apps::AppUsageError("batch mode (--sources) writes CSV: use -o FILE.csv or FILE.txt");
      if (png.requested()) throw edgefront::apps::AppUsageError("--png draws one field: not with --sources");
      if (side_opt->count() > 0) throw edgefront::apps::AppUsageError("--side applies only to --loop");
      const edgefront::MeshReadResult read = edgefront::read_mesh(input);
      for (const std::string& w : read.report.warnings) std::cerr << kAppName << ": warning: " << w << "\n";
      const edgefront::Mesh& mesh = read.mesh;
      const size_t n = mesh.n_vertices();
      const std::vector<VertexHandle> sources = sources_file.empty()
                                                    ? parse_vertex_list(sources_text, n, "--sources")
                                                    : read_vertex_file(sources_file, n, "--sources-file");
      std::vector<VertexHandle> targets;
      if (!targets_text.empty()) targets = parse_vertex_list(targets_text, n, "--targets");
      if (!targets_file.empty()) targets = read_vertex_file(targets_file, n, "--targets-file");
      const bool matrix = !targets.empty();
      edgefront::DistanceOptions options;
      options.max_distance = max_distance;
      options.directions = false;
      options.method = edgefront::parse_distance_method(method);
      const bool bar = !quiet && isatty(fileno(stderr));
      edgefront::BatchOptions bo;
      bo.threads = threads;
      if (bar) {
        bo.progress = [](size_t done, size_t total) {
          edgefront::apps::draw_progress_bar("distances", total ? static_cast<double>(done) / static_cast<double>(total) : 1.0,
                                             std::to_string(done) + "/" + std::to_string(total) + " sources");
          return true;
        };
      }
      const auto t0 = std::chrono::steady_clock::now();
      const edgefront::DistanceMatrix m = matrix ? edgefront::geodesic_distances(mesh, sources, targets, options, bo)
                                                 : edgefront::geodesic_distances(mesh, sources, options, bo);
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      if (bar) std::fprintf(stderr, "\n");
      EF_CHECK(m.status == edgefront::BatchStatus::Complete, "the batch did not complete");
      std::string text;
      text.reserve((m.rows + 1) * (m.columns + 1) * 12);
      text.append(matrix ? "source" : "vertex");
      for (const VertexHandle v : matrix ? targets : sources) text.append(",").append(std::to_string(v.idx()));
      text.push_back('\n');
      if (matrix) {
        for (size_t i = 0; i < m.rows; ++i) {
          text.append(std::to_string(sources[i].idx()));
          for (size_t j = 0; j < m.columns; ++j) {
            text.push_back(',');
            append_number(text, m(i, j));
          }
          text.push_back('\n');
        }
      } else {
        for (size_t v = 0; v < m.columns; ++v) {
          text.append(std::to_string(v));
          for (size_t i = 0; i < m.rows; ++i) {
            text.push_back(',');
            append_number(text, m(i, v));
          }
          text.push_back('\n');
        }
      }
      edgefront::apps::write_text(output, text);
      std::ostringstream s;
      s << kAppName << ": " << method << ", " << m.rows << " sources x " << m.columns << (matrix ? " targets" : " vertices")
        << ", " << m.threads << " thread(s), " << std::fixed << std::setprecision(3) << seconds * 1e3 << " ms, peak working memory "
        << m.peak_working_memory_bytes << " bytes (all threads) + result " << m.values.size() * sizeof(double)
        << " bytes + table " << m.table_bytes << " bytes\n";
      std::cerr << s.str();
      return 0;
    }
    if (!output.empty() && lower_extension(output) == ".csv") {
      throw edgefront::apps::AppUsageError("-o FILE.csv is the batch table: use --sources (or -o FILE.txt)");
    }
    if (app.get_option("--threads")->count() > 0) {
      throw edgefront::apps::AppUsageError("--threads applies to the batch mode (--sources, --sources-file)");
    }
    if (source_text.empty() && loop_text.empty() && point_texts.empty()) {
      throw edgefront::apps::AppUsageError("one of --source, --sources, --sources-file, --loop or --point is required");
    }
    if (!loop_text.empty() && (method == "windows" || method == "fast")) {
      throw edgefront::apps::AppUsageError("--method " + method + " takes --source or --point, not --loop");
    }
    if (loop_opt->count() == 0 && side_opt->count() > 0) {
      throw edgefront::apps::AppUsageError("--side applies only to --loop");
    }
    const std::string out_ext = output.empty() ? std::string() : lower_extension(output);

    const edgefront::MeshReadResult read = edgefront::read_mesh(input);
    for (const std::string& w : read.report.warnings) std::cerr << kAppName << ": warning: " << w << "\n";
    const edgefront::Mesh& mesh = read.mesh;
    const size_t n = mesh.n_vertices();

    edgefront::DistanceOptions options;
    options.max_distance = max_distance;
    options.directions = false;
    options.method = edgefront::parse_distance_method(method);
    edgefront::FrontSource source;
    std::vector<edgefront::SurfacePoint> points;
    if (!source_text.empty()) {
      source = edgefront::FrontSource::from_vertices(parse_vertex_list(source_text, n, "--source"));
    } else if (!loop_text.empty()) {
      std::vector<VertexHandle> path = parse_vertex_list(loop_text, n, "--loop");
      // Accept the closing vertex written out again ("1,2,3,1"; "1,2,1" is then a path of 2).
      if (path.size() > 1 && path.front() == path.back()) path.pop_back();
      source = edgefront::loop_from_vertices(
          mesh, path, side == "right" ? edgefront::LoopSide::Right : edgefront::LoopSide::Left);
    } else {
      for (const std::string& text : point_texts) points.push_back(parse_point(text, mesh.n_faces()));
    }

    const auto t0 = std::chrono::steady_clock::now();
    const edgefront::DistanceField field =
        points.empty() ? edgefront::geodesic_distance(mesh, source, options)
                       : edgefront::geodesic_distance(mesh, points, options);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    EF_CHECK(field.distance.size() == n, "the distance field does not have one value per vertex");

    size_t reached = 0;
    double max_finite = 0.0;
    for (const double d : field.distance) {
      if (std::isfinite(d)) {
        ++reached;
        max_finite = std::max(max_finite, d);
      }
    }

    if (out_ext == ".ply") {
      edgefront::MeshWriteOptions wo;
      wo.vertex_colors = isoline_colors(field.distance, max_finite);
      wo.vertex_scalars.emplace_back("distance", field.distance);
      // MeshLab reads a property named "quality" as its per-vertex quality (colorize by quality,
      // isolines by quality, selection by quality); -1 where not reached keeps its ranges finite.
      std::vector<double> quality = field.distance;
      for (double& q : quality) q = std::isfinite(q) ? q : -1.0;
      wo.vertex_scalars.emplace_back("quality", std::move(quality));
      edgefront::write_mesh(mesh, output, wo);
    } else {
      std::string text;
      text.reserve(n * 20);
      for (const double d : field.distance) {
        append_number(text, d);
        text.push_back('\n');
      }
      edgefront::apps::write_text(output, text);
    }

    if (png.requested()) {
      edgefront::render::Scene scene{.mesh = &mesh, .field = edgefront::render::ScalarField{.values = field.distance}};
      if (!loop_text.empty()) {
        scene.lines.push_back(edgefront::render::polyline_from_halfedges(mesh, source.loop));
      } else {
        edgefront::render::PointSet sources{.color = {220, 30, 30}, .radius_px = 4.0};
        for (const VertexHandle v : source.vertices) sources.points.push_back(mesh.point(v));
        for (const edgefront::SurfacePoint& p : points) {
          auto it = mesh.cfv_iter(p.face);
          edgefront::Vec3 at(0, 0, 0);
          for (size_t k = 0; k < 3; ++k, ++it) at += mesh.point(*it) * p.bary[k];
          sources.points.push_back(at);
        }
        scene.points.push_back(std::move(sources));
      }
      png.write(scene);
    }

    std::ostringstream s;
    s << kAppName << ": " << method << ", " << std::fixed << std::setprecision(3) << seconds * 1e3 << " ms, "
      << reached << " of " << n << " vertices reached, largest distance " << std::defaultfloat << std::setprecision(6) << max_finite;
    if (method == "dijkstra" || method == "fast") {
      s << ", no front (per-mesh arrays)";
    } else {
      s << ", peak front " << field.peak_front << " edges";
    }
    s << ", peak working memory " << field.peak_working_memory_bytes << " bytes, stop: " << stop_name(field.stop)
      << "\n";
    std::cerr << s.str();
    return 0;
  }, {"MESH"});
}
