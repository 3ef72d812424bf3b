// Uses an installed EdgeFront the way an embedding reconstructor would: a mesh, a geodesic field,
// a point index, a small GCS reconstruction with the twist repair registered, a twist check and
// an offscreen picture. Exits non-zero on the first wrong answer. Built and run by .ci/run
// against `cmake --install`.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <vector>

#include "edgefront/arrays.h"
#include "edgefront/error.h"
#include "edgefront/mesh.h"
#include "edgefront/mesh_stats.h"
#include "edgefront/minimal_distance_front.h"
#include "edgefront/point_index.h"
#include "shapes/shapes.h"
#include "gcs/reconstructor.h"
#include "gcs/twist_operation.h"
#include "render/render.h"
#include "twist/arrays.h"
#include "twist/detect.h"
#include "twist/repair_session.h"

namespace {

int failures = 0;

void check(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "edgefront_consumer: FAILED: %s\n", what);
    ++failures;
  }
}

}  // namespace

int main() {
  try {
    // 1. A mesh built by hand.
    edgefront::Mesh tet;
    const edgefront::VertexHandle v[4] = {tet.add_vertex({0.0, 0.0, 0.0}), tet.add_vertex({1.0, 0.0, 0.0}),
                                          tet.add_vertex({0.0, 1.0, 0.0}), tet.add_vertex({0.0, 0.0, 1.0})};
    tet.add_face(v[0], v[2], v[1]);
    tet.add_face(v[0], v[1], v[3]);
    tet.add_face(v[1], v[2], v[3]);
    tet.add_face(v[2], v[0], v[3]);
    std::printf("EdgeFront %s consumer: tetrahedron with %zu vertices, %zu edges, %zu faces\n",
                EDGEFRONT_VERSION_STRING, tet.n_vertices(), tet.n_edges(), tet.n_faces());
    check(tet.n_vertices() == 4 && tet.n_edges() == 6 && tet.n_faces() == 4, "tetrahedron counts");

    // 2. Geodesic distance on the unit sphere: the antipode of a vertex is pi away.
    const edgefront::Mesh sphere = edgefront::shapes::icosphere(3);
    const edgefront::VertexHandle s0(0);
    const edgefront::DistanceField field = edgefront::geodesic_distance(sphere, edgefront::FrontSource::vertex(s0));
    double far = 0;
    for (double d : field.distance) far = std::max(far, d);
    std::printf("geodesic: farthest vertex of the icosphere at %.4f (pi = %.4f)\n", far, std::numbers::pi);
    check(std::abs(far - std::numbers::pi) < 0.03 * std::numbers::pi, "geodesic distance to the antipode");

    // 3. Point index.
    std::vector<edgefront::Vec3> pts;
    for (auto vh : sphere.vertices()) pts.push_back(sphere.point(vh));
    const edgefront::PointIndex index(pts);
    check(index.nearest(pts[17] * 1.01).index == 17, "nearest point");

    // 4. A GCS reconstruction with the twist repair registered as an operation.
    edgefront::shapes::SampleOptions so;
    so.points = 3000;
    gcs::ReconstructOptions ro;
    ro.target_vertices = 300;
    gcs::Reconstructor rec(edgefront::shapes::sample("icosphere", so), ro);
    rec.add_operation(std::make_shared<gcs::TwistOperation>());
    const gcs::ReconstructResult result = rec.run();
    const edgefront::MeshStats stats = edgefront::compute_stats(result.mesh);
    std::printf("gcs: %zu vertices, %zu faces, %zu component(s), %zu border loop(s), %s\n", result.mesh.n_vertices(),
                result.mesh.n_faces(), stats.components, stats.border_loops, gcs::to_string(result.stop_reason).c_str());
    check(result.mesh.n_vertices() >= 250 && result.mesh.n_faces() > 0, "reconstruction size");

    // 5. Twist detection on a correct mesh finds nothing.
    check(twist::detect(sphere).empty(), "no twisted region on a sphere");

    // 6. An offscreen picture with the field.
    edgefront::render::Scene scene;
    scene.mesh = &sphere;
    scene.field = edgefront::render::ScalarField{.values = field.distance};
    edgefront::render::RenderOptions opts;
    opts.width = 64;
    opts.height = 48;
    const edgefront::render::Image image = edgefront::render::render(scene, opts);
    check(image.width == 64 && image.height == 48 && image.rgb.size() == 64u * 48u * 3u, "rendered image size");

    // 7. The array API: a host's plain arrays in, distances and an edit record out.
    const edgefront::MeshArrays arrays = edgefront::mesh_to_arrays(sphere);
    edgefront::GeodesicSolver solver(arrays.vertices, arrays.faces);
    const edgefront::DistanceArrays d = solver.distance_from_vertices(std::vector<int>{0});
    check(d.distance.size() == arrays.n_vertices() && d.distance[0] == 0.0, "array distances");
    check(std::abs(*std::max_element(d.distance.begin(), d.distance.end()) - far) < 1e-12, "array distances = mesh distances");
    twist::RepairSession session(arrays.vertices, arrays.faces);
    check(session.initial_record().empty() && session.repair().empty(), "a sphere needs no repair");
    const twist::ArrayRepair repaired = twist::repair_arrays(arrays.vertices, arrays.faces);
    std::vector<double> V = arrays.vertices;
    std::vector<int> F = arrays.faces;
    twist::apply(repaired.record, V, F);
    check(F == arrays.faces, "the record of a clean sphere changes no face");
  } catch (const edgefront::Error& e) {
    std::fprintf(stderr, "edgefront_consumer: %s\n", e.what());
    return 1;
  }
  if (failures) return 1;
  std::printf("edgefront_consumer: all checks passed\n");
  return 0;
}
