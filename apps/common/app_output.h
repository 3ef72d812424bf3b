#pragma once
/// \file app_output.h
/// Output helpers shared by the command-line tools: file extensions. (The colormap is
/// edgefront::render::colormap, render/color.h.)

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>

namespace edgefront::apps {

/// Lower-case extension of `path` (".txt", ".ply", ...).
inline std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

}  // namespace edgefront::apps
