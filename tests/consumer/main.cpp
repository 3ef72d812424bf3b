// Uses an installed EdgeFront: builds a tetrahedron with edgefront::Mesh, prints its counts, and
// exits non-zero if they are wrong. Built and run by .ci/run against `cmake --install`.
#include <cstdio>

#include "edgefront/error.h"
#include "edgefront/mesh.h"

int main() {
  edgefront::Mesh mesh;
  const edgefront::VertexHandle v[4] = {
      mesh.add_vertex({0.0, 0.0, 0.0}),
      mesh.add_vertex({1.0, 0.0, 0.0}),
      mesh.add_vertex({0.0, 1.0, 0.0}),
      mesh.add_vertex({0.0, 0.0, 1.0}),
  };
  mesh.add_face(v[0], v[2], v[1]);
  mesh.add_face(v[0], v[1], v[3]);
  mesh.add_face(v[1], v[2], v[3]);
  mesh.add_face(v[2], v[0], v[3]);

  std::printf("EdgeFront %s consumer: tetrahedron with %zu vertices, %zu edges, %zu faces\n",
              EDGEFRONT_VERSION_STRING, mesh.n_vertices(), mesh.n_edges(), mesh.n_faces());

  // Something compiled into libedgefront, so the link against the installed archive is exercised.
  try {
    EF_CHECK(mesh.n_vertices() == 4 && mesh.n_edges() == 6 && mesh.n_faces() == 4,
             "a tetrahedron has 4 vertices, 6 edges and 4 faces");
  } catch (const edgefront::InternalError& e) {
    std::fprintf(stderr, "edgefront_consumer: %s\n", e.what());
    return 1;
  }
  return 0;
}
