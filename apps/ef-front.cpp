/// ef-front: run a Vertex Front or a Minimal Edge Front over a mesh and write each vertex's level
/// (its breadth-first hop distance from the source).
///
///   ef-front MESH (--source V[,V...] | --loop V,V,V...) [--side left|right] [--levels K]
///            [--method vf|mef] [-o FILE.txt | -o FILE.ply] [--png FILE.png [--azimuth A] [--elevation E] [--size WxH]]
///
/// Output: one line per vertex in input order (then the copies of pinched vertices the reader
/// appended) with the level at which it joined the front (-1
/// when not reached), on stdout or into FILE.txt; FILE.ply gets the mesh with a per-vertex scalar
/// "level" and colors (a colormap over the levels, alternate levels slightly darker, grey for
/// unreached vertices). --png renders the levels as colors (isolines at a nice level step, grey
/// where not reached) with the front where the run stopped: the MEF's loops as red lines (inert
/// loops resting on a border in orange), the VF's front vertices as points. A summary (levels, reached vertices, loops, events, peak front, peak
/// working memory, time) goes to stderr.
///
/// Exit codes: 0 ok, 1 error (one line "ef-front: error: ..." on stderr), 2 usage error.

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "app_options.h"
#include "app_output.h"
#include "app_render.h"
#include "app_util.h"
#include "app_parse.h"
#include "edgefront/error.h"
#include "edgefront/front_source.h"
#include "edgefront/mesh.h"
#include "edgefront/mesh_io.h"
#include "edgefront/minimal_edge_front.h"
#include "edgefront/vertex_front.h"
#include "render/color.h"
#include "render/scene.h"

namespace {

using edgefront::render::colormap;
using edgefront::apps::lower_extension;
using edgefront::apps::parse_vertex_list;

using edgefront::VertexHandle;

constexpr const char* kAppName = "ef-front";

/// Counts of the Minimal Edge Front's events.
struct EventCounts {
  size_t collisions = 0, splits = 0, merges = 0, annihilations = 0, border_reached = 0, pinches = 0;
};

/// What a front run left behind, for the summary.
struct RunSummary {
  int levels = 0;
  size_t peak_front = 0;
  size_t peak_bytes = 0;
  std::optional<size_t> loops_left;  // MEF only
  size_t inert_loops = 0;
  std::optional<EventCounts> events;  // MEF only
  std::string front_unit;
};

std::string plural(size_t n, const std::string& word) { return std::to_string(n) + " " + word + (n == 1 ? "" : "s"); }

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Run a Vertex Front or Minimal Edge Front from vertices or a closed vertex loop and write every "
               "vertex's level (hop distance; -1 when not reached).",
               kAppName};
  std::string input;
  std::string source_text;
  std::string loop_text;
  std::string side = "left";
  int levels = -1;
  std::string method = "mef";
  std::string output;
  app.add_option("MESH", input, "mesh file (.off, .obj, .ply, .stl)")->required();
  CLI::Option* source_opt = app.add_option("--source", source_text, "source vertices: V[,V...] (0-based indices)")
                                ->check(edgefront::apps::index_list());
  CLI::Option* loop_opt =
      app.add_option("--loop", loop_text, "source loop: closed vertex path V,V,V... joined by mesh edges")
          ->check(edgefront::apps::index_list());
  source_opt->excludes(loop_opt);
  loop_opt->excludes(source_opt);
  app.add_option("--side", side, "side of the loop the front expands to: left (default) or right")
      ->check(CLI::IsMember({"left", "right"}));
  app.add_option("--levels", levels, "number of levels to run, >= 0 (default: to exhaustion)")
      ->check(edgefront::apps::integer_range(0, std::numeric_limits<int>::max()));
  app.add_option("--method", method, "vf (Vertex Front) or mef (Minimal Edge Front, default)")
      ->check(CLI::IsMember({"vf", "mef"}));
  app.add_option("-o,--output", output, "write the levels to FILE.txt, or a PLY with level and colors to FILE.ply")
      ->check(edgefront::apps::output_file({".txt", ".ply"}));
  edgefront::apps::PngOutput png(app);

  return edgefront::apps::run_app(app, argc, argv, [&] {
    if (source_text.empty() && loop_text.empty()) {
      throw edgefront::apps::AppUsageError("one of --source or --loop is required");
    }
    const std::string out_ext = output.empty() ? std::string() : lower_extension(output);
    if (loop_opt->count() == 0 && app.get_option("--side")->count() > 0) {
      throw edgefront::apps::AppUsageError("--side applies only to --loop");
    }

    const edgefront::MeshReadResult read = edgefront::read_mesh(input);
    for (const std::string& w : read.report.warnings) std::cerr << kAppName << ": warning: " << w << "\n";
    const edgefront::Mesh& mesh = read.mesh;
    const size_t n = mesh.n_vertices();

    edgefront::FrontSource source;
    if (!source_text.empty()) {
      source = edgefront::FrontSource::from_vertices(parse_vertex_list(source_text, n, "--source"));
    } else {
      std::vector<VertexHandle> path = parse_vertex_list(loop_text, n, "--loop");
      // Accept the closing vertex written out again ("1,2,3,1").
      if (path.size() > 3 && path.front() == path.back()) path.pop_back();
      source = edgefront::loop_from_vertices(
          mesh, path, side == "right" ? edgefront::LoopSide::Right : edgefront::LoopSide::Left);
    }
    edgefront::validate_source(mesh, source);

    std::vector<int> level(n, -1);
    const auto record = [&level](VertexHandle v, int l) {
      int& slot = level[static_cast<size_t>(v.idx())];
      if (slot < 0) slot = l;
    };
    RunSummary summary;
    std::vector<edgefront::render::Polyline> front_lines;  // for --png
    edgefront::render::PointSet front_points{.color = {220, 30, 30}, .radius_px = 2.5};
    const auto t0 = std::chrono::steady_clock::now();
    if (method == "vf") {
      edgefront::VertexFront front(mesh);
      front.set_enclosed_callback(record);
      front.reset(source);
      front.run(levels);
      for (const auto& [v, l] : front.front_vertices()) {
        record(v, l);
        front_points.points.push_back(mesh.point(v));
      }
      summary.levels = front.level();
      summary.peak_front = front.peak_front_size();
      summary.peak_bytes = front.peak_working_memory_bytes();
      summary.front_unit = "vertices";
    } else {
      edgefront::MinimalEdgeFront front(mesh, edgefront::MinimalEdgeFrontOptions{.track_loops = true});
      EventCounts events;
      front.set_enclosed_callback(record);
      front.set_event_callback([&events](const edgefront::FrontEvent& e) {
        using Kind = edgefront::FrontEvent::Kind;
        switch (e.kind) {
          case Kind::Collision: ++events.collisions; break;
          case Kind::Split: ++events.splits; break;
          case Kind::Merge: ++events.merges; break;
          case Kind::Annihilation: ++events.annihilations; break;
          case Kind::BorderReached: ++events.border_reached; break;
          case Kind::Pinch: ++events.pinches; break;
        }
      });
      front.reset(source);
      front.run(levels);
      for (const auto& [v, l] : front.front_vertices()) record(v, l);
      const std::vector<edgefront::FrontLoop> loops = front.loops();
      for (const edgefront::FrontLoop& loop : loops) {
        front_lines.push_back(edgefront::render::polyline_from_halfedges(
            mesh, loop.halfedges, loop.inert ? edgefront::render::Rgb{255, 150, 0} : edgefront::render::Rgb{220, 30, 30}));
      }
      summary.levels = front.level();
      summary.peak_front = front.peak_front_size();
      summary.peak_bytes = front.peak_working_memory_bytes();
      summary.loops_left = loops.size();
      summary.inert_loops =
          static_cast<size_t>(std::count_if(loops.begin(), loops.end(), [](const auto& l) { return l.inert; }));
      summary.events = events;
      summary.front_unit = "edges";
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

    // Output.
    if (out_ext == ".ply") {
      const int max_level = level.empty() ? 0 : *std::max_element(level.begin(), level.end());
      edgefront::MeshWriteOptions wo;
      std::vector<double> values(n);
      wo.vertex_colors.resize(n);
      for (size_t i = 0; i < n; ++i) {
        values[i] = level[i];
        if (level[i] < 0) {
          wo.vertex_colors[i] = {128, 128, 128};
          continue;
        }
        std::array<uint8_t, 3> c = colormap(max_level > 0 ? static_cast<double>(level[i]) / max_level : 0.0);
        if (level[i] % 2 == 1) {
          for (uint8_t& channel : c) channel = static_cast<uint8_t>(channel * 0.8);
        }
        wo.vertex_colors[i] = c;
      }
      wo.vertex_scalars.emplace_back("level", std::move(values));
      edgefront::write_mesh(mesh, output, wo);
    } else {
      std::string text;
      text.reserve(n * 4);
      for (const int l : level) text.append(std::to_string(l)).push_back('\n');
      edgefront::apps::write_text(output, text);
    }

    if (png.requested()) {
      std::vector<double> values(n);
      for (size_t i = 0; i < n; ++i) values[i] = level[i] >= 0 ? level[i] : std::numeric_limits<double>::infinity();
      edgefront::render::Scene scene{.mesh = &mesh, .field = edgefront::render::ScalarField{.values = std::move(values)}};
      scene.lines = std::move(front_lines);
      scene.points.push_back(std::move(front_points));
      png.write(scene);
    }

    // Summary.
    const size_t reached = static_cast<size_t>(std::count_if(level.begin(), level.end(), [](int l) { return l >= 0; }));
    std::ostringstream s;
    s << kAppName << ": " << method << ", " << plural(static_cast<size_t>(summary.levels), "level") << " run, "
      << reached << " of " << n << " vertices reached";
    if (summary.loops_left) {
      s << ", " << plural(*summary.loops_left, "loop") << " left (" << summary.inert_loops << " inert)";
    }
    s << "\n";
    if (summary.events) {
      const EventCounts& e = *summary.events;
      s << kAppName << ": events: " << plural(e.collisions, "collision") << ", " << plural(e.splits, "split") << ", "
        << plural(e.merges, "merge") << ", " << plural(e.annihilations, "annihilation") << ", " << e.border_reached
        << " border reached";
      if (e.pinches > 0) s << ", " << e.pinches << (e.pinches == 1 ? " pinch" : " pinches");
      s << "\n";
    }
    s << kAppName << ": peak front " << summary.peak_front << " " << summary.front_unit << ", peak working memory "
      << summary.peak_bytes << " bytes, time " << std::fixed << std::setprecision(3) << seconds * 1e3 << " ms\n";
    std::cerr << s.str();
    return 0;
  }, {"MESH"});
}
