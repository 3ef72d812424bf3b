/// ef-shapes: write an analytic test shape as oriented points or as a mesh.
///
///   ef-shapes SHAPE [--points N | --mesh] [--resolution K] [--thickness T] [--noise S]
///             [--outliers F] [--seed S] [shape options] -o FILE
///   ef-shapes --list
///
/// Points are written as .xyz (x y z nx ny nz per line) or .ply; meshes as .off, .obj, .ply or
/// .stl (the extension decides). Exit codes: 0 ok, 1 error (one line "ef-shapes: error: ..." on
/// stderr), 2 usage error.

#include <cmath>
#include <cstdint>
#include <iostream>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "app_options.h"
#include "app_util.h"
#include "edgefront/mesh_io.h"
#include "edgefront/point_cloud_io.h"
#include "shapes/shapes.h"

namespace {

namespace sh = edgefront::shapes;

/// Largest --points (SampleOptions' limit): about 50 bytes per point in memory (4 * 10^6 points
/// peak at 195 MB), so 10^8 need 5 GB, and 12 GB as .xyz text.
constexpr unsigned long long kMaxPoints = 100000000;

/// Rounds every coordinate to `decimals` decimal places (to keep bundled files small).
double round_to(double x, int decimals) {
  const double scale = std::pow(10.0, decimals);
  const double r = std::round(x * scale) / scale;
  return r == 0.0 ? 0.0 : r;  // no "-0"
}

edgefront::Vec3 round_to(const edgefront::Vec3& p, int decimals) {
  return edgefront::Vec3(round_to(p[0], decimals), round_to(p[1], decimals), round_to(p[2], decimals));
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Write an analytic test shape as area-uniform oriented points (default) or as a mesh.", "ef-shapes"};
  std::string shape;
  std::string output;
  bool list = false;
  bool mesh = false;
  std::size_t points = 10000;
  int resolution = 32;
  bool isotropic = false;
  std::optional<int> decimals;
  sh::SampleOptions sample_options;
  sh::ShapeParams& params = sample_options.shape;

  app.add_option("SHAPE", shape, "shape name (see --list)")->check(CLI::IsMember(sh::shape_names()));
  app.add_flag("--list", list, "list the shapes and exit");
  CLI::Option* points_opt = app.add_option("--points", points, "number of points to sample, 1 ... 1e8 (default 10000; about 50 bytes each in memory, 120 in a .xyz file)")
                                ->check(edgefront::apps::integer_range(1, kMaxPoints));
  CLI::Option* mesh_opt = app.add_flag("--mesh", mesh, "write a mesh instead of points");
  points_opt->excludes(mesh_opt);
  mesh_opt->excludes(points_opt);
  CLI::Option* resolution_opt =
      app.add_option("--resolution", resolution, "mesh resolution: edges around the main circle, 3 ... 4096 (default 32)")
          ->check(edgefront::apps::integer_range(3, 4096));
  CLI::Option* noise_opt = app.add_option("--noise", sample_options.noise_sigma,
                                          "standard deviation of Gaussian noise along the normal (absolute)")
                                ->check(edgefront::apps::non_negative());
  CLI::Option* isotropic_opt = app.add_flag("--isotropic", isotropic, "make the noise isotropic instead");
  CLI::Option* outliers_opt =
      app.add_option("--outliers", sample_options.outlier_fraction, "share of points replaced by outliers, 0..1")
          ->check(edgefront::apps::real_range(0.0, 1.0));
  CLI::Option* seed_opt = edgefront::apps::add_seed_option(app, "--seed", sample_options.seed, "sampling seed");
  using edgefront::apps::positive;
  app.add_option("--radius", params.radius, "main radius R (half side of plates and grids; default 1)")->check(positive());
  app.add_option("--thickness", params.thickness, "wall thickness of vault-shell, thin-plate, hairpin (default 0.1)")
      ->check(positive());
  app.add_option("--length", params.length, "height or length along the axis (default 2)")->check(positive());
  app.add_option("--width", params.width, "width of ribbon, mobius, hairpin (default 0.5)")->check(positive());
  app.add_option("--minor-radius", params.minor_radius, "tube radius of the tori (default 0.35)")->check(positive());
  app.add_option("--inner-radius", params.inner_radius, "inner sphere radius of nested-spheres (default 0.5)")
      ->check(positive());
  app.add_option("--gap", params.gap, "gap between the hairpin's arms (default 0.05)")->check(positive());
  app.add_option("--amplitude", params.amplitude, "bump or relief amplitude (default 0.1)")
      ->check(edgefront::apps::non_negative());
  app.add_option("--frequency", params.frequency, "bump or wave frequency (default 4)")->check(positive());
  edgefront::apps::add_seed_option(app, "--surface-seed", params.surface_seed,
                                   "seed of the landscape relief and the grid jitter");
  app.add_option("--decimals", decimals, "round coordinates and normals to this many decimals (0..17)")
      ->check(edgefront::apps::integer_range(0, 17));
  app.add_option("-o,--output", output, "output file (.xyz/.ply for points; .off/.obj/.ply/.stl for meshes)");

  return edgefront::apps::run_app(app, argc, argv, [&] {
    if (list) {
      for (const std::string& name : sh::shape_names()) std::cout << name << "  " << sh::describe(name) << "\n";
      std::cout.flush();
      return std::cout ? 0 : 1;
    }
    if (shape.empty()) throw edgefront::apps::AppUsageError("SHAPE is required (see --list)");
    if (output.empty()) throw edgefront::apps::AppUsageError("-o FILE is required");
    // The output's extension and directory, before any work.
    std::string where = output;
    const std::string problem = edgefront::apps::output_file(
        mesh ? std::vector<std::string>{".off", ".obj", ".ply", ".stl"}
             : std::vector<std::string>{".xyz", ".txt", ".pts", ".ply"})(where);
    if (!problem.empty()) throw edgefront::apps::AppUsageError("-o: " + problem);
    if (mesh) {
      for (const CLI::Option* o : {noise_opt, isotropic_opt, outliers_opt, seed_opt})
        if (o->count() > 0) throw edgefront::apps::AppUsageError(o->get_name() + " applies to points, not to --mesh");
      sh::MeshOptions mesh_options;
      mesh_options.resolution = resolution;
      mesh_options.shape = params;
      edgefront::Mesh m = sh::make(shape, mesh_options);
      if (decimals)
        for (const auto v : m.vertices()) m.set_point(v, round_to(m.point(v), *decimals));
      edgefront::write_mesh(m, output);
      std::cout << "ef-shapes: wrote " << shape << " mesh, " << m.n_vertices() << " vertices, " << m.n_faces()
                << " faces, to " << output << "\n";
      return 0;
    }
    if (resolution_opt->count() > 0)
      throw edgefront::apps::AppUsageError("--resolution applies to --mesh, not to points");
    sample_options.points = points;
    sample_options.noise = isotropic ? sh::NoiseKind::isotropic : sh::NoiseKind::along_normal;
    edgefront::PointCloud cloud = sh::sample(shape, sample_options);
    if (decimals) {
      for (auto& p : cloud.points) p = round_to(p, *decimals);
      for (auto& n : cloud.normals) n = round_to(n, *decimals);
    }
    edgefront::write_points(cloud, output);
    std::cout << "ef-shapes: wrote " << cloud.size() << " points of " << shape << " to " << output << "\n";
    return 0;
  }, {"--points", "--resolution"});
}
