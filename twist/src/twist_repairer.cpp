// TwistRepairer: the incremental repair (the refinement loop's), which re-tests only the faces that
// changed enough and cuts out a region that twists again at the same place.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "detail/geometry.h"
#include "detail/repair_steps.h"
#include "edgefront/error.h"
#include "twist/repair.h"

namespace twist {

using edgefront::FaceHandle;
using edgefront::InvalidInput;
using edgefront::Mesh;
using edgefront::Vec3;
using edgefront::VertexHandle;

using detail::DupList;
using detail::repair_impl;

TwistRepairer::TwistRepairer(RepairOptions options, size_t max_retwists)
    : options_(std::move(options)), max_retwists_(max_retwists) {}

std::vector<FaceHandle> TwistRepairer::retest(const Mesh& mesh, const std::vector<FaceHandle>& changed, double mean_edge_length,
                                              std::vector<std::pair<int, Snapshot>>& current) const {
  current.clear();
  const bool all = options_.retest_turn_degrees == 0 && options_.retest_move == 0;
  const double min_cos = std::cos(options_.retest_turn_degrees * std::numbers::pi / 180.0);
  const double max_move2 = std::pow(options_.retest_move * mean_edge_length, 2);
  std::vector<FaceHandle> out;
  for (FaceHandle f : changed) {
    if (!edgefront::is_live(mesh, f)) continue;
    const FaceGeometry g = face_geometry(mesh, f);
    const Snapshot s{g.normal, g.centre, true};
    const size_t k = static_cast<size_t>(f.idx());
    bool test = all || k >= tested_.size() || !tested_[k].valid;
    if (!test) {
      const Snapshot& t = tested_[k];
      const Vec3 moved = s.centre - t.centre;
      const double across = OpenMesh::dot(t.normal, moved);
      test = OpenMesh::dot(t.normal, s.normal) < min_cos || across * across > max_move2 ||
             moved.sqrnorm() > 16 * max_move2;
    }
    if (!test) continue;
    out.push_back(f);
    current.emplace_back(f.idx(), s);
  }
  return out;
}

RepairReport TwistRepairer::repair_changed(Mesh& mesh, const std::vector<FaceHandle>& changed, double mean_edge_length) {
  ++calls_;
  RepairOptions o = options_;
  std::vector<std::pair<int, Snapshot>> snapshots;
  const bool local = mean_edge_length > 0 && std::isfinite(mean_edge_length);
  o.detect.restrict_to = local ? retest(mesh, changed, mean_edge_length, snapshots) : changed;
  if (local) {
    // Local mode: keep the face grid current (a rebuild only when the edge length drifted by 2x).
    o.detect.mean_edge_length = mean_edge_length;
    const double cell = o.detect.radius > 0 ? o.detect.radius : 2.0 * mean_edge_length;
    if (grid_.cell() == 0 || grid_.cell() > 2 * cell || grid_.cell() < cell / 2) {
      grid_.rebuild(mesh, cell);
    } else {
      grid_.update(mesh, changed);
      grid_.update_new(mesh);
    }
  }
  o.detect.audit_offset = calls_ * 7919;  // a different audit sample every call
  o.global_orientation = false;
  auto rule = [this](const Mesh& m, const TwistRegion& region) {
    Vec3 centre(0, 0, 0);
    for (FaceHandle f : region.faces) centre += detail::centroid(detail::face_points(m, f));
    centre /= static_cast<double>(region.faces.size());
    double radius = 0;
    for (FaceHandle f : region.faces) radius = std::max(radius, (detail::centroid(detail::face_points(m, f)) - centre).norm());
    for (Place& p : places_) {
      // The same place: centres within half the larger radius and radii within a factor 2 (a
      // small region near a large earlier one is a different place).
      const double lo = std::min(p.radius, radius), hi = std::max(p.radius, radius);
      if ((p.centre - centre).norm() <= 0.5 * hi && lo >= 0.5 * hi) {
        ++p.count;
        return p.count > max_retwists_;
      }
    }
    places_.push_back(Place{centre, radius, 1});
    return false;
  };
  RepairReport report = repair_impl(mesh, o, rule, cuts_, grid_.cell() > 0 && o.detect.mean_edge_length > 0 ? &grid_ : nullptr);
  // Remember what the tested faces looked like; when the repairs were capped, regions may be
  // left over: everything is tested again next time.
  if (!report.capped) {
    for (const auto& [idx, snap] : snapshots) {
      if (static_cast<size_t>(idx) >= tested_.size()) tested_.resize(static_cast<size_t>(idx) + 1);
      tested_[static_cast<size_t>(idx)] = snap;
    }
  }
  return report;
}

void TwistRepairer::renumber(const Mesh& mesh, const std::vector<int>& vertex_map, const std::vector<int>& face_map) {
  auto mapped = [&](const std::vector<int>& map, size_t old, size_t live_count, const char* what) {
    if (old >= map.size()) {
      throw InvalidInput(std::string("twist::TwistRepairer::renumber: the ") + what + " map has " + std::to_string(map.size()) +
                         " entries, but the repairer holds " + what + " " + std::to_string(old));
    }
    const int to = map[old];
    if (to >= static_cast<int>(live_count)) {
      throw InvalidInput(std::string("twist::TwistRepairer::renumber: ") + what + " " + std::to_string(old) + " maps to " +
                         std::to_string(to) + ", beyond the renumbered mesh");
    }
    return to;
  };
  std::vector<Snapshot> tested;
  for (size_t i = 0; i < tested_.size(); ++i) {
    if (!tested_[i].valid) continue;
    const int to = mapped(face_map, i, mesh.n_faces(), "face");
    if (to < 0) continue;
    if (static_cast<size_t>(to) >= tested.size()) tested.resize(static_cast<size_t>(to) + 1);
    tested[static_cast<size_t>(to)] = tested_[i];
  }
  DupList cuts;
  for (const auto& [copy, original] : cuts_) {
    const int c = mapped(vertex_map, static_cast<size_t>(copy.idx()), mesh.n_vertices(), "vertex");
    const int o = mapped(vertex_map, static_cast<size_t>(original.idx()), mesh.n_vertices(), "vertex");
    if (c >= 0 && o >= 0) cuts.emplace_back(VertexHandle(c), VertexHandle(o));
  }
  tested_ = std::move(tested);
  cuts_ = std::move(cuts);
  if (grid_.cell() > 0) grid_.rebuild(mesh, grid_.cell());
}

RepairReport TwistRepairer::finish(Mesh& mesh) {
  RepairReport r = repair_impl(mesh, options_, nullptr, cuts_);
  grid_ = FaceGrid();  // the final repair may garbage-collect: handles change
  tested_.clear();
  return r;
}

}  // namespace twist
