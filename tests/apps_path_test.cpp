// Tests of the ef-path command-line tool: real runs of the built executable on bundled and
// generated meshes, output compared with the library, OBJ/PLY polylines read back, exit codes.

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "app_test_util.h"
#include "edgefront/connection_path.h"
#include "edgefront/mesh.h"
#include "edgefront/mesh_io.h"
#include "shapes/shapes.h"

namespace {

namespace fs = std::filesystem;
using namespace edgefront;

class AppsPathTest : public eftest::AppTest {
 protected:
  AppsPathTest() : AppTest("ef-path") {}
};

std::string data_file(const std::string& name) { return (fs::path(EDGEFRONT_DATA_DIR) / name).string(); }

// The value after "key " on its own line.
std::string field(const std::string& out, const std::string& key) {
  std::istringstream in(out);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind(key + " ", 0) == 0) return line.substr(key.size() + 1);
  }
  return "";
}

TEST_F(AppsPathTest, PrintsTheLibrarysPathForEveryMethod) {
  const std::string file = data_file("bumpy-sphere.off");
  const Mesh mesh = load_mesh(file);
  for (const auto& [name, method] : {std::pair{"vf", PathMethod::VertexFront},
                                     {"mef", PathMethod::MinimalEdgeFront}, {"mdf", PathMethod::MinimalDistance}}) {
    const ConnectionPath p = connection_path(mesh, VertexHandle(0), VertexHandle(100), {.method = method});
    const auto r = run(eftest::shell_quoted(file) + " 0 100 --method " + name);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(field(r.out, "edges"), std::to_string(p.edges)) << name;
    EXPECT_DOUBLE_EQ(std::stod(field(r.out, "length")), p.length) << name;
    std::string vs;
    for (VertexHandle v : p.vertices) {
      if (!vs.empty()) vs.push_back(' ');
      vs.append(std::to_string(v.idx()));
    }
    EXPECT_EQ(field(r.out, "vertices"), vs) << name;
    EXPECT_NE(r.err.find("elements processed"), std::string::npos) << r.err;
  }
}

TEST_F(AppsPathTest, WritesThePolylineAsObjAndPly) {
  const std::string file = data_file("bumpy-sphere.off");
  const Mesh mesh = load_mesh(file);
  const ConnectionPath p = connection_path(mesh, VertexHandle(3), VertexHandle(400), {.polyline = true});
  for (const char* ext : {".obj", ".ply"}) {
    std::string name = "path";
    name.append(ext);
    const fs::path out = dir_ / name;
    const auto r = run(eftest::shell_quoted(file) + " 3 400 --polyline -o " + eftest::shell_quoted(out.string()));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(field(r.out, "polyline-points"), std::to_string(p.polyline.size()));
    ASSERT_TRUE(fs::exists(out));
    const std::string text = eftest::slurp(out);
    if (std::string(ext) == ".obj") {
      size_t v_records = 0;
      std::istringstream in(text);
      std::string l_record;
      for (std::string line; std::getline(in, line);) {
        if (line.rfind("v ", 0) == 0) ++v_records;
        if (line.rfind("l ", 0) == 0) l_record = line;
      }
      EXPECT_EQ(v_records, p.polyline.size());
      EXPECT_EQ(l_record.rfind("l 1 2 ", 0), 0u) << l_record;
    } else {
      EXPECT_NE(text.find("element vertex " + std::to_string(p.polyline.size())), std::string::npos);
      EXPECT_NE(text.find("element edge " + std::to_string(p.polyline.size() - 1)), std::string::npos);
    }
  }
}

TEST_F(AppsPathTest, NoPathEqualEndpointsAndErrors) {
  const fs::path nested = dir_ / "nested.off";
  write_mesh(shapes::nested_spheres(1), nested);
  const Mesh mesh = load_mesh(nested);
  const auto last = std::to_string(mesh.n_vertices() - 1);
  auto r = run(eftest::shell_quoted(nested.string()) + " 0 " + last + " --method mef");
  EXPECT_EQ(r.exit_code, 3) << r.err;  // documented: 3 = no path
  EXPECT_EQ(r.out, "no path\n");
  r = run(eftest::shell_quoted(nested.string()) + " 5 5");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(field(r.out, "edges"), "0");
  EXPECT_EQ(field(r.out, "vertices"), "5");
  r = run(eftest::shell_quoted(nested.string()) + " 0 100000");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("ef-path: error: TO: vertex 100000 is out of range"), std::string::npos) << r.err;
  r = run(eftest::shell_quoted((dir_ / "missing.off").string()) + " 0 1");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err.rfind("ef-path: error: ", 0), 0u) << r.err;
  for (const std::string bad : {" 0", " 0 1 --method dijkstra", " zero 1", " 0 1 -o path.txt"}) {
    r = run(eftest::shell_quoted(nested.string()) + bad);
    EXPECT_EQ(r.exit_code, 2) << bad << "\n" << r.err;
  }
}

TEST_F(AppsPathTest, NoPathExitsThreeAndLeavesNoStaleOutput) {
  // An earlier run's path at -o would look like this run's answer: it is removed.
  const fs::path nested = dir_ / "nested.off";
  write_mesh(shapes::nested_spheres(1), nested);
  const auto last = std::to_string(load_mesh(nested).n_vertices() - 1);
  const fs::path out = dir_ / "path.obj";
  auto r = run(eftest::shell_quoted(nested.string()) + " 0 5 -o " + eftest::shell_quoted(out.string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_TRUE(fs::exists(out));
  r = run(eftest::shell_quoted(nested.string()) + " 0 " + last + " -o " + eftest::shell_quoted(out.string()));
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_EQ(r.out, "no path\n");
  EXPECT_FALSE(fs::exists(out)) << "a stale path file was left at -o";
  EXPECT_NE(r.err.find("no path: removed the old"), std::string::npos) << r.err;
  r = run("--help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("3 no path"), std::string::npos) << r.out;
}

}  // namespace
