#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

#include <unistd.h>

#include "edgefront/error.h"
#include "edgefront/mesh_io.h"
#include "edgefront/point_cloud_io.h"

namespace fs = std::filesystem;
using namespace edgefront;

namespace {

const fs::path kData = EDGEFRONT_TEST_DATA_DIR;

void spit(const fs::path& p, const std::string& content) {
  std::ofstream out(p, std::ios::binary);
  out << content;
}

class PointCloudIoTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / ("edgefront_pcio_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  fs::path dir_;
};

/// Expects read_points to throw IoError whose message names the file and contains `part`.
void expect_refused(const fs::path& path, const std::string& part) {
  try {
    read_points(path);
    ADD_FAILURE() << path << " was accepted";
  } catch (const IoError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path.filename().string()), std::string::npos) << what;
    EXPECT_NE(what.find(part), std::string::npos) << "expected '" << part << "' in: " << what;
  }
}

PointCloud sample_cloud(bool normals) {
  PointCloud c;
  c.points = {{0, 0, 0}, {0.1, -2.5e-8, 3e12}, {1.0 / 3.0, 2.0 / 3.0, -1}};
  if (normals) c.normals = {{0, 0, 1}, {1, 0, 0}, {0.6, 0.8, 0}};
  return c;
}

}  // namespace

TEST_F(PointCloudIoTest, XyzWithNormalsCommentsAndBlankLines) {
  const PointCloud c = read_points(kData / "points_normals.xyz");
  ASSERT_EQ(c.size(), 3u);
  ASSERT_TRUE(c.has_normals());
  EXPECT_EQ(c.points[1], Vec3(1, 0, 0));
  EXPECT_EQ(c.normals[0], Vec3(0, 0, 1));  // (0 0 2) normalized
  EXPECT_NEAR(c.normals[2][1], 0.6, 1e-15);
  EXPECT_NEAR(c.normals[2][2], 0.8, 1e-15);
}

TEST_F(PointCloudIoTest, PlyWithNormalsIgnoresFacesAndOtherProperties) {
  const PointCloud c = read_points(kData / "points_normals.ply");
  ASSERT_EQ(c.size(), 3u);
  ASSERT_TRUE(c.has_normals());
  EXPECT_EQ(c.normals[1], Vec3(0, 0, 1));
  EXPECT_NEAR(c.normals[2][0], 0.6, 1e-7);
}

TEST_F(PointCloudIoTest, MeshFilesGiveTheirVerticesAndTheirFacesAreChecked) {
  const PointCloud off = read_points(kData / "tetra.off");
  EXPECT_EQ(off.size(), 4u);
  EXPECT_FALSE(off.has_normals());
  spit(dir_ / "pts.obj", "v 0 0 0\nv 1 2 3\nf 1 2 1\n");
  EXPECT_EQ(read_points(dir_ / "pts.obj").points[1], Vec3(1, 2, 3));
  // Broken faces make a broken file, for the cloud reader as for the mesh reader (issue 29: the
  // cloud reader used to skip them, and so took a face record for a point).
  spit(dir_ / "broken_faces.off", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 99\n");
  expect_refused(dir_ / "broken_faces.off", "line 6: face 0: vertex index 99 is out of range (the file has 3 vertices)");
  spit(dir_ / "broken_faces.obj", "v 0 0 0\nv 1 2 3\nf 1 2 7\n");
  expect_refused(dir_ / "broken_faces.obj", "line 3: vertex index 7 is out of range");
}

TEST_F(PointCloudIoTest, RoundTripsExactlyWithAndWithoutNormals) {
  for (const bool normals : {false, true}) {
    for (const char* name : {"c.xyz", "c.ply", "c.pts"}) {
      SCOPED_TRACE(std::string(name) + (normals ? " with normals" : ""));
      const PointCloud c = sample_cloud(normals);
      write_points(c, dir_ / name);
      const PointCloud r = read_points(dir_ / name);
      EXPECT_EQ(r.points, c.points);
      EXPECT_EQ(r.has_normals(), normals);
      if (normals) {
        for (size_t i = 0; i < c.size(); ++i) {
          EXPECT_NEAR((r.normals[i] - c.normals[i]).norm(), 0, 1e-15);
        }
      }
    }
  }
}

TEST_F(PointCloudIoTest, ReadFromBuffer) {
  const PointCloud c = read_points_from_buffer("# in memory\n1 2 3\n4 5 6\n", "mem.xyz");
  ASSERT_EQ(c.size(), 2u);
  EXPECT_EQ(c.points[1], Vec3(4, 5, 6));
  EXPECT_THROW(read_points_from_buffer("1 2 3\n", "mem.stl"), IoError);
}

TEST_F(PointCloudIoTest, PtsCountLine) {
  spit(dir_ / "count.pts", "2\n0 0 0\n1 1 1\n");
  EXPECT_EQ(read_points(dir_ / "count.pts").size(), 2u);
  spit(dir_ / "wrong_count.pts", "3\n0 0 0\n1 1 1\n");
  expect_refused(dir_ / "wrong_count.pts", "declares 3 points but has 2");
}

TEST_F(PointCloudIoTest, BadFilesNameTheLineAndTheProblem) {
  const fs::path bad = kData / "bad";
  expect_refused(bad / "mixed_columns.xyz", "line 3: expected 3 numbers like line 1, found 6");
  expect_refused(bad / "nan_points.xyz", "line 3: non-finite coordinate");
  expect_refused(bad / "zero_normal.xyz", "line 2: zero-length normal");
  expect_refused(bad / "no_points.xyz", "no points");
  expect_refused(bad / "empty.off", "file is empty");
  expect_refused(bad / "nan.obj", "line 4");
  expect_refused(bad / "truncated.off", "truncated");
  expect_refused(bad / "huge_count.ply", "truncated or corrupt");
  expect_refused(bad / "bad_header.ply", "unknown type 'flaot'");
  expect_refused(bad / "missing.xyz", "does not exist");
  expect_refused(bad / "unknown_extension.abc", "unknown point file extension");
  spit(dir_ / "words.xyz", "1 2 three\n");
  expect_refused(dir_ / "words.xyz", "line 1: malformed number 'three'");
  spit(dir_ / "four.xyz", "1 2 3 4\n");
  expect_refused(dir_ / "four.xyz", "line 1: expected 3 or 6 numbers");
  spit(dir_ / "zero_normal.ply",
       "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\n"
       "property float nx\nproperty float ny\nproperty float nz\nend_header\n0 0 0 0 0 1\n1 0 0 0 0 0\n");
  expect_refused(dir_ / "zero_normal.ply", "vertex 1: zero-length normal");
  spit(dir_ / "partial_normal.ply",
       "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
       "property float nx\nend_header\n0 0 0 1\n");
  expect_refused(dir_ / "partial_normal.ply", "only some of nx, ny, nz");
}

TEST_F(PointCloudIoTest, WriteErrors) {
  PointCloud c = sample_cloud(true);
  c.normals.pop_back();
  EXPECT_THROW(write_points(c, dir_ / "a.xyz"), InvalidInput);
  EXPECT_THROW(write_points(sample_cloud(false), dir_ / "a.off"), InvalidInput);
  PointCloud n = sample_cloud(false);
  n.points[0][0] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(write_points(n, dir_ / "a.xyz"), InvalidInput);
  EXPECT_FALSE(fs::exists(dir_ / "a.xyz"));
  EXPECT_THROW(write_points(sample_cloud(false), dir_ / "nope" / "a.xyz"), IoError);
}

TEST_F(PointCloudIoTest, DamagedFilesAreReadOrRefusedWithIoErrorOnly) {
  write_points(sample_cloud(true), dir_ / "src.xyz");
  write_points(sample_cloud(true), dir_ / "src.ply");
  for (const char* name : {"src.xyz", "src.ply"}) {
    std::ifstream in(dir_ / name, std::ios::binary);
    const std::string original((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const fs::path damaged = dir_ / ("damaged" + fs::path(name).extension().string());
    for (size_t cut = 0; cut < original.size(); ++cut) {
      try {
        read_points_from_buffer(original.substr(0, cut), damaged);
      } catch (const IoError&) {
      } catch (const std::exception& e) {
        ADD_FAILURE() << name << " cut at " << cut << ": unexpected exception: " << e.what();
      }
    }
  }
}
