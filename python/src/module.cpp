// The extension module edgefront._edgefront: exception translation and the parts' registration.
// The user-facing package is python/edgefront/__init__.py, which re-exports these functions.

#include <pybind11/pybind11.h>

#include <exception>

#include "bindings.h"
#include "edgefront/error.h"

namespace py = pybind11;

PYBIND11_MODULE(_edgefront, m) {
  m.doc() = "EdgeFront's C++ core (use the package `edgefront`, which re-exports everything here).";
  // Every docstring starts with its own signature line in Python terms (pybind11's would name the
  // array arguments `handle`).
  py::options options;
  options.disable_function_signatures();

  // The library's errors, with its message: InvalidInput -> ValueError, IoError -> OSError,
  // every other error (TopologyError, InternalError, std::exception) -> RuntimeError.
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const edgefront::InvalidInput& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const edgefront::IoError& e) {
      PyErr_SetString(PyExc_OSError, e.what());
    } catch (const edgefront::Error& e) {
      PyErr_SetString(PyExc_RuntimeError, e.what());
    }
  });

  efpy::register_io(m);
  efpy::register_geodesic(m);
  efpy::register_twist(m);
  efpy::register_reconstruct(m);
}
