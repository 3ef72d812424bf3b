#include "gcs/twist_operation.h"

#include "detail/border_rejoin.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <tuple>
#include <ctime>
#include <limits>
#include <string>

#include "edgefront/error.h"
#include "edgefront/triangle_bvh.h"

namespace gcs {

TwistOperation::TwistOperation(TwistOperationOptions options) : options_(std::move(options)) {
  options_.repair.garbage_collect = false;  // the loop's handles are indices
  // TEMP ablation (issue 26 goal 3 attribution)
  if (const char* e = std::getenv("EF_TW_RETWISTS")) options_.max_retwists = std::stoul(e);
  if (const char* e = std::getenv("EF_TW_SHARE")) options_.repair.cuts.min_cut_piece_share = std::stod(e);
  if (const char* e = std::getenv("EF_TW_PEEL")) options_.repair.experimental.peel_flaps = std::stoi(e);
  if (const char* e = std::getenv("EF_TW_TURNED")) options_.repair.experimental.drop_turned_patches = std::stoul(e);
  if (const char* e = std::getenv("EF_TW_MINCOMP")) options_.repair.cuts.min_component_faces = std::stoul(e);
  if (const char* e = std::getenv("EF_TW_REGROW")) options_.repair.experimental.regrow_cut_outs = std::stoi(e) != 0;
  if (!(options_.max_border_ratio_without_normals >= 0) || !std::isfinite(options_.max_border_ratio_without_normals)) {
    throw edgefront::InvalidInput("twist operation: max_border_ratio_without_normals must be finite and >= 0, got " +
                                  std::to_string(options_.max_border_ratio_without_normals));
  }
}

TwistOperation::~TwistOperation() = default;

const std::vector<std::pair<edgefront::VertexHandle, edgefront::VertexHandle>>& TwistOperation::cuts() const {
  static const std::vector<std::pair<edgefront::VertexHandle, edgefront::VertexHandle>> none;
  return repairer_ ? repairer_->cuts() : none;
}

// Renumbering (operation.h): twist::TwistRepairer keeps state by handle index (cut pairs, face
// snapshots, face grid); it translates that state itself, so the loop may always renumber.
bool TwistOperation::can_follow_renumbering() const { return true; }
void TwistOperation::on_renumbered(const edgefront::Mesh& mesh, const MeshRenumbering& map) {
  if (repairer_) repairer_->renumber(mesh, map.vertex, map.face);
}

OperationResult TwistOperation::apply(edgefront::Mesh& mesh, const ChangeSet& changed, const OperationContext& context) {
  const std::clock_t cpu0 = std::clock();
  struct AddCpu {
    double& total;
    std::clock_t start;
    ~AddCpu() { total += static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC; }
  } add_cpu{stats_.cpu_seconds, cpu0};
  OperationResult result;
  ++stats_.calls;
  if (!reference_checked_) {
    reference_checked_ = true;
    // The loop's query subsample of a large cloud when it has one (OperationContext::query_points).
    const edgefront::PointCloud& samples = context.query_points ? *context.query_points : context.points;
    if (options_.use_point_normals && samples.has_normals()) {
      reference_ = std::make_unique<twist::ReferenceNormals>(samples);
    }
  }
  if (!repairer_) {
    twist::RepairOptions o = options_.repair;
    o.detect.reference = reference_.get();
    if (!reference_) o.cuts.max_border_ratio = options_.max_border_ratio_without_normals;
    repairer_ = std::make_unique<twist::TwistRepairer>(o, options_.max_retwists);
  }
  if (context.live_vertices < options_.min_vertices && !context.final_call) return result;
  if (changed.faces.empty() && !context.final_call) return result;
  // Re-joins orientation-compatible borders (see TwistOperationOptions::rejoin_borders).
  auto rejoin = [&]() -> size_t {
    if (!options_.rejoin_borders || context.points.size() == 0) return 0;
    if (!cloud_index_) cloud_index_ = std::make_unique<edgefront::PointIndex>(context.points.points);
    const detail::CloudQuery cloud = [&](const edgefront::Vec3& p) -> detail::CloudHit {
      const edgefront::PointIndex::Neighbor nb = cloud_index_->nearest(p);
      const double nan = std::numeric_limits<double>::quiet_NaN();
      return {std::sqrt(nb.distance2), context.points.has_normals() ? context.points.normals[nb.index] : edgefront::Vec3(nan, nan, nan)};
    };
    // Stricter than the loop's own merging (chains within 2 mean edges, strips within 2.25 mean
    // edges of the points): on a thin shell a looser join bridges the two walls and re-twists
    // (bench/results/twist-vaults.md).
    const detail::RejoinResult j = detail::rejoin_borders(mesh, cloud, {context.mean_edge_length, 0.5 * context.mean_edge_length, 1.0});
    stats_.borders_rejoined += j.strips + j.loops_merged;
    return j.strips + j.loops_merged;
  };
  // TEMP trace: faces (by exact corner positions) removed by this call, and their area.
  static const bool trace = std::getenv("EF_TW_TRACE") != nullptr;
  using Key = std::tuple<double, double, double>;
  std::map<Key, double> before_faces;
  auto face_key = [&](edgefront::FaceHandle f, double& area) {
    edgefront::Vec3 c(0, 0, 0), p[3];
    int i = 0;
    for (auto v : mesh.fv_range(f)) p[i++] = mesh.point(v);
    c = (p[0] + p[1] + p[2]) / 3.0;
    area = 0.5 * ((p[1] - p[0]) % (p[2] - p[0])).norm();
    return Key{c[0], c[1], c[2]};
  };
  auto opposed_area = [&]() {
    if (!reference_) return 0.0;
    double a = 0;
    for (auto f : mesh.faces()) {
      edgefront::Vec3 p[3];
      int i = 0;
      for (auto v : mesh.fv_range(f)) p[i++] = mesh.point(v);
      const edgefront::Vec3 n = (p[1] - p[0]) % (p[2] - p[0]);
      const edgefront::Vec3 c = (p[0] + p[1] + p[2]) / 3.0;
      const edgefront::Vec3 r = reference_->nearest_normal(c);
      if (n.norm() > 0 && (n | r) < -0.3 * n.norm() * r.norm()) a += 0.5 * n.norm();
    }
    return a;
  };
  const double opposed_before = trace ? opposed_area() : 0.0;
  // TEMP: which samples lie within one mean edge of the mesh
  auto covered = [&]() {
    std::vector<char> out(context.points.size(), 0);
    std::vector<edgefront::Triangle> tris;
    for (auto f : mesh.faces()) {
      edgefront::Vec3 p[3];
      int i = 0;
      for (auto v : mesh.fv_range(f)) p[i++] = mesh.point(v);
      tris.emplace_back(std::array<edgefront::Vec3, 3>{p[0], p[1], p[2]});
    }
    if (tris.empty()) return out;
    const edgefront::TriangleBvh bvh(std::move(tris));
    const double d2 = std::pow(0.01 * context.bbox_diagonal, 2);
    for (size_t k = 0; k < context.points.size(); ++k) out[k] = bvh.nearest(context.points.points[k]).dist2 <= d2;
    return out;
  };
  const std::vector<char> covered_before = trace ? covered() : std::vector<char>{};
  if (trace) {
    for (auto f : mesh.faces()) {
      double a = 0;
      const Key k = face_key(f, a);
      before_faces[k] = a;
    }
  }
  // The final call re-joins first, so that its full repair (and its flap peeling) sees the joins.
  const size_t joined_first = context.final_call && !repairer_->cuts().empty() ? rejoin() : 0;
  const twist::RepairReport r =
      context.final_call ? repairer_->finish(mesh)
                         : repairer_->repair_changed(mesh, changed.faces, options_.local ? context.mean_edge_length : 0.0);
  stats_.regions_found += r.regions_found;
  stats_.faces_tested += r.detect_stats.faces_tested;
  stats_.repairs += r.repairs;
  stats_.regions_cut_out += r.regions_cut_out;
  stats_.faces_flipped += r.faces_flipped;
  stats_.faces_removed += r.faces_removed;
  stats_.regions_scattered += r.regions_scattered;
  stats_.turned_faces_dropped += r.turned_faces_removed + r.turned_faces_collapsed + r.turned_faces_straightened;
  stats_.components_flipped += r.components_flipped;
  stats_.non_orientable = stats_.non_orientable || r.non_orientable;
  if (!context.final_call && (r.repairs > 0 || r.faces_removed > 0)) rejoin();
  if (trace && (r.repairs > 0 || r.faces_removed > 0 || context.final_call)) {
    double total = 0, removed = 0;
    size_t n_removed = 0;
    std::map<Key, double> after;
    for (auto f : mesh.faces()) {
      double a = 0;
      after[face_key(f, a)] = a;
      total += a;
    }
    const std::vector<char> covered_after = covered();
    size_t lost = 0, gained = 0;
    for (size_t k = 0; k < covered_after.size(); ++k) {
      lost += covered_before[k] && !covered_after[k];
      gained += !covered_before[k] && covered_after[k];
    }
    std::fprintf(stderr, "TWCOV batch %zu final %d lost %zu gained %zu of %zu samples cutouts %zu\n", context.batch,
                 int(context.final_call), lost, gained, covered_after.size(), r.regions_cut_out);
    for (const auto& [k, a] : before_faces) {
      if (!after.count(k)) {
        removed += a;
        ++n_removed;
        std::fprintf(stderr, "TWREM %zu %g %g %g %g\n", context.batch, std::get<0>(k), std::get<1>(k), std::get<2>(k), a);
      }
    }
    std::fprintf(stderr, "TWCALL batch %zu final %d live %zu repairs %zu cutout %zu flipped %zu removed_faces %zu (traced %zu, area %g of %g) opposed %g -> %g scattered %zu flaps %zu turned %zu\n",
                 context.batch, int(context.final_call), context.live_vertices, r.repairs, r.regions_cut_out, r.faces_flipped,
                 r.faces_removed, n_removed, removed, total, opposed_before, opposed_area(), r.regions_scattered, r.flap_faces_removed, r.turned_faces_removed);
    for (const auto& rec : r.records) {
      std::fprintf(stderr, "TWREC batch %zu region %zu flipped %zu other %zu region_side %d removed %d tiny %zu joined %zu kept %zu\n", context.batch,
                   rec.region_faces, rec.flipped_faces, rec.other_side_faces, int(rec.flipped_region), int(rec.removed), rec.tiny_faces_removed, rec.tiny_faces_joined, rec.small_pieces_kept);
    }
  }
  result.mesh_changed = joined_first > 0 || r.repairs > 0 || r.components_flipped > 0 || r.faces_removed > 0 ||
                        r.turned_faces_collapsed > 0 || r.turned_faces_straightened > 0;
  if (result.mesh_changed) {
    result.summary = std::to_string(r.repairs) + " twist(s) repaired (" + std::to_string(r.faces_flipped) + " faces flipped, " +
                     std::to_string(r.regions_cut_out) + " cut out), " + std::to_string(r.components_flipped) +
                     " component(s) flipped globally";
  }
  return result;
}

}  // namespace gcs
