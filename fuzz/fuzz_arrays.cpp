// libFuzzer harness of the array API (edgefront/arrays.h, twist/arrays.h, twist/repair_session.h):
// the bytes become vertex and face arrays as a host would pass them (double or float, int32 or
// int64), with NaN, infinities, huge and tiny values, negative and out-of-range indices and
// repeated corners, then
//   mesh_from_arrays (dropping or refusing faces a half-edge mesh cannot hold),
//   a distance field (every method, maybe bounded), a bounded query and an MEF level field,
//   detect_arrays and repair_arrays, replaying the repair's record on the input arrays,
//   a RepairSession: a batch of edits from the remaining bytes, a repair, the record replayed.
// Allowed refusals: edgefront::InvalidInput (bad arrays, bad options, edits that do not fit) and
// edgefront::TopologyError (what the detector cannot handle). Anything else (another exception,
// InternalError, a crash, a sanitizer report), or a result that breaks its documented contract,
// aborts, and libFuzzer keeps the input.
//
// Input layout (missing bytes read as 0): byte 0 flags, byte 1 vertex count (0-63), byte 2 face
// count (0-127), then per coordinate one byte (a table entry or, for bytes >= 0xf0, 8 raw bytes as a
// double), then per face corner one signed byte (an index, maybe out of range), then the query and
// edit bytes.

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <limits>
#include <string>
#include <vector>

#include "edgefront/arrays.h"
#include "edgefront/error.h"
#include "twist/arrays.h"
#include "twist/repair_session.h"

namespace {

[[noreturn]] void fail(const char* where, const std::string& what) {
  std::fprintf(stderr, "fuzz_arrays: %s: %s\n", where, what.c_str());
  std::abort();
}

void check(bool ok, const char* where, const char* what) {
  if (!ok) fail(where, what);
}

class Bytes {
 public:
  Bytes(const uint8_t* d, size_t n) : d_(d), n_(n) {}
  uint8_t u8() { return i_ < n_ ? d_[i_++] : 0; }
  double raw_double() {
    uint64_t b = 0;
    for (int k = 0; k < 8; ++k) b = (b << 8) | u8();
    double x;
    std::memcpy(&x, &b, sizeof x);
    return x;
  }
  bool empty() const { return i_ >= n_; }

 private:
  const uint8_t* d_;
  size_t n_;
  size_t i_ = 0;
};

double coordinate(Bytes& b) {
  static const double table[] = {0.0, -0.0, 1.0, -1.0, 0.5, 2.0, 1e-310, 1e-300, 1e150, 1e151, 1e308, -1e308,
                                 std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                                 -std::numeric_limits<double>::infinity(), 1e-9};
  const uint8_t c = b.u8();
  if (c >= 0xf0) return b.raw_double();
  if (c < 0x80) return static_cast<double>(c % 16) * 0.25 - 1.0;  // a small grid: shared points, flat parts
  if (c < 0xa0) return table[c % 16];
  return static_cast<double>(static_cast<int>(c) - 0xd0) * 0.03;  // near-coincident values
}

template <class Fn>
void allowed(const char* where, Fn&& fn) {
  try {
    fn();
  } catch (const edgefront::InvalidInput&) {
  } catch (const edgefront::TopologyError&) {
  } catch (const edgefront::InternalError& e) {
    fail(where, std::string("InternalError: ") + e.what());
  } catch (const std::exception& e) {
    fail(where, std::string("unexpected exception: ") + e.what());
  }
}

/// The converted mesh keeps its documented contract.
void check_conversion(const edgefront::ArrayMesh& a, size_t nv, size_t nf) {
  const char* w = "mesh_from_arrays";
  check(a.report.input_vertices == nv && a.report.input_faces == nf, w, "report counts differ from the input");
  check(a.face_of_row.size() == nf, w, "face_of_row has the wrong size");
  check(a.mesh.n_vertices() == nv + a.report.vertex_copies, w, "vertex count is not input + copies");
  check(a.vertex_row.size() == a.mesh.n_vertices(), w, "vertex_row has the wrong size");
  check(a.face_row.size() == a.mesh.n_faces(), w, "face_row has the wrong size");
  check(a.mesh.n_faces() + a.report.dropped_faces.size() == nf, w, "kept + dropped faces differ from the input");
  for (size_t i = 0; i < nv; ++i) check(a.vertex_row[i] == static_cast<int>(i), w, "an input vertex moved");
  for (size_t i = nv; i < a.vertex_row.size(); ++i)
    check(a.vertex_row[i] >= 0 && static_cast<size_t>(a.vertex_row[i]) < nv, w, "a copy names no input vertex");
  for (size_t r = 0; r < nf; ++r) {
    const int f = a.face_of_row[r];
    if (f < 0) continue;
    check(static_cast<size_t>(f) < a.face_row.size() && a.face_row[static_cast<size_t>(f)] == static_cast<int>(r), w,
          "face maps are not inverse");
  }
}

void check_field(const edgefront::DistanceArrays& d, size_t nv, int source, const char* w) {
  check(d.distance.size() == nv, w, "distance array has the wrong size");
  check(d.distance[static_cast<size_t>(source)] == 0.0, w, "the source's distance is not 0");
  for (double x : d.distance) check(x >= 0 && !std::isnan(x), w, "a negative or NaN distance");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  Bytes b(data, size);
  const uint8_t flags = b.u8();
  const size_t nv = b.u8() % 64, nf = b.u8() % 128;
  const bool as_float = flags & 1, as_int64 = flags & 2, refuse = flags & 4;
  std::vector<double> Vd(3 * nv);
  for (double& x : Vd) x = coordinate(b);
  std::vector<float> Vf(Vd.begin(), Vd.end());
  std::vector<std::int32_t> F32(3 * nf);
  for (std::int32_t& i : F32) i = static_cast<int8_t>(b.u8());
  std::vector<std::int64_t> F64(F32.begin(), F32.end());
  if (as_int64 && !F64.empty() && (flags & 8)) F64[0] += std::int64_t{1} << 40;  // beyond int
  const edgefront::VertexArrayView V = as_float ? edgefront::VertexArrayView(Vf) : edgefront::VertexArrayView(Vd);
  const edgefront::FaceArrayView F = as_int64 ? edgefront::FaceArrayView(F64) : edgefront::FaceArrayView(F32);
  edgefront::ConversionOptions conv;
  conv.drop_nonmanifold_faces = !refuse;

  // 1. The conversion and the queries of the stateless API.
  allowed("conversion", [&] {
    edgefront::ArrayMesh a = edgefront::mesh_from_arrays(V, F, conv);
    check_conversion(a, nv, nf);
    edgefront::GeodesicSolver solver(std::move(a));
    const int source = static_cast<int>(b.u8() % std::max<size_t>(nv, 1));
    edgefront::ArrayDistanceOptions o;
    o.method = static_cast<edgefront::DistanceMethod>(b.u8() % 4);
    const uint8_t bound = b.u8();
    if (bound < 0x40) o.max_distance = bound * 0.05;
    if (bound == 0xff) o.max_distance = -1.0;  // refused
    o.directions = flags & 16;
    allowed("distance_from_vertices", [&] {
      const std::vector<int> src{source};
      check_field(solver.distance_from_vertices(src, o), nv, source, "distance_from_vertices");
    });
    allowed("distances_within", [&] {
      const std::vector<int> src{source};
      const edgefront::SparseDistances s = solver.distances_within(src, 0.05 * (bound % 64));
      check(s.vertex.size() == s.distance.size(), "distances_within", "sizes differ");
      for (size_t i = 0; i + 1 < s.distance.size(); ++i) check(s.distance[i] <= s.distance[i + 1], "distances_within", "not in settling order");
    });
    allowed("distance_between", [&] {
      const int to = static_cast<int>(b.u8() % std::max<size_t>(nv, 1));
      const std::optional<double> d = solver.distance_between(source, to, 0.1 * (bound % 32));
      check(!d || (*d >= 0 && *d <= 0.1 * (bound % 32) + 1e-9), "distance_between", "a distance beyond the bound");
    });
    allowed("levels", [&] {
      const std::vector<int> src{source};
      check(solver.levels(src, bound % 8).size() == nv, "levels", "level array has the wrong size");
    });
  });

  // 2. Detection and the one-shot repair; the record replays on the input arrays.
  twist::DetectOptions det;
  det.self_intersections = flags & 32;
  allowed("detect_arrays", [&] {
    const twist::ArrayDetection d = twist::detect_arrays(V, F, det);
    check(d.face_region.size() == nf, "detect_arrays", "face_region has the wrong size");
  });
  allowed("repair_arrays", [&] {
    twist::RepairOptions ro;
    ro.detect = det;
    const twist::ArrayRepair r = twist::repair_arrays(V, F, ro);
    check(r.record.vertices_before == nv && r.record.faces_before == nf, "repair_arrays", "record index spaces differ from the input");
    std::vector<double> hv(Vd);
    std::vector<int> hf(F32.begin(), F32.end());
    try {
      twist::apply(r.record, hv, hf);
    } catch (const std::exception& e) {
      fail("repair_arrays", std::string("its record does not replay on the input: ") + e.what());
    }
    check(hv.size() == 3 * r.record.vertices_after() && hf.size() == 3 * r.record.faces_after(), "repair_arrays", "replay sizes");
  });

  // 3. A session: created from the arrays, one batch of edits, a repair, the record replayed.
  if (flags & 64) {
    allowed("session", [&] {
      twist::RepairSession s(V, F);
      std::vector<double> hv(Vd);
      std::vector<int> hf(F32.begin(), F32.end());
      twist::apply(s.initial_record(), hv, hf);
      const size_t edits = b.u8() % 8;
      for (size_t i = 0; i < edits; ++i) {
        const uint8_t kind = b.u8();
        const int index = static_cast<int8_t>(b.u8());
        allowed("session edit", [&] {
          switch (kind % 4) {
            case 0: s.set_vertex(index, {coordinate(b), coordinate(b), coordinate(b)}); break;
            case 1: s.set_face(index, {static_cast<int8_t>(b.u8()), static_cast<int8_t>(b.u8()), static_cast<int8_t>(b.u8())}); break;
            case 2: s.remove_face(index); break;
            default: s.remove_vertex(index); break;
          }
        });
      }
      // A refused batch changes nothing and is not half-applied (the session says so): the host
      // then replays nothing. An accepted one must replay on the host's arrays as they are.
      twist::EditRecord r;
      try {
        r = (flags & 128) ? s.repair() : s.sync();
      } catch (const edgefront::InvalidInput&) {
        check(!s.pending(), "session", "a refused batch left edits behind");
        return;
      }
      // The record is on the session's state after the batch: its index spaces are the session's.
      check(r.vertices_after() == s.vertex_slots() && r.faces_after() == s.face_slots(), "session",
            "record index spaces differ from the session's");
    });
  }
  return 0;
}
