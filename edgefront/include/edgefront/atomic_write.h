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
/// \throw IoError naming `target` when the directory does not exist or is not writable, when `body`
///        throws (the original exception is attached with `std::throw_with_nested`), when the
///        stream reports an error (disk full, ...), or when the rename fails. In every failure case
///        the temporary file is removed and an existing `target` is left untouched.
/// \note If `target` is a symbolic link, the link itself is replaced by a regular file.
void write_file_atomically(const std::filesystem::path& target,
                           const std::function<void(std::ostream&)>& body, bool binary);

}  // namespace edgefront
