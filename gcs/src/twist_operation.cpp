#include "gcs/twist_operation.h"

#include "detail/border_rejoin.h"

#include <cmath>
#include <ctime>
#include <limits>
#include <string>

#include "edgefront/error.h"

namespace gcs {

TwistOperation::TwistOperation(TwistOperationOptions options) : options_(std::move(options)) {
  options_.repair.garbage_collect = false;  // the loop's handles are indices
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
