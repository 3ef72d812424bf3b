#include <gtest/gtest.h>

#include "app_test_util.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

#include "edgefront/mesh.h"
#include "edgefront/mesh_stats.h"

namespace fs = std::filesystem;
using namespace edgefront;

namespace {

Mesh make_mesh(const std::vector<Vec3>& points, const std::vector<std::array<int, 3>>& faces) {
  Mesh m;
  for (const Vec3& p : points) m.add_vertex(p);
  for (const auto& f : faces) {
    const FaceHandle fh = m.add_face(VertexHandle(f[0]), VertexHandle(f[1]), VertexHandle(f[2]));
    EXPECT_TRUE(fh.is_valid()) << "test mesh face refused";
  }
  return m;
}

Mesh tetrahedron() {
  return make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}},
                   {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}});
}

/// A torus from a 4x4 grid with wrap-around in both directions: V 16, E 48, F 32, genus 1.
Mesh torus4x4() {
  constexpr int n = 4;
  std::vector<Vec3> points;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double u = 2 * M_PI * i / n, v = 2 * M_PI * j / n;
      points.emplace_back((2 + std::cos(v)) * std::cos(u), (2 + std::cos(v)) * std::sin(u), std::sin(v));
    }
  }
  const auto id = [](int i, int j) { return ((i + n) % n) * n + (j + n) % n; };
  std::vector<std::array<int, 3>> faces;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  return make_mesh(points, faces);
}

}  // namespace

TEST(MeshStats, TetrahedronIsAClosedGenusZeroSurface) {
  const MeshStats s = compute_stats(tetrahedron());
  EXPECT_EQ(s.vertices, 4u);
  EXPECT_EQ(s.edges, 6u);
  EXPECT_EQ(s.faces, 4u);
  EXPECT_EQ(s.euler_characteristic, 2);
  EXPECT_EQ(s.components, 1u);
  EXPECT_EQ(s.border_loops, 0u);
  EXPECT_EQ(s.isolated_vertices, 0u);
  EXPECT_EQ(s.nonmanifold_vertices, 0u);
  EXPECT_EQ(s.degenerate_faces, 0u);
  EXPECT_EQ(s.duplicate_faces, 0u);
  ASSERT_EQ(s.per_component.size(), 1u);
  EXPECT_EQ(s.per_component[0].euler, 2);
  EXPECT_EQ(s.per_component[0].genus, 0.0);
  EXPECT_EQ(s.valence_histogram, (std::vector<size_t>{0, 0, 0, 4}));
  EXPECT_EQ(s.bbox_min, Vec3(0, 0, 0));
  EXPECT_EQ(s.bbox_max, Vec3(1, 1, 1));
  EXPECT_DOUBLE_EQ(s.bbox_diagonal, std::sqrt(3.0));
  EXPECT_DOUBLE_EQ(s.min_edge_length, 1.0);
  EXPECT_DOUBLE_EQ(s.max_edge_length, std::sqrt(2.0));
  EXPECT_DOUBLE_EQ(s.mean_edge_length, (3 + 3 * std::sqrt(2.0)) / 6);
}

TEST(MeshStats, SquareOfTwoTrianglesHasOneBorderLoop) {
  const Mesh m = make_mesh({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 2, 3}});
  const MeshStats s = compute_stats(m);
  EXPECT_EQ(s.edges, 5u);
  EXPECT_EQ(s.border_loops, 1u);
  EXPECT_EQ(s.euler_characteristic, 1);
  ASSERT_EQ(s.per_component.size(), 1u);
  EXPECT_EQ(s.per_component[0].border_loops, 1u);
  EXPECT_EQ(s.per_component[0].genus, 0.0);
  EXPECT_EQ(s.valence_histogram, (std::vector<size_t>{0, 0, 2, 2}));
}

TEST(MeshStats, TwoDisjointTrianglesAndAnIsolatedVertex) {
  const Mesh m = make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {5, 5, 5}, {5, 0, 0}, {6, 0, 0}, {5, 1, 0}},
                           {{0, 1, 2}, {4, 5, 6}});
  const MeshStats s = compute_stats(m);
  EXPECT_EQ(s.components, 3u);
  EXPECT_EQ(s.isolated_vertices, 1u);
  EXPECT_EQ(s.border_loops, 2u);
  ASSERT_EQ(s.per_component.size(), 3u);
  // Components are ordered by their lowest vertex: {0,1,2}, {3}, {4,5,6}.
  EXPECT_EQ(s.per_component[0].faces, 1u);
  EXPECT_EQ(s.per_component[1].vertices, 1u);
  EXPECT_EQ(s.per_component[1].faces, 0u);
  EXPECT_EQ(s.per_component[1].euler, 1);
  EXPECT_EQ(s.per_component[2].vertices, 3u);
  EXPECT_EQ(s.per_component[2].euler, 1);
  EXPECT_EQ(s.per_component[2].genus, 0.0);
  EXPECT_EQ(s.valence_histogram[0], 1u);

  const ComponentLabels labels = connected_components(m);
  EXPECT_EQ(labels.count, 3u);
  EXPECT_EQ(labels.vertex_component, (std::vector<int>{0, 0, 0, 1, 2, 2, 2}));
}

TEST(MeshStats, TorusFromAWrappedGridHasGenusOne) {
  const MeshStats s = compute_stats(torus4x4());
  EXPECT_EQ(s.vertices, 16u);
  EXPECT_EQ(s.edges, 48u);
  EXPECT_EQ(s.faces, 32u);
  EXPECT_EQ(s.euler_characteristic, 0);
  EXPECT_EQ(s.border_loops, 0u);
  EXPECT_EQ(s.components, 1u);
  ASSERT_EQ(s.per_component.size(), 1u);
  EXPECT_EQ(s.per_component[0].genus, 1.0);
  EXPECT_EQ(s.valence_histogram, (std::vector<size_t>{0, 0, 0, 0, 0, 0, 16}));
}

TEST(MeshStats, DeletedElementsAreSkipped) {
  Mesh m = tetrahedron();
  m.delete_face(FaceHandle(2), false);  // opens the tetrahedron; no garbage collection
  MeshStats s = compute_stats(m);
  EXPECT_EQ(s.faces, 3u);
  EXPECT_EQ(s.edges, 6u);
  EXPECT_EQ(s.border_loops, 1u);
  EXPECT_EQ(s.euler_characteristic, 1);
  EXPECT_EQ(s.per_component[0].genus, 0.0);

  Mesh t = tetrahedron();
  t.delete_vertex(VertexHandle(3), true);  // leaves the bottom triangle
  s = compute_stats(t);
  EXPECT_EQ(s.vertices, 3u);
  EXPECT_EQ(s.faces, 1u);
  EXPECT_EQ(s.edges, 3u);
  EXPECT_EQ(s.border_loops, 1u);
  EXPECT_EQ(s.bbox_max, Vec3(1, 1, 0));
  const ComponentLabels labels = connected_components(t);
  EXPECT_EQ(labels.vertex_component, (std::vector<int>{0, 0, 0, -1}));
}

TEST(MeshStats, NonManifoldDegenerateAndDuplicateFaces) {
  // Bowtie: two triangles meeting at vertex 0 only.
  const Mesh bowtie =
      make_mesh({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {-1, 0, 0}, {-1, -1, 0}}, {{0, 1, 2}, {0, 3, 4}});
  const MeshStats b = compute_stats(bowtie);
  EXPECT_EQ(b.nonmanifold_vertices, 1u);
  EXPECT_EQ(b.components, 1u);

  // Two copies of a triangle with opposite orientation (a closed "pillow"), and a collinear one.
  const Mesh m = make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {3, 0, 0}, {4, 0, 0}, {5, 0, 0}},
                           {{0, 1, 2}, {0, 2, 1}, {3, 4, 5}});
  const MeshStats s = compute_stats(m);
  EXPECT_EQ(s.duplicate_faces, 1u);
  EXPECT_EQ(s.degenerate_faces, 1u);
  EXPECT_EQ(s.per_component[0].euler, 2);  // the pillow is a sphere
}

TEST(MeshStats, EmptyMeshAndFormatting) {
  const MeshStats empty = compute_stats(Mesh());
  EXPECT_EQ(empty.vertices, 0u);
  EXPECT_EQ(empty.components, 0u);
  EXPECT_EQ(empty.bbox_diagonal, 0.0);
  EXPECT_TRUE(empty.valence_histogram.empty());
  EXPECT_NE(format_stats(empty).find("(none)"), std::string::npos);

  const std::string text = format_stats(compute_stats(torus4x4()));
  EXPECT_NE(text.find("vertices:             16 (0 isolated, 0 non-manifold)\n"), std::string::npos) << text;
  EXPECT_NE(text.find("euler characteristic: 0\n"), std::string::npos) << text;
  EXPECT_NE(text.find("valence histogram:    6: 16\n"), std::string::npos) << text;
  EXPECT_NE(text.find("component 0: 16 vertices, 32 faces, 0 border loops, euler 0, genus 1\n"),
            std::string::npos)
      << text;
}

// ---------------------------------------------------------------------------------------------
// ef-info, run as a real command.

namespace {

using eftest::CommandResult;

class MeshStatsEfInfo : public ::testing::Test {
 protected:
  void SetUp() override {
    app_ = fs::path(EDGEFRONT_APP_DIR) / "ef-info";
    ASSERT_TRUE(fs::exists(app_)) << "ef-info is not built at " << app_;
    dir_ = fs::temp_directory_path() / ("edgefront_efinfo_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    if (!dir_.empty()) fs::remove_all(dir_, ec);
  }
  static std::string quoted(const std::string& text) { return eftest::shell_quoted(text); }
  CommandResult run(const std::string& args) { return eftest::run_command(app_, args, dir_); }
  static std::string data(const std::string& name) {
    return quoted((fs::path(EDGEFRONT_TEST_DATA_DIR) / name).string());
  }
  fs::path app_, dir_;
};

}  // namespace

TEST_F(MeshStatsEfInfo, PrintsStatisticsOfAValidMesh) {
  const CommandResult r = run(data("tetra.off"));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_NE(r.out.find("vertices:             4 (0 isolated, 0 non-manifold)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("euler characteristic: 2"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("genus 0"), std::string::npos) << r.out;
}

TEST_F(MeshStatsEfInfo, PrintsReadWarnings) {
  const CommandResult r = run(data("bad/nonmanifold.off"));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("warning: 1 triangle dropped"), std::string::npos) << r.out;
}

TEST_F(MeshStatsEfInfo, MissingFileIsOneErrorLineAndExitOne) {
  const CommandResult r = run(data("no_such_mesh.off"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err.rfind("ef-info: error: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find("no_such_mesh.off: file does not exist"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

TEST_F(MeshStatsEfInfo, StrictModeRefusesNonManifoldFile) {
  const CommandResult r = run("--strict " + data("bad/nonmanifold.off"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("line 11"), std::string::npos) << r.err;
}

TEST_F(MeshStatsEfInfo, UsageErrorsExitTwo) {
  EXPECT_EQ(run("").exit_code, 2);
  EXPECT_EQ(run("--strict --drop-nonmanifold " + data("tetra.off")).exit_code, 2);
  const CommandResult unknown = run("--bogus " + data("tetra.off"));
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_EQ(unknown.err.rfind("ef-info: error: ", 0), 0u) << unknown.err;
  const CommandResult help = run("--help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_NE(help.out.find("--strict"), std::string::npos);
}
