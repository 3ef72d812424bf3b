#pragma once
/// \file image.h
/// An 8-bit RGB image in memory (row-major, top row first), and PNG files of it.

#include <cstdint>
#include <filesystem>
#include <vector>

#include "render/color.h"

namespace edgefront::render {

/// An RGB image: `width` x `height` pixels, 3 bytes per pixel, rows top to bottom.
struct Image {
  int width = 0;   ///< pixels per row, >= 0
  int height = 0;  ///< rows, >= 0
  std::vector<std::uint8_t> rgb;  ///< size 3 * width * height

  Image() = default;
  /// A `width` x `height` image filled with `fill`. Negative sizes count as 0.
  Image(int w, int h, const Rgb& fill);

  /// The pixel at column `x`, row `y` (0, 0 is the top-left corner). No bounds check.
  Rgb at(int x, int y) const {
    const std::uint8_t* p = rgb.data() + 3 * (static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x));
    return {p[0], p[1], p[2]};
  }
  /// Sets the pixel at column `x`, row `y` to `c`. No bounds check.
  void set(int x, int y, const Rgb& c) {
    std::uint8_t* p = rgb.data() + 3 * (static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x));
    p[0] = c[0];
    p[1] = c[1];
    p[2] = c[2];
  }
};

/// Writes `image` as an 8-bit RGB PNG (libpng), atomically (edgefront/atomic_write.h): readers
/// see the old file or the complete new one.
/// \throw InvalidInput if the image is empty or its pixel buffer does not match its size.
/// \throw IoError naming `path` if libpng fails or the file cannot be written (missing or
///        unwritable directory, disk full).
void write_png(const Image& image, const std::filesystem::path& path);

/// Reads a PNG file (any bit depth and color type; converted to 8-bit RGB, alpha composited over
/// black by libpng's simplified API).
/// \throw IoError naming `path` if the file cannot be opened or is not a valid PNG.
Image read_png(const std::filesystem::path& path);

}  // namespace edgefront::render
