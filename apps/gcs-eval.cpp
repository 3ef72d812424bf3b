/// gcs-eval: judge a reconstructed mesh against a ground truth (gcs/evaluation.h).
///
///   gcs-eval MESH GT [--samples N] [--seed S] [--json] [--no-self-intersections] [--point-to-sample] [--threads N]
///
/// GT is a point set (.xyz/.txt/.pts, or .ply/.off/.obj without faces; with or without normals)
/// or a mesh (.off/.obj/.ply/.stl with faces): a mesh file is taken as a mesh when it has faces.
/// Exit codes: 0 ok, 1 error (one line "gcs-eval: error: ..." on stderr), 2 usage error.

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <string>

#include <CLI/CLI.hpp>

#include "app_options.h"
#include "app_util.h"
#include "edgefront/mesh_io.h"
#include "edgefront/point_cloud_io.h"
#include "gcs/evaluation.h"

namespace {

std::string lower_extension(const std::filesystem::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

void print_read_warnings(const std::string& what, const edgefront::MeshReadReport& r) {
  for (const std::string& w : r.warnings) std::cerr << "gcs-eval: warning: " << what << ": " << w << "\n";
}

gcs::GroundTruth load_ground_truth(const std::filesystem::path& path) {
  const std::string ext = lower_extension(path);
  if (ext == ".off" || ext == ".obj" || ext == ".ply" || ext == ".stl") {
    edgefront::MeshReadResult r = edgefront::read_mesh(path);
    if (r.mesh.n_faces() > 0) {
      print_read_warnings("ground truth", r.report);
      return gcs::GroundTruth::from_mesh(std::move(r.mesh));
    }
    if (ext == ".stl") throw edgefront::IoError("ground truth " + path.string() + " has no facets");
  }
  return gcs::GroundTruth::from_points(edgefront::read_points(path));
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Judge a reconstructed mesh against a ground truth point set or mesh: Chamfer-L1, Hausdorff, "
      "F-scores, normal and orientation consistency, and mesh validity.",
      "gcs-eval"};
  std::string mesh_path, gt_path;
  gcs::EvaluationOptions options;
  bool json = false;
  bool no_self = false;
  bool point_to_sample = false;
  app.add_option("MESH", mesh_path, "the reconstructed mesh (.off, .obj, .ply, .stl)")->required();
  app.add_option(
         "GT", gt_path,
         "ground truth: points (.xyz, .ply/.off/.obj without faces; normals optional) or a mesh with faces")
      ->required();
  app.add_option("--samples", options.samples,
                 "area-uniform samples per mesh surface, 1 ... 1e8 (about 140 bytes each in memory: 1e8 need 14 GB)")
      ->default_val(options.samples)
      ->check(edgefront::apps::integer_range(1, 100000000));
  edgefront::apps::add_seed_option(app, "--seed", options.seed, "sampling seed");
  edgefront::apps::add_threads_option(app, options.threads);
  app.add_flag("--json", json, "print one JSON object instead of the table");
  app.add_flag("--no-self-intersections", no_self, "skip the self-intersection count");
  app.add_flag("--point-to-sample", point_to_sample,
               "measure distances to a mesh to its nearest sample instead of exactly to its surface "
               "(point-to-point both ways, as many published figures)");

  return edgefront::apps::run_app(app, argc, argv, [&] {
    options.self_intersections = !no_self;
    options.exact_surface_distance = !point_to_sample;
    edgefront::MeshReadResult result = edgefront::read_mesh(mesh_path);
    print_read_warnings("mesh", result.report);
    const gcs::GroundTruth gt = load_ground_truth(gt_path);
    gcs::Evaluation e = gcs::evaluate(result.mesh, gt, options);
    e.validity.faces_dropped_when_read = result.report.faces_dropped_nonmanifold;
    if (json) {
      std::cout << gcs::evaluation_to_json(e);
    } else {
      std::cout << "mesh:                    " << mesh_path << "\n";
      std::cout << "ground truth file:       " << gt_path << "\n";
      std::cout << gcs::format_evaluation(e);
    }
    std::cout.flush();
    if (!std::cout) throw std::runtime_error("cannot write to standard output");
    return 0;
  }, {"--samples", "MESH", "GT"});
}
