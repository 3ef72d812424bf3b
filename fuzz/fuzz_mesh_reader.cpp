// libFuzzer harness of the mesh reader: every input is parsed as OFF, OBJ, PLY and STL
// (read_mesh_from_buffer). The reader may refuse an input only with edgefront::IoError; a mesh
// it accepts must keep its promises: the report's counts match the mesh, every coordinate is
// finite and within coordinate_range.h's range, every face names three distinct live vertices.
// Anything else aborts, and libFuzzer keeps the input.

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string_view>

#include "edgefront/coordinate_range.h"
#include "edgefront/error.h"
#include "edgefront/mesh_io.h"

namespace {

[[noreturn]] void fail(const char* format, const char* what) {
  std::fprintf(stderr, "fuzz_mesh_reader: %s: %s\n", format, what);
  std::abort();
}

void check(bool ok, const char* format, const char* what) {
  if (!ok) fail(format, what);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  for (const char* name : {"fuzz.off", "fuzz.obj", "fuzz.ply", "fuzz.stl"}) {
    try {
      const edgefront::MeshReadResult r = edgefront::read_mesh_from_buffer(bytes, name);
      const edgefront::Mesh& m = r.mesh;
      // The file's vertices, then one copy per extra fan of each pinched vertex.
      check(m.n_vertices() == r.report.vertices + r.report.vertex_copies, name,
            "vertex count differs from the report");
      check((r.report.pinched_vertices == 0) == (r.report.vertex_copies == 0), name,
            "pinched vertices and their copies disagree");
      check(m.n_faces() == r.report.triangles_added, name, "face count differs from the report");
      check(edgefront::coordinate_range_problem(m).empty(), name, "a coordinate outside the range");
      for (const auto f : m.faces()) {
        int idx[3], k = 0;
        for (const auto v : m.fv_range(f)) idx[k++] = v.idx();
        check(k == 3 && idx[0] != idx[1] && idx[1] != idx[2] && idx[0] != idx[2], name, "a bad face");
      }
    } catch (const edgefront::IoError&) {
      // refused with a message: fine
    } catch (const std::exception& e) {
      fail(name, e.what());
    }
  }
  return 0;
}
