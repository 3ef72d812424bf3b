// The surface fit of the GCS result (gcs/src/detail/surface_fit.h, PostProcessOptions::fit_surface):
// vertices move along their normals toward the sampled surface, faces do not turn past the bound,
// no self-intersections appear, the reconstruction stays deterministic, bad options are rejected.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "../gcs/src/detail/surface_fit.h"
#include "edgefront/error.h"
#include "edgefront/mesh.h"
#include "shapes/shapes.h"
#include "gcs/evaluation.h"
#include "gcs/reconstructor.h"

namespace {

using edgefront::Mesh;
using edgefront::Vec3;

std::vector<Vec3> sphere_samples(std::size_t n, double radius, std::vector<Vec3>* normals = nullptr) {
  edgefront::shapes::SampleOptions so;
  so.points = n;
  so.shape.radius = radius;
  const edgefront::PointCloud c = edgefront::shapes::sample("icosphere", so);
  if (normals) *normals = c.normals;
  return c.points;
}

gcs::detail::SurfaceFitParams params_for(double max_move) {
  gcs::detail::SurfaceFitParams p;
  p.max_move = max_move;
  p.max_sample_distance = 0.5;
  return p;
}

std::vector<Vec3> unit_vertex_normals(const Mesh& m) {
  std::vector<Vec3> n(m.n_vertices(), Vec3(0, 0, 0));
  for (auto f : m.faces()) {
    auto it = m.cfv_iter(f);
    const Vec3 a = m.point(*it), b = m.point(*++it), c = m.point(*++it);
    for (auto v : m.fv_range(f)) n[v.idx()] += (b - a) % (c - a);
  }
  for (Vec3& v : n) v.normalize();
  return n;
}

// A mesh 5% outside the sampled sphere: every vertex moves inward, along its normal, and ends
// nearer the sphere; the samples end nearer the mesh.
TEST(GcsSurfaceFit, OffsetSphereMovesEveryVertexTowardTheSurfaceAlongItsNormal) {
  Mesh m = edgefront::shapes::icosphere(3, 1.05);
  const Mesh before = m;
  const std::vector<Vec3> n0 = unit_vertex_normals(m);
  const std::vector<Vec3> samples = sphere_samples(4000, 1.0);
  gcs::detail::SurfaceFitParams p = params_for(0.2);
  p.rounds = 1;  // one round: each move is exactly along the starting vertex normal
  const gcs::detail::SurfaceFitReport r = gcs::detail::fit_to_samples(m, samples, {}, p);
  EXPECT_EQ(r.samples_used, samples.size());
  EXPECT_EQ(r.vertices_moved, m.n_vertices());
  EXPECT_EQ(r.intersections_undone, 0u);
  EXPECT_LT(r.mean_distance_after, 0.3 * r.mean_distance_before);
  for (auto v : m.vertices()) {
    const Vec3 d = m.point(v) - before.point(v);
    EXPECT_LT((d - (d | n0[v.idx()]) * n0[v.idx()]).norm(), 1e-12 + 1e-9 * d.norm()) << "tangential move at " << v.idx();
    EXPECT_LT(d | n0[v.idx()], 0) << "vertex " << v.idx() << " moved away from the sphere";
    EXPECT_LT(std::abs(m.point(v).norm() - 1.0), std::abs(before.point(v).norm() - 1.0)) << v.idx();
  }
  // The report's distances are the real ones.
  EXPECT_NEAR(r.mean_distance_before, gcs::detail::mean_sample_distance(before, samples, 0.5), 1e-12);
  EXPECT_NEAR(r.mean_distance_after, gcs::detail::mean_sample_distance(m, samples, 0.5), 1e-12);
}

// Vertices already on the sampled sphere: the chords miss the samples between them; the fit moves
// the vertices slightly outward so that the triangles pass through the samples.
TEST(GcsSurfaceFit, VerticesOnTheSurfaceCloseTheChordGap) {
  Mesh m = edgefront::shapes::icosphere(2, 1.0);
  const std::vector<Vec3> samples = sphere_samples(3000, 1.0);
  const gcs::detail::SurfaceFitReport r = gcs::detail::fit_to_samples(m, samples, {}, params_for(0.1));
  EXPECT_GT(r.vertices_moved, 0u);
  EXPECT_LT(r.mean_distance_after, 0.5 * r.mean_distance_before);
  for (auto v : m.vertices()) EXPECT_GT(m.point(v).norm(), 1.0) << v.idx();
}

// Samples that pull neighbouring vertices in opposite directions by far more than an edge (a
// sawtooth): the face-turn bound holds for every face, no face flips, no self-intersection.
TEST(GcsSurfaceFit, NoFaceTurnsPastTheBoundAndNoSelfIntersectionAppears) {
  Mesh m = edgefront::shapes::icosphere(3, 1.0);
  std::vector<Vec3> samples;
  for (auto v : m.vertices()) {
    const Vec3 x = m.point(v);
    samples.push_back(x * (v.idx() % 2 ? 1.3 : 0.7));  // alternate far outside / far inside
  }
  std::vector<Vec3> before_normal;
  for (auto f : m.faces()) before_normal.push_back(m.calc_face_normal(f));
  const std::size_t si_before = gcs::count_self_intersections(m);
  gcs::detail::SurfaceFitParams p = params_for(0.5);
  p.smoothness = 0;
  p.min_face_cos = std::cos(30.0 * M_PI / 180.0);
  // Without the bound (any turn allowed), some face would turn past it: the case tests the bound.
  Mesh unbounded = m;
  gcs::detail::SurfaceFitParams loose = p;
  loose.min_face_cos = -1;
  gcs::detail::fit_to_samples(unbounded, samples, {}, loose);
  std::size_t turned = 0;
  for (auto f : unbounded.faces()) turned += (unbounded.calc_face_normal(f) | before_normal[f.idx()]) < p.min_face_cos;
  EXPECT_GT(turned, 0u);
  const gcs::detail::SurfaceFitReport r = gcs::detail::fit_to_samples(m, samples, {}, p);
  EXPECT_GT(r.vertices_moved, 0u);
  for (auto f : m.faces()) {
    const Vec3 n = m.calc_face_normal(f);
    EXPECT_GE(n | before_normal[f.idx()], p.min_face_cos - 1e-9) << "face " << f.idx();
  }
  EXPECT_LE(gcs::count_self_intersections(m), si_before);
  for (auto v : m.vertices()) EXPECT_LE(std::abs(m.point(v).norm() - 1.0), 0.5 + 1e-12);  // max_move
}

// Nine samples in ten on the sphere of radius 1.05, one in ten far outside (1.35): the least-squares
// fit is pulled outward by the outliers; with l1_weights (the default) the later rounds weight them
// down, so the vertices end nearer the 1.05 sphere and the mean sample distance is smaller.
TEST(GcsSurfaceFit, L1WeightsResistOutliers) {
  std::vector<Vec3> samples = sphere_samples(4000, 1.05);
  for (std::size_t i = 0; i < samples.size(); i += 10) samples[i] *= 1.35 / 1.05;
  gcs::detail::SurfaceFitParams p = params_for(0.2);
  p.max_sample_distance = 0.6;
  p.rounds = 4;
  ASSERT_TRUE(p.l1_weights);
  Mesh l1 = edgefront::shapes::icosphere(3, 1.0);
  Mesh l2 = l1;
  const gcs::detail::SurfaceFitReport r1 = gcs::detail::fit_to_samples(l1, samples, {}, p);
  p.l1_weights = false;
  const gcs::detail::SurfaceFitReport r2 = gcs::detail::fit_to_samples(l2, samples, {}, p);
  EXPECT_EQ(r1.samples_used, samples.size());
  EXPECT_EQ(r2.samples_used, samples.size());
  EXPECT_LT(r1.mean_distance_after, 0.9 * r2.mean_distance_after);
  double off1 = 0, off2 = 0;
  for (auto v : l1.vertices()) {
    off1 += std::abs(l1.point(v).norm() - 1.05);
    off2 += std::abs(l2.point(v).norm() - 1.05);
  }
  EXPECT_LT(off1, 0.5 * off2);
}

// A sample whose normal is perpendicular to its closest face (another layer) is ignored.
TEST(GcsSurfaceFit, SamplesFacingSidewaysAreIgnored) {
  Mesh m = edgefront::shapes::icosphere(2, 1.05);
  std::vector<Vec3> normals;
  const std::vector<Vec3> samples = sphere_samples(500, 1.0, &normals);
  std::vector<Vec3> sideways(samples.size());
  for (std::size_t i = 0; i < samples.size(); ++i) sideways[i] = normals[i] % Vec3(0.3, 0.5, 0.81);  // _|_ normal
  const Mesh before = m;
  const gcs::detail::SurfaceFitReport r = gcs::detail::fit_to_samples(m, samples, sideways, params_for(0.2));
  EXPECT_LT(r.samples_used, samples.size() / 10);
  Mesh m2 = before;
  EXPECT_EQ(gcs::detail::fit_to_samples(m2, samples, normals, params_for(0.2)).samples_used, samples.size());
}

TEST(GcsSurfaceFit, BadParametersAreRejected) {
  Mesh m = edgefront::shapes::icosphere(1, 1.0);
  const std::vector<Vec3> samples = sphere_samples(100, 1.0);
  auto expect_rejected = [&](gcs::detail::SurfaceFitParams p, const std::string& word) {
    try {
      gcs::detail::fit_to_samples(m, samples, {}, p);
      ADD_FAILURE() << "accepted, expected an error naming " << word;
    } catch (const edgefront::InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find(word), std::string::npos) << e.what();
    }
  };
  gcs::detail::SurfaceFitParams p = params_for(0.1);
  p.rounds = 0;
  expect_rejected(p, "rounds");
  p = params_for(0.1);
  p.smoothness = std::numeric_limits<double>::quiet_NaN();
  expect_rejected(p, "smoothness");
  expect_rejected(params_for(0.0), "max_move");
  p = params_for(0.1);
  p.max_sample_distance = -1;
  expect_rejected(p, "max_sample_distance");
  EXPECT_THROW(gcs::detail::fit_to_samples(m, samples, std::vector<Vec3>(3, Vec3(0, 0, 1)), params_for(0.1)),
               edgefront::InvalidInput);
}

edgefront::PointCloud torus_cloud() {
  edgefront::shapes::SampleOptions so;
  so.points = 3000;
  return edgefront::shapes::sample("torus", so);
}

TEST(GcsSurfaceFit, ReconstructionOptionsOutOfRangeAreRejected) {
  const edgefront::PointCloud cloud = torus_cloud();
  auto expect_rejected = [&](gcs::ReconstructOptions o, const std::string& word) {
    try {
      gcs::Reconstructor r(cloud, o);
      ADD_FAILURE() << "accepted, expected an error naming " << word;
    } catch (const edgefront::InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find(word), std::string::npos) << e.what();
    }
  };
  gcs::ReconstructOptions o;
  o.target_vertices = 300;  // within the cloud's 3000 points: only the fit option is out of range
  o.post.fit_rounds = 0;
  expect_rejected(o, "fit_rounds");
  o.post.fit_rounds = 21;
  expect_rejected(o, "fit_rounds");
  o.post.fit_rounds = gcs::ReconstructOptions{}.post.fit_rounds;
  o.post.fit_smoothness = -0.5;
  expect_rejected(o, "fit_smoothness");
  o.post.fit_smoothness = std::numeric_limits<double>::infinity();
  expect_rejected(o, "fit_smoothness");
}

// The fit is deterministic (same seed, same mesh to the bit), changes only positions, and brings
// the samples nearer the mesh than the unfitted result.
TEST(GcsSurfaceFit, ReconstructionIsDeterministicAndTheFitOnlyMovesVertices) {
  const edgefront::PointCloud cloud = torus_cloud();
  gcs::ReconstructOptions o;
  o.target_vertices = 300;
  o.seed = 3;
  const Mesh a = gcs::reconstruct(cloud, o).mesh;
  const Mesh b = gcs::reconstruct(cloud, o).mesh;
  o.post.fit_surface = false;
  const Mesh plain = gcs::reconstruct(cloud, o).mesh;
  ASSERT_EQ(a.n_vertices(), b.n_vertices());
  ASSERT_EQ(a.n_vertices(), plain.n_vertices());
  ASSERT_EQ(a.n_faces(), plain.n_faces());
  std::size_t moved = 0;
  for (auto v : a.vertices()) {
    EXPECT_EQ(a.point(v), b.point(v)) << v.idx();
    moved += a.point(v) != plain.point(v);
  }
  for (auto f : a.faces()) {
    auto ia = a.cfv_iter(f), ip = plain.cfv_iter(f);
    for (int k = 0; k < 3; ++k, ++ia, ++ip) EXPECT_EQ(ia->idx(), ip->idx());
  }
  EXPECT_GT(moved, a.n_vertices() / 2);
  const double ell = 0.2;
  EXPECT_LT(gcs::detail::mean_sample_distance(a, cloud.points, ell),
            gcs::detail::mean_sample_distance(plain, cloud.points, ell));
}

}  // namespace
