// Tests of the side-aware reference judgement, the incremental face grid and local detection,
// re-growing cut-out regions, and the same-orientation layer count (twist/, issue 7).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <limits>
#include <vector>

#include "edgefront/error.h"
#include "edgefront/mesh_stats.h"
#include "shapes/shapes.h"
#include "twist/detect.h"
#include "twist/reference_normals.h"
#include "twist/repair.h"
#include "shapes/twisted_shapes.h"

namespace {

using edgefront::FaceHandle;
using edgefront::InvalidInput;
using edgefront::Mesh;
using edgefront::Vec3;

/// A wall of thickness t: the plane z = 0 with normals up and z = -t with normals down, sampled
/// on a square grid of spacing h.
twist::ReferenceNormals thin_wall(double t, double h) {
  edgefront::PointCloud cloud;
  for (int i = -20; i <= 20; ++i) {
    for (int j = -20; j <= 20; ++j) {
      cloud.points.emplace_back(i * h, j * h, 0.0);
      cloud.normals.emplace_back(0, 0, 1);
      cloud.points.emplace_back(i * h + h / 2, j * h + h / 2, -t);
      cloud.normals.emplace_back(0, 0, -1);
    }
  }
  return twist::ReferenceNormals(cloud);
}

TEST(TwistJudge, TellsTheOwnWallAndAbstainsBetweenTheWalls) {
  const double t = 0.02, h = 0.05;  // the wall is thinner than the sample spacing
  const auto ref = thin_wall(t, h);
  // On the top wall, slightly off a sample: the nearest point can be on the bottom wall ...
  const Vec3 on_top(0.45 * h, 0.45 * h, -0.002);
  EXPECT_EQ(ref.nearest_normal(on_top)[2], -1.0) << "the plainly nearest point is on the other wall";
  // ... but the judgement by sides takes the face's own wall.
  EXPECT_EQ(ref.judge(on_top, Vec3(0, 0, 1)), 1);
  EXPECT_EQ(ref.judge(on_top, Vec3(0, 0, -1)), -1);
  EXPECT_EQ(ref.judge(Vec3(0.25 * h, 0.25 * h, -t), Vec3(0, 0, -1)), 1);
  // Half way between the walls neither orientation is decidable.
  EXPECT_EQ(ref.judge(Vec3(0.25 * h, 0.25 * h, -t / 2), Vec3(0, 0, 1)), 0);
  EXPECT_EQ(ref.judge(Vec3(0.25 * h, 0.25 * h, -t / 2), Vec3(0, 0, -1)), 0);
  EXPECT_EQ(ref.judge(on_top, Vec3(0, 0, 0)), 0);
  EXPECT_THROW(ref.judge(on_top, Vec3(0, 0, 1), 0), InvalidInput);
  EXPECT_THROW(ref.judge(on_top, Vec3(0, 0, 1), 16, 0.5), InvalidInput);
  EXPECT_THROW(ref.judge(on_top, Vec3(0, 0, 1), 16, 4.0, std::nan("")), InvalidInput);
}

std::vector<FaceHandle> brute_force(const Mesh& mesh, const Vec3& p, double r) {
  std::vector<FaceHandle> out;
  for (FaceHandle f : mesh.faces()) {
    if ((mesh.calc_face_centroid(f) - p).norm() < r) out.push_back(f);
  }
  return out;
}

TEST(TwistFaceGrid, AnswersLikeABruteForceSearchAndFollowsUpdates) {
  Mesh mesh = edgefront::shapes::icosphere(3);
  twist::FaceGrid grid;
  EXPECT_THROW(grid.rebuild(mesh, 0.0), InvalidInput);
  grid.rebuild(mesh, 0.2);
  EXPECT_EQ(grid.size(), mesh.n_faces());
  std::vector<FaceHandle> got;
  for (const Vec3& p : {Vec3(1, 0, 0), Vec3(0, 0.7, 0.7), Vec3(0, 0, 0)}) {
    for (double r : {0.05, 0.3, 1.1}) {
      grid.query(mesh, p, r, got);
      EXPECT_EQ(got, brute_force(mesh, p, r));
    }
  }
  // Move a vertex far away; after updating its faces the grid finds them at the new place.
  const edgefront::VertexHandle v(0);
  std::vector<FaceHandle> ring(mesh.vf_range(v).begin(), mesh.vf_range(v).end());
  mesh.set_point(v, Vec3(5, 5, 5));
  grid.update(mesh, ring);
  grid.query(mesh, Vec3(5, 5, 5) * (1.0 / 3.0), 2.0, got);
  EXPECT_EQ(got, brute_force(mesh, Vec3(5, 5, 5) * (1.0 / 3.0), 2.0));
  // Deleted faces are not returned; new faces come in with update_new.
  mesh.delete_face(ring[0], false);
  grid.query(mesh, mesh.point(edgefront::VertexHandle(1)), 0.5, got);
  EXPECT_EQ(std::count(got.begin(), got.end(), ring[0]), 0);
  const auto a = mesh.add_vertex(Vec3(9, 9, 9)), b = mesh.add_vertex(Vec3(9.1, 9, 9)), c = mesh.add_vertex(Vec3(9, 9.1, 9));
  const FaceHandle nf = mesh.add_face(a, b, c);
  grid.update_new(mesh);
  grid.query(mesh, Vec3(9, 9, 9), 0.2, got);
  EXPECT_EQ(got, std::vector<FaceHandle>{nf});
}

TEST(TwistFaceGrid, HugeQueriesScanTheGridAndBadQueriesAreRefused) {
  const Mesh mesh = edgefront::shapes::icosphere(2);
  twist::FaceGrid grid;
  grid.rebuild(mesh, 0.01);  // small cells: a radius of 1e9 would span ~1e33 of them
  std::vector<FaceHandle> got;
  grid.query(mesh, Vec3(0.1, 0, 0), 1e9, got);
  EXPECT_EQ(got, brute_force(mesh, Vec3(0.1, 0, 0), 1e9));
  EXPECT_EQ(got.size(), mesh.n_faces());
  grid.query(mesh, Vec3(1e300, 0, 0), 1.0, got);  // beyond the integer range of cells
  EXPECT_TRUE(got.empty());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(grid.query(mesh, Vec3(0, 0, 0), nan, got), InvalidInput);
  EXPECT_THROW(grid.query(mesh, Vec3(0, 0, 0), -1.0, got), InvalidInput);
  EXPECT_THROW(grid.query(mesh, Vec3(nan, 0, 0), 1.0, got), InvalidInput);
  EXPECT_THROW(grid.query(mesh, Vec3(0, 0, 0), std::numeric_limits<double>::infinity(), got), InvalidInput);
  twist::DetectOptions o;
  o.experimental.reference_side_weight = 0.5;  // neither off (0) nor in [1, 100]
  EXPECT_THROW(twist::detect(mesh, o), InvalidInput);
}

TEST(TwistLocalDetection, FindsTheSameRegionWithTheFaceGrid) {
  const twist::TwistedShape s = twist::flipped_disk_plate();
  const auto full = twist::detect(s.mesh);
  ASSERT_EQ(full.size(), 1u);
  double mean_edge = 0;
  for (auto e : s.mesh.edges()) mean_edge += s.mesh.calc_edge_length(e);
  mean_edge /= static_cast<double>(s.mesh.n_edges());
  twist::FaceGrid grid;
  grid.rebuild(s.mesh, 2 * mean_edge);
  twist::DetectOptions o;
  o.incremental.restrict_to = std::vector<FaceHandle>{full[0].faces.front()};
  o.incremental.audit_faces = 4;
  const auto with_tree = twist::detect_regions(s.mesh, o);
  o.incremental.face_grid = &grid;
  o.mean_edge_length = mean_edge;
  const auto with_grid = twist::detect_regions(s.mesh, o);
  ASSERT_EQ(with_grid.regions.size(), 1u);
  ASSERT_EQ(with_tree.regions.size(), 1u);
  EXPECT_EQ(with_grid.regions[0].faces, with_tree.regions[0].faces);
  EXPECT_EQ(with_grid.regions[0].faces, full[0].faces);
  EXPECT_LT(with_grid.stats.faces_tested, s.mesh.n_faces() / 2) << "local: not every face is tested";
  o.mean_edge_length = -1;
  EXPECT_THROW(twist::detect_regions(s.mesh, o), InvalidInput);
}

TEST(TwistRegrow, ACutOutRegionIsReplacedByAConsistentPatchNotAHole) {
  for (bool regrow : {false, true}) {
    twist::TwistedShape s = twist::flipped_disk_plate();
    twist::RepairOptions o;
    o.experimental.regrow_cut_outs = regrow;
    o.garbage_collect = false;
    twist::TwistRepairer repairer(o, 1);  // a place repaired a second time is cut out
    {
      twist::TwistedShape first = twist::flipped_disk_plate();  // the first repair at this place
      std::vector<FaceHandle> all(first.mesh.faces().begin(), first.mesh.faces().end());
      ASSERT_EQ(repairer.repair_changed(first.mesh, all).regions_cut_out, 0u);
    }
    std::vector<FaceHandle> all(s.mesh.faces().begin(), s.mesh.faces().end());
    const twist::RepairReport r = repairer.repair_changed(s.mesh, all);
    ASSERT_EQ(r.regions_cut_out, 1u) << regrow;
    const edgefront::MeshStats st = edgefront::compute_stats(s.mesh);
    EXPECT_EQ(st.nonmanifold_vertices, 0u) << regrow;
    const edgefront::ComponentLabels labels = edgefront::connected_components(s.mesh);
    std::vector<size_t> faces_of(labels.count, 0);
    for (FaceHandle f : s.mesh.faces()) ++faces_of[static_cast<size_t>(labels.vertex_component[static_cast<size_t>((*s.mesh.cfv_begin(f)).idx())])];
    for (size_t c = 0; c < labels.count; ++c) {
      if (faces_of[c] > 0) {
        EXPECT_GE(faces_of[c], o.cuts.min_component_faces) << regrow << ": no tiny component left";
      }
    }
    if (regrow) {
      EXPECT_EQ(st.border_loops, 0u) << "the plate stays closed";
      EXPECT_GT(twist::truth_consistency(s.mesh, s), 0.99) << "the re-grown patch faces the right way";
      // The patch is wound like its surroundings: the surface is still a closed, consistently
      // oriented shell with positive volume.
      double volume = 0;
      for (FaceHandle f : s.mesh.faces()) {
        auto it = s.mesh.cfv_begin(f);
        const Vec3 a = s.mesh.point(*it), b = s.mesh.point(*++it), c = s.mesh.point(*++it);
        volume += OpenMesh::dot(a, OpenMesh::cross(b, c)) / 6.0;
      }
      EXPECT_GT(volume, 0.0);
    } else {
      EXPECT_GE(st.border_loops, 1u) << "without re-growing the cut-out leaves a hole";
    }
  }
}

TEST(TwistSameOrientationLayers, CountsTwistedLayersOnlyOnTwistedMeshes) {
  for (twist::LayerRule rule : {twist::LayerRule::Facing, twist::LayerRule::Stacked}) {
    EXPECT_GT(twist::count_same_orientation_layers(twist::twisted_tube().mesh, {}, rule), 0u);
    EXPECT_EQ(twist::count_same_orientation_layers(edgefront::shapes::vault_shell(24, 1.0, 0.1), {}, rule), 0u);
    EXPECT_EQ(twist::count_same_orientation_layers(edgefront::shapes::icosphere(2), {}, rule), 0u);
  }
  EXPECT_THROW(twist::count_same_orientation_layers(edgefront::shapes::icosphere(1), {}, static_cast<twist::LayerRule>(7)),
               InvalidInput);
}

/// A copy of `mesh` in which the faces `flip` selects are wound the other way; the two groups
/// get their own copies of the vertices they share, so each stays consistently oriented (the
/// flipped group becomes its own component(s), geometrically in place).
Mesh with_faces_flipped(const Mesh& mesh, const std::function<bool(FaceHandle)>& flip) {
  Mesh out;
  std::map<std::pair<int, bool>, edgefront::VertexHandle> copy;
  for (FaceHandle f : mesh.faces()) {
    const bool flipped = flip(f);
    std::vector<edgefront::VertexHandle> vs;
    for (edgefront::VertexHandle v : mesh.fv_range(f)) {
      auto [it, added] = copy.emplace(std::make_pair(v.idx(), flipped), edgefront::VertexHandle());
      if (added) it->second = out.add_vertex(mesh.point(v));
      vs.push_back(it->second);
    }
    if (flipped) std::reverse(vs.begin(), vs.end());
    out.add_face(vs);
  }
  return out;
}

// The stacked rule (two layers covering each other front to back) against the facing rule on
// the three twists of the issue: it still counts them. (What it leaves out of the facing rule's
// count lies along the twist line and the fold band, where the layers cross at an angle.)
TEST(TwistSameOrientationLayers, StackedRuleCountsTheTwistedTube) {
  const twist::TwistedShape tube = twist::twisted_tube();
  const size_t facing = twist::count_same_orientation_layers(tube.mesh);
  const size_t stacked = twist::count_same_orientation_layers(tube.mesh, {}, twist::LayerRule::Stacked);
  EXPECT_GT(stacked, 0u);
  EXPECT_LE(stacked, facing);
  EXPECT_GE(static_cast<double>(stacked), 0.7 * static_cast<double>(facing));
}

TEST(TwistSameOrientationLayers, StackedRuleCountsTheFlippedDisk) {
  // The disk turned over in the top of the plate faces down, like the bottom 0.1 under it.
  twist::FlippedDiskOptions small;
  small.rings = 8;
  small.around = 24;
  const twist::TwistedShape disk = twist::flipped_disk_plate(small);
  const size_t facing = twist::count_same_orientation_layers(disk.mesh);
  const size_t stacked = twist::count_same_orientation_layers(disk.mesh, {}, twist::LayerRule::Stacked);
  EXPECT_GE(stacked, disk.twisted_faces) << "the turned disk and the bottom faces under it";
  EXPECT_LE(stacked, facing);
  EXPECT_GE(static_cast<double>(stacked), 0.7 * static_cast<double>(facing));
}

TEST(TwistSameOrientationLayers, StackedRuleCountsAShellWithOneWallFlipped) {
  // A closed vault shell (t/R 0.1) whose intrados is turned over: it then faces away from the
  // axis like the extrados 0.1 above it, two walls stacked with the same orientation. Nearly
  // every face of both walls has a stacked partner.
  const Mesh shell = edgefront::shapes::vault_shell(16, 1.0, 0.1);
  auto wall = [&](FaceHandle f, bool inner) {
    const Vec3 c = shell.calc_face_centroid(f);
    return c[2] > 0.05 && (std::hypot(c[0], c[2]) < 1.05) == inner && c[1] > 1e-9 && c[1] < 2.0 - 1e-9;
  };
  size_t intrados = 0, extrados = 0;
  for (FaceHandle f : shell.faces()) {
    intrados += wall(f, true);
    extrados += wall(f, false);
  }
  ASSERT_GT(intrados, 100u);
  const Mesh flipped = with_faces_flipped(shell, [&](FaceHandle f) { return wall(f, true); });
  const size_t stacked = twist::count_same_orientation_layers(flipped, {}, twist::LayerRule::Stacked);
  EXPECT_GE(static_cast<double>(stacked), 0.9 * static_cast<double>(intrados + extrados));
  EXPECT_LE(stacked, twist::count_same_orientation_layers(flipped));
}

TEST(TwistSameOrientationLayers, StackedRuleIgnoresFacesSideBySideAcrossAGap) {
  // A roof (two planes rising 25 degrees to a ridge along y), both halves facing up, slit open
  // along the ridge (0.04 wide): the halves are far apart along the surface (not connected), and
  // near the slit each face's normal tilts enough that the faces across the slit lie "behind" it
  // for the facing rule. They lie side by side on one surface, not stacked: the stacked rule
  // counts none (the case of one wall of a GCS result across a hole, bench/results/twist-vaults.md).
  Mesh roof;
  const int n = 10;
  const double cell = 0.1, gap = 0.02, slope = std::tan(25.0 * std::acos(-1.0) / 180.0);
  for (int side : {-1, 1}) {
    std::vector<std::vector<edgefront::VertexHandle>> v(n + 1, std::vector<edgefront::VertexHandle>(n + 1));
    for (int i = 0; i <= n; ++i) {
      for (int j = 0; j <= n; ++j) {
        const double x = side * (gap + i * cell);
        v[i][j] = roof.add_vertex(Vec3(x, j * cell, 1.0 - slope * std::abs(x)));
      }
    }
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) {
        // Counter-clockwise seen from above on both sides: the normals point up.
        if (side > 0) {
          roof.add_face(v[i][j], v[i + 1][j], v[i + 1][j + 1]);
          roof.add_face(v[i][j], v[i + 1][j + 1], v[i][j + 1]);
        } else {
          roof.add_face(v[i][j], v[i][j + 1], v[i + 1][j + 1]);
          roof.add_face(v[i][j], v[i + 1][j + 1], v[i + 1][j]);
        }
      }
    }
  }
  for (FaceHandle f : roof.faces()) ASSERT_GT(roof.calc_face_normal(f)[2], 0.8);
  EXPECT_GT(twist::count_same_orientation_layers(roof), 0u) << "the facing rule counts the faces along the slit";
  EXPECT_EQ(twist::count_same_orientation_layers(roof, {}, twist::LayerRule::Stacked), 0u);
  // Turn the right half by 180 degrees about the vertical line x = 0, y = 0.5 and lower it by
  // 0.1: it lies under the left half with the same orientation (a real stacked layer), and the
  // stacked rule counts it.
  Mesh stacked = roof;
  for (edgefront::VertexHandle v : stacked.vertices()) {
    const Vec3 p = stacked.point(v);
    if (p[0] > 0) stacked.set_point(v, Vec3(-p[0], 1.0 - p[1], p[2] - 0.1));
  }
  for (FaceHandle f : stacked.faces()) ASSERT_GT(stacked.calc_face_normal(f)[2], 0.8) << "the rotation keeps both halves up";
  EXPECT_GT(twist::count_same_orientation_layers(stacked, {}, twist::LayerRule::Stacked), 100u);
}

}  // namespace

namespace {

TEST(TwistScattered, ScatteredEvidenceIsLeftAloneInsteadOfShreddingTheSurface) {
  // A correct sphere whose reference disagrees on every third face: evidence everywhere, no
  // compact twisted region. Cutting along the border of what it grows into would shred it.
  const Mesh sphere = edgefront::shapes::icosphere(3);
  edgefront::PointCloud cloud;
  for (FaceHandle f : sphere.faces()) {
    const Vec3 c = sphere.calc_face_centroid(f);
    cloud.points.push_back(c);
    cloud.normals.push_back(f.idx() % 3 == 0 ? -c.normalized() : c.normalized());
  }
  const twist::ReferenceNormals ref(cloud);
  twist::RepairOptions o;
  o.detect.reference = &ref;
  o.label_by_reference = false;  // the detector's regions: its border-ratio guard is tested here
  // Reference points with opposed normals side by side read as a wall of thickness 0: by default
  // (VoteOptions::thin_wall) such rejections are no evidence, and nothing is found at all.
  Mesh untouched = sphere;
  EXPECT_EQ(twist::repair(untouched, o).regions_found, 0u);
  o.detect.vote.thin_wall = 0;  // the border-ratio guard is what is tested below
  Mesh kept = sphere;
  const twist::RepairReport r = twist::repair(kept, o);
  EXPECT_GE(r.regions_scattered, 1u);
  EXPECT_EQ(r.vertices_duplicated, 0u);
  EXPECT_EQ(edgefront::compute_stats(kept).components, 1u) << "not shredded";
  o.cuts.max_border_ratio = 0;  // no limit: the old behaviour cuts it apart
  Mesh cut = sphere;
  const twist::RepairReport r0 = twist::repair(cut, o);
  EXPECT_EQ(r0.regions_scattered, 0u);
  EXPECT_GT(r0.vertices_duplicated, 0u);
  // Shredded: the pieces too small to stand (min_cut_piece_share) are removed, the rest is in pieces.
  EXPECT_TRUE(edgefront::compute_stats(cut).components > 1u || cut.n_faces() < sphere.n_faces());
  EXPECT_GT(r0.faces_removed, 0u);
  o.cuts.max_border_ratio = -1;
  EXPECT_THROW(twist::repair(cut, o), InvalidInput);
}

}  // namespace

namespace {

double mean_edge_of(const Mesh& mesh) {
  double sum = 0;
  for (auto e : mesh.edges()) sum += mesh.calc_edge_length(e);
  return sum / static_cast<double>(mesh.n_edges());
}

TEST(TwistRetest, StableFacesAreNotTestedAgainButMovedOnesAndTwistsAre) {
  // A correct sphere handed over as "all changed" in every call (as GCS smoothing does): after
  // the first call only faces that turned or moved across their plane are tested again.
  Mesh mesh = edgefront::shapes::icosphere(3);
  const double edge = mean_edge_of(mesh);
  twist::RepairOptions o;
  o.detect.incremental.audit_faces = 0;
  o.garbage_collect = false;
  twist::TwistRepairer repairer(o);
  std::vector<FaceHandle> all(mesh.faces().begin(), mesh.faces().end());
  const twist::RepairReport first = repairer.repair_changed(mesh, all, edge);
  EXPECT_EQ(first.repairs, 0u);
  EXPECT_GE(first.detect_stats.faces_tested, mesh.n_faces());
  // Tangential jitter (along the surface, a tenth of an edge): nothing is tested.
  const edgefront::VertexHandle v0(0);
  const Vec3 p0 = mesh.point(v0);
  Vec3 tangent = OpenMesh::cross(p0.normalized(), Vec3(0, 0, 1));
  if (tangent.norm() < 0.1) tangent = OpenMesh::cross(p0.normalized(), Vec3(1, 0, 0));
  mesh.set_point(v0, p0 + tangent.normalized() * (0.1 * edge));
  EXPECT_EQ(repairer.repair_changed(mesh, all, edge).detect_stats.faces_tested, 0u);
  // Pushed out across the faces' planes by half an edge: the vertex's faces (and no more than
  // their neighbourhood) are tested again.
  mesh.set_point(v0, p0 * (1 + 0.5 * edge));
  const size_t ring = static_cast<size_t>(std::distance(mesh.vf_range(v0).begin(), mesh.vf_range(v0).end()));
  const size_t again = repairer.repair_changed(mesh, all, edge).detect_stats.faces_tested;
  EXPECT_GE(again, ring);
  EXPECT_LT(again, mesh.n_faces() / 4);
  // Every changed face tested every time when both thresholds are 0.
  o.experimental.retest_turn_degrees = o.experimental.retest_move = 0;
  twist::TwistRepairer all_again(o);
  all_again.repair_changed(mesh, all, edge);
  EXPECT_GE(all_again.repair_changed(mesh, all, edge).detect_stats.faces_tested, mesh.n_faces());
  o.experimental.retest_move = -1;
  EXPECT_THROW(twist::TwistRepairer(o).repair_changed(mesh, all, edge), InvalidInput);
  o.experimental.retest_move = 0;
  o.experimental.retest_turn_degrees = 181;
  EXPECT_THROW(twist::TwistRepairer(o).repair_changed(mesh, all, edge), InvalidInput);
}

TEST(TwistRetest, AfterARepairOnlyTheNewFacesAreTestedAgain) {
  // A plate with a disk turned inside out: the first call repairs it; a second call that calls
  // every face changed (nothing moved) tests only the faces the repair created.
  const twist::TwistedShape twisted = twist::flipped_disk_plate();
  Mesh mesh = twisted.mesh;
  const double edge = mean_edge_of(mesh);
  const twist::ReferenceNormals ref(twist::truth_points(twisted));
  twist::RepairOptions o;
  o.detect.reference = &ref;
  o.garbage_collect = false;
  twist::TwistRepairer repairer(o);
  std::vector<FaceHandle> all(mesh.faces().begin(), mesh.faces().end());
  const twist::RepairReport r = repairer.repair_changed(mesh, all, edge);
  EXPECT_EQ(r.repairs, 1u);
  // A second call with every face "changed" but nothing moved: only the faces the repair made
  // (the flipped disk, now its own component, which the global orientation judges) are tested
  // again, and nothing more is cut.
  std::vector<FaceHandle> now(mesh.faces().begin(), mesh.faces().end());
  const twist::RepairReport again = repairer.repair_changed(mesh, now, edge);
  EXPECT_EQ(again.repairs, 0u);
  EXPECT_LE(again.detect_stats.faces_tested, 2 * r.faces_flipped);
  EXPECT_LT(again.detect_stats.faces_tested, mesh.n_faces() / 4);
  EXPECT_GT(twist::truth_consistency(mesh, twisted), 0.99);
}

TEST(TwistFaceGrid, StoresTheGeometryOfTheFacesItHolds) {
  Mesh mesh = edgefront::shapes::icosphere(2);
  twist::FaceGrid grid;
  grid.rebuild(mesh, 0.3);
  const FaceHandle f(5);
  const twist::FaceGeometry* g = grid.geometry(f);
  ASSERT_NE(g, nullptr);
  const twist::FaceGeometry direct = twist::face_geometry(mesh, f);
  EXPECT_LT((g->centre - mesh.calc_face_centroid(f)).norm(), 1e-12);
  EXPECT_LT((g->normal - mesh.calc_face_normal(f).normalized()).norm(), 1e-12);
  EXPECT_EQ(g->vertices, direct.vertices);
  EXPECT_DOUBLE_EQ(g->longest, direct.longest);
  EXPECT_EQ(grid.geometry(FaceHandle(static_cast<int>(mesh.n_faces()) + 10)), nullptr);
  EXPECT_EQ(grid.geometry(FaceHandle()), nullptr);
  // After a move and an update the stored geometry follows.
  const edgefront::VertexHandle v(*mesh.cfv_begin(f));
  mesh.set_point(v, mesh.point(v) * 1.5);
  std::vector<FaceHandle> ring(mesh.vf_range(v).begin(), mesh.vf_range(v).end());
  grid.update(mesh, ring);
  EXPECT_LT((grid.geometry(f)->centre - mesh.calc_face_centroid(f)).norm(), 1e-12);
  // Handles that name no live face are refused.
  EXPECT_THROW(twist::face_geometry(mesh, FaceHandle()), InvalidInput);
  EXPECT_THROW(twist::face_geometry(mesh, FaceHandle(static_cast<int>(mesh.n_faces()))), InvalidInput);
  mesh.delete_face(FaceHandle(7), false);
  EXPECT_THROW(twist::face_geometry(mesh, FaceHandle(7)), InvalidInput);
}

TEST(TwistRetest, AbsurdRetestOptionsAreRefused) {
  Mesh mesh = edgefront::shapes::icosphere(2);
  for (const auto& [turn, move] : std::vector<std::pair<double, double>>{
           {-1, 0.25}, {181, 0.25}, {std::nan(""), 0.25}, {10, -1}, {10, std::numeric_limits<double>::infinity()}}) {
    twist::RepairOptions o;
    o.experimental.retest_turn_degrees = turn;
    o.experimental.retest_move = move;
    EXPECT_THROW(twist::repair(mesh, o), InvalidInput) << turn << " " << move;
  }
}

}  // namespace
