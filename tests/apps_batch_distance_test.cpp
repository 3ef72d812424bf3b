// ef-distance's batch mode (--sources, --sources-file, --targets, --threads): real runs of the
// built tool; the CSV table is parsed and compared with the library's fields value for value, and
// the file is the same bytes for any thread count.

#include <gtest/gtest.h>

#include "app_test_util.h"

#include <charconv>
#include <limits>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "edgefront/front_source.h"
#include "edgefront/mesh.h"
#include "edgefront/mesh_io.h"
#include "edgefront/minimal_distance_front.h"

namespace {

namespace fs = std::filesystem;
using edgefront::FrontSource;
using edgefront::Mesh;
using edgefront::VertexHandle;
using eftest::CommandResult;

std::string data_file(const std::string& name) { return eftest::shell_quoted((fs::path(EDGEFRONT_DATA_DIR) / name).string()); }

struct Table {
  std::vector<std::string> header;
  std::vector<std::vector<double>> rows;  // the first value is the row label
};

Table parse_csv(const std::string& text) {
  Table t;
  std::istringstream in(text);
  std::string line;
  bool first = true;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream ls(line);
    for (std::string cell; std::getline(ls, cell, ',');) cells.push_back(cell);
    if (first) {
      t.header = cells;
      first = false;
      continue;
    }
    std::vector<double> row;
    for (const std::string& c : cells) {
      double x = 0;
      if (c == "inf") {
        x = std::numeric_limits<double>::infinity();
      } else {
        const auto r = std::from_chars(c.data(), c.data() + c.size(), x);
        EXPECT_TRUE(r.ec == std::errc() && r.ptr == c.data() + c.size()) << "bad cell '" << c << "'";
      }
      row.push_back(x);
    }
    t.rows.push_back(row);
  }
  return t;
}

class AppsBatchDistanceTest : public eftest::AppTest {
 protected:
  AppsBatchDistanceTest() : AppTest("ef-distance") {}
  std::string path(const std::string& name) const { return eftest::shell_quoted((dir_ / name).string()); }
};

TEST_F(AppsBatchDistanceTest, OneColumnPerSourceIsTheLibrarysFieldAndThreadsDoNotChangeTheBytes) {
  const Mesh mesh = edgefront::read_mesh((fs::path(EDGEFRONT_DATA_DIR) / "torus.off").string()).mesh;
  const std::vector<int> sources{7, 0, 150, 7};
  for (const std::string method : {"mdf", "fast"}) {
    const CommandResult r =
        run(data_file("torus.off") + " --sources 7,0,150,7 --method " + method + " --threads 1 -o " + path("one.csv"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("4 sources x 192 vertices, 1 thread(s)"), std::string::npos) << r.err;
    const std::string one = eftest::slurp(dir_ / "one.csv");
    const Table t = parse_csv(one);
    ASSERT_EQ(t.header, (std::vector<std::string>{"vertex", "7", "0", "150", "7"}));
    ASSERT_EQ(t.rows.size(), mesh.n_vertices());
    edgefront::DistanceOptions o;
    o.method = edgefront::parse_distance_method(method);
    for (size_t i = 0; i < sources.size(); ++i) {
      const std::vector<double> f = edgefront::geodesic_distance(mesh, FrontSource::vertex(VertexHandle(sources[i])), o).distance;
      for (size_t v = 0; v < f.size(); ++v) {
        ASSERT_EQ(t.rows[v][0], static_cast<double>(v));
        EXPECT_EQ(t.rows[v][i + 1], f[v]) << method << " source " << sources[i] << " vertex " << v;
      }
    }
    for (const std::string threads : {"2", "3"}) {
      const CommandResult m = run(data_file("torus.off") + " --sources 7,0,150,7 --method " + method + " --threads " +
                                  threads + " -o " + path("many.csv"));
      ASSERT_EQ(m.exit_code, 0) << m.err;
      EXPECT_NE(m.err.find(threads + " thread(s)"), std::string::npos) << m.err;
      EXPECT_EQ(eftest::slurp(dir_ / "many.csv"), one) << method << ", " << threads << " threads";
    }
  }
}

TEST_F(AppsBatchDistanceTest, TargetsGiveAMatrixAndFilesTakeCommentsAndLines) {
  const Mesh mesh = edgefront::read_mesh((fs::path(EDGEFRONT_DATA_DIR) / "bumpy-sphere.off").string()).mesh;
  {
    std::ofstream f(dir_ / "sources.txt");
    f << "# landmarks\n3, 40\n\n100 # the last one\n";
  }
  const CommandResult r = run(data_file("bumpy-sphere.off") + " --sources-file " + path("sources.txt") +
                              " --targets 5,3,77 --max-distance 1.2 -o " + path("m.txt"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Table t = parse_csv(eftest::slurp(dir_ / "m.txt"));
  ASSERT_EQ(t.header, (std::vector<std::string>{"source", "5", "3", "77"}));
  ASSERT_EQ(t.rows.size(), 3u);
  const int sources[] = {3, 40, 100}, targets[] = {5, 3, 77};
  for (size_t i = 0; i < 3; ++i) {
    const std::vector<double> f =
        edgefront::geodesic_distance(mesh, FrontSource::vertex(VertexHandle(sources[i])), {.max_distance = 1.2}).distance;
    EXPECT_EQ(t.rows[i][0], sources[i]);
    for (size_t j = 0; j < 3; ++j) EXPECT_EQ(t.rows[i][j + 1], f[static_cast<size_t>(targets[j])]) << i << "," << j;
  }
  EXPECT_EQ(t.rows[0][2], 0.0);  // source 3 to target 3

  // The table goes to stdout without -o.
  const CommandResult s = run(data_file("bumpy-sphere.off") + " --sources 3 --targets 3");
  ASSERT_EQ(s.exit_code, 0) << s.err;
  EXPECT_EQ(s.out, "source,3\n3,0\n");
}

TEST_F(AppsBatchDistanceTest, BadBatchArgumentsAreClearErrors) {
  struct Case {
    std::string args;
    int code;
    std::string message;
  };
  {
    std::ofstream f(dir_ / "bad.txt");
    f << "1 2\n3 x9\n";
    std::ofstream g(dir_ / "empty.txt");
    g << "# nothing\n";
  }
  const std::vector<Case> cases = {
      {"--targets 1,2", 2, "--targets and --targets-file need --sources"},
      {"--sources 1 --source 2", 2, "excludes"},
      {"--sources 1 --threads -1", 2, "--threads"},
      {"--sources 1 --threads 5000", 2, "out of range"},
      {"--source 1 --threads 2", 2, "--threads applies to the batch mode"},
      {"--sources 1 -o " + path("x.ply"), 2, "writes CSV"},
      {"--source 1 -o " + path("x.csv"), 2, "batch table"},
      {"--sources 1,99999", 1, "--sources: vertex 99999 is out of range"},
      {"--sources-file " + path("bad.txt"), 2, "line 2: 'x9' is not a vertex index"},
      {"--sources-file " + path("empty.txt"), 1, "holds no vertex index"},
      {"--sources-file " + path("missing.txt"), 1, "is not a readable regular file"},
  };
  for (const Case& c : cases) {
    const CommandResult r = run(data_file("torus.off") + " " + c.args);
    EXPECT_EQ(r.exit_code, c.code) << c.args << ": " << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << ": " << r.err;
    EXPECT_NE(r.err.find("ef-distance: error: "), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "x.ply") || fs::exists(dir_ / "x.csv")) << c.args;
  }
}

}  // namespace
