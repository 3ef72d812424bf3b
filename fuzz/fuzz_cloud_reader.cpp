// libFuzzer harness of the point-cloud reader: every input is parsed as XYZ, PLY, OFF and OBJ
// (read_points_from_buffer). The reader may refuse an input only with edgefront::IoError; a
// cloud it accepts has points, all finite and within coordinate_range.h's range, and no normals
// or one unit normal per point. The mesh and the cloud reader share their checks: an OFF or OBJ
// input the mesh reader refuses is refused by the cloud reader with the same message.
// Anything else aborts, and libFuzzer keeps the input.

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>
#include <string_view>

#include "edgefront/coordinate_range.h"
#include "edgefront/error.h"
#include "edgefront/mesh_io.h"
#include "edgefront/point_cloud_io.h"

namespace {

[[noreturn]] void fail(const char* format, const std::string& what) {
  std::fprintf(stderr, "fuzz_cloud_reader: %s: %s\n", format, what.c_str());
  std::abort();
}

void check(bool ok, const char* format, const char* what) {
  if (!ok) fail(format, what);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  for (const char* name : {"fuzz.xyz", "fuzz.ply", "fuzz.off", "fuzz.obj"}) {
    std::string cloud_error;
    try {
      const edgefront::PointCloud c = edgefront::read_points_from_buffer(bytes, name);
      check(!c.points.empty(), name, "an empty cloud was accepted");
      check(c.normals.empty() || c.normals.size() == c.points.size(), name, "normals do not match the points");
      check(edgefront::coordinate_range_problem(c.points).empty(), name, "a coordinate outside the range");
      for (const edgefront::Vec3& n : c.normals) check(std::abs(n.norm() - 1.0) < 1e-9, name, "a normal not of unit length");
    } catch (const edgefront::IoError& e) {
      cloud_error = e.what();
    } catch (const std::exception& e) {
      fail(name, e.what());
    }
    if (std::strcmp(name, "fuzz.off") != 0 && std::strcmp(name, "fuzz.obj") != 0) continue;
    try {
      edgefront::read_mesh_from_buffer(bytes, name);
    } catch (const edgefront::IoError& e) {
      if (cloud_error != e.what()) fail(name, "the mesh reader says '" + std::string(e.what()) + "', the cloud reader '" + cloud_error + "'");
    } catch (const std::exception& e) {
      fail(name, e.what());
    }
  }
  return 0;
}
