#pragma once
/// \file bindings.h
/// The parts of the extension module, one per source file.

#include <pybind11/pybind11.h>

namespace efpy {

/// read_mesh, write_mesh, read_points, write_points, render_png (io.cpp).
void register_io(pybind11::module_& m);
/// geodesic_distance, GeodesicSolver, geodesic_path, edge_front_levels (geodesic.cpp).
void register_geodesic(pybind11::module_& m);
/// detect_twists, repair_twists (twist.cpp).
void register_twist(pybind11::module_& m);
/// reconstruct, evaluate (reconstruct.cpp).
void register_reconstruct(pybind11::module_& m);

}  // namespace efpy
