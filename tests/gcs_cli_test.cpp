// Tests of the gcs-reconstruct command-line tool: real runs of the built executable on the bundled
// vault cloud, the written mesh read back, determinism of the file, and the exit codes (0 ok, 1
// error with one line "gcs-reconstruct: error: ..." on stderr, 2 usage error).

#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include "app_test_util.h"
#include "render/image.h"
#include "edgefront/mesh_io.h"
#include "edgefront/mesh_stats.h"
#include "edgefront/point_cloud_io.h"
#include "gcs/evaluation.h"

namespace {

namespace fs = std::filesystem;

class GcsCli : public eftest::AppTest {
 protected:
  GcsCli() : AppTest("gcs-reconstruct") {}
  std::string q(const fs::path& p) const { return eftest::shell_quoted(p.string()); }
  static std::string vault() { return (fs::path(EDGEFRONT_DATA_DIR) / "vault-sheet.xyz").string(); }
};

TEST_F(GcsCli, WritesTheMeshAndASummary) {
  const fs::path out = dir_ / "vault.ply";
  // --no-twist: the plain loop, whose vertex count is exactly the target (the twist repair may
  // duplicate vertices along a cut or remove tiny pieces).
  const eftest::CommandResult r = run(q(vault()) + " -o " + q(out) + " --vertices 300 --no-twist");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.find("twist-repair"), std::string::npos) << r.out;
  EXPECT_EQ(r.err, "");  // stderr is a file here: no progress bar
  EXPECT_NE(r.out.find("300 vertices"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("target reached"), std::string::npos) << r.out;
  const edgefront::Mesh mesh = edgefront::load_mesh(out);
  const edgefront::MeshStats s = edgefront::compute_stats(mesh);
  EXPECT_EQ(s.vertices, 300u);
  EXPECT_EQ(s.nonmanifold_vertices, 0u);
  EXPECT_GT(s.faces, 400u);
}

TEST_F(GcsCli, PresetScanIsTheDefaultOthersChangeTheMeshUnknownIsAUsageError) {
  const fs::path plain = dir_ / "plain.off", scan = dir_ / "scan.off", bare = dir_ / "bare.off", sheet = dir_ / "sheet.off";
  const std::string base = q(vault()) + " --vertices 150 --no-twist -q -o ";
  ASSERT_EQ(run(base + q(plain)).exit_code, 0);
  ASSERT_EQ(run(base + q(scan) + " --preset scan").exit_code, 0);
  EXPECT_EQ(eftest::slurp(plain), eftest::slurp(scan));
  // Without normals open_sheet fits quadric normals: another mesh; a flag still applies on top.
  ASSERT_EQ(run(base + q(bare) + " --ignore-normals").exit_code, 0);
  ASSERT_EQ(run(base + q(sheet) + " --ignore-normals --preset open_sheet").exit_code, 0);
  EXPECT_NE(eftest::slurp(bare), eftest::slurp(sheet));
  const fs::path sheet_flag = dir_ / "sheet-flag.off";
  ASSERT_EQ(run(base + q(sheet_flag) + " --ignore-normals --quadric-normals").exit_code, 0);
  EXPECT_EQ(eftest::slurp(sheet), eftest::slurp(sheet_flag));
  const eftest::CommandResult bad = run(base + q(dir_ / "x.off") + " --preset thin-shell");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("thin_shell"), std::string::npos) << bad.err;
}

TEST_F(GcsCli, SameSeedSameFileAndNoTwistIsAccepted) {
  const fs::path a = dir_ / "a.off", b = dir_ / "b.off", c = dir_ / "c.off";
  ASSERT_EQ(run(q(vault()) + " -o " + q(a) + " --vertices 150 --seed 7 --quiet").exit_code, 0);
  const eftest::CommandResult rb = run(q(vault()) + " -o " + q(b) + " --vertices 150 --seed 7");
  ASSERT_EQ(rb.exit_code, 0);
  EXPECT_NE(rb.out.find("twist-repair"), std::string::npos) << rb.out;  // on by default, reported
  ASSERT_EQ(run(q(vault()) + " -o " + q(c) + " --vertices 150 --seed 8").exit_code, 0);
  EXPECT_EQ(eftest::slurp(a), eftest::slurp(b));
  EXPECT_NE(eftest::slurp(a), eftest::slurp(c));
  const fs::path d = dir_ / "d.off", e = dir_ / "e.off";
  ASSERT_EQ(run(q(vault()) + " -o " + q(d) + " --vertices 150 --seed 7 --no-twist").exit_code, 0);
  ASSERT_EQ(run(q(vault()) + " -o " + q(e) + " --vertices 150 --seed 7 --no-twist").exit_code, 0);
  EXPECT_EQ(eftest::slurp(d), eftest::slurp(e));
}

TEST_F(GcsCli, IgnoreNormalsReconstructsFromThePointsAlone) {
  // The bundled vault's points written without their normals give the same file as the vault
  // read with --ignore-normals, and another file than the vault with its normals.
  edgefront::PointCloud bare = edgefront::read_points(vault());
  ASSERT_TRUE(bare.has_normals());
  bare.normals.clear();
  const fs::path points = dir_ / "points.xyz";
  edgefront::write_points(bare, points);
  const fs::path a = dir_ / "a.off", b = dir_ / "b.off", c = dir_ / "c.off";
  ASSERT_EQ(run(q(points) + " -o " + q(a) + " --vertices 200").exit_code, 0);
  ASSERT_EQ(run(q(vault()) + " -o " + q(b) + " --vertices 200 --ignore-normals").exit_code, 0);
  ASSERT_EQ(run(q(vault()) + " -o " + q(c) + " --vertices 200").exit_code, 0);
  EXPECT_EQ(eftest::slurp(a), eftest::slurp(b));
  EXPECT_NE(eftest::slurp(b), eftest::slurp(c));
}

TEST_F(GcsCli, NoOrientWinnersSwitchesTheOrientedWinnersOff) {
  // The vault cloud has normals, so the oriented winner search is on by default from 150 vertices:
  // switching it off changes the mesh, and the result is still deterministic.
  const fs::path a = dir_ / "a.off", b = dir_ / "b.off", c = dir_ / "c.off";
  const std::string common = " --vertices 300 --seed 7 --no-twist";
  ASSERT_EQ(run(q(vault()) + " -o " + q(a) + common).exit_code, 0);
  const eftest::CommandResult rb = run(q(vault()) + " -o " + q(b) + common + " --no-orient-winners");
  ASSERT_EQ(rb.exit_code, 0) << rb.err;
  ASSERT_EQ(run(q(vault()) + " -o " + q(c) + common + " --no-orient-winners").exit_code, 0);
  EXPECT_NE(eftest::slurp(a), eftest::slurp(b));
  EXPECT_EQ(eftest::slurp(b), eftest::slurp(c));
  const edgefront::MeshStats s = edgefront::compute_stats(edgefront::load_mesh(b));
  EXPECT_EQ(s.nonmanifold_vertices, 0u);
  EXPECT_GT(s.faces, 400u);
}

TEST_F(GcsCli, RejoinBordersIsAcceptedAndAFlagWithoutAValue) {
  // The twist operation's border re-join (off by default) on a thin shell, where the repair cuts:
  // a valid manifold mesh, the twist report, the same file twice.
  const fs::path shell = fs::path(EDGEFRONT_DATA_DIR) / "vault-shell.xyz";
  const fs::path a = dir_ / "a.off", b = dir_ / "b.off";
  const std::string common = " --vertices 400 --seed 3 --rejoin-borders --quiet";
  const eftest::CommandResult ra = run(q(shell) + " -o " + q(a) + common);
  ASSERT_EQ(ra.exit_code, 0) << ra.err;
  EXPECT_NE(ra.out.find("twist-repair"), std::string::npos) << ra.out;
  ASSERT_EQ(run(q(shell) + " -o " + q(b) + common).exit_code, 0);
  EXPECT_EQ(eftest::slurp(a), eftest::slurp(b));
  const edgefront::MeshStats s = edgefront::compute_stats(edgefront::load_mesh(a));
  EXPECT_EQ(s.nonmanifold_vertices, 0u);
  EXPECT_GT(s.faces, 100u);
  // A value that is not a boolean: a usage error, no file.
  const eftest::CommandResult bad = run(q(shell) + " -o " + q(dir_ / "c.off") + " --vertices 100 --rejoin-borders=maybe");
  EXPECT_EQ(bad.exit_code, 2) << bad.err;
  // The border growth's rows: 0 ... 8, else a usage error naming the option, no file.
  for (const char* rows : {"9", "-1", "two"}) {
    const eftest::CommandResult g = run(q(shell) + " -o " + q(dir_ / "g.off") + " --vertices 100 --grow-borders " + rows);
    EXPECT_EQ(g.exit_code, 2) << rows << ": " << g.err;
    EXPECT_NE(g.err.find("--grow-borders"), std::string::npos) << g.err;
    EXPECT_FALSE(fs::exists(dir_ / "g.off"));
  }
  EXPECT_FALSE(fs::exists(dir_ / "c.off"));
  EXPECT_NE(run("--help").out.find("--rejoin-borders"), std::string::npos);
}

TEST_F(GcsCli, PictureAndSnapshots) {
  const fs::path snaps = dir_ / "snaps";
  fs::create_directories(snaps);
  const eftest::CommandResult r = run(q(vault()) + " -o " + q(dir_ / "v.ply") + " --vertices 200 --quiet --png " +
                                      q(dir_ / "v.png") + " --size 160x120 --snapshots " + q(snaps) +
                                      " --snapshot-every 50");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const edgefront::render::Image image = edgefront::render::read_png(dir_ / "v.png");
  EXPECT_EQ(image.width, 160);
  EXPECT_EQ(image.height, 120);
  EXPECT_NE(image.at(80, 60), (edgefront::render::Rgb{255, 255, 255}));  // the vault covers the centre
  // Growth from the start box to 200 vertices in steps of 50: at least 3 snapshots, all readable.
  int n = 0;
  for (const auto& entry : fs::directory_iterator(snaps)) {
    EXPECT_EQ(edgefront::render::read_png(entry.path()).width, 160) << entry.path();
    ++n;
  }
  EXPECT_GE(n, 3);
  EXPECT_NE(r.out.find(std::to_string(n) + " snapshot(s)"), std::string::npos) << r.out;
  // A snapshot directory that does not exist: a usage error (at parse time) naming it.
  const eftest::CommandResult bad = run(q(vault()) + " -o " + q(dir_ / "w.ply") + " --vertices 100 --snapshots " +
                                        q(dir_ / "absent"));
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("absent"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(dir_ / "w.ply"));
}

TEST_F(GcsCli, ErrorsAndUsage) {
  const fs::path out = dir_ / "x.ply";
  eftest::CommandResult r = run(q(dir_ / "missing.xyz") + " -o " + q(out));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err.rfind("gcs-reconstruct: error: ", 0), 0u) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(fs::exists(out));
  // Three points: a clear error, no file.
  const fs::path few = dir_ / "few.xyz";
  std::ofstream(few) << "0 0 0\n1 0 0\n0 1 0\n";
  r = run(q(few) + " -o " + q(out));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("at least 4 points"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
  // Target above the point count (the vault has 3000 points).
  r = run(q(vault()) + " -o " + q(out) + " --vertices 3001");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("more than the number of points (3000)"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
  EXPECT_EQ(run(q(vault()) + " -o " + q(out) + " --vertices 3").exit_code, 2);
  EXPECT_EQ(run(q(vault())).exit_code, 2);                                       // no -o
  EXPECT_EQ(run(q(vault()) + " -o " + q(dir_ / "x.abc") + " --vertices 50").exit_code, 2);  // bad extension: parse time
  r = run("--help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("--no-twist"), std::string::npos);
  EXPECT_NE(r.out.find("twist repair"), std::string::npos);
  EXPECT_NE(r.out.find("--no-orient-winners"), std::string::npos);
}

}  // namespace

namespace {

TEST_F(GcsCli, FitOptionsAreCheckedAndNoFitKeepsTheConnectivity) {
  const fs::path a = dir_ / "a.off", b = dir_ / "b.off";
  const std::string common = " --vertices 150 --seed 2 --no-twist --quiet";
  ASSERT_EQ(run(q(vault()) + " -o " + q(a) + common).exit_code, 0);
  const eftest::CommandResult rb = run(q(vault()) + " -o " + q(b) + common + " --no-fit");
  ASSERT_EQ(rb.exit_code, 0) << rb.err;
  const edgefront::Mesh ma = edgefront::load_mesh(a), mb = edgefront::load_mesh(b);
  ASSERT_EQ(ma.n_vertices(), mb.n_vertices());
  ASSERT_EQ(ma.n_faces(), mb.n_faces());
  EXPECT_NE(eftest::slurp(a), eftest::slurp(b));  // the fit moved vertices
  for (const char* bad : {" --fit-rounds 0", " --fit-rounds 21", " --fit-smoothness -1", " --fit-rounds x"}) {
    const fs::path c = dir_ / "c.off";
    const eftest::CommandResult r = run(q(vault()) + " -o " + q(c) + " --vertices 100" + bad);
    EXPECT_EQ(r.exit_code, 2) << bad << ": " << r.err;
    EXPECT_NE(r.err.find("--fit-"), std::string::npos) << bad << ": " << r.err;
    EXPECT_FALSE(fs::exists(c)) << bad;
  }
}

// --no-delaunay-flips (with --no-fit, so that the positions are comparable) gives the same vertices
// and a different triangulation whose smallest angle is not larger than with the flips.
TEST_F(GcsCli, NoDelaunayFlipsIsAcceptedAndKeepsTheVertexCount) {
  const fs::path a = dir_ / "a.off", b = dir_ / "b.off";
  const std::string common = " --vertices 150 --seed 2 --no-twist --no-fit --quiet";
  ASSERT_EQ(run(q(vault()) + " -o " + q(a) + common).exit_code, 0);
  const eftest::CommandResult rb = run(q(vault()) + " -o " + q(b) + common + " --no-delaunay-flips");
  ASSERT_EQ(rb.exit_code, 0) << rb.err;
  const edgefront::Mesh ma = edgefront::load_mesh(a), mb = edgefront::load_mesh(b);
  ASSERT_EQ(ma.n_vertices(), mb.n_vertices());
  ASSERT_EQ(ma.n_faces(), mb.n_faces());
  for (auto v : ma.vertices()) EXPECT_EQ(ma.point(v), mb.point(v)) << v.idx();
  EXPECT_NE(eftest::slurp(a), eftest::slurp(b));  // some edges were flipped
  EXPECT_GE(gcs::mesh_validity(ma).min_angle_deg, gcs::mesh_validity(mb).min_angle_deg);
}

TEST_F(GcsCli, SkipUnfacedSamplesIsAcceptedAndChangesTheShell) {
  // The bundled thin shell (input normals): skipping samples that no vertex nearby faces changes
  // which vertices move; the result is a valid manifold mesh either way.
  const std::string shell = (fs::path(EDGEFRONT_DATA_DIR) / "vault-shell.xyz").string();
  const fs::path a = dir_ / "a.off", b = dir_ / "b.off";
  const std::string common = " --vertices 400 --seed 1 --quiet";
  ASSERT_EQ(run(q(shell) + " -o " + q(a) + common).exit_code, 0);
  const eftest::CommandResult rb = run(q(shell) + " -o " + q(b) + common + " --skip-unfaced-samples");
  ASSERT_EQ(rb.exit_code, 0) << rb.err;
  EXPECT_NE(eftest::slurp(a), eftest::slurp(b));
  const edgefront::MeshStats s = edgefront::compute_stats(edgefront::load_mesh(b));
  EXPECT_EQ(s.nonmanifold_vertices, 0u);
  EXPECT_GT(s.faces, 400u);
}

TEST_F(GcsCli, KeepCrossingsLeavesTheShellsSelfIntersectionsAndTheDefaultResolvesThem) {
  // The bundled thin shell at 300 vertices (seed 3, no twist): the loop's mesh has crossing faces.
  const std::string shell = (fs::path(EDGEFRONT_DATA_DIR) / "vault-shell.xyz").string();
  const fs::path a = dir_ / "a.off", b = dir_ / "b.off";
  const std::string common = " --vertices 300 --seed 3 --no-twist --quiet";
  const eftest::CommandResult ra = run(q(shell) + " -o " + q(a) + common);
  ASSERT_EQ(ra.exit_code, 0) << ra.err;
  const eftest::CommandResult rb = run(q(shell) + " -o " + q(b) + common + " --keep-crossings");
  ASSERT_EQ(rb.exit_code, 0) << rb.err;
  EXPECT_NE(ra.out.find("self-intersecting face pair(s) resolved"), std::string::npos) << ra.out;
  EXPECT_EQ(rb.out.find("self-intersecting"), std::string::npos) << rb.out;
  EXPECT_EQ(gcs::count_self_intersections(edgefront::load_mesh(a)), 0u);
  EXPECT_GT(gcs::count_self_intersections(edgefront::load_mesh(b)), 0u);
}

TEST_F(GcsCli, KeepFalseBordersLeavesALoopTheDefaultCloses) {
  // The bundled thin closed shell at 300 vertices (seed 1): one of its border loops has samples
  // beyond it that no face covers; the default closes it by a patch, --keep-false-borders does not.
  const std::string shell = (fs::path(EDGEFRONT_DATA_DIR) / "vault-shell.xyz").string();
  const fs::path a = dir_ / "a.off", b = dir_ / "b.off";
  const std::string common = " --vertices 300 --seed 1 --quiet";
  const eftest::CommandResult ra = run(q(shell) + " -o " + q(a) + common);
  ASSERT_EQ(ra.exit_code, 0) << ra.err;
  const eftest::CommandResult rb = run(q(shell) + " -o " + q(b) + common + " --keep-false-borders");
  ASSERT_EQ(rb.exit_code, 0) << rb.err;
  EXPECT_NE(ra.out.find("1 of 3 false border(s) closed"), std::string::npos) << ra.out;
  EXPECT_EQ(rb.out.find("false border"), std::string::npos) << rb.out;
  const edgefront::MeshStats sa = edgefront::compute_stats(edgefront::load_mesh(a));
  const edgefront::MeshStats sb = edgefront::compute_stats(edgefront::load_mesh(b));
  EXPECT_EQ(sa.border_loops + 1, sb.border_loops);
  EXPECT_EQ(sa.nonmanifold_vertices, 0u);
  EXPECT_EQ(sa.components, sb.components);
}

}  // namespace
