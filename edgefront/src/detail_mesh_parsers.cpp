#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstring>
#include <limits>
#include <unordered_map>

#include "detail/io_common.h"
#include "detail/mesh_parsers.h"
#include "detail/ply.h"
#include "edgefront/coordinate_range.h"
#include "edgefront/error.h"

namespace edgefront::detail {

namespace fs = std::filesystem;

namespace {

constexpr uint64_t kMaxVertices = static_cast<uint64_t>(std::numeric_limits<int>::max());

bool finite(const Vec3& p) { return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]); }

std::string describe_non_finite(const Vec3& p) {
  std::string out = "non-finite coordinate (";
  for (int i = 0; i < 3; ++i) {
    if (i > 0) out += ", ";
    append_double(out, p[i]);
  }
  return out + ")";
}

/// `v` as text for a message ("7", "-1", "2.5", "inf").
std::string number_text(double v) {
  std::string out;
  append_double(out, v);
  return out;
}

/// Reads the next line that has content after comment stripping.
bool next_content(LineReader& lines, std::string_view& line) {
  while (lines.next(line)) {
    line = strip_comment(line);
    if (!line.empty()) return true;
  }
  return false;
}

/// Parses three coordinates from tokens[first..first+2]; throws naming the line.
/// (The message prefix is built only on error: this runs once per vertex.)
Vec3 parse_point(const std::vector<std::string_view>& tokens, size_t first, const fs::path& file, size_t line,
                 size_t vertex) {
  const auto what = [vertex] { return "vertex " + std::to_string(vertex); };
  if (tokens.size() < first + 3) {
    throw_io_line(file, line,
                  what() + ": expected 3 coordinates, found " +
                      std::to_string(tokens.size() - std::min(first, tokens.size())));
  }
  Vec3 p;
  for (int k = 0; k < 3; ++k) {
    if (!parse_double(tokens[first + k], p[k])) {
      throw_io_line(file, line, what() + ": " + bad_number(tokens[first + k]));
    }
  }
  if (!finite(p)) throw_io_line(file, line, what() + ": " + describe_non_finite(p));
  return p;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// OFF

RawMesh parse_off(std::string_view data, const fs::path& file) {
  data = text_content(data, file, "an OFF");
  RawMesh raw;
  LineReader lines(data);
  std::string_view line;
  std::vector<std::string_view> tokens;
  if (!next_content(lines, line)) throw_io(file, "not an OFF file: it has no content besides comments");
  split_tokens(line, tokens);
  const std::string_view keyword = tokens[0];
  const size_t keyword_line = lines.line_number();
  if (keyword.size() < 3 || keyword.substr(keyword.size() - 3) != "OFF") {
    throw_io_line(file, keyword_line, "not an OFF file: expected the 'OFF' keyword, found " + quote(keyword));
  }
  std::string_view prefix = keyword.substr(0, keyword.size() - 3);
  if (prefix.substr(0, 2) == "ST") prefix.remove_prefix(2);
  if (!prefix.empty() && prefix.front() == 'C') prefix.remove_prefix(1);
  if (!prefix.empty() && prefix.front() == 'N') prefix.remove_prefix(1);
  if (!prefix.empty() && (prefix.front() == '4' || prefix.front() == 'n')) {
    throw_io_line(file, keyword_line,
                  "unsupported OFF variant " + quote(keyword) + " (only 3-D vertices are supported)");
  }
  if (!prefix.empty()) {
    throw_io_line(file, keyword_line, "not an OFF file: unknown keyword " + quote(keyword));
  }
  size_t first_count = 1;
  if (tokens.size() == 1) {
    if (!next_content(lines, line)) throw_io(file, "truncated file: no vertex and face counts after 'OFF'");
    split_tokens(line, tokens);
    first_count = 0;
  } else if (tokens[1] == "BINARY") {
    throw_io_line(file, keyword_line, "binary OFF is not supported");
  }
  const size_t counts_line = lines.line_number();
  const size_t n_counts = tokens.size() - first_count;
  if (n_counts < 2 || n_counts > 3) {
    throw_io_line(
        file, counts_line,
        "expected the counts '<vertices> <faces> [<edges>]', found " + std::to_string(n_counts) + " values");
  }
  int64_t counts[2] = {0, 0};
  for (int k = 0; k < 2; ++k) {
    const std::string_view t = tokens[first_count + k];
    if (!parse_int64(t, counts[k])) {
      throw_io_line(file, counts_line,
                    std::string(k == 0 ? "vertex" : "face") + " count " + quote(t) + " is not an integer");
    }
    if (counts[k] < 0) {
      throw_io_line(file, counts_line,
                    std::string(k == 0 ? "vertex" : "face") + " count " + quote(t) + " is negative");
    }
  }
  if (n_counts == 3) {
    int64_t edges = 0;
    if (!parse_int64(tokens[first_count + 2], edges)) {
      throw_io_line(file, counts_line, "edge count " + quote(tokens[first_count + 2]) + " is not an integer");
    }
  }
  const uint64_t nv = static_cast<uint64_t>(counts[0]);
  const uint64_t nf = static_cast<uint64_t>(counts[1]);
  // Never trust the counts for allocation: every vertex line needs at least "0 0 0\n" and every
  // face line "3 0 0 0\n", so reserve no more than the remaining bytes can hold. A count larger
  // than the file ends in a truncation error below.
  const uint64_t available = lines.remaining();
  if (nv > kMaxVertices) {
    throw_io_line(file, counts_line,
                  "the header declares " + std::to_string(nv) + " vertices, more than " +
                      (nv > available / 6 ? "the " + std::to_string(available) +
                                                " remaining bytes can hold (truncated or corrupt file)"
                                          : "the supported maximum of " + std::to_string(kMaxVertices)));
  }
  raw.points.reserve(std::min<uint64_t>(nv, available / 6 + 1));
  for (uint64_t i = 0; i < nv; ++i) {
    if (!next_content(lines, line)) {
      throw_io(file, "truncated file: the header declares " + std::to_string(nv) +
                         " vertices but the file ends after " + std::to_string(i) + " (line " +
                         std::to_string(lines.line_number()) + ")");
    }
    split_tokens(line, tokens);
    raw.points.push_back(parse_point(tokens, 0, file, lines.line_number(), i));
  }
  raw.faces.reserve(std::min<uint64_t>(nf, lines.remaining() / 8 + 1));
  for (uint64_t j = 0; j < nf; ++j) {
    if (!next_content(lines, line)) {
      throw_io(file, "truncated file: the header declares " + std::to_string(nf) +
                         " faces but the file ends after " + std::to_string(j) + " (line " +
                         std::to_string(lines.line_number()) + ")");
    }
    split_tokens(line, tokens);
    const size_t ln = lines.line_number();
    const auto what = [j] { return "face " + std::to_string(j); };
    int64_t k = 0;
    if (!parse_int64(tokens[0], k))
      throw_io_line(file, ln, what() + ": malformed vertex count " + quote(tokens[0]));
    if (k < 3) {
      throw_io_line(file, ln, what() + " has " + std::to_string(k) + " vertices; a face needs at least 3");
    }
    if (static_cast<uint64_t>(k) > tokens.size() - 1) {
      throw_io_line(file, ln,
                    what() + " declares " + std::to_string(k) + " vertices but the line has only " +
                        std::to_string(tokens.size() - 1) + " indices");
    }
    RawFace face;
    face.first = raw.indices.size();
    face.count = static_cast<uint32_t>(k);
    face.where = ln;
    for (int64_t m = 1; m <= k; ++m) {
      int64_t index = 0;
      if (!parse_int64(tokens[m], index))
        throw_io_line(file, ln, what() + ": malformed vertex index " + quote(tokens[m]));
      if (index < 0) throw_io_line(file, ln, what() + ": negative vertex index " + std::to_string(index));
      if (static_cast<uint64_t>(index) >= nv) {
        throw_io_line(file, ln,
                      what() + ": vertex index " + std::to_string(index) + " is out of range (the file has " +
                          std::to_string(nv) + " vertices)");
      }
      raw.indices.push_back(static_cast<int>(index));
    }
    raw.faces.push_back(face);
  }
  if (next_content(lines, line)) {
    raw.warnings.push_back("content after the last face (from line " + std::to_string(lines.line_number()) +
                           ") was ignored");
  }
  return raw;
}

// ---------------------------------------------------------------------------------------------
// OBJ

RawMesh parse_obj(std::string_view data, const fs::path& file) {
  data = text_content(data, file, "an OBJ");
  RawMesh raw;
  LineReader lines(data);
  std::string_view line;
  std::vector<std::string_view> tokens;
  size_t unknown = 0, first_unknown_line = 0, lines_and_points = 0;
  std::string first_unknown;
  while (next_content(lines, line)) {
    split_tokens(line, tokens);
    const std::string_view kw = tokens[0];
    const size_t ln = lines.line_number();
    if (kw == "v") {
      if (raw.points.size() >= kMaxVertices) throw_io_line(file, ln, "too many vertices");
      raw.points.push_back(parse_point(tokens, 1, file, ln, raw.points.size()));
    } else if (kw == "f") {
      const size_t face_index = raw.faces.size();
      const auto what = [face_index] { return "face " + std::to_string(face_index); };
      if (tokens.size() < 4) {
        throw_io_line(
            file, ln,
            what() + " has " + std::to_string(tokens.size() - 1) + " vertices; a face needs at least 3");
      }
      RawFace face;
      face.first = raw.indices.size();
      face.count = static_cast<uint32_t>(tokens.size() - 1);
      face.where = ln;
      for (size_t m = 1; m < tokens.size(); ++m) {
        std::string_view t = tokens[m];
        t = t.substr(0, t.find('/'));
        int64_t index = 0;
        if (!parse_int64(t, index))
          throw_io_line(file, ln, what() + ": malformed vertex index " + quote(tokens[m]));
        if (index == 0)
          throw_io_line(file, ln, what() + ": vertex index 0 is invalid (OBJ indices start at 1)");
        if (index < 0) {
          // Relative index: -1 is the last vertex defined so far.
          const int64_t resolved = static_cast<int64_t>(raw.points.size()) + index;
          if (resolved < 0) {
            throw_io_line(file, ln,
                          what() + ": relative vertex index " + std::to_string(index) +
                              " is out of range (only " + std::to_string(raw.points.size()) +
                              " vertices are defined before this line)");
          }
          raw.indices.push_back(static_cast<int>(resolved));
        } else {
          if (static_cast<uint64_t>(index) > kMaxVertices) {
            throw_io_line(file, ln, what() + ": vertex index " + std::to_string(index) + " is out of range");
          }
          raw.indices.push_back(static_cast<int>(index - 1));  // range checked once all vertices are known
        }
      }
      raw.faces.push_back(face);
    } else if (kw == "l" || kw == "p") {
      ++lines_and_points;
    } else if (kw == "vn" || kw == "vt" || kw == "vp" || kw == "g" || kw == "o" || kw == "s" || kw == "mg" ||
               kw == "usemtl" || kw == "mtllib" || kw == "usemap" || kw == "maplib" || kw == "lod" ||
               kw == "bevel" || kw == "c_interp" || kw == "d_interp" || kw == "shadow_obj" ||
               kw == "trace_obj" || kw == "cstype" || kw == "deg" || kw == "bmat" || kw == "step" ||
               kw == "curv" || kw == "curv2" || kw == "surf" || kw == "parm" || kw == "trim" ||
               kw == "hole" || kw == "scrv" || kw == "sp" || kw == "end" || kw == "con" || kw == "ctech" ||
               kw == "stech") {
      // attributes, grouping, materials and free-form geometry: not part of the triangle mesh
    } else {
      if (unknown++ == 0) {
        first_unknown_line = ln;
        first_unknown = std::string(kw);
      }
    }
  }
  if (raw.points.empty() && unknown > 0) {
    throw_io_line(file, first_unknown_line,
                  "not an OBJ file: no vertex ('v') records, and unknown keyword " + quote(first_unknown));
  }
  const size_t nv = raw.points.size();
  for (const RawFace& face : raw.faces) {
    for (uint32_t m = 0; m < face.count; ++m) {
      const int index = raw.indices[face.first + m];
      if (static_cast<size_t>(index) >= nv) {
        throw_io_line(file, face.where,
                      "vertex index " + std::to_string(index + 1) + " is out of range (the file has " +
                          std::to_string(nv) + " vertices)");
      }
    }
  }
  if (unknown > 0) {
    raw.warnings.push_back(count_noun(unknown, "line", "lines") +
                           " with an unknown keyword ignored (first: " + quote(first_unknown) + " at line " +
                           std::to_string(first_unknown_line) + ")");
  }
  if (lines_and_points > 0) {
    raw.warnings.push_back(count_noun(lines_and_points, "polyline or point record ('l', 'p')",
                                      "polyline and point records ('l', 'p')") +
                           " ignored");
  }
  if (raw.points.empty()) raw.warnings.push_back("the file contains no vertices");
  return raw;
}

// ---------------------------------------------------------------------------------------------
// PLY

namespace {

/// The body of a PLY file whose header is `header`; `trailing` tells whether data follows the
/// last element.
RawMesh parse_ply_body(std::string_view data, const PlyHeader& header, const fs::path& file, bool normals,
                       bool& trailing) {
  RawMesh raw;
  raw.where_is_line = header.format == PlyFormat::kAscii;
  const int vi = header.find("vertex");
  if (vi < 0) throw_io(file, "bad PLY header: no 'vertex' element");
  const PlyElement& vertex = header.elements[vi];
  int coord[3];
  const char* names[3] = {"x", "y", "z"};
  for (int k = 0; k < 3; ++k) {
    coord[k] = vertex.find(names[k]);
    if (coord[k] < 0 || vertex.properties[coord[k]].is_list) {
      throw_io_line(
          file, vertex.header_line,
          std::string("bad PLY header: the 'vertex' element has no scalar property '") + names[k] + "'");
    }
  }
  int normal[3] = {-1, -1, -1};
  if (normals) {
    const char* nnames[3] = {"nx", "ny", "nz"};
    int found = 0;
    for (int k = 0; k < 3; ++k) {
      normal[k] = vertex.find(nnames[k]);
      if (normal[k] >= 0 && vertex.properties[normal[k]].is_list) {
        throw_io_line(file, vertex.header_line,
                      std::string("bad PLY header: property '") + nnames[k] + "' is a list");
      }
      found += normal[k] >= 0 ? 1 : 0;
    }
    if (found != 0 && found != 3) {
      throw_io_line(file, vertex.header_line,
                    "bad PLY header: the 'vertex' element has only some of nx, ny, nz");
    }
  }
  const bool with_normals = normal[0] >= 0;
  if (vertex.count > kMaxVertices) throw_io(file, "too many vertices (" + std::to_string(vertex.count) + ")");
  const uint64_t nv = vertex.count;

  int face_prop = -1;
  const int fi = header.find("face");
  if (fi >= 0) {
    const PlyElement& face = header.elements[fi];
    face_prop = face.find("vertex_indices");
    if (face_prop < 0) face_prop = face.find("vertex_index");
    if (face_prop < 0 || !face.properties[face_prop].is_list) {
      throw_io_line(file, face.header_line,
                    "bad PLY header: the 'face' element has no list property 'vertex_indices'");
    }
  }
  for (size_t e = 0; e < header.elements.size(); ++e) {
    const PlyElement& element = header.elements[e];
    if (static_cast<int>(e) == vi || static_cast<int>(e) == fi || element.count == 0) continue;
    raw.warnings.push_back("element " + quote(element.name) + " (" + std::to_string(element.count) +
                           " instances) ignored");
  }

  PlyBodyReader reader(data, header, file);
  PlyInstance instance;
  std::vector<bool> want_face_list;
  if (fi >= 0) {
    want_face_list.assign(header.elements[fi].properties.size(), false);
    want_face_list[face_prop] = true;
  }
  const std::vector<bool> no_lists;
  while (reader.current_element() >= 0) {
    const int current = reader.current_element();
    if (current == vi) {
      raw.points.reserve(nv);
      if (with_normals) raw.normals.reserve(nv);
      for (uint64_t i = 0; i < nv; ++i) {
        reader.read_instance(instance, no_lists);
        const Vec3 p(instance.values[coord[0]], instance.values[coord[1]], instance.values[coord[2]]);
        if (!finite(p)) reader.fail(describe_non_finite(p));
        raw.points.push_back(p);
        if (with_normals) {
          raw.normals.emplace_back(instance.values[normal[0]], instance.values[normal[1]],
                                   instance.values[normal[2]]);
        }
      }
    } else if (current == fi) {
      const uint64_t nf = header.elements[fi].count;
      raw.faces.reserve(nf);
      for (uint64_t j = 0; j < nf; ++j) {
        reader.read_instance(instance, want_face_list);
        const std::vector<double>& list = instance.lists[face_prop];
        if (list.size() < 3) {
          reader.fail("face has " + std::to_string(list.size()) + " vertices; a face needs at least 3");
        }
        RawFace face;
        face.first = raw.indices.size();
        face.count = static_cast<uint32_t>(list.size());
        face.where = raw.where_is_line ? reader.instance_line() : j;
        for (const double v : list) {
          if (!std::isfinite(v) || v != std::floor(v)) {
            reader.fail("vertex index " + number_text(v) + " is not an integer");
          }
          if (v < 0) reader.fail("negative vertex index " + number_text(v));
          if (v >= static_cast<double>(nv)) {
            reader.fail("vertex index " + number_text(v) + " is out of range (the file has " +
                        std::to_string(nv) + " vertices)");
          }
          raw.indices.push_back(static_cast<int>(v));
        }
        raw.faces.push_back(face);
      }
    } else {
      reader.skip_element();
    }
  }
  trailing = reader.has_trailing_data();
  if (trailing) raw.warnings.push_back("data after the last element was ignored");
  return raw;
}

/// Called when the body of a PLY file could not be read: when other elements follow the vertices
/// and the file reads correctly, to its last byte, with a vertex count one lower or one higher
/// than the header's, the header's count is what is wrong (a face record read as a vertex gives "face 0 has 0 vertices" and the like),
/// and that is thrown. Returns otherwise.
void diagnose_vertex_count(std::string_view data, const PlyHeader& header, const fs::path& file, bool normals) {
  const int vi = header.find("vertex");
  if (vi < 0) return;
  // Only a count followed by other data can be diagnosed: a last element that comes up short is a
  // truncated file, as the reader says.
  bool data_follows = false;
  for (size_t e = static_cast<size_t>(vi) + 1; e < header.elements.size(); ++e) {
    data_follows = data_follows || header.elements[e].count > 0;
  }
  if (!data_follows) return;
  const uint64_t declared = header.elements[vi].count;
  for (const int delta : {-1, 1}) {
    if (delta < 0 && declared == 0) continue;
    PlyHeader corrected = header;
    corrected.elements[vi].count = delta < 0 ? declared - 1 : declared + 1;
    bool trailing = true;
    try {
      parse_ply_body(data, corrected, file, normals, trailing);
    } catch (const IoError&) {
      continue;
    }
    if (trailing) continue;
    throw_io_line(file, header.elements[vi].header_line,
                  "the header declares " + count_noun(declared, "vertex", "vertices") + " but the data holds " +
                      std::to_string(corrected.elements[vi].count) + ": the vertex count is one too " +
                      (delta < 0 ? "high" : "low") + " (with " + std::to_string(corrected.elements[vi].count) +
                      " the rest of the file reads correctly)");
  }
}

}  // namespace

RawMesh parse_ply(std::string_view data, const fs::path& file, const ParseOptions& options) {
  data = skip_utf8_bom(data);
  const PlyHeader header = parse_ply_header(data, file);
  bool trailing = false;
  try {
    return parse_ply_body(data, header, file, options.normals, trailing);
  } catch (const IoError&) {
    diagnose_vertex_count(data, header, file, options.normals);
    throw;
  }
}

// ---------------------------------------------------------------------------------------------
// STL

namespace {

/// Merges bitwise-identical corners into shared vertices, in order of first appearance.
class CornerMerger {
 public:
  CornerMerger(RawMesh& raw, size_t expected_corners) : raw_(raw) {
    index_.reserve(expected_corners / 4 + 16);
  }
  int add(Vec3 p) {
    Key key;
    for (int k = 0; k < 3; ++k) {
      if (p[k] == 0.0) p[k] = 0.0;  // -0 == +0
      std::memcpy(&key[k], &p[k], sizeof(double));
    }
    const auto [it, inserted] = index_.try_emplace(key, static_cast<int>(raw_.points.size()));
    if (inserted) raw_.points.push_back(p);
    return it->second;
  }

 private:
  using Key = std::array<uint64_t, 3>;
  struct KeyHash {
    size_t operator()(const Key& k) const {
      uint64_t h = 0;
      for (const uint64_t v : k) h = mix(h ^ v);
      return static_cast<size_t>(h);
    }
    /// The splitmix64 finalizer: every input bit affects every output bit.
    static uint64_t mix(uint64_t z) {
      z += 0x9e3779b97f4a7c15ull;
      z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
      z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
      return z ^ (z >> 31);
    }
  };
  RawMesh& raw_;
  std::unordered_map<Key, int, KeyHash> index_;
};

bool iequals(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    if (std::tolower(static_cast<unsigned char>(a[i])) != std::tolower(static_cast<unsigned char>(b[i])))
      return false;
  }
  return true;
}

/// Whitespace-separated tokens with their line numbers.
class TokenStream {
 public:
  explicit TokenStream(std::string_view data) : data_(data) {}
  bool next(std::string_view& token) {
    while (pos_ < data_.size() && std::isspace(static_cast<unsigned char>(data_[pos_]))) {
      if (data_[pos_] == '\n') ++line_;
      ++pos_;
    }
    if (pos_ >= data_.size()) return false;
    const size_t start = pos_;
    while (pos_ < data_.size() && !std::isspace(static_cast<unsigned char>(data_[pos_]))) ++pos_;
    token = data_.substr(start, pos_ - start);
    return true;
  }
  void skip_line() {
    while (pos_ < data_.size() && data_[pos_] != '\n') ++pos_;
  }
  size_t line() const { return line_; }

 private:
  std::string_view data_;
  size_t pos_ = 0;
  size_t line_ = 1;
};

bool starts_with_solid(std::string_view data) {
  size_t i = 0;
  while (i < data.size() && std::isspace(static_cast<unsigned char>(data[i]))) ++i;
  const std::string_view word = data.substr(i, 5);
  if (!iequals(word, "solid")) return false;
  return i + 5 == data.size() || std::isspace(static_cast<unsigned char>(data[i + 5]));
}

RawMesh parse_stl_ascii(std::string_view data, const fs::path& file) {
  RawMesh raw;
  CornerMerger merger(raw, data.size() / 128);
  TokenStream in(data);
  std::string_view token;
  const auto expect = [&](const char* keyword) {
    if (!in.next(token)) {
      throw_io_line(file, in.line(),
                    std::string("truncated file: expected '") + keyword + "', found the end of the file");
    }
    if (!iequals(token, keyword)) {
      throw_io_line(file, in.line(), std::string("expected '") + keyword + "', found " + quote(token));
    }
  };
  const auto number = [&](const char* what) {
    if (!in.next(token)) throw_io_line(file, in.line(), std::string("truncated file: expected ") + what);
    double v = 0;
    if (!parse_double(token, v))
      throw_io_line(file, in.line(), bad_number(token) + " in " + what);
    return v;
  };
  expect("solid");
  in.skip_line();
  std::vector<int> corners;
  bool closed = false;
  while (in.next(token)) {
    if (iequals(token, "endsolid")) {
      in.skip_line();
      closed = true;
      if (!in.next(token)) break;
      if (!iequals(token, "solid")) {
        throw_io_line(file, in.line(),
                      "expected 'solid' or the end of the file after 'endsolid', found " + quote(token));
      }
      in.skip_line();
      closed = false;
      continue;
    }
    if (!iequals(token, "facet")) {
      throw_io_line(file, in.line(), "expected 'facet' or 'endsolid', found " + quote(token));
    }
    const size_t facet_line = in.line();
    const size_t facet_index = raw.faces.size();
    const auto what = [facet_index] { return "facet " + std::to_string(facet_index); };
    expect("normal");
    for (int k = 0; k < 3; ++k) number("the facet normal");
    expect("outer");
    expect("loop");
    corners.clear();
    for (;;) {
      if (!in.next(token)) throw_io_line(file, in.line(), "truncated file: the file ends inside " + what());
      if (iequals(token, "endloop")) break;
      if (!iequals(token, "vertex"))
        throw_io_line(file, in.line(), "expected 'vertex' or 'endloop', found " + quote(token));
      Vec3 p;
      for (int k = 0; k < 3; ++k) p[k] = number("a vertex");
      if (!finite(p)) throw_io_line(file, in.line(), what() + ": " + describe_non_finite(p));
      corners.push_back(merger.add(p));
    }
    if (corners.size() < 3) {
      throw_io_line(file, facet_line,
                    what() + " has " + std::to_string(corners.size()) + " vertices; a face needs at least 3");
    }
    expect("endfacet");
    RawFace face;
    face.first = raw.indices.size();
    face.count = static_cast<uint32_t>(corners.size());
    face.where = facet_line;
    raw.indices.insert(raw.indices.end(), corners.begin(), corners.end());
    raw.faces.push_back(face);
  }
  if (!closed) raw.warnings.push_back("the file has no 'endsolid' line");
  if (raw.faces.empty()) raw.warnings.push_back("the file contains no facets");
  return raw;
}

RawMesh parse_stl_binary(std::string_view data, const fs::path& file) {
  constexpr size_t kHeader = 84, kFacet = 50;
  if (data.size() < kHeader) {
    throw_io(file, "not an STL file: too short for binary STL (" + std::to_string(data.size()) +
                       " bytes, the header alone has 84) and it does not start with 'solid'");
  }
  const uint64_t n = load_bytes<uint32_t>(data.data() + 80, true);
  const uint64_t expected = kHeader + n * kFacet;
  RawMesh raw;
  raw.where_is_line = false;
  if (data.size() < expected) {
    throw_io(file, "truncated binary STL: the header declares " + std::to_string(n) + " triangles (" +
                       std::to_string(expected) + " bytes) but the file has " + std::to_string(data.size()) +
                       " bytes");
  }
  if (data.size() - expected >= kFacet) {
    // Room for more triangles than declared: a wrong count (or not an STL file at all, such as a
    // sparse file of zeros), not padding.
    throw_io(file, "the header declares " + count_noun(n, "triangle", "triangles") + " (" +
                       std::to_string(expected) + " bytes) but the file has " + std::to_string(data.size()) +
                       " bytes: a wrong triangle count, or not an STL file");
  }
  if (data.size() > expected) {
    raw.warnings.push_back(std::to_string(data.size() - expected) +
                           " bytes after the last triangle were ignored");
  }
  CornerMerger merger(raw, 3 * n);
  raw.indices.reserve(3 * n);
  raw.faces.reserve(n);
  for (uint64_t t = 0; t < n; ++t) {
    const char* facet = data.data() + kHeader + t * kFacet;
    RawFace face;
    face.first = raw.indices.size();
    face.count = 3;
    face.where = t;
    for (int c = 0; c < 3; ++c) {
      Vec3 p;
      for (int k = 0; k < 3; ++k) p[k] = load_bytes<float>(facet + 12 + 12 * c + 4 * k, true);
      if (!finite(p)) throw_io(file, "triangle " + std::to_string(t) + ": " + describe_non_finite(p));
      raw.indices.push_back(merger.add(p));
    }
    raw.faces.push_back(face);
  }
  if (n == 0) raw.warnings.push_back("the file contains no triangles");
  return raw;
}

}  // namespace

RawMesh parse_stl(std::string_view data, const fs::path& file) {
  if (data.size() >= 84) {
    const uint64_t n = load_bytes<uint32_t>(data.data() + 80, true);
    if (84 + 50 * n == data.size()) return parse_stl_binary(data, file);
  }
  const std::string_view text = skip_utf8_bom(data);
  if (starts_with_solid(text) && !looks_binary(text)) return parse_stl_ascii(text, file);
  return parse_stl_binary(data, file);
}

RawMesh parse_mesh_file(std::string_view data, const fs::path& file, const std::string& ext,
                        const ParseOptions& options) {
  if (data.empty()) throw_io(file, "file is empty");
  RawMesh raw;
  if (ext == ".off") {
    raw = parse_off(data, file);
  } else if (ext == ".obj") {
    raw = parse_obj(data, file);
  } else if (ext == ".ply") {
    raw = parse_ply(data, file, options);
  } else if (ext == ".stl") {
    raw = parse_stl(data, file);
  } else {
    EF_CHECK(false, "parse_mesh_file: unknown extension " + ext);
  }
  if (std::string why = coordinate_range_problem(raw.points, "vertex"); !why.empty()) throw_io(file, why);
  return raw;
}

}  // namespace edgefront::detail
