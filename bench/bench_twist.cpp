/// bench_twist: the twist repair inside GCS reconstruction of the synthetic vaults, with and
/// without the repair operation, and the standalone repair on the deterministic twisted meshes.
///
///   bench_twist [--vertices N] [--points P] [--seeds S] [--first-seed S0] [--shapes a,b,...]
///               [--thickness t] [--side-weight W] [--thin-wall E] [--margin M] [--max-retwists K] [--regrow]
///               [--min-flagged K] [--global-index] [--border-ratio R] [--no-normals] [--quadric-normals]
///               [--edge-per-thickness K] [--retest-all] [--no-orient-winners] [--rejoin]
///               [--no-rejoin] [--peel N] [--turned N] [--stacked-rounds N] [--no-post] [--only-repair] [--explain 1|2]
///               [--keep-crossings] [--skip-unfaced-samples] [--trace] [--dump PREFIX]
///   bench_twist --explain-mesh MESH [--shapes S] [--thickness t] [--explain 2]
///                                     where the same-orientation pairs of a saved result lie
///   bench_twist --detect-scaling      time per incremental detection call vs mesh size
///   bench_twist --cloud FILE [--vertices N] [--seeds S] [--retest-all] [--rejoin] [--no-rejoin] [--peel N]
///                                     GCS on a point file with and without the twist operation:
///                                     wall and CPU time, the twist operation's share, faces tested
///
/// Resolution rule for the thin shells (`--edge-per-thickness K`): a user reconstructing a thin
/// shell uses enough vertices to resolve its walls, so for vault-shell cases the vertex count is
/// chosen such that the expected mean edge is K times the wall thickness t: a mesh of V vertices
/// has about 2V faces, and with near-equilateral faces of edge e it covers A = 2V (sqrt(3)/4) e²,
/// hence V = ceil(2 A / (sqrt(3) (K t)²)), with A the area of the shell (summed over
/// `shapes::make("vault-shell")` at resolution 256). The point count becomes
/// max(P, 3 V), so the samples resolve the walls too. K = 0.5 gives an edge of half the wall.
///
/// For every shape and seed: sample P oriented points (shapes::sample, exact normals), run GCS
/// from the box start to N vertices with and without the twist operation, and report the
/// orientation consistency of the result against the analytic normals (area share whose normal
/// agrees with the nearest of 200k exact samples; "abs" without any sign forgiven, "comp" with
/// the best sign per connected component), the twisted regions left (geometric detector, no
/// reference), faces with a same-orientation layer (close in space, far along the surface, same
/// orientation: `twist::count_same_orientation_layers`, "stacked / facing" under the two
/// `twist::LayerRule`s), border loops and components, the regions
/// repaired, and the share of the run spent in the twist operation.
/// `--quadric-normals` sets `InputOptions::quadric_normals` (with `--no-normals`).
/// `--no-orient-winners` runs GCS with `InputOptions::orient_winners` off (plain winners, as
/// in the published loop): with oriented samples the oriented winner search keeps most runs from
/// twisting at all, so this is the setting that shows what the repair does on a twisted GCS.
/// "coverage" is the share of the exact samples with a vertex, edge midpoint or face centroid of
/// the result within 2% of the bounding-box diagonal: consistency alone does not show a result
/// that lost most of its surface (a repair that shreds the shell lets the loop delete the pieces).
/// `--thin-wall E` sets `DetectOptions::thin_wall` (0 = off: the nearest normal decides on walls
/// thinner than the faces too).
/// `--rejoin` / `--no-rejoin` turn the border re-join after repairs on / off
/// (`TwistOperationOptions::rejoin_borders`, default off; the session-5 vault table used `--rejoin`),
/// `--peel N` sets the rounds of border-flap peeling of the final call (`RepairOptions::peel_flaps`),
/// `--turned N` the largest turned-over patch the final call removes, collapses or straightens
/// (`RepairOptions::drop_turned_patches`, 0 = off; column "turned dropped"),
/// `--stacked-rounds N` the rounds of the reconstructor's last post-processing step, the removal of
/// small stacked double layers at borders (`PostProcessOptions::stacked_layer_rounds`, 0 = off;
/// column "stacked before the removal / removed / pleats flattened": the faces with a stacked
/// partner it found on the post-processed mesh, before it changed anything (0 when it did not
/// scan: off, or no border), the faces it removed and the pleats it smoothed flat, for the plain
/// and the repair run); "self-int. pairs": the result's self-intersecting face pairs
/// (`gcs::count_self_intersections`, as gcs-eval counts them), plain and repair run, and for the
/// repair run what the last post-processing step (`PostProcessOptions::resolve_self_intersections`)
/// found and did: pairs found / vertices smoothed / faces cut out, and its share of the run's wall
/// time. `--keep-crossings` turns it off. `--skip-unfaced-samples` sets
/// `ExperimentalOptions::skip_unfaced_samples` (off by default).
/// Diagnostics (stderr): `--explain 1|2` says where the same-orientation face pairs of each result
/// lie (2: one line per pair), `--trace` logs faces, area and components before and after every
/// twist call, `--dump PREFIX` writes every result as PREFIX-shape-thickness-sSEED-{plain,repair}.off,
/// `--only-repair` skips the runs without the operation (their columns are then zero),
/// `--no-post` turns off the reconstructor's post-processing of the returned mesh (projection to
/// the samples and surface fit), so the result is the loop's mesh as the final twist call left it.
/// Prints a markdown table.

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <ctime>
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "edgefront/mesh_io.h"
#include "edgefront/mesh_stats.h"
#include "edgefront/point_cloud_io.h"
#include "edgefront/point_index.h"
#include "shapes/shapes.h"
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
  double judged = 0, undecided = 0;  ///< by sides (ReferenceNormals::judge): per component among decided area; undecided share
};

Consistency consistency(const Mesh& mesh, const twist::ReferenceNormals& ref) {
  const edgefront::ComponentLabels labels = edgefront::connected_components(mesh);
  std::vector<double> agree(labels.count, 0), total(labels.count, 0), j_agree(labels.count, 0), j_total(labels.count, 0);
  double undecided = 0;
  for (edgefront::FaceHandle f : mesh.faces()) {
    const auto n = mesh.calc_face_normal(f);
    const double a = mesh.calc_face_area(f);
    if (!(a > 0)) continue;
    const int c = labels.vertex_component[static_cast<size_t>((*mesh.cfv_begin(f)).idx())];
    total[static_cast<size_t>(c)] += a;
    if (OpenMesh::dot(n, ref.nearest_normal(mesh.calc_face_centroid(f))) > 0) agree[static_cast<size_t>(c)] += a;
    const int vote = ref.judge(mesh.calc_face_centroid(f), n);
    if (vote == 0) {
      undecided += a;
    } else {
      j_total[static_cast<size_t>(c)] += a;
      if (vote > 0) j_agree[static_cast<size_t>(c)] += a;
    }
  }
  double JA = 0, JT = 0;
  for (size_t c = 0; c < labels.count; ++c) {
    JA += std::max(j_agree[c], j_total[c] - j_agree[c]);
    JT += j_total[c];
  }
  double A = 0, B = 0, T = 0;
  for (size_t c = 0; c < labels.count; ++c) {
    A += agree[c];
    B += std::max(agree[c], total[c] - agree[c]);
    T += total[c];
  }
  return {T > 0 ? A / T : 0, T > 0 ? B / T : 0, JT > 0 ? JA / JT : 0, T > 0 ? undecided / T : 0};
}

/// Share of the truth samples (every 10th of the dense cloud) that have a vertex, edge midpoint or
/// face centroid of the mesh within 2% of the samples' bounding-box diagonal: how much of the shape the result
/// still covers (a repair that shreds the surface and lets the loop delete the pieces scores
/// high consistency on what is left, but low coverage).
double coverage(const Mesh& mesh, const edgefront::PointCloud& truth) {
  std::vector<edgefront::Vec3> pts;
  for (auto v : mesh.vertices()) pts.push_back(mesh.point(v));
  for (auto f : mesh.faces()) pts.push_back(mesh.calc_face_centroid(f));
  for (auto e : mesh.edges()) pts.push_back(mesh.calc_edge_midpoint(e));
  if (pts.empty() || truth.size() == 0) return 0;
  edgefront::Vec3 lo = truth.points[0], hi = truth.points[0];
  for (const auto& p : truth.points) {
    lo.minimize(p);
    hi.maximize(p);
  }
  const double tol2 = std::pow(0.02 * (hi - lo).norm(), 2);
  const edgefront::PointIndex index(std::move(pts));
  size_t covered = 0, total = 0;
  for (size_t i = 0; i < truth.size(); i += 10, ++total) covered += index.nearest(truth.points[i]).distance2 <= tol2;
  return static_cast<double>(covered) / static_cast<double>(total);
}

/// Time per incremental detection call vs mesh size (issue 7, Speed): a correct vault shell
/// mesh (t/R = 0.1) at growing resolution; each call gets 64 "changed" faces (a breadth-first
/// patch around a different face) plus the 64-face audit, once with a k-d tree over all face
/// centroids per call (no face grid) and once with a face grid kept across calls.
void detect_scaling() {
  std::printf("| arch segments | faces | k-d tree per call: ms | faces tested | face grid per call: ms | faces tested | ratio |\n");
  std::printf("|---|---|---|---|---|---|---|\n");
  for (int arch : {16, 32, 64, 128, 256, 512}) {
    const Mesh mesh = edgefront::shapes::vault_shell(arch, 1.0, 0.1, 2.0);
    const size_t nf = mesh.n_faces();
    std::vector<std::vector<edgefront::FaceHandle>> patches;
    for (size_t call = 0; call < 20; ++call) {
      std::vector<edgefront::FaceHandle> patch{edgefront::FaceHandle(static_cast<int>((call * 7919 + nf / 3) % nf))};
      std::vector<char> seen(nf, 0);
      seen[static_cast<size_t>(patch[0].idx())] = 1;
      for (size_t q = 0; q < patch.size() && patch.size() < 64; ++q) {
        for (auto g : mesh.ff_range(patch[q])) {
          if (!seen[static_cast<size_t>(g.idx())] && patch.size() < 64) {
            seen[static_cast<size_t>(g.idx())] = 1;
            patch.push_back(g);
          }
        }
      }
      std::sort(patch.begin(), patch.end(), [](auto a, auto b) { return a.idx() < b.idx(); });
      patches.push_back(std::move(patch));
    }
    double mean_edge = 0;
    for (auto e : mesh.edges()) mean_edge += mesh.calc_edge_length(e);
    mean_edge /= static_cast<double>(mesh.n_edges());
    twist::FaceGrid grid;
    grid.rebuild(mesh, 2 * mean_edge);
    double ms[2] = {0, 0};
    size_t tested[2] = {0, 0};
    for (int local = 0; local < 2; ++local) {
      const auto t0 = std::chrono::steady_clock::now();
      for (size_t call = 0; call < patches.size(); ++call) {
        twist::DetectOptions o;
        o.restrict_to = patches[call];
        o.audit_offset = call * 7919;
        if (local) {
          grid.update(mesh, patches[call]);
          o.face_grid = &grid;
          o.mean_edge_length = mean_edge;
        }
        tested[local] += twist::detect_regions(mesh, o).stats.faces_tested;
      }
      ms[local] = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count() /
                  static_cast<double>(patches.size());
    }
    std::printf("| %d | %zu | %.3f | %zu | %.3f | %zu | %.1fx |\n", arch, nf, ms[0], tested[0] / patches.size(), ms[1],
                tested[1] / patches.size(), ms[0] / ms[1]);
    std::fflush(stdout);
  }
}

/// `--explain`: where the same-orientation face pairs of a result lie (one line per run on
/// stderr, then one per pair with --explain 2): same component or not, the sizes of the
/// components, the exact normals' verdict on both faces (+1 agrees, -1 disagrees, 0 undecided),
/// whether either face touches a border, and whether the geometric detector (no reference) puts
/// either face in a twisted region; under one pair rule (`twist::LayerRule`).
void explain_pairs(const Mesh& mesh, const twist::ReferenceNormals& truth, const std::string& label, size_t seed, int level,
                   twist::LayerRule rule) {
  const auto pairs = twist::same_orientation_pairs(mesh, {}, rule);
  const edgefront::ComponentLabels labels = edgefront::connected_components(mesh);
  std::vector<size_t> comp_faces(labels.count, 0);
  auto comp = [&](edgefront::FaceHandle f) { return labels.vertex_component[static_cast<size_t>((*mesh.cfv_begin(f)).idx())]; };
  for (auto f : mesh.faces()) ++comp_faces[static_cast<size_t>(comp(f))];
  std::map<int, char> in_region;
  for (const auto& r : twist::detect(mesh)) {
    for (auto f : r.faces) in_region[f.idx()] = 1;
  }
  auto on_border = [&](edgefront::FaceHandle f) {
    for (auto v : mesh.fv_range(f)) {
      if (mesh.is_boundary(v)) return true;
    }
    return false;
  };
  auto vote = [&](edgefront::FaceHandle f) { return truth.judge(mesh.calc_face_centroid(f), mesh.calc_face_normal(f).normalized()); };
  size_t same = 0, both_right = 0, same_wall = 0, one_wrong = 0, undecided = 0, border = 0, detected = 0;
  std::set<int> wrong_faces;  // the distinct faces the exact normals reject among the pairs
  std::map<size_t, size_t> small_comp;  // component faces -> pairs with a face in it (components below 100 faces)
  for (const auto& [f, g] : pairs) {
    const int cf = comp(f), cg = comp(g);
    same += cf == cg;
    const int vf = vote(f), vg = vote(g);
    // Both right and the exact normals nearest to both agree: the two faces approximate the
    // same wall (no two walls of these shapes face the same way within the radius), far apart
    // along the mesh only because a border (a hole) runs between them.
    if (vf > 0 && vg > 0 &&
        OpenMesh::dot(truth.nearest_normal(mesh.calc_face_centroid(f)), truth.nearest_normal(mesh.calc_face_centroid(g))) > 0.9) {
      ++same_wall;
    }
    if (vf > 0 && vg > 0) ++both_right;
    else if (vf < 0 || vg < 0) ++one_wrong;
    else ++undecided;
    if (vf < 0) wrong_faces.insert(f.idx());
    if (vg < 0) wrong_faces.insert(g.idx());
    border += on_border(f) || on_border(g);
    detected += in_region.count(f.idx()) || in_region.count(g.idx());
    const size_t smaller = std::min(comp_faces[static_cast<size_t>(cf)], comp_faces[static_cast<size_t>(cg)]);
    if (smaller < 100) ++small_comp[smaller];
    if (level >= 2) {
      const double d = (mesh.calc_face_centroid(f) - mesh.calc_face_centroid(g)).norm();
      std::fprintf(stderr, "  pair f%d g%d comp %d(%zu) %d(%zu) votes %+d %+d border %d%d dist %.4f dot %.3f centre (%.3f %.3f %.3f)\n",
                   f.idx(), g.idx(), cf, comp_faces[static_cast<size_t>(cf)], cg, comp_faces[static_cast<size_t>(cg)], vf, vg,
                   on_border(f), on_border(g), d, OpenMesh::dot(mesh.calc_face_normal(f), mesh.calc_face_normal(g)),
                   mesh.calc_face_centroid(f)[0], mesh.calc_face_centroid(f)[1], mesh.calc_face_centroid(f)[2]);
    }
  }
  std::fprintf(stderr, "%s seed %zu [%s]: %zu pairs; same component %zu; both right %zu (on one wall %zu), one wrong %zu, undecided %zu; touching a border %zu; in a detected region %zu; components %zu",
               label.c_str(), seed, rule == twist::LayerRule::Stacked ? "stacked" : "facing", pairs.size(), same, both_right, same_wall, one_wrong, undecided, border, detected, labels.count);
  double wrong_area = 0, area = 0;
  for (auto f : mesh.faces()) area += mesh.calc_face_area(f);
  for (int k : wrong_faces) wrong_area += mesh.calc_face_area(edgefront::FaceHandle(k));
  std::fprintf(stderr, "; distinct rejected faces in the pairs %zu (area share %.5f)", wrong_faces.size(), area > 0 ? wrong_area / area : 0.0);
  std::fprintf(stderr, "; face counts of components:");
  std::vector<size_t> sizes = comp_faces;
  std::sort(sizes.rbegin(), sizes.rend());
  for (size_t k : sizes) std::fprintf(stderr, " %zu", k);
  std::fprintf(stderr, "\n");
}

/// `--trace`: an operation that logs the mesh (live faces, area, components) to stderr each time
/// the loop calls it; registered before and after the twist operation, it shows what the loop's
/// own topology pass and what the twist repair did to the mesh in each batch.
class TraceOperation : public gcs::Operation {
 public:
  explicit TraceOperation(std::string tag) : tag_(std::move(tag)) {}
  std::string name() const override { return "trace-" + tag_; }
  gcs::OperationResult apply(Mesh& mesh, const gcs::ChangeSet&, const gcs::OperationContext& context) override {
    size_t faces = 0;
    double area = 0;
    for (auto f : mesh.faces()) {
      ++faces;
      area += mesh.calc_face_area(f);
    }
    std::fprintf(stderr, "  batch %zu%s %s: %zu live vertices, %zu faces, area %.3f, %zu components\n", context.batch,
                 context.final_call ? " (final)" : "", tag_.c_str(), context.live_vertices, faces, area,
                 edgefront::connected_components(mesh).count - isolated(mesh));
    return {};
  }

 private:
  static size_t isolated(const Mesh& mesh) {
    size_t n = 0;
    for (auto v : mesh.vertices()) n += mesh.is_isolated(v);
    return n;
  }
  std::string tag_;
};

double cpu_seconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

/// Surface area of a shape's reference mesh (for the resolution rule).
double shape_area(const std::string& shape, double thickness) {
  edgefront::shapes::MeshOptions mo;
  mo.resolution = 256;
  mo.shape.thickness = thickness;
  const Mesh mesh = edgefront::shapes::make(shape, mo);
  double area = 0;
  for (edgefront::FaceHandle f : mesh.faces()) area += mesh.calc_face_area(f);
  return area;
}

/// The vertex count whose expected mean edge is `edge` on a surface of this area (see the file comment).
size_t vertices_for_edge(double area, double edge) {
  return static_cast<size_t>(std::ceil(2.0 * area / (std::sqrt(3.0) * edge * edge)));
}

/// GCS on a point file with and without the twist operation (the cost of twist handling on a
/// closed scan, issue 7's Speed).
void cloud_run(const std::string& path, size_t vertices, size_t seeds, bool retest_all, bool rejoin, int peel) {
  const edgefront::PointCloud cloud = edgefront::read_points(path);
  std::printf("%s: %zu points%s, %zu vertices%s\n\n", path.c_str(), cloud.size(), cloud.has_normals() ? " with normals" : "",
              vertices, retest_all ? ", every changed face retested" : "");
  std::printf("| seed | no twist: wall s | CPU s | consistency | components / loops / genus | with twist: wall s | CPU s | twist wall s | twist CPU s | twist share wall | twist share CPU | calls | faces tested | found | repaired | cut out | consistency | components / loops / genus |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (size_t seed = 1; seed <= seeds; ++seed) {
    double wall[2] = {0, 0}, cpu[2] = {0, 0}, cons[2] = {0, 0};
    std::string topology[2];
    gcs::TwistOperationStats stats;
    double op_wall = 0;
    for (int with = 0; with < 2; ++with) {
      gcs::ReconstructOptions ro;
      ro.target_vertices = vertices;
      ro.seed = seed;
      gcs::Reconstructor rec(cloud, ro);
      std::shared_ptr<gcs::TwistOperation> op;
      if (with) {
        gcs::TwistOperationOptions to;
        if (retest_all) to.repair.retest_turn_degrees = to.repair.retest_move = 0;
        to.rejoin_borders = rejoin;
        if (peel >= 0) to.repair.peel_flaps = peel;
        op = std::make_shared<gcs::TwistOperation>(to);
        rec.add_operation(op);
      }
      const double c0 = cpu_seconds();
      const gcs::ReconstructResult r = rec.run();
      cpu[with] = cpu_seconds() - c0;
      wall[with] = r.seconds_total;
      if (with) {
        stats = op->stats();
        op_wall = r.seconds_operations;
      }
      if (cloud.has_normals()) cons[with] = gcs::orientation_consistency(r.mesh, cloud).per_component;
      const edgefront::MeshStats ms = edgefront::compute_stats(r.mesh);
      topology[with] = std::to_string(ms.components) + " / " + std::to_string(ms.border_loops) + " / " +
                       std::to_string((2 * static_cast<long>(ms.components) - ms.euler_characteristic -
                                       static_cast<long>(ms.border_loops)) / 2);
    }
    std::printf("| %zu | %.2f | %.2f | %.4f | %s | %.2f | %.2f | %.2f | %.2f | %.1f%% | %.1f%% | %zu | %zu | %zu | %zu | %zu | %.4f | %s |\n", seed,
                wall[0], cpu[0], cons[0], topology[0].c_str(), wall[1], cpu[1], op_wall, stats.cpu_seconds,
                100 * op_wall / wall[1], 100 * stats.cpu_seconds / cpu[1], stats.calls, stats.faces_tested,
                stats.regions_found, stats.repairs, stats.regions_cut_out, cons[1], topology[1].c_str());
    std::fflush(stdout);
  }
}

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  for (std::string item; std::getline(ss, item, ',');) out.push_back(item);
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  size_t vertices = 1500, points = 20000, seeds = 3, first_seed = 1, max_retwists = 2, min_flagged = 0;
  double side_weight = 0.0, only_thickness = 0, margin = 1.5, border_ratio = 0.0;
  double thin_wall = twist::DetectOptions{}.thin_wall;
  int explain = 0;
  bool only_repair = false, trace = false, rejoin = gcs::TwistOperationOptions{}.rejoin_borders;
  int peel = -1, turned = -1, stacked_rounds = -1;
  std::string dump;
  bool post = true;  // the reconstructor's projection and surface fit of the returned mesh
  bool resolve_crossings = true;  // PostProcessOptions::resolve_self_intersections
  bool skip_unfaced = false;      // ExperimentalOptions::skip_unfaced_samples
  bool normals = true, regrow = false, local = true, retest_all = false, orient_winners = true, quadric = false;
  double edge_per_thickness = 0;
  std::string only, cloud_path, explain_mesh;
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
    else if (a == "--regrow") regrow = true;
    else if (a == "--margin") margin = std::stod(next());
    else if (a == "--thin-wall") thin_wall = std::stod(next());
    else if (a == "--min-flagged") min_flagged = std::stoul(next());
    else if (a == "--global-index") local = false;
    else if (a == "--border-ratio") border_ratio = std::stod(next());
    else if (a == "--edge-per-thickness") edge_per_thickness = std::stod(next());
    else if (a == "--retest-all") retest_all = true;
    else if (a == "--no-orient-winners") orient_winners = false;
    else if (a == "--quadric-normals") quadric = true;
    else if (a == "--cloud") cloud_path = next();
    else if (a == "--explain") explain = std::stoi(next());
    else if (a == "--only-repair") only_repair = true;
    else if (a == "--trace") trace = true;
    else if (a == "--no-rejoin") rejoin = false;
    else if (a == "--rejoin") rejoin = true;
    else if (a == "--peel") peel = std::stoi(next());
    else if (a == "--turned") turned = std::stoi(next());
    else if (a == "--stacked-rounds") stacked_rounds = std::stoi(next());
    else if (a == "--dump") dump = next();
    else if (a == "--explain-mesh") explain_mesh = next();
    else if (a == "--no-post") post = false;
    else if (a == "--keep-crossings") resolve_crossings = false;
    else if (a == "--skip-unfaced-samples") skip_unfaced = true;
    else if (a == "--detect-scaling") {
      detect_scaling();
      return 0;
    }
    else {
      std::cerr << "usage: bench_twist [--vertices N] [--points P] [--seeds S] [--first-seed S0] [--shapes a,b] [--thickness t]"
                   " [--side-weight W] [--thin-wall E] [--max-retwists K] [--regrow] [--margin M] [--min-flagged K] [--global-index] [--border-ratio R] [--no-normals]"
                   " [--edge-per-thickness K] [--retest-all] [--no-orient-winners] [--explain 1|2] [--only-repair] [--dump PREFIX] [--trace] [--rejoin] [--no-rejoin] [--peel N] [--turned N] [--stacked-rounds N] [--no-post] [--keep-crossings] [--skip-unfaced-samples] | --detect-scaling | --cloud FILE [--vertices N] [--seeds S] [--retest-all] [--rejoin] [--no-rejoin] [--peel N]\n";
      return 2;
    }
  }
  if (!(edge_per_thickness >= 0) || !std::isfinite(edge_per_thickness)) {
    std::cerr << "bench_twist: --edge-per-thickness must be finite and >= 0\n";
    return 2;
  }
  if (!cloud_path.empty()) {
    cloud_run(cloud_path, vertices, seeds, retest_all, rejoin, peel);
    return 0;
  }
  if (!explain_mesh.empty()) {
    // Where the same-orientation pairs of a saved result (e.g. a --dump file) lie, against the
    // exact normals of the shape (--shapes, first name; --thickness for the shell).
    const std::string shape = only.empty() ? std::string("vault-shell") : split(only).front();
    edgefront::shapes::SampleOptions dense;
    dense.points = 200000;
    dense.seed = 999;
    if (only_thickness > 0) dense.shape.thickness = only_thickness;
    const twist::ReferenceNormals truth(edgefront::shapes::sample(shape, dense));
    const Mesh mesh = edgefront::load_mesh(explain_mesh);
    for (twist::LayerRule rule : {twist::LayerRule::Facing, twist::LayerRule::Stacked}) {
      explain_pairs(mesh, truth, explain_mesh, 0, std::max(explain, 1), rule);
    }
    return 0;
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
  std::printf("GCS from the box start, %zu vertices, %zu points%s, seeds %zu-%zu, side weight %g, margin %g, thin wall %g, max re-twists %zu, %s, border ratio %g%s%s",
              vertices, points, normals ? " with exact normals" : " without normals", first_seed, first_seed + seeds - 1,
              side_weight, margin, thin_wall, max_retwists, regrow ? "cut-outs re-grown" : "cut-outs left as holes", border_ratio,
              retest_all ? ", every changed face retested" : "",
              orient_winners ? ", oriented winners" : ", plain winners (--no-orient-winners)");
  if (edge_per_thickness > 0) std::printf("; vault shells at %g x thickness mean edge (vertices and points per row)", edge_per_thickness);
  std::printf("\n\n| shape | seed | no repair: abs / comp | coverage | eval comp | judged comp (undecided) | same-orient. faces: stacked / facing | borders | with repair: abs / comp | coverage | eval comp | judged comp (undecided) | same-orient. faces: stacked / facing | borders | components | found | repaired | cut out | faces removed | re-joined | turned dropped | stacked before the removal / removed / pleats flattened: plain, repair | self-int. pairs: plain / repair (before the resolution: found / vertices smoothed / faces cut, repair run; its share of the repair run's time) | twist time share | twist CPU share |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const Case& c : cases) {
    size_t case_vertices = vertices, case_points = points;
    std::string label = c.label;
    if (edge_per_thickness > 0 && c.shape == "vault-shell") {
      case_vertices = vertices_for_edge(shape_area(c.shape, c.thickness), edge_per_thickness * c.thickness);
      case_points = std::max(points, 3 * case_vertices);
      label += " (" + std::to_string(case_vertices) + " v, " + std::to_string(case_points) + " pts)";
    }
    edgefront::shapes::SampleOptions dense;
    dense.points = 200000;
    dense.seed = 999;
    dense.shape.thickness = c.thickness;
    const edgefront::PointCloud dense_cloud = edgefront::shapes::sample(c.shape, dense);
    const twist::ReferenceNormals truth(dense_cloud);
    for (size_t seed = first_seed; seed < first_seed + seeds; ++seed) {
      edgefront::shapes::SampleOptions so;
      so.points = case_points;
      so.seed = seed;
      so.shape.thickness = c.thickness;
      edgefront::PointCloud cloud = edgefront::shapes::sample(c.shape, so);
      if (!normals) cloud.normals.clear();
      gcs::ReconstructOptions ro;
      ro.target_vertices = case_vertices;
      ro.seed = seed;
      ro.input.orient_winners = orient_winners;
      ro.input.quadric_normals = quadric;
      ro.post.project_to_samples = ro.post.fit_surface = post;
      ro.post.resolve_self_intersections = resolve_crossings;
      ro.experimental.skip_unfaced_samples = skip_unfaced;
      if (stacked_rounds >= 0) ro.post.stacked_layer_rounds = stacked_rounds;
      Consistency cons[2];
      double cover[2] = {0, 0};
      gcs::OrientationConsistency eval[2];
      size_t left[2] = {0, 0}, crossing[2] = {0, 0}, stacked[2] = {0, 0}, borders[2] = {0, 0}, components[2] = {0, 0}, stacked_removed[2] = {0, 0}, stacked_found[2] = {0, 0}, pleats[2] = {0, 0};
      gcs::TwistOperationStats stats;
      std::array<size_t, 3> resolution{};
      double crossing_share = 0;
      double share = 0, cpu_share = 0;
      for (int with = only_repair ? 1 : 0; with < 2; ++with) {
        gcs::Reconstructor rec(cloud, ro);
        std::shared_ptr<gcs::TwistOperation> op;
        if (with) {
          gcs::TwistOperationOptions to;
          to.repair.detect.reference_side_weight = side_weight;
          to.repair.detect.reference_margin = margin;
          to.repair.detect.thin_wall = thin_wall;
          if (min_flagged > 0) to.repair.detect.min_flagged_faces = min_flagged;
          to.local = local;
          to.repair.max_border_ratio = border_ratio;
          to.max_retwists = max_retwists;
          to.repair.regrow_cut_outs = regrow;
          to.rejoin_borders = rejoin;
          if (peel >= 0) to.repair.peel_flaps = peel;
          if (turned >= 0) to.repair.drop_turned_patches = static_cast<size_t>(turned);
          if (retest_all) to.repair.retest_turn_degrees = to.repair.retest_move = 0;
          op = std::make_shared<gcs::TwistOperation>(to);
          if (trace) rec.add_operation(std::make_shared<TraceOperation>("before twist"));
          rec.add_operation(op);
          if (trace) rec.add_operation(std::make_shared<TraceOperation>("after twist"));
        }
        const double c0 = cpu_seconds();
        const gcs::ReconstructResult r = rec.run();
        const double run_cpu = cpu_seconds() - c0;
        stacked_removed[with] = r.stacked_faces_removed;
        stacked_found[with] = r.stacked_faces_found;
        pleats[with] = r.stacked_pleats_flattened;
        cons[with] = consistency(r.mesh, truth);
        cover[with] = coverage(r.mesh, dense_cloud);
        eval[with] = gcs::orientation_consistency(r.mesh, dense_cloud);  // the eval branch's metric, for comparison
        left[with] = twist::count_same_orientation_layers(r.mesh);
        stacked[with] = twist::count_same_orientation_layers(r.mesh, {}, twist::LayerRule::Stacked);
        crossing[with] = gcs::count_self_intersections(r.mesh);
        if (with) {
          resolution = {r.crossing_pairs_found, r.crossing_vertices_moved, r.crossing_faces_removed};
          crossing_share = r.seconds_total > 0 ? r.seconds_crossings / r.seconds_total : 0;
        }
        if (explain > 0) {
          for (twist::LayerRule rule : {twist::LayerRule::Facing, twist::LayerRule::Stacked}) {
            explain_pairs(r.mesh, truth, c.label + (with ? " repair" : " plain"), seed, explain, rule);
          }
        }
        if (!dump.empty()) {
          edgefront::write_mesh(r.mesh, dump + "-" + c.shape + "-" + std::to_string(c.thickness).substr(0, 4) + "-s" +
                                            std::to_string(seed) + (with ? "-repair" : "-plain") + ".off");
        }
        const edgefront::MeshStats ms = edgefront::compute_stats(r.mesh);
        borders[with] = ms.border_loops;
        components[with] = ms.components;
        if (with) {
          stats = op->stats();
          share = r.seconds_total > 0 ? r.seconds_operations / r.seconds_total : 0;
          cpu_share = run_cpu > 0 ? stats.cpu_seconds / run_cpu : 0;
        }
      }
      std::printf("| %s | %zu | %.4f / %.4f | %.4f | %.4f | %.4f (%.2f) | %zu / %zu | %zu | %.4f / %.4f | %.4f | %.4f | %.4f (%.2f) | %zu / %zu | %zu | %zu | %zu | %zu | %zu | %zu | %zu | %zu | %zu / %zu / %zu, %zu / %zu / %zu | %zu / %zu (%zu / %zu / %zu; %.1f%%) | %.1f%% | %.1f%% |\n",
                  label.c_str(), seed, cons[0].absolute, cons[0].per_component, cover[0], eval[0].per_component, cons[0].judged,
                  cons[0].undecided, stacked[0], left[0], borders[0], cons[1].absolute, cons[1].per_component, cover[1], eval[1].per_component,
                  cons[1].judged, cons[1].undecided, stacked[1], left[1], borders[1], components[1],
                  stats.regions_found, stats.repairs, stats.regions_cut_out, stats.faces_removed, stats.borders_rejoined, stats.turned_faces_dropped, stacked_found[0], stacked_removed[0], pleats[0], stacked_found[1], stacked_removed[1], pleats[1], crossing[0], crossing[1], resolution[0], resolution[1], resolution[2], 100 * crossing_share, 100 * share, 100 * cpu_share);
      std::fflush(stdout);
    }
  }
  return 0;
}
