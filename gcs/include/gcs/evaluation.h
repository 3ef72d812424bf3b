#pragma once
/// \file evaluation.h
/// How a reconstruction is judged (`/work/shared/notes/gcs-and-twist.md` §5): distances to a
/// ground truth (Chamfer-L1, Hausdorff and its 95th percentile, F-scores), normal and
/// orientation consistency, and the validity of the result mesh (manifoldness, components,
/// border loops, genus, self-intersecting face pairs, valences, minimum angles).
///
/// \code
///   edgefront::Mesh mesh = edgefront::load_mesh("kitten-gcs.off");
///   gcs::GroundTruth gt = gcs::GroundTruth::from_points(edgefront::read_points("kitten.xyz"));
///   gcs::Evaluation e = gcs::evaluate(mesh, gt);
///   std::cout << gcs::format_evaluation(e);   // or gcs::evaluation_to_json(e)
/// \endcode
///
/// Method (exact, no approximation beyond the sampling):
/// - A mesh is represented by `samples` area-uniform random points (seeded; a face is picked with
///   probability proportional to its area, then a uniform point in it), each with its face's
///   normal. A point-set ground truth is used as it is: all of its points.
/// - Distance *to a mesh* is the exact point-to-triangle distance, found with a bounding-volume
///   hierarchy (axis-aligned boxes, median split, leaves of up to 4 triangles) over the mesh's
///   triangles and a nearest-first traversal that prunes by box distance (or, with
///   `exact_surface_distance = false`, the distance to the nearest of the mesh's samples).
///   Distance *to a point set* is the distance to its nearest point (a nanoflann kd-tree).
/// - Result -> ground truth distances are taken from the result's samples ("accuracy", the
///   precision side); ground truth -> result distances from the ground truth's points or samples
///   ("completeness", the recall side).
/// - Normals: a result sample's normal is its face's normal; the ground truth's normal at the
///   nearest point is the point's normal (oriented point set) or the nearest triangle's normal
///   (mesh). Since the samples are area-uniform, shares of samples estimate shares of area.
/// - Self-intersections: every pair of faces whose boxes overlap (same hierarchy,
///   edgefront::TriangleBvh) is tested with edgefront::triangles_intersect, the kernel's
///   tolerance-guarded triangle-triangle test (each edge of one triangle against the other
///   triangle, coplanar cases in 2D) that the twist detector uses too. Faces sharing an edge count only when they
///   are coplanar and folded onto each other; faces sharing a vertex count only when they meet
///   beyond it. "Sharing" is by vertex index: faces that merely touch (also at distinct but
///   coincident vertices, as along an unwelded seam) count. The counts agree with CGAL's
///   Polygon_mesh_processing::self_intersections on CGAL's sample models and the test shapes
///   (bench/cgal_self_intersection_reference).
///
/// Cost: O((S + G) log F) for S result samples, G ground-truth points/samples, F faces; 100K
/// samples against 100K faces take well under a few seconds (see bench/results/).

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "edgefront/mesh.h"
#include "edgefront/point_cloud.h"

namespace gcs {

/// Options of `evaluate` and `orientation_consistency`.
struct EvaluationOptions {
  /// Area-uniform samples per mesh surface (the result, and a mesh ground truth), in [1, 10^8].
  std::size_t samples = 100000;
  /// Seed of the sampling (same seed, same figures); any value.
  std::uint64_t seed = 1;
  /// F-score thresholds as fractions of the ground truth's bounding-box diagonal; each finite
  /// and > 0. Default 0.5% and 1%.
  std::vector<double> fscore_thresholds = {0.005, 0.01};
  /// Count self-intersecting face pairs (the most expensive validity check; O(F log F)).
  bool self_intersections = true;
  /// How the distance *to a mesh* is measured: true (default) the exact distance to its surface;
  /// false the distance to the nearest of its `samples` samples, i.e. point-to-point both ways
  /// as in many published evaluations (and the kitten figures of anchors.md). The point-to-point
  /// variant adds the sampling gap (about 0.5 / sqrt(samples / area)) to every distance to a mesh.
  bool exact_surface_distance = true;
  /// Threads for the nearest-point queries and the self-intersection count, >= 0; 0 (the
  /// default) = all cores. The figures are the same for any count.
  unsigned threads = 0;
};

/// What a reconstruction is compared with: an oriented or unoriented point set, or a mesh.
class GroundTruth {
 public:
  /// A point set (with per-point unit normals, or without: then normal and orientation
  /// consistency are not available).
  static GroundTruth from_points(edgefront::PointCloud cloud);
  /// A triangle mesh: sampled like the result; its face normals give the orientation.
  static GroundTruth from_mesh(edgefront::Mesh mesh);

  /// True when the ground truth is a mesh (else a point set).
  bool is_mesh() const { return std::holds_alternative<edgefront::Mesh>(data_); }
  /// True for a mesh and for a point set with normals.
  bool has_normals() const;
  /// \pre !is_mesh()
  const edgefront::PointCloud& points() const { return std::get<edgefront::PointCloud>(data_); }
  /// \pre is_mesh()
  const edgefront::Mesh& mesh() const { return std::get<edgefront::Mesh>(data_); }

 private:
  explicit GroundTruth(std::variant<edgefront::PointCloud, edgefront::Mesh> data) : data_(std::move(data)) {}
  std::variant<edgefront::PointCloud, edgefront::Mesh> data_;
};

/// Nearest distances from one surface to the other, over its samples/points.
struct OneSidedDistance {
  std::size_t count = 0;  ///< samples or points measured
  double mean = 0;        ///< mean nearest distance (absolute length units)
  double rms = 0;         ///< root mean square
  double median = 0;      ///< median nearest distance
  double p95 = 0;  ///< 95th percentile (nearest rank: the ceil(0.95 n)-th smallest)
  double max = 0;  ///< one-sided Hausdorff distance (over the samples)
};

/// Precision, recall and F-score at one distance threshold.
struct FScore {
  double threshold_fraction = 0;  ///< of the ground truth's bbox diagonal
  double threshold = 0;           ///< absolute
  double precision = 0;           ///< share of result samples within `threshold` of the ground truth
  double recall = 0;              ///< share of ground-truth points/samples within `threshold` of the result
  double fscore = 0;              ///< 2 P R / (P + R); 0 when both are 0
};

/// Orientation of one connected component of the result against the ground truth.
struct ComponentOrientation {
  std::size_t faces = 0;    ///< live faces of the component
  std::size_t samples = 0;  ///< result samples on the component
  double area_share = 0;    ///< share of the result's area (estimated by samples)
  double agreeing = 0;      ///< share of the component's samples with n·n_gt > 0 (as it is)
  bool flipped = false;     ///< the component agrees better with its orientation reversed
};

/// Share of result area whose normal agrees with the ground truth's side (n·n_gt > 0).
struct OrientationConsistency {
  double raw = 0;            ///< as the mesh is
  double per_component = 0;  ///< each component with its better global sign: what a repair can reach by
                             ///< flipping whole components
  double unsigned_consistency = 0;  ///< mean |n·n_gt|, i.e. normal consistency
  /// Indexed by the component label of edgefront::connected_components(result); components
  /// without faces (isolated vertices) or without samples have `samples == 0`.
  std::vector<ComponentOrientation> components;
};

/// Validity of the result mesh (live elements only).
struct MeshValidity {
  ///@{
  /// Live vertices, edges and faces.
  std::size_t vertices = 0, edges = 0, faces = 0;
  ///@}
  /// OpenMesh's halfedge structure cannot hold an edge with more than two faces (read_mesh drops
  /// such faces and says so in its report), so this is always 0 for an edgefront::Mesh; kept so
  /// the report states it.
  std::size_t nonmanifold_edges = 0;
  std::size_t nonmanifold_vertices = 0;  ///< vertices whose faces form more than one fan
  /// Not measured here: set by a caller that read the mesh from a file (gcs-eval sets it from
  /// edgefront::MeshReadReport::faces_dropped_nonmanifold): faces of the file that would have
  /// made an edge or vertex non-manifold and were dropped, so the file was not manifold.
  std::size_t faces_dropped_when_read = 0;
  bool edge_manifold = true;    ///< no edge with more than two faces (always true for an edgefront::Mesh, see above)
  bool vertex_manifold = true;  ///< no non-manifold vertex
  std::size_t components = 0;  ///< connected components (isolated vertices included)
  std::size_t border_loops = 0;   ///< cycles of boundary halfedges
  bool closed = false;  ///< no border loops
  long euler_characteristic = 0;  ///< V - E + F over live elements
  /// Sum of the components' genus (each (2 - chi - borders) / 2); a half-integer hints at a
  /// non-manifold or non-orientable part.
  double genus = 0;
  std::vector<double> component_genus;  ///< per component, as edgefront::MeshStats
  std::size_t isolated_vertices = 0;  ///< live vertices without an incident edge
  std::size_t degenerate_faces = 0;  ///< see edgefront::kDegenerateAreaFactor
  std::size_t duplicate_faces = 0;   ///< faces with the vertex set of a face with a lower index
  /// Face pairs that intersect beyond a shared vertex or edge (nullopt when not computed).
  std::optional<std::size_t> self_intersecting_pairs;
  std::vector<std::size_t> valence_histogram;  ///< [k] = vertices with k incident edges
  double min_angle_deg = 0;                    ///< smallest interior angle over all faces (degrees)
  double median_min_angle_deg = 0;             ///< median over faces of each face's smallest angle
  double faces_min_angle_below_10 = 0;         ///< share of faces whose smallest angle is < 10 degrees
  double faces_min_angle_below_30 = 0;         ///< share of faces whose smallest angle is < 30 degrees
  double area = 0;                             ///< total surface area
};

/// Everything `evaluate` measures.
struct Evaluation {
  bool ground_truth_is_mesh = false;    ///< the ground truth was a mesh (else a point set)
  bool exact_surface_distance = true;   ///< as in the options
  std::size_t ground_truth_points = 0;  ///< points (point set) or samples (mesh) measured
  double gt_bbox_diagonal = 0;          ///< the scale of every "percent" below
  double scale(double absolute) const {
    return 100.0 * absolute / gt_bbox_diagonal;
  }  ///< absolute -> % of diagonal

  OneSidedDistance result_to_gt;  ///< accuracy (from the result's samples)
  OneSidedDistance gt_to_result;  ///< completeness (from the ground truth's points/samples)
  double chamfer_l1 = 0;          ///< (result_to_gt.mean + gt_to_result.mean) / 2
  double hausdorff = 0;           ///< max of the two one-sided maxima
  double hausdorff_p95 = 0;       ///< max of the two one-sided 95th percentiles
  std::vector<FScore> fscores;    ///< one per threshold of the options, same order

  /// Mean |n·n_gt| over the result's area; nullopt for an unoriented point-set ground truth.
  std::optional<double> normal_consistency;
  /// nullopt for an unoriented point-set ground truth ("not available").
  std::optional<OrientationConsistency> orientation;

  MeshValidity validity;  ///< the result mesh's validity
};

/// Judges `result` against `gt` (see the file comment for the method).
/// \throw edgefront::InvalidInput for: a result without vertices or without faces of positive
///        area, a ground truth without points or faces of positive area (a point set of one
///        point or of identical points: zero bounding-box diagonal), non-finite coordinates or
///        normals (naming the vertex or point), zero normals, normals of another count than the
///        points, `samples` outside [1, 10^8], non-positive or non-finite thresholds.
Evaluation evaluate(const edgefront::Mesh& result, const GroundTruth& gt,
                    const EvaluationOptions& options = {});

/// Orientation consistency of `mesh` against an oriented point set (for instance analytic
/// samples from edgefront::shapes::sample): area-uniform samples of the mesh, each compared with
/// the normal of its nearest ground-truth point. Same method and options (samples, seed) as
/// `evaluate`, without the rest of the evaluation. The measure to judge a reconstruction with;
/// twist::face_orientation_agreement (twist/reference_normals.h) is the cheaper, deterministic
/// one-vote-per-face share that estimates `raw` without sampling (what ef-twist prints).
/// \throw edgefront::InvalidInput as `evaluate`, and when `oriented_gt` has no normals.
OrientationConsistency orientation_consistency(const edgefront::Mesh& mesh,
                                               const edgefront::PointCloud& oriented_gt,
                                               const EvaluationOptions& options = {});

/// Validity measures of `mesh` alone (no ground truth needed).
/// \throw edgefront::InvalidInput for non-finite coordinates.
MeshValidity mesh_validity(const edgefront::Mesh& mesh, bool count_self_intersections = true);

/// Number of face pairs of `mesh` that intersect beyond their shared vertices/edges (see the file
/// comment). \throw edgefront::InvalidInput for non-finite coordinates.
std::size_t count_self_intersections(const edgefront::Mesh& mesh);

/// Readable multi-line table of `e` (ends with a newline).
std::string format_evaluation(const Evaluation& e);

/// `e` as one JSON object (ends with a newline); non-finite numbers become null, unavailable
/// metrics are null.
std::string evaluation_to_json(const Evaluation& e);

}  // namespace gcs
