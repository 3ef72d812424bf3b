// PNG files through libpng's simplified API (png_image_*), which reports errors through the
// png_image's message instead of longjmp, so no setjmp is needed here.
#include <png.h>

#include <cstring>
#include <string>

#include "edgefront/atomic_write.h"
#include "edgefront/error.h"
#include "render/image.h"

namespace edgefront::render {

Image::Image(int w, int h, const Rgb& fill) : width(w > 0 ? w : 0), height(h > 0 ? h : 0) {
  rgb.resize(3 * static_cast<size_t>(width) * static_cast<size_t>(height));
  for (size_t i = 0; i < rgb.size(); i += 3) {
    rgb[i] = fill[0];
    rgb[i + 1] = fill[1];
    rgb[i + 2] = fill[2];
  }
}

void write_png(const Image& image, const std::filesystem::path& path) {
  if (image.width <= 0 || image.height <= 0) {
    throw InvalidInput("write_png: the image is empty (" + std::to_string(image.width) + "x" +
                       std::to_string(image.height) + " pixels)");
  }
  if (image.rgb.size() != 3 * static_cast<size_t>(image.width) * static_cast<size_t>(image.height)) {
    throw InvalidInput("write_png: the pixel buffer has " + std::to_string(image.rgb.size()) + " bytes, expected 3 x " +
                       std::to_string(image.width) + " x " + std::to_string(image.height));
  }
  png_image png;
  std::memset(&png, 0, sizeof(png));
  png.version = PNG_IMAGE_VERSION;
  png.width = static_cast<png_uint_32>(image.width);
  png.height = static_cast<png_uint_32>(image.height);
  png.format = PNG_FORMAT_RGB;
  const png_int_32 stride = 3 * image.width;
  // First call: the size needed; second call: the encoding.
  png_alloc_size_t size = 0;
  if (!png_image_write_to_memory(&png, nullptr, &size, 0, image.rgb.data(), stride, nullptr)) {
    const std::string message = png.message;
    png_image_free(&png);
    throw IoError("cannot encode PNG for '" + path.string() + "': " + message);
  }
  std::vector<unsigned char> bytes(size);
  if (!png_image_write_to_memory(&png, bytes.data(), &size, 0, image.rgb.data(), stride, nullptr)) {
    const std::string message = png.message;
    png_image_free(&png);
    throw IoError("cannot encode PNG for '" + path.string() + "': " + message);
  }
  png_image_free(&png);
  bytes.resize(size);
  write_file_atomically(
      path,
      [&bytes](std::ostream& os) {
        os.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
      },
      true);
}

Image read_png(const std::filesystem::path& path) {
  png_image png;
  std::memset(&png, 0, sizeof(png));
  png.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&png, path.c_str())) {
    const std::string message = png.message;
    png_image_free(&png);
    throw IoError("cannot read PNG '" + path.string() + "': " + message);
  }
  png.format = PNG_FORMAT_RGB;
  Image image;
  image.width = static_cast<int>(png.width);
  image.height = static_cast<int>(png.height);
  image.rgb.resize(PNG_IMAGE_SIZE(png));
  if (!png_image_finish_read(&png, nullptr, image.rgb.data(), 0, nullptr)) {
    const std::string message = png.message;
    png_image_free(&png);
    throw IoError("cannot read PNG '" + path.string() + "': " + message);
  }
  png_image_free(&png);
  return image;
}

}  // namespace edgefront::render
