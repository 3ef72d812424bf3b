#pragma once
/// \file atomic_write.h
/// Write a file so that readers see either the old content or the complete new content, never a
/// partial file.

#include <filesystem>
#include <functional>
#include <ostream>

namespace edgefront {

/// Writes `target` atomically.
///
/// `body` writes the complete content to the stream it is given. The stream is a temporary file in
/// the same directory as `target` (named `.<target name>.tmp-<pid>-<n>`); after `body` returns, the
/// stream is flushed, closed, its state checked, the data synced to disk (POSIX `fsync`), and the
/// temporary is renamed over `target` (an atomic replace on POSIX file systems). When `target`
/// already exists its permission bits are carried over to the new file.
///
/// `binary` opens the stream in binary mode (no effect on POSIX; matters on Windows).
///
/// Interrupted writes leave no temporary behind where that can be helped: on SIGINT, SIGTERM or
/// SIGHUP the live temporaries are removed and the process then ends by the signal as it would
/// have (the handlers are installed on the first write, only for signals still at their default
/// action: an application's own handler is left alone). A temporary of a process that no longer
/// runs (SIGKILL, a crash) is removed by the next write to the same target: its name holds the
/// writer's process id.
///
/// \throw IoError naming `target` when the directory does not exist or is not writable, when
///        `target` exists and is a directory, a FIFO, a device or a socket, when `body`
///        throws (the original exception is attached with `std::throw_with_nested`), when the
///        stream reports an error (disk full, ...), or when the rename fails. In every failure case
///        the temporary file is removed and an existing `target` is left untouched.
/// \note If `target` is a symbolic link, the link itself is replaced by a regular file.
void write_file_atomically(const std::filesystem::path& target,
                           const std::function<void(std::ostream&)>& body, bool binary);

}  // namespace edgefront
