// Reconstruction (gcs/reconstructor.h with the twist repair, as gcs-reconstruct runs it) and
// evaluation (gcs/evaluation.h, the figures of gcs-eval) for Python.

#include <pybind11/stl.h>

#include <Python.h>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bindings.h"
#include "convert.h"
#include "edgefront/arrays.h"
#include "edgefront/error.h"
#include "gcs/evaluation.h"
#include "gcs/reconstructor.h"
#include "gcs/twist_operation.h"

namespace efpy {

namespace {

// The progress callback: called with the GIL held; a false return (other than None) or an
// exception (also KeyboardInterrupt from a pending Ctrl-C) cancels the run.
struct Progress {
  py::object fn;
  std::optional<py::error_already_set> error;

  bool operator()(const gcs::Progress& p) {
    py::gil_scoped_acquire acquire;
    try {
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      if (fn.is_none()) return true;
      py::dict d;
      d["vertices"] = p.vertices;
      d["target_vertices"] = p.target_vertices;
      d["basic_steps"] = p.basic_steps;
      d["seconds"] = p.seconds;
      const py::object r = fn(d);
      return r.is_none() || py::bool_(r).cast<bool>();
    } catch (py::error_already_set& e) {
      error = std::move(e);
      return false;
    }
  }
};

}  // namespace

void register_reconstruct(py::module_& m) {
  m.def(
      "reconstruct",
      [](const py::handle& points, const py::handle& normals, const py::handle& vertices, std::uint64_t seed,
         const py::handle& progress, bool twist, bool return_info, const std::string& preset) -> py::object {
        edgefront::PointCloud cloud = point_cloud(points, normals);
        gcs::ReconstructOptions o = gcs::ReconstructOptions::preset(preset);  // InvalidInput -> ValueError
        if (vertices.is_none()) {
          o.target_vertices = std::min<std::size_t>(5000, cloud.size());
        } else {
          // operator.index: an int or numpy integer, else TypeError (as Python's own functions do).
          const long long target = py::module_::import("operator").attr("index")(vertices).cast<long long>();
          if (target < 0) throw py::value_error("vertices must be a positive count, got " + std::to_string(target));
          o.target_vertices = static_cast<std::size_t>(target);
        }
        o.seed = seed;
        o.progress_interval = 50;  // as gcs-reconstruct: the same bytes for the same input, seed and target
        Progress state{py::reinterpret_borrow<py::object>(progress), std::nullopt};
        gcs::ReconstructResult r;
        {
          py::gil_scoped_release release;
          gcs::Reconstructor reconstructor(std::move(cloud), o);
          if (twist) reconstructor.add_operation(std::make_shared<gcs::TwistOperation>(gcs::TwistOperationOptions{}));
          r = reconstructor.run([&state](const gcs::Progress& p) { return state(p); });
        }
        py::tuple mesh = mesh_tuple(edgefront::mesh_to_arrays(r.mesh));
        if (state.error) {
          // The callback raised: the run stopped at a valid mesh; hand it over with the exception.
          try {
            state.error->value().attr("partial_result") = mesh;
          } catch (py::error_already_set&) {
          }
          throw std::move(*state.error);
        }
        if (!return_info) return mesh;
        py::dict info;
        info["stop_reason"] = gcs::to_string(r.stop_reason);
        info["cancelled"] = r.stop_reason == gcs::StopReason::cancelled;
        info["basic_steps"] = r.basic_steps;
        info["splits"] = r.splits;
        info["collapses"] = r.collapses;
        info["batches"] = r.batches;
        info["seconds"] = r.seconds_total;
        info["cloud_smoothed"] = r.cloud_smoothed;
        return py::make_tuple(mesh[0], mesh[1], info);
      },
      py::arg("points"), py::arg("normals") = py::none(), py::arg("vertices") = py::none(), py::arg("seed") = 1,
      py::arg("progress") = py::none(), py::arg("twist") = true, py::arg("return_info") = false,
      py::arg("preset") = "scan",
      "reconstruct(points, normals=None, vertices=None, seed=1, progress=None, twist=True, return_info=False, "
      "preset=\"scan\") -> (V, F)\n\n"
      "Reconstructs a triangle mesh from a point cloud with growing cell structures (the loop of\n"
      "Ivrissimtzis et al. with borders, handles and hole filling) and, with twist=True (default), the twist\n"
      "repair after every batch: the same mesh, byte for byte, as `gcs-reconstruct POINTS --vertices N\n"
      "--seed S` on the same points.\n"
      "points: (n, 3) float64/float32; normals: (n, 3) unit normals or None (then fitted).\n"
      "vertices: the target vertex count (default min(5000, n)), at most the number of distinct points.\n"
      "seed: the sample draws' seed; the same input, seed and target give the same bytes.\n"
      "preset: the options preset, as gcs-reconstruct --preset: \"scan\" (the defaults), \"thin_shell\"\n"
      "(thin closed shells) or \"open_sheet\" (open surfaces without normals); see docs/reconstruction.md.\n"
      "progress: called every 50 vertex splits and at the end with a dict (vertices, target_vertices,\n"
      "basic_steps, seconds). Return False (any false value other than None) to cancel: the run stops and\n"
      "the valid mesh reached so far comes back (return_info's stop_reason then says \"cancelled\"). If it\n"
      "raises (or Ctrl-C is pressed), the run stops the same way and the exception propagates, with the\n"
      "valid mesh so far as its attribute `partial_result` (V, F).\n"
      "Returns V float64 (k, 3), F int32 (m, 3); with return_info=True also a dict (stop_reason, cancelled,\n"
      "basic_steps, splits, collapses, batches, seconds, cloud_smoothed).\n"
      "The GIL is released while it runs (the callback re-acquires it). Raises ValueError for bad arrays\n"
      "(NaN, shape, dtype, normals of another count), fewer than 4 points, a target out of range, an\n"
      "unknown preset.");

  m.def(
      "evaluate",
      [](const py::handle& V, const py::handle& F, const py::handle& gt_points, const py::handle& gt_normals,
         const py::handle& gt_faces, std::size_t samples, std::uint64_t seed, bool self_intersections) {
        const edgefront::ArrayMesh result = array_mesh(V, F);
        std::optional<gcs::GroundTruth> gt;
        if (!gt_faces.is_none()) {
          if (!gt_normals.is_none()) throw py::value_error("evaluate: give gt_normals or gt_faces, not both");
          edgefront::ArrayMesh g = array_mesh(gt_points, gt_faces);
          gt = gcs::GroundTruth::from_mesh(std::move(g.mesh));
        } else {
          gt = gcs::GroundTruth::from_points(point_cloud(gt_points, gt_normals));
        }
        gcs::EvaluationOptions o;
        o.samples = samples;
        o.seed = seed;
        o.self_intersections = self_intersections;
        std::string json;
        {
          py::gil_scoped_release release;
          gcs::Evaluation e = gcs::evaluate(result.mesh, *gt, o);
          e.validity.faces_dropped_when_read = result.report.dropped_faces.size();
          json = gcs::evaluation_to_json(e);
        }
        return py::module_::import("json").attr("loads")(json);
      },
      py::arg("V"), py::arg("F"), py::arg("gt_points"), py::arg("gt_normals") = py::none(),
      py::arg("gt_faces") = py::none(), py::arg("samples") = 100000, py::arg("seed") = 1,
      py::arg("self_intersections") = true,
      "evaluate(V, F, gt_points, gt_normals=None, gt_faces=None, samples=100000, seed=1, self_intersections=True) -> dict\n\n"
      "Judges the mesh (V, F) against a ground truth: the points gt_points (k, 3) with optional unit normals\n"
      "gt_normals, or the mesh (gt_points, gt_faces). The figures of `gcs-eval --json` (the same JSON\n"
      "object, parsed): chamfer_l1, hausdorff, hausdorff_p95, fscores, result_to_gt/gt_to_result\n"
      "distances, normal and orientation consistency (null without normals), and the validity of the mesh\n"
      "(mesh: closed, border_loops, components, genus, self_intersecting_pairs, ...). Distances are\n"
      "absolute (the input's units); ground_truth.bbox_diagonal gives the scale (the *_percent figures use it).\n"
      "samples: area-uniform samples of the mesh, seeded by seed (same seed, same figures).\n"
      "Raises ValueError for bad arrays or options.");
}

}  // namespace efpy
