#pragma once
/// \file app_render.h
/// `--png FILE` for any command-line tool: adds the options
///   --png FILE         write a picture (offscreen render, render/render.h) to FILE.png
///   --azimuth DEG      camera azimuth around +y, 0 = from +z (default 30)
///   --elevation DEG    camera elevation, -90 ... 90 (default 20)
///   --size WxH         image size in pixels (default 800x600)
///   --orthographic     orthographic instead of perspective projection
/// and renders a render::Scene into FILE. In an app, three lines:
///
/// \code
///   edgefront::apps::PngOutput png(app);           // after the other add_option calls
///   ...                                            // in the run_app body, after computing:
///   if (png.requested()) png.write(scene);         // scene: mesh, field, lines, highlights
/// \endcode
///
/// Bad option values (a size that is not WxH within 1 ... 16384, an elevation outside [-90, 90],
/// a FILE not ending in .png) are parse errors: exit code 2 with a one-line message.

#include <charconv>
#include <chrono>
#include <cmath>
#include <iostream>
#include <string>

#include <CLI/CLI.hpp>

#include "app_output.h"
#include "edgefront/error.h"
#include "render/render.h"
#include "render/scene.h"

namespace edgefront::apps {

/// Parses "WxH" (e.g. "800x600") into `width`, `height`; an empty string when it is valid, else
/// what is wrong.
inline std::string parse_image_size(const std::string& text, int& width, int& height) {
  const size_t x = text.find_first_of("xX");
  const auto parse = [](const std::string& s, int& out) {
    const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
    return !s.empty() && ec == std::errc() && ptr == s.data() + s.size();
  };
  if (x == std::string::npos || !parse(text.substr(0, x), width) || !parse(text.substr(x + 1), height)) {
    return "--size: '" + text + "' is not WIDTHxHEIGHT (e.g. 800x600)";
  }
  if (width < 1 || height < 1 || width > render::kMaxImageSide || height > render::kMaxImageSide) {
    return "--size: " + text + " is out of range (each side 1 ... " + std::to_string(render::kMaxImageSide) +
           " pixels)";
  }
  return {};
}

/// The --png options of one app. Binds CLI11 options to its members: keep it alive and in place
/// until the app has parsed and run (not copyable, not movable).
class PngOutput {
 public:
  explicit PngOutput(CLI::App& app) : app_name_(app.get_name()) {
    app.add_option("--png", path_, "also write a rendered picture (offscreen) to FILE.png")
        ->type_name("FILE")
        ->check(CLI::Validator(
            [](std::string& p) {
              return lower_extension(p) == ".png" ? std::string() : "--png: '" + p + "' does not end in .png";
            },
            "FILE.png"));
    app.add_option("--azimuth", options_.azimuth_deg, "picture: camera azimuth in degrees around +y, 0 = from +z")
        ->capture_default_str()
        ->check(CLI::Range(-3600.0, 3600.0));
    app.add_option("--elevation", options_.elevation_deg, "picture: camera elevation in degrees, -90 ... 90")
        ->capture_default_str()
        ->check(CLI::Range(-90.0, 90.0));
    app.add_option("--size", size_, "picture: size in pixels, WIDTHxHEIGHT")
        ->capture_default_str()
        ->check(CLI::Validator(
            [](std::string& s) {
              int w = 0, h = 0;
              return parse_image_size(s, w, h);
            },
            "WxH"));
    app.add_flag("--orthographic", orthographic_, "picture: orthographic instead of perspective projection");
    options_.color_bar = true;
    app.add_flag("--no-color-bar{false}", options_.color_bar,
                 "picture: no color bar beside a scalar field (default: a bar with the field's values)");
  }
  PngOutput(const PngOutput&) = delete;
  PngOutput& operator=(const PngOutput&) = delete;

  /// True when --png was given.
  bool requested() const { return !path_.empty(); }
  const std::string& path() const { return path_; }

  /// The render options from the command line (size, camera).
  render::RenderOptions options() const {
    render::RenderOptions o = options_;
    const std::string error = parse_image_size(size_, o.width, o.height);
    if (!error.empty()) throw edgefront::InvalidInput(error);
    o.perspective = !orthographic_;
    return o;
  }

  /// Renders `scene`, writes the PNG file (atomically) and prints one line on stderr
  /// ("<app>: picture FILE, WxH, T ms"). Throws edgefront::InvalidInput or edgefront::IoError
  /// (e.g. an unwritable directory), which run_app reports.
  void write(const render::Scene& scene) const {
    const auto t0 = std::chrono::steady_clock::now();
    const render::RenderOptions o = options();
    render::render_png(scene, o, path_);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    std::cerr << app_name_ << ": picture " << path_ << ", " << o.width << "x" << o.height << ", "
              << static_cast<long>(std::lround(ms)) << " ms\n";
  }

 private:
  std::string app_name_;
  std::string path_;
  std::string size_ = "800x600";
  bool orthographic_ = false;
  render::RenderOptions options_;
};

}  // namespace edgefront::apps
