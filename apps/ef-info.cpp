/// ef-info: read a mesh, print what the reader found and changed, and the mesh statistics.
///
///   ef-info MESH [--drop-nonmanifold | --strict]
///
/// Exit codes: 0 ok, 1 error (one line "ef-info: error: ..." on stderr), 2 usage error.

#include <iostream>
#include <stdexcept>
#include <string>

#include <CLI/CLI.hpp>

#include "app_util.h"
#include "edgefront/mesh_io.h"
#include "edgefront/mesh_stats.h"

int main(int argc, char** argv) {
  CLI::App app{"Print the read report and the statistics of a mesh (OFF, OBJ, PLY, STL).", "ef-info"};
  std::string input;
  bool drop = false;
  bool strict = false;
  app.add_option("MESH", input, "mesh file (.off, .obj, .ply, .stl)")->required();
  CLI::Option* drop_opt =
      app.add_flag("--drop-nonmanifold", drop, "drop faces that would make the mesh non-manifold (default)");
  CLI::Option* strict_opt =
      app.add_flag("--strict", strict, "refuse files with faces that would be non-manifold");
  drop_opt->excludes(strict_opt);
  strict_opt->excludes(drop_opt);

  return edgefront::apps::run_app(app, argc, argv, [&] {
    edgefront::MeshReadOptions options;
    options.drop_nonmanifold_faces = !strict;
    const edgefront::MeshReadResult result = edgefront::read_mesh(input, options);
    const edgefront::MeshReadReport& r = result.report;
    std::cout << "file:                 " << input << "\n";
    std::cout << "read:                 " << r.vertices << " vertices, " << r.faces_in_file
              << " faces in file, " << r.triangles_added << " triangles added\n";
    std::cout << "read changes:         " << r.polygons_triangulated << " polygons triangulated, "
              << r.faces_dropped_nonmanifold << " non-manifold triangles dropped, " << r.faces_dropped_invalid
              << " invalid faces dropped\n";
    for (const std::string& warning : r.warnings) std::cout << "warning: " << warning << "\n";
    std::cout << edgefront::format_stats(edgefront::compute_stats(result.mesh));
    std::cout.flush();
    if (!std::cout) throw std::runtime_error("cannot write to standard output");
    return 0;
  }, {"MESH"});
}
