/// bench_twist: the twist repair inside GCS reconstruction of the synthetic vaults, with and
/// without the repair operation, and the standalone repair on the deterministic twisted meshes.
///
///   bench_twist [--vertices N] [--points P] [--seeds S] [--first-seed S0] [--shapes a,b,...]
///               [--thickness t] [--side-weight W] [--max-retwists K] [--no-regrow] [--no-normals]
///
/// For every shape and seed: sample P oriented points (shapes::sample, exact normals), run GCS
/// from the box start to N vertices with and without the twist operation, and report the
/// orientation consistency of the result against the analytic normals (area share whose normal
/// agrees with the nearest of 200k exact samples; "abs" without any sign forgiven, "comp" with
/// the best sign per connected component), the twisted regions left (geometric detector, no
/// reference), faces with a same-orientation layer (close in space, far along the surface, same
/// orientation: `twist::count_same_orientation_layers`), border loops and components, the regions
/// repaired, and the share of the run spent in the twist operation.
/// Prints a markdown table.

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "edgefront/mesh_stats.h"
#include "edgefront/shapes.h"
#include "gcs/evaluation.h"
#include "gcs/reconstructor.h"
#include "gcs/twist_operation.h"
#include "twist/detect.h"
#include "twist/reference_normals.h"

namespace {

using edgefront::Mesh;

struct Case {
  std::string label, shape;
  double thickness;
};

struct Consistency {
  double absolute = 0, per_component = 0;
};

Consistency consistency(const Mesh& mesh, const twist::ReferenceNormals& ref) {
  const edgefront::ComponentLabels labels = edgefront::connected_components(mesh);
  std::vector<double> agree(labels.count, 0), total(labels.count, 0);
  for (edgefront::FaceHandle f : mesh.faces()) {
    const auto n = mesh.calc_face_normal(f);
    const double a = mesh.calc_face_area(f);
    if (!(a > 0)) continue;
    const int c = labels.vertex_component[static_cast<size_t>((*mesh.cfv_begin(f)).idx())];
    total[static_cast<size_t>(c)] += a;
    if (OpenMesh::dot(n, ref.nearest_normal(mesh.calc_face_centroid(f))) > 0) agree[static_cast<size_t>(c)] += a;
  }
  double A = 0, B = 0, T = 0;
  for (size_t c = 0; c < labels.count; ++c) {
    A += agree[c];
    B += std::max(agree[c], total[c] - agree[c]);
    T += total[c];
  }
  return {T > 0 ? A / T : 0, T > 0 ? B / T : 0};
}

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  for (std::string item; std::getline(ss, item, ',');) out.push_back(item);
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  size_t vertices = 1500, points = 20000, seeds = 3, first_seed = 1, max_retwists = 2;
  double side_weight = 4.0, only_thickness = 0;
  bool normals = true, regrow = true;
  std::string only;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) throw std::runtime_error("missing value after " + a);
      return argv[++i];
    };
    if (a == "--vertices") vertices = std::stoul(next());
    else if (a == "--points") points = std::stoul(next());
    else if (a == "--seeds") seeds = std::stoul(next());
    else if (a == "--shapes") only = next();
    else if (a == "--no-normals") normals = false;
    else if (a == "--first-seed") first_seed = std::stoul(next());
    else if (a == "--thickness") only_thickness = std::stod(next());
    else if (a == "--side-weight") side_weight = std::stod(next());
    else if (a == "--max-retwists") max_retwists = std::stoul(next());
    else if (a == "--no-regrow") regrow = false;
    else {
      std::cerr << "usage: bench_twist [--vertices N] [--points P] [--seeds S] [--first-seed S0] [--shapes a,b] [--thickness t]"
                   " [--side-weight W] [--max-retwists K] [--no-regrow] [--no-normals]\n";
      return 2;
    }
  }
  std::vector<Case> cases = {{"vault-shell t/R=0.2", "vault-shell", 0.2},   {"vault-shell t/R=0.1", "vault-shell", 0.1},
                             {"vault-shell t/R=0.05", "vault-shell", 0.05}, {"vault-shell t/R=0.02", "vault-shell", 0.02},
                             {"vault-sheet", "vault-sheet", 0.1},           {"pointed-vault", "pointed-vault", 0.1},
                             {"groin-vault", "groin-vault", 0.1}};
  if (!only.empty()) {
    const auto keep = split(only);
    cases.erase(std::remove_if(cases.begin(), cases.end(),
                               [&](const Case& c) { return std::find(keep.begin(), keep.end(), c.shape) == keep.end(); }),
                cases.end());
  }
  if (only_thickness > 0) {
    cases.erase(std::remove_if(cases.begin(), cases.end(), [&](const Case& c) { return c.thickness != only_thickness; }),
                cases.end());
  }
  std::printf("GCS from the box start, %zu vertices, %zu points%s, seeds %zu-%zu, side weight %g, max re-twists %zu, %s\n\n",
              vertices, points, normals ? " with exact normals" : " without normals", first_seed, first_seed + seeds - 1,
              side_weight, max_retwists, regrow ? "cut-outs re-grown" : "cut-outs left as holes");
  std::printf("| shape | seed | no repair: abs / comp | eval comp | same-orient. faces | borders | with repair: abs / comp | eval comp | same-orient. faces | borders | components | found | repaired | cut out | faces removed | twist time share |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const Case& c : cases) {
    edgefront::shapes::SampleOptions dense;
    dense.points = 200000;
    dense.seed = 999;
    dense.shape.thickness = c.thickness;
    const edgefront::PointCloud dense_cloud = edgefront::shapes::sample(c.shape, dense);
    const twist::ReferenceNormals truth(dense_cloud);
    for (size_t seed = first_seed; seed < first_seed + seeds; ++seed) {
      edgefront::shapes::SampleOptions so;
      so.points = points;
      so.seed = seed;
      so.shape.thickness = c.thickness;
      edgefront::PointCloud cloud = edgefront::shapes::sample(c.shape, so);
      if (!normals) cloud.normals.clear();
      gcs::ReconstructOptions ro;
      ro.target_vertices = vertices;
      ro.seed = seed;
      Consistency cons[2];
      gcs::OrientationConsistency eval[2];
      size_t left[2] = {0, 0}, borders[2] = {0, 0}, components[2] = {0, 0};
      gcs::TwistOperationStats stats;
      double share = 0;
      for (int with = 0; with < 2; ++with) {
        gcs::Reconstructor rec(cloud, ro);
        std::shared_ptr<gcs::TwistOperation> op;
        if (with) {
          gcs::TwistOperationOptions to;
          to.repair.detect.reference_side_weight = side_weight;
          to.max_retwists = max_retwists;
          to.repair.regrow_cut_outs = regrow;
          op = std::make_shared<gcs::TwistOperation>(to);
          rec.add_operation(op);
        }
        const gcs::ReconstructResult r = rec.run();
        cons[with] = consistency(r.mesh, truth);
        eval[with] = gcs::orientation_consistency(r.mesh, dense_cloud);  // the eval branch's metric, for comparison
        left[with] = twist::count_same_orientation_layers(r.mesh);
        const edgefront::MeshStats ms = edgefront::compute_stats(r.mesh);
        borders[with] = ms.border_loops;
        components[with] = ms.components;
        if (with) {
          stats = op->stats();
          share = r.seconds_total > 0 ? r.seconds_operations / r.seconds_total : 0;
        }
      }
      std::printf("| %s | %zu | %.4f / %.4f | %.4f | %zu | %zu | %.4f / %.4f | %.4f | %zu | %zu | %zu | %zu | %zu | %zu | %zu | %.1f%% |\n",
                  c.label.c_str(), seed, cons[0].absolute, cons[0].per_component, eval[0].per_component, left[0], borders[0],
                  cons[1].absolute, cons[1].per_component, eval[1].per_component, left[1], borders[1], components[1],
                  stats.regions_found, stats.repairs, stats.regions_cut_out, stats.faces_removed, 100 * share);
      std::fflush(stdout);
    }
  }
  return 0;
}
