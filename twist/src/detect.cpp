#include "twist/detect.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <deque>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <tuple>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

#include "detail/detect_steps.h"
#include "detail/geometry.h"
#include "edgefront/error.h"
#include "edgefront/geometry.h"
#include "edgefront/minimal_distance_front.h"
#include "edgefront/minimal_edge_front.h"
#include "edgefront/parallel.h"
#include "edgefront/point_index.h"

namespace twist {

using edgefront::FaceHandle;
using edgefront::HalfedgeHandle;
using edgefront::InvalidInput;
using edgefront::Mesh;
using edgefront::Vec3;
using edgefront::VertexHandle;

const char* to_string(EvidenceKind kind) {
  switch (kind) {
    case EvidenceKind::Reference: return "reference";
    case EvidenceKind::FacingLayer: return "facing-layer";
    case EvidenceKind::FoldedEdge: return "folded-edge";
    case EvidenceKind::SelfIntersection: return "self-intersection";
  }
  return "unknown";
}

namespace {

void check_range(bool ok, const std::string& what) {
  if (!ok) throw InvalidInput("twist::detect: option " + what);
}

void validate_options(const Mesh& mesh, const DetectOptions& o) {
  check_range(std::isfinite(o.radius) && o.radius >= 0, "radius must be finite and >= 0 (0 = automatic)");
  check_range(std::isfinite(o.experimental.surface_factor) && o.experimental.surface_factor >= 1,
              "experimental.surface_factor must be finite and >= 1");
  check_range(o.experimental.parallel_cos >= 0 && o.experimental.parallel_cos <= 1,
              "experimental.parallel_cos must lie in [0, 1]");
  check_range(o.experimental.facing_cos > 0 && o.experimental.facing_cos <= 1,
              "experimental.facing_cos must lie in (0, 1]");
  check_range(o.experimental.fold_cos >= -1 && o.experimental.fold_cos <= 0,
              "experimental.fold_cos must lie in [-1, 0]");
  check_range(o.regions.grow_levels >= 1 && o.regions.grow_levels <= 64,
              "regions.grow_levels must lie in [1, 64]");
  check_range(o.regions.min_flagged_faces >= 1, "regions.min_flagged_faces must be >= 1");
  check_range(o.regions.min_flagged_share >= 0 && o.regions.min_flagged_share <= 1,
              "regions.min_flagged_share must lie in [0, 1]");
  check_range(o.vote.reference_cos >= -1 && o.vote.reference_cos <= 1,
              "vote.reference_cos must lie in [-1, 1]");
  check_range(o.experimental.reference_side_weight == 0 ||
                  (o.experimental.reference_side_weight >= 1 && o.experimental.reference_side_weight <= 100),
              "experimental.reference_side_weight must be 0 or lie in [1, 100]");
  check_range(std::isfinite(o.mean_edge_length) && o.mean_edge_length >= 0, "mean_edge_length must be finite and >= 0");
  check_range(o.experimental.reference_margin >= 1 && o.experimental.reference_margin <= 100,
              "experimental.reference_margin must lie in [1, 100]");
  check_range(o.vote.thin_wall >= 0 && o.vote.thin_wall <= 4, "vote.thin_wall must lie in [0, 4]");
  if (o.incremental.restrict_to) {
    for (FaceHandle f : *o.incremental.restrict_to) {
      if (!edgefront::is_live(mesh, f)) {
        throw InvalidInput("twist::detect: incremental.restrict_to names face " + std::to_string(f.idx()) +
                           ", which is not a live face of the mesh");
      }
    }
  }
}

/// Per-face geometry and the evidence tests.
class Detector {
 public:
  /// `quick`: no layer is looked for in front of a face the reference confirms (see `test`).
  Detector(const Mesh& mesh, const DetectOptions& o, bool quick)
      : quick_(quick),
        collect_behind_(o.incremental.restrict_to.has_value()),
        mesh_(mesh),
        o_(o),
        mdf_(mesh),
        grid_(o.incremental.face_grid) {
    if (!grid_) {
      // Full mode (or no incremental index given): a k-d tree over every live face's centroid.
      geo_.resize(mesh.n_faces());
      has_geo_.assign(mesh.n_faces(), 0);
      std::vector<Vec3> centers;
      for (FaceHandle f : mesh.faces()) {
        live_.push_back(f);
        centers.push_back(geo(f).centre);
      }
      index_ = std::make_unique<edgefront::PointIndex>(std::move(centers));
    }
    scan_intersections_ = o.self_intersections;
    mean_edge_ = o.mean_edge_length > 0 ? o.mean_edge_length : detail::mean_edge_length(mesh);
    if (!(mean_edge_ > 0)) throw InvalidInput("twist::detect: every edge of the mesh has zero length");
    radius_ = o.radius > 0 ? o.radius : 2.0 * mean_edge_;
    mdf_.set_settled_callback([this](VertexHandle v, double d, const Vec3&) {
      ++stats.vertices_settled;
      mark_near(v.idx(), d);
    });
  }

  /// The reference's verdict on f, asked once per face and detection.
  int vote(FaceHandle f) {
    const auto it = votes_.find(f.idx());
    if (it != votes_.end()) return it->second;
    const FaceGeometry& g = geo(f);
    return votes_.emplace(f.idx(), reference_vote(*o_.reference, o_, g.centre, g.normal, mean_edge_)).first->second;
  }
  /// Geometry of a face: the face grid's (kept current by the caller) or computed on first use.
  const FaceGeometry& geo(FaceHandle f) {
    if (grid_) {
      if (const FaceGeometry* g = grid_->geometry(f)) return *g;
      const auto it = extra_geo_.find(f.idx());
      if (it != extra_geo_.end()) return it->second;
      return extra_geo_.emplace(f.idx(), face_geometry(mesh_, f)).first->second;
    }
    const size_t i = static_cast<size_t>(f.idx());
    if (!has_geo_[i]) {
      geo_[i] = face_geometry(mesh_, f);
      has_geo_[i] = 1;
    }
    return geo_[i];
  }
  /// Do the faces share a vertex?
  bool shares_vertex(FaceHandle f, FaceHandle g) {
    const std::array<int, 3> a = geo(f).vertices;
    for (int b : geo(g).vertices) {
      if (b == a[0] || b == a[1] || b == a[2]) return true;
    }
    return false;
  }
  std::array<Vec3, 3> points(FaceHandle f) {
    const std::array<int, 3>& v = geo(f).vertices;
    return {mesh_.point(VertexHandle(v[0])), mesh_.point(VertexHandle(v[1])), mesh_.point(VertexHandle(v[2]))};
  }
  const Vec3& normal(FaceHandle f) { return geo(f).normal; }
  /// Do f and g (same orientation) cover each other along their mean normal (`LayerRule::Stacked`)?
  bool stacked_on(FaceHandle f, FaceHandle g) {
    return detail::stacked_layers(points(f), normal(f), geo(f).longest, points(g), normal(g), geo(g).longest);
  }
  const Vec3& center(FaceHandle f) { return geo(f).centre; }

  /// How far the self-intersection scan of f looks: a partner's centroid lies within the sum of
  /// the two longest edges; without incremental mode only partners with no longer edges are
  /// looked for (see `scan_intersections`), in incremental mode edges up to max(lf, 2 mean edges).
  double scan_radius(FaceHandle f) {
    const double lf = geo(f).longest;
    return collect_behind_ ? lf + std::max(lf, 2 * mean_edge_) : 2 * lf;
  }
  /// Live faces whose centroid lies within max(radius, scan radius) of f's centroid, in
  /// increasing index order; one query per face serves the layer, confirmation and
  /// self-intersection tests (the last face's answer is kept).
  const std::vector<FaceHandle>& around(FaceHandle f) {
    const double r = std::max(radius_, scan_intersections_ ? scan_radius(f) : 0.0);
    if (around_of_ == f && around_radius_ >= r) return around_;
    around_of_ = f;
    around_radius_ = r;
    around_.clear();
    const Vec3& p = center(f);
    if (grid_) {
      grid_->query(mesh_, p, r, around_);
    } else {
      index_->radius_search(p, r, near_);
      for (size_t k : near_) around_.push_back(live_[k]);
    }
    return around_;
  }

  /// Evaluates the evidence of one face; returns true and fills `ev` when it is flagged.
  bool test(FaceHandle f, Evidence& ev) {
    ++stats.faces_tested;
    tested_.emplace(f.idx(), 1);
    const Vec3 nf = normal(f);
    const Vec3 cf = center(f);
    if (nf.sqrnorm() == 0) return false;  // degenerate: no orientation to judge
    ev = Evidence{EvidenceKind::Reference, f, FaceHandle()};
    if (o_.reference && vote(f) < 0) return true;
    // (The quick pass looks for no layer in front of a face the reference confirms: see
    // `detect_regions`.)
    const FaceHandle layer = quick_ && o_.reference && vote(f) > 0 ? FaceHandle() : far_layer(f, 1.0);
    if (layer.is_valid()) {
      // Two layers facing each other: a wall turned inside out. Two layers pointing the same
      // way: f points into the other's back, unless f itself sits back to back with a layer of
      // its own wall, which makes the layer in front a stray (a fold band left over the face).
      const Vec3 d = center(layer) - cf;
      const bool mutual = OpenMesh::dot(normal(layer), d) < 0;
      if (mutual || !confirmed(f)) {
        ev = Evidence{EvidenceKind::FacingLayer, f, layer};
        return true;
      }
      ambiguous_.emplace(f.idx(), 1);  // evidence both ways: neither flagged nor confirmed
    }
    for (HalfedgeHandle h : mesh_.fh_range(f)) {
      const FaceHandle g = mesh_.opposite_face_handle(h);
      if (g.is_valid() && OpenMesh::dot(nf, normal(g)) <= o_.experimental.fold_cos) {
        ev = Evidence{EvidenceKind::FoldedEdge, f, g};
        return true;
      }
    }
    if (scan_intersections_) {
      scan_intersections(f);
      const auto it = si_partner_.find(f.idx());
      if (it != si_partner_.end()) {
        ev = Evidence{EvidenceKind::SelfIntersection, f, FaceHandle(it->second)};
        return true;
      }
    }
    return false;
  }

  /// Positive evidence that f is oriented right: it agrees with its reference normal, or (without
  /// reference) a layer with the opposite normal lies right behind it within the radius (back to
  /// back, as the two sides of a thin wall; near or far along the surface).
  bool confirmed(FaceHandle f) {
    const Vec3 nf = normal(f);
    if (nf.sqrnorm() == 0) return false;
    const Vec3 cf = center(f);
    if (o_.reference) return vote(f) > 0;
    for (FaceHandle g : around(f)) {
      if (g == f) continue;
      const Vec3 d = center(g) - cf;
      const double dist = d.norm();
      if (dist > 0 && dist <= radius_ && -OpenMesh::dot(nf, d) >= o_.experimental.facing_cos * dist &&
          OpenMesh::dot(nf, normal(g)) <= -o_.experimental.parallel_cos && !shares_vertex(f, g)) {
        return true;
      }
    }
    return false;
  }

  /// Confirmed and without a layer in front: safe to leave out of a region. Faces not tested yet
  /// are tested here.
  bool right(FaceHandle f) {
    if (!tested_.count(f.idx())) {
      Evidence ev;
      if (test(f, ev)) return false;
    }
    return !ambiguous_.count(f.idx()) && confirmed(f);
  }

  bool ambiguous(FaceHandle f) const { return ambiguous_.count(f.idx()) > 0; }

  /// Marks the candidate layers with vertex v that a path of length d reaches within their limit.
  void mark_near(int v, double d) {
    const auto it = cand_of_vertex_.find(v);
    if (it == cand_of_vertex_.end()) return;
    for (const auto& [i, limit] : it->second) {
      if (d <= limit && !near_flag_[i]) {
        near_flag_[i] = 1;
        --unresolved_;
      }
    }
  }

  /// Shortest paths from f's centroid through one of its corners and then along edges (a bounded
  /// Dijkstra), up to `reach`, marking candidate layers near; stops once none is unresolved.
  void edge_paths(FaceHandle f, double reach) {
    path_length_.clear();
    path_heap_.clear();
    const auto offer = [&](int v, double d) {
      if (d > reach) return;
      const auto [it, fresh] = path_length_.try_emplace(v, d);
      if (!fresh) {
        if (d >= it->second) return;
        it->second = d;
      }
      path_heap_.emplace_back(d, v);
      std::push_heap(path_heap_.begin(), path_heap_.end(), std::greater<>());
    };
    const Vec3 c = center(f);
    for (int v : geo(f).vertices) offer(v, (mesh_.point(VertexHandle(v)) - c).norm());
    while (unresolved_ > 0 && !path_heap_.empty()) {
      std::pop_heap(path_heap_.begin(), path_heap_.end(), std::greater<>());
      const auto [d, v] = path_heap_.back();
      path_heap_.pop_back();
      if (d > path_length_[v]) continue;  // a stale entry
      mark_near(v, d);
      const VertexHandle vh(v);
      for (VertexHandle w : mesh_.vv_range(vh)) offer(w.idx(), d + (mesh_.point(w) - mesh_.point(vh)).norm());
    }
  }

  /// The nearest roughly parallel face within the radius on the side `side` (+1: in front of f,
  /// -1: behind) that is far along the surface, or an invalid handle.
  /// `stacked` (with `same_orientation_only`): only partners stacked on f (`LayerRule::Stacked`).
  FaceHandle far_layer(FaceHandle f, double side, bool same_orientation_only = false, bool stacked = false) {
    const Vec3 nf = normal(f);
    const Vec3 cf = center(f);
    layers_.clear();
    for (FaceHandle g : around(f)) {
      if (g == f) continue;
      const Vec3 d = center(g) - cf;
      const double dist = d.norm();
      if (!(dist > 0 && dist <= radius_)) continue;
      const double along = OpenMesh::dot(nf, d);
      const double cos_ng = OpenMesh::dot(nf, normal(g));
      const bool layer = side * along >= o_.experimental.facing_cos * dist &&
                         (same_orientation_only ? cos_ng : std::abs(cos_ng)) >= o_.experimental.parallel_cos;
      // Behind f with the same orientation: g may point at f's back, so its evidence changed with f.
      const bool behind = !layer && collect_behind_ && side > 0 && !same_orientation_only &&
                          -along >= o_.experimental.facing_cos * dist &&
                          cos_ng >= o_.experimental.parallel_cos;
      if (!layer && !behind) continue;
      if (shares_vertex(f, g)) continue;
      if (layer && stacked && !stacked_on(f, g)) continue;
      if (layer) {
        layers_.emplace_back(dist, g);
      } else if (!o_.reference || vote(g) == 0) {
        behind_.push_back(g);  // (a reference that decides g either way is not changed by f)
      }
    }
    if (layers_.empty()) return FaceHandle();
    // Far along the surface? One bounded distance front from f's centroid answers for all.
    std::sort(layers_.begin(), layers_.end(), [](const auto& a, const auto& b) {
      return a.first < b.first || (a.first == b.first && a.second.idx() < b.second.idx());
    });
    double reach = 0;
    cand_of_vertex_.clear();
    near_flag_.assign(layers_.size(), 0);
    unresolved_ = layers_.size();
    // A layer is near when the surface distance to one of its vertices is within this limit.
    const auto limit_of = [&](size_t i) {
      return o_.experimental.surface_factor * layers_[i].first + mean_edge_;
    };
    for (size_t i = 0; i < layers_.size(); ++i) {
      reach = std::max(reach, limit_of(i));
      for (int v : geo(layers_[i].second).vertices) cand_of_vertex_[v].emplace_back(i, limit_of(i));
    }
    // Paths along edges first (from f's centroid straight to a corner inside f, then along mesh
    // edges) bound the geodesic distance from above: a layer with a vertex reached within its
    // limit that way is near, and needs no distance front (which costs several times more).
    edge_paths(f, reach);
    if (unresolved_ == 0) return FaceHandle();
    reach = 0;
    for (size_t i = 0; i < layers_.size(); ++i) {
      if (!near_flag_[i]) reach = std::max(reach, limit_of(i));
    }
    ++stats.distance_queries;
    edgefront::DistanceOptions dopt;
    dopt.max_distance = reach;
    dopt.directions = false;
    dopt.track_front = false;  // only the distances are read: the same ones, about 10% cheaper
    mdf_.reset(std::vector<edgefront::SurfacePoint>{edgefront::SurfacePoint{f, {1.0 / 3, 1.0 / 3, 1.0 / 3}}}, dopt);
    // Stop as soon as every candidate layer turned out to be near along the surface.
    while (unresolved_ > 0 && mdf_.step()) {
    }
    for (size_t i = 0; i < layers_.size(); ++i) {
      if (!near_flag_[i]) return layers_[i].second;
    }
    return FaceHandle();
  }

  /// Finds the faces intersecting f that have no longer edge than f (ties: lower index), and
  /// records both sides: a pair is found from its face with the longer edge, so scanning every
  /// face finds every pair. In incremental mode longer faces are taken too (up to twice the mean
  /// edge, or f's longest edge), since the longer face of a pair may not be tested.
  void scan_intersections(FaceHandle f) {
    if (!scanned_.emplace(f.idx(), 1).second) return;
    const double lf = geo(f).longest;
    const Vec3 cf = center(f);
    const double reach = scan_radius(f);
    for (FaceHandle g : around(f)) {
      if (g == f) continue;
      const FaceGeometry& gg = geo(g);
      const double lg = gg.longest;
      const bool longer = lg > lf || (lg == lf && g.idx() < f.idx());
      if (longer && (!collect_behind_ || scanned_.count(g.idx()))) continue;  // g's own scan finds the pair
      const Vec3 d = gg.centre - cf;
      const double dist = d.norm();
      if (dist > lf + lg || dist > reach) continue;
      // Every corner lies within the longest edge of its centroid: a centroid farther than that
      // from the other's plane puts the whole triangle on one side.
      if (std::abs(OpenMesh::dot(normal(f), d)) > lg || std::abs(OpenMesh::dot(gg.normal, d)) > lf) continue;
      // Pairs sharing a vertex are left to the fold test (tested before); testing them too (the
      // kernel's test handles them, as gcs::count_self_intersections does) lowered the twist
      // operation's result on TwistOperation.EndToEndVaultShellFromABox from >= 0.94 to 0.92.
      // Crossings only: faces touching along an unwelded seam (a repair's cut) are no twist.
      if (shares_vertex(f, g)) continue;
      if (edgefront::triangle_contact(edgefront::Triangle(points(f), geo(f).vertices),
                                      edgefront::Triangle(points(g), gg.vertices)) == edgefront::TriangleContact::Crossing) {
        si_partner_.emplace(f.idx(), g.idx());
        si_partner_.emplace(g.idx(), f.idx());
        if (si_log) si_log->emplace_back(f.idx(), g.idx());
      }
    }
  }

  /// Faces found right behind tested faces with the same orientation (they point at the tested
  /// face's back) since the last call; collected only in incremental mode.
  std::vector<FaceHandle> take_behind() {
    std::vector<FaceHandle> out;
    out.swap(behind_);
    return out;
  }

  /// Parallel whole-mesh detection (`detect_pass`): when set, `scan_intersections` also appends
  /// every pair it finds, (f, g) in the order found.
  std::vector<std::pair<int, int>>* si_log = nullptr;

  /// Takes the pairs the detectors of all chunks found, in chunk order, as if this detector had
  /// scanned every face in face order (the first partner found for a face is kept), and marks
  /// every face of `faces` scanned.
  void adopt_scans(const std::vector<std::vector<std::pair<int, int>>>& logs, const std::vector<FaceHandle>& faces) {
    si_partner_.clear();
    for (const auto& log : logs) {
      for (const auto& pair : log) {
        si_partner_.emplace(pair.first, pair.second);
        si_partner_.emplace(pair.second, pair.first);
      }
    }
    for (FaceHandle f : faces) scanned_.emplace(f.idx(), 1);
  }
  /// Takes the faces another detector tested, and those it found ambiguous, with its statistics.
  void adopt_tests(const Detector& other) {
    tested_.insert(other.tested_.begin(), other.tested_.end());
    ambiguous_.insert(other.ambiguous_.begin(), other.ambiguous_.end());
    stats.faces_tested += other.stats.faces_tested;
    stats.distance_queries += other.stats.distance_queries;
    stats.vertices_settled += other.stats.vertices_settled;
  }

  /// Whether `test` looks for self-intersections (`DetectOptions::self_intersections`, and in
  /// incremental mode only once the candidates are tested: see `detect_regions`).
  void set_scan_intersections(bool on) { scan_intersections_ = on && o_.self_intersections; }

  DetectStats stats;

 private:
  bool scan_intersections_ = false;
  bool quick_ = false;
  bool collect_behind_ = false;
  std::vector<FaceHandle> behind_;
  std::unordered_map<int, int> si_partner_;
  std::unordered_map<int, char> ambiguous_, tested_;
  std::unordered_map<int, char> scanned_;
  std::vector<FaceHandle> around_;
  FaceHandle around_of_;
  double around_radius_ = 0;
  const Mesh& mesh_;
  const DetectOptions& o_;
  edgefront::MinimalDistanceFront mdf_;
  std::unordered_map<int, double> path_length_;     // edge_paths: best length per vertex
  std::vector<std::pair<double, int>> path_heap_;   // edge_paths: (length, vertex), a min-heap
  const FaceGrid* grid_;
  std::vector<FaceGeometry> geo_;  ///< without a face grid: by face index
  std::vector<char> has_geo_;
  std::unordered_map<int, FaceGeometry> extra_geo_;  ///< with a face grid: faces it does not hold
  std::unordered_map<int, int> votes_;
  std::vector<FaceHandle> live_;
  std::unique_ptr<edgefront::PointIndex> index_;
  double mean_edge_ = 0, radius_ = 0;
  std::unordered_map<int, std::vector<std::pair<size_t, double>>> cand_of_vertex_;  // candidate, limit
  std::vector<char> near_flag_;
  size_t unresolved_ = 0;
  std::vector<size_t> near_;
  std::vector<std::pair<double, FaceHandle>> layers_;
};

}  // namespace

int reference_vote(const ReferenceNormals& reference, const DetectOptions& options, const Vec3& centre, const Vec3& normal,
                   double mean_edge_length) {
  if (options.experimental.reference_side_weight > 0) {
    return reference.judge(centre, normal, 16, options.experimental.reference_side_weight,
                           options.experimental.reference_margin);
  }
  const double c = OpenMesh::dot(normal, reference.nearest_normal(centre));
  if (c < options.vote.reference_cos) {
    const double thin = options.vote.thin_wall * mean_edge_length;
    return thin > 0 && reference.wall_thickness(centre) < thin ? 0 : -1;
  }
  return c >= -options.vote.reference_cos ? 1 : 0;
}

namespace {

/// The checks of a detection's input (in incremental mode only the candidates' vertices: no pass
/// over the mesh).
void check_pass_input(const Mesh& mesh, const DetectOptions& options) {
  edgefront::require_attributes(mesh, "twist::detect");
  if (options.incremental.face_grid && options.incremental.restrict_to) {
    // Incremental: no pass over the mesh; the candidates' vertices are checked.
    if (mesh.n_faces() == 0) throw InvalidInput("twist::detect: the mesh has no faces");
    for (FaceHandle f : *options.incremental.restrict_to) {
      if (!edgefront::is_live(mesh, f)) continue;  // reported by validate_options
      for (VertexHandle v : mesh.fv_range(f)) {
        const Vec3& p = mesh.point(v);
        if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
          throw InvalidInput("twist::detect: vertex " + std::to_string(v.idx()) + " has a non-finite coordinate");
        }
      }
    }
  } else {
    detail::check_mesh(mesh, "twist::detect");
  }
  validate_options(mesh, options);
}

/// The evidence found in one detection pass: the faces tested, the flagged ones with what flagged
/// them, and the flagged faces in the order found.
struct PassEvidence {
  std::unordered_map<int, Evidence> flagged;
  std::unordered_map<int, char> tested;
  std::vector<FaceHandle> order;  // flagged faces in the order found
  /// Tests f (once); returns whether it is flagged.
  bool run_test(Detector& det, FaceHandle f) {
    if (!tested.emplace(f.idx(), 1).second) return flagged.count(f.idx()) > 0;
    Evidence ev;
    if (!det.test(f, ev)) return false;
    flagged.emplace(f.idx(), ev);
    order.push_back(f);
    return true;
  }
};

/// Step 1 on the whole mesh on several threads: contiguous ranges of faces, a detector each (`det`
/// takes the first). The scan and the tests of a face do not depend on other faces' (the caches
/// are per face), so chunk by chunk gives what one detector gives face by face: the pairs are
/// merged in face order before the tests, the flagged faces are joined in chunk order.
void test_whole_mesh_parallel(const Mesh& mesh, const DetectOptions& options, bool quick, unsigned threads,
                              Detector& det, PassEvidence& pass) {
  const std::vector<FaceHandle> faces(mesh.faces().begin(), mesh.faces().end());
  const unsigned chunks = edgefront::threads_for(faces.size(), threads);
  std::vector<std::unique_ptr<Detector>> workers(chunks);
  std::vector<std::vector<std::pair<int, int>>> logs(chunks);
  std::vector<std::vector<std::pair<FaceHandle, Evidence>>> found(chunks);
  auto detector = [&](unsigned c) -> Detector& {
    if (c == 0) return det;
    if (!workers[c]) workers[c] = std::make_unique<Detector>(mesh, options, quick);
    return *workers[c];
  };
  if (options.self_intersections) {
    edgefront::parallel_for(faces.size(), chunks, [&](std::size_t begin, std::size_t end, unsigned c) {
      Detector& d = detector(c);
      d.si_log = &logs[c];
      for (std::size_t i = begin; i < end; ++i) d.scan_intersections(faces[i]);
      d.si_log = nullptr;
    });
  }
  edgefront::parallel_for(faces.size(), chunks, [&](std::size_t begin, std::size_t end, unsigned c) {
    Detector& d = detector(c);
    if (options.self_intersections) d.adopt_scans(logs, faces);
    for (std::size_t i = begin; i < end; ++i) {
      Evidence ev;
      if (d.test(faces[i], ev)) found[c].emplace_back(faces[i], ev);
    }
  });
  for (unsigned c = 0; c < chunks; ++c) {
    if (c > 0) det.adopt_tests(detector(c));
    for (const auto& [f, ev] : found[c]) {
      pass.flagged.emplace(f.idx(), ev);
      pass.order.push_back(f);
    }
  }
  for (FaceHandle f : faces) pass.tested.emplace(f.idx(), 1);
}

/// Step 1 on the whole mesh on one thread.
void test_whole_mesh(const Mesh& mesh, const DetectOptions& options, Detector& det, PassEvidence& pass) {
  if (options.self_intersections) {
    for (FaceHandle f : mesh.faces()) det.scan_intersections(f);
  }
  for (FaceHandle f : mesh.faces()) pass.run_test(det, f);
}

/// Step 1 in incremental mode: the candidates (`IncrementalOptions::restrict_to`) and an audit sample,
/// the faces right behind them, and the faces grown around flagged ones.
void test_candidates(const Mesh& mesh, const DetectOptions& options, Detector& det, PassEvidence& pass) {
  std::vector<FaceHandle> candidates = *options.incremental.restrict_to;
  // The audit: evenly spaced face indices (the next live face after a deleted one), so it
  // costs O(audit_faces), not a pass over the mesh.
  const size_t nf = mesh.n_faces();
  const size_t audit = std::min(options.incremental.audit_faces, nf);
  for (size_t i = 0; i < audit; ++i) {
    size_t k = (options.incremental.audit_offset + i * nf / audit) % nf;
    for (size_t probe = 0; probe < 16 && !edgefront::is_live(mesh, FaceHandle(static_cast<int>(k))); ++probe) k = (k + 1) % nf;
    if (edgefront::is_live(mesh, FaceHandle(static_cast<int>(k)))) candidates.push_back(FaceHandle(static_cast<int>(k)));
  }
  std::deque<std::pair<FaceHandle, int>> queue;
  // Self-intersections only mark where a twist line runs (a region needs orientation evidence,
  // see `require_orientation_evidence`), so the candidates are not scanned for them: only the
  // faces grown around flagged ones are (the scan is the costliest test, and most candidates
  // of a batch are right).
  det.set_scan_intersections(!options.regions.require_orientation_evidence);
  for (FaceHandle f : candidates) {
    if (pass.run_test(det, f)) queue.emplace_back(f, 0);
  }
  // Faces that point at a candidate's back from right behind: their evidence changed with the
  // candidate although they did not move (one level: partners of partners are not followed).
  for (FaceHandle g : det.take_behind()) {
    if (pass.run_test(det, g)) queue.emplace_back(g, 0);
  }
  det.set_scan_intersections(true);
  // Grow the evidence: test faces within grow_levels hops of a flagged face, so a twisted
  // region is found whole although only changed faces were candidates.
  while (!queue.empty()) {
    const auto [f, hops] = queue.front();
    queue.pop_front();
    if (hops >= options.regions.grow_levels) continue;
    for (HalfedgeHandle h : mesh.fh_range(f)) {
      const FaceHandle g = mesh.opposite_face_handle(h);
      if (!g.is_valid() || pass.tested.count(g.idx())) continue;
      // Flagged and ambiguous faces (evidence both ways) carry the search on.
      queue.emplace_back(g, pass.run_test(det, g) || det.ambiguous(g) ? 0 : hops + 1);
    }
  }
}

/// Whether f has core evidence.
/// A region needs a core: a face with orientation evidence whose neighbours across every edge
/// have it too, i.e. a patch whose orientation is wrong, not only faces turned against right
/// neighbours (a tangle: a triangle or two flipped over in a crease while the mesh moves, which
/// the loop's smoothing undoes and a cut would only tear open). With a reference, the reference
/// tells the side wherever it decides: a facing layer then only marks where a twist line may
/// run (two right parts of the surface also face each other across a gap narrower than the
/// radius: a tail over a back, a leg along a body), and counts for the core only where the side
/// judge abstains between the walls of a wall thinner than the faces.
bool core_evidence(const DetectOptions& options, Detector& det, const std::unordered_map<int, Evidence>& flagged,
                   FaceHandle f) {
  const auto it = flagged.find(f.idx());
  if (it == flagged.end()) return false;
  if (it->second.kind == EvidenceKind::Reference) return true;
  if (it->second.kind != EvidenceKind::FacingLayer) return false;
  return !options.reference || (options.experimental.reference_side_weight > 0 && det.vote(f) == 0);
}

/// A face of a core: with core evidence, as are its neighbours across every edge.
bool is_core(const Mesh& mesh, const DetectOptions& options, Detector& det,
             const std::unordered_map<int, Evidence>& flagged, FaceHandle f) {
  if (!core_evidence(options, det, flagged, f)) return false;
  for (HalfedgeHandle h : mesh.fh_range(f)) {
    const FaceHandle g = mesh.opposite_face_handle(h);
    if (g.is_valid() && !core_evidence(options, det, flagged, g)) return false;
  }
  return true;
}

/// Step 5, trim: faces added by growing or filling that show positive evidence of being right (a
/// back-to-back layer or an agreeing reference normal) leave the region, so the cut runs at the
/// twist line and does not flip right faces. Then the border loops of what remains.
void trim_right_faces(const Mesh& mesh, const std::unordered_map<int, Evidence>& flagged, Detector& det,
                      std::vector<TwistRegion>& regions) {
  for (TwistRegion& r : regions) {
    std::unordered_map<int, char> in_region, right;
    for (FaceHandle f : r.faces) in_region[f.idx()] = 1;
    for (FaceHandle f : r.faces) {
      if (!flagged.count(f.idx()) && det.right(f)) right[f.idx()] = 1;
    }
    if (!right.empty()) {
      std::vector<FaceHandle> kept;
      for (FaceHandle f : r.faces) {
        if (!right.count(f.idx())) kept.push_back(f);
      }
      r.faces = std::move(kept);
      r.area = 0;
      for (FaceHandle f : r.faces) r.area += detail::area(detail::face_points(mesh, f));
    }
    std::tie(r.border, r.border_on_mesh_border) = detail::border_loops(mesh, r.faces);
  }
}

/// One detection. `quick`: no layer is looked for in front of faces the reference confirms, and
/// the pass ends after the evidence, setting `has_core` (see `detect_regions`).
DetectResult detect_pass(const Mesh& mesh, const DetectOptions& options, bool quick, bool& has_core) {
  check_pass_input(mesh, options);
  Detector det(mesh, options, quick);
  DetectResult result;

  // 1. Evidence on the candidate faces.
  PassEvidence pass;
  // At most one thread per this many faces in a whole-mesh detection (each builds a detector).
  constexpr std::size_t kFacesPerThread = 1000;
  const unsigned threads = options.incremental.restrict_to
                               ? 1u
                               : static_cast<unsigned>(std::min<std::size_t>(
                                     edgefront::resolve_threads(options.threads),
                                     std::max<std::size_t>(1, mesh.n_faces() / kFacesPerThread)));
  if (!options.incremental.restrict_to && threads > 1) {
    test_whole_mesh_parallel(mesh, options, quick, threads, det, pass);
  } else if (!options.incremental.restrict_to) {
    test_whole_mesh(mesh, options, det, pass);
  } else {
    test_candidates(mesh, options, det, pass);
  }
  result.stats = det.stats;
  result.stats.flagged_faces = pass.flagged.size();
  if (pass.flagged.empty()) return result;
  // A region needs a core (see core_evidence).
  auto core = [&](FaceHandle f) { return is_core(mesh, options, det, pass.flagged, f); };
  // No core anywhere: no region can be kept, so none is grown (most calls of a refinement loop).
  has_core = std::any_of(pass.order.begin(), pass.order.end(), core);
  if (quick || (options.regions.require_orientation_evidence && !has_core)) return result;

  // 2. Grow the flagged faces into regions with a Minimal Edge Front from their vertices.
  const std::vector<edgefront::FrontLoop> loops =
      detail::grow_front(mesh, pass.order, options.regions.grow_levels);
  // 3. Regions: the surface behind the front, connected without crossing it.
  std::unordered_map<int, int> region_of;
  std::vector<TwistRegion> regions = detail::regions_behind_front(mesh, pass.order, pass.flagged, loops, region_of);
  // 4. Fill holes: pieces of the rest enclosed by a region and smaller than it join it.
  detail::fill_enclosed_pieces(mesh, loops, region_of, regions);
  // 5. Trim: faces added by growing or filling that show evidence of being right leave the region.
  trim_right_faces(mesh, pass.flagged, det, regions);
  auto orientation_evidence = [&](const TwistRegion& r) {
    if (!options.regions.require_orientation_evidence) return true;
    for (const Evidence& e : r.evidence) {
      if (core(e.face)) return true;
    }
    return false;
  };
  for (auto& r : regions) {
    const bool enough = r.flagged_faces >= options.regions.min_flagged_faces &&
                        static_cast<double>(r.flagged_faces) >=
                            options.regions.min_flagged_share * static_cast<double>(r.faces.size());
    if (enough && orientation_evidence(r)) result.regions.push_back(std::move(r));
  }
  std::stable_sort(result.regions.begin(), result.regions.end(), [](const TwistRegion& a, const TwistRegion& b) {
    return a.faces.size() > b.faces.size();
  });
  return result;
}

}  // namespace

DetectResult detect_regions(const Mesh& mesh, const DetectOptions& options) {
  bool has_core = false;
  if (options.reference && options.experimental.reference_side_weight == 0 &&
      options.regions.require_orientation_evidence) {
    // With a reference judging by the nearest normal, a core needs reference evidence, which does
    // not depend on layers: a first pass that looks for no layer in front of the faces the
    // reference confirms (two right parts of a surface facing each other across a narrow gap
    // cost a bounded distance front per test, every time they are tested) tells whether any
    // region can be kept; only then the full pass runs. (In incremental mode the quick pass grows
    // the tested set only from the faces it flags, so a core reached only through facing layers
    // waits for a later call or the final full pass.)
    DetectResult quick = detect_pass(mesh, options, true, has_core);
    if (!has_core) return quick;
    DetectResult full = detect_pass(mesh, options, false, has_core);
    // faces_tested counts faces: the quick pass tested the same candidates, with less evidence.
    full.stats.distance_queries += quick.stats.distance_queries;
    full.stats.vertices_settled += quick.stats.vertices_settled;
    return full;
  }
  return detect_pass(mesh, options, false, has_core);
}

std::vector<std::pair<FaceHandle, FaceHandle>> same_orientation_pairs(const Mesh& mesh, const DetectOptions& options,
                                                                     LayerRule rule) {
  detail::check_mesh(mesh, "twist::same_orientation_pairs");
  validate_options(mesh, options);
  if (rule != LayerRule::Facing && rule != LayerRule::Stacked) {
    throw InvalidInput("twist::same_orientation_pairs: unknown layer rule " + std::to_string(static_cast<int>(rule)));
  }
  DetectOptions full = options;
  full.incremental.restrict_to.reset();  // the detector as for the whole mesh; the set only picks the faces
  Detector det(mesh, full, false);
  std::vector<std::pair<FaceHandle, FaceHandle>> out;
  auto add_pair = [&](FaceHandle f, const std::unordered_set<int>* keep) {
    if (det.normal(f).sqrnorm() == 0) return;
    const bool stacked = rule == LayerRule::Stacked;
    FaceHandle g = det.far_layer(f, 1.0, true, stacked);
    if (!g.is_valid()) g = det.far_layer(f, -1.0, true, stacked);
    if (g.is_valid() && (!keep || keep->count(f.idx()) || keep->count(g.idx()))) out.emplace_back(f, g);
  };
  if (!options.incremental.restrict_to) {
    for (FaceHandle f : mesh.faces()) add_pair(f, nullptr);
    return out;
  }
  // A face whose partner is in the set lies within the layer radius of it: the set and the faces
  // around it are all that can make such a pair.
  const std::unordered_set<int> keep = [&] {
    std::unordered_set<int> k;
    for (FaceHandle f : *options.incremental.restrict_to) k.insert(f.idx());
    return k;
  }();
  std::vector<FaceHandle> candidates = *options.incremental.restrict_to;
  for (FaceHandle f : *options.incremental.restrict_to) {
    for (FaceHandle g : det.around(f)) candidates.push_back(g);
  }
  std::sort(candidates.begin(), candidates.end(), [](FaceHandle a, FaceHandle b) { return a.idx() < b.idx(); });
  candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
  for (FaceHandle f : candidates) add_pair(f, &keep);
  return out;
}

void validate_detect_options(const Mesh& mesh, const DetectOptions& options) { validate_options(mesh, options); }

size_t count_same_orientation_layers(const Mesh& mesh, const DetectOptions& options, LayerRule rule) {
  return same_orientation_pairs(mesh, options, rule).size();
}

std::vector<TwistRegion> detect(const Mesh& mesh, const DetectOptions& options) {
  return detect_regions(mesh, options).regions;
}

std::vector<HalfedgeHandle> reversed_seams(const Mesh& mesh) {
  std::vector<HalfedgeHandle> out;
  for (const std::vector<HalfedgeHandle>& hs : detail::coincident_border_halfedges(mesh)) {
    out.push_back(*std::min_element(hs.begin(), hs.end(), [](auto x, auto y) { return x.idx() < y.idx(); }));
  }
  std::sort(out.begin(), out.end(), [](auto x, auto y) { return x.idx() < y.idx(); });
  return out;
}

}  // namespace twist
