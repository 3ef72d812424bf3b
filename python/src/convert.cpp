// numpy <-> EdgeFront array views (see convert.h).

#include "convert.h"

#include <limits>
#include <optional>
#include <sstream>

#include "twist/arrays.h"

namespace efpy {

namespace {

std::string shape_text(const py::array& a) {
  std::ostringstream s;
  s << "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) s << (i ? ", " : "") << a.shape(i);
  if (a.ndim() == 1) s << ",";
  s << ")";
  return s.str();
}

std::string dtype_text(const py::array& a) { return py::str(a.dtype()).cast<std::string>(); }

// numpy.asarray(obj): arrays pass through, sequences become arrays (numpy's own conversion).
py::array as_array(const py::handle& obj, const char* name) {
  if (py::isinstance<py::array>(obj)) return py::reinterpret_borrow<py::array>(obj);
  try {
    return py::module_::import("numpy").attr("asarray")(obj);
  } catch (py::error_already_set& e) {
    throw py::value_error(std::string(name) + ": not an array (" + e.what() + ")");
  }
}

// C-contiguous and native byte order as it is, else one copy (numpy.ascontiguousarray).
py::array contiguous(py::array a) {
  const bool native = a.dtype().attr("isnative").cast<bool>();
  if (native && (a.flags() & py::array::c_style)) return a;
  py::object dt = a.dtype().attr("newbyteorder")("=");
  return py::module_::import("numpy").attr("ascontiguousarray")(a, dt);
}

py::array n_by_3(const py::handle& obj, const char* name, char kind, const char* wanted) {
  py::array a = as_array(obj, name);
  const char k = a.dtype().kind();
  const auto size = a.dtype().itemsize();
  bool ok = false;
  if (kind == 'f') ok = (k == 'f' && (size == 4 || size == 8));
  if (kind == 'i') ok = (k == 'i' && (size == 4 || size == 8));
  if (!ok) throw py::value_error(std::string(name) + " must be " + wanted + ", got dtype " + dtype_text(a));
  if (a.ndim() != 2 || a.shape(1) != 3) {
    throw py::value_error(std::string(name) + " must have shape (n, 3), got shape " + shape_text(a));
  }
  if (a.shape(0) == 0) throw py::value_error(std::string(name) + " is empty (shape " + shape_text(a) + ")");
  return contiguous(std::move(a));
}

}  // namespace

VertexArg vertex_arg(const py::handle& obj, const char* name) {
  VertexArg out;
  out.array = n_by_3(obj, name, 'f', "float32 or float64");
  const auto rows = static_cast<size_t>(out.array.shape(0));
  if (out.array.dtype().itemsize() == 8) {
    out.view = edgefront::VertexArrayView(static_cast<const double*>(out.array.data()), rows);
  } else {
    out.view = edgefront::VertexArrayView(static_cast<const float*>(out.array.data()), rows);
  }
  return out;
}

FaceArg face_arg(const py::handle& obj, const char* name) {
  FaceArg out;
  out.array = n_by_3(obj, name, 'i', "int32 or int64");
  const auto rows = static_cast<size_t>(out.array.shape(0));
  if (out.array.dtype().itemsize() == 8) {
    out.view = edgefront::FaceArrayView(static_cast<const std::int64_t*>(out.array.data()), rows);
  } else {
    out.view = edgefront::FaceArrayView(static_cast<const std::int32_t*>(out.array.data()), rows);
  }
  return out;
}

std::vector<int> index_list(const py::handle& obj, const char* name) {
  if (py::isinstance<py::bool_>(obj)) throw py::value_error(std::string(name) + " must be integers, got a bool");
  py::array a = as_array(obj, name);
  const char k = a.dtype().kind();
  if (a.size() == 0 && a.ndim() == 1) return {};  // [] is float64 to numpy; the callee says what is missing
  if (k != 'i' && k != 'u') {
    throw py::value_error(std::string(name) + " must be integer vertex indices, got dtype " + dtype_text(a));
  }
  if (a.ndim() > 1) throw py::value_error(std::string(name) + " must be an int or a 1-D array, got shape " + shape_text(a));
  py::array_t<std::int64_t> v = py::module_::import("numpy").attr("ascontiguousarray")(a.attr("ravel")(), "int64");
  std::vector<int> out;
  out.reserve(static_cast<size_t>(v.size()));
  const std::int64_t* p = v.data();
  for (py::ssize_t i = 0; i < v.size(); ++i) {
    if (p[i] < std::numeric_limits<int>::min() || p[i] > std::numeric_limits<int>::max()) {
      throw py::value_error(std::string(name) + "[" + std::to_string(i) + "] = " + std::to_string(p[i]) +
                            " is out of range");
    }
    out.push_back(static_cast<int>(p[i]));
  }
  return out;
}

std::vector<double> double_list(const py::handle& obj, const char* name, long n) {
  py::array a = as_array(obj, name);
  const char k = a.dtype().kind();
  if (k != 'f' && k != 'i' && k != 'u') {
    throw py::value_error(std::string(name) + " must be numbers, got dtype " + dtype_text(a));
  }
  if (a.ndim() != 1) throw py::value_error(std::string(name) + " must be a 1-D array, got shape " + shape_text(a));
  if (n >= 0 && a.shape(0) != n) {
    throw py::value_error(std::string(name) + " must have " + std::to_string(n) + " values (one per vertex), got " +
                          std::to_string(a.shape(0)));
  }
  py::array_t<double> v = py::module_::import("numpy").attr("ascontiguousarray")(a, "float64");
  return std::vector<double>(v.data(), v.data() + v.size());
}

edgefront::PointCloud point_cloud(const py::handle& points, const py::handle& normals) {
  VertexArg p = vertex_arg(points, "points");
  edgefront::PointCloud cloud;
  std::optional<VertexArg> n;
  if (!normals.is_none()) {
    n = vertex_arg(normals, "normals");
    if (n->rows() != p.rows()) {
      throw py::value_error("normals: " + std::to_string(n->rows()) + " rows for " + std::to_string(p.rows()) + " points");
    }
  }
  py::gil_scoped_release release;
  p.view.check_values("points");
  cloud.points.reserve(p.rows());
  for (size_t i = 0; i < p.rows(); ++i) cloud.points.push_back(p.view.point(i));
  if (n) {
    n->view.check_values("normals");
    cloud.normals.reserve(n->rows());
    for (size_t i = 0; i < n->rows(); ++i) cloud.normals.push_back(n->view.point(i));
  }
  return cloud;
}

py::tuple mesh_tuple(edgefront::MeshArrays&& mesh) {
  static_assert(sizeof(int) == sizeof(std::int32_t), "F is returned as int32");
  return py::make_tuple(to_numpy_rows(std::move(mesh.vertices)), to_numpy_rows(std::move(mesh.faces)));
}

edgefront::ArrayMesh array_mesh(const py::handle& V, const py::handle& F, bool drop_nonmanifold_faces) {
  const VertexArg v = vertex_arg(V, "V");
  const FaceArg f = face_arg(F, "F");
  py::gil_scoped_release release;
  return edgefront::mesh_from_arrays(v.view, f.view, {.drop_nonmanifold_faces = drop_nonmanifold_faces});
}

}  // namespace efpy
