#pragma once
// The reconstructor's state and loop (gcs::Reconstructor::Impl), shared by its translation units
// along the concepts of the algorithm:
//   reconstructor.cpp        the public API (Reconstructor forwarding, reconstruct, to_string)
//   reconstructor_setup.cpp  input checks, noise smoothing, normals, query tree, start mesh
//   reconstructor_step.cpp   the basic step, ring smoothing, vertex split, edge collapse, renumbering
//                            (the hot path: everything a basic step calls is here or inline below)
//   reconstructor_batch.cpp  batches: topology pass, operations, resync, run(), validate()
//   reconstructor_post.cpp   post-processing of the returned mesh (make_result)

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

#include "detail/border_topology.h"
#include "detail/counter_heap.h"
#include "detail/neighbor_cache.h"
#include "detail/spatial_order.h"
#include "detail/vertex_grid.h"
#include "edgefront/mesh.h"
#include "edgefront/point_index.h"
#include "gcs/reconstructor.h"

namespace gcs {

using edgefront::EdgeHandle;
using edgefront::FaceHandle;
using edgefront::HalfedgeHandle;
using edgefront::InvalidInput;
using edgefront::Mesh;
using edgefront::PointIndex;
using edgefront::Vec3;
using edgefront::VertexHandle;

namespace detail {

using Clock = std::chrono::steady_clock;
inline double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

inline Vec3 face_normal_of(const Vec3& a, const Vec3& b, const Vec3& c) { return (b - a) % (c - a); }

// Sample indices are drawn as one 64-bit draw modulo n (portable, unlike
// std::uniform_int_distribution; the modulo bias is below n / 2^64).
// x % n for a fixed n without a 64-bit division (tens of cycles, on the basic step's critical
// path): q = floor(x * floor((2^64 - 1) / n) / 2^64) is at most 2 below floor(x / n), so the
// remainder x - q n is corrected by at most two subtractions. Exactly x % n.
class FixedModulo {
 public:
  explicit FixedModulo(std::uint64_t n = 1) : n_(n), m_(~std::uint64_t(0) / n) {}
  std::uint64_t operator()(std::uint64_t x) const {
    __extension__ using Wide = unsigned __int128;
    const std::uint64_t q = static_cast<std::uint64_t>((static_cast<Wide>(x) * m_) >> 64);
    std::uint64_t r = x - q * n_;
    while (r >= n_) r -= n_;
    return r;
  }

 private:
  std::uint64_t n_, m_;
};

// What the basic step reads of a sample: the point and its oriented normal, side by side (one or
// two cache lines per draw instead of two far apart). Large arrays are advised for transparent
// huge pages (Linux): a uniform draw over a large cloud otherwise misses the TLB on most steps.
struct DrawSample {
  Vec3 point;
  Vec3 normal;  // oriented normal, zero when the loop does not orient the winners
};
class DrawSamples {
 public:
  void assign(const std::vector<Vec3>& points, const std::vector<Vec3>* normals);
  const DrawSample& operator[](std::size_t i) const { return data_.get()[i]; }

 private:
  struct Free {
    void operator()(DrawSample* p) const { std::free(p); }
  };
  std::unique_ptr<DrawSample, Free> data_;
};
static_assert(std::is_trivially_destructible_v<DrawSample>, "DrawSamples frees without destructors");

// Drops the points that repeat an earlier one exactly (with their normals); the others keep their
// input order. Returns how many were dropped. Sorts a copy: O(n log n).
std::size_t drop_repeated_points(edgefront::PointCloud& c);

}  // namespace detail

using detail::Clock;
using detail::DrawSample;
using detail::DrawSamples;
using detail::FixedModulo;
using detail::face_normal_of;
using detail::seconds_since;

struct Reconstructor::Impl {
  ReconstructOptions opt;
  edgefront::PointCloud cloud;  // centred
  Vec3 offset{0, 0, 0};
  double bbox_diagonal = 0;
  double noise_ratio = 0;  // estimated noise / spacing of the input (InputOptions::smooth_noise_ratio)
  bool cloud_smoothed = false;
  size_t normals_filled = 0;     // missing input normals fitted (fill_missing_normals)
  bool normals_unusable = false;  // the cloud had normals, none usable
  double sample_spacing = 0;
  // The nearest-sample queries (topology passes, projection, normal fits): a k-d tree over the
  // whole (static, centred) cloud, or for a large cloud with normals over a spatially even
  // subsample of it (InputOptions::max_query_points), whose points and normals are then
  // kept side by side in tree order (query_points, subsample.normals: no scattered reads in the
  // cloud).
  std::unique_ptr<PointIndex> tree;
  // Subsampled: the tree's points and their input normals (OperationContext::query_points); else
  // empty.
  edgefront::PointCloud subsample;
  const std::vector<Vec3>* query_points = nullptr;  // the tree's points: the cloud's or the subsample's
  std::vector<PointIndex::Neighbor> knn;  // query scratch
  std::vector<Vec3> fitted_normal;  // lazily fitted normals (inputs without normals)
  std::vector<double> fitted_residual;  // with quadric_normals: their fits' residuals (orient_normals' noise)
  bool oriented = false;  // orient_winners with input normals or orientable fitted ones (double_layer.h)
  bool encloses = false;  // oriented, and the oriented normals point outward as around a volume
  std::vector<Vec3> oriented_fitted;  // without input normals: the fitted normals, oriented

  Mesh mesh;
  detail::VertexGrid grid;
  std::vector<double> tau;  // scaled counters: true counter = tau * scale
  double scale = 1.0;
  double decay = 1.0;
  detail::CounterHeap order;  // the scaled counters of the live vertices, most active on top
  std::vector<std::uint64_t> last_win;
  std::vector<std::uint64_t> vstamp, fstamp;
  std::uint64_t clock = 1;
  size_t live = 0;
  // The mesh is renumbered in spatial order (memory locality of the basic step) when the live
  // vertex count reaches this; then at 1.5 times that count, and so on (reorder_if_due).
  size_t next_reorder_live = 2048;  // smaller meshes fit in the caches

  std::mt19937_64 rng;
  static constexpr size_t kNoSample = std::numeric_limits<size_t>::max();
  size_t next_sample = kNoSample;  // the sample of the next basic step, drawn ahead (basic_step)
  DrawSamples draw;  // the cloud's points with their oriented normals, for the basic step
  FixedModulo draw_mod;  // % cloud.size()
  std::uint64_t steps = 0;
  std::uint64_t next_collapse_scan = 0;
  size_t splits = 0, collapses = 0, faces_removed = 0, loops_merged = 0, slits_zipped = 0, holes_filled = 0, batches = 0;
  size_t splits_in_batch = 0;
  size_t topology_last_live = 0;
  double seconds_ops = 0, seconds_topology = 0;
  bool finished = false;
  StopReason finished_reason = StopReason::target_reached;

  struct Registered {
    std::shared_ptr<Operation> op;
    std::uint64_t last = 0;
    OperationReport report;
  };
  std::vector<Registered> ops;

  // Snapshot of face vertex triples for detecting what an operation re-connected.
  std::vector<std::array<int, 3>> face_snapshot;


  // ---------------------------------------------------------------- setup
  void init(edgefront::PointCloud points, const ReconstructOptions& options, const ProgressCallback& progress);

  // A large cloud queried whole is put in spatial (Morton) order once: the kd-tree's leaves and
  // the nearest-sample queries of the topology passes (over faces that are in spatial order too,
  // see reorder_if_due) then touch far fewer cache lines. The samples are drawn uniformly by index,
  // so the draws keep their distribution. Small clouds fit in the cache and keep their order.
  static constexpr size_t kSpatialSortMinPoints = 65536;
  // InputOptions::max_query_points = 0: max(kAutoQueryPoints, kAutoQueryPerVertex * target).
  static constexpr size_t kAutoQueryPoints = 100000, kAutoQueryPerVertex = 5;
  // The tree over a spatially even subsample of at most `limit` points: the cloud in a coarse
  // Morton order (cheaper than sort_cloud_spatially's, as good for the surface fit's walk over
  // the samples), then one point out of every run (detail::stride_subsample).
  void build_subsampled_tree(size_t limit);

  void sort_cloud_spatially() { permute_cloud(detail::morton_order(cloud.points)); }
  void permute_cloud(const std::vector<size_t>& perm);

  void build_start_mesh(Vec3 lo, Vec3 hi);

  // ---------------------------------------------------------------- bookkeeping
  void ensure_sizes();

  void set_tau(int v, double true_value) {
    tau[v] = true_value / scale;
    order.set(v, tau[v]);
  }
  double true_tau(int v) const { return tau[v] * scale; }
  void drop_tau(int v) {
    order.erase(v);
    tau[v] = -1.0;
  }
  void update_decay() {
    decay = std::pow(0.5, 1.0 / (opt.growth.decay_half_life * static_cast<double>(std::max<size_t>(live, 1))));
  }
  std::uint64_t collapse_window() const {
    return static_cast<std::uint64_t>(std::ceil(opt.growth.inactivity_window * static_cast<double>(live)));
  }
  void renormalize();
  void stamp(VertexHandle v) { vstamp[v.idx()] = clock; }
  void stamp_ring(VertexHandle v);

  double mean_edge_length() const;

  // The input normal of point i, or (without input normals) its fitted normal: with
  // quadric_normals fit_normals' (cloud_normals.h), all fitted on first use; else the normal of a
  // plane fitted to its 20 nearest points, computed once on first use, NaN where the neighbourhood
  // is not flat. Either is unsigned, NaN where undefined. (A cloud without normals is never
  // subsampled: the tree indices are cloud indices here.)
  const Vec3& point_normal(size_t i);

  const Vec3& oriented_normal(size_t i) const { return cloud.has_normals() ? cloud.normals[i] : oriented_fitted[i]; }

  // The normal of tree point k: point_normal (the input or the fitted one) for cloud_query,
  // oriented_normal for the others; both are the input normal in a subsample.
  const Vec3& query_point_normal(size_t k);
  const Vec3& query_oriented_normal(size_t k) const {
    return subsample.empty() ? oriented_normal(k) : subsample.normals[k];
  }

  // The part of the searched cloud (detail::cloud_parts) that tree point k lies on; the parts
  // are found on the first call (only a pass that would remove a piece asks).
  std::vector<int> query_parts;
  int query_point_part(size_t k);

  detail::CloudHit cloud_query(const Vec3& p);

  // The k samples nearest to p with their oriented normals (the film test of the border creation).
  std::vector<PointIndex::Neighbor> knn_oriented;  // its scratch (point_normal uses knn)
  void oriented_neighbors(const Vec3& p, size_t k, std::vector<detail::CloudHit>& out);

  // ---------------------------------------------------------------- geometry helpers
  double mean_adjacent_edge_length(VertexHandle v) const;

  // ---------------------------------------------------------------- the basic step
  void basic_step();
  // n basic steps (Reconstructor::run_basic_steps): no splits, collapses or batches.
  void basic_steps(std::uint64_t n);
  // One growth step of run(): steps_per_split basic steps (with the collapse scans that fall due
  // among them), then the split of the most active vertex. Defined with basic_step in one
  // translation unit so that the loop's innermost calls stay inlinable.
  void grow_until_split();
  // The global decay of every basic step (with or without a winner).
  void end_step() {
    scale *= decay;
    if (scale < 1e-150) renormalize();
    ++steps;
  }

  // The winner's 1-ring (the members) with the ring of each member, gathered once per basic step
  // as vertex ids, so that the smoothing passes run over two small arrays instead of re-walking
  // the halfedge structure. The rings are read from the neighbour cache (one line per vertex).
  struct RingCache {
    struct Member {
      int vid;               // the member's vertex id
      int begin, end;        // its neighbours: entries [begin, end)
      int border_a = -1;     // border members: the two border neighbours (vertex ids)
      int border_b = -1;
      bool winner_face = false;  // the winner's outgoing halfedge to this member has a face
      double inv_k = 0;      // 1 / (end - begin)
      double n0 = 0, n1 = 0, n2 = 0;  // its normal for this basic step (smooth_member_first)
      double inv_nn = 0;              // 1 / |n|^2, 0 without a usable normal
    };
    struct Entry {
      int a;  // neighbour, in outgoing-halfedge order
      int b;  // the next vertex of the face of that halfedge, -1 at a border
    };
    std::vector<Member> members;
    std::vector<Entry> entries;
  } ring;
  detail::NeighborCache neighbors;
  // Rings longer than the cache holds, walked (neighbour ids and face flags in voh order).
  struct WalkedRing {
    std::vector<int> nb;
    std::vector<char> face;
  } walked_winner, walked_member;

  // v's neighbours in the order of mesh.voh_range(v) and whether each outgoing halfedge has a
  // face: from the neighbour cache, or walked into `scratch` for rings it does not hold.
  template <class F>
  void with_ring(VertexHandle v, WalkedRing& scratch, F&& f);

  void gather_ring(VertexHandle w);

  // The winner's area-weighted normal (detail::vertex_normal_sum: the same sum in the same order)
  // from the ring gathered for it, at the current positions.
  Vec3 ring_normal_sum(int wi) const;

  // The tangential Laplacian update of ring member m (border vertices: along the border only):
  // the ring mean minus the vertex, without its component along the member's area-weighted
  // normal n: L_t = L - (L.n / n.n) n (no square root). The normal is computed in the first pass
  // of a basic step (smooth_member_first) and kept for the other passes: a pass moves the members
  // by 5% of their Laplacian, which turns the normal by a small fraction of a degree, so the
  // recomputation bought nothing measurable (bench/results/gcs.md, session 6) at about half of the
  // smoothing's cost. On scalars so that the compiler keeps the values in registers; `pos` is the
  // mesh's position array.
  void smooth_member(Vec3* pos, const RingCache::Member& m) const;

  // The first pass: computes and keeps m's normal (sum over its faces of the cross products, taken
  // relative to the member), then updates it as above.
  void smooth_member_first(Vec3* pos, RingCache::Member& m) const;

  // ---------------------------------------------------------------- vertex split
  // mesh.valence(x) and mesh.is_boundary(x) (whether x's outgoing halfedge has no face) from the
  // neighbour cache.
  unsigned valence_of(VertexHandle x);
  bool border_of(VertexHandle x);

  bool flip_geometry_ok(EdgeHandle e) const;

  // Flips the edge of `h` (which runs between v and a neighbour) so that m gains a neighbour.
  bool try_flip(HalfedgeHandle h);

  // Valence-driven edge flips on the edges at v and m (a design addition to the paper's split,
  // which alone leaves about a quarter of the vertices at valence 6 on a sphere): an edge is
  // flipped when that lowers the squared deviation of its four vertices from the ideal valence
  // (6 inside, 4 on a border), the two triangles are nearly coplanar and none folds.
  void improve_valences(VertexHandle v, VertexHandle m);

  void split_most_active();

  // Splits append vertices, edges and faces at the ends of the mesh's arrays, so a vertex's ring
  // spreads over memory as the mesh grows; renumbering the mesh in spatial order (Morton) brings
  // it back together (fewer cache misses per basic step on large meshes). Registered operations
  // may keep handles between their calls: only when all of them can follow (operation.h), and they
  // get the maps. Also drops the deleted elements.
  void reorder_if_due();

  // ---------------------------------------------------------------- collapses
  double collapse_cost(HalfedgeHandle h);

  bool collapse_geometry_ok(HalfedgeHandle h) const;

  bool try_collapse(VertexHandle v);

  void collapse_inactive();

  // ---------------------------------------------------------------- resync after foreign changes
  void snapshot_faces();

  // Brings counters, grid and stamps in line with a mesh changed by someone else.
  void resync();

  void full_rebuild();

  // `target`: mean_edge_length() of the mesh as it is.
  void rebuild_grid_if_needed(double target);

  // ---------------------------------------------------------------- batches
  ChangeSet changes_since(std::uint64_t last) const;

  // A face farther than this from every sample is unsupported (ell: the mean edge length).
  double support_distance(double ell) const { return opt.topology.unsupported_distance * std::max(ell, sample_spacing); }
  // Faces added across a border (loop merges, slit zips, hole fills) may lie up to 1.5 times as
  // far from the samples as a face may before it is removed: a hysteresis, so that the strip
  // across a sparsely sampled stretch is not refused by the test that tore it open.
  static constexpr double kBridgeSlack = 1.5;
  double bridge_distance(double ell) const { return kBridgeSlack * support_distance(ell); }

  // `ell`: mean_edge_length() of the mesh as it is. Returns false when the pass was not due (the
  // mesh is then unchanged).
  bool topology_pass(bool force, double ell);

  // Splits per batch at the current size (GrowthOptions::batch_growth_vertices).
  size_t batch_size() const {
    const size_t g = opt.growth.batch_growth_vertices;
    if (g == 0 || live <= g) return opt.growth.batch_splits;
    return static_cast<size_t>(std::ceil(static_cast<double>(opt.growth.batch_splits) * static_cast<double>(live) /
                                         static_cast<double>(g)));
  }

  void end_batch(bool final_call);

  // `ell`: mean_edge_length() of the mesh as it is; returns it after the operations.
  double run_operations(bool final_call, double ell);

  // `step(fraction)` is called before each post-processing step and at the end (may be empty).
  ReconstructResult make_result(double seconds, const std::function<void(double)>& step = {});

  ReconstructResult run(const ProgressCallback& progress);

  // ---------------------------------------------------------------- validation
  void validate() const;
};

}  // namespace gcs
