#pragma once
/// \file render.h
/// An offscreen software rasterizer (no display, no GPU): z-buffer, Lambert + ambient shading
/// with a headlight, back faces in a distinct tint, scalar fields with isolines, lines and points
/// with a depth test, optional 2x2 supersampling. The camera is fitted to the scene's bounding
/// sphere: centered on the bounding box, through the farthest point of the mesh, lines and points.

#include <filesystem>

#include "render/color.h"
#include "render/image.h"
#include "render/scene.h"

namespace edgefront::render {

/// Camera and image options.
struct RenderOptions {
  int width = 800;   ///< pixels, 1 ... kMaxImageSide
  int height = 600;  ///< pixels, 1 ... kMaxImageSide
  /// The camera looks at the center of the scene's bounding box from the direction given by
  /// azimuth (degrees, around the +y axis, 0 = from +z, 90 = from +x) and elevation (degrees above
  /// the xz plane, -90 ... 90); +y points up in the image.
  double azimuth_deg = 30.0;    ///< degrees, any finite value (default 30)
  double elevation_deg = 20.0;  ///< degrees, -90 ... 90 (default 20)
  bool perspective = true;       ///< false: orthographic
  double field_of_view_deg = 30.0;  ///< perspective only; the smaller image side, 1 ... 120
  /// The bounding sphere fills this share of the smaller image side (1 = touches the edges;
  /// above 1 crops). (0, 10], default 0.92.
  double fill = 0.92;
  int supersample = 2;  ///< samples per pixel along each axis (1 = none, 2 = 2x2), 1 ... 4
  Rgb background = {255, 255, 255};  ///< color of pixels no surface, line or point covers (white)
  /// Faces seen from behind (their normal points away from the camera) are shaded in this color,
  /// mixed with their field/base color by `back_face_tint` (1 = this color only).
  Rgb back_face_color = {215, 95, 35};
  double back_face_tint = 0.75;  ///< 0 ... 1: 0 = no tint, 1 = `back_face_color` only
  double ambient = 0.3;       ///< light share independent of the angle, 0 ... 1
  /// Gouraud with area-weighted vertex normals (corners sharper than 45 degrees keep the face
  /// normal); false: flat per face.
  bool smooth_shading = true;
  double isoline_width_px = 1.2;  ///< in output pixels, 0 ... 100
  /// With a scalar field: a vertical color bar at the right edge with the field's values at
  /// "nice" ticks (1, 2 or 5 x 10^k); the mesh is fitted into the rest of the image. Needs an
  /// image at least 160 pixels wide and 80 high (smaller images are drawn without it).
  bool color_bar = false;
};

/// Largest accepted width or height, in pixels.
inline constexpr int kMaxImageSide = 16384;
/// Largest number of samples, width * height * supersample^2, of one render (2^27): bounds the
/// memory of the sample buffers (color, depth and per-sample weights, a few bytes each).
inline constexpr double kMaxSamples = 128.0 * 1024 * 1024;

/// Renders `scene`.
/// \param scene what to draw (the mesh it borrows must be alive).
/// \param options camera and image settings.
/// \return the image, `options.width` x `options.height` pixels.
/// \throw InvalidInput for a zero, negative or absurd image size or option, a scene with nothing
///        to draw, a mesh without faces, non-finite coordinates (naming the vertex or point),
///        or a field/highlight that does not fit the mesh.
Image render(const Scene& scene, const RenderOptions& options);

/// Renders `scene` and writes it as a PNG file (atomically).
/// \throw as render() and write_png().
void render_png(const Scene& scene, const RenderOptions& options, const std::filesystem::path& path);

}  // namespace edgefront::render
