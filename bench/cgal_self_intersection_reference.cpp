// cgal_self_intersection_reference: gcs::count_self_intersections against CGAL's
// Polygon_mesh_processing::self_intersections (exact predicates) on the same meshes.
//
//   cgal_self_intersection_reference [MESH...] [--repeats R]
//
// Each mesh is read with edgefront::read_mesh and copied face by face into a CGAL::Surface_mesh
// (same vertices, same triangles). Generated cases come first: two interpenetrating icospheres
// (subdivision 3, centres 0.8 apart) in one mesh, and edgefront::shapes meshes at resolution 64:
// torus, a thin vault shell (thickness 0.02), grid, hairpin, Möbius strip, bumpy sphere (s = 6). Prints one
// markdown row per mesh: faces, both pair counts, whether they agree, and the best of R (default 3) times of
// each. Exit codes: 0 done (also when the counts differ: it is a measurement), 1 error, 2 usage.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include "bench_timing.h"
#include "edgefront/mesh_io.h"
#include "shapes/shapes.h"
#include "gcs/evaluation.h"

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using SurfaceMesh = CGAL::Surface_mesh<Kernel::Point_3>;

SurfaceMesh to_cgal(const edgefront::Mesh& mesh) {
  SurfaceMesh sm;
  std::vector<SurfaceMesh::Vertex_index> map(mesh.n_vertices());
  for (const auto v : mesh.vertices()) {
    const edgefront::Vec3& p = mesh.point(v);
    map[static_cast<std::size_t>(v.idx())] = sm.add_vertex(Kernel::Point_3(p[0], p[1], p[2]));
  }
  for (const auto f : mesh.faces()) {
    std::vector<SurfaceMesh::Vertex_index> fv;
    for (const auto v : mesh.fv_range(f)) fv.push_back(map[static_cast<std::size_t>(v.idx())]);
    if (sm.add_face(fv) == SurfaceMesh::null_face()) throw std::runtime_error("CGAL refused a face");
  }
  return sm;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> files;
  int repeats = 3;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--repeats" && i + 1 < argc) {
      repeats = std::atoi(argv[++i]);
      if (repeats < 1) {
        std::cerr << "cgal_self_intersection_reference: error: --repeats must be >= 1\n";
        return 2;
      }
    } else if (!arg.empty() && arg[0] == '-') {
      std::cerr << "usage: cgal_self_intersection_reference [MESH...] [--repeats R]\n";
      return 2;
    } else {
      files.push_back(arg);
    }
  }
  try {
    namespace shapes = edgefront::shapes;
    std::vector<std::pair<std::string, edgefront::Mesh>> cases;
    {
      edgefront::Mesh two = shapes::icosphere(3);
      const edgefront::Mesh other = shapes::icosphere(3);
      std::vector<edgefront::VertexHandle> map;
      for (const auto v : other.vertices())
        map.push_back(two.add_vertex(other.point(v) + edgefront::Vec3(0.8, 0, 0)));
      for (const auto f : other.faces()) {
        std::vector<edgefront::VertexHandle> fv;
        for (const auto v : other.fv_range(f)) fv.push_back(map[static_cast<std::size_t>(v.idx())]);
        two.add_face(fv);
      }
      cases.emplace_back("two interpenetrating icospheres", std::move(two));
    }
    for (const char* name : {"torus", "vault-shell", "grid", "hairpin", "mobius"}) {
      shapes::MeshOptions o;
      o.resolution = 64;
      o.shape.thickness = 0.02;
      cases.emplace_back(std::string(name) + " (shapes, 64)", shapes::make(name, o));
    }
    cases.emplace_back("bumpy sphere (s = 6)", shapes::bumpy_sphere(6));
    for (const std::string& file : files) cases.emplace_back(file, edgefront::load_mesh(file));

    std::cout << "| mesh | faces | CGAL pairs | gcs pairs | agree | CGAL time | gcs time | CGAL / gcs |\n";
    std::cout << "|---|---|---|---|---|---|---|---|\n";
    for (const auto& [file, mesh] : cases) {
      const SurfaceMesh sm = to_cgal(mesh);
      std::size_t cgal_pairs = 0, gcs_pairs = 0;
      const double t_cgal = efbench::best_seconds(repeats, [&] {
        std::vector<std::pair<SurfaceMesh::Face_index, SurfaceMesh::Face_index>> pairs;
        CGAL::Polygon_mesh_processing::self_intersections(sm, std::back_inserter(pairs));
        cgal_pairs = pairs.size();
      });
      const double t_gcs =
          efbench::best_seconds(repeats, [&] { gcs_pairs = gcs::count_self_intersections(mesh); });
      std::cout << "| " << file << " | " << mesh.n_faces() << " | " << cgal_pairs << " | " << gcs_pairs
                << " | " << (cgal_pairs == gcs_pairs ? "yes" : "**no**") << " | " << t_cgal << " s | "
                << t_gcs << " s | " << t_cgal / t_gcs << " |\n";
    }
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "cgal_self_intersection_reference: error: " << e.what() << "\n";
    return 1;
  }
}
