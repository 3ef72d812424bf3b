// Twist detection and repair (twist/arrays.h) for Python.

#include <pybind11/stl.h>

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bindings.h"
#include "convert.h"
#include "edgefront/error.h"
#include "twist/arrays.h"

namespace efpy {

namespace {

// Reference normals from points/normals (both or neither).
std::optional<twist::ReferenceNormals> reference(const py::handle& points, const py::handle& normals) {
  if (points.is_none() && normals.is_none()) return std::nullopt;
  if (points.is_none() || normals.is_none()) {
    throw py::value_error("points and normals go together: give both (an oriented reference cloud) or neither");
  }
  const VertexArg p = vertex_arg(points, "points");
  const VertexArg n = vertex_arg(normals, "normals");
  py::gil_scoped_release release;
  return twist::reference_from_arrays(p.view, n.view);
}

py::dict record_dict(const twist::EditRecord& r) {
  std::vector<int> added_original, moved, corners, added_faces;
  std::vector<double> added_position, moved_position;
  for (const twist::VertexAdded& a : r.vertices_added) {
    added_original.push_back(a.original);
    added_position.insert(added_position.end(), a.position.begin(), a.position.end());
  }
  for (const twist::VertexMoved& a : r.vertices_moved) {
    moved.push_back(a.vertex);
    moved_position.insert(moved_position.end(), a.position.begin(), a.position.end());
  }
  for (const twist::CornerReplaced& c : r.corners_replaced) corners.insert(corners.end(), {c.face, c.from, c.to});
  for (const std::array<int, 3>& f : r.faces_added) added_faces.insert(added_faces.end(), f.begin(), f.end());
  py::dict d;
  d["vertices_before"] = r.vertices_before;
  d["faces_before"] = r.faces_before;
  d["vertices_added_original"] = to_numpy(std::move(added_original));
  d["vertices_added_position"] = to_numpy_rows(std::move(added_position));
  d["vertices_moved"] = to_numpy(std::move(moved));
  d["vertices_moved_position"] = to_numpy_rows(std::move(moved_position));
  d["faces_flipped"] = to_numpy(std::vector<int>(r.faces_flipped));
  d["corners_replaced"] = to_numpy_rows(std::move(corners));
  d["faces_removed"] = to_numpy(std::vector<int>(r.faces_removed));
  d["faces_added"] = to_numpy_rows(std::move(added_faces));
  d["vertices_removed"] = to_numpy(std::vector<int>(r.vertices_removed));
  return d;
}

}  // namespace

void register_twist(py::module_& m) {
  m.def(
      "detect_twists",
      [](const py::handle& V, const py::handle& F, const py::handle& points, const py::handle& normals, double radius) {
        const std::optional<twist::ReferenceNormals> ref = reference(points, normals);
        const VertexArg v = vertex_arg(V, "V");
        const FaceArg f = face_arg(F, "F");
        twist::ArrayDetection d;
        {
          py::gil_scoped_release release;
          twist::DetectOptions o;
          o.radius = radius;
          if (ref) o.reference = &*ref;
          d = twist::detect_arrays(v.view, f.view, o);
        }
        return to_numpy(std::move(d.face_region));
      },
      py::arg("V"), py::arg("F"), py::arg("points") = py::none(), py::arg("normals") = py::none(),
      py::arg("radius") = 0.0,
      "detect_twists(V, F, points=None, normals=None, radius=0) -> numpy.ndarray\n\n"
      "Finds twisted regions: parts of the surface whose orientation disagrees with the side of the\n"
      "surface they approximate (facing layers of a thin structure, folds, self-intersections, or with\n"
      "points and normals, an oriented reference cloud (both (k, 3)) that decides the right side).\n"
      "radius: layer search radius (> 0), or 0 (default): twice the mean edge length.\n"
      "Returns, per face row of F, its region (int32; 0 = the largest region), -1 for none (and for rows\n"
      "a half-edge mesh cannot hold). The number of regions is labels.max() + 1.\n"
      "Raises ValueError for bad arrays or options; RuntimeError when a front meets a non-manifold vertex.");

  m.def(
      "repair_twists",
      [](const py::handle& V, const py::handle& F, const py::handle& points, const py::handle& normals,
         std::size_t max_repairs, double radius) {
        const std::optional<twist::ReferenceNormals> ref = reference(points, normals);
        const VertexArg v = vertex_arg(V, "V");
        const FaceArg f = face_arg(F, "F");
        twist::ArrayRepair r;
        std::vector<double> vertices;
        std::vector<int> faces;
        {
          py::gil_scoped_release release;
          twist::RepairOptions o;
          o.max_repairs = max_repairs;
          o.detect.radius = radius;
          if (ref) o.detect.reference = &*ref;
          r = twist::repair_arrays(v.view, f.view, o);
          vertices.reserve(3 * r.record.vertices_after());
          for (size_t i = 0; i < v.rows(); ++i) {
            for (size_t k = 0; k < 3; ++k) vertices.push_back(v.view.at(i, k));
          }
          faces.reserve(3 * r.record.faces_after());
          for (size_t i = 0; i < f.rows(); ++i) {
            for (size_t k = 0; k < 3; ++k) faces.push_back(static_cast<int>(f.view.at(i, k)));
          }
          twist::apply(r.record, vertices, faces);
          twist::compact_faces(faces);
        }
        return py::make_tuple(to_numpy_rows(std::move(vertices)), to_numpy_rows(std::move(faces)), record_dict(r.record));
      },
      py::arg("V"), py::arg("F"), py::arg("points") = py::none(), py::arg("normals") = py::none(),
      py::arg("max_repairs") = 16, py::arg("radius") = 0.0,
      "repair_twists(V, F, points=None, normals=None, max_repairs=16, radius=0) -> (V2, F2, record)\n\n"
      "With points and normals (an oriented scan): every face is labelled keep or flip by a minimum cut\n"
      "(each face votes with its area by the nearest scan normal; a cut costs half a mean edge per unit\n"
      "length), so consistently oriented regions are flipped whole and the mesh is cut only where regions\n"
      "that disagree meet (the twist line); then small folds and flaps the scan still rejects are mended\n"
      "(edges swapped, vertices moved, a patch re-grown as a fan from its rim). Without them: detects twisted regions (as\n"
      "detect_twists), cuts each off along its border, flips the smaller side and orients the surface\n"
      "globally (closed components outward); at most max_repairs regions.\n"
      "Returns the repaired mesh, V2 float64 (n2, 3) (the input's vertices, then the copies a cut appended;\n"
      "a vertex the repair no longer uses stays, unreferenced) and F2 int32 (the faces kept, in slot order,\n"
      "removed slots dropped), and the edit record as a dict of numpy arrays that replays the repair on the\n"
      "input's own indices (edgefront.apply_record does it in numpy; twist/edit_record.h documents it):\n"
      "  vertices_before, faces_before            index spaces before (ints)\n"
      "  vertices_added_original, _position       step 1: append copies of these vertices (-1: new point) at these positions\n"
      "  vertices_moved, vertices_moved_position  step 2: move vertices\n"
      "  faces_flipped                            step 3: reverse these faces' corner order (a b c -> a c b)\n"
      "  corners_replaced                         step 4: rows (face, from, to): in face, the corner holding from takes to\n"
      "  faces_removed                            step 5: remove these faces (empty slots)\n"
      "  faces_added                              step 6: append these faces (k, 3)\n"
      "  vertices_removed                         vertices no face uses afterwards (nothing to replay)\n"
      "The record also holds what the conversion changed (faces dropped, pinched vertices split).\n"
      "Raises ValueError for bad arrays or options.");
}

}  // namespace efpy
