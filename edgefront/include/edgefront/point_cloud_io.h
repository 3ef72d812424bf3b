#pragma once
/// \file point_cloud_io.h
/// Reading and writing point clouds (points with optional normals).
///
/// \code
///   edgefront::PointCloud cloud = edgefront::read_points("scan.xyz");
///   edgefront::write_points(cloud, "scan.ply");
/// \endcode

#include <filesystem>
#include <string_view>

#include "edgefront/point_cloud.h"

namespace edgefront {

/// Reads a point cloud; the format comes from the extension (case-insensitive):
/// - `.xyz`, `.txt`, `.pts`: one point per line, 3 (`x y z`) or 6 (`x y z nx ny nz`) numbers
///   separated by blanks, the same count on every line; `#` starts a comment; blank lines are
///   skipped. A first line holding a single integer is taken as the point count (as some `.pts`
///   files have) and checked;
/// - `.ply`: the `vertex` element's `x y z` and, when all three are present, `nx ny nz`; faces
///   and other elements are ignored;
/// - `.off`, `.obj`: the vertices.
/// PLY, OFF and OBJ files go through the mesh reader's parser and checks: their faces are read
/// and validated, then dropped, so that a file read_mesh refuses is refused here too, with the
/// same message. Text files may start with a UTF-8 byte-order mark; only regular files are read
/// (as read_mesh). Normals are normalized to unit length.
/// \throw IoError naming the file and the line (or vertex) for: a missing or empty file, anything
///        but a regular file, an unknown extension, malformed numbers or numbers beyond the range
///        of double, a line with another number count, NaN or infinite coordinates or normals,
///        coordinates outside the range EdgeFront computes with (coordinate_range.h), zero-length
///        normals and normals whose length overflows ("too long"), a file without points, and
///        every error read_mesh reports for PLY/OFF/OBJ files.
PointCloud read_points(const std::filesystem::path& path);

/// Like read_points, for file content already in memory; `name` only picks the format by its
/// extension and names the data in messages.
/// \throw IoError as read_points.
PointCloud read_points_from_buffer(std::string_view data, const std::filesystem::path& name);

/// Writes `cloud` as `.xyz` (also `.txt`, `.pts`: `x y z [nx ny nz]` per line, shortest
/// round-trip decimals) or `.ply` (binary little endian, `double` properties), atomically.
/// \throw InvalidInput for another extension, non-finite coordinates or normals, or `normals`
///        neither empty nor the size of `points`; IoError when the file cannot be written.
void write_points(const PointCloud& cloud, const std::filesystem::path& path);

}  // namespace edgefront
