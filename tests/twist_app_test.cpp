// Tests of the ef-twist tool: a real process repairs a twisted mesh file and writes it; errors
// are one line with exit code 1 (2 for usage).

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "app_test_util.h"
#include "edgefront/mesh_io.h"
#include "edgefront/mesh_stats.h"
#include "edgefront/point_cloud_io.h"
#include "render/image.h"
#include "twist/repair.h"
#include "shapes/twisted_shapes.h"

namespace {

namespace fs = std::filesystem;

class TwistApp : public eftest::AppTest {
 protected:
  TwistApp() : AppTest("ef-twist") {}
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
};

TEST_F(TwistApp, RepairsAFlippedDiskAndWritesTheResult) {
  const twist::TwistedShape s = twist::flipped_disk_plate();
  edgefront::write_mesh(s.mesh, path("twisted.off"));
  const auto r = run(eftest::shell_quoted(path("twisted.off")) + " -o " + eftest::shell_quoted(path("fixed.ply")));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("regions found:      1"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("repairs:            1"), std::string::npos) << r.out;
  const edgefront::Mesh fixed = edgefront::load_mesh(path("fixed.ply"));
  // At most a sliver the cut split off is removed (never left as a tiny component).
  EXPECT_LE(fixed.n_faces(), s.mesh.n_faces());
  EXPECT_GT(fixed.n_faces() + twist::RepairOptions{}.cuts.min_component_faces, s.mesh.n_faces());
  EXPECT_DOUBLE_EQ(twist::truth_consistency(fixed, s), 1.0);
  EXPECT_EQ(edgefront::compute_stats(fixed).nonmanifold_vertices, 0u);
}

TEST_F(TwistApp, PicturesShowTheRegionBeforeAndNoBackFacesAfter) {
  const twist::TwistedShape s = twist::flipped_disk_plate();
  edgefront::write_mesh(s.mesh, path("twisted.off"));
  const auto r = run(eftest::shell_quoted(path("twisted.off")) + " -o " + eftest::shell_quoted(path("fixed.ply")) +
                     " --png " + eftest::shell_quoted(path("t.png")) + " --size 200x200 --elevation 0 --azimuth 0");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const edgefront::render::Image before = edgefront::render::read_png(dir_ / "t-before.png");
  const edgefront::render::Image after = edgefront::render::read_png(dir_ / "t.png");
  EXPECT_EQ(after.width, 200);
  EXPECT_EQ(after.height, 200);
  // The region is highlighted (red family: strong red, weak green and blue) before, not after.
  auto reddish = [](const edgefront::render::Image& im) {
    int n = 0;
    for (int y = 0; y < im.height; ++y) {
      for (int x = 0; x < im.width; ++x) {
        const auto c = im.at(x, y);
        n += c[0] > 120 && c[1] < 80 && c[2] < 80 ? 1 : 0;
      }
    }
    return n;
  };
  EXPECT_GT(reddish(before), 50);
  EXPECT_LT(reddish(after), reddish(before) / 4);
}

TEST_F(TwistApp, UsesOrientedPointsAndReportsConsistency) {
  const twist::TwistedShape s = twist::flipped_disk_plate();
  edgefront::write_mesh(s.mesh, path("twisted.off"));
  const edgefront::PointCloud cloud = twist::truth_points(s);
  edgefront::write_points(cloud, path("cloud.ply"));
  const auto r = run(eftest::shell_quoted(path("twisted.off")) + " --points " + eftest::shell_quoted(path("cloud.ply")) +
                     " -o " + eftest::shell_quoted(path("fixed.off")));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("consistency:"), std::string::npos) << r.out;
  EXPECT_DOUBLE_EQ(twist::truth_consistency(edgefront::load_mesh(path("fixed.off")), s), 1.0);
}

TEST_F(TwistApp, LabelsByThePointsOrUsesTheDetectorWhenAsked) {
  twist::TwistedTubeOptions to;
  to.along = 24;
  to.around = 16;
  to.length = 1.6;
  const twist::TwistedShape s = twist::twisted_tube(to);
  edgefront::write_mesh(s.mesh, path("tube.off"));
  edgefront::write_points(twist::truth_points(s), path("cloud.ply"));
  const std::string in = eftest::shell_quoted(path("tube.off")) + " --points " + eftest::shell_quoted(path("cloud.ply"));
  const auto r = run(in + " --mend 0 -o " + eftest::shell_quoted(path("labelled.off")));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("faces flipped, cut along"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("faces removed:      0 (0% of the area)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("components:         1 -> 2"), std::string::npos) << r.out;
  EXPECT_GE(twist::truth_consistency(edgefront::load_mesh(path("labelled.off")), s), 0.99);
  EXPECT_NE(r.out.find("twist lines cut:    1"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("mended:"), std::string::npos) << r.out;
  // By default the folds left on the twist line are mended (the report says how).
  const auto m = run(in + " -o " + eftest::shell_quoted(path("mended.off")));
  ASSERT_EQ(m.exit_code, 0) << m.err;
  EXPECT_NE(m.out.find("components:         1 -> 2"), std::string::npos) << m.out;
  EXPECT_NE(m.out.find("mended:"), std::string::npos) << m.out;
  EXPECT_GE(twist::truth_consistency(edgefront::load_mesh(path("mended.off")), s), 0.99);
  const auto d = run(in + " --detector -o " + eftest::shell_quoted(path("detected.off")));
  ASSERT_EQ(d.exit_code, 0) << d.err;
  EXPECT_NE(d.out.find("fronts visited"), std::string::npos) << d.out;
  const auto priced = run(in + " --cut-cost 100 -o " + eftest::shell_quoted(path("priced.off")));
  ASSERT_EQ(priced.exit_code, 0) << priced.err;
  EXPECT_NE(priced.out.find("repairs:            0"), std::string::npos) << priced.out;
  const auto bad = run(in + " --cut-cost 101 -o " + eftest::shell_quoted(path("bad.off")));
  EXPECT_EQ(bad.exit_code, 2) << bad.err;
  EXPECT_NE(bad.err.find("--cut-cost"), std::string::npos) << bad.err;
  for (const char* mend : {"-1", "65", "x"}) {
    const auto refused = run(in + " --mend " + mend + " -o " + eftest::shell_quoted(path("mend.off")));
    EXPECT_EQ(refused.exit_code, 2) << mend << ": " << refused.err;
    EXPECT_NE(refused.err.find("--mend"), std::string::npos) << refused.err;
    EXPECT_FALSE(fs::exists(path("mend.off")));
  }
}

TEST_F(TwistApp, ErrorsAreOneLine) {
  const auto missing = run(eftest::shell_quoted(path("missing.off")) + " -o " + eftest::shell_quoted(path("x.off")));
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_EQ(missing.err.rfind("ef-twist: error: ", 0), 0u) << missing.err;
  EXPECT_FALSE(fs::exists(path("x.off")));
  const auto usage = run(eftest::shell_quoted(path("missing.off")));
  EXPECT_EQ(usage.exit_code, 2) << usage.err;
  const twist::TwistedShape s = twist::flipped_disk_plate();
  edgefront::write_mesh(s.mesh, path("twisted.off"));
  const auto bad = run(eftest::shell_quoted(path("twisted.off")) + " -o " + eftest::shell_quoted(path("out.xyz")));
  EXPECT_EQ(bad.exit_code, 2) << bad.err;  // the output's extension is checked at parse time
  EXPECT_NE(bad.err.find("xyz"), std::string::npos) << bad.err;
}

}  // namespace
