// The reconstructor's parallel phases (noise estimate and smoothing, normal fits, evaluation) and
// the reconstruction itself give the same bytes for 1, 2 and 3 threads; gcs-reconstruct and
// gcs-eval take --threads and write the same files with any count.

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "app_test_util.h"
#include "edgefront/mesh_io.h"
#include "edgefront/point_cloud_io.h"
#include "edgefront/point_index.h"
#include "shapes/shapes.h"
#include "gcs/cloud_noise.h"
#include "gcs/cloud_normals.h"
#include "gcs/evaluation.h"
#include "gcs/reconstructor.h"
#include "twist/detect.h"
#include "twist/reference_normals.h"
#include "shapes/twisted_shapes.h"

namespace {

namespace fs = std::filesystem;
using edgefront::PointCloud;
using edgefront::Vec3;

template <class T>
std::string bytes_of(const std::vector<T>& v) {
  return std::string(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
}

// A noisy cloud without normals: what makes the reconstructor smooth and fit normals.
PointCloud noisy_cloud(std::size_t n, double sigma = 0.02) {
  edgefront::shapes::SampleOptions so;
  so.points = n;
  so.noise_sigma = sigma;
  so.seed = 3;
  PointCloud c = edgefront::shapes::sample("bumpy-sphere", so);
  c.normals.clear();
  return c;
}

TEST(ThreadsPhases, NoiseEstimateAndSmoothingAreTheSameForAnyThreadCount) {
  const PointCloud cloud = noisy_cloud(6000);
  gcs::NoiseOptions eo;
  eo.threads = 1;
  const gcs::NoiseEstimate one = gcs::estimate_noise(cloud, eo);
  EXPECT_GT(one.noise, 0.0);
  EXPECT_GT(one.points_used, 1000u);
  gcs::SmoothNoiseOptions so;
  so.threads = 1;
  PointCloud smooth_one = cloud;
  const std::size_t moved_one = gcs::smooth_noise(smooth_one, so);
  EXPECT_GT(moved_one, cloud.size() / 2);
  for (unsigned t : {2u, 3u, 0u}) {
    eo.threads = t;
    const gcs::NoiseEstimate e = gcs::estimate_noise(cloud, eo);
    EXPECT_EQ(bytes_of(std::vector<double>{e.noise, e.residual, e.wide_residual, e.spacing}),
              bytes_of(std::vector<double>{one.noise, one.residual, one.wide_residual, one.spacing}))
        << t << " threads";
    EXPECT_EQ(e.points_used, one.points_used);
    so.threads = t;
    PointCloud c = cloud;
    EXPECT_EQ(gcs::smooth_noise(c, so), moved_one);
    EXPECT_EQ(bytes_of(c.points), bytes_of(smooth_one.points)) << t << " threads";
  }
}

TEST(ThreadsPhases, NormalFitsAreTheSameForAnyThreadCount) {
  const PointCloud cloud = noisy_cloud(5000, 0.002);
  const edgefront::PointIndex index(cloud.points);
  for (bool best : {true, false}) {
    gcs::NormalFitOptions o;
    o.best_neighbourhood = best;
    o.quadric_normal = true;
    o.threads = 1;
    std::vector<double> r1;
    const std::vector<Vec3> one = gcs::fit_normals(cloud.points, index, o, &r1);
    std::size_t defined = 0;
    for (const Vec3& n : one) defined += std::isfinite(n[0]) ? 1 : 0;
    EXPECT_GT(defined, cloud.size() / 2);
    for (unsigned t : {2u, 3u}) {
      o.threads = t;
      std::vector<double> r;
      const std::vector<Vec3> n = gcs::fit_normals(cloud.points, index, o, &r);
      EXPECT_EQ(bytes_of(n), bytes_of(one)) << t << " threads, best_neighbourhood " << best;
      EXPECT_EQ(bytes_of(r), bytes_of(r1));
    }
  }
}

TEST(ThreadsPhases, EvaluationIsTheSameForAnyThreadCount) {
  edgefront::shapes::MeshOptions mo;
  mo.resolution = 20;
  const edgefront::Mesh mesh = edgefront::shapes::make("bumpy-sphere", mo);
  edgefront::shapes::SampleOptions so;
  so.points = 3000;
  const gcs::GroundTruth truth = gcs::GroundTruth::from_points(edgefront::shapes::sample("bumpy-sphere", so));
  for (bool exact : {true, false}) {
    gcs::EvaluationOptions o;
    o.samples = 4000;
    o.exact_surface_distance = exact;
    o.threads = 1;
    const std::string one = gcs::evaluation_to_json(gcs::evaluate(mesh, truth, o));
    for (unsigned t : {2u, 3u}) {
      o.threads = t;
      EXPECT_EQ(gcs::evaluation_to_json(gcs::evaluate(mesh, truth, o)), one) << t << " threads, exact " << exact;
    }
  }
}

// Everything a detection returns, as text (handles, evidence, areas as exact bits). (A stream:
// GCC 12 warns -Wrestrict on "..." + std::string&&.)
std::string describe(const twist::DetectResult& r) {
  std::ostringstream out;
  out << r.stats.faces_tested << " " << r.stats.distance_queries << " " << r.stats.vertices_settled << " "
      << r.stats.flagged_faces << "\n";
  for (const twist::TwistRegion& region : r.regions) {
    out << "region";
    for (const auto f : region.faces) out << " " << f.idx();
    out << " |";
    for (const auto& loop : region.border) {
      for (const auto h : loop) out << " " << h.idx();
      out << ";";
    }
    for (const twist::Evidence& e : region.evidence) {
      out << " " << static_cast<int>(e.kind) << ":" << e.face.idx() << ":" << e.partner.idx();
    }
    out << " " << region.flagged_faces << " " << std::hexfloat << region.area << std::defaultfloat << "\n";
  }
  return out.str();
}

TEST(ThreadsPhases, WholeMeshTwistDetectionIsTheSameForAnyThreadCount) {
  twist::TwistedTubeOptions to;
  to.along = 48;
  to.around = 24;
  const twist::TwistedShape shape = twist::twisted_tube(to);
  // (One detector thread per 1,000 faces: 2 threads here.)
  ASSERT_GE(shape.mesh.n_faces(), 2000u) << "too few faces for 2 detector threads";
  const twist::ReferenceNormals reference(twist::truth_points(shape));
  for (bool with_reference : {false, true}) {
    twist::DetectOptions o;
    if (with_reference) o.reference = &reference;
    o.threads = 1;
    const twist::DetectResult one = twist::detect_regions(shape.mesh, o);
    EXPECT_FALSE(one.regions.empty()) << "the twisted tube shows no region: the test compares nothing";
    EXPECT_EQ(one.stats.faces_tested, shape.mesh.n_faces());
    const std::string want = describe(one);
    o.threads = 2;
    EXPECT_EQ(describe(twist::detect_regions(shape.mesh, o)), want) << "2 threads, reference " << with_reference;
  }
}

TEST(ThreadsPhases, ReconstructionIsByteIdenticalForOneTwoAndThreeThreads) {
  // Smoothed (noisy) and without normals: the parallel phases all run (quadric normal fits).
  const PointCloud cloud = noisy_cloud(3000);
  std::string reference;
  const fs::path dir = fs::temp_directory_path() / ("edgefront_threads_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  for (unsigned t : {1u, 2u, 3u}) {
    gcs::ReconstructOptions o;
    o.target_vertices = 250;
    o.input.quadric_normals = true;
    o.seed = 5;
    o.threads = t;
    gcs::Reconstructor r(cloud, o);
    const gcs::ReconstructResult result = r.run();
    EXPECT_TRUE(result.cloud_smoothed) << "the cloud was not smoothed: the test does not reach the phase";
    const fs::path out = dir / ("mesh-" + std::to_string(t) + ".ply");
    edgefront::write_mesh(result.mesh, out);
    const std::string bytes = eftest::slurp(out);
    EXPECT_GT(bytes.size(), 1000u);
    if (t == 1) {
      reference = bytes;
    } else {
      EXPECT_EQ(bytes, reference) << t << " threads: the written mesh differs from 1 thread's";
    }
  }
  fs::remove_all(dir);
}

class ThreadsApps : public eftest::AppTest {
 protected:
  ThreadsApps() : AppTest("gcs-reconstruct") {}
  std::string q(const fs::path& p) const { return eftest::shell_quoted(p.string()); }
};

TEST_F(ThreadsApps, GcsReconstructAndGcsEvalWriteTheSameWithOneAndTwoThreads) {
  const fs::path vault = fs::path(EDGEFRONT_DATA_DIR) / "vault-sheet.xyz";
  const fs::path a = dir_ / "a.ply", b = dir_ / "b.ply";
  const eftest::CommandResult ra = run(q(vault) + " -o " + q(a) + " --vertices 200 --threads 1");
  ASSERT_EQ(ra.exit_code, 0) << ra.err;
  const eftest::CommandResult rb = run(q(vault) + " -o " + q(b) + " --vertices 200 --threads 2");
  ASSERT_EQ(rb.exit_code, 0) << rb.err;
  EXPECT_EQ(eftest::slurp(a), eftest::slurp(b));
  const eftest::CommandResult bad = run(q(vault) + " -o " + q(dir_ / "c.ply") + " --threads x");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("--threads"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(dir_ / "c.ply"));

  const fs::path eval = fs::path(EDGEFRONT_APP_DIR) / "gcs-eval";
  const eftest::CommandResult e1 = eftest::run_command(eval, q(a) + " " + q(vault) + " --samples 5000 --json --threads 1", dir_);
  ASSERT_EQ(e1.exit_code, 0) << e1.err;
  const eftest::CommandResult e2 = eftest::run_command(eval, q(a) + " " + q(vault) + " --samples 5000 --json --threads 2", dir_);
  ASSERT_EQ(e2.exit_code, 0) << e2.err;
  EXPECT_EQ(e1.out, e2.out);
  EXPECT_NE(e1.out.find("chamfer"), std::string::npos) << e1.out;
  const eftest::CommandResult e3 = eftest::run_command(eval, q(a) + " " + q(vault) + " --threads -2", dir_);
  EXPECT_EQ(e3.exit_code, 2) << e3.err;
}

}  // namespace
