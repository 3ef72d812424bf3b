#pragma once
/// \file io_common.h
/// Private helpers shared by the readers and writers: whole-file reading, error messages that
/// name the file and line, line splitting, strict number parsing, shortest round-trip number
/// formatting, byte order.

#include <array>
#include <bit>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace edgefront::detail {

/// Lower-case extension including the dot (".ply"), or empty.
std::string lower_extension(const std::filesystem::path& path);

/// Throws IoError "<file>: <what>".
[[noreturn]] void throw_io(const std::filesystem::path& file, const std::string& what);
/// Throws IoError "<file>: line <line>: <what>".
[[noreturn]] void throw_io_line(const std::filesystem::path& file, size_t line, const std::string& what);

/// The whole content of `file`. Throws IoError when the file is missing, a directory, unreadable,
/// or empty ("file is empty").
std::string read_whole_file(const std::filesystem::path& file);

/// True when the first bytes of `data` contain a NUL byte (a binary file given to a text reader).
bool looks_binary(std::string_view data);

/// `token` quoted for an error message, shortened and with unprintable bytes escaped.
std::string quote(std::string_view token);

/// Iterates the lines of a text buffer. Lines end with "\n", "\r\n" or end of data; the line
/// terminator is not part of the returned line.
class LineReader {
 public:
  explicit LineReader(std::string_view data, size_t first_line_number = 1)
      : data_(data), next_line_number_(first_line_number) {}
  /// Next line, or false at end of data.
  bool next(std::string_view& line);
  /// Number (1-based) of the line returned last.
  size_t line_number() const { return next_line_number_ - 1; }
  /// Bytes not consumed yet.
  size_t remaining() const { return data_.size() - pos_; }
  /// True when no more lines follow.
  bool at_end() const { return pos_ >= data_.size(); }

 private:
  std::string_view data_;
  size_t pos_ = 0;
  size_t next_line_number_;
};

/// `line` without a '#' comment and surrounding whitespace.
std::string_view strip_comment(std::string_view line);

/// Splits `line` at blanks (space, tab, \r, \v, \f) into `tokens` (cleared first).
void split_tokens(std::string_view line, std::vector<std::string_view>& tokens);

/// Strict parse of a whole token as a decimal floating-point number ("1", "-2.5e3", "+4", "nan",
/// "inf"). False when the token is not a number or is out of the range of double.
bool parse_double(std::string_view token, double& value);
/// Strict parse of a whole token as a decimal integer (optional sign).
bool parse_int64(std::string_view token, int64_t& value);
/// Strict parse of a whole token as a non-negative decimal integer.
bool parse_uint64(std::string_view token, uint64_t& value);

/// Appends the shortest decimal text that reads back as exactly `value` ("inf", "-inf", "nan" for
/// non-finite values).
void append_double(std::string& out, double value);
void append_int(std::string& out, long long value);

/// Byte order helpers: appends `value` in little-endian order.
template <class T>
void append_le(std::string& out, T value) {
  std::array<char, sizeof(T)> bytes;
  std::memcpy(bytes.data(), &value, sizeof(T));
  if constexpr (std::endian::native == std::endian::big) {
    for (size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(bytes[i], bytes[sizeof(T) - 1 - i]);
  }
  out.append(bytes.data(), sizeof(T));
}

/// Reads a `T` stored at `p` in the given byte order.
template <class T>
T load_bytes(const char* p, bool little_endian) {
  std::array<char, sizeof(T)> bytes;
  std::memcpy(bytes.data(), p, sizeof(T));
  const bool native_little = std::endian::native == std::endian::little;
  if (little_endian != native_little) {
    for (size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(bytes[i], bytes[sizeof(T) - 1 - i]);
  }
  T value;
  std::memcpy(&value, bytes.data(), sizeof(T));
  return value;
}

/// The count with its noun, singular or plural: "1 face", "2 faces".
std::string count_noun(size_t n, const char* singular, const char* plural);

}  // namespace edgefront::detail
