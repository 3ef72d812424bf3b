#include "twist/detect.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <deque>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <tuple>
#include <unordered_map>
#include <unordered_set>

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
// 21 bits per axis: far cells may share a key, which only adds candidates (queries check distances).
std::uint64_t key_of_cell(std::int64_t x, std::int64_t y, std::int64_t z) {
  const auto bits = [](std::int64_t c) { return static_cast<std::uint64_t>(c) & 0x1FFFFFu; };
  return (bits(x) << 42) | (bits(y) << 21) | bits(z);
}
std::uint64_t cell_key(const Vec3& p, double cell) {
  const auto c = [&](int i) { return static_cast<std::int64_t>(std::floor(p[i] / cell)); };
  return key_of_cell(c(0), c(1), c(2));
}
}  // namespace

FaceGeometry face_geometry(const Mesh& mesh, FaceHandle f) {
  if (!edgefront::is_live(mesh, f)) {
    throw InvalidInput("twist::face_geometry: face " + std::to_string(f.idx()) +
                       " is not a live face of the mesh (invalid, out of range or deleted)");
  }
  FaceGeometry g;
  std::array<Vec3, 3> p;
  size_t i = 0;
  for (VertexHandle v : mesh.fv_range(f)) {
    EF_CHECK(i < 3, "face " + std::to_string(f.idx()) + " is not a triangle");
    p[i] = mesh.point(v);
    g.vertices[i++] = v.idx();
  }
  EF_CHECK(i == 3, "face " + std::to_string(f.idx()) + " is not a triangle");
  g.normal = detail::unit_normal(p);
  g.centre = detail::centroid(p);
  for (size_t k = 0; k < 3; ++k) g.longest = std::max(g.longest, (p[k] - p[(k + 1) % 3]).norm());
  return g;
}

void FaceGrid::insert(const Mesh& mesh, FaceHandle f) {
  if (!edgefront::is_live(mesh, f)) return;
  const FaceGeometry g = face_geometry(mesh, f);
  const std::uint64_t key = cell_key(g.centre, cell_);
  const size_t i = static_cast<size_t>(f.idx());
  if (i >= records_.size()) records_.resize(std::max(i + 1, 2 * records_.size()));
  Record& r = records_[i];
  r.geometry = g;
  if (r.key != kNoKey) {
    auto& old = cells_[r.key];
    const auto pos = std::find_if(old.begin(), old.end(), [&](const Entry& e) { return e.face == f.idx(); });
    if (r.key == key && pos != old.end()) {
      pos->centre = g.centre;
      return;
    }
    if (pos != old.end()) {
      *pos = old.back();
      old.pop_back();
      --size_;
    }
  }
  r.key = key;
  cells_[key].push_back(Entry{f.idx(), g.centre});
  ++size_;
}

void FaceGrid::update(const Mesh& mesh, const std::vector<FaceHandle>& faces) {
  EF_CHECK(cell_ > 0, "FaceGrid::update before rebuild");
  for (FaceHandle f : faces) insert(mesh, f);
}

void FaceGrid::update_new(const Mesh& mesh) {
  EF_CHECK(cell_ > 0, "FaceGrid::update_new before rebuild");
  for (size_t i = seen_faces_; i < mesh.n_faces(); ++i) insert(mesh, FaceHandle(static_cast<int>(i)));
  seen_faces_ = mesh.n_faces();
}

void FaceGrid::rebuild(const Mesh& mesh, double cell) {
  if (!(cell > 0) || !std::isfinite(cell)) throw InvalidInput("twist::FaceGrid: the cell size must be finite and > 0");
  cell_ = cell;
  cells_.clear();
  records_.assign(mesh.n_faces(), Record{});
  size_ = 0;
  ++rebuilds_;
  for (FaceHandle f : mesh.faces()) insert(mesh, f);
  seen_faces_ = mesh.n_faces();
}

void FaceGrid::query(const Mesh& mesh, const Vec3& p, double radius, std::vector<FaceHandle>& out) const {
  out.clear();
  if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]) || !std::isfinite(radius) || radius < 0)
    throw InvalidInput("twist::FaceGrid::query: the point and the radius must be finite, the radius >= 0");
  if (!(cell_ > 0)) return;
  const double r2 = radius * radius;
  const auto take = [&](const std::vector<Entry>& entries) {
    for (const Entry& e : entries) {
      if ((e.centre - p).sqrnorm() >= r2) continue;
      const FaceHandle f(e.face);
      if (edgefront::is_live(mesh, f)) out.push_back(f);
    }
  };
  // Cell ranges in doubles first: a query box with more cells than the grid holds (or beyond the
  // integer range) scans the occupied cells instead of the box.
  double lo[3], hi[3], span = 1;
  for (int i = 0; i < 3; ++i) {
    lo[i] = std::floor((p[i] - radius) / cell_);
    hi[i] = std::floor((p[i] + radius) / cell_);
    span *= hi[i] - lo[i] + 1;
  }
  const bool in_range = std::abs(lo[0]) < 1e15 && std::abs(hi[0]) < 1e15 && std::abs(lo[1]) < 1e15 &&
                        std::abs(hi[1]) < 1e15 && std::abs(lo[2]) < 1e15 && std::abs(hi[2]) < 1e15;
  if (!in_range || span > static_cast<double>(cells_.size())) {
    for (const auto& cell : cells_) take(cell.second);
  } else {
    const auto c = [](double v) { return static_cast<std::int64_t>(v); };
    for (std::int64_t x = c(lo[0]); x <= c(hi[0]); ++x) {
      for (std::int64_t y = c(lo[1]); y <= c(hi[1]); ++y) {
        for (std::int64_t z = c(lo[2]); z <= c(hi[2]); ++z) {
          const auto it = cells_.find(key_of_cell(x, y, z));
          if (it != cells_.end()) take(it->second);
        }
      }
    }
  }
  std::sort(out.begin(), out.end(), [](FaceHandle a, FaceHandle b) { return a.idx() < b.idx(); });
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

namespace {

void check_range(bool ok, const std::string& what) {
  if (!ok) throw InvalidInput("twist::detect: option " + what);
}

void validate_options(const Mesh& mesh, const DetectOptions& o) {
  check_range(std::isfinite(o.radius) && o.radius >= 0, "radius must be finite and >= 0 (0 = automatic)");
  check_range(std::isfinite(o.surface_factor) && o.surface_factor >= 1, "surface_factor must be finite and >= 1");
  check_range(o.parallel_cos >= 0 && o.parallel_cos <= 1, "parallel_cos must lie in [0, 1]");
  check_range(o.facing_cos > 0 && o.facing_cos <= 1, "facing_cos must lie in (0, 1]");
  check_range(o.fold_cos >= -1 && o.fold_cos <= 0, "fold_cos must lie in [-1, 0]");
  check_range(o.grow_levels >= 1 && o.grow_levels <= 64, "grow_levels must lie in [1, 64]");
  check_range(o.min_flagged_faces >= 1, "min_flagged_faces must be >= 1");
  check_range(o.min_flagged_share >= 0 && o.min_flagged_share <= 1, "min_flagged_share must lie in [0, 1]");
  check_range(o.reference_cos >= -1 && o.reference_cos <= 1, "reference_cos must lie in [-1, 1]");
  check_range(o.reference_side_weight == 0 || (o.reference_side_weight >= 1 && o.reference_side_weight <= 100),
              "reference_side_weight must be 0 or lie in [1, 100]");
  check_range(std::isfinite(o.mean_edge_length) && o.mean_edge_length >= 0, "mean_edge_length must be finite and >= 0");
  check_range(o.reference_margin >= 1 && o.reference_margin <= 100, "reference_margin must lie in [1, 100]");
  check_range(o.thin_wall >= 0 && o.thin_wall <= 4, "thin_wall must lie in [0, 4]");
  if (o.restrict_to) {
    for (FaceHandle f : *o.restrict_to) {
      if (!edgefront::is_live(mesh, f)) {
        throw InvalidInput("twist::detect: restrict_to names face " + std::to_string(f.idx()) +
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
      : quick_(quick), collect_behind_(o.restrict_to.has_value()), mesh_(mesh), o_(o), mdf_(mesh), grid_(o.face_grid) {
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
      if (g.is_valid() && OpenMesh::dot(nf, normal(g)) <= o_.fold_cos) {
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
      if (dist > 0 && dist <= radius_ && -OpenMesh::dot(nf, d) >= o_.facing_cos * dist && OpenMesh::dot(nf, normal(g)) <= -o_.parallel_cos &&
          !shares_vertex(f, g)) {
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
      const bool layer = side * along >= o_.facing_cos * dist &&
                         (same_orientation_only ? cos_ng : std::abs(cos_ng)) >= o_.parallel_cos;
      // Behind f with the same orientation: g may point at f's back, so its evidence changed with f.
      const bool behind = !layer && collect_behind_ && side > 0 && !same_orientation_only &&
                          -along >= o_.facing_cos * dist && cos_ng >= o_.parallel_cos;
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
    const auto limit_of = [&](size_t i) { return o_.surface_factor * layers_[i].first + mean_edge_; };
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


/// The border of a face set as closed loops of halfedges with the set on their right (the face
/// of each halfedge lies outside or is missing), and per loop whether it lies on the mesh border.
std::pair<std::vector<std::vector<HalfedgeHandle>>, std::vector<bool>> border_loops(const Mesh& mesh,
                                                                                   const std::vector<FaceHandle>& faces) {
  std::unordered_map<int, char> in_set;
  for (FaceHandle f : faces) in_set[f.idx()] = 1;
  std::vector<HalfedgeHandle> starts;
  std::unordered_map<int, char> unused;  // border halfedges not yet in a loop
  for (FaceHandle f : faces) {
    for (HalfedgeHandle h : mesh.fh_range(f)) {
      const HalfedgeHandle o = mesh.opposite_halfedge_handle(h);
      const FaceHandle g = mesh.face_handle(o);
      if (g.is_valid() && in_set.count(g.idx())) continue;
      starts.push_back(o);
      unused[o.idx()] = 1;
    }
  }
  std::sort(starts.begin(), starts.end(), [](HalfedgeHandle a, HalfedgeHandle b) { return a.idx() < b.idx(); });
  std::vector<std::vector<HalfedgeHandle>> loops;
  std::vector<bool> on_border;
  for (HalfedgeHandle s0 : starts) {
    if (!unused.count(s0.idx())) continue;
    std::vector<HalfedgeHandle> loop;
    HalfedgeHandle h = s0;
    while (h.is_valid() && unused.erase(h.idx())) {
      loop.push_back(h);
      // The next border halfedge leaves to_vertex(h): turn around it from h's opposite.
      HalfedgeHandle next;
      const HalfedgeHandle back = mesh.opposite_halfedge_handle(h);
      HalfedgeHandle g = back;
      do {
        g = mesh.cw_rotated_halfedge_handle(g);
        if (unused.count(g.idx()) || g == s0) {
          next = g;
          break;
        }
      } while (g != back);
      h = next;
    }
    bool all_border = true;
    for (HalfedgeHandle x : loop) all_border = all_border && mesh.is_boundary(x);
    loops.push_back(std::move(loop));
    on_border.push_back(all_border);
  }
  return {loops, on_border};
}

}  // namespace

int reference_vote(const ReferenceNormals& reference, const DetectOptions& options, const Vec3& centre, const Vec3& normal,
                   double mean_edge_length) {
  if (options.reference_side_weight > 0) {
    return reference.judge(centre, normal, 16, options.reference_side_weight, options.reference_margin);
  }
  const double c = OpenMesh::dot(normal, reference.nearest_normal(centre));
  if (c < options.reference_cos) {
    const double thin = options.thin_wall * mean_edge_length;
    return thin > 0 && reference.wall_thickness(centre) < thin ? 0 : -1;
  }
  return c >= -options.reference_cos ? 1 : 0;
}

namespace {

/// One detection. `quick`: no layer is looked for in front of faces the reference confirms, and
/// the pass ends after the evidence, setting `has_core` (see `detect_regions`).
DetectResult detect_pass(const Mesh& mesh, const DetectOptions& options, bool quick, bool& has_core) {
  edgefront::require_attributes(mesh, "twist::detect");
  if (options.face_grid && options.restrict_to) {
    // Incremental: no pass over the mesh; the candidates' vertices are checked.
    if (mesh.n_faces() == 0) throw InvalidInput("twist::detect: the mesh has no faces");
    for (FaceHandle f : *options.restrict_to) {
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
  Detector det(mesh, options, quick);
  DetectResult result;

  // 1. Evidence on the candidate faces.
  std::unordered_map<int, Evidence> flagged;
  std::unordered_map<int, char> tested;
  std::vector<FaceHandle> order;  // flagged faces in the order found
  auto run_test = [&](FaceHandle f) -> bool {
    if (!tested.emplace(f.idx(), 1).second) return flagged.count(f.idx()) > 0;
    Evidence ev;
    if (!det.test(f, ev)) return false;
    flagged.emplace(f.idx(), ev);
    order.push_back(f);
    return true;
  };
  // At most one thread per this many faces in a whole-mesh detection (each builds a detector).
  constexpr std::size_t kFacesPerThread = 1000;
  const unsigned threads =
      options.restrict_to ? 1u
                          : static_cast<unsigned>(std::min<std::size_t>(edgefront::resolve_threads(options.threads),
                                                                        std::max<std::size_t>(1, mesh.n_faces() / kFacesPerThread)));
  if (!options.restrict_to && threads > 1) {
    // Whole mesh on several threads: contiguous ranges of faces, a detector each (this one takes
    // the first). The scan and the tests of a face do not depend on other faces' (the caches are
    // per face), so chunk by chunk gives what one detector gives face by face: the pairs are
    // merged in face order before the tests, the flagged faces are joined in chunk order.
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
        flagged.emplace(f.idx(), ev);
        order.push_back(f);
      }
    }
    for (FaceHandle f : faces) tested.emplace(f.idx(), 1);
  } else if (!options.restrict_to) {
    if (options.self_intersections) {
      for (FaceHandle f : mesh.faces()) det.scan_intersections(f);
    }
    for (FaceHandle f : mesh.faces()) run_test(f);
  } else {
    std::vector<FaceHandle> candidates = *options.restrict_to;
    // The audit: evenly spaced face indices (the next live face after a deleted one), so it
    // costs O(audit_faces), not a pass over the mesh.
    const size_t nf = mesh.n_faces();
    const size_t audit = std::min(options.audit_faces, nf);
    for (size_t i = 0; i < audit; ++i) {
      size_t k = (options.audit_offset + i * nf / audit) % nf;
      for (size_t probe = 0; probe < 16 && !edgefront::is_live(mesh, FaceHandle(static_cast<int>(k))); ++probe) k = (k + 1) % nf;
      if (edgefront::is_live(mesh, FaceHandle(static_cast<int>(k)))) candidates.push_back(FaceHandle(static_cast<int>(k)));
    }
    std::deque<std::pair<FaceHandle, int>> queue;
    // Self-intersections only mark where a twist line runs (a region needs orientation evidence,
    // see `require_orientation_evidence`), so the candidates are not scanned for them: only the
    // faces grown around flagged ones are (the scan is the costliest test, and most candidates
    // of a batch are right).
    det.set_scan_intersections(!options.require_orientation_evidence);
    for (FaceHandle f : candidates) {
      if (run_test(f)) queue.emplace_back(f, 0);
    }
    // Faces that point at a candidate's back from right behind: their evidence changed with the
    // candidate although they did not move (one level: partners of partners are not followed).
    for (FaceHandle g : det.take_behind()) {
      if (run_test(g)) queue.emplace_back(g, 0);
    }
    det.set_scan_intersections(true);
    // Grow the evidence: test faces within grow_levels hops of a flagged face, so a twisted
    // region is found whole although only changed faces were candidates.
    while (!queue.empty()) {
      const auto [f, hops] = queue.front();
      queue.pop_front();
      if (hops >= options.grow_levels) continue;
      for (HalfedgeHandle h : mesh.fh_range(f)) {
        const FaceHandle g = mesh.opposite_face_handle(h);
        if (!g.is_valid() || tested.count(g.idx())) continue;
        // Flagged and ambiguous faces (evidence both ways) carry the search on.
        queue.emplace_back(g, run_test(g) || det.ambiguous(g) ? 0 : hops + 1);
      }
    }
  }
  result.stats = det.stats;
  result.stats.flagged_faces = flagged.size();
  if (flagged.empty()) return result;
  // A region needs a core: a face with orientation evidence whose neighbours across every edge
  // have it too, i.e. a patch whose orientation is wrong, not only faces turned against right
  // neighbours (a tangle: a triangle or two flipped over in a crease while the mesh moves, which
  // the loop's smoothing undoes and a cut would only tear open). With a reference, the reference
  // tells the side wherever it decides: a facing layer then only marks where a twist line may
  // run (two right parts of the surface also face each other across a gap narrower than the
  // radius: a tail over a back, a leg along a body), and counts for the core only where the side
  // judge abstains between the walls of a wall thinner than the faces.
  auto core_evidence = [&](FaceHandle f) {
    const auto it = flagged.find(f.idx());
    if (it == flagged.end()) return false;
    if (it->second.kind == EvidenceKind::Reference) return true;
    if (it->second.kind != EvidenceKind::FacingLayer) return false;
    return !options.reference || (options.reference_side_weight > 0 && det.vote(f) == 0);
  };
  auto is_core = [&](FaceHandle f) {
    if (!core_evidence(f)) return false;
    for (HalfedgeHandle h : mesh.fh_range(f)) {
      const FaceHandle g = mesh.opposite_face_handle(h);
      if (g.is_valid() && !core_evidence(g)) return false;
    }
    return true;
  };
  // No core anywhere: no region can be kept, so none is grown (most calls of a refinement loop).
  has_core = std::any_of(order.begin(), order.end(), is_core);
  if (quick || (options.require_orientation_evidence && !has_core)) return result;

  // 2. Grow the flagged faces into regions with a Minimal Edge Front from their vertices.
  std::vector<VertexHandle> sources;
  {
    std::unordered_map<int, char> seen;
    for (FaceHandle f : order) {
      for (VertexHandle v : mesh.fv_range(f)) {
        if (seen.emplace(v.idx(), 1).second) sources.push_back(v);
      }
    }
    std::sort(sources.begin(), sources.end(), [](VertexHandle a, VertexHandle b) { return a.idx() < b.idx(); });
  }
  edgefront::MinimalEdgeFront front(mesh);
  front.reset(edgefront::FrontSource::from_vertices(sources));
  front.run(options.grow_levels);
  const std::vector<edgefront::FrontLoop> loops = front.loops();
  std::unordered_map<int, char> front_edge;
  for (const auto& loop : loops) {
    for (HalfedgeHandle h : loop.halfedges) front_edge[mesh.edge_handle(h).idx()] = 1;
  }

  // 3. Regions: the surface behind the front, connected without crossing it.
  std::unordered_map<int, int> region_of;
  std::vector<FaceHandle> seeds = order;
  std::sort(seeds.begin(), seeds.end(), [](FaceHandle a, FaceHandle b) { return a.idx() < b.idx(); });
  std::vector<TwistRegion> regions;
  for (FaceHandle seed : seeds) {
    if (region_of.count(seed.idx())) continue;
    const int id = static_cast<int>(regions.size());
    regions.emplace_back();
    TwistRegion& r = regions.back();
    std::deque<FaceHandle> queue{seed};
    region_of[seed.idx()] = id;
    while (!queue.empty()) {
      const FaceHandle f = queue.front();
      queue.pop_front();
      r.faces.push_back(f);
      r.area += detail::area(detail::face_points(mesh, f));
      const auto ev = flagged.find(f.idx());
      if (ev != flagged.end()) r.evidence.push_back(ev->second);
      for (HalfedgeHandle h : mesh.fh_range(f)) {
        if (front_edge.count(mesh.edge_handle(h).idx())) continue;
        const FaceHandle g = mesh.opposite_face_handle(h);
        if (!g.is_valid() || region_of.count(g.idx())) continue;
        region_of[g.idx()] = id;
        queue.push_back(g);
      }
    }
    std::sort(r.faces.begin(), r.faces.end(), [](FaceHandle a, FaceHandle b) { return a.idx() < b.idx(); });
    std::sort(r.evidence.begin(), r.evidence.end(),
              [](const Evidence& a, const Evidence& b) { return a.face.idx() < b.face.idx(); });
    r.flagged_faces = r.evidence.size();
  }
  // 4. Fill holes: a piece of the rest enclosed by a region (bounded by one of several border
  //    loops) and smaller than the region joins it; the largest piece always stays outside.
  //    Each piece is explored with a budget of the region's size, so this is semi-local.
  std::unordered_map<int, char> filled;
  for (size_t id = 0; id < regions.size(); ++id) {
    TwistRegion& r = regions[id];
    std::vector<std::vector<FaceHandle>> pieces;
    std::unordered_map<int, char> explored;
    bool some_outside = false;
    for (const auto& loop : loops) {
      if (loop.halfedges.empty()) continue;
      const FaceHandle behind = mesh.opposite_face_handle(loop.halfedges.front());
      const auto it = behind.is_valid() ? region_of.find(behind.idx()) : region_of.end();
      if (it == region_of.end() || it->second != static_cast<int>(id)) continue;
      for (HalfedgeHandle h0 : loop.halfedges) {
        const FaceHandle start = mesh.face_handle(h0);
        if (!start.is_valid() || region_of.count(start.idx()) || explored.count(start.idx())) continue;
        std::vector<FaceHandle> piece{start};
        explored[start.idx()] = 1;
        bool fits = true;
        for (size_t q = 0; q < piece.size() && fits; ++q) {
          for (HalfedgeHandle h : mesh.fh_range(piece[q])) {
            const FaceHandle g = mesh.opposite_face_handle(h);
            if (!g.is_valid() || explored.count(g.idx())) continue;
            const auto owner = region_of.find(g.idx());
            if (owner != region_of.end()) {
              if (owner->second != static_cast<int>(id)) fits = false;  // touches another region
              continue;
            }
            explored[g.idx()] = 1;
            piece.push_back(g);
            if (piece.size() >= r.faces.size()) fits = false;
          }
        }
        if (fits) {
          pieces.push_back(std::move(piece));
        } else {
          some_outside = true;
        }
      }
    }
    if (!some_outside && !pieces.empty()) {  // keep the largest piece outside
      const auto largest = std::max_element(pieces.begin(), pieces.end(),
                                            [](const auto& a, const auto& b) { return a.size() < b.size(); });
      pieces.erase(largest);
    }
    for (const auto& piece : pieces) {
      for (FaceHandle f : piece) {
        filled[f.idx()] = 1;
        region_of[f.idx()] = static_cast<int>(id);
        r.faces.push_back(f);
        r.area += detail::area(detail::face_points(mesh, f));
      }
    }
    std::sort(r.faces.begin(), r.faces.end(), [](FaceHandle a, FaceHandle b) { return a.idx() < b.idx(); });
  }
  // 5. Trim: faces added by growing or filling that show positive evidence of being right (a
  //    back-to-back layer or an agreeing reference normal) leave the region, so the cut runs at
  //    the twist line and does not flip right faces. Then the border loops of what remains.
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
    std::tie(r.border, r.border_on_mesh_border) = border_loops(mesh, r.faces);
  }
  auto orientation_evidence = [&](const TwistRegion& r) {
    if (!options.require_orientation_evidence) return true;
    for (const Evidence& e : r.evidence) {
      if (is_core(e.face)) return true;
    }
    return false;
  };
  for (auto& r : regions) {
    const bool enough = r.flagged_faces >= options.min_flagged_faces &&
                        static_cast<double>(r.flagged_faces) >= options.min_flagged_share * static_cast<double>(r.faces.size());
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
  if (options.reference && options.reference_side_weight == 0 && options.require_orientation_evidence) {
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
  full.restrict_to.reset();  // the detector as for the whole mesh; the set only picks the faces
  Detector det(mesh, full, false);
  std::vector<std::pair<FaceHandle, FaceHandle>> out;
  auto add_pair = [&](FaceHandle f, const std::unordered_set<int>* keep) {
    if (det.normal(f).sqrnorm() == 0) return;
    const bool stacked = rule == LayerRule::Stacked;
    FaceHandle g = det.far_layer(f, 1.0, true, stacked);
    if (!g.is_valid()) g = det.far_layer(f, -1.0, true, stacked);
    if (g.is_valid() && (!keep || keep->count(f.idx()) || keep->count(g.idx()))) out.emplace_back(f, g);
  };
  if (!options.restrict_to) {
    for (FaceHandle f : mesh.faces()) add_pair(f, nullptr);
    return out;
  }
  // A face whose partner is in the set lies within the layer radius of it: the set and the faces
  // around it are all that can make such a pair.
  const std::unordered_set<int> keep = [&] {
    std::unordered_set<int> k;
    for (FaceHandle f : *options.restrict_to) k.insert(f.idx());
    return k;
  }();
  std::vector<FaceHandle> candidates = *options.restrict_to;
  for (FaceHandle f : *options.restrict_to) {
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
