#pragma once
/// \file mesh_io.h
/// Reading and writing triangle meshes: OFF, OBJ, PLY and STL in, OFF, OBJ, PLY and STL out.
///
/// The readers are EdgeFront's own (not OpenMesh's), so that every problem in a file is reported
/// with the file, the line or element, and what is wrong, and everything that was changed on the
/// way in (triangulated polygons, dropped faces) is counted in a MeshReadReport.
///
/// \code
///   edgefront::MeshReadResult r = edgefront::read_mesh("bunny.ply");
///   for (const std::string& w : r.report.warnings) std::cerr << "warning: " << w << "\n";
///   edgefront::write_mesh(r.mesh, "bunny.off");
/// \endcode

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "edgefront/mesh.h"

namespace edgefront {

/// Options of read_mesh and read_mesh_from_buffer.
struct MeshReadOptions {
  /// Faces a half-edge mesh cannot hold (a third face on an edge, a face using an edge in the same
  /// direction as an earlier face: wound against it, or a second copy of an oriented face) are
  /// dropped and counted when true (default); when false the file is refused with IoError naming
  /// the face. (Pinched vertices are split, never a reason to drop: see `read_mesh`.)
  bool drop_nonmanifold_faces = true;
};

/// What read_mesh found and changed. Counters refer to the file's face records unless noted.
struct MeshReadReport {
  size_t vertices = 0;                   ///< vertices in the file (all kept, in file order)
  size_t faces_in_file = 0;              ///< face records in the file (facets for STL)
  size_t triangles_added = 0;            ///< triangles in the mesh
  size_t polygons_triangulated = 0;      ///< face records with more than 3 vertices (fan-triangulated)
  size_t faces_dropped_nonmanifold = 0;  ///< triangles a half-edge mesh cannot hold (dropped; after triangulation)
  size_t faces_dropped_invalid = 0;      ///< face records with a repeated vertex index (dropped)
  size_t degenerate_faces = 0;           ///< added triangles with area <= 1e-12 * bbox_diagonal^2 (kept)
  size_t duplicate_faces =
      0;  ///< triangles with the vertex set of an earlier one (kept if OpenMesh accepts them)
  size_t isolated_vertices = 0;  ///< vertices used by no triangle of the mesh (kept)
  size_t pinched_vertices = 0;   ///< file vertices where several fans meet, split (see `read_mesh`)
  size_t vertex_copies = 0;      ///< copies appended for them
  std::vector<std::string>
      warnings;  ///< human-readable, e.g. "12 polygons were triangulated into 30 triangles"
};

/// What read_mesh returns: the mesh and the report of what was found and changed.
struct MeshReadResult {
  Mesh mesh;              ///< the mesh, face normals computed
  MeshReadReport report;  ///< counts and warnings of the read
};

/// Reads a mesh; the format comes from the extension (case-insensitive):
/// - `.off`: OFF, with the optional ST/C/N prefixes (extra per-vertex values are ignored), `#`
///   comments; one vertex or face per line;
/// - `.obj`: `v` and `f` records (`f 1/2/3 ...` and negative relative indices accepted; other
///   records ignored, unknown keywords counted in a warning);
/// - `.ply`: ascii, binary_little_endian and binary_big_endian; vertex `x y z` of any numeric
///   type; faces from the `vertex_indices` (or `vertex_index`) list of the `face` element, any
///   count and index type; all other elements and properties are skipped (and named in a
///   warning); ascii bodies hold one element instance per line;
/// - `.stl`: ASCII and binary; exactly coincident corners are merged into shared vertices (in
///   order of first appearance).
///
/// Text formats (OFF, OBJ, ASCII PLY headers, ASCII STL) may start with a UTF-8 byte-order mark.
/// Only regular files are read: a directory, a FIFO or a device (/dev/zero) is refused before it
/// is opened. The file is mapped, not copied: a file refused after its first bytes costs no
/// more than those.
///
/// Vertex i of the file is `VertexHandle(i)` of the mesh (STL: i-th distinct corner), isolated
/// vertices included; a file with vertices and no faces is a valid mesh without faces. Polygons
/// are fan-triangulated from their first vertex (exact for convex polygons). A pinched vertex
/// (several fans of faces meeting only at the vertex) is split as by `mesh_from_arrays`
/// (edgefront/arrays.h, the same builder): the fan of its first face keeps it, every other fan
/// gets a copy appended after the file's vertices, linked as twins (edgefront/vertex_twins.h).
/// Face normals of the result are up to date.
///
/// \throw IoError naming the file, the line (text formats) or element index, and the problem,
///        for: a missing or unreadable file, anything but a regular file, an unknown extension,
///        an empty file, UTF-16 text, a truncated file, malformed numbers or numbers beyond the
///        range of double, NaN or infinite coordinates, coordinates outside the range EdgeFront
///        computes with (coordinate_range.h: 1e308, 1e-310), a PLY vertex count one off (named
///        as such), face indices out of range or
///        negative, faces with fewer than 3 indices, bad PLY headers, element counts that cannot
///        fit in the file, content that is not a mesh in the expected format, and (with
///        `drop_nonmanifold_faces == false`) faces a half-edge mesh cannot hold.
/// \param path the file; its extension picks the format.
/// \param options what to do with faces a half-edge mesh cannot hold.
/// \return the mesh and the report of everything that was changed on the way in.
MeshReadResult read_mesh(const std::filesystem::path& path, const MeshReadOptions& options = {});

/// Like read_mesh, for file content already in memory (network buffers, embedded resources,
/// fuzzing). `name` is used only to pick the format by its extension and to name the data in
/// messages; nothing is read from disk.
/// \throw IoError as read_mesh.
MeshReadResult read_mesh_from_buffer(std::string_view data, const std::filesystem::path& name,
                                     const MeshReadOptions& options = {});

/// `read_mesh(path).mesh`: reads with default options and discards the report.
/// \throw IoError as read_mesh.
Mesh load_mesh(const std::filesystem::path& path);

/// Options of write_mesh.
struct MeshWriteOptions {
  /// PLY only: binary_little_endian when true (default), ascii when false.
  bool binary = true;
  /// PLY only: one `double` vertex property per entry (name, one value per vertex). Values are
  /// indexed by `VertexHandle::idx()`, so each vector's size must equal `mesh.n_vertices()`
  /// (deleted vertices included; their values are skipped). Non-finite values are written as they
  /// are (IEEE inf/nan in binary, "inf"/"-inf"/"nan" in ascii): +inf is meaningful, for instance,
  /// for vertices a distance field did not reach. Names must be non-empty, without whitespace,
  /// and distinct from x, y, z, red, green, blue and each other.
  std::vector<std::pair<std::string, std::vector<double>>> vertex_scalars = {};
  /// PLY (`red green blue` uchar properties) and OFF (written as COFF, alpha 255): empty, or one
  /// RGB color per vertex indexed by `VertexHandle::idx()` (size `mesh.n_vertices()`).
  std::vector<std::array<uint8_t, 3>> vertex_colors = {};
};

/// Writes `mesh` to `path`; the format comes from the extension: `.off`, `.obj`, `.ply`, `.stl`
/// (binary STL, triangles only). Only non-deleted vertices and faces are written; when the mesh
/// has deleted vertices the rest are renumbered in index order. Coordinates are written exactly
/// (shortest round-trip decimal text, or `double` in binary PLY; STL stores `float`). The file is
/// written atomically (see write_file_atomically).
/// \param mesh the mesh to write (not changed).
/// \param path the file to create or replace; its extension picks the format.
/// \param options PLY/OFF extras (binary or ascii PLY, per-vertex scalars and colors).
/// \throw InvalidInput for an unsupported extension, option arrays whose size is not
///        `mesh.n_vertices()`, bad scalar property names, options the format cannot store
///        (scalars outside PLY, colors in OBJ or STL), or non-finite vertex coordinates.
/// \throw IoError when the file cannot be written.
void write_mesh(const Mesh& mesh, const std::filesystem::path& path, const MeshWriteOptions& options = {});

/// Writes a polyline: `.obj` with one `v` record per point and one `l` record through all of
/// them, or `.ply` (binary little endian) with a `vertex` element and an `edge` element
/// (`vertex1 vertex2`) per segment. With fewer than 2 points only the vertices are written.
/// Written atomically.
/// \throw InvalidInput for another extension or non-finite points; IoError when writing fails.
void write_polyline(const std::vector<Vec3>& points, const std::filesystem::path& path);

}  // namespace edgefront
