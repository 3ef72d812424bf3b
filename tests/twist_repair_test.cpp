// Tests of twist/repair.h and twist/orient_soup.h: the deterministic twisted meshes are repaired
// to full orientation consistency, manifold, flipping at most half and visiting at most twice
// the flipped side; a Möbius strip terminates and is reported; bad input throws.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "edgefront/error.h"
#include "edgefront/mesh_stats.h"
#include "edgefront/point_cloud.h"
#include "shapes/shapes.h"
#include "twist/orient_soup.h"
#include "twist/reference_normals.h"
#include "twist/repair.h"
#include "shapes/twisted_shapes.h"

namespace {

using edgefront::FaceHandle;
using edgefront::InvalidInput;
using edgefront::Mesh;
using edgefront::Vec3;

/// Face count of the smallest connected component.
size_t smallest_component_faces(const Mesh& mesh) {
  const edgefront::ComponentLabels labels = edgefront::connected_components(mesh);
  std::vector<size_t> faces(labels.count, 0);
  for (FaceHandle f : mesh.faces()) ++faces[static_cast<size_t>(labels.vertex_component[static_cast<size_t>((*mesh.cfv_begin(f)).idx())])];
  size_t smallest = std::numeric_limits<size_t>::max();
  for (size_t n : faces) {
    if (n > 0) smallest = std::min(smallest, n);
  }
  return smallest;
}

void expect_repaired(twist::TwistedShape s, const std::string& what) {
  const size_t faces = s.mesh.n_faces();
  ASSERT_LT(twist::truth_consistency(s.mesh, s), 0.99) << what << ": the input is twisted";
  const twist::RepairReport r = twist::repair(s.mesh);
  EXPECT_EQ(r.regions_found, 1u) << what;
  ASSERT_EQ(r.repairs, 1u) << what;
  ASSERT_EQ(r.records.size(), 1u) << what;
  EXPECT_DOUBLE_EQ(twist::truth_consistency(s.mesh, s), 1.0) << what;
  // A cut may split off a sliver of the other side (a face that hung on the region by its edges):
  // it is removed, never left as a tiny component; nothing else is lost.
  EXPECT_LT(r.faces_removed, twist::RepairOptions{}.cuts.min_component_faces) << what;
  EXPECT_EQ(s.mesh.n_faces(), faces - r.faces_removed) << what << ": no face lost but tiny pieces";
  EXPECT_GE(smallest_component_faces(s.mesh), twist::RepairOptions{}.cuts.min_component_faces)
      << what << ": no tiny component";
  EXPECT_GT(r.faces_flipped, 0u) << what;
  EXPECT_LE(2 * r.faces_flipped, faces) << what << ": at most half flipped";
  EXPECT_LE(r.faces_visited, 2 * r.faces_flipped) << what << ": at most twice the flipped side visited";
  EXPECT_GT(r.cut_edges, 0u) << what;
  EXPECT_GT(r.vertices_duplicated, 0u) << what;
  const edgefront::MeshStats st = edgefront::compute_stats(s.mesh);
  EXPECT_EQ(st.nonmanifold_vertices, 0u) << what;
  EXPECT_EQ(st.faces, faces - r.faces_removed) << what;
  EXPECT_FALSE(r.non_orientable) << what;
  // Nothing twisted is left but, at most, faces of the twist line itself (which the repair cuts
  // through but does not move; a refinement loop pulls them onto the surface).
  for (const auto& region : twist::detect(s.mesh)) {
    for (FaceHandle f : region.faces) EXPECT_FALSE(s.truth(s.mesh.calc_face_centroid(f)).has_value()) << what;
  }
  // Repairing again does not undo anything.
  twist::repair(s.mesh);
  EXPECT_DOUBLE_EQ(twist::truth_consistency(s.mesh, s), 1.0) << what;
}

TEST(TwistRepair, TwistedTubeIsRepairedToFullConsistency) {
  twist::TwistedTubeOptions o;
  o.along = 24;
  o.around = 16;
  o.length = 1.6;
  expect_repaired(twist::twisted_tube(o), "tube");
}

TEST(TwistRepair, TwistedTubeWithTheTwistOffCentreFlipsTheSmallerSide) {
  twist::TwistedTubeOptions o;
  o.along = 24;
  o.around = 16;
  o.length = 1.6;
  o.twist_segment = 6;  // the inverted part is the larger one: the fronts flip the right part
  expect_repaired(twist::twisted_tube(o), "off-centre tube");
}

TEST(TwistRepair, FlippedDiskIsRepairedToFullConsistency) { expect_repaired(twist::flipped_disk_plate(), "disk"); }

TEST(TwistRepair, ReferenceNormalsGiveTheSameResult) {
  twist::TwistedShape s = twist::flipped_disk_plate();
  const edgefront::PointCloud cloud = twist::truth_points(s);
  const twist::ReferenceNormals ref(cloud);
  twist::RepairOptions o;
  o.detect.reference = &ref;
  const auto r = twist::repair(s.mesh, o);
  EXPECT_EQ(r.repairs, 1u);
  EXPECT_DOUBLE_EQ(twist::truth_consistency(s.mesh, s), 1.0);
}

/// Adds an n x n grid of unit cells at height z with offset (x0, y0), normals +z (-z when
/// `down`); returns its vertices, row by row.
std::vector<Mesh::VertexHandle> add_grid(Mesh& m, int n, double x0, double y0, double z, bool down = false) {
  std::vector<Mesh::VertexHandle> v;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) v.push_back(m.add_vertex(Vec3(x0 + i, y0 + j, z)));
  }
  const auto at = [&](int i, int j) { return v[static_cast<size_t>(j * (n + 1) + i)]; };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      if (down) {
        m.add_face(at(i, j), at(i + 1, j + 1), at(i + 1, j));
        m.add_face(at(i, j), at(i, j + 1), at(i + 1, j + 1));
      } else {
        m.add_face(at(i, j), at(i + 1, j), at(i + 1, j + 1));
        m.add_face(at(i, j), at(i + 1, j + 1), at(i, j + 1));
      }
    }
  }
  return v;
}

TEST(TwistRepair, BorderFlapsOverAnotherLayerArePeeledWhenAsked) {
  // A 10 x 10 plate and a 2 x 2 flap lying 0.5 above its middle, both facing +z: a double layer
  // (same orientation, close in space, far along the surface), not a twist; the reference (+z)
  // confirms both, so nothing is cut. Peeling removes the flap (every face of it touches its
  // border) and leaves the plate (its faces under the flap are interior).
  Mesh m;
  add_grid(m, 10, 0, 0, 0);
  add_grid(m, 2, 4, 4, 0.5);
  edgefront::PointCloud cloud;
  for (double x = 0; x <= 10; x += 0.25) {
    for (double y = 0; y <= 10; y += 0.25) {
      cloud.points.emplace_back(x, y, 0);
      cloud.normals.emplace_back(0, 0, 1);
    }
  }
  const twist::ReferenceNormals ref(cloud);
  twist::RepairOptions o;
  o.detect.reference = &ref;
  ASSERT_GE(twist::same_orientation_pairs(m).size(), 8u + 8u) << "the flap's 8 faces and the plate faces under it";
  Mesh kept = m;
  EXPECT_EQ(twist::repair(kept, o).flap_faces_removed, 0u) << "off by default";
  EXPECT_EQ(kept.n_faces(), 208u);
  o.experimental.drop_turned_patches = 4;
  const twist::RepairReport right = twist::repair(kept, o);
  EXPECT_EQ(right.turned_faces_removed + right.turned_faces_collapsed, 0u) << "the flap is oriented right: not turned over";
  EXPECT_EQ(kept.n_faces(), 208u);
  o.experimental.drop_turned_patches = 0;
  o.experimental.peel_flaps = 1;
  const twist::RepairReport r = twist::repair(m, o);
  EXPECT_EQ(r.repairs, 0u);
  EXPECT_EQ(r.flap_faces_removed, 8u);
  EXPECT_EQ(m.n_faces(), 200u);
  EXPECT_EQ(edgefront::compute_stats(m).components, 1u);
  EXPECT_EQ(twist::same_orientation_pairs(m).size(), 0u);
  o.experimental.peel_flaps = 17;
  EXPECT_THROW(twist::repair(m, o), InvalidInput);
  o.experimental.peel_flaps = 1;
  for (double share : {-0.1, 1.5, std::numeric_limits<double>::quiet_NaN()}) {
    o.cuts.min_cut_piece_share = share;
    EXPECT_THROW(twist::repair(m, o), InvalidInput) << share;
  }
}

TEST(TwistRepair, CleanUpsSpareFacesThatAloneCoverTheSamples) {
  // The same 10 x 10 plate with a 2 x 2 flap 1.5 above its middle, both facing +z. Sampled only
  // on the plate, the flap is a double layer and peeling removes it, with or without
  // cuts.support_radius. Sampled on the flap too (a shelf over the plate), the flap is the only
  // surface within half a mean edge of those samples: peeling it would lose area the samples
  // support, so with cuts.support_radius it stays.
  for (bool flap_sampled : {false, true}) {
    Mesh m;
    add_grid(m, 10, 0, 0, 0);
    add_grid(m, 2, 4, 4, 1.5);
    edgefront::PointCloud cloud;
    for (double x = 0; x <= 10; x += 0.25) {
      for (double y = 0; y <= 10; y += 0.25) {
        cloud.points.emplace_back(x, y, 0);
        cloud.normals.emplace_back(0, 0, 1);
        if (flap_sampled && x >= 4 && x <= 6 && y >= 4 && y <= 6) {
          cloud.points.emplace_back(x, y, 1.5);
          cloud.normals.emplace_back(0, 0, 1);
        }
      }
    }
    const twist::ReferenceNormals ref(cloud);
    twist::RepairOptions o;
    o.detect.reference = &ref;
    o.experimental.peel_flaps = 1;
    for (double radius : {0.0, 0.5}) {
      o.cuts.support_radius = radius;
      Mesh r = m;
      const twist::RepairReport report = twist::repair(r, o);
      const bool spared = flap_sampled && radius > 0;
      EXPECT_EQ(report.flap_faces_removed, spared ? 0u : 8u) << flap_sampled << " " << radius;
      EXPECT_EQ(report.supported_faces_spared, spared ? 8u : 0u) << flap_sampled << " " << radius;
      EXPECT_EQ(r.n_faces(), spared ? 208u : 200u) << flap_sampled << " " << radius;
    }
  }
  // Off in both presets; absurd radii are refused, naming the option.
  EXPECT_EQ(twist::RepairOptions::in_loop().cuts.support_radius, 0.0);
  EXPECT_EQ(twist::RepairOptions::finished_mesh().cuts.support_radius, 0.0);
  Mesh m;
  add_grid(m, 4, 0, 0, 0);
  twist::RepairOptions o;
  for (double radius : {-0.5, 4.5, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    o.cuts.support_radius = radius;
    try {
      twist::repair(m, o);
      ADD_FAILURE() << "accepted support_radius " << radius;
    } catch (const InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find("support_radius"), std::string::npos) << e.what();
    }
  }
}

/// Two parallel 6 x 6 plates 0.5 apart, the two walls of a slab facing out (z = 0 down, z = 0.5
/// up), and reference points with those normals on both.
struct Slab {
  Mesh mesh;
  std::vector<Mesh::VertexHandle> top;
  edgefront::PointCloud cloud;
};
Slab slab() {
  Slab s;
  add_grid(s.mesh, 6, 0, 0, 0, true);
  s.top = add_grid(s.mesh, 6, 0, 0, 0.5);
  for (double x = 0; x <= 6; x += 0.25) {
    for (double y = 0; y <= 6; y += 0.25) {
      for (double z : {0.0, 0.5}) {
        s.cloud.points.emplace_back(x, y, z);
        s.cloud.normals.emplace_back(0, 0, z > 0 ? 1 : -1);
      }
    }
  }
  return s;
}

TEST(TwistRepair, TurnedOverRimFlapIsRemovedWhenAsked) {
  // One triangle on the top plate's border edge y = 0, folded back under the plate (normal -z,
  // pointing at the bottom plate's back: a same-orientation layer). The reference rejects it,
  // but alone against right neighbours it is no region the detector repairs (no core).
  Slab s = slab();
  const twist::ReferenceNormals ref(s.cloud);
  // The top plate's border halfedge runs (3, 0) -> (2, 0); the flap continues it.
  const FaceHandle flap = s.mesh.add_face(s.top[3], s.top[2], s.mesh.add_vertex(Vec3(2.5, 0.8, 0.45)));
  ASSERT_TRUE(flap.is_valid());
  ASSERT_LT(s.mesh.calc_face_normal(flap)[2], -0.9);
  ASSERT_GT(twist::same_orientation_pairs(s.mesh).size(), 0u);
  twist::RepairOptions o;
  o.detect.reference = &ref;
  Mesh kept = s.mesh;
  const twist::RepairReport off = twist::repair(kept, o);
  EXPECT_EQ(off.repairs, 0u);
  EXPECT_EQ(off.turned_faces_removed, 0u) << "off by default";
  EXPECT_EQ(kept.n_faces(), 145u);
  o.experimental.drop_turned_patches = 4;
  const twist::RepairReport r = twist::repair(s.mesh, o);
  EXPECT_EQ(r.repairs, 0u);
  EXPECT_EQ(r.turned_faces_removed, 1u);
  EXPECT_EQ(r.turned_faces_collapsed, 0u);
  EXPECT_EQ(s.mesh.n_faces(), 144u);
  EXPECT_EQ(twist::same_orientation_pairs(s.mesh).size(), 0u);
  EXPECT_DOUBLE_EQ(twist::face_orientation_agreement(s.mesh, ref), 1.0);
  o.experimental.drop_turned_patches = 65;
  EXPECT_THROW(twist::repair(s.mesh, o), InvalidInput);
}

/// Faces of the slab's top plate (z = 0.5) that face down.
std::vector<FaceHandle> turned_top_faces(const Mesh& mesh) {
  std::vector<FaceHandle> out;
  for (FaceHandle f : mesh.faces()) {
    if (mesh.calc_face_normal(f)[2] < 0 && mesh.calc_face_centroid(f)[2] > 0.25) out.push_back(f);
  }
  return out;
}

/// A full repair with the reference and turned patches of up to 4 faces dropped.
twist::RepairReport drop_turned(Mesh& mesh, const twist::ReferenceNormals& ref) {
  twist::RepairOptions o;
  o.detect.reference = &ref;
  o.experimental.drop_turned_patches = 4;
  return twist::repair(mesh, o);
}

/// `drop_turned` on a slab with turned top faces that no collapse or removal should touch:
/// straightened in place, every face right, no same-orientation pair left.
twist::RepairReport expect_straightened(Mesh& mesh, const twist::ReferenceNormals& ref) {
  const twist::RepairReport r = drop_turned(mesh, ref);
  EXPECT_EQ(r.repairs, 0u);
  EXPECT_GE(r.turned_faces_straightened, 1u);
  EXPECT_EQ(r.turned_faces_collapsed, 0u);
  EXPECT_EQ(r.turned_faces_removed, 0u);
  EXPECT_EQ(mesh.n_faces(), 144u);
  EXPECT_DOUBLE_EQ(twist::face_orientation_agreement(mesh, ref), 1.0);
  EXPECT_EQ(twist::same_orientation_pairs(mesh).size(), 0u);
  return r;
}

TEST(TwistRepair, InteriorFaceFoldedByOneVertexIsStraightenedWhenAsked) {
  // The top plate's vertex (3, 3) pushed across the edge (4, 3)-(4, 4) of its star, far enough
  // that the one face it turns over is no sliver (every edge over half the mean edge): nothing to
  // collapse, and an interior face is not removed. Moving one of its vertices to the centroid of
  // that vertex's neighbours turns it back; every face is right afterwards, none is removed.
  Slab s = slab();
  const twist::ReferenceNormals ref(s.cloud);
  s.mesh.set_point(s.top[3 * 7 + 3], Vec3(4.4, 3.5, 0.5));
  const std::vector<FaceHandle> turned = turned_top_faces(s.mesh);
  ASSERT_EQ(turned.size(), 1u);
  double mean_edge = 0;
  for (auto e : s.mesh.edges()) mean_edge += s.mesh.calc_edge_length(e) / static_cast<double>(s.mesh.n_edges());
  for (auto h : s.mesh.fh_range(turned[0])) ASSERT_GT(s.mesh.calc_edge_length(h), 0.5 * mean_edge) << "no sliver";
  ASSERT_GT(twist::same_orientation_pairs(s.mesh).size(), 0u);
  EXPECT_EQ(expect_straightened(s.mesh, ref).turned_faces_straightened, 1u);
  for (FaceHandle f : s.mesh.faces()) EXPECT_GT(s.mesh.calc_face_area(f), 0.05) << "no face degenerates";
}

TEST(TwistRepair, TangleOfTwoPushedVerticesIsSmoothedWhenAsked) {
  // The top plate's vertices (3, 3) and (4, 4), each pushed across the other's star: two faces
  // turn over, no sliver among them, and moving any one of their vertices to the centroid of its
  // neighbours leaves a face turned (the neighbours are displaced too). Smoothing the faces'
  // vertices and their neighbours together turns them back; nothing is removed.
  Slab s = slab();
  const twist::ReferenceNormals ref(s.cloud);
  s.mesh.set_point(s.top[3 * 7 + 3], Vec3(3.75, 4.25, 0.5));
  s.mesh.set_point(s.top[4 * 7 + 4], Vec3(4.75, 3.0, 0.5));
  const std::vector<FaceHandle> turned = turned_top_faces(s.mesh);
  ASSERT_EQ(turned.size(), 2u);
  for (FaceHandle f : turned) {
    for (auto h : s.mesh.fh_range(f)) ASSERT_GT(s.mesh.calc_edge_length(h), 0.7) << "no sliver";
    for (auto v : s.mesh.fv_range(f)) {
      Vec3 sum(0, 0, 0);
      for (auto w : s.mesh.vv_range(v)) sum += s.mesh.point(w);
      const Vec3 old = s.mesh.point(v);
      s.mesh.set_point(v, sum / static_cast<double>(s.mesh.valence(v)));
      EXPECT_FALSE(turned_top_faces(s.mesh).empty()) << "one vertex moved alone leaves a turned face";
      s.mesh.set_point(v, old);
    }
  }
  expect_straightened(s.mesh, ref);
}

TEST(TwistRepair, InvertedInteriorSliverIsCollapsedWhenAsked) {
  // The top plate's vertex (3, 3) moved just across the edge (4, 3)-(4, 4) of its convex star:
  // exactly one face turns over, a sliver among right neighbours, facing the bottom plate's
  // back. Collapsing its shortest edge removes it and leaves every face right.
  Slab s = slab();
  const twist::ReferenceNormals ref(s.cloud);
  s.mesh.set_point(s.top[3 * 7 + 3], Vec3(4.05, 3.1, 0.5));
  ASSERT_EQ(turned_top_faces(s.mesh).size(), 1u);
  const twist::RepairReport r = drop_turned(s.mesh, ref);
  EXPECT_EQ(r.repairs, 0u);
  EXPECT_EQ(r.turned_faces_collapsed, 1u);
  EXPECT_EQ(r.turned_faces_removed, 0u);
  EXPECT_EQ(s.mesh.n_faces(), 142u) << "a collapse removes the sliver and its neighbour across the edge";
  EXPECT_DOUBLE_EQ(twist::face_orientation_agreement(s.mesh, ref), 1.0);
  EXPECT_EQ(edgefront::compute_stats(s.mesh).components, 2u);
  EXPECT_EQ(twist::same_orientation_pairs(s.mesh).size(), 0u);
}

TEST(TwistRepair, CorrectMeshIsLeftAlone) {
  Mesh m = edgefront::shapes::vault_shell(16, 1.0, 0.05);
  const size_t faces = m.n_faces();
  const auto r = twist::repair(m);
  EXPECT_EQ(r.regions_found, 0u);
  EXPECT_EQ(r.repairs, 0u);
  EXPECT_EQ(r.components_flipped, 0u);
  EXPECT_EQ(m.n_faces(), faces);
}

TEST(TwistRepair, InsideOutClosedMeshIsTurnedOutward) {
  Mesh m = edgefront::shapes::icosphere(2);
  std::vector<std::array<edgefront::VertexHandle, 3>> tris;
  for (FaceHandle f : m.faces()) {
    std::array<edgefront::VertexHandle, 3> t;
    int i = 0;
    for (auto v : m.fv_range(f)) t[static_cast<size_t>(i++)] = v;
    tris.push_back({t[0], t[2], t[1]});
  }
  Mesh inside_out;
  for (auto v : m.vertices()) inside_out.add_vertex(m.point(v));
  for (const auto& t : tris) inside_out.add_face(t[0], t[1], t[2]);
  const auto r = twist::repair(inside_out);
  EXPECT_EQ(r.components_flipped, 1u);
  double volume = 0;
  for (FaceHandle f : inside_out.faces()) {
    auto it = inside_out.fv_begin(f);
    const Vec3 a = inside_out.point(*it++), b = inside_out.point(*it++), c = inside_out.point(*it);
    volume += OpenMesh::dot(a, OpenMesh::cross(b, c)) / 6;
  }
  EXPECT_GT(volume, 0);
}

// Spheres as separate components (centre, radius, outward or not), and their signed volumes.
struct Ball {
  Vec3 centre;
  double radius;
  bool outward;
};
Mesh balls(const std::vector<Ball>& parts) {
  const Mesh unit = edgefront::shapes::icosphere(2);
  Mesh m;
  for (const Ball& b : parts) {
    std::vector<edgefront::VertexHandle> id;
    for (auto v : unit.vertices()) id.push_back(m.add_vertex(b.centre + b.radius * unit.point(v)));
    for (FaceHandle f : unit.faces()) {
      std::vector<edgefront::VertexHandle> t;
      for (auto v : unit.fv_range(f)) t.push_back(id[static_cast<size_t>(v.idx())]);
      if (!b.outward) std::swap(t[1], t[2]);
      m.add_face(t);
    }
  }
  return m;
}
std::vector<double> component_volumes(const Mesh& m) {
  const edgefront::ComponentLabels labels = edgefront::connected_components(m);
  std::vector<double> volume(labels.count, 0);
  for (FaceHandle f : m.faces()) {
    auto it = m.cfv_begin(f);
    const auto c = static_cast<size_t>(labels.vertex_component[static_cast<size_t>(it->idx())]);
    const Vec3 a = m.point(*it++), b = m.point(*it++), d = m.point(*it);
    volume[c] += OpenMesh::dot(a, OpenMesh::cross(b, d)) / 6;
  }
  return volume;
}

TEST(TwistRepair, ClosedSurfaceInsideAnotherFacesIntoItsCavity) {
  // A hollow ball (outer R 1, inner 0.5), a solid ball in its cavity (0.25) and a ball beside it:
  // without reference normals, outward, into the cavity, outward, outward, whichever way each
  // came in. Component labels follow the vertices, i.e. the order of the parts.
  const std::vector<double> sign = {1, -1, 1, 1};
  for (int turned : {0, 1, 2, 5, 10, 15}) {  // bit k: ball k comes in turned the other way
    std::vector<Ball> parts = {{Vec3(0, 0, 0), 1.0, true}, {Vec3(0, 0, 0), 0.5, false},
                               {Vec3(0.05, 0, 0), 0.25, true}, {Vec3(3, 0, 0), 0.5, true}};
    size_t wrong = 0;
    for (size_t k = 0; k < parts.size(); ++k)
      if (turned >> k & 1) {
        parts[k].outward = !parts[k].outward;
        ++wrong;
      }
    Mesh m = balls(parts);
    const auto r = twist::repair(m);
    EXPECT_EQ(r.repairs, 0u) << "turned " << turned;  // nothing twisted: only whole components turn
    EXPECT_EQ(r.components_flipped, wrong) << "turned " << turned;
    const std::vector<double> volume = component_volumes(m);
    ASSERT_EQ(volume.size(), 4u);
    for (size_t k = 0; k < 4; ++k) EXPECT_GT(sign[k] * volume[k], 0) << "turned " << turned << ", ball " << k;
  }
}

TEST(TwistRepair, IncrementalRepairerFindsTheRegionFromAChangedFace) {
  twist::TwistedShape s = twist::flipped_disk_plate();
  const auto regions = twist::detect(s.mesh);
  ASSERT_EQ(regions.size(), 1u);
  twist::RepairOptions o;
  o.detect.incremental.audit_faces = 0;
  twist::TwistRepairer repairer(o);
  const auto r = repairer.repair_changed(s.mesh, {regions[0].faces.back()});
  EXPECT_EQ(r.repairs, 1u);
  EXPECT_LT(r.detect_stats.faces_tested, s.mesh.n_faces() / 2);
  repairer.finish(s.mesh);
  EXPECT_DOUBLE_EQ(twist::truth_consistency(s.mesh, s), 1.0);
}

// The mesh's faces as sorted triangles of corner positions: equal for meshes that differ only in
// their numbering.
std::vector<std::array<std::array<double, 3>, 3>> triangles(const Mesh& m) {
  std::vector<std::array<std::array<double, 3>, 3>> out;
  for (FaceHandle f : m.faces()) {
    std::array<std::array<double, 3>, 3> t;
    size_t i = 0;
    for (auto v : m.fv_range(f)) t[i++] = {m.point(v)[0], m.point(v)[1], m.point(v)[2]};
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());  // keep the winding
    out.push_back(t);
  }
  std::sort(out.begin(), out.end());
  return out;
}

TEST(TwistRepair, ARenumberedRepairerRepairsAsOneThatWasNot) {
  // Two repairers follow the same twisted tube; after the first call one mesh is renumbered
  // (OpenMesh's garbage collection: deleted elements dropped, the last ones moved into the holes)
  // and its repairer told the maps. The second call (a re-twist at the same place, and every face
  // reported changed) and the final repair must do the same on both.
  twist::TwistedShape a = twist::twisted_tube();
  twist::TwistedShape b = twist::twisted_tube();
  twist::RepairOptions o;
  o.detect.incremental.audit_faces = 0;  // the audit samples by index
  o.garbage_collect = false;
  twist::TwistRepairer ra(o, 1), rb(o, 1);
  double mean_edge = 0;
  for (auto e : a.mesh.edges()) mean_edge += a.mesh.calc_edge_length(e);
  mean_edge /= static_cast<double>(a.mesh.n_edges());
  const std::vector<FaceHandle> first(a.mesh.faces_begin(), a.mesh.faces_end());
  const auto a1 = ra.repair_changed(a.mesh, first, mean_edge);
  const auto b1 = rb.repair_changed(b.mesh, first, mean_edge);
  ASSERT_EQ(a1.repairs, 1u);
  ASSERT_EQ(b1.repairs, 1u);
  ASSERT_FALSE(rb.cuts().empty());
  // Renumber b: every handle, old -> new.
  std::vector<edgefront::VertexHandle> vall, vold;
  std::vector<FaceHandle> fall, fold;
  for (size_t i = 0; i < b.mesh.n_vertices(); ++i) vall.emplace_back(static_cast<int>(i));
  for (size_t i = 0; i < b.mesh.n_faces(); ++i) fall.emplace_back(static_cast<int>(i));
  vold = vall;
  fold = fall;
  std::vector<edgefront::VertexHandle*> vp;
  std::vector<edgefront::HalfedgeHandle*> hp;
  std::vector<FaceHandle*> fp;
  for (auto& v : vall) vp.push_back(&v);
  for (auto& f : fall) fp.push_back(&f);
  const size_t faces_before = b.mesh.n_faces();
  b.mesh.garbage_collection(vp, hp, fp);
  ASSERT_LT(b.mesh.n_faces(), faces_before) << "the cut deleted faces: indices move";
  std::vector<int> vmap, fmap;
  for (size_t i = 0; i < vall.size(); ++i) vmap.push_back(a.mesh.status(vold[i]).deleted() ? -1 : vall[i].idx());
  for (size_t i = 0; i < fall.size(); ++i) fmap.push_back(a.mesh.status(fold[i]).deleted() ? -1 : fall[i].idx());
  rb.renumber(b.mesh, vmap, fmap);
  // The cut pairs whose vertices still exist (the others are dropped), in the same order.
  std::vector<std::pair<edgefront::VertexHandle, edgefront::VertexHandle>> live_cuts;
  for (const auto& [copy, original] : ra.cuts()) {
    if (!a.mesh.status(copy).deleted() && !a.mesh.status(original).deleted()) live_cuts.emplace_back(copy, original);
  }
  ASSERT_EQ(rb.cuts().size(), live_cuts.size());
  for (size_t i = 0; i < live_cuts.size(); ++i) {
    EXPECT_EQ(b.mesh.point(rb.cuts()[i].first), a.mesh.point(live_cuts[i].first));
    EXPECT_EQ(b.mesh.point(rb.cuts()[i].second), a.mesh.point(live_cuts[i].second));
  }
  EXPECT_EQ(triangles(a.mesh), triangles(b.mesh));
  // Every face reported changed: the snapshots decide which are tested again.
  std::vector<FaceHandle> all_a(a.mesh.faces_begin(), a.mesh.faces_end()), all_b(b.mesh.faces_begin(), b.mesh.faces_end());
  const auto a2 = ra.repair_changed(a.mesh, all_a, mean_edge);
  const auto b2 = rb.repair_changed(b.mesh, all_b, mean_edge);
  EXPECT_EQ(a2.detect_stats.faces_tested, b2.detect_stats.faces_tested);
  EXPECT_EQ(a2.regions_found, b2.regions_found);
  EXPECT_EQ(a2.repairs, b2.repairs);
  const auto a3 = ra.finish(a.mesh);
  const auto b3 = rb.finish(b.mesh);
  EXPECT_EQ(a3.components_flipped, b3.components_flipped);
  EXPECT_EQ(triangles(a.mesh), triangles(b.mesh));
  EXPECT_DOUBLE_EQ(twist::truth_consistency(b.mesh, b), twist::truth_consistency(a.mesh, a));
  // A map too short for what the repairer holds is refused.
  EXPECT_THROW(rb.renumber(b.mesh, {}, {}), InvalidInput);
}

TEST(TwistRepair, ARegionThatReTwistsIsCutOut) {
  twist::RepairOptions o;
  twist::TwistRepairer repairer(o, 1);
  twist::TwistedShape a = twist::flipped_disk_plate();
  const auto first = repairer.repair_changed(a.mesh, {FaceHandle(0)});
  EXPECT_EQ(first.repairs, 1u);
  EXPECT_EQ(first.regions_cut_out, 0u);
  twist::TwistedShape b = twist::flipped_disk_plate();  // the same twist again, same place
  const auto again = repairer.repair_changed(b.mesh, {FaceHandle(0)});
  EXPECT_EQ(again.repairs, 0u + 1u);
  EXPECT_EQ(again.regions_cut_out, 1u);
  EXPECT_GT(again.faces_removed, 0u);
  EXPECT_EQ(edgefront::compute_stats(b.mesh).nonmanifold_vertices, 0u);
}

TEST(TwistRepair, CutMobiusStripTerminatesAndIsReportedNonOrientable) {
  Mesh m = edgefront::shapes::mobius_strip(48, 4);
  const size_t faces = m.n_faces();
  const auto r = twist::repair(m);
  EXPECT_TRUE(r.non_orientable);
  EXPECT_EQ(r.seam_edges, 4u);
  EXPECT_EQ(m.n_faces(), faces);
  EXPECT_EQ(edgefront::compute_stats(m).nonmanifold_vertices, 0u);
}

TEST(TwistRepair, MobiusSoupIsCutOpenAndReportedNonOrientable) {
  // A real Möbius band as a triangle soup: the last column of quads is glued to the first with
  // the width reversed. OpenMesh cannot hold it; orient_soup cuts it.
  const int around = 24, across = 3;
  const double pi = 3.14159265358979323846;
  std::vector<Vec3> pts;
  for (int i = 0; i < around; ++i) {
    const double u = 2 * pi * i / around;
    for (int j = 0; j <= across; ++j) {
      const double v = -0.25 + 0.5 * j / across;
      pts.emplace_back((1 + v * std::cos(u / 2)) * std::cos(u), (1 + v * std::cos(u / 2)) * std::sin(u), v * std::sin(u / 2));
    }
  }
  auto id = [&](int i, int j) {
    if (i == around) return j == across - j ? j : (across - j);  // u = 2 pi is u = 0 with v reversed
    return i * (across + 1) + j;
  };
  std::vector<std::array<int, 3>> tris;
  for (int i = 0; i < around; ++i) {
    for (int j = 0; j < across; ++j) {
      tris.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      tris.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  const twist::SoupOrientation o = twist::orient_soup(pts, tris);
  EXPECT_TRUE(o.non_orientable);
  EXPECT_GT(o.cut_edges, 0u);
  EXPECT_GT(o.vertices_duplicated, 0u);
  EXPECT_EQ(o.faces_dropped, 0u);
  EXPECT_EQ(o.mesh.n_faces(), tris.size());
  const auto st = edgefront::compute_stats(o.mesh);
  EXPECT_EQ(st.nonmanifold_vertices, 0u);
  EXPECT_EQ(st.components, 1u);

  // The same soup with every other face wound the wrong way, but orientable (an annulus): fixed
  // without any cut.
  std::vector<std::array<int, 3>> annulus;
  auto aid = [&](int i, int j) { return (i % around) * (across + 1) + j; };
  for (int i = 0; i < around; ++i) {
    for (int j = 0; j < across; ++j) {
      annulus.push_back({aid(i, j), aid(i + 1, j), aid(i + 1, j + 1)});
      annulus.push_back({aid(i, j), aid(i, j + 1), aid(i + 1, j + 1)});  // reversed winding
    }
  }
  const twist::SoupOrientation a = twist::orient_soup(pts, annulus);
  EXPECT_FALSE(a.non_orientable);
  EXPECT_EQ(a.cut_edges, 0u);
  EXPECT_EQ(a.faces_reversed, annulus.size() / 2);
  EXPECT_EQ(a.mesh.n_faces(), annulus.size());
  EXPECT_EQ(edgefront::compute_stats(a.mesh).border_loops, 2u);
}

/// A flat spiral ramp: the annulus 1 <= r <= 2 (2 segments across, 24 around a turn) wound
/// through one turn plus `extra` segments, rising `pitch` per turn, facing +z. Its two ends
/// overlap over `extra` segments: one wall's border curled over itself, two layers with the same
/// orientation, close in space, a turn apart along the surface.
Mesh spiral_ramp(int extra, double pitch = 0.05) {
  Mesh m;
  constexpr int kAround = 24;
  const int columns = kAround + extra;
  std::vector<Mesh::VertexHandle> v;
  for (int i = 0; i <= columns; ++i) {
    const double a = 2 * std::numbers::pi * i / kAround;
    for (int k = 0; k <= 2; ++k) {
      const double r = 1.0 + 0.5 * k;
      v.push_back(m.add_vertex(Vec3(r * std::cos(a), r * std::sin(a), pitch * i / kAround)));
    }
  }
  const auto at = [&](int i, int k) { return v[static_cast<size_t>(i * 3 + k)]; };
  for (int i = 0; i < columns; ++i) {
    for (int k = 0; k < 2; ++k) {
      m.add_face(at(i, k), at(i + 1, k), at(i + 1, k + 1));
      m.add_face(at(i, k), at(i + 1, k + 1), at(i, k + 1));
    }
  }
  return m;
}

/// Is the point (x, y) inside the xy projection of some face of `mesh`?
bool covered_in_plan(const Mesh& mesh, double x, double y) {
  for (FaceHandle f : mesh.faces()) {
    std::array<Vec3, 3> p;
    size_t i = 0;
    for (auto v : mesh.fv_range(f)) p[i++] = mesh.point(v);
    double s[3];
    for (size_t e = 0; e < 3; ++e) {
      const Vec3& a = p[e];
      const Vec3& b = p[(e + 1) % 3];
      s[e] = (b[0] - a[0]) * (y - a[1]) - (b[1] - a[1]) * (x - a[0]);
    }
    if ((s[0] >= -1e-12 && s[1] >= -1e-12 && s[2] >= -1e-12) || (s[0] <= 1e-12 && s[1] <= 1e-12 && s[2] <= 1e-12)) return true;
  }
  return false;
}

TEST(TwistRepair, StackedBorderLayerOfACurledRimIsRemoved) {
  // The ramp's two ends overlap over one segment (4 faces each): each of them is stacked on a
  // face of the other end, all touching the border.
  Mesh m = spiral_ramp(1);
  const Mesh before = m;
  const size_t stacked = twist::count_same_orientation_layers(m, {}, twist::LayerRule::Stacked);
  ASSERT_GE(stacked, 8u) << "both ends' overlapping faces";
  const twist::StackedLayerReport r = twist::remove_stacked_layers(m);
  EXPECT_EQ(r.pairs_before, stacked);
  EXPECT_EQ(r.pairs_after, 0u);
  EXPECT_EQ(twist::count_same_orientation_layers(m, {}, twist::LayerRule::Stacked), 0u);
  EXPECT_GE(r.faces_removed, 4u);
  EXPECT_LE(r.faces_removed, 8u) << "no more than the overlap";
  const edgefront::MeshStats st = edgefront::compute_stats(m);
  EXPECT_EQ(st.components, 1u);
  EXPECT_EQ(st.nonmanifold_vertices, 0u);
  EXPECT_EQ(st.border_loops, 1u);
  // No hole where the layers overlapped: every face centroid of the ramp (in plan) is still
  // covered by a face.
  for (FaceHandle f : before.faces()) {
    const Vec3 c = before.calc_face_centroid(f);
    EXPECT_TRUE(covered_in_plan(m, c[0], c[1])) << "uncovered at (" << c[0] << ", " << c[1] << ")";
  }
  // Rounds: the same result with more of them; the input without a curl is left as it is.
  Mesh again = before;
  twist::StackedLayerOptions o;
  o.rounds = 16;
  EXPECT_EQ(twist::remove_stacked_layers(again, o).faces_removed, r.faces_removed);
  Mesh flat = spiral_ramp(0);
  const twist::StackedLayerReport none = twist::remove_stacked_layers(flat);
  EXPECT_EQ(none.pairs_before, 0u);
  EXPECT_EQ(none.faces_removed, 0u);
  EXPECT_EQ(flat.n_faces(), 96u);
}

TEST(TwistRepair, PairsRestrictedToFacesAreThoseOfTheWholeScan) {
  // `same_orientation_pairs` with `restrict_to`: exactly the pairs of the whole scan in which the
  // face or its partner is one of the given faces (the flap peeling and the turned-patch
  // dropping look only around their candidates).
  const Mesh m = spiral_ramp(1);
  for (twist::LayerRule rule : {twist::LayerRule::Facing, twist::LayerRule::Stacked}) {
    const auto all = twist::same_orientation_pairs(m, {}, rule);
    ASSERT_GE(all.size(), 8u);
    // A face half a turn from the overlap (in no pair) and the first face of the first pair.
    const FaceHandle middle(static_cast<int>(m.n_faces() / 2));
    for (const auto& p : all) ASSERT_TRUE(p.first != middle && p.second != middle);
    const std::vector<FaceHandle> some{middle, all.front().first};
    twist::DetectOptions o;
    o.incremental.restrict_to = some;
    std::vector<std::pair<FaceHandle, FaceHandle>> expected;
    for (const auto& p : all) {
      if (std::find(some.begin(), some.end(), p.first) != some.end() || std::find(some.begin(), some.end(), p.second) != some.end()) {
        expected.push_back(p);
      }
    }
    ASSERT_GE(expected.size(), 1u);
    ASSERT_LT(expected.size(), all.size());
    EXPECT_EQ(twist::same_orientation_pairs(m, o, rule), expected);
    o.incremental.restrict_to = std::vector<FaceHandle>{middle};
    EXPECT_TRUE(twist::same_orientation_pairs(m, o, rule).empty());
    o.incremental.restrict_to = std::vector<FaceHandle>{FaceHandle(static_cast<int>(m.n_faces()))};
    EXPECT_THROW(twist::same_orientation_pairs(m, o, rule), InvalidInput);
  }
}

TEST(TwistRepair, StackedLayersOfALargeOverlapOrAClosedMeshAreLeft) {
  // Six overlapping segments (24 faces per end): a layer that large is not a curled rim.
  Mesh m = spiral_ramp(6);
  const size_t stacked = twist::count_same_orientation_layers(m, {}, twist::LayerRule::Stacked);
  ASSERT_GE(stacked, 40u);
  const twist::StackedLayerReport r = twist::remove_stacked_layers(m);
  EXPECT_EQ(r.faces_removed, 0u);
  EXPECT_EQ(r.pairs_after, stacked);
  twist::StackedLayerOptions o;
  o.max_group_faces = 1000;
  EXPECT_GT(twist::remove_stacked_layers(m, o).faces_removed, 0u) << "unless the group limit allows it";
  // A closed twisted tube has stacked layers but no border: nothing to remove, and no scan.
  twist::TwistedShape tube = twist::twisted_tube();
  ASSERT_GT(twist::count_same_orientation_layers(tube.mesh, {}, twist::LayerRule::Stacked), 0u);
  const size_t faces = tube.mesh.n_faces();
  const twist::StackedLayerReport closed = twist::remove_stacked_layers(tube.mesh);
  EXPECT_EQ(closed.faces_removed, 0u);
  EXPECT_EQ(tube.mesh.n_faces(), faces);
}

TEST(TwistRepair, PleatAroundAnOpenTubeIsSmoothedFlat) {
  // An open tube along x (radius 1, 12 segments around) with a Z fold all around: the rings at
  // x = 0, 1, 2, 3, then back to x = 2 (radius 1.03), then x = 3, 4, 5, 6 (radius 1.06). The
  // tube's faces over 2 <= x <= 3 and the wider ones above them face out, stacked; the band
  // between them faces in. The borders are the tube's ends, far from the fold.
  constexpr int kAround = 12;
  const double xs[] = {0, 1, 2, 3, 2, 3, 4, 5, 6};
  const double rs[] = {1, 1, 1, 1, 1.03, 1.06, 1.06, 1.06, 1.06};
  Mesh m;
  std::vector<Mesh::VertexHandle> v;
  for (int i = 0; i < 9; ++i) {
    for (int k = 0; k < kAround; ++k) {
      const double a = 2 * std::numbers::pi * k / kAround;
      v.push_back(m.add_vertex(Vec3(xs[i], rs[i] * std::cos(a), rs[i] * std::sin(a))));
    }
  }
  const auto at = [&](int i, int k) { return v[static_cast<size_t>(i * kAround + k % kAround)]; };
  for (int i = 0; i < 8; ++i) {
    for (int k = 0; k < kAround; ++k) {
      m.add_face(at(i, k), at(i, k + 1), at(i + 1, k + 1));
      m.add_face(at(i, k), at(i + 1, k + 1), at(i + 1, k));
    }
  }
  auto inward = [](const Mesh& mesh) {
    size_t n = 0;
    for (FaceHandle f : mesh.faces()) {
      const Vec3 c = mesh.calc_face_centroid(f);
      n += OpenMesh::dot(mesh.calc_face_normal(f), Vec3(0, c[1], c[2])) < 0;
    }
    return n;
  };
  ASSERT_EQ(inward(m), 2u * kAround) << "the turned band";
  const size_t stacked = twist::count_same_orientation_layers(m, {}, twist::LayerRule::Stacked);
  ASSERT_GE(stacked, 4u * kAround) << "both outward layers over the band";
  Mesh kept = m;
  EXPECT_EQ(twist::remove_stacked_layers(kept).pleats_flattened, 0u) << "a fold all around is no small pleat";
  EXPECT_EQ(inward(kept), 2u * kAround);
  twist::StackedLayerOptions o;
  o.max_group_faces = 1000;
  const twist::StackedLayerReport r = twist::remove_stacked_layers(m, o);
  EXPECT_EQ(r.faces_removed, 0u) << "no face of the pairs touches a border";
  EXPECT_GT(r.pleats_flattened, 0u);
  EXPECT_EQ(r.pairs_after, 0u);
  EXPECT_EQ(twist::count_same_orientation_layers(m, {}, twist::LayerRule::Stacked), 0u);
  EXPECT_EQ(inward(m), 0u) << "the band turned out with its neighbours";
  const edgefront::MeshStats st = edgefront::compute_stats(m);
  EXPECT_EQ(st.faces, 16u * kAround);
  EXPECT_EQ(st.degenerate_faces, 0u);
  EXPECT_EQ(st.border_loops, 2u);
}

TEST(TwistRepair, FaceTurnedOverItsOwnStarIsStraightenedAlone) {
  // The slab's top plate (z = 0.5, facing up) with its vertex (3, 3) pushed across the edge
  // (4, 3)-(4, 4) of its star and down to z = 0.3: one face turns over (facing down, like the
  // bottom plate under it: a stacked same-orientation pair, no face on a border; two of its
  // edges fold against its neighbours) and tucks under its neighbour across that edge, which
  // then lies right behind it facing the other way, so the pleat smoothing of both layers is
  // refused (the interleaved-walls guard). The turned face is straightened alone: the bottom
  // plate does not move (vault shell t/R 0.1 at 1500 vertices, seed 1, repair: one face of the
  // outer wall turned over onto the inner one).
  Slab s = slab();
  s.mesh.set_point(s.top[3 * 7 + 3], Vec3(4.4, 3.5, 0.3));
  ASSERT_EQ(turned_top_faces(s.mesh).size(), 1u);
  const FaceHandle turned = turned_top_faces(s.mesh).front();
  const size_t stacked = twist::count_same_orientation_layers(s.mesh, {}, twist::LayerRule::Stacked);
  ASSERT_GE(stacked, 2u) << "the turned face and the bottom face under it";
  // Right behind the turned face (from its centroid up through the top plate) lies the face
  // across its moved edge, facing up.
  const Vec3 c = s.mesh.calc_face_centroid(turned);
  bool tucked = false;
  for (FaceHandle h : s.mesh.faces()) {
    if (h == turned || s.mesh.calc_face_normal(h)[2] < 0.9) continue;
    std::vector<Vec3> p;
    for (auto v : s.mesh.fv_range(h)) p.push_back(s.mesh.point(v));
    auto side = [&](const Vec3& a, const Vec3& b) { return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]); };
    tucked = tucked || (side(p[0], p[1]) > 0 && side(p[1], p[2]) > 0 && side(p[2], p[0]) > 0 && c[2] < p[0][2]);
  }
  ASSERT_TRUE(tucked);
  std::vector<Vec3> bottom;
  for (int i = 0; i < 49; ++i) bottom.push_back(s.mesh.point(Mesh::VertexHandle(i)));
  const twist::StackedLayerReport r = twist::remove_stacked_layers(s.mesh);
  EXPECT_EQ(r.pairs_before, stacked);
  EXPECT_GE(r.pleats_flattened, 1u);
  EXPECT_EQ(r.faces_removed, 0u);
  EXPECT_EQ(r.pairs_after, 0u);
  EXPECT_EQ(twist::count_same_orientation_layers(s.mesh, {}, twist::LayerRule::Stacked), 0u);
  EXPECT_TRUE(turned_top_faces(s.mesh).empty()) << "the face turned back with its neighbours";
  for (int i = 0; i < 49; ++i) EXPECT_EQ(s.mesh.point(Mesh::VertexHandle(i)), bottom[static_cast<size_t>(i)]) << "bottom vertex " << i;
  const edgefront::MeshStats st = edgefront::compute_stats(s.mesh);
  EXPECT_EQ(st.faces, 144u);
  EXPECT_EQ(st.degenerate_faces, 0u);
  EXPECT_EQ(st.border_loops, 2u);
}

TEST(TwistRepair, StackedLayerRemovalRejectsBadOptions) {
  Mesh m = spiral_ramp(1);
  Mesh empty;
  EXPECT_THROW(twist::remove_stacked_layers(empty), InvalidInput);
  twist::StackedLayerOptions o;
  for (int rounds : {0, 17, -1}) {
    o.rounds = rounds;
    EXPECT_THROW(twist::remove_stacked_layers(m, o), InvalidInput) << rounds;
  }
  o = {};
  for (size_t group : {size_t{0}, size_t{1001}}) {
    o.max_group_faces = group;
    EXPECT_THROW(twist::remove_stacked_layers(m, o), InvalidInput) << group;
  }
  o = {};
  o.min_component_faces = 0;
  EXPECT_THROW(twist::remove_stacked_layers(m, o), InvalidInput);
  o = {};
  o.detect.experimental.surface_factor = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(twist::remove_stacked_layers(m, o), InvalidInput);
  Mesh nan = spiral_ramp(1);
  nan.set_point(*nan.vertices().begin(), Vec3(std::numeric_limits<double>::quiet_NaN(), 0, 0));
  EXPECT_THROW(twist::remove_stacked_layers(nan), InvalidInput);
  EXPECT_EQ(m.n_faces(), 100u) << "a refused call changes nothing";
}

TEST(TwistRepair, BadInputThrowsNamingTheProblem) {
  Mesh empty;
  EXPECT_THROW(twist::repair(empty), InvalidInput);
  Mesh m = edgefront::shapes::icosphere(1);
  twist::RepairOptions o;
  o.max_repairs = 0;
  try {
    twist::repair(m, o);
    FAIL() << "no exception";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("max_repairs"), std::string::npos) << e.what();
  }
  // A grouped option is named with its group, as the caller writes it.
  auto expect_named = [&](const twist::RepairOptions& bad, const std::string& name) {
    try {
      twist::repair(m, bad);
      ADD_FAILURE() << "no exception for " << name;
    } catch (const InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  };
  o = {};
  o.cuts.min_component_faces = 0;
  expect_named(o, "cuts.min_component_faces");
  o = {};
  o.experimental.peel_flaps = 17;
  expect_named(o, "experimental.peel_flaps");
  o = {};
  o.detect.regions.grow_levels = 100;
  expect_named(o, "regions.grow_levels");
  EXPECT_THROW(twist::orient_soup({Vec3(0, 0, 0)}, {}), InvalidInput);
  EXPECT_THROW(twist::orient_soup({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}, {{0, 1, 3}}), InvalidInput);
  EXPECT_THROW(twist::orient_soup({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}, {{0, 1, 1}}), InvalidInput);
}

}  // namespace
