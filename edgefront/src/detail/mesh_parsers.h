#pragma once
/// \file mesh_parsers.h
/// Private: the format parsers behind read_mesh and read_points. Each parser reads the file's
/// vertices (in file order) and face records into a RawMesh, validating numbers, counts and
/// index ranges with messages that name the file and the line or element; building the
/// OpenMesh mesh from it is done by mesh_io.cpp.

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "edgefront/mesh.h"

namespace edgefront::detail {

/// One face record of the file: `count` indices starting at `first` in RawMesh::indices.
struct RawFace {
  size_t first = 0;
  uint32_t count = 0;
  uint64_t where = 0;  ///< line number (text formats) or face index (binary formats)
};

struct RawMesh {
  std::vector<Vec3> points;
  std::vector<Vec3> normals;  ///< per-vertex normals when the file has them (PLY nx ny nz), else empty
  std::vector<int> indices;   ///< face vertex indices, all in [0, points.size())
  std::vector<RawFace> faces;
  bool where_is_line = true;          ///< RawFace::where is a line number (else a face index)
  std::vector<std::string> warnings;  ///< format-level remarks (ignored elements, trailing data, ...)
};

/// What to read besides vertices and faces.
struct ParseOptions {
  bool normals = false;  ///< PLY: read nx ny nz when present
};

RawMesh parse_off(std::string_view data, const std::filesystem::path& file);
RawMesh parse_obj(std::string_view data, const std::filesystem::path& file);
RawMesh parse_ply(std::string_view data, const std::filesystem::path& file, const ParseOptions& options);
/// ASCII or binary STL; coincident corners are merged (bitwise-equal coordinates, -0 == 0).
RawMesh parse_stl(std::string_view data, const std::filesystem::path& file);

/// The one entry of the mesh reader and the point-cloud reader for mesh files: the parser for
/// `ext` (".off", ".obj", ".ply", ".stl"; lower case), faces always read and validated (a point
/// cloud reader drops them afterwards), then the checks every reader shares: an empty file, the
/// coordinate range (coordinate_range.h). So both readers refuse the same files with the same
/// messages. \throw IoError naming `file`.
RawMesh parse_mesh_file(std::string_view data, const std::filesystem::path& file, const std::string& ext,
                        const ParseOptions& options);

}  // namespace edgefront::detail
