// Tests of the reference labelling repair (twist/repair.h: label_by_reference, repair with a
// reference) and of what the repair can and cannot find without a reference: the twisted test
// meshes, spheres and tori with hand-flipped patches, a turned-over disk on a thick plate.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <string>
#include <unordered_set>
#include <vector>

#include "edgefront/error.h"
#include "edgefront/mesh_stats.h"
#include "edgefront/point_cloud.h"
#include "shapes/shapes.h"
#include "twist/reference_normals.h"
#include "twist/repair.h"
#include "shapes/twisted_shapes.h"

namespace {

using edgefront::FaceHandle;
using edgefront::InvalidInput;
using edgefront::Mesh;
using edgefront::Vec3;
using edgefront::VertexHandle;

size_t components(const Mesh& mesh) {
  const edgefront::ComponentLabels labels = edgefront::connected_components(mesh);
  std::unordered_set<int> used;
  for (FaceHandle f : mesh.faces()) used.insert(labels.vertex_component[static_cast<size_t>((*mesh.cfv_begin(f)).idx())]);
  return used.size();
}

double total_area(const Mesh& mesh) {
  double a = 0;
  for (FaceHandle f : mesh.faces()) a += mesh.calc_face_area(f);
  return a;
}

/// Oriented reference points: the centroid and unit normal of every face of a correct mesh.
edgefront::PointCloud face_cloud(const Mesh& mesh) {
  edgefront::PointCloud c;
  for (FaceHandle f : mesh.faces()) {
    c.points.push_back(mesh.calc_face_centroid(f));
    c.normals.push_back(mesh.calc_face_normal(f).normalized());
  }
  return c;
}

/// `mesh` with `count` patches turned over by hand, as a file written with some faces wound the
/// other way reads into a half-edge mesh: each patch (a breadth-first disk of `patch_faces` faces
/// around a random face) gets its own copies of its vertices and reversed winding, so it lies in
/// its hole as a separate component whose border runs the same way as the hole's.
Mesh flip_patches(const Mesh& mesh, int count, size_t patch_faces, std::uint32_t seed, size_t* flipped_faces) {
  std::mt19937 rng(seed);
  std::vector<char> in_patch(mesh.n_faces(), 0);
  for (int k = 0; k < count; ++k) {
    FaceHandle start(static_cast<int>(rng() % mesh.n_faces()));
    std::vector<FaceHandle> patch{start};
    std::unordered_set<int> seen{start.idx()};
    for (size_t q = 0; q < patch.size() && patch.size() < patch_faces; ++q) {
      for (FaceHandle g : mesh.ff_range(patch[q])) {
        if (patch.size() < patch_faces && seen.insert(g.idx()).second) patch.push_back(g);
      }
    }
    for (FaceHandle f : patch) in_patch[static_cast<size_t>(f.idx())] = 1;
  }
  Mesh out;
  std::vector<VertexHandle> same, copy;
  for (VertexHandle v : mesh.vertices()) same.push_back(out.add_vertex(mesh.point(v)));
  copy.assign(same.size(), VertexHandle());
  // Patches touching each other share their copies (one turned-over region).
  size_t n = 0;
  for (FaceHandle f : mesh.faces()) {
    std::vector<VertexHandle> t;
    for (VertexHandle v : mesh.fv_range(f)) {
      const size_t i = static_cast<size_t>(v.idx());
      if (in_patch[static_cast<size_t>(f.idx())]) {
        if (!copy[i].is_valid()) copy[i] = out.add_vertex(mesh.point(v));
        t.push_back(copy[i]);
      } else {
        t.push_back(same[i]);
      }
    }
    if (in_patch[static_cast<size_t>(f.idx())]) {
      std::swap(t[1], t[2]);
      ++n;
    }
    EXPECT_TRUE(out.add_face(t).is_valid());
  }
  *flipped_faces = n;
  edgefront::restore_attributes(out);
  return out;
}

void expect_labelled_repair(twist::TwistedShape s, const std::string& what) {
  const edgefront::PointCloud cloud = twist::truth_points(s);
  const twist::ReferenceNormals ref(cloud);
  twist::RepairOptions o;
  o.detect.reference = &ref;
  o.mend_patches = 0;  // the labelling alone; mending the folds of the twist line: below
  const twist::TwistedShape input = s;
  const size_t faces = s.mesh.n_faces();
  const double area = total_area(s.mesh);
  const size_t pieces = components(s.mesh);
  ASSERT_LT(twist::truth_consistency(s.mesh, s), 0.99) << what << ": the input is twisted";
  const twist::ReferenceLabelling labels = twist::label_by_reference(s.mesh, o);
  ASSERT_EQ(labels.regions.size(), 1u) << what;
  // What the reference still rejects after the flip lies on the twist line (its faces have no
  // truth: they cross between the layers), a fraction of what it rejected before.
  EXPECT_LT(labels.wrong_area_after, labels.wrong_area_before) << what;
  const twist::RepairReport r = twist::repair(s.mesh, o);
  EXPECT_EQ(r.regions_found, 1u) << what;
  EXPECT_EQ(r.repairs, 1u) << what;
  EXPECT_GT(r.cut_edges, 0u) << what;
  EXPECT_GE(twist::truth_consistency(s.mesh, s), 0.99) << what;
  EXPECT_EQ(r.faces_removed, 0u) << what;
  EXPECT_EQ(s.mesh.n_faces(), faces) << what << ": nothing removed";
  EXPECT_NEAR(total_area(s.mesh), area, 1e-9 * area) << what;
  EXPECT_LE(components(s.mesh), pieces + 1) << what << ": one twist line, at most one extra piece";
  const edgefront::MeshStats st = edgefront::compute_stats(s.mesh);
  EXPECT_EQ(st.nonmanifold_vertices, 0u) << what;
  EXPECT_FALSE(r.non_orientable) << what;
  EXPECT_EQ(r.cut_lines, 1u) << what << ": one twist line";
  // Labelling again finds nothing more to flip.
  EXPECT_EQ(twist::label_by_reference(s.mesh, o).regions.size(), 0u) << what;
  // With the defaults the folds left on the twist line are mended too: no piece more, nothing
  // removed that is not re-grown, at least as consistent.
  twist::TwistedShape m = input;
  twist::RepairOptions d;
  d.detect.reference = &ref;
  const twist::RepairReport rd = twist::repair(m.mesh, d);
  EXPECT_EQ(rd.cut_lines, 1u) << what;
  EXPECT_GE(twist::truth_consistency(m.mesh, m), twist::truth_consistency(s.mesh, s) - 1e-12) << what;
  EXPECT_LE(components(m.mesh), pieces + 1) << what;
  EXPECT_EQ(rd.faces_removed, rd.mend_faces_cut_out) << what;
  EXPECT_EQ(edgefront::compute_stats(m.mesh).nonmanifold_vertices, 0u) << what;
}

TEST(TwistLabel, TwistedTubeIsHealedByTheReference) {
  twist::TwistedTubeOptions o;
  o.along = 24;
  o.around = 16;
  o.length = 1.6;
  expect_labelled_repair(twist::twisted_tube(o), "tube");
  o.twist_segment = 6;  // the larger part is inside out
  expect_labelled_repair(twist::twisted_tube(o), "off-centre tube");
}

TEST(TwistLabel, FlippedDiskIsHealedByTheReference) { expect_labelled_repair(twist::flipped_disk_plate(), "disk"); }

TEST(TwistLabel, ACutTooExpensiveIsNotMade) {
  twist::TwistedTubeOptions to;
  to.along = 24;
  to.around = 16;
  to.length = 1.6;
  to.twist_segment = 16;  // a third inside out: flipping it needs a cut around the tube
  twist::TwistedShape s = twist::twisted_tube(to);
  const edgefront::PointCloud cloud = twist::truth_points(s);
  const twist::ReferenceNormals ref(cloud);
  twist::RepairOptions o;
  o.detect.reference = &ref;
  o.cuts.cut_cost = 100;
  const twist::ReferenceLabelling priced_out = twist::label_by_reference(s.mesh, o);
  EXPECT_EQ(priced_out.regions.size(), 0u);
  EXPECT_DOUBLE_EQ(priced_out.wrong_area_after, priced_out.wrong_area_before);
  o.cuts.cut_cost = 1;
  EXPECT_EQ(twist::label_by_reference(s.mesh, o).regions.size(), 1u);
}

TEST(TwistLabel, HandFlippedPatchesOfSphereAndTorusAreFlippedBack) {
  struct Case {
    std::string name;
    Mesh mesh;
  };
  std::vector<Case> cases;
  cases.push_back({"sphere", edgefront::shapes::icosphere(4)});
  cases.push_back({"torus", edgefront::shapes::torus(64, 24)});
  for (Case& c : cases) {
    const twist::ReferenceNormals ref(face_cloud(c.mesh));
    for (std::uint32_t seed = 1; seed <= 3; ++seed) {
      size_t flipped = 0;
      Mesh m = flip_patches(c.mesh, 4, 40 + 60 * seed, seed, &flipped);
      const std::string what = c.name + " seed " + std::to_string(seed);
      ASSERT_EQ(m.n_faces(), c.mesh.n_faces()) << what;
      ASSERT_LT(twist::face_orientation_agreement(m, ref), 0.97) << what;
      const size_t pieces = components(m);
      for (bool seams : {true, false}) {
        // With the seam rule the patches are flipped before the labelling; without it the labels
        // flip them (whole pieces: no cut).
        Mesh mm = m;
        twist::RepairOptions o;
        o.detect.reference = &ref;
        o.experimental.flip_seam_pieces = seams;
        const twist::RepairReport r = twist::repair(mm, o);
        EXPECT_DOUBLE_EQ(twist::face_orientation_agreement(mm, ref), 1.0) << what << seams;
        EXPECT_EQ(mm.n_faces(), c.mesh.n_faces()) << what;
        EXPECT_EQ(r.faces_removed, 0u) << what;
        EXPECT_EQ(r.cut_edges, 0u) << what << ": whole pieces are flipped, no cut";
        EXPECT_LE(components(mm), pieces) << what;
        EXPECT_FALSE(r.non_orientable) << what << ": the patches' seams are compatible once flipped";
        EXPECT_EQ(r.seam_faces_flipped + r.faces_flipped + r.faces_flipped_globally, flipped) << what << seams;
        EXPECT_EQ(r.seam_faces_flipped > 0, seams) << what;
      }
    }
  }
}

TEST(TwistLabel, HandFlippedPatchesNeedNoReference) {
  // The geometry shows them: each patch's border lies on its hole's border running the same way
  // (a reversed seam between two pieces); the smaller side of each seam is flipped.
  const Mesh sphere = edgefront::shapes::icosphere(4);
  const twist::ReferenceNormals ref(face_cloud(sphere));
  for (std::uint32_t seed = 1; seed <= 3; ++seed) {
    size_t flipped = 0;
    Mesh m = flip_patches(sphere, 4, 40 + 60 * seed, seed, &flipped);
    ASSERT_LT(twist::face_orientation_agreement(m, ref), 0.97) << seed;
    twist::RepairOptions o;
    o.experimental.flip_seam_pieces = true;
    Mesh off = m;
    EXPECT_EQ(twist::repair(off).seam_faces_flipped, 0u) << "off by default";
    const twist::RepairReport r = twist::repair(m, o);
    EXPECT_DOUBLE_EQ(twist::face_orientation_agreement(m, ref), 1.0) << seed;
    EXPECT_EQ(r.seam_faces_flipped, flipped) << seed;
    EXPECT_GE(r.seam_pieces_flipped, 1u) << seed;
    EXPECT_EQ(r.faces_removed, 0u) << seed;
    EXPECT_FALSE(r.non_orientable) << seed;
  }
  // The whole sphere inside out but for the patches: the patches are the smaller side and are
  // flipped, then the surface (one closed group) gets outward normals.
  size_t flipped = 0;
  Mesh m = flip_patches(sphere, 3, 150, 7, &flipped);
  {
    // Reverse every face: the rest is inside out, the patches are right.
    Mesh r;
    for (VertexHandle v : m.vertices()) r.add_vertex(m.point(v));
    for (FaceHandle f : m.faces()) {
      std::vector<VertexHandle> t(m.fv_range(f).begin(), m.fv_range(f).end());
      std::swap(t[1], t[2]);
      r.add_face(t);
    }
    edgefront::restore_attributes(r);
    m = std::move(r);
  }
  ASSERT_LT(twist::face_orientation_agreement(m, ref), 0.5);
  twist::RepairOptions o;
  o.experimental.flip_seam_pieces = true;
  const twist::RepairReport r = twist::repair(m, o);
  EXPECT_DOUBLE_EQ(twist::face_orientation_agreement(m, ref), 1.0);
  EXPECT_EQ(r.seam_faces_flipped, flipped);
  EXPECT_GE(r.components_flipped, 1u) << "the group is closed: outward normals";
}

TEST(TwistLabel, AnOpenSurfaceFacingInwardNeedsTheReference) {
  // What the geometry cannot show: which way an open surface as a whole should face. A
  // hemisphere wound inward is consistent in itself, nothing lies in front of it within the search
  // radius, it has no seam and encloses no volume, so without a reference it keeps its
  // orientation (the convention for open parts); with one it is flipped whole, without a cut.
  const Mesh right = edgefront::shapes::hemisphere(32, 8);
  const twist::ReferenceNormals ref(face_cloud(right));
  Mesh inward;
  for (VertexHandle v : right.vertices()) inward.add_vertex(right.point(v));
  for (FaceHandle f : right.faces()) {
    std::vector<VertexHandle> t(right.fv_range(f).begin(), right.fv_range(f).end());
    std::swap(t[1], t[2]);
    inward.add_face(t);
  }
  edgefront::restore_attributes(inward);
  ASSERT_DOUBLE_EQ(twist::face_orientation_agreement(inward, ref), 0.0);
  Mesh alone = inward;
  const twist::RepairReport r = twist::repair(alone);
  EXPECT_EQ(r.regions_found, 0u) << "not found without a reference";
  EXPECT_EQ(r.components_flipped, 0u);
  EXPECT_DOUBLE_EQ(twist::face_orientation_agreement(alone, ref), 0.0);
  twist::RepairOptions o;
  o.detect.reference = &ref;
  const twist::RepairReport fixed = twist::repair(inward, o);
  EXPECT_EQ(fixed.repairs, 1u);
  EXPECT_EQ(fixed.cut_edges, 0u);
  EXPECT_DOUBLE_EQ(twist::face_orientation_agreement(inward, ref), 1.0);
}

TEST(TwistLabel, ATwistAcrossAWallThickerThanTheRadiusNeedsTheRadiusOrTheReference) {
  // What the geometry shows only within the search radius: a disk turned over on a plate whose
  // walls lie farther apart than the radius (2 mean edges by default) faces the other wall from
  // too far; without a reference the disk stays inside out. A radius above
  // the wall thickness finds and fixes it, and so does the reference at the default radius.
  twist::FlippedDiskOptions fo;
  fo.thickness = 0.5;
  const twist::TwistedShape s = twist::flipped_disk_plate(fo);
  const double edge = edgefront::compute_stats(s.mesh).mean_edge_length;
  ASSERT_GT(fo.thickness, 2 * edge) << "the walls lie farther apart than the default radius";
  const double before = twist::truth_consistency(s.mesh, s);
  ASSERT_LT(before, 0.99);
  twist::TwistedShape alone = s;
  twist::repair(alone.mesh);
  EXPECT_LT(twist::truth_consistency(alone.mesh, alone), 0.99) << "not fixed without a reference at the default radius";
  twist::TwistedShape wide = s;
  twist::RepairOptions o;
  o.detect.radius = 1.5 * fo.thickness;
  const twist::RepairReport rw = twist::repair(wide.mesh, o);
  EXPECT_GE(rw.repairs, 1u);
  EXPECT_GE(twist::truth_consistency(wide.mesh, wide), 0.99) << "found and fixed with a radius above the thickness";
  twist::TwistedShape referenced = s;
  const twist::ReferenceNormals ref(twist::truth_points(s));
  twist::RepairOptions ro;
  ro.detect.reference = &ref;
  twist::repair(referenced.mesh, ro);
  EXPECT_GE(twist::truth_consistency(referenced.mesh, referenced), 0.99) << "or with the reference";
}

TEST(TwistLabel, ScatteredRejectionsDoNotShredTheSurface) {
  // A correct sphere whose reference rejects every third face: no region is worth its cut, so
  // nothing is flipped and the sphere stays whole (the detector path needs its border-ratio guard
  // for this; the labelling prices the cuts).
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
  o.detect.vote.thin_wall = 0;  // every rejection counts as a vote
  Mesh m = sphere;
  const twist::RepairReport r = twist::repair(m, o);
  EXPECT_EQ(r.repairs, 0u);
  EXPECT_EQ(r.cut_edges, 0u);
  EXPECT_EQ(m.n_faces(), sphere.n_faces());
  EXPECT_EQ(components(m), 1u);
  o.cuts.cut_cost = 0;  // free cuts: every rejected face would be flipped, but alone each is a tiny piece
  const twist::ReferenceLabelling free_cuts = twist::label_by_reference(sphere, o);
  EXPECT_EQ(free_cuts.regions.size(), 0u);
  EXPECT_GT(free_cuts.regions_too_small, 100u);
}

TEST(TwistLabel, OptionsAreChecked) {
  twist::TwistedShape s = twist::flipped_disk_plate();
  twist::RepairOptions o;
  EXPECT_THROW(twist::label_by_reference(s.mesh, o), InvalidInput) << "no reference";
  const edgefront::PointCloud cloud = twist::truth_points(s);
  const twist::ReferenceNormals ref(cloud);
  o.detect.reference = &ref;
  for (double bad : {-1.0, 101.0, std::nan("")}) {
    o.cuts.cut_cost = bad;
    EXPECT_THROW(twist::label_by_reference(s.mesh, o), InvalidInput) << bad;
    EXPECT_THROW(twist::repair(s.mesh, o), InvalidInput) << bad;
  }
  Mesh empty;
  o.cuts.cut_cost = 1;
  EXPECT_THROW(twist::label_by_reference(empty, o), InvalidInput);
}

}  // namespace
