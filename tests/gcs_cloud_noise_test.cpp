// Noise in point clouds (gcs/cloud_noise.h) and the reconstructor's smoothing of noisy clouds
// (InputOptions::smooth_noise_ratio, gcs-reconstruct --keep-noise): the estimate finds the
// noise that was added, clean clouds and thin shells with normals are not called noisy, smoothing
// brings the points (and the mesh) nearer the true surface, bad input is refused.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "app_test_util.h"
#include "edgefront/error.h"
#include "edgefront/point_cloud_io.h"
#include "shapes/shapes.h"
#include "gcs/cloud_noise.h"
#include "gcs/reconstructor.h"

namespace {

using edgefront::InvalidInput;
using edgefront::PointCloud;
using edgefront::Vec3;

PointCloud sphere_cloud(std::size_t n, double sigma, std::uint64_t seed = 1) {
  edgefront::shapes::SampleOptions so;
  so.points = n;
  so.noise_sigma = sigma;
  so.seed = seed;
  return edgefront::shapes::sample("icosphere", so);  // radius 1 around the origin
}

double mean_sphere_error(const std::vector<Vec3>& points) {
  double sum = 0;
  for (const Vec3& p : points) sum += std::abs(p.norm() - 1.0);
  return sum / static_cast<double>(points.size());
}

TEST(CloudNoise, TheEstimateFindsTheAddedNoiseAndCleanCloudsAreClean) {
  const double sigma = 0.01;  // about a third of the spacing of 3000 points on the unit sphere
  const gcs::NoiseEstimate noisy = gcs::estimate_noise(sphere_cloud(3000, sigma));
  EXPECT_GT(noisy.noise, 0.7 * sigma);
  EXPECT_LT(noisy.noise, 1.3 * sigma);
  EXPECT_GT(noisy.spacing, 0);
  EXPECT_EQ(noisy.points_used, 3000u);
  EXPECT_NEAR(noisy.ratio(), noisy.noise / noisy.spacing, 1e-15);

  const gcs::NoiseEstimate clean = gcs::estimate_noise(sphere_cloud(3000, 0.0));
  EXPECT_LT(clean.ratio(), 0.01);  // the quadric follows the curvature
}

TEST(CloudNoise, ALargeCloudLookedAtInPatchesGivesTheSameEstimate) {
  // 20,000 points: with max_points 20,000 every point is looked at; with 1,000 (a cloud of more
  // than 4 times max_points) the estimate looks at patches of the cloud only.
  const PointCloud cloud = sphere_cloud(20000, 0.004);
  gcs::NoiseOptions whole, patches;
  whole.max_points = 20000;
  patches.max_points = 1000;
  const gcs::NoiseEstimate a = gcs::estimate_noise(cloud, whole), b = gcs::estimate_noise(cloud, patches);
  EXPECT_EQ(a.points_used, 20000u);
  EXPECT_LE(b.points_used, 1000u);
  EXPECT_GT(b.points_used, 500u);
  EXPECT_NEAR(b.noise, a.noise, 0.1 * a.noise);
  EXPECT_NEAR(b.spacing, a.spacing, 0.1 * a.spacing);
  EXPECT_GT(a.noise, 0.7 * 0.004);
  EXPECT_LT(a.noise, 1.3 * 0.004);
}

TEST(CloudNoise, TheOtherWallOfAThinShellIsNotNoiseWhenTheNormalsSayWhichSideIsWhich) {
  edgefront::shapes::SampleOptions so;
  so.points = 6000;
  so.shape.thickness = 0.06;  // about 1.5 point spacings: 10 neighbours reach the other wall
  const PointCloud shell = edgefront::shapes::sample("vault-shell", so);
  PointCloud bare = shell;
  bare.normals.clear();
  const gcs::NoiseEstimate with_normals = gcs::estimate_noise(shell), without = gcs::estimate_noise(bare);
  EXPECT_LT(with_normals.ratio(), 0.05);
  // The normal filter keeps the fits on one wall; without it the other wall spoils them, and only
  // the second, wider fit tells that this is misfit, not noise.
  EXPECT_GT(without.residual, 4 * with_normals.residual);
  EXPECT_GT(without.wide_residual, 2 * without.residual);
  EXPECT_LT(without.ratio(), 0.05);
}

TEST(CloudNoise, CoarseCleanSamplingOfDetailIsNotNoise) {
  // A clean cloud too coarse for its bumps (like a scanned model's vertex set): the quadric of 10
  // neighbours misses the surface by several percent of the spacing, and more with 20 neighbours.
  edgefront::shapes::SampleOptions so;
  so.points = 2000;
  so.shape.frequency = 8;
  so.shape.amplitude = 0.15;
  const PointCloud coarse = edgefront::shapes::sample("bumpy-sphere", so);
  const gcs::NoiseEstimate clean = gcs::estimate_noise(coarse);
  EXPECT_GT(clean.residual, 0.05 * clean.spacing);  // one fit alone would call it noisy
  EXPECT_GT(clean.wide_residual, 2 * clean.residual);
  EXPECT_LT(clean.ratio(), 0.01);
  // The same cloud with noise of about 0.2 spacings along the normal is noisy.
  so.noise = edgefront::shapes::NoiseKind::along_normal;
  so.noise_sigma = 0.2 * clean.spacing;
  const gcs::NoiseEstimate noisy = gcs::estimate_noise(edgefront::shapes::sample("bumpy-sphere", so));
  EXPECT_GT(noisy.ratio(), 0.1);
  EXPECT_LT(noisy.ratio(), 0.3);
  // The reconstructor leaves the clean cloud as it is.
  gcs::ReconstructOptions o;
  o.target_vertices = 300;
  EXPECT_FALSE(gcs::reconstruct(coarse, o).cloud_smoothed);
}

TEST(CloudNoise, SmoothingBringsNoisyPointsOntoTheSurfaceWhateverTheirOrder) {
  PointCloud cloud = sphere_cloud(3000, 0.02);
  const double before = mean_sphere_error(cloud.points);
  PointCloud shuffled = cloud;
  std::vector<std::size_t> order(cloud.size());
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), std::mt19937(5));
  for (std::size_t i = 0; i < order.size(); ++i) {
    shuffled.points[i] = cloud.points[order[i]];
    shuffled.normals[i] = cloud.normals[order[i]];
  }
  const std::vector<Vec3> normals = cloud.normals;
  EXPECT_EQ(gcs::smooth_noise(cloud), cloud.size());
  EXPECT_EQ(cloud.normals, normals);
  EXPECT_LT(mean_sphere_error(cloud.points), 0.3 * before);
  gcs::smooth_noise(shuffled);
  for (std::size_t i = 0; i < order.size(); ++i) {
    EXPECT_LT((shuffled.points[i] - cloud.points[order[i]]).norm(), 1e-9) << i;
  }
  // Fewer neighbours average less.
  PointCloud again = sphere_cloud(3000, 0.02);
  gcs::SmoothNoiseOptions small;
  small.neighbours = 12;
  gcs::smooth_noise(again, small);
  EXPECT_GT(mean_sphere_error(again.points), mean_sphere_error(cloud.points));
  EXPECT_LT(mean_sphere_error(again.points), before);
}

TEST(CloudNoise, BadInputIsRefused) {
  PointCloud tiny = sphere_cloud(7, 0.0);
  EXPECT_THROW(gcs::estimate_noise(tiny), InvalidInput);
  EXPECT_THROW(gcs::smooth_noise(tiny), InvalidInput);
  PointCloud nan = sphere_cloud(100, 0.0);
  nan.points[3][1] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(gcs::estimate_noise(nan), InvalidInput);
  EXPECT_THROW(gcs::smooth_noise(nan), InvalidInput);
  PointCloud mismatched = sphere_cloud(100, 0.0);
  mismatched.normals.pop_back();
  EXPECT_THROW(gcs::estimate_noise(mismatched), InvalidInput);
  PointCloud ok = sphere_cloud(100, 0.0);
  gcs::NoiseOptions no;
  no.neighbours = 7;
  EXPECT_THROW(gcs::estimate_noise(ok, no), InvalidInput);
  no.neighbours = 257;
  EXPECT_THROW(gcs::estimate_noise(ok, no), InvalidInput);
  no.neighbours = 10;
  no.max_points = 0;
  EXPECT_THROW(gcs::estimate_noise(ok, no), InvalidInput);
  gcs::SmoothNoiseOptions so;
  so.neighbours = 300;
  EXPECT_THROW(gcs::smooth_noise(ok, so), InvalidInput);
  // All points on a line: no neighbourhood is a surface; nothing moves, nothing is estimated.
  PointCloud line;
  for (int i = 0; i < 50; ++i) line.points.emplace_back(0.01 * i, 0, 0);
  EXPECT_EQ(gcs::estimate_noise(line).points_used, 0u);
  EXPECT_EQ(gcs::smooth_noise(line), 0u);
}

double mean_vertex_sphere_error(const edgefront::Mesh& mesh) {
  double sum = 0;
  for (auto v : mesh.vertices()) sum += std::abs(mesh.point(v).norm() - 1.0);
  return sum / static_cast<double>(mesh.n_vertices());
}

TEST(CloudNoise, TheReconstructorSmoothsNoisyCloudsOnlyAndItsMeshIsNearerTheTruth) {
  gcs::ReconstructOptions o;
  o.target_vertices = 400;
  const PointCloud noisy = sphere_cloud(3000, 0.02);
  const gcs::ReconstructResult smoothed = gcs::reconstruct(noisy, o);
  EXPECT_TRUE(smoothed.cloud_smoothed);
  EXPECT_GT(smoothed.noise_ratio, o.input.smooth_noise_ratio);
  gcs::ReconstructOptions keep = o;
  keep.input.smooth_noise_ratio = std::numeric_limits<double>::infinity();
  const gcs::ReconstructResult raw = gcs::reconstruct(noisy, keep);
  EXPECT_FALSE(raw.cloud_smoothed);
  EXPECT_LT(mean_vertex_sphere_error(smoothed.mesh), 0.7 * mean_vertex_sphere_error(raw.mesh));

  const PointCloud clean = sphere_cloud(3000, 0.0);
  const gcs::ReconstructResult c = gcs::reconstruct(clean, o);
  EXPECT_FALSE(c.cloud_smoothed);
  EXPECT_LT(c.noise_ratio, 0.01);

  gcs::ReconstructOptions bad = o;
  bad.input.smooth_noise_ratio = -0.1;
  EXPECT_THROW(gcs::reconstruct(clean, bad), InvalidInput);
  bad.input.smooth_noise_ratio = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(gcs::reconstruct(clean, bad), InvalidInput);
}

class GcsCliNoise : public eftest::AppTest {
 protected:
  GcsCliNoise() : AppTest("gcs-reconstruct") {}
};

TEST_F(GcsCliNoise, ANoisyCloudIsSmoothedUnlessKeepNoiseIsGiven) {
  const std::filesystem::path cloud = dir_ / "noisy.xyz", a = dir_ / "a.ply", b = dir_ / "b.ply";
  edgefront::write_points(sphere_cloud(3000, 0.02), cloud);
  const eftest::CommandResult smoothed =
      run(eftest::shell_quoted(cloud.string()) + " -o " + eftest::shell_quoted(a.string()) + " --vertices 300");
  ASSERT_EQ(smoothed.exit_code, 0) << smoothed.err;
  EXPECT_NE(smoothed.out.find("cloud smoothed first"), std::string::npos) << smoothed.out;
  const eftest::CommandResult kept = run(eftest::shell_quoted(cloud.string()) + " -o " +
                                         eftest::shell_quoted(b.string()) + " --vertices 300 --keep-noise");
  ASSERT_EQ(kept.exit_code, 0) << kept.err;
  EXPECT_EQ(kept.out.find("smoothed"), std::string::npos) << kept.out;
  EXPECT_NE(eftest::slurp(a), eftest::slurp(b));
}

}  // namespace
