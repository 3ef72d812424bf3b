// Tests of the ef-front and ef-distance command-line tools: real runs of the built executables
// (EDGEFRONT_APP_DIR) on the bundled meshes (EDGEFRONT_DATA_DIR), with the output compared to the
// library's own answers, PLY output read back, and the documented exit codes (0 ok, 1 error with
// one line "<app>: error: ..." on stderr, 2 usage error). ef-distance: every --method, every
// source form, the summary line, the PLY's values and colours, bad values and bad meshes.

#include <gtest/gtest.h>

#include "app_test_util.h"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "edgefront/front_source.h"
#include "edgefront/mesh.h"
#include "edgefront/mesh_io.h"
#include "edgefront/minimal_distance_front.h"
#include "edgefront/minimal_edge_front.h"
#include "shapes/shapes.h"
#include "edgefront/vertex_front.h"
#include "render/color.h"

namespace {

namespace fs = std::filesystem;
using edgefront::FrontSource;
using edgefront::Mesh;
using edgefront::VertexHandle;

using eftest::CommandResult;
using eftest::slurp;
std::string quoted(const std::string& text) { return eftest::shell_quoted(text); }

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::string data_file(const std::string& name) { return (fs::path(EDGEFRONT_DATA_DIR) / name).string(); }

/// Runs one of the apps in a private temporary directory.
class AppsFrontTest : public ::testing::Test {
 protected:
  void use_app(const std::string& name) {
    app_ = fs::path(EDGEFRONT_APP_DIR) / name;
    ASSERT_TRUE(fs::exists(app_)) << name << " is not built at " << app_;
  }
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("edgefront_apps_front_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    if (!dir_.empty()) fs::remove_all(dir_, ec);
  }
  CommandResult run(const std::string& args) const { return eftest::run_command(app_, args, dir_); }
  /// Expects exit code 1 and exactly one line "<app>: error: ..." on stderr, mentioning `hint`.
  void expect_error(const std::string& args, const std::string& hint) const {
    const CommandResult r = run(args);
    const std::string prefix = app_.filename().string() + ": error: ";
    EXPECT_EQ(r.exit_code, 1) << args << "\n" << r.err;
    EXPECT_EQ(r.err.rfind(prefix, 0), 0u) << args << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(hint), std::string::npos) << args << "\n" << r.err;
    EXPECT_EQ(r.out, "") << args;
  }
  void expect_usage_error(const std::string& args, const std::string& hint = "") const {
    const CommandResult r = run(args);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(app_.filename().string() + ": error: "), std::string::npos) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(hint), std::string::npos) << args << "\n" << r.err;
  }
  fs::path path(const std::string& name) const { return dir_ / name; }

  fs::path app_, dir_;
};

/// Parses one integer per line.
std::vector<int> parse_levels(const std::string& text) {
  std::vector<int> out;
  for (const std::string& line : lines_of(text)) {
    size_t used = 0;
    out.push_back(std::stoi(line, &used));
    EXPECT_EQ(used, line.size()) << "'" << line << "'";
  }
  return out;
}

/// The number in front of `word` in a summary such as "3 collisions, 2 splits" (-1 if absent).
int summary_count(const std::string& summary, const std::string& word) {
  const std::regex pattern("(\\d+) " + word);
  std::smatch m;
  return std::regex_search(summary, m, pattern) ? std::stoi(m[1].str()) : -1;
}

// ---- ef-front -----------------------------------------------------------------------------

TEST_F(AppsFrontTest, EfFrontLevelsOnTorusMatchTheLibrary) {
  use_app("ef-front");
  const Mesh mesh = edgefront::read_mesh(data_file("torus.off")).mesh;
  const CommandResult r = run(quoted(data_file("torus.off")) + " --source 0");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<int> levels = parse_levels(r.out);
  ASSERT_EQ(levels.size(), mesh.n_vertices());
  EXPECT_EQ(levels, edgefront::edge_front_levels(mesh, FrontSource::vertex(VertexHandle(0))));
  EXPECT_EQ(levels[0], 0);
  EXPECT_TRUE(std::all_of(levels.begin(), levels.end(), [](int l) { return l >= 0; }));
  // The summary: a closed torus ends with no loop; the front split and merged on the way.
  EXPECT_NE(r.err.find("192 of 192 vertices reached"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("0 loops left (0 inert)"), std::string::npos) << r.err;
  EXPECT_GE(summary_count(r.err, "split"), 1) << r.err;
  EXPECT_GE(summary_count(r.err, "merge"), 1) << r.err;
  EXPECT_GE(summary_count(r.err, "annihilation"), 1) << r.err;
  EXPECT_EQ(summary_count(r.err, "border reached"), 0) << r.err;
  EXPECT_NE(r.err.find("peak front"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("error"), std::string::npos) << r.err;
}

TEST_F(AppsFrontTest, EfFrontVertexFrontSeveralSourcesAndLevelLimit) {
  use_app("ef-front");
  const Mesh mesh = edgefront::read_mesh(data_file("neck.off")).mesh;
  const FrontSource source = FrontSource::from_vertices({VertexHandle(5), VertexHandle(70)});
  for (const std::string method : {"vf", "mef"}) {
    const CommandResult r = run(quoted(data_file("neck.off")) + " --source 5,70 --levels 2 --method " + method);
    ASSERT_EQ(r.exit_code, 0) << method << ": " << r.err;
    const std::vector<int> levels = parse_levels(r.out);
    ASSERT_EQ(levels.size(), mesh.n_vertices()) << method;
    EXPECT_EQ(levels, edgefront::edge_front_levels(mesh, source, 2)) << method;
    EXPECT_EQ(levels, edgefront::vertex_front_levels(mesh, source, 2)) << method;
    EXPECT_EQ(*std::max_element(levels.begin(), levels.end()), 2) << method;
    EXPECT_GT(std::count(levels.begin(), levels.end(), -1), 0) << method;
    EXPECT_NE(r.err.find(method + ", 2 levels run"), std::string::npos) << r.err;
  }
}

TEST_F(AppsFrontTest, EfFrontLoopSourceOnBothSides) {
  use_app("ef-front");
  // The neck's minimum pathway 43-44-45 (data/README.md): a 3-cycle without a face that
  // separates the two blobs. Each side of the loop reaches only its own blob.
  const Mesh mesh = edgefront::read_mesh(data_file("neck.off")).mesh;
  const std::vector<VertexHandle> path = {VertexHandle(43), VertexHandle(44), VertexHandle(45)};
  std::vector<int> left, right;
  for (const auto& [side, out] : {std::pair{std::string("left"), &left}, std::pair{std::string("right"), &right}}) {
    const CommandResult r = run(quoted(data_file("neck.off")) + " --loop 43,44,45 --side " + side);
    ASSERT_EQ(r.exit_code, 0) << side << ": " << r.err;
    *out = parse_levels(r.out);
    const auto loop = edgefront::loop_from_vertices(
        mesh, path, side == "left" ? edgefront::LoopSide::Left : edgefront::LoopSide::Right);
    EXPECT_EQ(*out, edgefront::edge_front_levels(mesh, loop)) << side;
  }
  ASSERT_EQ(left.size(), mesh.n_vertices());
  ASSERT_EQ(right.size(), mesh.n_vertices());
  for (size_t i = 0; i < left.size(); ++i) {
    if (i == 43 || i == 44 || i == 45) {
      EXPECT_EQ(left[i], 0);
      EXPECT_EQ(right[i], 0);
    } else {
      EXPECT_NE(left[i] >= 0, right[i] >= 0) << "vertex " << i << " on both or neither side";
    }
  }
  // The closing vertex may be written again; the result is the same.
  const CommandResult again = run(quoted(data_file("neck.off")) + " --loop 43,44,45,43");
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_EQ(parse_levels(again.out), left);
}

TEST_F(AppsFrontTest, EfFrontWritesTextAndPlyFiles) {
  use_app("ef-front");
  const Mesh mesh = edgefront::read_mesh(data_file("torus.off")).mesh;
  const CommandResult on_stdout = run(quoted(data_file("torus.off")) + " --source 3 --levels 4");
  ASSERT_EQ(on_stdout.exit_code, 0) << on_stdout.err;

  const CommandResult txt =
      run(quoted(data_file("torus.off")) + " --source 3 --levels 4 -o " + quoted(path("levels.txt").string()));
  ASSERT_EQ(txt.exit_code, 0) << txt.err;
  EXPECT_EQ(txt.out, "");
  EXPECT_EQ(slurp(path("levels.txt")), on_stdout.out);

  const CommandResult ply =
      run(quoted(data_file("torus.off")) + " --source 3 --levels 4 -o " + quoted(path("levels.ply").string()));
  ASSERT_EQ(ply.exit_code, 0) << ply.err;
  EXPECT_EQ(ply.out, "");
  const edgefront::MeshReadResult back = edgefront::read_mesh(path("levels.ply"));
  EXPECT_EQ(back.mesh.n_vertices(), mesh.n_vertices());
  EXPECT_EQ(back.mesh.n_faces(), mesh.n_faces());
  const std::string text = slurp(path("levels.ply"));
  const std::string header = text.substr(0, text.find("end_header"));
  EXPECT_NE(header.find("property double level"), std::string::npos) << header;
  EXPECT_NE(header.find("property uchar red"), std::string::npos) << header;
}

TEST_F(AppsFrontTest, EfFrontBadInputIsOneErrorLineAndExitOne) {
  use_app("ef-front");
  const std::string torus = quoted(data_file("torus.off"));
  expect_error(quoted(path("missing.off").string()) + " --source 0", "missing.off");
  expect_error(torus + " --source 192", "out of range");
  expect_usage_error(torus + " --source 0,-1", "not a vertex index");
  expect_usage_error(torus + " --source 1x", "not a vertex index");
  expect_usage_error(torus + " --source 0,,2", "not a vertex index");
  expect_error(torus + " --source 99999999999999999999999", "out of range");
  expect_error(torus + " --source 4,4", "given twice");
  // 0 and 100 are far apart on the torus: the loop does not close along edges.
  expect_error(torus + " --loop 0,1,100", "edge");
  expect_error(torus + " --loop 0,1", "3");
  EXPECT_FALSE(fs::exists(path("never.txt")));
  expect_error(torus + " --source 500 -o " + quoted(path("never.txt").string()), "out of range");
  EXPECT_FALSE(fs::exists(path("never.txt")));
}

TEST_F(AppsFrontTest, EfFrontUsageErrorsExitTwo) {
  use_app("ef-front");
  const std::string torus = quoted(data_file("torus.off"));
  expect_usage_error(torus);                                   // no source
  expect_usage_error(torus + " --source 0 --loop 0,1,2");      // both
  expect_usage_error(torus + " --source 0 --method bfs");      // unknown method
  expect_usage_error(torus + " --source 0 --levels -2");       // negative levels
  expect_usage_error(torus + " --source 0 --levels two");      // not a number
  expect_usage_error(torus + " --loop 0,1,2 --side up");       // unknown side
  expect_usage_error(torus + " --source 0 --side left");       // side without a loop
  expect_usage_error(torus + " --source 0 -o out.obj");        // unsupported output
  expect_usage_error(torus + " --source 0 --bogus");           // unknown flag
  expect_usage_error("--source 0");                            // no mesh
  expect_usage_error(torus + " --source 0 --levels ''");       // empty: CLI11 alone read it as 0
  expect_usage_error(torus + " --source 0 --levels=");
  const CommandResult empty = run(torus + " --source '' --levels 2");
  EXPECT_EQ(empty.exit_code, 2);
  EXPECT_NE(empty.err.find("empty value for --source"), std::string::npos) << empty.err;
  const CommandResult help = run("--help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_NE(help.out.find("--method"), std::string::npos);
}

// ---- ef-distance --------------------------------------------------------------------------

/// Parses one distance per line ("inf" for unreached).
std::vector<double> parse_distances(const std::string& text) {
  std::vector<double> out;
  for (const std::string& line : lines_of(text)) {
    size_t used = 0;
    out.push_back(std::stod(line, &used));
    EXPECT_EQ(used, line.size()) << "'" << line << "'";
  }
  return out;
}

TEST_F(AppsFrontTest, EfDistanceFromAVertexMatchesTheLibraryExactly) {
  use_app("ef-distance");
  const Mesh mesh = edgefront::read_mesh(data_file("torus.off")).mesh;
  const FrontSource source = FrontSource::vertex(VertexHandle(7));
  const CommandResult mdf = run(quoted(data_file("torus.off")) + " --source 7");
  ASSERT_EQ(mdf.exit_code, 0) << mdf.err;
  const std::vector<double> d = parse_distances(mdf.out);
  ASSERT_EQ(d.size(), mesh.n_vertices());
  EXPECT_EQ(d[7], 0.0);
  for (size_t i = 0; i < d.size(); ++i) {
    if (i != 7) {
      EXPECT_TRUE(std::isfinite(d[i]) && d[i] > 0) << i << ": " << d[i];
    }
  }
  // Written with round-trip precision: the very same doubles as the library's.
  EXPECT_EQ(d, edgefront::geodesic_distance(mesh, source).distance);
  EXPECT_NE(mdf.err.find("mdf, "), std::string::npos) << mdf.err;
  EXPECT_NE(mdf.err.find("192 of 192 vertices reached"), std::string::npos) << mdf.err;
  EXPECT_NE(mdf.err.find("stop: exhausted"), std::string::npos) << mdf.err;
  EXPECT_EQ(std::count(mdf.err.begin(), mdf.err.end(), '\n'), 1) << mdf.err;

  const CommandResult dij = run(quoted(data_file("torus.off")) + " --source 7 --method dijkstra");
  ASSERT_EQ(dij.exit_code, 0) << dij.err;
  const std::vector<double> e = parse_distances(dij.out);
  EXPECT_EQ(e, edgefront::dijkstra_distance(mesh, source).distance);
  ASSERT_EQ(e.size(), d.size());
  for (size_t i = 0; i < d.size(); ++i) EXPECT_LE(d[i], e[i] * (1 + 1e-12)) << i;  // MDF below the edge paths

  // --method windows and --method fast: the library's field of that mode, byte for byte, never
  // above the edge paths; the summary names the method.
  auto mode_field = [&](const std::string& method, const edgefront::DistanceOptions& options) {
    const CommandResult r = run(quoted(data_file("torus.off")) + " --source 7 --method " + method);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    const std::vector<double> f = parse_distances(r.out);
    EXPECT_EQ(f, edgefront::geodesic_distance(mesh, source, options).distance);
    EXPECT_EQ(f.size(), e.size());
    for (size_t i = 0; i < std::min(f.size(), e.size()); ++i) EXPECT_LE(f[i], e[i] * (1 + 1e-12)) << i;
    EXPECT_NE(r.err.find(method + ", "), std::string::npos) << r.err;
    return std::make_pair(f, r.err);
  };
  const auto [w, win_err] = mode_field("windows", {.method = edgefront::DistanceMethod::Windows});
  EXPECT_NE(w, d);  // the two modes really differ on the torus

  // The fast mode also never goes below the straight distance and has no front.
  const auto [f, fast_err] = mode_field("fast", {.method = edgefront::DistanceMethod::Fast});
  EXPECT_NE(f, e);  // not the edge paths
  for (size_t i = 0; i < f.size(); ++i) {
    EXPECT_GE(f[i], (mesh.point(VertexHandle(static_cast<int>(i))) - mesh.point(VertexHandle(7))).norm() * (1 - 1e-12)) << i;
  }
  EXPECT_NE(fast_err.find("no front"), std::string::npos) << fast_err;
}

TEST_F(AppsFrontTest, EfDistanceMaxDistanceBoundsEveryFiniteOutput) {
  use_app("ef-distance");
  for (const std::string method : {"mdf", "dijkstra"}) {
    const CommandResult r = run(quoted(data_file("bumpy-sphere.off")) + " --source 0 --max-distance 0.6 --method " + method);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::vector<double> d = parse_distances(r.out);
    ASSERT_EQ(d.size(), 642u);
    size_t finite = 0;
    for (const double x : d) {
      if (std::isfinite(x)) {
        ++finite;
        EXPECT_LE(x, 0.6) << method;
      } else {
        EXPECT_EQ(x, std::numeric_limits<double>::infinity()) << method;
      }
    }
    EXPECT_GT(finite, 5u) << method;
    EXPECT_LT(finite, 642u) << method;
    EXPECT_NE(r.err.find("stop: max distance"), std::string::npos) << r.err;
  }
}

TEST_F(AppsFrontTest, EfDistanceIsInfiniteOnAnotherComponent) {
  use_app("ef-distance");
  // Two concentric spheres: the outer one's vertices come first.
  const Mesh mesh = edgefront::shapes::nested_spheres(1);
  const fs::path file = path("nested.off");
  edgefront::write_mesh(mesh, file);
  const std::vector<int> component = [&] {
    std::vector<int> levels = edgefront::edge_front_levels(mesh, FrontSource::vertex(VertexHandle(0)));
    for (int& l : levels) l = l >= 0 ? 0 : 1;
    return levels;
  }();
  ASSERT_GT(std::count(component.begin(), component.end(), 1), 0);
  const CommandResult r = run(quoted(file.string()) + " --source 0");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<double> d = parse_distances(r.out);
  ASSERT_EQ(d.size(), mesh.n_vertices());
  for (size_t i = 0; i < d.size(); ++i) EXPECT_EQ(std::isfinite(d[i]), component[i] == 0) << i << ": " << d[i];
  EXPECT_NE(r.out.find("inf\n"), std::string::npos);
}

TEST_F(AppsFrontTest, EfDistanceFromALoopAndFromSurfacePoints) {
  use_app("ef-distance");
  const Mesh neck = edgefront::read_mesh(data_file("neck.off")).mesh;
  const std::vector<VertexHandle> path_vertices = {VertexHandle(43), VertexHandle(44), VertexHandle(45)};
  const CommandResult loop = run(quoted(data_file("neck.off")) + " --loop 43,44,45 --side right");
  ASSERT_EQ(loop.exit_code, 0) << loop.err;
  const std::vector<double> d = parse_distances(loop.out);
  ASSERT_EQ(d.size(), neck.n_vertices());
  EXPECT_EQ(d, edgefront::geodesic_distance(
                   neck, edgefront::loop_from_vertices(neck, path_vertices, edgefront::LoopSide::Right))
                   .distance);
  for (const VertexHandle v : path_vertices) EXPECT_EQ(d[static_cast<size_t>(v.idx())], 0.0);
  // Only the right side's blob is reached: the same vertices as ef-front's levels.
  const std::vector<int> levels = edgefront::edge_front_levels(
      neck, edgefront::loop_from_vertices(neck, path_vertices, edgefront::LoopSide::Right));
  for (size_t i = 0; i < d.size(); ++i) EXPECT_EQ(std::isfinite(d[i]), levels[i] >= 0) << i;

  const Mesh torus = edgefront::read_mesh(data_file("torus.off")).mesh;
  const CommandResult points = run(quoted(data_file("torus.off")) + " --point 10:0.2,0.3,0.5 --point 200:1,0,0");
  ASSERT_EQ(points.exit_code, 0) << points.err;
  const std::vector<double> p = parse_distances(points.out);
  edgefront::SurfacePoint a, b;
  a.face = edgefront::FaceHandle(10);
  a.bary = {0.2, 0.3, 0.5};
  b.face = edgefront::FaceHandle(200);
  b.bary = {1, 0, 0};
  EXPECT_EQ(p, edgefront::geodesic_distance(torus, std::vector<edgefront::SurfacePoint>{a, b}).distance);
  EXPECT_EQ(p[static_cast<size_t>((*torus.cfv_begin(edgefront::FaceHandle(200))).idx())], 0.0);
}

TEST_F(AppsFrontTest, EfDistanceWritesTextAndPlyFiles) {
  use_app("ef-distance");
  const std::string torus = quoted(data_file("torus.off"));
  const CommandResult on_stdout = run(torus + " --source 3 --max-distance 1");
  ASSERT_EQ(on_stdout.exit_code, 0) << on_stdout.err;
  const CommandResult txt = run(torus + " --source 3 --max-distance 1 -o " + quoted(path("d.txt").string()));
  ASSERT_EQ(txt.exit_code, 0) << txt.err;
  EXPECT_EQ(txt.out, "");
  EXPECT_EQ(slurp(path("d.txt")), on_stdout.out);
  const CommandResult ply = run(torus + " --source 3 --max-distance 1 -o " + quoted(path("d.PLY").string()));
  ASSERT_EQ(ply.exit_code, 0) << ply.err;
  const edgefront::MeshReadResult back = edgefront::read_mesh(path("d.PLY"));
  EXPECT_EQ(back.mesh.n_vertices(), 192u);
  EXPECT_EQ(back.mesh.n_faces(), 384u);
  const std::string text = slurp(path("d.PLY"));
  const std::string header = text.substr(0, text.find("end_header"));
  EXPECT_NE(header.find("property double distance"), std::string::npos) << header;
  EXPECT_NE(header.find("property uchar blue"), std::string::npos) << header;
}

TEST_F(AppsFrontTest, EfDistanceBadInputExitsOneAndBadUsageTwo) {
  use_app("ef-distance");
  const std::string torus = quoted(data_file("torus.off"));
  expect_error(quoted(path("missing.off").string()) + " --source 0", "missing.off");
  expect_error(torus + " --source 192", "out of range");
  expect_usage_error(torus + " --source zero", "not a vertex index");
  expect_error(torus + " --loop 0,1,100", "edge");
  expect_error(torus + " --point 384:1,0,0", "out of range");
  // The syntax of --point is checked at parse time (usage errors), its values with the mesh.
  expect_usage_error(torus + " --point 0:0.5,0.5", "3 barycentric");
  expect_usage_error(torus + " --point 0:0.5,x,0.5", "not a number");
  expect_usage_error(torus + " --point 3,4:1,0,0", "not a face index");
  expect_usage_error(torus + " --point 0-0.5,0,0.5", "F:b0,b1,b2");
  expect_error(torus + " --point 0:0.5,0.6,0.5", "sum");
  expect_error(torus + " --point 0:-0.5,1,0.5", "non-negative");
  // A missing output directory: a usage error at parse time, before any work (issue 29).
  expect_usage_error(torus + " --source 0 -o " + quoted(path("no-such-dir/d.txt").string()), "no-such-dir");

  expect_usage_error(torus);
  expect_usage_error(torus + " --source 0 --loop 0,1,2");
  expect_usage_error(torus + " --source 0 --point 0:1,0,0");
  expect_usage_error(torus + " --loop 0,1,2 --method windows", "--loop");
  expect_usage_error(torus + " --loop 0,1,2 --method fast", "--loop");
  expect_usage_error(torus + " --source 0 --method heat");
  expect_usage_error(torus + " --source 0 --max-distance -1");
  expect_usage_error(torus + " --source 0 --max-distance nan");
  expect_usage_error(torus + " --source 0 --side right");
  expect_usage_error(torus + " --source 0 -o d.xyz");
}


/// The library's field for ef-distance's --method (the CLI runs without directions).
edgefront::DistanceField library_field(const Mesh& mesh, const FrontSource& source, const std::string& method,
                                       edgefront::DistanceOptions options = {}) {
  options.directions = false;
  options.method = edgefront::parse_distance_method(method);
  return edgefront::geodesic_distance(mesh, source, options);
}

// Every method: the library's field byte for byte, inf exactly on the other component, the
// summary's count of reached vertices equal to the finite lines, --max-distance 0 only the
// source, --max-distance inf no limit.
TEST_F(AppsFrontTest, EfDistanceEveryMethodOnTwoComponents) {
  use_app("ef-distance");
  const Mesh mesh = edgefront::shapes::nested_spheres(1);
  const fs::path file = path("nested.off");
  edgefront::write_mesh(mesh, file);
  const std::vector<int> hops = edgefront::edge_front_levels(mesh, FrontSource::vertex(VertexHandle(3)));
  const auto reached = static_cast<size_t>(std::count_if(hops.begin(), hops.end(), [](int h) { return h >= 0; }));
  ASSERT_LT(reached, mesh.n_vertices());
  for (const std::string method : {"mdf", "windows", "fast", "dijkstra"}) {
    const CommandResult r = run(quoted(file.string()) + " --source 3 --method " + method);
    ASSERT_EQ(r.exit_code, 0) << method << ": " << r.err;
    const std::vector<double> d = parse_distances(r.out);
    EXPECT_EQ(d, library_field(mesh, FrontSource::vertex(VertexHandle(3)), method).distance) << method;
    ASSERT_EQ(d.size(), mesh.n_vertices());
    for (size_t i = 0; i < d.size(); ++i) {
      EXPECT_EQ(std::isfinite(d[i]), hops[i] >= 0) << method << ": vertex " << i << " at " << d[i];
      if (i != 3) {
        EXPECT_GT(d[i], 0) << method << ": vertex " << i;
      }
    }
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_EQ(summary_count(r.err, "of " + std::to_string(mesh.n_vertices()) + " vertices reached"),
              static_cast<int>(reached))
        << r.err;
    EXPECT_NE(r.err.find(" ms, "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(method == "mdf" || method == "windows" ? "peak front " : "no front"), std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find("peak working memory "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("stop: exhausted"), std::string::npos) << r.err;

    const CommandResult zero = run(quoted(file.string()) + " --source 3,5 --max-distance 0 --method " + method);
    ASSERT_EQ(zero.exit_code, 0) << zero.err;
    const std::vector<double> z = parse_distances(zero.out);
    ASSERT_EQ(z.size(), mesh.n_vertices());
    for (size_t i = 0; i < z.size(); ++i) {
      EXPECT_EQ(z[i], i == 3 || i == 5 ? 0.0 : std::numeric_limits<double>::infinity()) << method << ": " << i;
    }
    EXPECT_NE(zero.err.find("2 of " + std::to_string(mesh.n_vertices()) + " vertices reached"), std::string::npos)
        << zero.err;
    EXPECT_NE(zero.err.find("stop: max distance"), std::string::npos) << zero.err;
    const CommandResult unbounded = run(quoted(file.string()) + " --source 3 --max-distance inf --method " + method);
    ASSERT_EQ(unbounded.exit_code, 0) << unbounded.err;
    EXPECT_EQ(unbounded.out, r.out) << method;
  }
  // Surface points in the modes that take them; the closing vertex of a loop may be repeated.
  const Mesh torus = edgefront::read_mesh(data_file("torus.off")).mesh;
  edgefront::SurfacePoint p;
  p.face = edgefront::FaceHandle(10);
  p.bary = {0.2, 0.3, 0.5};
  for (const std::string method : {"windows", "fast", "dijkstra"}) {
    const CommandResult r = run(quoted(data_file("torus.off")) + " --point 10:0.2,0.3,0.5 --method " + method);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(parse_distances(r.out),
              edgefront::geodesic_distance(torus, std::vector<edgefront::SurfacePoint>{p},
                                           {.directions = false, .method = edgefront::parse_distance_method(method)})
                  .distance)
        << method;
  }
  const std::string neck = quoted(data_file("neck.off"));
  const CommandResult open_form = run(neck + " --loop 43,44,45 --side right --method dijkstra");
  const CommandResult closed_form = run(neck + " --loop 43,44,45,43 --side right --method dijkstra");
  ASSERT_EQ(open_form.exit_code, 0) << open_form.err;
  ASSERT_EQ(closed_form.exit_code, 0) << closed_form.err;
  EXPECT_EQ(closed_form.out, open_form.out);
  EXPECT_NE(open_form.out.find("inf\n"), std::string::npos);  // the loop's other side
}

// The PLY for MeshLab: binary little endian, x y z, the distance as a double property, then
// red green blue; the distances are those of the text output (inf kept), grey exactly where not
// reached, and colours from the colormap with isolines (the source lies on the first, darkened).
TEST_F(AppsFrontTest, EfDistancePlyHoldsTheDistancesAndIsolineColors) {
  use_app("ef-distance");
  const std::string torus = quoted(data_file("torus.off"));
  const CommandResult txt = run(torus + " --source 3 --max-distance 1.5");
  ASSERT_EQ(txt.exit_code, 0) << txt.err;
  const std::vector<double> expected = parse_distances(txt.out);
  const CommandResult ply = run(torus + " --source 3 --max-distance 1.5 -o " + quoted(path("d.ply").string()));
  ASSERT_EQ(ply.exit_code, 0) << ply.err;
  const std::string bytes = slurp(path("d.ply"));
  const std::string end_header = "end_header\n";
  const size_t body = bytes.find(end_header);
  ASSERT_NE(body, std::string::npos);
  const std::string header = bytes.substr(0, body);
  EXPECT_EQ(header.rfind("ply\nformat binary_little_endian 1.0\n", 0), 0u) << header;
  EXPECT_NE(header.find("\nelement vertex 192\nproperty double x\nproperty double y\nproperty double z\n"
                        "property double distance\nproperty double quality\nproperty uchar red\nproperty uchar green\n"
                        "property uchar blue\n"
                        "element face 384\n"),
            std::string::npos)
      << header;
  constexpr size_t kRecord = 5 * sizeof(double) + 3;
  ASSERT_GE(bytes.size(), body + end_header.size() + 192 * kRecord);
  const char* at = bytes.data() + body + end_header.size();
  std::set<std::array<uint8_t, 3>> colors;
  size_t unreached = 0;
  for (size_t i = 0; i < 192; ++i, at += kRecord) {
    double d = 0;
    double quality = 0;
    std::memcpy(&d, at + 3 * sizeof(double), sizeof d);  // the machine is little endian
    std::memcpy(&quality, at + 4 * sizeof(double), sizeof quality);
    std::array<uint8_t, 3> c{};
    std::memcpy(c.data(), at + 5 * sizeof(double), 3);
    EXPECT_EQ(d, expected[i]) << "vertex " << i;
    EXPECT_EQ(quality, std::isinf(d) ? -1.0 : d) << "vertex " << i;  // MeshLab's per-vertex quality
    const bool grey = c == std::array<uint8_t, 3>{128, 128, 128};
    EXPECT_EQ(grey, std::isinf(d)) << "vertex " << i;
    unreached += std::isinf(d);
    colors.insert(c);
  }
  EXPECT_GT(unreached, 0u);
  EXPECT_LT(unreached, 150u);
  EXPECT_GT(colors.size(), 10u);  // a colormap, not one colour
  // The source (distance 0) sits on the first isoline: the colormap's start at 30% brightness.
  const std::array<uint8_t, 3> start = edgefront::render::colormap(0.0);
  std::array<uint8_t, 3> source{};
  std::memcpy(source.data(), bytes.data() + body + end_header.size() + 3 * kRecord + 5 * sizeof(double), 3);
  for (size_t k = 0; k < 3; ++k) EXPECT_EQ(source[k], static_cast<uint8_t>(start[k] * 0.3)) << k;
}

TEST_F(AppsFrontTest, EfDistanceRefusesBadValuesAndMeshes) {
  use_app("ef-distance");
  const std::string torus = quoted(data_file("torus.off"));
  // CLI11 reads an empty number as 0; ef-distance refuses it, and NaN, and what overflows a double.
  expect_usage_error(torus + " --source 0 --max-distance ''", "--max-distance");
  expect_usage_error(torus + " --source 0 --max-distance 1e400", "'1e400' is out of the range of a double");
  expect_usage_error(torus + " --source 0 --max-distance=-inf", "-inf is out of range (>= 0)");
  expect_usage_error(torus + " --source 0 --max-distance 1x", "'1x' is not a number");
  expect_usage_error(torus + " --source -1", "not a vertex index");
  expect_error(torus + " --source 99999999999999999999999", "out of range");
  expect_error(torus + " --source 0,191,0", "twice");
  expect_error(torus + " --loop 0,1,0", "at least 3 vertices, got 2");
  expect_error(torus + " --point 0:0.3,0.3,0.3", "sum");
  expect_usage_error(torus + " --point 0:nan,0.5,0.5", "nan is not a number");

  // A vertex where two fans meet (two triangles sharing only vertex 0): the reader splits it into
  // one vertex per fan (a copy appended after the file's vertices, linked as its twin, with a
  // warning), so every method runs and lists the file's 5 vertices, then the copy.
  const fs::path bowtie = path("bowtie.off");
  std::ofstream(bowtie) << "OFF\n5 2 0\n0 0 0\n1 0 0\n1 1 0\n-1 0 0\n-1 -1 0\n3 0 1 2\n3 0 3 4\n";
  for (const std::string method : {"mdf", "windows", "fast", "dijkstra"}) {
    const CommandResult r = run(quoted(bowtie.string()) + " --source 1 --method " + method);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("pinched vertex was split"), std::string::npos) << r.err;
    EXPECT_EQ(parse_distances(r.out).size(), 6u) << method;
  }

  const fs::path nan_off = path("nan.off");
  std::ofstream(nan_off) << "OFF\n3 1 0\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n";
  expect_error(quoted(nan_off.string()) + " --source 0", "non-finite");
  const fs::path empty = path("empty.off");
  std::ofstream(empty) << "OFF\n0 0 0\n";
  expect_error(quoted(empty.string()) + " --source 0", "the mesh has 0 vertices");

  const CommandResult help = run("--help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_NE(help.out.find("may be repeated"), std::string::npos) << help.out;
}

}  // namespace
