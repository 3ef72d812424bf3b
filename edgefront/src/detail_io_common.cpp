#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <system_error>

#include "detail/io_common.h"
#include "edgefront/error.h"

namespace edgefront::detail {

namespace fs = std::filesystem;

std::string lower_extension(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

void throw_io(const fs::path& file, const std::string& what) { throw IoError(file.string() + ": " + what); }

void throw_io_line(const fs::path& file, size_t line, const std::string& what) {
  throw IoError(file.string() + ": line " + std::to_string(line) + ": " + what);
}

std::string read_whole_file(const fs::path& file) {
  std::error_code ec;
  const fs::file_status st = fs::status(file, ec);
  if (!fs::exists(st)) throw_io(file, "file does not exist");
  if (fs::is_directory(st)) throw_io(file, "is a directory, not a file");
  std::ifstream in(file, std::ios::binary);
  if (!in.is_open()) {
    const int err = errno;
    throw_io(file, std::string("cannot open the file for reading") +
                       (err != 0 ? std::string(": ") + std::strerror(err) : std::string()));
  }
  std::string data;
  if (fs::is_regular_file(st)) {
    const uintmax_t size = fs::file_size(file, ec);
    if (!ec) data.reserve(static_cast<size_t>(size));
  }
  char buffer[1 << 16];
  while (in) {
    in.read(buffer, sizeof(buffer));
    data.append(buffer, static_cast<size_t>(in.gcount()));
  }
  if (in.bad()) throw_io(file, "read error");
  if (data.empty()) throw_io(file, "file is empty");
  return data;
}

bool looks_binary(std::string_view data) {
  const std::string_view head = data.substr(0, 4096);
  return head.find('\0') != std::string_view::npos;
}

std::string quote(std::string_view token) {
  constexpr size_t kMax = 40;
  std::string out = "'";
  const size_t n = std::min(token.size(), kMax);
  for (size_t i = 0; i < n; ++i) {
    const unsigned char c = static_cast<unsigned char>(token[i]);
    if (c >= 0x20 && c < 0x7f) {
      out += static_cast<char>(c);
    } else {
      static const char* hex = "0123456789abcdef";
      out += "\\x";
      out += hex[c >> 4];
      out += hex[c & 15];
    }
  }
  if (token.size() > kMax) out += "...";
  out += "'";
  return out;
}

bool LineReader::next(std::string_view& line) {
  if (pos_ >= data_.size()) return false;
  const size_t end = data_.find('\n', pos_);
  size_t stop = end == std::string_view::npos ? data_.size() : end;
  line = data_.substr(pos_, stop - pos_);
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  pos_ = end == std::string_view::npos ? data_.size() : end + 1;
  ++next_line_number_;
  return true;
}

namespace {
bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }
}  // namespace

std::string_view strip_comment(std::string_view line) {
  const size_t hash = line.find('#');
  if (hash != std::string_view::npos) line = line.substr(0, hash);
  while (!line.empty() && is_blank(line.front())) line.remove_prefix(1);
  while (!line.empty() && is_blank(line.back())) line.remove_suffix(1);
  return line;
}

void split_tokens(std::string_view line, std::vector<std::string_view>& tokens) {
  tokens.clear();
  size_t i = 0;
  const size_t n = line.size();
  while (i < n) {
    while (i < n && is_blank(line[i])) ++i;
    if (i >= n) break;
    const size_t start = i;
    while (i < n && !is_blank(line[i])) ++i;
    tokens.push_back(line.substr(start, i - start));
  }
}

bool parse_double(std::string_view token, double& value) {
  if (token.empty()) return false;
  if (token.front() == '+') {
    token.remove_prefix(1);
    if (token.empty() || token.front() == '-' || token.front() == '+') return false;
  }
  const char* first = token.data();
  const char* last = first + token.size();
  const auto [ptr, ec] = std::from_chars(first, last, value, std::chars_format::general);
  if (ec == std::errc::result_out_of_range) {
    // Underflow to a denormal or zero is harmless; overflow is not.
    double probe = 0;
    std::string copy(token);
    char* end = nullptr;
    errno = 0;
    probe = std::strtod(copy.c_str(), &end);
    if (end != copy.c_str() + copy.size() || std::isinf(probe)) return false;
    value = probe;
    return true;
  }
  return ec == std::errc() && ptr == last;
}

bool parse_int64(std::string_view token, int64_t& value) {
  if (token.empty()) return false;
  if (token.front() == '+') {
    token.remove_prefix(1);
    if (token.empty() || token.front() == '-') return false;
  }
  const char* last = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), last, value);
  return ec == std::errc() && ptr == last;
}

bool parse_uint64(std::string_view token, uint64_t& value) {
  if (token.empty()) return false;
  if (token.front() == '+') token.remove_prefix(1);
  if (token.empty() || token.front() == '-') return false;
  const char* last = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), last, value);
  return ec == std::errc() && ptr == last;
}

void append_double(std::string& out, double value) {
  if (std::isnan(value)) {
    out += "nan";
    return;
  }
  if (std::isinf(value)) {
    out += value > 0 ? "inf" : "-inf";
    return;
  }
  char buffer[64];
  const auto [ptr, ec] = std::to_chars(buffer, buffer + sizeof(buffer), value);
  EF_CHECK(ec == std::errc(), "to_chars failed for a double");
  out.append(buffer, ptr);
}

void append_int(std::string& out, long long value) {
  char buffer[32];
  const auto [ptr, ec] = std::to_chars(buffer, buffer + sizeof(buffer), value);
  EF_CHECK(ec == std::errc(), "to_chars failed for an integer");
  out.append(buffer, ptr);
}

std::string count_noun(size_t n, const char* singular, const char* plural) {
  return std::to_string(n) + " " + (n == 1 ? singular : plural);
}

}  // namespace edgefront::detail
