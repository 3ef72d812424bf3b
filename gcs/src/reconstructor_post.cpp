// gcs::Reconstructor, post-processing of the returned mesh (a copy; the loop's own mesh stays as
// it is): projection onto the samples, Delaunay flips, surface fit, stacked-layer removal and
// resolution of self-intersections, then the result's figures.
#include <cmath>
#include <numbers>

#include "detail/close_borders.h"
#include "detail/reconstructor_impl.h"
#include "detail/sample_projection.h"
#include "detail/surface_fit.h"
#include "detail/untangle.h"
#include "twist/repair.h"

namespace gcs {

namespace {

// The Delaunay flips before the fit flip only edges between nearly coplanar faces (cosine of the
// dihedral angle at least this: about 26 degrees), in at most this many passes over the edges.
constexpr double kFlipMinDihedralCos = 0.9;
constexpr int kFlipMaxPasses = 10;
// The projection, the fit and the crossing resolution move a vertex at most this many mean edge
// lengths: farther, a vertex would leave its place in the mesh's sampling of the surface.
constexpr double kMaxMoveEdges = 0.5;
// The fit ignores samples farther than this many mean edge lengths from the mesh (parts the mesh
// does not cover), keeps every face within this angle of its direction (degrees; no folds), and
// uses at most this many samples per vertex (cost: the big clouds use an even stride).
constexpr double kFitMaxSampleEdges = 1.0;
constexpr double kFitMaxFaceTurnDeg = 45.0;
constexpr std::size_t kFitSamplesPerVertex = 2;

}  // namespace

ReconstructResult Reconstructor::Impl::make_result(double seconds, const std::function<void(double)>& step) {
  ReconstructResult r;
  r.noise_ratio = noise_ratio;
  r.cloud_smoothed = cloud_smoothed;
  r.normals_filled = normals_filled;
  r.normals_unusable = normals_unusable;
  r.mesh = mesh;
  r.mesh.garbage_collection();
  auto report = [&](double fraction) {
    if (step) step(fraction);
  };
  // Post-processing of the copy only (the loop's own mesh stays as it is).
  const double ell = mean_edge_length();
  report(0);
  if (opt.post.project_to_samples) {
    detail::project_to_samples(r.mesh, [this](const Vec3& p) { return cloud_query(p); }, kMaxMoveEdges * ell);
  }
  report(0.1);
  if (opt.post.delaunay_flips) {
    const auto t_flips = Clock::now();
    detail::delaunay_flips(r.mesh, kFlipMinDihedralCos, kFlipMaxPasses);
    r.seconds_fit += seconds_since(t_flips);
  }
  report(0.2);
  if (opt.post.fit_surface) {
    const auto t_fit = Clock::now();
    detail::SurfaceFitParams fp;
    fp.rounds = opt.post.fit_rounds;
    fp.smoothness = opt.post.fit_smoothness;
    fp.max_move = kMaxMoveEdges * ell;
    fp.max_sample_distance = kFitMaxSampleEdges * ell;
    fp.min_face_cos = std::cos(kFitMaxFaceTurnDeg * std::numbers::pi / 180.0);
    fp.max_samples = kFitSamplesPerVertex * r.mesh.n_vertices();
    // The samples' normals (input, or fitted and oriented) when the loop uses them: a sample is
    // fitted only by a face that faces its way (not by the other layer of a thin shell).
    fp.oriented_normals = true;
    fp.measure_after = false;
    const std::vector<Vec3> none;
    detail::fit_to_samples(r.mesh, cloud.points, !oriented ? none : cloud.has_normals() ? cloud.normals : oriented_fitted, fp);
    r.seconds_fit += seconds_since(t_fit);
  }
  report(0.6);
  if (opt.post.stacked_layer_rounds > 0 && r.mesh.n_faces() > 0) {
    const auto t_layers = Clock::now();
    twist::StackedLayerOptions so;
    so.rounds = opt.post.stacked_layer_rounds;
    const twist::StackedLayerReport layers = twist::remove_stacked_layers(r.mesh, so);
    r.stacked_faces_found = layers.pairs_before;
    r.stacked_faces_removed = layers.faces_removed;
    r.stacked_pleats_flattened = layers.pleats_flattened;
    if (r.stacked_faces_removed > 0) r.mesh.garbage_collection();
    r.seconds_fit += seconds_since(t_layers);
  }
  report(0.7);
  if (opt.post.resolve_self_intersections && r.mesh.n_faces() > 0) {
    const auto t_untangle = Clock::now();
    detail::UntangleParams up;
    up.max_move = kMaxMoveEdges * ell;
    up.fill_support = bridge_distance(ell);  // as the topology pass's hole fills
    const detail::UntangleReport u = detail::untangle(r.mesh, [this](const Vec3& p) { return cloud_query(p); }, up);
    r.crossing_pairs_found = u.pairs_before;
    r.crossing_pairs_left = u.pairs_after;
    r.crossing_vertices_moved = u.vertices_moved;
    r.crossing_faces_removed = u.faces_removed;
    r.crossing_holes_filled = u.holes_filled;
    if (u.faces_removed > 0) r.mesh.garbage_collection();
    r.seconds_crossings = seconds_since(t_untangle);
    r.seconds_fit += r.seconds_crossings;
  }
  if (opt.post.close_false_borders && r.mesh.n_faces() > 0) {
    const auto t_close = Clock::now();
    detail::CloseBordersParams cp;
    cp.mean_edge_length = ell;
    cp.max_loop_vertices = opt.post.close_borders_max_vertices;
    // The oriented normals (input, or fitted and oriented); else the fitted ones, unoriented.
    std::vector<Vec3> normals;
    cp.normals_oriented = oriented;
    for (size_t k = 0; k < query_points->size(); ++k)
      normals.push_back(oriented ? query_oriented_normal(k) : query_point_normal(k));
    const detail::CloseBordersReport c = detail::close_false_borders(r.mesh, *query_points, normals, cp);
    r.false_borders_found = c.false_loops;
    r.false_borders_closed = c.closed;
    if (c.closed > 0) r.mesh.garbage_collection();
    r.seconds_fit += seconds_since(t_close);
  }
  for (auto v : r.mesh.vertices()) r.mesh.point(v) += offset;
  r.mesh.update_face_normals();
  report(1);
  r.stop_reason = finished_reason;
  r.basic_steps = steps;
  r.splits = splits;
  r.collapses = collapses;
  r.faces_removed = faces_removed;
  r.loops_merged = loops_merged;
  r.slits_zipped = slits_zipped;
  r.holes_filled = holes_filled;
  r.batches = batches;
  r.seconds_total = seconds + r.seconds_fit;  // the flips and the fit run after the loop's clock stopped
  r.seconds_operations = seconds_ops;
  r.seconds_topology = seconds_topology;
  for (const Registered& reg : ops) r.operations.push_back(reg.report);
  return r;
}

}  // namespace gcs
