#include "edgefront/atomic_write.h"

#include <atomic>
#include <cerrno>
#include <cstring>
#include <exception>
#include <fstream>
#include <string>
#include <system_error>

#if defined(__unix__) || defined(__APPLE__)
#include <fcntl.h>
#include <unistd.h>
#define EDGEFRONT_HAVE_POSIX 1
#endif

#include "edgefront/error.h"

namespace edgefront {

namespace {

namespace fs = std::filesystem;

[[noreturn]] void fail(const fs::path& target, const std::string& what) {
  throw IoError(target.string() + ": cannot write: " + what);
}

long process_id() {
#ifdef EDGEFRONT_HAVE_POSIX
  return static_cast<long>(::getpid());
#else
  return 0;
#endif
}

/// A temporary name next to `target` that does not exist yet.
fs::path temporary_name(const fs::path& target) {
  static std::atomic<unsigned long> counter{0};
  const fs::path dir = target.parent_path();
  for (int attempt = 0; attempt < 1000; ++attempt) {
    // Built with append: GCC 12 reports a false -Wrestrict on chained operator+ here.
    std::string name(".");
    name.append(target.filename().string());
    name.append(".tmp-");
    name.append(std::to_string(process_id()));
    name.append("-");
    name.append(std::to_string(counter.fetch_add(1)));
    fs::path candidate = dir.empty() ? fs::path(name) : dir / name;
    std::error_code ec;
    if (!fs::exists(candidate, ec) && !ec) return candidate;
  }
  fail(target, "could not find an unused temporary file name");
}

/// Flushes the file's data to the storage device. Returns an empty string or the error.
std::string sync_file(const fs::path& file) {
#ifdef EDGEFRONT_HAVE_POSIX
  const int fd = ::open(file.c_str(), O_RDONLY);
  if (fd < 0) return std::strerror(errno);
  std::string error;
  if (::fsync(fd) != 0 && errno != EINVAL && errno != EROFS) error = std::strerror(errno);
  ::close(fd);
  return error;
#else
  (void)file;
  return {};
#endif
}

/// Removes the temporary file unless it was renamed (disarmed).
class TemporaryGuard {
 public:
  explicit TemporaryGuard(fs::path path) : path_(std::move(path)) {}
  TemporaryGuard(const TemporaryGuard&) = delete;
  TemporaryGuard& operator=(const TemporaryGuard&) = delete;
  ~TemporaryGuard() {
    if (armed_) {
      std::error_code ec;
      fs::remove(path_, ec);
    }
  }
  void disarm() { armed_ = false; }

 private:
  fs::path path_;
  bool armed_ = true;
};

}  // namespace

void write_file_atomically(const fs::path& target, const std::function<void(std::ostream&)>& body,
                           bool binary) {
  if (target.empty()) throw IoError("cannot write a file with an empty path");
  if (!target.has_filename()) fail(target, "the path names a directory, not a file");
  if (!body) fail(target, "no content writer was given");

  const fs::path dir = target.parent_path();
  std::error_code ec;
  if (!dir.empty()) {
    const fs::file_status st = fs::status(dir, ec);
    if (!fs::exists(st)) fail(target, "directory '" + dir.string() + "' does not exist");
    if (!fs::is_directory(st)) fail(target, "'" + dir.string() + "' is not a directory");
  }
  const fs::file_status target_status = fs::status(target, ec);
  if (fs::is_directory(target_status)) fail(target, "the path is a directory");

  const fs::path tmp = temporary_name(target);
  std::ios::openmode mode = std::ios::out | std::ios::trunc;
  if (binary) mode |= std::ios::binary;
  std::ofstream out(tmp, mode);
  if (!out.is_open()) {
    const int err = errno;
    fail(target, "cannot create a temporary file in '" + (dir.empty() ? std::string(".") : dir.string()) +
                     "'" + (err != 0 ? std::string(": ") + std::strerror(err) : std::string()));
  }
  TemporaryGuard guard(tmp);

  try {
    body(out);
  } catch (const std::exception& e) {
    out.close();
    std::throw_with_nested(IoError(target.string() + ": cannot write: " + e.what()));
  } catch (...) {
    out.close();
    std::throw_with_nested(IoError(target.string() + ": cannot write: unknown error while writing"));
  }

  out.flush();
  if (!out) fail(target, "error while writing the data (disk full?)");
  out.close();
  if (out.fail()) fail(target, "error while closing the file (disk full?)");

  const std::string sync_error = sync_file(tmp);
  if (!sync_error.empty()) fail(target, "cannot sync the data to disk: " + sync_error);

  if (fs::exists(target_status)) {
    fs::permissions(tmp, target_status.permissions(), fs::perm_options::replace, ec);  // best effort
  }
  fs::rename(tmp, target, ec);
  if (ec) fail(target, "cannot rename the temporary file over the target: " + ec.message());
  guard.disarm();
}

}  // namespace edgefront
