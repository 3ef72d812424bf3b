/// ef-twist: find and repair twisted (inconsistently oriented) regions of a mesh.
///
///   ef-twist MESH [--points CLOUD] [--radius R] [--max-repairs N] [--threads N] -o FIXED [--png FILE.png ...]
///
/// --png writes FILE.png (the repaired mesh) and FILE-before.png (the input with the twisted
/// regions found in red and their sealed borders in purple); back faces are tinted orange.
///
/// Detects regions whose orientation disagrees with the side of the surface they approximate
/// (facing layers of a thin structure, or disagreement with the oriented points of CLOUD), cuts
/// each off along its border, flips the smaller side, orients the result globally, prints the
/// report and writes FIXED atomically. Exit codes: 0 ok, 1 error, 2 usage error.

#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include <CLI/CLI.hpp>

#include "app_options.h"
#include "app_render.h"
#include "app_util.h"
#include "edgefront/mesh_io.h"
#include "edgefront/mesh_stats.h"
#include "edgefront/point_cloud_io.h"
#include "twist/detect.h"
#include "twist/repair.h"

int main(int argc, char** argv) {
  CLI::App app{"Find twisted surface regions and repair them: cut, flip the smaller side, orient globally.", "ef-twist"};
  std::string input, output, points;
  double radius = 0;
  size_t max_repairs = 16;
  app.add_option("MESH", input, "mesh file (.off, .obj, .ply, .stl)")->required();
  app.add_option("-o,--output", output, "repaired mesh (.off, .obj, .ply, .stl), written atomically")
      ->required()
      ->check(edgefront::apps::output_file({".off", ".obj", ".ply", ".stl"}));
  app.add_option("--points", points, "oriented point cloud whose normals decide the right side (.xyz, .ply, .off, .obj)");
  app.add_option("--radius", radius, "layer search radius (0: twice the mean edge length)")
      ->check(edgefront::apps::non_negative());
  app.add_option("--max-repairs", max_repairs, "most regions repaired")
      ->check(edgefront::apps::integer_range(1, std::numeric_limits<std::size_t>::max()));
  unsigned threads = 0;
  edgefront::apps::add_threads_option(app, threads);
  edgefront::apps::PngOutput png(app);  // FILE.png: the repaired mesh; FILE-before.png: the input, twisted regions red

  return edgefront::apps::run_app(app, argc, argv, [&] {
    edgefront::MeshReadResult read = edgefront::read_mesh(input);
    if (read.report.faces_dropped_nonmanifold > 0) {
      std::cerr << "ef-twist: warning: " << read.report.faces_dropped_nonmanifold
                << " faces were dropped on reading (non-manifold or inconsistently oriented: a non-orientable"
                   " surface cannot be held by a half-edge mesh)\n";
    }
    std::unique_ptr<twist::ReferenceNormals> reference;
    if (!points.empty()) {
      reference = std::make_unique<twist::ReferenceNormals>(edgefront::read_points(points));
    }
    twist::RepairOptions options;
    options.detect.radius = radius;
    options.detect.reference = reference.get();
    options.max_repairs = max_repairs;
    options.detect.threads = threads;
    const size_t faces_before = read.mesh.n_faces();
    if (png.requested()) {
      // The input with what the detector finds: twisted regions in red, their sealed borders as lines.
      edgefront::render::Scene before{.mesh = &read.mesh};
      edgefront::render::FaceHighlight regions;
      for (const twist::TwistRegion& region : twist::detect(read.mesh, options.detect)) {
        regions.faces.insert(regions.faces.end(), region.faces.begin(), region.faces.end());
        for (const auto& loop : region.border) {
          edgefront::render::Polyline line = edgefront::render::polyline_from_halfedges(read.mesh, loop);
          line.color = {150, 0, 150};
          before.lines.push_back(std::move(line));
        }
      }
      before.highlights.push_back(std::move(regions));
      std::string before_path = png.path();
      before_path.insert(before_path.size() - 4, "-before");
      edgefront::render::render_png(before, png.options(), before_path);
      std::cerr << "ef-twist: picture " << before_path << " (the input, twisted regions red)\n";
    }
    const twist::RepairReport r = twist::repair(read.mesh, options);
    std::cout << "input:              " << input << " (" << faces_before << " faces)\n";
    std::cout << "regions found:      " << r.regions_found << (r.capped ? " (more than --max-repairs)" : "") << "\n";
    std::cout << "repairs:            " << r.repairs << "\n";
    for (size_t i = 0; i < r.records.size(); ++i) {
      const twist::RepairRecord& rec = r.records[i];
      std::cout << "  repair " << i + 1 << ": region of " << rec.region_faces << " faces, cut " << rec.cut_edges
                << " edges (" << rec.vertices_duplicated << " vertices duplicated), "
                << (rec.removed ? "removed " : "flipped ") << (rec.removed ? rec.faces_visited - rec.other_side_faces : rec.flipped_faces)
                << " faces (" << (rec.flipped_region ? "the region side" : "the other side") << "), fronts visited "
                << rec.faces_visited << " faces\n";
    }
    std::cout << "faces flipped:      " << r.faces_flipped << " by repairs, " << r.faces_flipped_globally << " by the global orientation ("
              << r.components_flipped << " components)\n";
    std::cout << "faces removed:      " << r.faces_removed << "\n";
    if (r.regions_scattered > 0) {
      std::cout << "left alone:         " << r.regions_scattered
                << " scattered region(s) (border far longer than a disk's of their size: noise or a wall thinner than the"
                   " faces, not a twist; cutting there would shred the surface)\n";
    }
    std::cout << "non-orientable:     " << (r.non_orientable ? "yes (" + std::to_string(r.seam_edges) + " seam edges left cut open)" : std::string("no")) << "\n";
    std::cout << "evidence:           " << r.detect_stats.faces_tested << " faces tested, " << r.detect_stats.distance_queries
              << " bounded distance fronts, " << r.detect_stats.flagged_faces << " faces flagged\n";
    if (reference) std::cout << "consistency:        " << twist::orientation_consistency(read.mesh, *reference) << " of the area agrees with --points\n";
    edgefront::write_mesh(read.mesh, output);
    if (png.requested()) png.write(edgefront::render::Scene{.mesh = &read.mesh});
    std::cout << "written:            " << output << "\n";
    std::cout.flush();
    if (!std::cout) throw std::runtime_error("cannot write to standard output");
    return 0;
  }, {"MESH", "--points"});
}
