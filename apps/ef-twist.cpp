/// ef-twist: find and repair twisted (inconsistently oriented) regions of a mesh.
///
///   ef-twist MESH [--points CLOUD [--cut-cost C] [--mend N] [--detector]] [--radius R] [--max-repairs N] [--threads N]
///            -o FIXED [--png FILE.png ...]
///
/// --png writes FILE.png (the repaired mesh) and FILE-before.png (the input). Without --points
/// the twisted regions found are red and their sealed borders purple; with --points the faces the
/// cloud's normals reject are red. Back faces are tinted orange.
///
/// Without --points: detects regions whose orientation disagrees with the side of the surface
/// they approximate (facing layers of a thin structure), cuts each off along its border, flips
/// the smaller side. With --points: labels every face keep or flip by the cloud's normals (a
/// minimum cut: regions flipped whole by their area-weighted vote, cut only where regions that
/// disagree meet; --detector: the detector's regions instead). Then orients the result globally
/// (with --points: then mends small folds and flaps the cloud still rejects, --mend), prints the
/// report and writes FIXED atomically. Exit codes: 0 ok, 1 error, 2 usage error.

#include <cmath>
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
  app.add_option("--max-repairs", max_repairs, "most regions repaired (detector only)")
      ->check(edgefront::apps::integer_range(1, std::numeric_limits<std::size_t>::max()));
  double cut_cost = twist::RepairOptions{}.cuts.cut_cost;
  bool detector = false;
  app.add_option("--cut-cost", cut_cost,
                 "with --points: price of a cut per unit length, in mean edge lengths (0 ... 100; a wrongly oriented disk is"
                 " flipped from a radius of about 2 x this many edges)")
      ->capture_default_str()
      ->check(edgefront::apps::real_range(0.0, 100.0));
  size_t turned = 0;
  app.add_option("--turned", turned,
                 "with --points: straighten, collapse or (at a border) remove turned-over patches of up to this many faces that"
                 " lie over another layer (0 ... 64, default 0 = off)")
      ->check(edgefront::apps::integer_range(0, 64));
  size_t mend = twist::RepairOptions{}.mend_patches;
  app.add_option("--mend", mend,
                 "with --points: mend the geometry of patches of up to this many faces the points still reject (edge swaps,"
                 " unfolding vertex moves, cut out and re-grown from the rim; 0 ... 64, 0 = off)")
      ->capture_default_str()
      ->check(edgefront::apps::integer_range(0, 64));
  app.add_flag("--detector", detector, "with --points: repair the detector's regions instead of labelling every face by the points");
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
    options.cuts.cut_cost = cut_cost;
    options.experimental.drop_turned_patches = turned;
    options.mend_patches = mend;
    options.label_by_reference = !detector;
    options.detect.threads = threads;
    const size_t faces_before = read.mesh.n_faces();
    auto area_of = [](const edgefront::Mesh& mesh) {
      double a = 0;
      for (edgefront::FaceHandle f : mesh.faces()) a += mesh.calc_face_area(f);
      return a;
    };
    const double area_before = area_of(read.mesh);
    const size_t pieces_before = edgefront::compute_stats(read.mesh).components;
    const double consistency_before = reference ? twist::face_orientation_agreement(read.mesh, *reference) : 0.0;
    // With --points: the faces the points' normals reject, in red.
    auto rejected = [&](const edgefront::Mesh& mesh) {
      edgefront::render::FaceHighlight h;
      for (edgefront::FaceHandle f : mesh.faces()) {
        const twist::FaceGeometry g = twist::face_geometry(mesh, f);
        if (g.normal.sqrnorm() > 0 && OpenMesh::dot(g.normal, reference->nearest_normal(g.centre)) < 0) h.faces.push_back(f);
      }
      return h;
    };
    if (png.requested() && reference) {
      edgefront::render::Scene before{.mesh = &read.mesh};
      before.highlights.push_back(rejected(read.mesh));
      std::string before_path = png.path();
      before_path.insert(before_path.size() - 4, "-before");
      edgefront::render::render_png(before, png.options(), before_path);
      std::cerr << "ef-twist: picture " << before_path << " (the input, faces the points reject red)\n";
    } else if (png.requested()) {
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
    const bool labelled = reference && options.label_by_reference;
    for (size_t i = 0; i < r.records.size(); ++i) {
      const twist::RepairRecord& rec = r.records[i];
      if (labelled) {
        std::cout << "  region " << i + 1 << ": " << rec.region_faces << " faces flipped, cut along " << rec.cut_edges << " edges ("
                  << rec.vertices_duplicated << " vertices on the cut)\n";
        continue;
      }
      std::cout << "  repair " << i + 1 << ": region of " << rec.region_faces << " faces, cut " << rec.cut_edges
                << " edges (" << rec.vertices_duplicated << " vertices duplicated), "
                << (rec.removed ? "removed " : "flipped ") << (rec.removed ? rec.faces_visited - rec.other_side_faces : rec.flipped_faces)
                << " faces (" << (rec.flipped_region ? "the region side" : "the other side") << "), fronts visited "
                << rec.faces_visited << " faces\n";
    }
    std::cout << "faces flipped:      " << r.faces_flipped << " by repairs, " << r.faces_flipped_globally << " by the global orientation ("
              << r.components_flipped << " components)\n";
    const double area_after = area_of(read.mesh);
    const double removed_share = (area_before - area_after) / area_before;  // rounding noise of a flip below 1e-9
    std::cout << "faces removed:      " << r.faces_removed << " (" << (std::abs(removed_share) < 1e-9 ? 0.0 : 100.0 * removed_share)
              << "% of the area)\n";
    std::cout << "components:         " << pieces_before << " -> " << edgefront::compute_stats(read.mesh).components << "\n";
    if (labelled) std::cout << "twist lines cut:    " << r.cut_lines << "\n";
    if (r.mend_edges_flipped + r.mend_vertices_moved + r.mend_faces_cut_out > 0) {
      std::cout << "mended:             " << r.mend_edges_flipped << " edges swapped, " << r.mend_vertices_moved
                << " vertices moved, " << r.mend_faces_cut_out << " faces cut out and re-grown as " << r.mend_faces_added
                << " (net area above)\n";
    }
    if (r.seam_pieces_flipped > 0) {
      std::cout << "seams:              " << r.seam_pieces_flipped << " piece(s) (" << r.seam_faces_flipped
                << " faces) flipped to meet their neighbours along reversed seams\n";
    }
    if (r.regions_scattered > 0) {
      std::cout << "left alone:         " << r.regions_scattered
                << " scattered region(s) (border far longer than a disk's of their size: noise or a wall thinner than the"
                   " faces, not a twist; cutting there would shred the surface)\n";
    }
    std::cout << "non-orientable:     " << (r.non_orientable ? "yes (" + std::to_string(r.seam_edges) + " seam edges left cut open)" : std::string("no")) << "\n";
    std::cout << "evidence:           " << r.detect_stats.faces_tested << " faces tested, " << r.detect_stats.distance_queries
              << " bounded distance fronts, " << r.detect_stats.flagged_faces << " faces flagged\n";
    if (reference) {
      std::cout << "consistency:        " << consistency_before << " -> " << twist::face_orientation_agreement(read.mesh, *reference)
                << " of the area agrees with --points\n";
      // What disagrees still, by the reference's verdict (reference_vote, as the repair judges).
      double total = 0, rejected_area = 0, undecided = 0;
      const double edge = edgefront::compute_stats(read.mesh).mean_edge_length;
      for (edgefront::FaceHandle f : read.mesh.faces()) {
        const twist::FaceGeometry g = twist::face_geometry(read.mesh, f);
        const double a = read.mesh.calc_face_area(f);
        total += a;
        if (g.normal.sqrnorm() == 0 || OpenMesh::dot(g.normal, reference->nearest_normal(g.centre)) >= 0) continue;
        const int vote = twist::reference_vote(*reference, options.detect, g.centre, g.normal, edge);
        (vote < 0 ? rejected_area : undecided) += a;
      }
      std::cout << "disagreeing still:  " << rejected_area / total << " rejected (patches too small or too costly to cut), "
                << undecided / total << " undecided (about perpendicular to the points' normals, or on a wall thinner than the faces)\n";
    }
    edgefront::write_mesh(read.mesh, output);
    if (png.requested()) {
      edgefront::render::Scene after{.mesh = &read.mesh};
      if (reference) after.highlights.push_back(rejected(read.mesh));
      png.write(after);
    }
    std::cout << "written:            " << output << "\n";
    std::cout.flush();
    if (!std::cout) throw std::runtime_error("cannot write to standard output");
    return 0;
  }, {"MESH", "--points"});
}
