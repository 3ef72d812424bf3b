// Input tolerance of the reconstructor and gcs-reconstruct (issue 25): invalid normals in a file
// (zero-length, NaN) are dropped and counted, the rest used; --ignore-normals never reads them;
// all-zero normals mean "no normals"; without --vertices the target is min(5000, the cloud's
// distinct points); the progress names every phase. Real files written here, real app runs.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "app_test_util.h"
#include "edgefront/error.h"
#include "edgefront/mesh_io.h"
#include "edgefront/mesh_stats.h"
#include "edgefront/point_cloud_io.h"
#include "shapes/shapes.h"
#include "gcs/reconstructor.h"

namespace {

namespace fs = std::filesystem;
using edgefront::PointCloud;
using edgefront::Vec3;

PointCloud sphere_cloud(size_t points, std::uint64_t seed = 1) {
  edgefront::shapes::SampleOptions o;
  o.points = points;
  o.seed = seed;
  return edgefront::shapes::sample("icosphere", o);
}

// Writes `c` as .xyz; normal i is written as `bad(i)` when it returns non-empty text.
template <class Bad>
void write_xyz(const PointCloud& c, const fs::path& path, Bad&& bad) {
  std::ofstream out(path);
  out.precision(17);
  for (size_t i = 0; i < c.size(); ++i) {
    out << c.points[i][0] << ' ' << c.points[i][1] << ' ' << c.points[i][2] << ' ';
    const std::string b = bad(i);
    if (!b.empty()) {
      out << b << '\n';
    } else {
      out << c.normals[i][0] << ' ' << c.normals[i][1] << ' ' << c.normals[i][2] << '\n';
    }
  }
}

class InputTolerance : public eftest::AppTest {
 protected:
  InputTolerance() : AppTest("gcs-reconstruct") {}
  std::string q(const fs::path& p) const { return eftest::shell_quoted(p.string()); }
};

// ------------------------------------------------------------------ the reader

TEST_F(InputTolerance, ReaderDropsInvalidNormalsAndCountsThem) {
  const PointCloud c = sphere_cloud(200);
  const fs::path path = dir_ / "some_bad.xyz";
  write_xyz(c, path, [](size_t i) -> std::string {
    if (i == 3 || i == 50) return "0 0 0";
    if (i == 7) return "nan 0 1";
    if (i == 9) return "inf 1 0";
    return "";
  });
  // The default still refuses the file, naming the line.
  try {
    edgefront::read_points(path);
    ADD_FAILURE() << "accepted";
  } catch (const edgefront::IoError& e) {
    EXPECT_NE(std::string(e.what()).find("line 4: zero-length normal"), std::string::npos) << e.what();
  }
  edgefront::PointReadOptions options;
  options.tolerate_invalid_normals = true;
  edgefront::PointReadReport report;
  const PointCloud r = edgefront::read_points(path, options, &report);
  ASSERT_EQ(r.size(), 200u);
  ASSERT_TRUE(r.has_normals());
  EXPECT_EQ(report.points, 200u);
  EXPECT_EQ(report.invalid_normals, 4u);
  EXPECT_EQ(report.zero_normals, 2u);
  EXPECT_FALSE(report.all_normals_invalid);
  EXPECT_NE(report.warning.find("4 of 200 normals are invalid"), std::string::npos) << report.warning;
  EXPECT_NE(report.warning.find("line 4: zero-length normal"), std::string::npos) << report.warning;
  for (size_t i = 0; i < r.size(); ++i) {
    const bool bad = i == 3 || i == 50 || i == 7 || i == 9;
    EXPECT_EQ(std::isnan(r.normals[i][0]), bad) << i;
    if (!bad) {
      EXPECT_NEAR(r.normals[i].norm(), 1.0, 1e-12) << i;
      EXPECT_NEAR((r.normals[i] - c.normals[i]).norm(), 0, 1e-9) << i;
    }
  }
}

TEST_F(InputTolerance, ReaderAllZeroNormalsMeanNoNormalsAndIgnoreNeverParsesThem) {
  const PointCloud c = sphere_cloud(100);
  const fs::path zero = dir_ / "zero.xyz", junk = dir_ / "junk.xyz";
  write_xyz(c, zero, [](size_t) { return std::string("0 0 0"); });
  write_xyz(c, junk, [](size_t i) { return i % 2 ? std::string("nan nan nan") : std::string("x y z"); });
  edgefront::PointReadOptions tolerate;
  tolerate.tolerate_invalid_normals = true;
  edgefront::PointReadReport report;
  const PointCloud z = edgefront::read_points(zero, tolerate, &report);
  EXPECT_EQ(z.size(), 100u);
  EXPECT_TRUE(z.normals.empty());
  EXPECT_TRUE(report.all_normals_invalid);
  EXPECT_EQ(report.zero_normals, 100u);
  EXPECT_NE(report.warning.find("all 100 normals are zero-length"), std::string::npos) << report.warning;
  // A normal that is not a number at all is still a malformed file when the normals are read...
  EXPECT_THROW(edgefront::read_points(junk, tolerate), edgefront::IoError);
  // ... but ignored normals are not looked at.
  edgefront::PointReadOptions ignore;
  ignore.ignore_normals = true;
  const PointCloud j = edgefront::read_points(junk, ignore, &report);
  EXPECT_EQ(j.size(), 100u);
  EXPECT_TRUE(j.normals.empty());
  EXPECT_TRUE(report.normals_ignored);
  EXPECT_EQ(report.invalid_normals, 0u);
  EXPECT_EQ(report.warning, "");
  for (size_t i = 0; i < j.size(); ++i) EXPECT_NEAR((j.points[i] - c.points[i]).norm(), 0, 1e-12);
}

TEST_F(InputTolerance, ReaderToleratesAZeroNormalInAPly) {
  PointCloud c = sphere_cloud(50);
  c.normals[10] = Vec3(0, 0, 0);  // write_points refuses only non-finite normals
  const fs::path path = dir_ / "zero.ply";
  edgefront::write_points(c, path);
  EXPECT_THROW(edgefront::read_points(path), edgefront::IoError);
  edgefront::PointReadOptions tolerate;
  tolerate.tolerate_invalid_normals = true;
  edgefront::PointReadReport report;
  const PointCloud r = edgefront::read_points(path, tolerate, &report);
  EXPECT_EQ(report.invalid_normals, 1u);
  EXPECT_NE(report.warning.find("vertex 10: zero-length normal"), std::string::npos) << report.warning;
  EXPECT_TRUE(std::isnan(r.normals[10][0]));
}

// ------------------------------------------------------------------ the reconstructor

gcs::ReconstructOptions small(size_t target) {
  gcs::ReconstructOptions o;
  o.target_vertices = target;
  o.growth.batch_splits = 50;
  o.progress_interval = 25;
  return o;
}

double signed_volume(const edgefront::Mesh& m) {
  double vol = 0;
  for (auto f : m.faces()) {
    auto it = m.cfv_iter(f);
    const Vec3 a = m.point(*it), b = m.point(*++it), c = m.point(*++it);
    vol += (a | (b % c)) / 6.0;
  }
  return vol;
}

TEST(InputToleranceLibrary, MissingNormalsAreFittedOrientedAndCounted) {
  PointCloud c = sphere_cloud(2000);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  size_t dropped = 0;
  for (size_t i = 0; i < c.size(); i += 7, ++dropped) c.normals[i] = i % 2 ? Vec3(0, 0, 0) : Vec3(nan, nan, nan);
  const gcs::ReconstructResult r = gcs::reconstruct(c, small(300));
  EXPECT_EQ(r.normals_filled, dropped);
  EXPECT_FALSE(r.normals_unusable);
  const edgefront::MeshStats s = edgefront::compute_stats(r.mesh);
  EXPECT_EQ(s.components, 1u);
  EXPECT_EQ(s.border_loops, 0u);
  EXPECT_EQ(s.euler_characteristic, 2);
  EXPECT_GT(signed_volume(r.mesh), 0.8 * 4.0 / 3.0 * M_PI);  // outward, as the given normals
  // A cloud whose normals are all missing is a cloud without normals: the same mesh.
  PointCloud none = c, bare = c;
  for (Vec3& n : none.normals) n = Vec3(0, 0, 0);
  bare.normals.clear();
  const gcs::ReconstructResult a = gcs::reconstruct(none, small(200));
  const gcs::ReconstructResult b = gcs::reconstruct(bare, small(200));
  EXPECT_TRUE(a.normals_unusable);
  EXPECT_EQ(a.normals_filled, 0u);
  EXPECT_FALSE(b.normals_unusable);
  ASSERT_EQ(a.mesh.n_vertices(), b.mesh.n_vertices());
  for (auto v : a.mesh.vertices()) ASSERT_EQ(a.mesh.point(v), b.mesh.point(v));
}

TEST(InputToleranceLibrary, ProgressNamesEveryPhaseInOrder) {
  for (const bool normals : {true, false}) {
    PointCloud c = sphere_cloud(1500);
    if (normals) {
      c.normals[5] = Vec3(0, 0, 0);  // one missing normal: the normal fitting runs for it
    } else {
      c.normals.clear();
    }
    std::vector<gcs::Phase> phases;
    std::vector<double> fractions;
    const gcs::ReconstructResult r = gcs::reconstruct(c, small(200), [&](const gcs::Progress& p) {
      if (phases.empty() || phases.back() != p.phase) phases.push_back(p.phase);
      fractions.push_back(p.phase_fraction);
      EXPECT_GE(p.phase_fraction, 0.0);
      EXPECT_LE(p.phase_fraction, 1.0);
      return true;
    });
    EXPECT_EQ(r.stop_reason, gcs::StopReason::target_reached);
    const std::vector<gcs::Phase> expected =
        normals ? std::vector<gcs::Phase>{gcs::Phase::normal_fitting, gcs::Phase::noise_estimate, gcs::Phase::growth,
                                          gcs::Phase::post_processing}
                : std::vector<gcs::Phase>{gcs::Phase::noise_estimate, gcs::Phase::normal_fitting, gcs::Phase::growth,
                                          gcs::Phase::post_processing};
    EXPECT_EQ(phases, expected) << "normals " << normals;
    ASSERT_FALSE(fractions.empty());
    EXPECT_EQ(fractions.back(), 1.0);
  }
  EXPECT_EQ(gcs::to_string(gcs::Phase::noise_estimate), "noise estimate");
  EXPECT_EQ(gcs::to_string(gcs::Phase::post_processing), "post-processing");
}

TEST(InputToleranceLibrary, MaxTargetVerticesCountsDistinctPoints) {
  PointCloud c = sphere_cloud(300);
  EXPECT_EQ(gcs::max_target_vertices(c), 300u);
  c.points.insert(c.points.end(), c.points.begin(), c.points.begin() + 40);
  EXPECT_EQ(gcs::max_target_vertices(c), 300u);
  gcs::ReconstructOptions o = small(301);
  c.normals.clear();
  try {
    gcs::Reconstructor r(c, o);
    ADD_FAILURE() << "a target above the distinct points was accepted";
  } catch (const edgefront::InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("number of distinct points (300"), std::string::npos) << e.what();
  }
}

// ------------------------------------------------------------------ the app

TEST_F(InputTolerance, AppDropsInvalidNormalsWithAWarningAndIgnoreNormalsNeverReadsThem) {
  const PointCloud c = sphere_cloud(1500);
  const fs::path path = dir_ / "scan.xyz";
  write_xyz(c, path, [](size_t i) { return i % 10 == 0 ? std::string("0 0 0") : i % 10 == 5 ? std::string("nan nan nan") : std::string(); });
  const fs::path out = dir_ / "mesh.off";
  const eftest::CommandResult r = run(q(path) + " -o " + q(out) + " --vertices 300");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("gcs-reconstruct: warning:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("300 of 1500 normals are invalid (150 zero-length, 150 NaN"), std::string::npos) << r.err;
  EXPECT_NE(r.out.find("300 missing normal(s) fitted"), std::string::npos) << r.out;
  const edgefront::MeshStats s = edgefront::compute_stats(edgefront::load_mesh(out));
  EXPECT_EQ(s.components, 1u);
  EXPECT_EQ(s.border_loops, 0u);
  // --ignore-normals: no warning, and the same file as the points written without normals.
  PointCloud bare = c;
  bare.normals.clear();
  const fs::path bare_path = dir_ / "bare.xyz";
  edgefront::write_points(bare, bare_path);
  const fs::path a = dir_ / "a.off", b = dir_ / "b.off";
  const eftest::CommandResult ra = run(q(path) + " -o " + q(a) + " --vertices 200 --ignore-normals");
  ASSERT_EQ(ra.exit_code, 0) << ra.err;
  EXPECT_EQ(ra.err, "");
  ASSERT_EQ(run(q(bare_path) + " -o " + q(b) + " --vertices 200").exit_code, 0);
  EXPECT_EQ(eftest::slurp(a), eftest::slurp(b));
}

TEST_F(InputTolerance, AppAllZeroNormalsMeanNoNormals) {
  const PointCloud c = sphere_cloud(1000);
  const fs::path zero = dir_ / "zero.xyz";
  write_xyz(c, zero, [](size_t) { return std::string("0 0 0"); });
  PointCloud bare = c;
  bare.normals.clear();
  const fs::path bare_path = dir_ / "bare.xyz";
  edgefront::write_points(bare, bare_path);
  const fs::path a = dir_ / "a.off", b = dir_ / "b.off";
  const eftest::CommandResult r = run(q(zero) + " -o " + q(a) + " --vertices 200");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("all 1000 normals are zero-length: the cloud is read without normals"), std::string::npos) << r.err;
  ASSERT_EQ(run(q(bare_path) + " -o " + q(b) + " --vertices 200").exit_code, 0);
  EXPECT_EQ(eftest::slurp(a), eftest::slurp(b));
}

TEST_F(InputTolerance, AppDefaultTargetIsWhatTheCloudCanHold) {
  PointCloud c = sphere_cloud(400);
  c.points.insert(c.points.end(), c.points.begin(), c.points.begin() + 20);  // 20 repeats
  c.normals.insert(c.normals.end(), c.normals.begin(), c.normals.begin() + 20);
  const fs::path path = dir_ / "small.xyz", out = dir_ / "small.off";
  edgefront::write_points(c, path);
  const eftest::CommandResult r = run(q(path) + " -o " + q(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("target 400 vertices (the default 5000 is more than the cloud's 400 distinct points)"),
            std::string::npos)
      << r.out;
  EXPECT_GT(edgefront::compute_stats(edgefront::load_mesh(out)).vertices, 300u);
  // An explicit target above the limit is refused, naming it.
  const eftest::CommandResult e = run(q(path) + " -o " + q(out) + " --vertices 500");
  EXPECT_EQ(e.exit_code, 1);
  EXPECT_NE(e.err.find("number of distinct points (400; 20 repeat an earlier one)"), std::string::npos) << e.err;
  // Fewer than 4 distinct points: a clear error, not a target below 4.
  PointCloud tiny;
  tiny.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 1, 0)};
  const fs::path tiny_path = dir_ / "tiny.xyz";
  edgefront::write_points(tiny, tiny_path);
  const eftest::CommandResult t = run(q(tiny_path) + " -o " + q(out));
  EXPECT_EQ(t.exit_code, 1);
  EXPECT_NE(t.err.find("3 distinct points"), std::string::npos) << t.err;
}

TEST_F(InputTolerance, AppProgressBarNamesThePhases) {
  // The bar is drawn only on a terminal: `script` gives the app one.
  if (std::system("script --version >/dev/null 2>&1") != 0) GTEST_SKIP() << "no script(1) for a terminal";
  const PointCloud c = sphere_cloud(1500);
  PointCloud bare = c;
  bare.normals.clear();
  const fs::path path = dir_ / "bare.xyz", out = dir_ / "bare.off", log = dir_ / "tty.txt";
  edgefront::write_points(bare, path);
  const std::string command = eftest::shell_quoted(app_.string()) + " " + q(path) + " -o " + q(out) + " --vertices 200";
  const std::string shell = "script -qec " + eftest::shell_quoted(command) + " /dev/null > " + q(log) + " 2>&1";
  ASSERT_EQ(std::system(shell.c_str()), 0) << eftest::slurp(log);
  const std::string tty = eftest::slurp(log);
  for (const char* phase : {"noise estimate", "normal fitting", "growth", "post-processing"})
    EXPECT_NE(tty.find(phase), std::string::npos) << phase << " missing in: " << tty;
  EXPECT_NE(tty.find("200/200 vertices"), std::string::npos) << tty;
}

}  // namespace
