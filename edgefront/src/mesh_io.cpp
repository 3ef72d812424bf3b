#include "edgefront/mesh_io.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "detail/io_common.h"
#include "detail/mesh_builder.h"
#include "detail/mesh_parsers.h"
#include "edgefront/atomic_write.h"
#include "edgefront/error.h"
#include "edgefront/mesh_stats.h"

namespace edgefront {

namespace fs = std::filesystem;

namespace {

// ---------------------------------------------------------------------------------------------
// Building the mesh

/// Number of entries equal to an earlier entry (sorts `keys`).
size_t count_repeats(std::vector<std::array<int, 3>>& keys) {
  std::sort(keys.begin(), keys.end());
  size_t repeats = 0;
  for (size_t i = 1; i < keys.size(); ++i) repeats += keys[i] == keys[i - 1] ? 1 : 0;
  return repeats;
}

std::string where_text(const detail::RawMesh& raw, uint64_t where) {
  return (raw.where_is_line ? "line " : "face ") + std::to_string(where);
}

bool has_repeated_index(const int* idx, uint32_t n) {
  if (n <= 16) {
    for (uint32_t i = 0; i < n; ++i) {
      for (uint32_t j = i + 1; j < n; ++j) {
        if (idx[i] == idx[j]) return true;
      }
    }
    return false;
  }
  std::vector<int> copy(idx, idx + n);
  std::sort(copy.begin(), copy.end());
  return std::adjacent_find(copy.begin(), copy.end()) != copy.end();
}

double bbox_diagonal(const std::vector<Vec3>& points) {
  if (points.empty()) return 0;
  Vec3 lo = points[0], hi = points[0];
  for (const Vec3& p : points) {
    lo.minimize(p);
    hi.maximize(p);
  }
  return (hi - lo).norm();
}

MeshReadResult build_mesh(detail::RawMesh& raw, const MeshReadOptions& options, const fs::path& file) {
  MeshReadResult result;
  MeshReadReport& report = result.report;
  const size_t nv = raw.points.size();
  report.vertices = nv;
  report.faces_in_file = raw.faces.size();

  // Fan-triangulate the records (from their first vertex); records with a repeated index go.
  std::vector<int> tris;
  std::vector<uint64_t> tri_where;
  size_t triangles = 0;
  for (const detail::RawFace& f : raw.faces) triangles += f.count - 2;
  tris.reserve(3 * triangles);
  tri_where.reserve(triangles);
  std::vector<std::array<int, 3>> keys;  // sorted vertex triples, for counting duplicates
  keys.reserve(triangles);
  size_t triangles_from_polygons = 0;
  uint64_t first_invalid = 0;
  for (const detail::RawFace& face : raw.faces) {
    const int* idx = raw.indices.data() + face.first;
    if (has_repeated_index(idx, face.count)) {
      if (report.faces_dropped_invalid++ == 0) first_invalid = face.where;
      continue;
    }
    if (face.count > 3) {
      ++report.polygons_triangulated;
      triangles_from_polygons += face.count - 2;
    }
    for (uint32_t k = 1; k + 1 < face.count; ++k) {
      tris.insert(tris.end(), {idx[0], idx[k], idx[k + 1]});
      tri_where.push_back(face.where);
      std::array<int, 3> key{idx[0], idx[k], idx[k + 1]};
      std::sort(key.begin(), key.end());
      keys.push_back(key);
    }
  }

  // The mesh: the same builder as the array conversion (faces a half-edge mesh cannot hold
  // dropped, pinched vertices split into copies appended after the file's vertices).
  ArrayMesh built = detail::build_mesh(detail::PointRows{nullptr, &raw.points}, tris);
  const std::vector<DroppedFace>& dropped = built.report.dropped_faces;
  if (!options.drop_nonmanifold_faces && !dropped.empty()) {
    const DroppedFace& d = dropped.front();
    const int a = tris[3 * d.row], b = tris[3 * d.row + 1], c = tris[3 * d.row + 2];
    throw IoError(file.string() + ": " + where_text(raw, tri_where[d.row]) + ": face (" + std::to_string(a) + ", " +
                  std::to_string(b) + ", " + std::to_string(c) +
                  ") cannot be added: it would make an edge non-manifold, or it repeats an existing face with the "
                  "same orientation (strict mode refuses such files)");
  }
  result.mesh = std::move(built.mesh);
  report.faces_dropped_nonmanifold = dropped.size();
  report.triangles_added = tri_where.size() - dropped.size();
  report.pinched_vertices = built.report.pinched_vertices;
  report.vertex_copies = built.report.vertex_copies;
  report.isolated_vertices = built.report.isolated_vertices;
  const double diagonal = bbox_diagonal(raw.points);
  const double degenerate_area = kDegenerateAreaFactor * diagonal * diagonal;
  for (size_t r = 0; r < tri_where.size(); ++r) {
    if (built.face_of_row[r] < 0) continue;
    const Vec3& pa = raw.points[static_cast<size_t>(tris[3 * r])];
    const double area =
        0.5 * cross(raw.points[static_cast<size_t>(tris[3 * r + 1])] - pa, raw.points[static_cast<size_t>(tris[3 * r + 2])] - pa).norm();
    if (area <= degenerate_area) ++report.degenerate_faces;
  }
  report.duplicate_faces = count_repeats(keys);
  const uint64_t first_refused = dropped.empty() ? 0 : tri_where[dropped.front().row];

  std::vector<std::string>& w = report.warnings;
  w = std::move(raw.warnings);
  if (report.polygons_triangulated > 0) {
    w.push_back(detail::count_noun(report.polygons_triangulated, "polygon was", "polygons were") +
                " triangulated into " + detail::count_noun(triangles_from_polygons, "triangle", "triangles"));
  }
  if (report.faces_dropped_invalid > 0) {
    w.push_back(detail::count_noun(report.faces_dropped_invalid, "face", "faces") +
                " with a repeated vertex index dropped (first at " + where_text(raw, first_invalid) + ")");
  }
  if (report.faces_dropped_nonmanifold > 0) {
    w.push_back(detail::count_noun(report.faces_dropped_nonmanifold, "triangle", "triangles") +
                " dropped because they would make an edge non-manifold (first at " +
                where_text(raw, first_refused) + ")");
  }
  if (report.pinched_vertices > 0) {
    w.push_back(detail::count_noun(report.pinched_vertices, "pinched vertex was", "pinched vertices were") +
                " split into one vertex per fan (" + detail::count_noun(report.vertex_copies, "copy", "copies") +
                " appended after the file's vertices, linked as twins)");
  }
  if (report.duplicate_faces > 0) {
    w.push_back(detail::count_noun(report.duplicate_faces, "triangle repeats", "triangles repeat") +
                " the vertex set of an earlier triangle");
  }
  if (report.degenerate_faces > 0) {
    w.push_back(detail::count_noun(report.degenerate_faces, "degenerate (zero-area) triangle",
                                   "degenerate (zero-area) triangles") +
                " kept");
  }
  if (report.isolated_vertices > 0 && report.faces_in_file > 0) {
    w.push_back(detail::count_noun(report.isolated_vertices, "vertex is", "vertices are") +
                " used by no face (kept as isolated vertices)");
  }
  return result;
}

// ---------------------------------------------------------------------------------------------
// Writing

/// Buffers output and hands it to the stream in large pieces.
class ChunkWriter {
 public:
  explicit ChunkWriter(std::ostream& out) : out_(out) { buffer_.reserve(kChunk + 256); }
  ~ChunkWriter() = default;
  std::string& buffer() { return buffer_; }
  void maybe_flush() {
    if (buffer_.size() >= kChunk) flush();
  }
  void flush() {
    out_.write(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
    buffer_.clear();
  }

 private:
  static constexpr size_t kChunk = 1 << 20;
  std::ostream& out_;
  std::string buffer_;
};

/// Live vertices renumbered in index order, and live faces as triples of new indices.
struct Compacted {
  std::vector<int> old_of_new;  // new index -> VertexHandle index
  std::vector<std::array<int, 3>> faces;
};

/// Appends "<prefix>a b c\n" with the face's indices plus `base` (OFF/PLY: "3 ", 0; OBJ: "f ", 1).
void append_face_line(std::string& b, const char* prefix, const std::array<int, 3>& f, int base) {
  b += prefix;
  for (int k = 0; k < 3; ++k) {
    if (k) b += ' ';
    detail::append_int(b, f[k] + base);
  }
  b += '\n';
}

Compacted compact(const Mesh& mesh) {
  Compacted c;
  std::vector<int> new_of_old(mesh.n_vertices(), -1);
  c.old_of_new.reserve(mesh.n_vertices());
  for (size_t i = 0; i < mesh.n_vertices(); ++i) {
    const VertexHandle v(static_cast<int>(i));
    if (mesh.status(v).deleted()) continue;
    new_of_old[i] = static_cast<int>(c.old_of_new.size());
    c.old_of_new.push_back(static_cast<int>(i));
  }
  c.faces.reserve(mesh.n_faces());
  for (size_t i = 0; i < mesh.n_faces(); ++i) {
    const FaceHandle f(static_cast<int>(i));
    if (mesh.status(f).deleted()) continue;
    // Start at the to-vertex of the face's halfedge: for a face added as add_face(a, b, c) this
    // gives (a, b, c), so files round-trip with their face vertex order.
    HalfedgeHandle h = mesh.halfedge_handle(f);
    std::array<int, 3> tri;
    for (int k = 0; k < 3; ++k) {
      const int nv = new_of_old[mesh.to_vertex_handle(h).idx()];
      EF_CHECK(nv >= 0, "a live face uses a deleted vertex");
      tri[k] = nv;
      h = mesh.next_halfedge_handle(h);
    }
    EF_CHECK(h == mesh.halfedge_handle(f), "a face of the triangle mesh is not a triangle");
    c.faces.push_back(tri);
  }
  return c;
}

bool valid_property_name(const std::string& name) {
  if (name.empty()) return false;
  return std::all_of(name.begin(), name.end(), [](unsigned char ch) { return ch > 0x20 && ch < 0x7f; });
}

void validate_mesh_write(const Mesh& mesh, const fs::path& path, const std::string& ext,
                         const MeshWriteOptions& options) {
  const std::string where = "write_mesh(" + path.string() + "): ";
  if (ext != ".off" && ext != ".obj" && ext != ".ply" && ext != ".stl") {
    throw InvalidInput(where + "unsupported extension " + detail::quote(path.extension().string()) +
                       " (supported: .off, .obj, .ply, .stl)");
  }
  if (!options.vertex_scalars.empty() && ext != ".ply") {
    throw InvalidInput(where + "vertex scalars can only be written to PLY");
  }
  if (!options.vertex_colors.empty() && ext != ".ply" && ext != ".off") {
    throw InvalidInput(where + "vertex colors can only be written to PLY and OFF");
  }
  if (!options.vertex_colors.empty() && options.vertex_colors.size() != mesh.n_vertices()) {
    throw InvalidInput(where + "vertex_colors has " + std::to_string(options.vertex_colors.size()) +
                       " entries but the mesh has " + std::to_string(mesh.n_vertices()) + " vertices");
  }
  std::vector<std::string> names = {"x", "y", "z"};
  if (!options.vertex_colors.empty()) names.insert(names.end(), {"red", "green", "blue"});
  for (const auto& [name, values] : options.vertex_scalars) {
    if (!valid_property_name(name)) {
      throw InvalidInput(where + "invalid vertex property name " + detail::quote(name) +
                         " (must be non-empty printable text without spaces)");
    }
    if (std::find(names.begin(), names.end(), name) != names.end()) {
      throw InvalidInput(where + "vertex property name " + detail::quote(name) + " is used twice");
    }
    names.push_back(name);
    if (values.size() != mesh.n_vertices()) {
      throw InvalidInput(where + "vertex scalar " + detail::quote(name) + " has " +
                         std::to_string(values.size()) + " values but the mesh has " +
                         std::to_string(mesh.n_vertices()) + " vertices");
    }
  }
  for (size_t i = 0; i < mesh.n_vertices(); ++i) {
    const VertexHandle v(static_cast<int>(i));
    if (mesh.status(v).deleted()) continue;
    const Vec3& p = mesh.point(v);
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
      throw InvalidInput(where + "vertex " + std::to_string(i) + " has a non-finite coordinate");
    }
  }
  if (ext == ".stl" && mesh.n_faces() > std::numeric_limits<uint32_t>::max()) {
    throw InvalidInput(where + "too many faces for STL");
  }
}

void append_point(std::string& out, const Vec3& p) {
  detail::append_double(out, p[0]);
  out += ' ';
  detail::append_double(out, p[1]);
  out += ' ';
  detail::append_double(out, p[2]);
}

void write_off(std::ostream& os, const Mesh& mesh, const Compacted& c, const MeshWriteOptions& options) {
  ChunkWriter w(os);
  std::string& b = w.buffer();
  const bool colors = !options.vertex_colors.empty();
  b += colors ? "COFF\n" : "OFF\n";
  b += std::to_string(c.old_of_new.size()) + " " + std::to_string(c.faces.size()) + " 0\n";
  for (const int old : c.old_of_new) {
    append_point(b, mesh.point(VertexHandle(old)));
    if (colors) {
      const auto& rgb = options.vertex_colors[old];
      b +=
          ' ' + std::to_string(rgb[0]) + ' ' + std::to_string(rgb[1]) + ' ' + std::to_string(rgb[2]) + " 255";
    }
    b += '\n';
    w.maybe_flush();
  }
  for (const auto& f : c.faces) {
    append_face_line(b, "3 ", f, 0);
    w.maybe_flush();
  }
  w.flush();
}

void write_obj(std::ostream& os, const Mesh& mesh, const Compacted& c) {
  ChunkWriter w(os);
  std::string& b = w.buffer();
  b += "# written by EdgeFront\n";
  b += "# " + std::to_string(c.old_of_new.size()) + " vertices, " + std::to_string(c.faces.size()) +
       " faces\n";
  for (const int old : c.old_of_new) {
    b += "v ";
    append_point(b, mesh.point(VertexHandle(old)));
    b += '\n';
    w.maybe_flush();
  }
  for (const auto& f : c.faces) {
    append_face_line(b, "f ", f, 1);
    w.maybe_flush();
  }
  w.flush();
}

void write_ply(std::ostream& os, const Mesh& mesh, const Compacted& c, const MeshWriteOptions& options) {
  ChunkWriter w(os);
  std::string& b = w.buffer();
  const bool colors = !options.vertex_colors.empty();
  b += "ply\n";
  b += options.binary ? "format binary_little_endian 1.0\n" : "format ascii 1.0\n";
  b += "comment written by EdgeFront\n";
  b += "element vertex " + std::to_string(c.old_of_new.size()) + "\n";
  b += "property double x\nproperty double y\nproperty double z\n";
  for (const auto& s : options.vertex_scalars) b += "property double " + s.first + "\n";
  if (colors) b += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  b += "element face " + std::to_string(c.faces.size()) + "\n";
  b += "property list uchar int vertex_indices\n";
  b += "end_header\n";
  for (const int old : c.old_of_new) {
    const Vec3& p = mesh.point(VertexHandle(old));
    if (options.binary) {
      for (int k = 0; k < 3; ++k) detail::append_le<double>(b, p[k]);
      for (const auto& s : options.vertex_scalars) detail::append_le<double>(b, s.second[old]);
      if (colors) {
        for (int k = 0; k < 3; ++k) detail::append_le<uint8_t>(b, options.vertex_colors[old][k]);
      }
    } else {
      append_point(b, p);
      for (const auto& s : options.vertex_scalars) {
        b += ' ';
        detail::append_double(b, s.second[old]);
      }
      if (colors) {
        for (int k = 0; k < 3; ++k) b += ' ' + std::to_string(options.vertex_colors[old][k]);
      }
      b += '\n';
    }
    w.maybe_flush();
  }
  for (const auto& f : c.faces) {
    if (options.binary) {
      detail::append_le<uint8_t>(b, 3);
      for (int k = 0; k < 3; ++k) detail::append_le<int32_t>(b, f[k]);
    } else {
      append_face_line(b, "3 ", f, 0);
    }
    w.maybe_flush();
  }
  w.flush();
}

void write_stl(std::ostream& os, const Mesh& mesh, const Compacted& c) {
  ChunkWriter w(os);
  std::string& b = w.buffer();
  std::string header = "binary STL written by EdgeFront";  // must not start with "solid"
  header.resize(80, ' ');
  b += header;
  detail::append_le<uint32_t>(b, static_cast<uint32_t>(c.faces.size()));
  for (const auto& f : c.faces) {
    const Vec3& p0 = mesh.point(VertexHandle(c.old_of_new[f[0]]));
    const Vec3& p1 = mesh.point(VertexHandle(c.old_of_new[f[1]]));
    const Vec3& p2 = mesh.point(VertexHandle(c.old_of_new[f[2]]));
    Vec3 n = cross(p1 - p0, p2 - p0);
    const double len = n.norm();
    n = len > 0 ? n / len : Vec3(0, 0, 0);
    for (int k = 0; k < 3; ++k) detail::append_le<float>(b, static_cast<float>(n[k]));
    for (const Vec3* p : {&p0, &p1, &p2}) {
      for (int k = 0; k < 3; ++k) detail::append_le<float>(b, static_cast<float>((*p)[k]));
    }
    detail::append_le<uint16_t>(b, 0);
    w.maybe_flush();
  }
  w.flush();
}

}  // namespace

namespace {

void check_mesh_extension(const fs::path& path, const std::string& ext) {
  if (ext != ".off" && ext != ".obj" && ext != ".ply" && ext != ".stl") {
    detail::throw_io(path, "unknown mesh file extension " + detail::quote(path.extension().string()) +
                               " (supported: .off, .obj, .ply, .stl)");
  }
}

MeshReadResult parse_and_build(std::string_view data, const fs::path& path, const std::string& ext,
                               const MeshReadOptions& options) {
  detail::RawMesh raw = detail::parse_mesh_file(data, path, ext, detail::ParseOptions{});
  return build_mesh(raw, options, path);
}

}  // namespace

MeshReadResult read_mesh(const fs::path& path, const MeshReadOptions& options) {
  const std::string ext = detail::lower_extension(path);
  check_mesh_extension(path, ext);
  const detail::FileContent content(path);
  return parse_and_build(content.view(), path, ext, options);
}

MeshReadResult read_mesh_from_buffer(std::string_view data, const fs::path& name,
                                     const MeshReadOptions& options) {
  const std::string ext = detail::lower_extension(name);
  check_mesh_extension(name, ext);
  return parse_and_build(data, name, ext, options);
}

Mesh load_mesh(const fs::path& path) { return std::move(read_mesh(path).mesh); }

void write_mesh(const Mesh& mesh, const fs::path& path, const MeshWriteOptions& options) {
  const std::string ext = detail::lower_extension(path);
  validate_mesh_write(mesh, path, ext, options);
  const Compacted c = compact(mesh);
  const bool binary = ext == ".stl" || (ext == ".ply" && options.binary);
  write_file_atomically(
      path,
      [&](std::ostream& os) {
        if (ext == ".off") {
          write_off(os, mesh, c, options);
        } else if (ext == ".obj") {
          write_obj(os, mesh, c);
        } else if (ext == ".ply") {
          write_ply(os, mesh, c, options);
        } else {
          write_stl(os, mesh, c);
        }
      },
      binary);
}

void write_polyline(const std::vector<Vec3>& points, const fs::path& path) {
  const std::string ext = detail::lower_extension(path);
  if (ext != ".obj" && ext != ".ply") {
    throw InvalidInput("write_polyline(" + path.string() + "): unsupported extension " +
                       detail::quote(path.extension().string()) + " (supported: .obj, .ply)");
  }
  for (size_t i = 0; i < points.size(); ++i) {
    const Vec3& p = points[i];
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
      throw InvalidInput("write_polyline(" + path.string() + "): point " + std::to_string(i) +
                         " has a non-finite coordinate");
    }
  }
  if (points.size() > static_cast<size_t>(std::numeric_limits<int32_t>::max())) {
    throw InvalidInput("write_polyline(" + path.string() + "): too many points");
  }
  const size_t segments = points.size() >= 2 ? points.size() - 1 : 0;
  write_file_atomically(
      path,
      [&](std::ostream& os) {
        ChunkWriter w(os);
        std::string& b = w.buffer();
        if (ext == ".obj") {
          b += "# polyline written by EdgeFront: " + std::to_string(points.size()) + " points\n";
          for (const Vec3& p : points) {
            b += "v ";
            append_point(b, p);
            b += '\n';
            w.maybe_flush();
          }
          if (segments > 0) {
            b += 'l';
            for (size_t i = 1; i <= points.size(); ++i) {
              b += ' ';
              detail::append_int(b, static_cast<long long>(i));
              w.maybe_flush();
            }
            b += '\n';
          }
        } else {
          b += "ply\nformat binary_little_endian 1.0\ncomment polyline written by EdgeFront\n";
          b += "element vertex " + std::to_string(points.size()) + "\n";
          b += "property double x\nproperty double y\nproperty double z\n";
          b += "element edge " + std::to_string(segments) + "\n";
          b += "property int vertex1\nproperty int vertex2\nend_header\n";
          for (const Vec3& p : points) {
            for (int k = 0; k < 3; ++k) detail::append_le<double>(b, p[k]);
            w.maybe_flush();
          }
          for (size_t i = 0; i < segments; ++i) {
            detail::append_le<int32_t>(b, static_cast<int32_t>(i));
            detail::append_le<int32_t>(b, static_cast<int32_t>(i + 1));
            w.maybe_flush();
          }
        }
        w.flush();
      },
      ext == ".ply");
}

}  // namespace edgefront
