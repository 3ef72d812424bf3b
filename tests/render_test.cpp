// Tests of the offscreen renderer (render/render.h, render/image.h, render/color.h, render/scene.h)
// on scenes with known pictures: a unit cube (silhouette area against the analytic projected
// area), a colored field on a flat grid (ramp direction, isolines), a flipped cube (back faces),
// lines with a depth test, PNG round trips, errors; and the --png option of the built apps.

#include <gtest/gtest.h>

#include "app_test_util.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "edgefront/error.h"
#include "edgefront/mesh.h"
#include "render/color.h"
#include "render/image.h"
#include "render/render.h"
#include "render/scene.h"

namespace {

namespace fs = std::filesystem;
using edgefront::Mesh;
using edgefront::Vec3;
using edgefront::VertexHandle;
namespace render = edgefront::render;
using render::Rgb;

constexpr double kPi = 3.14159265358979323846;

/// The unit cube [0, 1]^3 as 12 triangles, outward oriented (or inward when `flipped`).
Mesh unit_cube(bool flipped = false) {
  Mesh mesh;
  VertexHandle v[8];
  for (int i = 0; i < 8; ++i) v[i] = mesh.add_vertex(Vec3(i & 1, (i >> 1) & 1, (i >> 2) & 1));
  // Each quad counter-clockwise seen from outside.
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    if (flipped) {
      mesh.add_face(v[q[0]], v[q[2]], v[q[1]]);
      mesh.add_face(v[q[0]], v[q[3]], v[q[2]]);
    } else {
      mesh.add_face(v[q[0]], v[q[1]], v[q[2]]);
      mesh.add_face(v[q[0]], v[q[2]], v[q[3]]);
    }
  }
  return mesh;
}

/// An n x n grid of squares over [0, 1]^2 in the plane z = 0, normals +z.
Mesh unit_grid(int n) {
  Mesh mesh;
  std::vector<VertexHandle> v;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) v.push_back(mesh.add_vertex(Vec3(double(i) / n, double(j) / n, 0.0)));
  }
  const auto at = [&](int i, int j) { return v[static_cast<size_t>(j * (n + 1) + i)]; };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      mesh.add_face(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      mesh.add_face(at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
  }
  return mesh;
}

int count_not(const render::Image& image, const Rgb& background) {
  int n = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) n += image.at(x, y) != background ? 1 : 0;
  }
  return n;
}

int channel_distance(const Rgb& a, const Rgb& b) {
  int d = 0;
  for (size_t k = 0; k < 3; ++k) d = std::max(d, std::abs(int(a[k]) - int(b[k])));
  return d;
}

render::RenderOptions ortho_options(int w, int h, double az, double el) {
  render::RenderOptions o;
  o.width = w;
  o.height = h;
  o.azimuth_deg = az;
  o.elevation_deg = el;
  o.perspective = false;
  o.supersample = 1;
  return o;
}

// ---- colors -----------------------------------------------------------------------------------

TEST(RenderColor, ColormapRunsFromDarkVioletToYellowAndGetsLighter) {
  EXPECT_EQ(render::colormap(0.0), (Rgb{68, 1, 84}));
  EXPECT_EQ(render::colormap(1.0), (Rgb{253, 231, 37}));
  EXPECT_EQ(render::colormap(-3.0), render::colormap(0.0));
  EXPECT_EQ(render::colormap(7.0), render::colormap(1.0));
  EXPECT_EQ(render::colormap(std::nan("")), render::colormap(0.0));
  double last = -1;
  for (int i = 0; i <= 100; ++i) {
    const Rgb c = render::colormap(i / 100.0);
    const double luma = 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
    EXPECT_GT(luma, last) << "t = " << i / 100.0;
    last = luma;
  }
}

TEST(RenderColor, NiceStepIsOneTwoOrFiveTimesAPowerOfTen) {
  EXPECT_DOUBLE_EQ(render::nice_step(1.0, 10), 0.1);
  EXPECT_DOUBLE_EQ(render::nice_step(3.12508, 12), 0.2);
  EXPECT_DOUBLE_EQ(render::nice_step(100.0, 20), 5.0);
  EXPECT_DOUBLE_EQ(render::nice_step(37.0, 2), 20.0);
  EXPECT_EQ(render::nice_step(0.0, 10), 0.0);
  EXPECT_EQ(render::nice_step(std::numeric_limits<double>::infinity(), 10), 0.0);
  EXPECT_EQ(render::nice_step(1.0, 0), 0.0);
  for (const double range : {0.003, 0.7, 1.0, 9.99, 12.5, 480.0, 1e6}) {
    const double step = render::nice_step(range, 12);
    const double mantissa = step / std::pow(10.0, std::floor(std::log10(step) + 1e-9));
    EXPECT_TRUE(std::abs(mantissa - 1) < 1e-9 || std::abs(mantissa - 2) < 1e-9 || std::abs(mantissa - 5) < 1e-9)
        << range << " -> " << step;
    EXPECT_GE(range / step, 12 / 1.6) << range;
    EXPECT_LE(range / step, 12 * 1.6) << range;
  }
}

// ---- the cube -----------------------------------------------------------------------------------

TEST(Render, ImageHasTheRequestedSizeAndBackgroundInTheCorners) {
  const Mesh cube = unit_cube();
  render::RenderOptions o;
  o.width = 160;
  o.height = 90;
  o.background = {10, 20, 30};
  const render::Image image = render::render(render::Scene{.mesh = &cube}, o);
  ASSERT_EQ(image.width, 160);
  ASSERT_EQ(image.height, 90);
  ASSERT_EQ(image.rgb.size(), 160u * 90u * 3u);
  for (const auto& [x, y] : {std::pair{0, 0}, {159, 0}, {0, 89}, {159, 89}}) {
    EXPECT_EQ(image.at(x, y), o.background) << x << "," << y;
  }
  // The fitted cube is in the middle.
  EXPECT_NE(image.at(80, 45), o.background);
}

TEST(Render, OrthographicCubeCoversItsAnalyticProjectedArea) {
  // An orthographic view of the unit cube along the unit direction d covers |dx| + |dy| + |dz|
  // square units. The camera maps the sphere around the cube's center through its corners
  // (radius sqrt(3)/2) to `fill` of the smaller half side.
  const Mesh cube = unit_cube();
  const int w = 400, h = 300;
  for (const auto& [az, el] : {std::pair{0.0, 0.0}, {45.0, 0.0}, {30.0, 20.0}, {-70.0, 35.0}, {160.0, -50.0}, {25.0, 90.0}, {0.0, -90.0}}) {
    render::RenderOptions o = ortho_options(w, h, az, el);
    const render::Image image = render::render(render::Scene{.mesh = &cube}, o);
    const double a = az * kPi / 180, e = el * kPi / 180;
    const double area_units = std::abs(std::cos(e) * std::sin(a)) + std::abs(std::sin(e)) + std::abs(std::cos(e) * std::cos(a));
    const double pixels_per_unit = o.fill * 0.5 * std::min(w, h) / (std::sqrt(3.0) / 2);
    const double expected = area_units * pixels_per_unit * pixels_per_unit;
    const int covered = count_not(image, o.background);
    // Pixel centers on the silhouette edge go either way: allow a one-pixel band around it.
    const double perimeter_bound = 8.0 * pixels_per_unit;
    EXPECT_NEAR(covered, expected, perimeter_bound) << "azimuth " << az << ", elevation " << el;
    EXPECT_NEAR(covered / expected, 1.0, 0.02) << "azimuth " << az << ", elevation " << el;
  }
}

TEST(Render, PerspectiveCubeSeenHeadOnIsTheFrontSquare) {
  // From +z, the front face (z = 1) hides the rest: a square of side focal / (distance to it),
  // centered in the image.
  const Mesh cube = unit_cube();
  render::RenderOptions o;
  o.width = 300;
  o.height = 300;
  o.azimuth_deg = 0;
  o.elevation_deg = 0;
  o.supersample = 1;
  const render::Image image = render::render(render::Scene{.mesh = &cube}, o);
  const double tan_half = std::tan(0.5 * o.field_of_view_deg * kPi / 180);
  const double radius = std::sqrt(3.0) / 2;
  const double distance = radius / std::sin(std::atan(o.fill * tan_half));
  const double side = (0.5 * 300 / tan_half) / (distance - 0.5);
  int x_min = 300, x_max = -1, y_min = 300, y_max = -1;
  for (int y = 0; y < 300; ++y) {
    for (int x = 0; x < 300; ++x) {
      if (image.at(x, y) == o.background) continue;
      x_min = std::min(x_min, x);
      x_max = std::max(x_max, x);
      y_min = std::min(y_min, y);
      y_max = std::max(y_max, y);
    }
  }
  EXPECT_NEAR(x_max - x_min + 1, side, 1.5);
  EXPECT_NEAR(y_max - y_min + 1, side, 1.5);
  EXPECT_NEAR(0.5 * (x_min + x_max + 1), 150.0, 1.0);
  EXPECT_NEAR(0.5 * (y_min + y_max + 1), 150.0, 1.0);
  EXPECT_NEAR(count_not(image, o.background), side * side, 4 * side);
  // Head on, the front face gets the full headlight at its center: the base color.
  EXPECT_LE(channel_distance(image.at(150, 150), render::Scene{}.base_color), 3);
}

TEST(Render, BackFacesAreTintedAndFrontFacesAreNot) {
  const Mesh outward = unit_cube(false);
  const Mesh inward = unit_cube(true);  // seen from outside, every visible face shows its back
  const render::RenderOptions o = ortho_options(200, 200, 30, 20);
  const Rgb front = render::render(render::Scene{.mesh = &outward}, o).at(100, 100);
  const Rgb back = render::render(render::Scene{.mesh = &inward}, o).at(100, 100);
  // Grey base color in front: no hue. Orange-red behind: red well above blue.
  EXPECT_LE(std::abs(int(front[0]) - int(front[2])), 3) << int(front[0]) << " " << int(front[1]) << " " << int(front[2]);
  EXPECT_GE(int(back[0]) - int(back[2]), 60) << int(back[0]) << " " << int(back[1]) << " " << int(back[2]);
  EXPECT_GT(back[0], back[1]);
  // Without the tint, both render the same grey: the tint is what tells them apart.
  render::RenderOptions untinted = o;
  untinted.back_face_tint = 0;
  const Rgb back_plain = render::render(render::Scene{.mesh = &inward}, untinted).at(100, 100);
  EXPECT_LE(std::abs(int(back_plain[0]) - int(back_plain[2])), 3);
}

TEST(Render, SupersamplingBlendsTheSilhouetteEdge) {
  // A black cube (ambient light only: no shading) on white: without supersampling every pixel is
  // black or white; with 2x2 the silhouette gets the in-between quarters.
  const Mesh cube = unit_cube();
  render::RenderOptions o = ortho_options(120, 120, 30, 20);
  o.ambient = 1.0;
  const render::Scene scene{.mesh = &cube, .base_color = {0, 0, 0}};
  const auto grey_levels = [](const render::Image& image) {
    std::vector<int> seen(256, 0);
    for (size_t i = 0; i < image.rgb.size(); i += 3) {
      EXPECT_TRUE(image.rgb[i] == image.rgb[i + 1] && image.rgb[i] == image.rgb[i + 2]);
      ++seen[image.rgb[i]];
    }
    return seen;
  };
  const std::vector<int> hard = grey_levels(render::render(scene, o));
  EXPECT_GT(hard[0], 0);
  EXPECT_GT(hard[255], 0);
  EXPECT_EQ(hard[0] + hard[255], 120 * 120);
  o.supersample = 2;
  const std::vector<int> soft = grey_levels(render::render(scene, o));
  int between = 0;
  for (int v = 1; v < 255; ++v) {
    if (soft[static_cast<size_t>(v)] == 0) continue;
    EXPECT_TRUE(v == 64 || v == 128 || v == 191) << v;  // 3/4, 2/4, 1/4 of the samples covered
    between += soft[static_cast<size_t>(v)];
  }
  EXPECT_GT(between, 100);  // the silhouette is several hundred pixels long
}

// ---- a field on a grid --------------------------------------------------------------------------

/// The grid seen head-on, orthographic, with full light (a pixel shows the field color itself).
struct GridView {
  Mesh grid = unit_grid(20);
  render::RenderOptions options = ortho_options(200, 200, 0, 0);
  /// The pixel column of grid coordinate x in [0, 1].
  int column(double x) const {
    const double pixels_per_unit = options.fill * 100.0 / (std::sqrt(2.0) / 2);
    return static_cast<int>(std::floor(100.0 + (x - 0.5) * pixels_per_unit));
  }
  std::vector<double> field_x() const {
    std::vector<double> values;
    for (const auto v : grid.vertices()) values.push_back(grid.point(v)[0]);
    return values;
  }
};

TEST(Render, ColorRampRunsFromLowToHighAcrossTheField) {
  GridView view;
  render::Scene scene{.mesh = &view.grid, .field = render::ScalarField{.values = view.field_x(), .isoline_step = -1}};
  scene.border_color.reset();
  const render::Image image = render::render(scene, view.options);
  // The field is x: the left edge shows the low end of the colormap, the right edge the high end.
  const Rgb left = image.at(view.column(0.01), 100), right = image.at(view.column(0.99), 100);
  EXPECT_LE(channel_distance(left, render::colormap(0.01)), 4);
  EXPECT_LE(channel_distance(right, render::colormap(0.99)), 4);
  // In between it follows the colormap, and the green channel rises steadily.
  for (const double x : {0.25, 0.5, 0.75}) {
    EXPECT_LE(channel_distance(image.at(view.column(x), 100), render::colormap(x)), 6) << x;
  }
  int last_green = -1;
  for (int col = view.column(0.02); col <= view.column(0.98); col += 4) {
    EXPECT_GE(int(image.at(col, 100)[1]), last_green) << col;
    last_green = image.at(col, 100)[1];
  }
  // A vertical line of the image has one color: the field does not depend on y.
  EXPECT_EQ(image.at(view.column(0.3), 40), image.at(view.column(0.3), 160));
}

// The color bar: the mesh fills the image without the bar's columns exactly as it would fill an
// image that narrow; the bar's strip runs through the colormap from the bottom (min) to the top
// (max); its labels are dark pixels to the strip's right; small images get no bar.
TEST(Render, ColorBarBesideTheFieldShowsTheColormapAndLabels) {
  GridView view;
  render::Scene scene{.mesh = &view.grid, .field = render::ScalarField{.values = view.field_x(), .isoline_step = -1}};
  render::RenderOptions o = ortho_options(400, 300, 0, 0);
  const render::Image plain = render::render(scene, o);
  o.color_bar = true;
  const render::Image with_bar = render::render(scene, o);
  ASSERT_EQ(with_bar.width, 400);
  // Find the strip: the column (right of the mesh) whose middle row has colormap(0.5).
  int strip = -1;
  for (int x = 399; x >= 200 && strip < 0; --x) {
    if (channel_distance(with_bar.at(x, 150), render::colormap(0.5)) <= 8) strip = x;
  }
  ASSERT_GE(strip, 0) << "no colormap strip found";
  int top = 0, bottom = 299;
  while (top < 300 && channel_distance(with_bar.at(strip, top), render::colormap(1.0)) > 8) ++top;
  while (bottom >= 0 && channel_distance(with_bar.at(strip, bottom), render::colormap(0.0)) > 8) --bottom;
  EXPECT_LT(top, 100);      // the high end near the top
  EXPECT_GT(bottom, 200);   // the low end near the bottom
  // Labels: dark text pixels right of the strip.
  int dark = 0;
  for (int y = 0; y < 300; ++y) {
    for (int x = strip + 4; x < 400; ++x) dark += channel_distance(with_bar.at(x, y), Rgb{40, 40, 40}) <= 2 ? 1 : 0;
  }
  EXPECT_GT(dark, 100);
  // The mesh part equals a render of the narrower image.
  int bar_width = 400 - strip;
  while (bar_width < 200) {
    render::RenderOptions narrow = ortho_options(400 - bar_width, 300, 0, 0);
    const render::Image left = render::render(scene, narrow);
    bool same = true;
    for (int y = 0; y < 300 && same; ++y) {
      for (int x = 0; x < left.width && same; ++x) same = left.at(x, y) == with_bar.at(x, y);
    }
    if (same) break;
    ++bar_width;
  }
  EXPECT_LT(bar_width, 200) << "the mesh part is not the narrower image";
  EXPECT_NE(plain.rgb, with_bar.rgb);
  // Too small for a bar: drawn without it.
  render::RenderOptions tiny = ortho_options(100, 60, 0, 0);
  const render::Image tiny_plain = render::render(scene, tiny);
  tiny.color_bar = true;
  EXPECT_EQ(render::render(scene, tiny).rgb, tiny_plain.rgb);
}

TEST(Render, ExplicitRangeClampsTheColormap) {
  GridView view;
  render::Scene scene{.mesh = &view.grid,
                      .field = render::ScalarField{.values = view.field_x(), .min = 0.5, .max = 1.0, .isoline_step = -1}};
  scene.border_color.reset();
  const render::Image image = render::render(scene, view.options);
  EXPECT_LE(channel_distance(image.at(view.column(0.2), 100), render::colormap(0.0)), 2);
  EXPECT_LE(channel_distance(image.at(view.column(0.75), 100), render::colormap(0.5)), 6);
}

TEST(Render, IsolinesSitAtMultiplesOfTheStep) {
  GridView view;
  render::Scene scene{.mesh = &view.grid,
                      .field = render::ScalarField{.values = view.field_x(), .isoline_step = 0.25, .isoline_color = {255, 0, 0}}};
  scene.border_color.reset();
  view.options.isoline_width_px = 2;
  const render::Image image = render::render(scene, view.options);
  const Rgb red{255, 0, 0};
  for (const double x : {0.25, 0.5, 0.75}) {
    // Some pixel within one of the line's column is the isoline color.
    const int c = view.column(x);
    const bool hit = image.at(c - 1, 100) == red || image.at(c, 100) == red || image.at(c + 1, 100) == red;
    EXPECT_TRUE(hit) << x;
  }
  for (const double x : {0.125, 0.375, 0.625, 0.875}) {
    EXPECT_NE(image.at(view.column(x), 100), red) << x;
  }
  // Exactly three lines cross the middle row (x = 0 and 1 lie on the grid's edge, half drawn).
  int runs = 0;
  for (int col = view.column(0.05); col <= view.column(0.95); ++col) {
    runs += (image.at(col, 100) == red && image.at(col - 1, 100) != red) ? 1 : 0;
  }
  EXPECT_EQ(runs, 3);
}

TEST(Render, NonFiniteValuesAndHighlightsUseTheirColors) {
  GridView view;
  std::vector<double> values = view.field_x();
  for (const auto v : view.grid.vertices()) {
    if (view.grid.point(v)[0] > 0.7) values[static_cast<size_t>(v.idx())] = std::numeric_limits<double>::infinity();
  }
  render::Scene scene{.mesh = &view.grid, .field = render::ScalarField{.values = values, .isoline_step = -1}};
  scene.border_color.reset();
  // Highlight the faces with a vertex left of x = 0.2.
  render::FaceHighlight highlight{.color = {0, 0, 255}};
  for (const auto f : view.grid.faces()) {
    for (const auto v : view.grid.fv_range(f)) {
      if (view.grid.point(v)[0] < 0.2) {
        highlight.faces.push_back(f);
        break;
      }
    }
  }
  scene.highlights.push_back(highlight);
  const render::Image image = render::render(scene, view.options);
  EXPECT_EQ(image.at(view.column(0.1), 100), (Rgb{0, 0, 255}));
  EXPECT_EQ(image.at(view.column(0.9), 100), scene.field->no_value_color);
  EXPECT_LE(channel_distance(image.at(view.column(0.45), 100), render::colormap(0.45 / 0.7)), 6);
}

// ---- lines and points ---------------------------------------------------------------------------

TEST(Render, ALineAloneCoversItsPixelsAndNothingElse) {
  // A horizontal segment through the middle of the picture (on the boundary between rows 49 and
  // 50), 2 pixels wide: exactly those two rows, from end to end.
  render::Scene scene;
  scene.lines.push_back(render::Polyline{.points = {Vec3(-1, 0, 0), Vec3(1, 0, 0)}, .color = {0, 0, 0}, .width_px = 2});
  const render::RenderOptions o = ortho_options(200, 100, 0, 0);
  const render::Image image = render::render(scene, o);
  // The segment (the camera's bounding sphere has radius 1) spans fill * 50 pixels either side
  // of the center.
  const double half = o.fill * 50;
  for (int x = static_cast<int>(100 - half) + 1; x < static_cast<int>(100 + half) - 1; ++x) {
    EXPECT_EQ(image.at(x, 49), (Rgb{0, 0, 0})) << x;
    EXPECT_EQ(image.at(x, 50), (Rgb{0, 0, 0})) << x;
    EXPECT_EQ(image.at(x, 48), o.background) << x;
    EXPECT_EQ(image.at(x, 51), o.background) << x;
  }
  EXPECT_EQ(image.at(static_cast<int>(100 - half) - 3, 50), o.background);
  EXPECT_EQ(image.at(static_cast<int>(100 + half) + 3, 50), o.background);
  // Two rows of the segment's length, plus the round caps (at most a pixel each side).
  EXPECT_NEAR(count_not(image, o.background), 2 * 2 * half, 6);
}

TEST(Render, LinesBehindTheSurfaceAreHiddenAndLinesOnItShow) {
  const Mesh grid = unit_grid(4);  // normal +z, seen from +z
  const render::RenderOptions o = ortho_options(200, 200, 0, 0);
  const Rgb red{255, 0, 0}, blue{0, 0, 255};
  render::Scene scene{.mesh = &grid};
  scene.border_color.reset();
  // Diagonals: one under the grid (z = -0.3), one on it.
  scene.lines.push_back(render::Polyline{.points = {Vec3(0.1, 0.9, -0.3), Vec3(0.9, 0.1, -0.3)}, .color = red});
  scene.lines.push_back(render::Polyline{.points = {Vec3(0.1, 0.1, 0), Vec3(0.9, 0.9, 0)}, .color = blue});
  const render::Image image = render::render(scene, o);
  int red_pixels = 0, blue_pixels = 0;
  for (int y = 0; y < 200; ++y) {
    for (int x = 0; x < 200; ++x) {
      red_pixels += image.at(x, y) == red ? 1 : 0;
      blue_pixels += image.at(x, y) == blue ? 1 : 0;
    }
  }
  EXPECT_EQ(red_pixels, 0);
  EXPECT_GT(blue_pixels, 150);
  // Seen from below (elevation -90 looks up along +y... use azimuth 180: from -z), the red
  // line is in front and the blue one lies on the back face.
  const render::Image below = render::render(scene, ortho_options(200, 200, 180, 0));
  int red_below = 0;
  for (int y = 0; y < 200; ++y) {
    for (int x = 0; x < 200; ++x) red_below += below.at(x, y) == red ? 1 : 0;
  }
  EXPECT_GT(red_below, 150);
}

TEST(Render, BorderLoopsAndPointsAreDrawn) {
  const Mesh grid = unit_grid(4);
  render::Scene scene{.mesh = &grid, .border_color = Rgb{0, 200, 0}};
  scene.points.push_back(render::PointSet{.points = {Vec3(0.5, 0.5, 0)}, .color = {255, 0, 255}, .radius_px = 4});
  const render::RenderOptions o = ortho_options(200, 200, 0, 0);
  const render::Image image = render::render(scene, o);
  EXPECT_EQ(image.at(100, 100), (Rgb{255, 0, 255}));
  EXPECT_EQ(image.at(102, 101), (Rgb{255, 0, 255}));
  EXPECT_NE(image.at(108, 100), (Rgb{255, 0, 255}));
  // The border (x = 0) runs down the grid's left edge.
  const double pixels_per_unit = o.fill * 100.0 / (std::sqrt(2.0) / 2);
  const int left = static_cast<int>(std::floor(100.0 - 0.5 * pixels_per_unit));
  EXPECT_EQ(image.at(left, 100), (Rgb{0, 200, 0}));
  EXPECT_EQ(render::border_polylines(grid, {0, 0, 0}, 1).size(), 1u);
  EXPECT_EQ(render::border_polylines(grid, {0, 0, 0}, 1)[0].points.size(), 16u);
  const Mesh cube = unit_cube();
  EXPECT_TRUE(render::border_polylines(cube, {0, 0, 0}, 1).empty());
}

TEST(Render, PolylineFromHalfedgesClosesALoop) {
  const Mesh cube = unit_cube();
  // The three halfedges around face 0.
  std::vector<edgefront::HalfedgeHandle> loop;
  for (const auto h : cube.fh_range(cube.face_handle(0))) loop.push_back(h);
  const render::Polyline line = render::polyline_from_halfedges(cube, loop);
  EXPECT_TRUE(line.closed);
  EXPECT_EQ(line.points.size(), 3u);
  loop.pop_back();
  const render::Polyline open = render::polyline_from_halfedges(cube, loop);
  EXPECT_FALSE(open.closed);
  EXPECT_EQ(open.points.size(), 3u);
  EXPECT_THROW(render::polyline_from_halfedges(cube, {edgefront::HalfedgeHandle(999)}), edgefront::InvalidInput);
  EXPECT_THROW(render::polyline_from_vertices(cube, {VertexHandle(0), VertexHandle(8)}, false), edgefront::InvalidInput);
}

// ---- PNG files and errors -----------------------------------------------------------------------

class RenderFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("edgefront_render_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  fs::path dir_;
};

TEST_F(RenderFiles, PngRoundTripKeepsEveryPixel) {
  const Mesh cube = unit_cube();
  const render::Image image = render::render(render::Scene{.mesh = &cube}, ortho_options(64, 48, 30, 20));
  const fs::path file = dir_ / "cube.png";
  render::write_png(image, file);
  const std::string bytes = eftest::slurp(file);
  ASSERT_GE(bytes.size(), 8u);
  EXPECT_EQ(bytes.substr(1, 3), "PNG");
  const render::Image back = render::read_png(file);
  EXPECT_EQ(back.width, 64);
  EXPECT_EQ(back.height, 48);
  EXPECT_EQ(back.rgb, image.rgb);
  // render_png writes the same picture.
  render::render_png(render::Scene{.mesh = &cube}, ortho_options(64, 48, 30, 20), dir_ / "again.png");
  EXPECT_EQ(render::read_png(dir_ / "again.png").rgb, image.rgb);
  // Nothing but the two pictures is left behind (no temporary files).
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 2);
}

TEST_F(RenderFiles, UnwritableOrUnreadablePathsAreIoErrors) {
  const render::Image image(4, 4, {1, 2, 3});
  try {
    render::write_png(image, dir_ / "missing-dir" / "x.png");
    ADD_FAILURE() << "expected IoError";
  } catch (const edgefront::IoError& e) {
    EXPECT_NE(std::string(e.what()).find("missing-dir"), std::string::npos) << e.what();
  }
  EXPECT_THROW(render::read_png(dir_ / "absent.png"), edgefront::IoError);
  const fs::path not_png = dir_ / "text.png";
  {
    std::ofstream out(not_png);
    out << "not a picture\n";
  }
  EXPECT_THROW(render::read_png(not_png), edgefront::IoError);
  EXPECT_THROW(render::write_png(render::Image{}, dir_ / "empty.png"), edgefront::InvalidInput);
  EXPECT_FALSE(fs::exists(dir_ / "empty.png"));
}

/// Expects render() to throw InvalidInput with `hint` in the message.
void expect_invalid(const render::Scene& scene, const render::RenderOptions& o, const std::string& hint) {
  try {
    render::render(scene, o);
    ADD_FAILURE() << "expected InvalidInput mentioning '" << hint << "'";
  } catch (const edgefront::InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find(hint), std::string::npos) << e.what();
  }
}

TEST(Render, BadSizesAndOptionsAreClearErrors) {
  const Mesh cube = unit_cube();
  const render::Scene scene{.mesh = &cube};
  render::RenderOptions o;
  o.width = 0;
  expect_invalid(scene, o, "at least 1x1");
  o.width = 100;
  o.height = -5;
  expect_invalid(scene, o, "at least 1x1");
  o.height = 100000;
  expect_invalid(scene, o, "exceeds the limit");
  o.height = 16000;
  o.width = 16000;
  expect_invalid(scene, o, "samples");
  o = {};
  o.elevation_deg = 95;
  expect_invalid(scene, o, "elevation");
  o = {};
  o.azimuth_deg = std::nan("");
  expect_invalid(scene, o, "azimuth");
  o = {};
  o.supersample = 0;
  expect_invalid(scene, o, "supersample");
}

TEST(Render, BadScenesAreClearErrors) {
  const render::RenderOptions o;
  expect_invalid(render::Scene{}, o, "nothing to draw");
  const Mesh empty;
  expect_invalid(render::Scene{.mesh = &empty}, o, "the mesh is empty");
  Mesh cube = unit_cube();
  cube.set_point(VertexHandle(3), Vec3(0, std::nan(""), 0));
  expect_invalid(render::Scene{.mesh = &cube}, o, "vertex 3 has a non-finite coordinate");
  const Mesh good = unit_cube();
  expect_invalid(render::Scene{.mesh = &good, .field = render::ScalarField{.values = {1, 2, 3}}}, o,
                 "3 values for 8 vertices");
  expect_invalid(render::Scene{.mesh = &good, .highlights = {render::FaceHighlight{.faces = {edgefront::FaceHandle(12)}}}}, o,
                 "face 12");
  render::Scene lines;
  lines.lines.push_back(render::Polyline{.points = {Vec3(0, 0, 0), Vec3(1, std::numeric_limits<double>::infinity(), 0)}});
  expect_invalid(lines, o, "line 0, point 1");
}

// ---- the apps' --png ----------------------------------------------------------------------------

class RenderApps : public RenderFiles {
 protected:
  eftest::CommandResult run(const std::string& app, const std::string& args) {
    const fs::path exe = fs::path(EDGEFRONT_APP_DIR) / app;
    if (!fs::exists(exe)) {
      ADD_FAILURE() << app << " is not built at " << exe;
      return {};
    }
    return eftest::run_command(exe, args, dir_);
  }
  static std::string data(const std::string& name) { return eftest::shell_quoted((fs::path(EDGEFRONT_DATA_DIR) / name).string()); }
  std::string out(const std::string& name) const { return eftest::shell_quoted((dir_ / name).string()); }
};

TEST_F(RenderApps, EfDistanceAndEfFrontWritePictures) {
  eftest::CommandResult r = run("ef-distance", data("bumpy-sphere.off") + " --source 0 -o " + out("d.txt") +
                                                   " --png " + out("d.png") + " --size 120x90 --azimuth 200");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  render::Image image = render::read_png(dir_ / "d.png");
  EXPECT_EQ(image.width, 120);
  EXPECT_EQ(image.height, 90);
  EXPECT_EQ(image.at(0, 0), (Rgb{255, 255, 255}));
  EXPECT_NE(image.at(60, 45), (Rgb{255, 255, 255}));
  // The default size.
  r = run("ef-front", data("torus.off") + " --source 0 --levels 4 --png " + out("f.png"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  image = render::read_png(dir_ / "f.png");
  EXPECT_EQ(image.width, 800);
  EXPECT_EQ(image.height, 600);
  // After 4 levels on the torus the MEF has loops left: drawn in red.
  int red = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) red += image.at(x, y) == Rgb{220, 30, 30} ? 1 : 0;
  }
  EXPECT_GT(red, 50);
}

TEST_F(RenderApps, EfPathDrawsThePath) {
  const eftest::CommandResult r =
      run("ef-path", data("bumpy-sphere.off") + " 0 300 --polyline --png " + out("p.png") + " --size 400x300");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const render::Image image = render::read_png(dir_ / "p.png");
  EXPECT_EQ(image.width, 400);
  EXPECT_EQ(image.height, 300);
  int red = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) red += image.at(x, y) == Rgb{220, 30, 30} ? 1 : 0;
  }
  EXPECT_GT(red, 30);  // the visible part of the path, drawn 3 pixels wide
}

TEST_F(RenderApps, BadPictureOptionsExitWithOneLine) {
  // Zero size and a wrong extension: usage errors (2).
  for (const std::string& bad : {std::string(" --size 0x0"), std::string(" --size 800"), std::string(" --elevation 91")}) {
    const eftest::CommandResult r = run("ef-distance", data("bumpy-sphere.off") + " --source 0 --png " + out("a.png") + bad);
    EXPECT_EQ(r.exit_code, 2) << bad << "\n" << r.err;
    EXPECT_EQ(r.err.rfind("ef-distance: error: ", 0), 0u) << r.err;
  }
  eftest::CommandResult r = run("ef-front", data("torus.off") + " --source 0 --png " + out("a.jpg"));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find(".png"), std::string::npos) << r.err;
  // An unwritable place: an error (1) naming the file, nothing written.
  r = run("ef-front", data("torus.off") + " --source 0 --png " + out("no-such-dir/a.png"));
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("no-such-dir"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

}  // namespace
