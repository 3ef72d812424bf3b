// Geodesic distances, paths and front levels (edgefront/arrays.h) for Python.

#include <pybind11/stl.h>

#include <chrono>
#include <exception>
#include <cstdint>
#include <limits>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bindings.h"
#include "convert.h"
#include "edgefront/arrays.h"
#include "edgefront/batch_distance.h"
#include "edgefront/error.h"

namespace efpy {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Sources: vertex indices, or surface points (face rows and barycentric coordinates).
struct Sources {
  std::vector<int> vertices;
  std::vector<int> faces;
  std::vector<double> bary;
  bool points = false;
};

Sources parse_sources(const py::handle& obj) {
  Sources s;
  if ((py::isinstance<py::tuple>(obj) || py::isinstance<py::list>(obj)) && py::len(obj) == 2) {
    py::sequence seq = py::reinterpret_borrow<py::sequence>(obj);
    py::array second = py::module_::import("numpy").attr("asarray")(seq[1]);
    const bool float_kind = second.dtype().kind() == 'f';
    const bool many = second.ndim() == 2;
    const bool one = second.ndim() == 1 && second.shape(0) == 3 && float_kind &&
                     py::module_::import("numpy").attr("ndim")(seq[0]).cast<int>() == 0;
    if (many || one) {
      s.points = true;
      s.faces = index_list(seq[0], "sources faces");
      py::array_t<double> b = py::module_::import("numpy").attr("ascontiguousarray")(second, "float64");
      if (!float_kind && second.dtype().kind() != 'i') {
        throw py::value_error("sources barycentric coordinates must be numbers, got dtype " +
                              py::str(second.dtype()).cast<std::string>());
      }
      if ((many && second.shape(1) != 3) || (many && static_cast<size_t>(second.shape(0)) != s.faces.size())) {
        throw py::value_error("sources: (faces, barycentric) needs barycentric of shape (k, 3) for k faces");
      }
      s.bary.assign(b.data(), b.data() + b.size());
      return s;
    }
  }
  s.vertices = index_list(obj, "sources");
  return s;
}

edgefront::ArrayDistanceOptions distance_options(const std::string& method, double max_distance) {
  edgefront::ArrayDistanceOptions o;
  o.method = edgefront::parse_distance_method(method);
  o.max_distance = max_distance;
  return o;
}

py::array_t<double> field(const edgefront::GeodesicSolver& solver, const py::handle& sources, const std::string& method,
                          double max_distance) {
  const Sources s = parse_sources(sources);
  const edgefront::ArrayDistanceOptions o = distance_options(method, max_distance);
  edgefront::DistanceArrays d;
  {
    py::gil_scoped_release release;
    d = s.points ? solver.distance_from_points(s.faces, s.bary, o) : solver.distance_from_vertices(s.vertices, o);
  }
  return to_numpy(std::move(d.distance));
}

// The input-vertex positions of a vertex chain.
py::array_t<double> chain_points(const edgefront::GeodesicSolver& solver, const std::vector<int>& chain) {
  std::vector<double> p;
  p.reserve(3 * chain.size());
  const edgefront::Mesh& mesh = solver.converted().mesh;
  for (const int v : chain) {
    const edgefront::Vec3 q = mesh.point(edgefront::VertexHandle(v));
    p.insert(p.end(), {q[0], q[1], q[2]});
  }
  return to_numpy_rows(std::move(p));
}

/// The library's solver with a lock for its non-const queries (their buffers are shared); the
/// const field queries run concurrently from several Python threads with the GIL released.
class PySolver {
 public:
  PySolver(const py::handle& V, const py::handle& F) : solver_(make(V, F)) {}

  size_t n_vertices() const { return solver_.n_vertices(); }
  size_t n_faces() const { return solver_.n_faces(); }
  size_t dropped_faces() const { return solver_.converted().report.dropped_faces.size(); }

  py::array_t<double> distance(const py::handle& sources, const std::string& method, double max_distance) const {
    return field(solver_, sources, method, max_distance);
  }

  py::tuple within(const py::handle& sources, double max_distance, const std::string& method) {
    const std::vector<int> s = index_list(sources, "sources");
    const edgefront::DistanceMethod m = edgefront::parse_distance_method(method);
    edgefront::SparseDistances d;
    {
      py::gil_scoped_release release;
      std::lock_guard<std::mutex> lock(mutex_);
      d = solver_.distances_within(s, max_distance, m);
    }
    return py::make_tuple(to_numpy(std::move(d.vertex)), to_numpy(std::move(d.distance)));
  }

  py::array_t<double> batch(const py::handle& sources, const py::handle& targets, const std::string& method,
                            double max_distance, unsigned threads, const py::object& progress) const {
    const std::vector<int> s = index_list(sources, "sources");
    const std::vector<int> t = targets.is_none() ? std::vector<int>() : index_list(targets, "targets");
    edgefront::ArrayBatchOptions o;
    o.method = edgefront::parse_distance_method(method);
    o.max_distance = max_distance;
    edgefront::BatchOptions b;
    b.threads = threads;
    // The callback runs on the worker threads, one call at a time: it takes the GIL for the call.
    // An exception in it cancels the batch and is raised here.
    std::exception_ptr raised;
    if (!progress.is_none()) {
      b.progress = [&progress, &raised](std::size_t done, std::size_t total) {
        py::gil_scoped_acquire acquire;
        try {
          const py::object r = progress(done, total);
          return r.is_none() || r.cast<bool>();
        } catch (...) {
          raised = std::current_exception();
          return false;
        }
      };
    }
    edgefront::DistanceMatrix d;
    {
      py::gil_scoped_release release;
      d = edgefront::geodesic_distances(solver_, s, t, o, b);
    }
    if (raised) std::rethrow_exception(raised);
    const auto rows = static_cast<py::ssize_t>(d.rows), cols = static_cast<py::ssize_t>(d.columns);
    return to_numpy<double>(std::move(d.values), {rows, cols});
  }

  std::optional<double> between(int a, int b, double max_distance) {
    py::gil_scoped_release release;
    std::lock_guard<std::mutex> lock(mutex_);
    return solver_.distance_between(a, b, max_distance);
  }

  py::array_t<int> levels(const py::handle& sources, int max_levels) const {
    const std::vector<int> s = index_list(sources, "sources");
    std::vector<int> l;
    {
      py::gil_scoped_release release;
      l = solver_.levels(s, max_levels);
    }
    return to_numpy(std::move(l));
  }

  // One path query (the GIL released, the solver's path buffers locked).
  edgefront::PathArrays find_path(int a, int b, bool polyline) {
    py::gil_scoped_release release;
    std::lock_guard<std::mutex> lock(mutex_);
    edgefront::ConnectionPathOptions o;
    o.polyline = polyline;
    return solver_.connection_path(a, b, o);
  }

  py::tuple path(int a, int b, bool polyline) {
    edgefront::PathArrays p = find_path(a, b, polyline);
    if (p.status == edgefront::PathStatus::NoPath) {
      return py::make_tuple(to_numpy_rows(std::vector<double>()), kInf);
    }
    if (polyline) return py::make_tuple(to_numpy_rows(std::move(p.points)), p.length);
    return py::make_tuple(chain_points(solver_, p.vertices), p.length);
  }

  // The geodesic polyline's points as surface points: (faces, barycentric), a `sources` argument.
  py::tuple path_sources(int a, int b) {
    edgefront::PathArrays p = find_path(a, b, true);
    if (p.status == edgefront::PathStatus::NoPath) {
      p.face.clear();
      p.barycentric.clear();
    }
    return py::make_tuple(to_numpy(std::move(p.face)), to_numpy_rows(std::move(p.barycentric)));
  }

 private:
  static edgefront::GeodesicSolver make(const py::handle& V, const py::handle& F) {
    const VertexArg v = vertex_arg(V, "V");
    const FaceArg f = face_arg(F, "F");
    py::gil_scoped_release release;
    return edgefront::GeodesicSolver(v.view, f.view);
  }

  edgefront::GeodesicSolver solver_;
  std::mutex mutex_;
};

constexpr const char* kMethods =
    "method: \"mdf\" (default: the Minimal Distance Front, 0.1-0.3% mean error on scanned models, O(front)\n"
    "memory), \"windows\" (per-edge windows: near exact, about 3-4x the MDF's time), \"fast\" (one unfolding\n"
    "per edge: about 2x Dijkstra's time), \"dijkstra\" (along mesh edges; overestimates by 4-9%).";

}  // namespace

void register_geodesic(py::module_& m) {
  const std::string methods = kMethods;

  m.def(
      "geodesic_distance",
      [](const py::handle& V, const py::handle& F, const py::handle& sources, const std::string& method,
         double max_distance) {
        PySolver solver(V, F);
        return solver.distance(sources, method, max_distance);
      },
      py::arg("V"), py::arg("F"), py::arg("sources"), py::arg("method") = "mdf", py::arg("max_distance") = kInf,
      ("geodesic_distance(V, F, sources, method=\"mdf\", max_distance=inf) -> numpy.ndarray\n\n"
       "Geodesic distance from the sources to every vertex of the mesh (V, F).\n\n"
       "V: (n, 3) float64 or float32 vertex positions; F: (m, 3) int32 or int64 triangles (0-based rows of V).\n"
       "Both are read in place when C-contiguous (else copied once).\n"
       "sources: a vertex index, a 1-D sequence of vertex indices (all at distance 0), or surface points as\n"
       "(faces, barycentric): k face rows of F and a (k, 3) array of barycentric coordinates (non-negative,\n"
       "summing to 1) with respect to each row's vertices in the row's order; (face, [b0, b1, b2]) for one.\n" +
       methods +
       "\nmax_distance: stop beyond this distance (>= 0, default inf); vertices farther away are inf.\n\n"
       "Returns a float64 array of n distances (inf where not reached: another component, beyond max_distance).\n"
       "Faces a half-edge mesh cannot hold (a third face on an edge, faces wound against each other) are\n"
       "dropped; pinched vertices are treated as one point. The GIL is released while it computes.\n\n"
       "Raises ValueError for bad arrays (dtype, shape, NaN/inf coordinates, out-of-range indices), a bad\n"
       "source, method or max_distance, with the library's message naming the row.\n\n"
       "Example:\n    d = edgefront.geodesic_distance(V, F, [0])")
          .c_str());

  py::class_<PySolver>(m, "GeodesicSolver",
                       "GeodesicSolver(V, F)\n\n"
                       "Many geodesic queries on one mesh: converts (V, F) once and keeps its buffers (and, after the\n"
                       "first method=\"fast\" query, its table) across queries. `distance` and `levels` may run from\n"
                       "several Python threads at once (the GIL is released); the other queries take a lock.\n"
                       "Raises ValueError for bad arrays, as geodesic_distance.")
      .def(py::init<const py::handle&, const py::handle&>(), py::arg("V"), py::arg("F"),
           "GeodesicSolver(V, F)\n\nConverts the mesh once (V (n, 3) float64/float32, F (m, 3) int32/int64).")
      .def_property_readonly("n_vertices", &PySolver::n_vertices, "Rows of V (int).")
      .def_property_readonly("n_faces", &PySolver::n_faces, "Rows of F (int).")
      .def_property_readonly("dropped_faces", &PySolver::dropped_faces,
                             "Rows of F the conversion dropped (faces a half-edge mesh cannot hold).")
      .def("distance", &PySolver::distance, py::arg("sources"), py::arg("method") = "mdf",
           py::arg("max_distance") = kInf,
           ("distance(sources, method=\"mdf\", max_distance=inf) -> numpy.ndarray\n\n"
            "The distance field from `sources` (as in geodesic_distance): n float64 values, inf where not "
            "reached.\n" +
            methods)
               .c_str())
      .def("distances", &PySolver::batch, py::arg("sources"), py::arg("targets") = py::none(),
           py::arg("method") = "mdf", py::arg("max_distance") = kInf, py::arg("threads") = 0u,
           py::arg("progress") = py::none(),
           ("distances(sources, targets=None, method=\"mdf\", max_distance=inf, threads=0, progress=None)\n"
            "    -> numpy.ndarray\n\n"
            "One distance field per source vertex, computed on `threads` threads (0: all cores): a (k, n)\n"
            "float64 array, row i the field of sources[i]; with targets (vertex indices), the (k, t) matrix\n"
            "between the two sets (MDF and windows rows stop once every target has settled). The values\n"
            "are the same bytes for any thread count, and row i equals distance(sources[i]).\n" +
            methods +
            "\nprogress(done, total): called after each row (with the GIL); return False to cancel: the rows\n"
            "not computed are NaN. An exception raised in it cancels and is raised here.\n"
            "Raises ValueError for no source, an index out of range, a bad method or max_distance.")
               .c_str())
      .def("distances_within", &PySolver::within, py::arg("sources"), py::arg("max_distance"),
           py::arg("method") = "mdf",
           "distances_within(sources, max_distance, method=\"mdf\") -> (vertices, distances)\n\n"
           "The vertices within max_distance of the source vertices, in the order they settled (non-decreasing\n"
           "distance), as int32 indices and float64 distances. Costs what the front visits, not the mesh.\n"
           "method: \"mdf\" or \"windows\".")
      .def("distance_between", &PySolver::between, py::arg("a"), py::arg("b"), py::arg("max_distance") = kInf,
           "distance_between(a, b, max_distance=inf) -> float or None\n\n"
           "The geodesic distance from vertex a to vertex b when it is at most max_distance, else None\n"
           "(the front stops at b or beyond the bound).")
      .def("levels", &PySolver::levels, py::arg("sources"), py::arg("max_levels") = -1,
           "levels(sources, max_levels=-1) -> numpy.ndarray\n\n"
           "Minimal Edge Front levels (breadth-first hop distance) per vertex, int32, -1 where not reached\n"
           "within max_levels (all levels when negative).")
      .def("path", &PySolver::path, py::arg("a"), py::arg("b"), py::arg("polyline") = true,
           "path(a, b, polyline=True) -> (points, length)\n\n"
           "As geodesic_path, on this solver's mesh.")
      .def("path_sources", &PySolver::path_sources, py::arg("a"), py::arg("b"),
           "path_sources(a, b) -> (faces, barycentric)\n\n"
           "The points of path(a, b)'s geodesic polyline as surface points: k face rows of F (int32) and a\n"
           "(k, 3) float64 array of barycentric coordinates in each row's corner order, in polyline order.\n"
           "Pass the pair (or a slice of both) as `sources` to distance() to measure from polyline points.\n"
           "Empty arrays when a and b lie in different components.");

  m.def(
      "geodesic_path",
      [](const py::handle& V, const py::handle& F, int a, int b, bool polyline) {
        PySolver solver(V, F);
        return solver.path(a, b, polyline);
      },
      py::arg("V"), py::arg("F"), py::arg("a"), py::arg("b"), py::arg("polyline") = true,
      "geodesic_path(V, F, a, b, polyline=True) -> (points, length)\n\n"
      "A shortest path between vertices a and b (two Minimal Distance Fronts meeting halfway).\n"
      "polyline=True: the geodesic polyline across faces, a (k, 3) float64 array of points on mesh edges\n"
      "from a to b, and its length. polyline=False: the vertex chain along mesh edges (its positions) and the\n"
      "MDF's geodesic estimate of its length.\n"
      "When a and b lie in different components: an empty (0, 3) array and inf.\n"
      "Raises ValueError for bad arrays or vertex indices.");

  m.def(
      "edge_front_levels",
      [](const py::handle& V, const py::handle& F, const py::handle& source, int max_levels) {
        PySolver solver(V, F);
        return solver.levels(source, max_levels);
      },
      py::arg("V"), py::arg("F"), py::arg("source"), py::arg("max_levels") = -1,
      "edge_front_levels(V, F, source, max_levels=-1) -> numpy.ndarray\n\n"
      "The Minimal Edge Front's levels from the source vertex (or vertices): per vertex the level at which\n"
      "the front enclosed it (breadth-first hop distance), int32, -1 where not reached (another component,\n"
      "or beyond max_levels when max_levels >= 0).");

  // For bench/python: times of the C++ call the Python function makes (edgefront::geodesic_distance
  // on views of the same numpy buffers), without the Python layer, in the same process.
  m.def(
      "_time_cpp_geodesic_distance",
      [](const py::handle& V, const py::handle& F, const py::handle& sources, const std::string& method,
         int repeats) {
        const VertexArg v = vertex_arg(V, "V");
        const FaceArg f = face_arg(F, "F");
        const std::vector<int> s = index_list(sources, "sources");
        const edgefront::ArrayDistanceOptions o = distance_options(method, kInf);
        std::vector<double> seconds;
        py::gil_scoped_release release;
        for (int i = 0; i < repeats; ++i) {
          const auto t0 = std::chrono::steady_clock::now();
          edgefront::DistanceArrays d = edgefront::geodesic_distance(v.view, f.view, s, o);
          const auto t1 = std::chrono::steady_clock::now();
          EF_CHECK(d.distance.size() == v.rows(), "one distance per vertex");
          seconds.push_back(std::chrono::duration<double>(t1 - t0).count());
        }
        return seconds;
      },
      py::arg("V"), py::arg("F"), py::arg("sources"), py::arg("method") = "mdf", py::arg("repeats") = 1,
      "Benchmark helper: wall times (s) of the C++ call edgefront::geodesic_distance on the same arrays.");
}

}  // namespace efpy
