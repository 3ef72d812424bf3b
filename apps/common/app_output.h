#pragma once
/// \file app_output.h
/// Output helpers shared by the command-line tools: file extensions and text output. (The
/// colormap is edgefront::render::colormap, render/color.h.)

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <iostream>
#include <string>

#include "edgefront/atomic_write.h"
#include "edgefront/error.h"

namespace edgefront::apps {

/// Lower-case extension of `path` (".txt", ".ply", ...).
inline std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

/// Writes `text` to `output` atomically, or to standard output when `output` is empty.
/// \throws edgefront::IoError when it cannot be written.
inline void write_text(const std::filesystem::path& output, const std::string& text) {
  if (output.empty()) {
    std::cout.write(text.data(), static_cast<std::streamsize>(text.size()));
    std::cout.flush();
    if (!std::cout) throw edgefront::IoError("cannot write to standard output");
  } else {
    edgefront::write_file_atomically(output, [&text](std::ostream& os) { os << text; }, false);
  }
}

}  // namespace edgefront::apps
