#pragma once
/// \file coordinate_range.h
/// The range of coordinates EdgeFront computes with.
///
/// The algorithms form squared lengths, areas and squared areas: products of up to four
/// coordinate differences. For these to stay finite, normal numbers, every coordinate must lie
/// within +-kMaxCoordinate and the points, unless they all coincide, must span at least
/// kMinExtent along some axis. Beyond that, squares overflow to infinity (coordinates of 1e308:
/// distances come out as inf, which means "unreached", figures as NaN) or underflow to zero
/// (coordinates of 1e-310: every distance is 0). The readers (read_mesh, read_points) refuse
/// files outside the range, and so do the reconstructor, the evaluation and the distance fronts
/// (these check each vertex they reach against kMaxCoordinate).
///
/// \code
///   if (std::string why = edgefront::coordinate_range_problem(points); !why.empty()) ...
/// \endcode

#include <string>
#include <vector>

#include "edgefront/mesh.h"

namespace edgefront {

/// Largest accepted absolute coordinate: its fourth power, times a few, is still finite.
inline constexpr double kMaxCoordinate = 1e75;
/// Smallest accepted span (largest side of the bounding box) of points that do not all coincide:
/// its fourth power is still a normal double.
inline constexpr double kMinExtent = 1e-75;

/// Empty when every point is finite and the points are within the range above; otherwise why
/// not, e.g. "point 3 has the coordinate 1e308, beyond +-1e75: squared lengths and areas would
/// overflow (scale the data down)" or "the points span only 1e-310, less than 1e-75: squared
/// lengths and areas would underflow to zero (scale the data up)".
/// `noun` names the points in the message ("point 3", "vertex 3").
std::string coordinate_range_problem(const std::vector<Vec3>& points, const char* noun = "point");
/// The same for the live (not deleted) vertices of `mesh`; points are named "vertex N".
std::string coordinate_range_problem(const Mesh& mesh);

/// \throw InvalidInput "<what>: <problem>" when coordinate_range_problem is not empty.
void check_coordinate_range(const std::vector<Vec3>& points, const std::string& what);
/// \throw InvalidInput "<what>: <problem>" when coordinate_range_problem(mesh) is not empty.
void check_coordinate_range(const Mesh& mesh, const std::string& what);

}  // namespace edgefront
