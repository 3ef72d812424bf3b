#include "edgefront/atomic_write.h"

#include <atomic>
#include <cerrno>
#include <cstring>
#include <exception>
#include <fstream>
#include <mutex>
#include <string>
#include <string_view>
#include <system_error>

#if defined(__unix__) || defined(__APPLE__)
#include <fcntl.h>
#include <signal.h>
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

// ---------------------------------------------------------------------------------------------
// Temporaries removed on SIGINT, SIGTERM and SIGHUP
//
// The live temporaries are kept in a fixed table of slots that a signal handler can walk without
// locks or allocation: a slot is claimed with a compare-and-swap, filled, then marked live; the
// handler unlinks the live ones (unlink is async-signal-safe), restores the default action and
// raises the signal again, so the process ends as it would have without the handler. The handlers
// are installed on the first write, only for signals whose action is still the default (an
// application's own handler, or an ignored signal, is left alone). A write beyond the table's
// capacity, or a SIGKILL, leaves its temporary to the clean-up of stale temporaries below.

#ifdef EDGEFRONT_HAVE_POSIX

constexpr int kSlots = 64;
constexpr size_t kMaxPath = 4096;
enum SlotState : int { kFree = 0, kBusy = 1, kLive = 2 };

struct Slot {
  std::atomic<int> state{kFree};
  char path[kMaxPath];
};
Slot g_slots[kSlots];
constexpr int kSignals[] = {SIGINT, SIGTERM, SIGHUP};

void remove_temporaries_and_reraise(int signal_number) {
  const int saved_errno = errno;
  for (Slot& slot : g_slots) {
    if (slot.state.load(std::memory_order_acquire) == kLive) ::unlink(slot.path);
  }
  errno = saved_errno;
  // SA_RESETHAND restored the default action on entry: the raised signal, delivered when the
  // handler returns, ends the process.
  ::raise(signal_number);
}

void install_handlers_once() {
  static std::once_flag once;
  std::call_once(once, [] {
    for (const int signal_number : kSignals) {
      struct sigaction previous {};
      if (::sigaction(signal_number, nullptr, &previous) != 0) continue;
      if ((previous.sa_flags & SA_SIGINFO) || previous.sa_handler != SIG_DFL) continue;
      struct sigaction action {};
      action.sa_handler = remove_temporaries_and_reraise;
      sigemptyset(&action.sa_mask);
      action.sa_flags = SA_RESETHAND;
      ::sigaction(signal_number, &action, nullptr);
    }
  });
}

/// Registers `path` for removal on a signal; returns its slot, or -1 (path too long, table full).
int register_temporary(const fs::path& path) {
  std::error_code ec;
  const std::string absolute = fs::absolute(path, ec).string();
  if (ec || absolute.size() >= kMaxPath) return -1;
  install_handlers_once();
  for (int i = 0; i < kSlots; ++i) {
    int expected = kFree;
    if (!g_slots[i].state.compare_exchange_strong(expected, kBusy, std::memory_order_acq_rel)) continue;
    std::memcpy(g_slots[i].path, absolute.c_str(), absolute.size() + 1);
    g_slots[i].state.store(kLive, std::memory_order_release);
    return i;
  }
  return -1;
}

void unregister_temporary(int slot) {
  if (slot >= 0) g_slots[slot].state.store(kFree, std::memory_order_release);
}

/// Removes the temporaries `.<name>.tmp-<pid>-<n>` of `target` left by processes that no longer
/// run (killed while writing, or beyond the signal table). Best effort: errors are ignored.
/// \note A process in another PID namespace writing the same target looks dead from here.
void remove_stale_temporaries(const fs::path& target) {
  std::string prefix(".");  // appended: GCC 12 reports a false -Wrestrict on "." + std::string&&
  prefix.append(target.filename().string()).append(".tmp-");
  const fs::path dir = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  const long own = static_cast<long>(::getpid());
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec); !ec && it != fs::directory_iterator(); it.increment(ec)) {
    const fs::directory_entry& entry = *it;
    const std::string name = entry.path().filename().string();
    if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) continue;
    // <pid>-<counter>, digits only
    const std::string_view rest = std::string_view(name).substr(prefix.size());
    const size_t dash = rest.find('-');
    if (dash == 0 || dash == std::string_view::npos || dash + 1 == rest.size() || dash > 9) continue;
    if (rest.find_first_not_of("0123456789", 0) != dash ||
        rest.find_first_not_of("0123456789", dash + 1) != std::string_view::npos) {
      continue;
    }
    const long pid = std::stol(std::string(rest.substr(0, dash)));
    if (pid <= 0 || pid == own) continue;
    if (::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH) continue;  // alive (or not ours to judge)
    std::error_code remove_ec;
    fs::remove(entry.path(), remove_ec);
  }
}

#else

int register_temporary(const fs::path&) { return -1; }
void unregister_temporary(int) {}
void remove_stale_temporaries(const fs::path&) {}

#endif

/// Removes the temporary file unless it was renamed (disarmed), and keeps it registered for the
/// signal handlers while it exists.
class TemporaryGuard {
 public:
  explicit TemporaryGuard(fs::path path) : path_(std::move(path)), slot_(register_temporary(path_)) {}
  TemporaryGuard(const TemporaryGuard&) = delete;
  TemporaryGuard& operator=(const TemporaryGuard&) = delete;
  ~TemporaryGuard() {
    if (armed_) {
      std::error_code ec;
      fs::remove(path_, ec);
    }
    unregister_temporary(slot_);
  }
  void disarm() { armed_ = false; }

 private:
  fs::path path_;
  int slot_;
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
  if (fs::exists(target_status) && !fs::is_regular_file(target_status)) {
    // Renaming over it would replace a FIFO or a device such as /dev/null with a regular file.
    fail(target, "the path exists and is not a regular file (a FIFO, device or socket): not replaced");
  }

  remove_stale_temporaries(target);
  const fs::path tmp = temporary_name(target);
  TemporaryGuard guard(tmp);  // registered for the signal handlers before the file exists
  std::ios::openmode mode = std::ios::out | std::ios::trunc;
  if (binary) mode |= std::ios::binary;
  std::ofstream out(tmp, mode);
  if (!out.is_open()) {
    const int err = errno;
    fail(target, "cannot create a temporary file in '" + (dir.empty() ? std::string(".") : dir.string()) +
                     "'" + (err != 0 ? std::string(": ") + std::strerror(err) : std::string()));
  }

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
