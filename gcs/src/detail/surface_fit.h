#pragma once
// Post-processing of the GCS result: a least-squares fit of the mesh to the samples.
//
// The loop leaves each vertex near the sampled surface (a running average of the samples it won,
// then smoothed), and a piecewise-linear surface through points *on* a curved surface still
// misses the samples between its vertices (the chord error). The fit moves each vertex along its
// normal so that the samples lie as nearly as possible on the triangles that are closest to them:
// for each sample p with closest mesh point q = sum_k b_k x_k on face f (unit normal m), the
// residual (p - q).m is a linear function of the vertices' normal displacements t_k:
//   sum_k b_k (n_k . m) t_k = (p - q) . m.
// These equations, a smoothness term (t_u - t_v)^2 per edge and a small pull toward t = 0 are
// solved in the least-squares sense (conjugate gradients), a few rounds with the closest points
// recomputed. With l1_weights, every round after the first weights each sample's equation by
// mean|r| / max(|r|, 0.1 mean|r|) (r: its residual at the start of the round, the mean over the
// round's samples): iteratively reweighted least squares toward the smallest mean distance (the
// evaluation's Chamfer-L1) instead of the smallest mean squared distance, so a few far samples
// (noise, the other side of a crease) pull less and the many near ones are met more closely. Tangential positions do not change (angles and valences stay as the loop made them).
// Guards: a vertex moves at most max_move in total; a face whose normal would turn by more than
// acos(min_face_cos) from where the fit started has its vertices' moves halved (up to 8 times,
// then dropped); both faces of every self-intersecting pair that the moves created have their
// vertices put back where they were (repeated until no face turns too far and no pair is new).

#include <cstddef>
#include <vector>

#include "edgefront/mesh.h"

namespace gcs::detail {

struct SurfaceFitParams {
  int rounds = 3;             ///< solve / recompute-closest-points rounds, >= 1
  double smoothness = 0.1;    ///< weight of (t_u - t_v)^2 per edge, relative to one sample, >= 0
  double max_move = 0;        ///< largest total move of a vertex (absolute length), > 0
  double max_sample_distance = 0;  ///< samples farther than this from the mesh are ignored, > 0
  double min_face_cos = 0.7;  ///< faces may turn by at most acos(this) from the start of the fit
  std::size_t max_samples = 0;  ///< use at most this many samples (an even stride); 0 = all
  /// The normals passed to fit_to_samples are oriented like the mesh: a sample is then also
  /// ignored when its normal points against its closest face's (the other side of a thin shell).
  bool oriented_normals = false;
  bool measure_after = true;  ///< fill SurfaceFitReport::mean_distance_after (one more search pass)
  bool l1_weights = true;     ///< rounds after the first reweight the samples (see the file comment)
};

struct SurfaceFitReport {
  std::size_t samples_used = 0;   ///< samples within max_sample_distance in the first round
  std::size_t vertices_moved = 0;
  double mean_distance_before = 0;  ///< mean distance of those samples to the mesh, before
  double mean_distance_after = 0;   ///< ... and after the fit (closest points recomputed; 0 without measure_after)
  std::size_t intersections_undone = 0;  ///< new self-intersecting pairs whose faces were put back
};

/// Fits the live vertices of `mesh` to `samples` (see the file comment). `normals` is empty or
/// one (unoriented) normal per sample: a sample whose normal makes |cos| < 0.3 with its closest
/// face (a sample of another layer; with oriented_normals, cos < 0.3) is ignored; a sample whose
/// normal is zero or not finite is used. Face normals are updated on return.
/// \throw edgefront::InvalidInput for parameters out of range or a normals count other than the
///        samples' (the caller checks the samples: finite).
SurfaceFitReport fit_to_samples(edgefront::Mesh& mesh, const std::vector<edgefront::Vec3>& samples,
                                const std::vector<edgefront::Vec3>& normals, const SurfaceFitParams& params);

/// Mean distance from `samples` (those within max_distance) to the surface of `mesh`, with the
/// closest point searched among the faces around the 3 mesh vertices nearest to each sample.
/// Returns 0 when no sample is within max_distance.
double mean_sample_distance(const edgefront::Mesh& mesh, const std::vector<edgefront::Vec3>& samples,
                            double max_distance);

}  // namespace gcs::detail
