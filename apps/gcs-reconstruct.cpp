/// gcs-reconstruct: reconstruct a triangle mesh from a point cloud with growing cell structures.
///
///   gcs-reconstruct POINTS -o MESH [--vertices N] [--seed S] [--preset NAME] [--no-twist] [--no-borders] [--no-orient-winners] [--quadric-normals]
///                   [--rejoin-borders] [--grow-borders R] [--skip-unfaced-samples] [--keep-noise] [--no-fit] [--fit-rounds R]
///                   [--fit-smoothness W]
///                   [--no-delaunay-flips] [--keep-crossings] [--keep-false-borders]
///                   [--quiet] [--threads N]
///                   [--png FILE.png [--azimuth A] [--elevation E] [--size WxH]]
///                   [--snapshots DIR [--snapshot-every K]]
///
/// --png renders the result (back faces tinted orange: a twisted region shows at a glance; border
/// loops in blue). --snapshots writes DIR/gcs-NNNNN.png (same camera options) every K
/// vertices of growth, so the growth, a twist and its repair can be watched.
///
/// Without --vertices the target is min(5000, the cloud's distinct points), stated in the summary.
/// Invalid normals in the file (zero-length, NaN, infinite) are dropped with a warning on stderr and
/// fitted from the neighbours; a file whose normals are all invalid is read as one without normals.
///
/// Prints a one-line summary on stdout; a progress bar on stderr, naming the phase (noise
/// estimate, normal fitting, growth, post-processing), when stderr is a terminal and --quiet is
/// not given. Exit codes: 0 ok, 1 error (one line "gcs-reconstruct: error: ..." on
/// stderr), 2 usage error.

#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

#include <CLI/CLI.hpp>

#include "app_options.h"
#include "app_render.h"
#include "app_util.h"
#include "edgefront/error.h"
#include "edgefront/mesh_io.h"
#include "edgefront/mesh_stats.h"
#include "edgefront/point_cloud_io.h"
#include "gcs/reconstructor.h"
#include "gcs/twist_operation.h"

int main(int argc, char** argv) {
  CLI::App app{"Reconstruct a triangle mesh from a point cloud (.xyz, .ply, .off, .obj) with growing cell structures.",
               "gcs-reconstruct"};
  std::string input, output;
  const gcs::ReconstructOptions defaults;
  std::size_t vertices = defaults.target_vertices;
  std::uint64_t seed = defaults.seed;
  std::string preset = "scan";
  unsigned threads = defaults.threads;
  int fit_rounds = defaults.post.fit_rounds;
  double fit_smoothness = defaults.post.fit_smoothness;
  bool quadric_normals = false, skip_unfaced = false;
  bool no_twist = false;
  bool quiet = false;
  bool no_borders = false;
  app.add_option("POINTS", input, "input point cloud (.xyz, .txt, .pts, .ply, .off, .obj)")->required();
  app.add_option("-o,--output", output, "output mesh (.ply, .off, .obj, .stl)")
      ->required()
      ->check(edgefront::apps::output_file({".ply", ".off", ".obj", ".stl"}));
  CLI::Option* vertices_option = app.add_option(
      "--vertices", vertices, "target vertex count (default: 5000, or the number of distinct points when the cloud has fewer)")
      ->check(edgefront::apps::integer_range(4, 50000000));
  edgefront::apps::add_seed_option(app, "--seed", seed, "random seed; the same seed gives the same mesh");
  std::string preset_names;
  for (const std::string& n : gcs::ReconstructOptions::preset_names()) preset_names += (preset_names.empty() ? "" : ", ") + n;
  app.add_option("--preset", preset,
                 "options preset (" + preset_names +
                     "; default scan): thin_shell for thin closed shells (walls about a mesh edge apart), "
                     "open_sheet for open surfaces without normals; the flags below apply on top of it")
      ->check(CLI::IsMember(gcs::ReconstructOptions::preset_names()));
  app.add_flag("--no-twist", no_twist, "disable the twist repair operation (on by default; off with --no-borders)");
  app.add_flag("--no-borders", no_borders,
               "keep the surface closed: no border creation and no loop merging (for closed objects; thin closed "
               "shells such as the bundled vault are torn apart by the border creation otherwise)");
  bool rejoin = false;
  app.add_flag("--rejoin-borders", rejoin,
               "after a twist repair, zip border chains that run close and orientation-compatible back together "
               "(fewer pieces on thin shells; off by default: on the thinnest shells it lowers the consistently "
               "oriented share a little)");
  std::size_t grow_rows = 0;
  app.add_option("--grow-borders", grow_rows,
                 "with the twist repair and input normals: grow up to R rows of faces beyond the borders after every "
                 "batch where the points continue the surface on the border face's side (the twist session heal's "
                 "growth: each side of a cut grows on along its own wall); 0 ... 8, default 0")
      ->check(CLI::Range(0, 8));
  bool no_orient = false;
  app.add_flag("--no-orient-winners", no_orient,
               "do not use the points' normals (or oriented fitted normals) to pick winners facing the sample's "
               "side and to remove faces facing against it (on by default; it keeps open and planar clouds from "
               "ending as a torn double layer)");
  app.add_flag("--quadric-normals", quadric_normals,
               "a cloud without normals: fit them by a quadric at each point (defined wherever the surface has "
               "a normal at the sampling scale) instead of a plane through 20 neighbours that must be flat (off by "
               "default: on CGAL's models the loop's border tests then open more holes; on in the thin_shell and "
               "open_sheet presets)");
  app.add_flag("--skip-unfaced-samples", skip_unfaced,
               "thin closed shells with input normals: a sample that no vertex nearby faces is skipped instead of "
               "pulling the other wall's vertex (better coverage and Chamfer on vault shells, but not closed, and "
               "sometimes more self-intersections; off by default, on in the thin_shell preset)");
  bool ignore_normals = false;
  app.add_flag("--ignore-normals", ignore_normals,
               "reconstruct from the points alone, as if the file had no normals (they are not read; normals are "
               "fitted to the points and oriented instead; for files whose normals are unreliable)");
  bool keep_noise = false;
  app.add_flag("--keep-noise", keep_noise,
               "do not smooth a noisy cloud before the loop (by default a cloud whose estimated noise exceeds 5% of "
               "its point spacing is smoothed first, so that the mesh does not carry the noise)");
  bool no_fit = false;
  app.add_flag("--no-fit", no_fit,
               "do not fit the result to the samples (on by default: each vertex is moved along its normal so "
               "that the samples lie on the mesh's triangles, without turning faces or adding self-intersections)");
  CLI::Option* fit_rounds_option = app.add_option("--fit-rounds", fit_rounds, "rounds of the surface fit, 1-20 (default 3)")
      ->check(edgefront::apps::integer_range(1, 20));
  CLI::Option* fit_smoothness_option = app.add_option("--fit-smoothness", fit_smoothness,
                 "smoothness weight of the surface fit, >= 0 (default 0.1; larger fits less)")
      ->check(edgefront::apps::real_range(0.0, 1e9));
  bool no_flips = false;
  app.add_flag("--no-delaunay-flips", no_flips,
               "do not flip edges of the result toward a Delaunay triangulation (on by default: only between nearly "
               "coplanar faces, vertex positions unchanged)");
  bool keep_crossings = false;
  app.add_flag("--keep-crossings", keep_crossings,
               "do not resolve self-intersecting face pairs of the result (by default the crossing faces' vertices "
               "are smoothed, and faces still crossing are cut out and their small holes filled; thin shells)");
  bool keep_false_borders = false;
  app.add_flag("--keep-false-borders", keep_false_borders,
               "do not close false borders of the result (by default a border loop beyond which the cloud goes on, "
               "e.g. a leg of a closed figure torn open, is closed by a patch pulled onto the samples, when it lies on "
               "them and crosses nothing; off in the open_sheet preset)");
  app.add_flag("-q,--quiet", quiet, "no progress bar");
  edgefront::apps::add_threads_option(app, threads);
  edgefront::apps::PngOutput png(app);
  std::string snapshots;
  std::size_t snapshot_every = 0;
  app.add_option("--snapshots", snapshots, "write a picture of the growing mesh to DIR/gcs-NNNNN.png every "
                                           "--snapshot-every vertices of growth (DIR must exist)")
      ->check(edgefront::apps::existing_directory());
  app.add_option("--snapshot-every", snapshot_every, "vertices of growth between snapshots (default: target / 20)")
      ->check(edgefront::apps::integer_range(1, 100000000));

  return edgefront::apps::run_app(app, argc, argv, [&] {
    edgefront::PointReadOptions read_options;
    read_options.tolerate_invalid_normals = true;
    read_options.ignore_normals = ignore_normals;
    edgefront::PointReadReport read_report;
    edgefront::PointCloud cloud = edgefront::read_points(input, read_options, &read_report);
    if (!read_report.warning.empty()) std::cerr << "gcs-reconstruct: warning: " << input << ": " << read_report.warning << "\n";
    // Without --vertices: 5000, or what the cloud can hold (its distinct points) when that is less.
    const bool default_target = vertices_option->count() == 0;
    std::size_t distinct_points = 0;
    if (default_target) {
      distinct_points = gcs::max_target_vertices(cloud);
      if (distinct_points < 4) {
        throw edgefront::InvalidInput("the cloud has only " + std::to_string(distinct_points) +
                                      " distinct points: at least 4 points are needed");
      }
      vertices = std::min(vertices, distinct_points);
    }
    // The preset, then the flags on top of it (a flag only ever switches away from the default).
    gcs::ReconstructOptions options = gcs::ReconstructOptions::preset(preset);
    options.target_vertices = vertices;
    options.seed = seed;
    options.threads = threads;
    options.progress_interval = 50;
    if (no_borders) options.topology.create_borders = options.topology.merge_borders = false;
    if (no_orient) options.input.orient_winners = false;
    if (quadric_normals) options.input.quadric_normals = true;
    if (skip_unfaced) options.experimental.skip_unfaced_samples = true;
    if (keep_noise) options.input.smooth_noise_ratio = std::numeric_limits<double>::infinity();
    if (no_fit) options.post.fit_surface = false;
    if (fit_rounds_option->count() > 0) options.post.fit_rounds = fit_rounds;
    if (fit_smoothness_option->count() > 0) options.post.fit_smoothness = fit_smoothness;
    if (no_flips) options.post.delaunay_flips = false;
    if (keep_crossings) options.post.resolve_self_intersections = false;
    if (keep_false_borders) options.post.close_false_borders = false;
    const bool bar = !quiet && isatty(fileno(stderr));
    if (!snapshots.empty() && !std::filesystem::is_directory(snapshots)) {
      throw edgefront::IoError("--snapshots: '" + snapshots + "' is not a directory");
    }
    gcs::Reconstructor* running = nullptr;
    const edgefront::render::RenderOptions picture = png.options();
    int n_snapshots = 0;
    std::size_t next_snapshot = 0;
    const std::size_t every = snapshot_every ? snapshot_every : std::max<std::size_t>(vertices / 20, 1);
    auto snapshot = [&](const gcs::Progress& p) {
      if (snapshots.empty() || !running || p.vertices < next_snapshot) return;
      next_snapshot = p.vertices + every;
      char name[32];
      std::snprintf(name, sizeof name, "gcs-%05d.png", n_snapshots++);
      edgefront::render::render_png(edgefront::render::Scene{.mesh = &running->mesh()}, picture,
                                    (std::filesystem::path(snapshots) / name).string());
    };
    gcs::ProgressCallback progress = [&, bar](const gcs::Progress& p) {
      if (p.phase == gcs::Phase::growth) snapshot(p);
      if (bar) {
        char detail[96];
        if (p.phase == gcs::Phase::growth) {
          std::snprintf(detail, sizeof detail, "%zu/%zu vertices, %.1f s", p.vertices, p.target_vertices, p.seconds);
        } else {
          std::snprintf(detail, sizeof detail, "%.1f s", p.seconds);
        }
        edgefront::apps::draw_progress_bar(gcs::to_string(p.phase), p.phase_fraction, detail);
      }
      return true;
    };
    if (!snapshots.empty()) options.progress_interval = std::min<std::size_t>(options.progress_interval, every);
    gcs::Reconstructor reconstructor(cloud, options, progress);
    running = &reconstructor;
    std::shared_ptr<gcs::TwistOperation> twist_op;
    // The repair cuts twisted regions off and relies on the loop's border merging to heal the
    // cuts: without borders (--no-borders) the cuts would stay open, so it is off then too.
    if (!no_twist && !no_borders) {
      gcs::TwistOperationOptions twist_options;
      twist_options.rejoin_borders = rejoin;
      twist_options.grow_rows = grow_rows;
      twist_op = std::make_shared<gcs::TwistOperation>(twist_options);
      reconstructor.add_operation(twist_op);
    }
    const gcs::ReconstructResult r = reconstructor.run(progress);
    if (bar) std::fprintf(stderr, "\n");
    edgefront::write_mesh(r.mesh, output);
    if (png.requested()) png.write(edgefront::render::Scene{.mesh = &r.mesh});
    const edgefront::MeshStats s = edgefront::compute_stats(r.mesh);
    std::cout << "gcs-reconstruct: ";
    if (default_target) {
      std::cout << "target " << vertices << " vertices ("
                << (vertices < 5000 ? "the default 5000 is more than the cloud's " + std::to_string(distinct_points) +
                                          " distinct points"
                                    : std::string("default"))
                << "): ";
    }
    std::cout << s.vertices << " vertices, " << s.faces << " faces, " << s.components
              << " component(s), " << s.border_loops << " border loop(s), " << gcs::to_string(r.stop_reason) << ", "
              << r.seconds_total << " s -> " << output;
    if (r.crossing_pairs_found > 0)
      std::cout << "; " << r.crossing_pairs_found << " self-intersecting face pair(s) resolved ("
                << r.crossing_vertices_moved << " vertices smoothed, " << r.crossing_faces_removed << " faces cut out, "
                << r.crossing_holes_filled << " hole(s) filled), " << r.crossing_pairs_left << " left";
    if (r.false_borders_found > 0)
      std::cout << "; " << r.false_borders_closed << " of " << r.false_borders_found << " false border(s) closed";
    if (r.normals_filled > 0)
      std::cout << "; " << r.normals_filled << " missing normal(s) fitted from the neighbours";
    if (r.normals_unusable) std::cout << "; no usable normal: normals fitted to the points";
    if (r.cloud_smoothed) std::cout << "; cloud smoothed first (noise " << r.noise_ratio << " of the point spacing)";
    if (twist_op) {  // on the same summary line
      const gcs::TwistOperationStats& t = twist_op->stats();
      std::cout << "; twist-repair: " << t.regions_found << " twisted region(s) found, " << t.repairs << " repaired ("
                << t.faces_flipped << " faces flipped, " << t.regions_cut_out << " cut out), " << t.components_flipped
                << " component(s) flipped globally" << (t.non_orientable ? ", non-orientable" : "") << ", "
                << r.seconds_operations << " s";
    }
    if (n_snapshots > 0) std::cout << "; " << n_snapshots << " snapshot(s) in " << snapshots;
    std::cout << "\n";
    std::cout.flush();
    if (!std::cout) throw std::runtime_error("cannot write to standard output");
    return 0;
  }, {"--vertices", "POINTS"});
}
