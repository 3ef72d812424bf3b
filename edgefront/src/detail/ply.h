#pragma once
/// \file ply.h
/// Private PLY support shared by the mesh and point-cloud readers and writers: a strict header
/// parser and a body reader for ascii, binary_little_endian and binary_big_endian data that
/// walks every element (skipping the ones a caller does not want, lists included).

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace edgefront::detail {

enum class PlyFormat { kAscii, kBinaryLittleEndian, kBinaryBigEndian };

enum class PlyType : uint8_t { kInt8, kUInt8, kInt16, kUInt16, kInt32, kUInt32, kFloat32, kFloat64 };

/// Size in bytes of one value of `type`.
size_t ply_type_size(PlyType type);
/// True for the integer types.
bool ply_type_is_integer(PlyType type);

struct PlyProperty {
  std::string name;
  bool is_list = false;
  PlyType type = PlyType::kFloat32;      ///< value type (item type of a list)
  PlyType count_type = PlyType::kUInt8;  ///< list count type (lists only)
};

struct PlyElement {
  std::string name;
  uint64_t count = 0;
  std::vector<PlyProperty> properties;
  size_t header_line = 0;  ///< line of the `element` record in the header

  /// Index of the property called `name`, or -1.
  int find(std::string_view property_name) const;
};

struct PlyHeader {
  PlyFormat format = PlyFormat::kAscii;
  std::vector<PlyElement> elements;
  std::vector<std::string> comments;
  size_t body_offset = 0;      ///< byte offset of the first body byte
  size_t body_first_line = 0;  ///< line number of the first body line (ascii)

  /// Index of the element called `name`, or -1.
  int find(std::string_view element_name) const;
};

/// True when `data` starts with the PLY magic line.
bool has_ply_magic(std::string_view data);

/// Parses the header of `data`. Checks the magic, the format line, element and property records,
/// and that the declared element counts can fit in the bytes that follow the header (so a header
/// claiming 10^12 elements is refused before anything is allocated).
/// \throw IoError naming `file` and the header line.
PlyHeader parse_ply_header(std::string_view data, const std::filesystem::path& file);

/// One instance of an element: `values[i]` is the value of scalar property i (for a list
/// property, its item count), `lists[i]` the items of list property i (empty for scalars, and
/// for lists the caller did not ask for).
struct PlyInstance {
  std::vector<double> values;
  std::vector<std::vector<double>> lists;
};

/// Reads the body element by element, in header order.
class PlyBodyReader {
 public:
  PlyBodyReader(std::string_view data, const PlyHeader& header, const std::filesystem::path& file);

  /// Index of the element whose instances come next, or -1 after the last element.
  int current_element() const { return element_; }
  /// Reads the next instance of the current element into `out`. List items are stored only for
  /// the properties with `want_list[i]` true (`want_list` may be empty: no lists stored).
  void read_instance(PlyInstance& out, const std::vector<bool>& want_list);
  /// Skips all remaining instances of the current element.
  void skip_element();
  /// Index (0-based) of the instance read last within its element.
  uint64_t instance_index() const { return last_instance_; }
  /// Where the instance read last is, for messages: "line 12 (face 7)" (ascii) or "face 7".
  std::string where() const;
  /// Line of the instance read last (ascii only; 0 for binary data).
  size_t instance_line() const { return instance_line_; }
  /// True for ascii bodies.
  bool is_ascii() const { return header_.format == PlyFormat::kAscii; }
  /// True when non-blank data follows the last element.
  bool has_trailing_data() const;

  /// Throws IoError "<file>: <where()>: <what>".
  [[noreturn]] void fail(const std::string& what) const;

 private:
  void advance_element();
  void read_ascii(PlyInstance& out, const std::vector<bool>& want_list);
  void read_binary(PlyInstance& out, const std::vector<bool>& want_list);
  double read_binary_value(PlyType type);

  std::string_view data_;
  const PlyHeader& header_;
  const std::filesystem::path& file_;
  size_t pos_;
  size_t line_;
  size_t instance_line_ = 0;
  std::string last_element_name_;
  uint64_t last_instance_ = 0;
  int element_ = -1;
  uint64_t instance_ = 0;
  std::vector<std::string_view> tokens_;
};

/// The PLY type name used when writing ("double", "uchar", "int").
const char* ply_type_name(PlyType type);

}  // namespace edgefront::detail
