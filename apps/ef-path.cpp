/// ef-path: the connection path between two vertices (paper §2.4): an edge-wise shortest path
/// with the Vertex Front or the Minimal Edge Front, or a geodesic vertex path with the Minimal
/// Distance Front, optionally straightened into a geodesic polyline across faces.
///
///   ef-path MESH FROM TO [--method vf|mef|mdf] [--polyline] [--directed] [-o FILE.obj|FILE.ply]
///           [--png FILE.png [--azimuth A] [--elevation E] [--size WxH]]
///
/// Prints "edges E", "length L" (the geometric length: the MDF's geodesic estimate, or the
/// polyline's length with --polyline, or the chain's edge length), "edge-length L" and
/// "vertices v0 v1 ..." (a path through a pinched vertex lists it and its copy one after the
/// other: not an edge) on stdout, or "no path" (exit 3) when the vertices lie in different
/// components. -o writes the path (the polyline with --polyline, else the vertex chain) as an OBJ
/// polyline (`v` and `l` records) or a PLY with `vertex` and `edge` elements; when there is no
/// path, a file left at -o by an earlier run is removed (it would look like this run's answer),
/// and --png still draws the mesh and the two vertices. A one-line summary (method, time,
/// processed elements) goes to stderr.
///
/// Exit codes: 0 a path was found, 1 error (one line "ef-path: error: ..." on stderr), 2 usage
/// error, 3 no path (the vertices lie in different components).

#include <charconv>
#include <chrono>
#include <filesystem>
#include <limits>
#include <iomanip>
#include <iostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "app_options.h"
#include "app_output.h"
#include "app_parse.h"
#include "app_render.h"
#include "app_util.h"
#include "edgefront/connection_path.h"
#include "edgefront/error.h"
#include "edgefront/mesh.h"
#include "edgefront/mesh_io.h"

namespace {

constexpr const char* kAppName = "ef-path";
constexpr int kExitNoPath = 3;

std::string number(double x) {
  char buf[64];
  const auto [ptr, ec] = std::to_chars(buf, buf + sizeof(buf), x);
  EF_CHECK(ec == std::errc(), "formatting a length failed");
  return std::string(buf, ptr);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Connection path between two vertices: edge-wise shortest (vf, mef) or geodesic (mdf), optionally "
               "as a polyline across faces. Exit codes: 0 path found, 1 error, 2 usage error, 3 no path (the "
               "vertices lie in different components; an old -o FILE is removed).",
               kAppName};
  std::string input, from_text, to_text, method = "mdf", output;
  bool polyline = false, directed = false;
  app.add_option("MESH", input, "mesh file (.off, .obj, .ply, .stl)")->required();
  const unsigned long long max_index = std::numeric_limits<int>::max();
  app.add_option("FROM", from_text, "first vertex (0-based index)")
      ->required()
      ->check(edgefront::apps::integer_range(0, max_index));
  app.add_option("TO", to_text, "second vertex (0-based index)")
      ->required()
      ->check(edgefront::apps::integer_range(0, max_index));
  app.add_option("--method", method, "vf, mef (edge-wise shortest) or mdf (geodesic, default)")
      ->check(CLI::IsMember({"vf", "mef", "mdf"}));
  app.add_flag("--polyline", polyline, "straighten the path into a geodesic polyline across faces");
  app.add_flag("--directed", directed, "directed search (bidirectional A* over the mesh edges)");
  app.add_option("-o,--output", output, "write the path as FILE.obj (v/l records) or FILE.ply (vertex/edge)")
      ->check(edgefront::apps::output_file({".obj", ".ply"}));
  edgefront::apps::PngOutput png(app);
  return edgefront::apps::run_app(app, argc, argv, [&] {
    const edgefront::MeshReadResult read = edgefront::read_mesh(input);
    for (const std::string& w : read.report.warnings) std::cerr << kAppName << ": warning: " << w << "\n";
    const edgefront::Mesh& mesh = read.mesh;
    const edgefront::VertexHandle from = edgefront::apps::parse_vertex(from_text, mesh.n_vertices(), "FROM");
    const edgefront::VertexHandle to = edgefront::apps::parse_vertex(to_text, mesh.n_vertices(), "TO");
    edgefront::ConnectionPathOptions options;
    options.method = method == "vf"    ? edgefront::PathMethod::VertexFront
                     : method == "mef" ? edgefront::PathMethod::MinimalEdgeFront
                                       : edgefront::PathMethod::MinimalDistance;
    options.polyline = polyline;
    options.directed = directed;
    const auto t0 = std::chrono::steady_clock::now();
    const edgefront::ConnectionPath path = edgefront::connection_path(mesh, from, to, options);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::cerr << kAppName << ": " << method << (directed ? " directed" : "") << ", " << std::fixed
              << std::setprecision(3) << seconds * 1e3 << " ms, " << path.processed << " elements processed in " << path.searches << " searches\n";
    // The picture: the mesh with the path (red) and its two ends (dark dots).
    auto picture = [&](const std::vector<edgefront::Vec3>& points) {
      if (!png.requested()) return;
      edgefront::render::Scene scene{.mesh = &mesh};
      if (points.size() >= 2) scene.lines.push_back(edgefront::render::Polyline{.points = points, .width_px = 3.0});
      scene.points.push_back(edgefront::render::PointSet{.points = {mesh.point(from), mesh.point(to)}, .radius_px = 4.0});
      png.write(scene);
    };
    if (path.status == edgefront::PathStatus::NoPath) {
      std::cout << "no path\n" << std::flush;
      std::error_code ec;
      if (!output.empty() && std::filesystem::remove(output, ec)) {
        std::cerr << kAppName << ": no path: removed the old " << output << "\n";
      }
      picture({});
      return kExitNoPath;
    }
    std::string text = "edges " + std::to_string(path.edges) + "\nlength " + number(path.length) +
                       "\nedge-length " + number(path.edge_length) + "\nvertices";
    for (edgefront::VertexHandle v : path.vertices) text += " " + std::to_string(v.idx());
    text += "\n";
    if (polyline) text += "polyline-points " + std::to_string(path.polyline.size()) + "\n";
    std::cout << text << std::flush;
    if (!std::cout) throw edgefront::IoError("writing to stdout failed");
    std::vector<edgefront::Vec3> points;
    if (polyline) {
      for (const edgefront::PathPoint& p : path.polyline) points.push_back(p.position);
    } else {
      for (edgefront::VertexHandle v : path.vertices) points.push_back(mesh.point(v));
    }
    if (!output.empty()) edgefront::write_polyline(points, output);
    picture(points);
    return 0;
  }, {"MESH"});
}
