#pragma once
/// \file reconstructor.h
/// Growing-cell-structures (GCS) surface reconstruction: a point cloud in, a triangle mesh out.
///
/// The loop of Ivrissimtzis, Jeong & Seidel, "Using Growing Cell Structures for Surface
/// Reconstruction" (SMI 2003): a closed start mesh scaled to the cloud; each *basic step* draws a
/// random sample, moves the nearest mesh vertex (the winner) toward it, smooths the winner's
/// 1-ring tangentially and counts the win in a decaying signal counter; after `steps_per_split`
/// basic steps the most active vertex is split; vertices that won nothing for a while are
/// removed by an edge collapse (valence cost, link condition, no normal flips). Every
/// intermediate mesh is a valid oriented 2-manifold triangle mesh (with borders once topology
/// changes are on). Topology (neural-mesh style, Ivrissimtzis et al. 2004): triangles that no
/// sample supports and overlong edges are removed, creating borders; two border loops that are
/// close, of similar length and orientation-compatible are joined by a strip of triangles,
/// creating a handle (optionally, slits within one loop are zipped the same way); border loops of
/// at most 8 vertices whose fan would lie on the samples are closed, and so are slits of up to 64
/// vertices whose zipping strip would lie on the samples (see ReconstructOptions). A piece lying on
/// a part of the cloud of its own is a separate surface, not debris, and is not removed as such.
///
/// After each batch of splits the registered Operations (operation.h) are called with the
/// elements changed since their last call; the loop then re-synchronizes its own state.
///
/// \code
///   edgefront::PointCloud cloud = edgefront::read_points("data/vault-shell.xyz");
///   gcs::ReconstructResult r = gcs::reconstruct(cloud, {.target_vertices = 2000});
///   // or a preset: gcs::ReconstructOptions::thin_shell(), open_sheet() (see ReconstructOptions)
///   edgefront::write_mesh(r.mesh, "vault.ply");
/// \endcode

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "edgefront/mesh.h"
#include "edgefront/point_cloud.h"
#include "gcs/operation.h"

namespace gcs {

/// The closed mesh the loop starts from, scaled to the cloud's bounding box.
enum class StartShape {
  box,         ///< 8 vertices, 12 triangles (default)
  tetrahedron  ///< 4 vertices, 4 triangles (the paper's start)
};

/// How the growing-cell-structures loop grows the mesh (the paper's parameters and the loop's
/// batching). The defaults follow the paper where it gives a value.
struct GrowthOptions {
  StartShape start = StartShape::box;  ///< start mesh; default box
  /// Basic steps between two vertex splits (the paper's lambda). Default 100; >= 1.
  int steps_per_split = 100;
  /// Winner learning rate alpha_w: x_w += alpha_w (s - x_w). Default 0.06; in (0, 1].
  double winner_rate = 0.06;
  /// Neighbour smoothing rate alpha_n of the tangential Laplacian. Default 0.05; in [0, 1].
  double neighbor_rate = 0.05;
  /// Smoothing passes over the winner's 1-ring per basic step (the paper: 5). Default 5; in
  /// [0, 100].
  int smoothing_iterations = 5;
  /// Signal counter half-life in units of |V| basic steps: every basic step multiplies all
  /// counters by 0.5^(1 / (half_life * |V|)). Default 6; finite, > 0.
  double decay_half_life = 6.0;
  /// Inactivity window mu in units of |V| basic steps: every mu * |V| basic steps, vertices that
  /// have not won during the last mu * |V| steps are collapsed. Default 20; finite, >= 0; 0
  /// disables collapses.
  double inactivity_window = 20.0;
  /// Vertex splits between two calls of the registered operations and of the built-in topology
  /// pass; on meshes above batch_growth_vertices, more (see there). Default 200; >= 1.
  std::size_t batch_splits = 200;
  /// From this many live vertices on, a batch has ceil(batch_splits x live / batch_growth_vertices)
  /// splits, so that the per-batch costs (the operations' change sets, the loop's bookkeeping over
  /// all faces) stay a fixed share of the run instead of growing with the square of the target.
  /// Default 10,000 vertices; 0 = batches of batch_splits always.
  std::size_t batch_growth_vertices = 10000;
  /// Safety stop: at most this many basic steps per target vertex; the loop then stops with
  /// StopReason::step_limit (collapses keep the mesh from growing). Default 2000; 0 = no limit.
  std::uint64_t max_steps_per_vertex = 2000;
  /// Field by field.
  bool operator==(const GrowthOptions&) const = default;
};

/// The built-in topology pass after each batch (neural-mesh style): border creation, loop
/// merging, component joining and hole filling. Distances are in units of the mesh's mean edge
/// length (at least the sample spacing for the support distance).
struct TopologyOptions {
  /// The pass starts once the mesh has this many live vertices (a coarse mesh does not hug the
  /// samples yet); also when the oriented winner search starts (InputOptions::orient_winners).
  /// Default 150; clamped to at most target_vertices / 2.
  std::size_t min_vertices = 150;
  /// Remove triangles no sample supports (creates borders on open surfaces). Default true.
  bool create_borders = true;
  /// A face is unsupported when its centroid is farther than this many mean edge lengths from
  /// every input point. Default 1.5; finite, > 0.
  double unsupported_distance = 1.5;
  /// Edges longer than this many mean edge lengths are removed with their faces. Default 10;
  /// finite, > 1.
  double long_edge_factor = 10.0;
  /// Film test, for oriented samples that surround a volume (their normals point away from the
  /// centroid): faces all of whose this many nearest samples (within the support distance) face
  /// sideways to them and have them in front are removed (a film spanning a tunnel or gap outside
  /// the object). Default 8 samples; in [0, 64]; 0 disables.
  std::size_t film_samples = 8;
  /// Join close, similar, orientation-compatible border loops by a triangle strip (handles).
  /// Default true.
  bool merge_borders = true;
  /// For clouds that do not surround a volume (open sheets, landscapes) and a mesh of several
  /// components: border chains of two components that run within 2 mean edge lengths of each
  /// other in opposite directions are zipped by a strip that lies on the cloud and agrees with the
  /// faces around (a piece torn off an open sheet is joined back). Not used for clouds around a
  /// volume (it would zip nested surfaces together) nor with ExperimentalOptions::zip_slits.
  /// Default true.
  bool join_components = true;
  /// Border loops of 9 up to this many vertices are closed by a strip zipping their two halves
  /// together when that strip lies on the cloud and agrees with the faces around (a slit torn into
  /// a closed surface where the samples are sparse). Wide holes and open sheets fail these checks.
  /// Default 64 vertices; 0 disables.
  std::size_t fill_slits_max_vertices = 64;
  /// When the strip joining two border loops is refused (its faces fold back against the faces
  /// around: curled or overlapping rims), or the fan closing a hole whose border is at most 10
  /// mean edge lengths long is refused, the join or fill is tried again with 1 ... this many rings
  /// of faces removed along the loop(s) (on a copy, kept only when the strip or fan is then added
  /// and no piece is cut off). Default 2 rings; in [0, 8]; 0 disables.
  std::size_t border_trim_rings = 2;
  /// Field by field.
  bool operator==(const TopologyOptions&) const = default;
};

/// How the input cloud is prepared and used: normals, noise, nearest-sample queries.
struct InputOptions {
  /// Oriented samples keep an open or planar cloud from ending as the start box collapsed onto it
  /// from both sides (a double layer): once the mesh has TopologyOptions::min_vertices vertices, a
  /// sample's winner is the nearest vertex whose normal agrees with the sample's (among its 8
  /// nearest), and faces that face against the nearest sample's normal are removed with the
  /// unsupported ones. The samples' normals are the input normals; without them, normals fitted to
  /// each point's neighbours (see quadric_normals) and oriented consistently over the neighbour
  /// graph (outward, or for a nearly flat open cloud along the positive side of its thinnest
  /// axis); not used when that graph is not connected. Default true.
  bool orient_winners = true;
  /// Clouds without normals only: fit them by gcs::fit_normals (a quadric's normal at the point,
  /// cloud_normals.h) and orient them with the reflection agreement and island links, instead of
  /// the default plane through each point's 20 nearest (undefined unless its smallest eigenvalue
  /// is < 5% of the middle one, oriented by Hoppe's criterion). The fitted normals are closer to the
  /// truth and far less often undefined; thin shells and open sheets without normals come out more
  /// consistently oriented and with fewer border loops, but coarse scans of figures get more border
  /// loops (the border tests, which undefined normals switch off, then act everywhere; see
  /// bench/results/gcs.md). Default false; ignored for clouds with normals.
  bool quadric_normals = false;
  /// Noisy clouds are smoothed first: the noise is estimated (gcs::estimate_noise, cloud_noise.h)
  /// and when it exceeds this share of the point spacing, every point is moved onto the quadric
  /// fitted to its 64 nearest points (gcs::smooth_noise). The loop and the post-processing then use
  /// the smoothed points (closer to the true surface, farther from the noisy points; see
  /// bench/results/gcs-noise.md). Default 0.05 (clean scans estimate below it); >= 0 and not NaN;
  /// 0 smooths every cloud; infinity turns it off.
  double smooth_noise_ratio = 0.05;
  /// For a large cloud with input normals, the nearest-sample queries of the topology passes and
  /// of the projection search a spatially even subsample of at most this many points (one point
  /// out of every run of ceil(n / limit) in spatial order; which one depends on the seed) instead
  /// of the whole cloud, so that their cost and the set-up's do not grow with the cloud. The basic
  /// steps still draw from every point, and the surface fit uses its own even stride. Default 0 =
  /// automatic: max(100000, 5 * target_vertices); a cloud of at most that many points (or without
  /// normals) is used whole. Otherwise at least target_vertices.
  std::size_t max_query_points = 0;
  /// Field by field.
  bool operator==(const InputOptions&) const = default;
};

/// Post-processing of the returned mesh, in this order. The loop's own mesh
/// (Reconstructor::mesh()) is not changed by it. Angles in degrees, distances in mean edge lengths.
struct PostProcessOptions {
  /// Every vertex not on a border is moved onto the tangent plane of its nearest sample (input
  /// normal, or the normal fitted to the sample's neighbours), unless that moves it more than half
  /// a mean edge length or turns one of its faces by more than 60 degrees. Default true.
  bool project_to_samples = true;
  /// Interior edges whose two opposite angles sum to more than 180 degrees are flipped (toward a
  /// Delaunay triangulation on the surface) unless, within 30 degrees of 180, the flip takes the
  /// four vertices' valences farther from 6 (4 on a border); edges within 30 degrees below 180 are
  /// flipped when that brings the valences nearer 6; all where the two faces and the two new faces
  /// are within about 25 degrees of each other (creases stay), no end drops below valence 3 (2 on a
  /// border) and no self-intersecting face pair is created. Vertex positions do not change; most
  /// thin faces go. Default true.
  bool delaunay_flips = true;
  /// A least-squares fit that moves every vertex along its normal so that the samples lie on the
  /// triangles closest to them (the chord error included), with a smoothness term between
  /// neighbours; samples farther than a mean edge length from the mesh are ignored, and of more
  /// than 2 samples per vertex an even stride of 2 per vertex is used. Rounds after the first
  /// reweight the samples by their residuals (iteratively reweighted least squares toward the
  /// smallest mean distance). Guards: a vertex moves at most half a mean edge length, no face turns
  /// by more than 45 degrees, no self-intersecting face pair is created. Tangential positions do not
  /// change. Default true.
  bool fit_surface = true;
  /// Rounds of the fit (closest points recomputed each round). Default 3; in [1, 20].
  int fit_rounds = 3;
  /// Weight of the squared difference of two neighbours' moves, per edge, relative to one sample's
  /// squared residual. Default 0.1; finite, >= 0; larger is smoother and fits less.
  double fit_smoothness = 0.1;
  /// Rounds of removing small double layers at borders (`twist::remove_stacked_layers`, its
  /// defaults otherwise): a face touching the border that has a same-orientation partner stacked
  /// on it (close in space, far along the surface), in a group of at most 8 such faces, is
  /// removed; a small pair with no face on the border (a pleat, a Z fold) is smoothed flat where
  /// that makes no new folds. Large groups (a wall twisted front to back) are left; a mesh without
  /// a border is not scanned. Default 3; in [0, 16]; 0 = off.
  int stacked_layer_rounds = 3;
  /// Self-intersecting face pairs are resolved, last: the vertices of the crossing faces (then 1
  /// and 2 rings around them) are smoothed toward their neighbours' mean (at most half a mean edge
  /// length; moves that make new crossings or turn a face by more than 60 degrees are put back);
  /// of a pair still crossing one face is cut out (the one touching a border, else the one farther
  /// from the samples; no cut that would cut off a large piece), and the small holes the cut left
  /// (at most 8 vertices) are filled when their fans lie on the samples and cross nothing. A mesh
  /// without crossings keeps its bytes. Default true; false leaves the crossings.
  bool resolve_self_intersections = true;
  /// Last, false borders are closed: a border loop beyond which the cloud goes on (samples near
  /// it that no face covers, some of them more than an edge from the mesh: a tube of a closed
  /// figure torn open where it lies close to another part) is closed by a patch, the triangulation
  /// of the loop with the least fold (then area), refined to the mesh's edge length and pulled
  /// onto those samples; the patch is kept when its vertices lie on the samples, it hardly folds
  /// against the faces at its rim and crosses nothing (docs/reconstruction.md, "False borders").
  /// The rim of an open sheet or a real hole (no samples beyond it) stays open; a mesh without
  /// borders keeps its bytes. Default true; off in the open_sheet preset.
  bool close_false_borders = true;
  /// Loops with more vertices are not closed (the triangulation's cost grows with the cube of the
  /// loop's length). Default 800; in [3, 4000].
  std::size_t close_borders_max_vertices = 800;
  /// Field by field.
  bool operator==(const PostProcessOptions&) const = default;
};

/// Knobs that are off by default because their effect is mixed (better on some clouds, worse on
/// others: figures in bench/results/gcs.md, closed.md and twist-vaults.md). The presets set some of
/// them where they measured better; a plain call should not need them.
struct ExperimentalOptions {
  /// Also zip slits: close the gap between two chains of one border loop that run within 2 mean
  /// edge lengths of each other in opposite directions (a torn tube), within and across loops.
  /// Default false (on closed scans it split torn loops into several that the loop merge does not
  /// join).
  bool zip_slits = false;
  /// With InputOptions::orient_winners and input normals: the winner is the nearest vertex facing
  /// the sample's side among its 32 nearest (within about four mean edges of the nearest) instead
  /// of 8 (two), and a sample none of them faces is skipped (no winner, no move, no signal) instead
  /// of pulling the plain nearest vertex to it. On a thin closed shell (walls about one edge
  /// apart) the vertices nearest to a sample on a wall whose own layer is missing there lie on the
  /// other wall and face away: pulling them dents that wall into the gap; skipping lets the missing
  /// layer grow back from its border. Covers thin shells better (higher coverage, lower Chamfer
  /// distance, fewer border loops on most shells) but adds border loops on the thinnest ones; other
  /// clouds are unchanged or nearly so. Default false (the published oriented loop's fallback);
  /// ignored without input normals. Set by ReconstructOptions::thin_shell().
  bool skip_unfaced_samples = false;
  /// Field by field.
  bool operator==(const ExperimentalOptions&) const = default;
};

/// Options of the reconstruction: four top-level settings and groups for the loop's stages. The
/// defaults (= ReconstructOptions::scan()) suit most clouds; the presets change a few fields for
/// the kinds of cloud where the project measured better results with them:
///
/// \code
///   gcs::reconstruct(cloud, {.target_vertices = 2000});                      // the defaults
///   gcs::reconstruct(cloud, {.target_vertices = 2000, .post = {.fit_rounds = 5}});
///   gcs::ReconstructOptions o = gcs::ReconstructOptions::thin_shell();
///   o.target_vertices = 6000;
///   gcs::reconstruct(cloud, o);
/// \endcode
struct ReconstructOptions {
  /// Stop when the mesh has this many live vertices. Default 5000; in [4, number of distinct input
  /// points] and at most 50,000,000 (points that repeat an earlier one exactly are dropped first).
  std::size_t target_vertices = 5000;
  /// Seed of the sample draws: the same seed, input and options give the same mesh, byte for byte.
  /// Default 1; any value.
  std::uint64_t seed = 1;
  /// Threads for the phases that are parallel over points (noise estimate and smoothing, the
  /// quadric normal fits). Default 0 = all cores; at most edgefront's kMaxThreads. The loop itself
  /// is sequential; the mesh is the same bytes for any count.
  unsigned threads = 0;
  /// Call the progress callback every this many vertex splits (and once at the end). Default 100;
  /// >= 1.
  std::size_t progress_interval = 100;
  GrowthOptions growth{};              ///< the growing-cell-structures loop
  TopologyOptions topology{};          ///< border creation, merging and filling
  InputOptions input{};                ///< normals, noise smoothing, query subsample
  PostProcessOptions post{};           ///< post-processing of the returned mesh
  ExperimentalOptions experimental{};  ///< mixed-effect knobs, off by default

  /// The defaults: scans of objects (closed surfaces, with or without normals), landscapes and
  /// open sheets with normals.
  static ReconstructOptions scan();
  /// Thin closed shells (walls about a mesh edge apart, e.g. a vault's two faces): the winner
  /// search skips samples no nearby vertex faces (ExperimentalOptions::skip_unfaced_samples; with
  /// input normals) and clouds without normals get quadric normals (InputOptions::quadric_normals).
  /// Better coverage and orientation on most shells; it does not close them and can add border
  /// loops (figures: docs/reconstruction.md, "Options and presets").
  static ReconstructOptions thin_shell();
  /// Open sheets without normals (a vault's single surface, a terrain patch scanned without
  /// normals): quadric normals (InputOptions::quadric_normals) and no closing of false borders
  /// (PostProcessOptions::close_false_borders: every border of an open sheet is true).
  static ReconstructOptions open_sheet();
  /// The preset named `name` ("scan", "thin_shell", "open_sheet"; see preset_names()).
  /// \throw edgefront::InvalidInput for another name, listing the valid ones.
  static ReconstructOptions preset(const std::string& name);
  /// The names preset() accepts, in the order above.
  static std::vector<std::string> preset_names();
  /// Field by field, the groups included.
  bool operator==(const ReconstructOptions&) const = default;
};

/// Why run() stopped.
enum class StopReason {
  target_reached,  ///< the mesh has target_vertices live vertices
  cancelled,       ///< the progress callback returned false
  step_limit,      ///< GrowthOptions::max_steps_per_vertex * target_vertices basic steps were done
  shrunk_by_operations  ///< the target was reached, but the operations' final calls removed parts
                        ///< (e.g. twisted regions cut out) and 3 rounds of regrowing left the mesh
                        ///< below 90% of the target
};

/// "target reached", "cancelled", "step limit", or what shrunk_by_operations means.
std::string to_string(StopReason reason);

/// The phases of a reconstruction, in order. The first two run in the Reconstructor's
/// constructor, the last two in run().
enum class Phase {
  noise_estimate,   ///< estimating the cloud's noise and, when it is noisy, smoothing it
  normal_fitting,   ///< fitting normals: to every point of a cloud without normals (and orienting
                    ///< them), or to the points whose input normals are missing (non-finite or zero)
  growth,           ///< the growing-cell-structures loop (vertices counts up to the target)
  post_processing   ///< projection, Delaunay flips, surface fit, stacked layers, crossings
};

/// "noise estimate", "normal fitting", "growth", "post-processing".
std::string to_string(Phase phase);

/// Passed to the progress callback.
struct Progress {
  Phase phase = Phase::growth;      ///< what the reconstructor is doing now
  /// Share of the current phase done, in [0, 1] (growth: vertices / target_vertices; the other
  /// phases: 0 when they start, 1 when they end, steps in between where the phase has steps).
  double phase_fraction = 0;
  std::size_t vertices = 0;         ///< live vertices now (0 before growth)
  std::size_t target_vertices = 0;  ///< the target
  std::uint64_t basic_steps = 0;    ///< basic steps so far
  double seconds = 0;               ///< wall time since the phase's call (constructor or run()) started
};

/// Returns false to cancel the growth: the run stops at once and returns the valid mesh reached so
/// far. The return value is ignored in the other phases (they are not interruptible).
using ProgressCallback = std::function<bool(const Progress&)>;

/// What one registered operation did over a run.
struct OperationReport {
  std::string name;              ///< the operation's `name()`
  std::size_t calls = 0;         ///< calls of its apply(), the final call included
  std::size_t changes = 0;       ///< calls that reported mesh_changed
  double seconds = 0;            ///< total time spent in apply()
  std::string last_summary;      ///< the last non-empty summary
};

/// The result of a run.
struct ReconstructResult {
  edgefront::Mesh mesh;  ///< garbage-collected, face normals up to date; in input coordinates
  StopReason stop_reason = StopReason::target_reached;  ///< why the run stopped
  std::uint64_t basic_steps = 0;  ///< basic steps (sample draws with winner move and smoothing) run
  std::size_t splits = 0;         ///< vertex splits
  std::size_t collapses = 0;      ///< edge collapses of inactive vertices
  std::size_t faces_removed = 0;  ///< by the built-in border creation
  std::size_t loops_merged = 0;   ///< border loop pairs joined by the built-in merge
  std::size_t slits_zipped = 0;   ///< border slits (close, opposite-running border chains) closed
  std::size_t holes_filled = 0;   ///< small border loops (<= 8 vertices) closed by a fan, and slits
                                  ///< (up to TopologyOptions::fill_slits_max_vertices) closed by a strip
  std::size_t batches = 0;        ///< split batches (each followed by the operations and the topology pass)
  double seconds_total = 0;       ///< wall time of run()
  double seconds_operations = 0;  ///< of it: in registered operations
  double seconds_topology = 0;    ///< of it: in the built-in border creation and merging
  double seconds_fit = 0;         ///< of it: in the surface fit, Delaunay flips, stacked-layer removal and crossing resolution of the returned mesh
  std::size_t stacked_faces_found = 0;    ///< faces with a stacked same-orientation partner before that removal
  std::size_t stacked_faces_removed = 0;  ///< by the stacked-layer removal (PostProcessOptions::stacked_layer_rounds)
  std::size_t stacked_pleats_flattened = 0;  ///< stacked pairs inside the surface it smoothed apart
  ///@{
  /// Self-intersecting face pairs before the last post-processing step (resolve_self_intersections;
  /// 0 when it is off), and after it.
  std::size_t crossing_pairs_found = 0, crossing_pairs_left = 0;
  ///@}
  std::size_t crossing_vertices_moved = 0;  ///< by its smoothing
  std::size_t crossing_faces_removed = 0;   ///< cut out by it
  std::size_t crossing_holes_filled = 0;    ///< holes it filled after the cut
  std::size_t false_borders_found = 0;      ///< border loops judged false (PostProcessOptions::close_false_borders)
  std::size_t false_borders_closed = 0;     ///< of them closed by a patch
  double seconds_crossings = 0;             ///< of seconds_fit: in it (the crossing count included)
  std::vector<OperationReport> operations;  ///< one per registered operation, in order
  double noise_ratio = 0;          ///< the cloud's estimated noise / point spacing (InputOptions::smooth_noise_ratio)
  bool cloud_smoothed = false;     ///< the loop ran on the smoothed cloud
  /// Input normals that were missing (non-finite, or zero: e.g. dropped by edgefront::read_points
  /// with tolerate_invalid_normals) and were replaced by a normal fitted to the point's neighbours
  /// and oriented like the nearest given normals; 0 for a cloud without normals.
  std::size_t normals_filled = 0;
  /// The cloud had normals but none was usable: it was reconstructed as a cloud without normals.
  bool normals_unusable = false;
};

/// A reconstruction in progress: holds the mesh, the loop's state and the registered operations.
/// Not copyable; not thread-safe.
class Reconstructor {
 public:
  /// Checks the input, estimates its noise (smoothing a noisy cloud), fits the normals that are
  /// missing and builds the start mesh. Input normals that are not finite or are zero count as
  /// missing: each gets a plane fitted to its point's 16 nearest points, oriented like the sum of
  /// the 8 nearest given normals (ReconstructResult::normals_filled); when no normal is usable the
  /// cloud is taken as one without normals (ReconstructResult::normals_unusable).
  /// \param points   the cloud (normals optional; moved in)
  /// \param options  see ReconstructOptions
  /// \param progress called at the start and end of the noise estimate and of the normal fitting
  ///        (Progress::phase; may be empty; its return value is ignored here).
  /// \throw edgefront::InvalidInput for fewer than 4 points, NaN or infinite coordinates,
  ///        coordinates outside edgefront/coordinate_range.h's range, points
  ///        that all coincide or are collinear (no surface to reconstruct), and options out of
  ///        their documented ranges (target below 4 or above the number of distinct points, ...:
  ///        see max_target_vertices).
  explicit Reconstructor(edgefront::PointCloud points, const ReconstructOptions& options = {},
                         const ProgressCallback& progress = {});
  ~Reconstructor();
  Reconstructor(const Reconstructor&) = delete;
  Reconstructor& operator=(const Reconstructor&) = delete;

  /// Registers an operation, called after each batch (in registration order) and once more after
  /// the loop stops. \throw edgefront::InvalidInput for a null pointer.
  void add_operation(std::shared_ptr<Operation> operation);

  /// Runs until the target, a cancel or the step limit. The callback (may be empty) is called
  /// every `progress_interval` splits (Phase::growth), and at the start and after each step of
  /// the post-processing (Phase::post_processing; not after a cancel); in the growth it may call
  /// validate() and inspect mesh(). Calling run()
  /// again after a cancel continues from where it stopped; after the target it returns at once.
  /// The returned mesh is a garbage-collected copy in input coordinates.
  /// \throw whatever an operation throws (the reconstructor is then unusable).
  ReconstructResult run(const ProgressCallback& progress = {});

  /// Runs n basic steps (sample, winner move, smoothing, counters) without splits, collapses,
  /// batches or operations: the mesh keeps its connectivity. For measuring the cost of a basic step
  /// at a given mesh size (bench/bench_gcs.cpp).
  void run_basic_steps(std::uint64_t n);

  /// The current mesh, in the loop's internal coordinates (the input translated so that the
  /// cloud's bounding-box centre is the origin), with deleted elements not yet collected.
  const edgefront::Mesh& mesh() const;
  /// The translation from internal to input coordinates (add it to mesh() points).
  edgefront::Vec3 offset() const;

  /// Checks the loop's state against the mesh: every live vertex is in the spatial index at its
  /// current position and in the counter order with its counter, no deleted vertex is, the mesh is
  /// a manifold oriented triangle mesh without degenerate structure (each face a triangle with
  /// three distinct live vertices, consistent halfedge links, no non-manifold vertex), the
  /// counters are finite and non-negative. \throw edgefront::InternalError naming the first
  /// mismatch.
  void validate() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// The largest target_vertices the reconstructor accepts for `points`: the number of distinct
/// points (points repeating an earlier one exactly are not counted), at most 50,000,000. A
/// caller without a target of its own can take min(5000, max_target_vertices(points)).
std::size_t max_target_vertices(const edgefront::PointCloud& points);

/// One call: `Reconstructor(points, options, progress).run(progress)`.
ReconstructResult reconstruct(edgefront::PointCloud points, const ReconstructOptions& options = {},
                              const ProgressCallback& progress = {});

}  // namespace gcs
