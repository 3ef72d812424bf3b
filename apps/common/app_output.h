#pragma once
/// \file app_output.h
/// Output helpers shared by the command-line tools: file extensions and per-vertex colors.

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>

namespace edgefront::apps {

/// Lower-case extension of `path` (".txt", ".ply", ...).
inline std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

/// A color for t in [0, 1]: piecewise-linear through five stops from dark violet over blue and
/// teal to green and yellow (perceptually ordered, readable on a grey background).
inline std::array<uint8_t, 3> colormap(double t) {
  static constexpr std::array<std::array<double, 3>, 5> kStops = {{
      {68, 1, 84}, {59, 82, 139}, {33, 145, 140}, {94, 201, 98}, {253, 231, 37}}};
  t = std::clamp(t, 0.0, 1.0);
  const double x = t * static_cast<double>(kStops.size() - 1);
  const size_t i = std::min(static_cast<size_t>(x), kStops.size() - 2);
  const double f = x - static_cast<double>(i);
  std::array<uint8_t, 3> c{};
  for (size_t k = 0; k < 3; ++k) {
    c[k] = static_cast<uint8_t>(std::lround((1.0 - f) * kStops[i][k] + f * kStops[i + 1][k]));
  }
  return c;
}

}  // namespace edgefront::apps
