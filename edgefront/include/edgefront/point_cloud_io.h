#pragma once
/// \file point_cloud_io.h
/// Reading and writing point clouds (points with optional normals).
///
/// \code
///   edgefront::PointCloud cloud = edgefront::read_points("scan.xyz");
///   edgefront::write_points(cloud, "scan.ply");
/// \endcode

#include <cstddef>
#include <filesystem>
#include <string>
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

/// How read_points treats the normals of a file (the overloads with options).
struct PointReadOptions {
  /// false (default): a normal that cannot be normalized (zero-length, NaN or infinite
  /// components, a length that underflows or overflows) is an error, as in read_points(path).
  /// true: such a normal is *dropped*: replaced by (NaN, NaN, NaN) and counted in
  /// PointReadReport::invalid_normals, the other normals are kept (normalized); when no normal of
  /// the file is valid (e.g. all zero), the cloud gets no normals at all (`normals` empty).
  /// A normal token that is not a number at all is still an error (a malformed file).
  bool tolerate_invalid_normals = false;
  /// true: the file's normals are not read or checked at all (the cloud has none); the columns of
  /// a 6-number text file must still be there (the count per line is checked) but are not parsed.
  bool ignore_normals = false;
};

/// What read_points with options dropped.
struct PointReadReport {
  std::size_t points = 0;           ///< points read
  std::size_t invalid_normals = 0;  ///< normals dropped (tolerate_invalid_normals)
  std::size_t zero_normals = 0;     ///< of them: exactly (0, 0, 0)
  /// The file had normals but none was valid: the cloud has none (tolerate_invalid_normals).
  bool all_normals_invalid = false;
  /// The file had normals and they were not read (ignore_normals).
  bool normals_ignored = false;
  /// One line per fact above worth telling a user, e.g. "3 of 20000 normals are invalid
  /// (3 zero-length) and were dropped (first: line 12: zero-length normal)"; empty when the
  /// file was read as it is.
  std::string warning;
};

/// read_points with PointReadOptions; `report` (may be null) receives what was dropped.
/// Dropped normals are (NaN, NaN, NaN) in the returned cloud, so a consumer must treat a
/// non-finite normal as "no normal for this point" (gcs::Reconstructor does: it fits one).
/// 	hrow IoError as read_points, except for the normals tolerated or ignored by `options`.
PointCloud read_points(const std::filesystem::path& path, const PointReadOptions& options,
                       PointReadReport* report = nullptr);

/// Like read_points, for file content already in memory; `name` only picks the format by its
/// extension and names the data in messages.
/// \throw IoError as read_points.
PointCloud read_points_from_buffer(std::string_view data, const std::filesystem::path& name);

/// read_points_from_buffer with PointReadOptions (see read_points with options).
/// \throw IoError as read_points_from_buffer, except for the normals tolerated or ignored.
PointCloud read_points_from_buffer(std::string_view data, const std::filesystem::path& name,
                                   const PointReadOptions& options, PointReadReport* report = nullptr);

/// Writes `cloud` as `.xyz` (also `.txt`, `.pts`: `x y z [nx ny nz]` per line, shortest
/// round-trip decimals) or `.ply` (binary little endian, `double` properties), atomically.
/// \throw InvalidInput for another extension, non-finite coordinates or normals, or `normals`
///        neither empty nor the size of `points`; IoError when the file cannot be written.
void write_points(const PointCloud& cloud, const std::filesystem::path& path);

}  // namespace edgefront
