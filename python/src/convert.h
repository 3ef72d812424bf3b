#pragma once
/// \file convert.h
/// numpy <-> EdgeFront array views for the Python bindings: at most one conversion per argument
/// (a C-contiguous float32/float64 or int32/int64 array is read in place; a non-contiguous one is
/// copied once; any other dtype is refused with ValueError naming the argument).

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "edgefront/arrays.h"
#include "edgefront/point_cloud.h"

namespace efpy {

namespace py = pybind11;

/// An (n, 3) float array argument: the numpy array kept alive and a view of its memory.
struct VertexArg {
  py::array array;  ///< keeps the buffer alive while the view is used
  edgefront::VertexArrayView view;
  size_t rows() const { return view.rows(); }
};

/// An (m, 3) integer array argument.
struct FaceArg {
  py::array array;
  edgefront::FaceArrayView view;
  size_t rows() const { return view.rows(); }
};

/// `obj` as an (n, 3) float32/float64 array (`name` is the argument's name in messages).
/// \throws ValueError (py::value_error) for another dtype, shape or an empty array.
VertexArg vertex_arg(const py::handle& obj, const char* name);

/// `obj` as an (m, 3) int32/int64 array. \throws ValueError as `vertex_arg`.
FaceArg face_arg(const py::handle& obj, const char* name);

/// `obj` (an int, or a 1-D sequence/array of integers) as a vector of int.
/// \throws ValueError for another dtype or shape, or a value outside the int range.
std::vector<int> index_list(const py::handle& obj, const char* name);

/// `obj` as a 1-D float64 vector of exactly `n` values (or any length when n < 0).
std::vector<double> double_list(const py::handle& obj, const char* name, long n = -1);

/// A PointCloud from points (n, 3) and optional normals (n, 3) or None; values are checked by
/// the library (InvalidInput -> ValueError naming the row).
edgefront::PointCloud point_cloud(const py::handle& points, const py::handle& normals);

/// A vector moved into a numpy array without a copy, with the given shape.
template <class T>
py::array_t<T> to_numpy(std::vector<T>&& values, std::vector<py::ssize_t> shape) {
  auto* owner = new std::vector<T>(std::move(values));
  py::capsule free_when_done(owner, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array_t<T>(shape, owner->data(), free_when_done);
}

/// 1-D numpy array of a vector.
template <class T>
py::array_t<T> to_numpy(std::vector<T>&& values) {
  const auto n = static_cast<py::ssize_t>(values.size());
  return to_numpy<T>(std::move(values), {n});
}

/// (n, 3) numpy array of a flat vector of 3 n values.
template <class T>
py::array_t<T> to_numpy_rows(std::vector<T>&& values) {
  const auto n = static_cast<py::ssize_t>(values.size() / 3);
  return to_numpy<T>(std::move(values), {n, 3});
}

/// (V, F) tuple of a MeshArrays (V float64 (n, 3), F int32 (m, 3)).
py::tuple mesh_tuple(edgefront::MeshArrays&& mesh);

/// The mesh of (V, F) as an edgefront::Mesh through `mesh_from_arrays` (the GIL released while it
/// converts).
edgefront::ArrayMesh array_mesh(const py::handle& V, const py::handle& F, bool drop_nonmanifold_faces = true);

}  // namespace efpy
