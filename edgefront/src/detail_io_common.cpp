#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <system_error>

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

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

namespace {

/// What a file of mode `mode` is, for a message ("a FIFO (named pipe)"), or empty for a regular file.
std::string non_regular_kind(mode_t mode) {
  if (S_ISREG(mode)) return {};
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

[[noreturn]] void throw_not_regular(const fs::path& file, const std::string& kind) {
  throw_io(file, "is " + kind + ", not a regular file (give the path of a mesh or point file)");
}

[[noreturn]] void throw_errno(const fs::path& file, const char* what, int err) {
  throw_io(file, std::string(what) + (err != 0 ? std::string(": ") + std::strerror(err) : std::string()));
}

}  // namespace

FileContent::FileContent(const fs::path& file) {
  // stat before open: opening a FIFO for reading blocks until a writer comes.
  struct stat st {};
  if (::stat(file.c_str(), &st) != 0) {
    const int err = errno;
    if (err == ENOENT) throw_io(file, "file does not exist");
    throw_errno(file, "cannot open the file for reading", err);
  }
  if (const std::string kind = non_regular_kind(st.st_mode); !kind.empty()) throw_not_regular(file, kind);
  const int fd = ::open(file.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
  if (fd < 0) throw_errno(file, "cannot open the file for reading", errno);
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  if (::fstat(fd, &st) != 0) throw_errno(file, "cannot read the file", errno);
  if (const std::string kind = non_regular_kind(st.st_mode); !kind.empty()) throw_not_regular(file, kind);
  const uint64_t size = static_cast<uint64_t>(st.st_size);
  if (size > std::numeric_limits<size_t>::max() / 2) throw_io(file, "file is too large to read");
  if (size > 0) {
    void* map = ::mmap(nullptr, static_cast<size_t>(size), PROT_READ, MAP_PRIVATE, fd, 0);
    if (map != MAP_FAILED) {
      map_ = map;
      map_size_ = static_cast<size_t>(size);
      ::madvise(map_, map_size_, MADV_SEQUENTIAL);
      view_ = std::string_view(static_cast<const char*>(map_), map_size_);
      return;
    }
  }
  // Not mappable, or a size of 0 that may still have content (/proc files): read to the end.
  copy_.reserve(static_cast<size_t>(size));
  char buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof(buffer));
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw_errno(file, "read error", errno);
    if (n == 0) break;
    copy_.append(buffer, static_cast<size_t>(n));
  }
  if (copy_.empty()) throw_io(file, "file is empty");
  view_ = copy_;
}

FileContent::~FileContent() {
  if (map_ != nullptr) ::munmap(map_, map_size_);
}

bool looks_binary(std::string_view data) {
  const std::string_view head = data.substr(0, 4096);
  return head.find('\0') != std::string_view::npos;
}

std::string_view skip_utf8_bom(std::string_view data) {
  if (data.substr(0, 3) == "\xEF\xBB\xBF") data.remove_prefix(3);
  return data;
}

std::string_view text_content(std::string_view data, const fs::path& file, const char* format) {
  const std::string_view head = data.substr(0, 2);
  if (head == "\xFF\xFE" || head == "\xFE\xFF") {
    throw_io(file, std::string("not ") + format + " file: it is UTF-16 text (save it as ASCII or UTF-8)");
  }
  if (looks_binary(data)) throw_io(file, std::string("not ") + format + " file: it contains binary data");
  return skip_utf8_bom(data);
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

std::string bad_number(std::string_view token) {
  // parse_double refuses a number beyond the range of double (it accepts underflow).
  std::string_view digits = token;
  if (!digits.empty() && digits.front() == '+') digits.remove_prefix(1);
  double value = 0;
  const char* end = digits.data() + digits.size();
  const std::from_chars_result r = std::from_chars(digits.data(), end, value, std::chars_format::general);
  if (!token.empty() && r.ec == std::errc::result_out_of_range && r.ptr == end) {
    return "number " + quote(token) + " is out of the range of a double (+-" +
           number_for_message(std::numeric_limits<double>::max()) + ")";
  }
  return "malformed number " + quote(token);
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
