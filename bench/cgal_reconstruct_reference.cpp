// cgal_reconstruct_reference: the reconstructions a user would reach for (CGAL's advancing front
// and Poisson), written as meshes and judged by gcs::evaluate against the input points: the
// reference the GCS reconstructor's targets are measured against (issue 6).
//
//   cgal_reconstruct_reference POINTS [-o DIR] [--samples N] [--seed S] [--only METHOD] [--no-eval]
//
// POINTS must have normals (Poisson needs them; e.g. data/models/kitten.xyz). Per method it
// prints the time of the reconstruction, writes DIR/<name>-<method>.off (default DIR: the current
// directory) and prints gcs::format_evaluation against the input points (all of them, with their
// normals) with N area-uniform samples of the mesh (default 100000, seed 1). The written files can
// be judged again with `gcs-eval DIR/<name>-<method>.off POINTS`, which gives the same figures.
// A last line per method gives the point-to-sample variant (`gcs-eval --point-to-sample`): the
// distance to the mesh measured to its nearest sample, as the anchors.md figures were.
// --only advancing-front|poisson runs that method alone; --no-eval writes the meshes and prints
// the time line without the evaluation (scripts/bench-closed.sh's peers judge the file against the
// model with gcs-eval).
//
// Methods, CGAL defaults as in its manual and its reconstruction tutorial on kitten.xyz:
// - advancing front: CGAL::advancing_front_surface_reconstruction(points), radius ratio bound 5,
//   beta 0.52 (the defaults);
// - Poisson: CGAL::poisson_surface_reconstruction_delaunay with the average spacing to the 6
//   nearest neighbours, sm_angle 20, sm_radius 30, sm_distance 0.375 (the defaults).
//
// Exit codes: 0 done, 1 error, 2 usage.

#ifndef CGAL_EIGEN3_ENABLED
#define CGAL_EIGEN3_ENABLED 1  // Poisson's default solver is Eigen's
#endif

#include <CGAL/Advancing_front_surface_reconstruction.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/compute_average_spacing.h>
#include <CGAL/poisson_surface_reconstruction.h>
#include <CGAL/property_map.h>

#include <array>
#include <chrono>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "edgefront/error.h"
#include "edgefront/mesh_io.h"
#include "edgefront/point_cloud_io.h"
#include "gcs/evaluation.h"

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point3 = Kernel::Point_3;
using Vector3 = Kernel::Vector_3;
using PointWithNormal = std::pair<Point3, Vector3>;
using SurfaceMesh = CGAL::Surface_mesh<Point3>;
using Clock = std::chrono::steady_clock;

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Args {
  std::filesystem::path points;
  std::filesystem::path out_dir = ".";
  gcs::EvaluationOptions eval;
  bool advancing_front = true;
  bool poisson = true;
  bool evaluate = true;
};

Args parse_args(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw UsageError(arg + " needs a value");
      return argv[++i];
    };
    auto number = [&](const std::string& text) -> unsigned long long {
      std::size_t used = 0;
      unsigned long long v = 0;
      try {
        v = std::stoull(text, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != text.size() || text.empty() || text[0] == '-')
        throw UsageError(arg + ": not a count: " + text);
      return v;
    };
    if (arg == "-o") {
      a.out_dir = value();
    } else if (arg == "--samples") {
      a.eval.samples = number(value());
    } else if (arg == "--seed") {
      a.eval.seed = number(value());
    } else if (arg == "--only") {
      const std::string method = value();
      if (method != "advancing-front" && method != "poisson")
        throw UsageError("--only: not advancing-front or poisson: " + method);
      a.advancing_front = method == "advancing-front";
      a.poisson = method == "poisson";
    } else if (arg == "--no-eval") {
      a.evaluate = false;
    } else if (!arg.empty() && arg[0] == '-') {
      throw UsageError("unknown option " + arg);
    } else if (a.points.empty()) {
      a.points = arg;
    } else {
      throw UsageError("more than one input file");
    }
  }
  if (a.points.empty()) throw UsageError("no input point file");
  return a;
}

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// CGAL triangles -> edgefront::Mesh through the project's own reader (counts refused faces).
edgefront::MeshReadResult to_mesh(const std::vector<Point3>& vertices,
                                  const std::vector<std::array<std::size_t, 3>>& triangles) {
  std::ostringstream off;
  off.precision(17);
  off << "OFF\n" << vertices.size() << " " << triangles.size() << " 0\n";
  for (const Point3& p : vertices) off << p.x() << " " << p.y() << " " << p.z() << "\n";
  for (const auto& t : triangles) off << "3 " << t[0] << " " << t[1] << " " << t[2] << "\n";
  return edgefront::read_mesh_from_buffer(off.str(), "reconstruction.off");
}

void report(const std::string& method, double seconds, const edgefront::MeshReadResult& r,
            const std::filesystem::path& file, const gcs::GroundTruth& gt, const Args& args) {
  edgefront::write_mesh(r.mesh, file);
  std::cout << "== " << method << ": " << seconds << " s, " << r.mesh.n_vertices() << " vertices, "
            << r.mesh.n_faces() << " faces -> " << file.string() << "\n";
  for (const std::string& w : r.report.warnings) std::cout << "   reader: " << w << "\n";
  if (!args.evaluate) return;
  const gcs::EvaluationOptions& options = args.eval;
  const Clock::time_point t0 = Clock::now();
  const gcs::Evaluation e = gcs::evaluate(r.mesh, gt, options);
  const double eval_seconds = seconds_since(t0);
  std::cout << gcs::format_evaluation(e);
  std::cout << "evaluation time:         " << eval_seconds << " s\n";
  gcs::EvaluationOptions p2p = options;
  p2p.exact_surface_distance = false;
  p2p.self_intersections = false;
  const gcs::Evaluation ep = gcs::evaluate(r.mesh, gt, p2p);
  std::cout << "point-to-sample variant: chamfer-L1 " << ep.scale(ep.chamfer_l1) << "% (gt -> result mean "
            << ep.scale(ep.gt_to_result.mean) << "%), hausdorff " << ep.scale(ep.hausdorff)
            << "%, F-score @ 1% " << ep.fscores.back().fscore << "\n\n";
}

}  // namespace

int main(int argc, char** argv) {
  Args args;
  try {
    args = parse_args(argc, argv);
  } catch (const UsageError& e) {
    std::cerr << "cgal_reconstruct_reference: error: " << e.what()
              << "\nusage: cgal_reconstruct_reference POINTS [-o DIR] [--samples N] [--seed S]"
                 " [--only advancing-front|poisson] [--no-eval]\n";
    return 2;
  }
  try {
    const edgefront::PointCloud cloud = edgefront::read_points(args.points);
    if (!cloud.has_normals())
      throw edgefront::InvalidInput(args.points.string() + " has no normals (Poisson needs them)");
    std::filesystem::create_directories(args.out_dir);
    const std::string stem = args.points.stem().string();
    const gcs::GroundTruth gt = gcs::GroundTruth::from_points(cloud);
    std::cout << "input: " << args.points.string() << ", " << cloud.size() << " points with normals; "
              << args.eval.samples << " mesh samples, seed " << args.eval.seed << "\n\n";

    std::vector<Point3> points;
    std::vector<PointWithNormal> oriented;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
      const edgefront::Vec3& p = cloud.points[i];
      const edgefront::Vec3& n = cloud.normals[i];
      points.emplace_back(p[0], p[1], p[2]);
      oriented.emplace_back(Point3(p[0], p[1], p[2]), Vector3(n[0], n[1], n[2]));
    }

    if (args.advancing_front) {  // Advancing front
      const Clock::time_point t0 = Clock::now();
      std::vector<std::array<std::size_t, 3>> facets;
      CGAL::advancing_front_surface_reconstruction(points.begin(), points.end(), std::back_inserter(facets));
      const double t = seconds_since(t0);
      report("CGAL advancing front", t, to_mesh(points, facets),
             args.out_dir / (stem + "-advancing-front.off"), gt, args);
    }
    if (args.poisson) {  // Poisson
      const Clock::time_point t0 = Clock::now();
      const double spacing = CGAL::compute_average_spacing<CGAL::Sequential_tag>(
          oriented, 6, CGAL::parameters::point_map(CGAL::First_of_pair_property_map<PointWithNormal>()));
      SurfaceMesh sm;
      const bool ok = CGAL::poisson_surface_reconstruction_delaunay(
          oriented.begin(), oriented.end(), CGAL::First_of_pair_property_map<PointWithNormal>(),
          CGAL::Second_of_pair_property_map<PointWithNormal>(), sm, spacing);
      const double t = seconds_since(t0);
      if (!ok) throw std::runtime_error("CGAL Poisson reconstruction failed");
      std::vector<Point3> vertices;
      std::vector<std::size_t> index(sm.number_of_vertices() + sm.number_of_removed_vertices(), 0);
      for (const auto v : sm.vertices()) {
        index[v.idx()] = vertices.size();
        vertices.push_back(sm.point(v));
      }
      std::vector<std::array<std::size_t, 3>> triangles;
      for (const auto f : sm.faces()) {
        std::array<std::size_t, 3> tri{};
        std::size_t k = 0;
        for (const auto v : CGAL::vertices_around_face(sm.halfedge(f), sm)) {
          if (k < 3) tri[k] = index[v.idx()];
          ++k;
        }
        if (k != 3) throw std::runtime_error("Poisson output has a non-triangle face");
        triangles.push_back(tri);
      }
      std::cout << "(Poisson average spacing " << spacing << ")\n";
      report("CGAL Poisson", t, to_mesh(vertices, triangles), args.out_dir / (stem + "-poisson.off"), gt,
             args);
    }
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "cgal_reconstruct_reference: error: " << e.what() << "\n";
    return 1;
  }
}
