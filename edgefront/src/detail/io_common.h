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

/// The content of a regular file, mapped read-only into memory (or read, where the file system
/// cannot map it). Mapping costs nothing up front: a parser that refuses a file after its first
/// bytes (a 2 GB sparse file, binary garbage given to a text reader) touches only those pages.
///
/// Anything but a regular file (a directory, a FIFO, /dev/zero or another device, a socket) is
/// refused before it is opened, so that nothing blocks or reads without end. The file is opened
/// non-blocking and checked again after opening (it may have been replaced in between).
/// \throw IoError when the file is missing, not a regular file, unreadable, or empty ("file is
///        empty").
/// \note A file truncated by another process while it is mapped raises SIGBUS on access, as with
///       every mapped reader.
class FileContent {
 public:
  explicit FileContent(const std::filesystem::path& file);
  ~FileContent();
  FileContent(const FileContent&) = delete;
  FileContent& operator=(const FileContent&) = delete;
  std::string_view view() const { return view_; }

 private:
  void* map_ = nullptr;
  size_t map_size_ = 0;
  std::string copy_;  ///< the content when it could not be mapped
  std::string_view view_;
};

/// True when the first bytes of `data` contain a NUL byte (a binary file given to a text reader).
bool looks_binary(std::string_view data);

/// `data` without a leading UTF-8 byte-order mark (EF BB BF), which some editors write at the
/// start of text files.
std::string_view skip_utf8_bom(std::string_view data);

/// The start of a text reader: `data` without a UTF-8 byte-order mark. Throws IoError "not a
/// <format> file: ..." when `data` is UTF-16 text (its byte-order mark) or contains binary data.
std::string_view text_content(std::string_view data, const std::filesystem::path& file, const char* format);

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
/// "inf"). False when the token is not a number or is out of the range of double (a number
/// too small for a double reads as 0 or a denormal).
bool parse_double(std::string_view token, double& value);
/// What is wrong with a token parse_double refused, for a message: "malformed number 'x1'" or
/// "number '1e400' is out of the range of a double (+-1.8e308)".
std::string bad_number(std::string_view token);
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
