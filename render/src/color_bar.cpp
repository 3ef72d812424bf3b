// The color bar (RenderOptions::color_bar): the colormap as a vertical strip with tick labels in
// a 5x7 pixel font (digits, '.', '-', '+', 'e'), scaled by a whole factor to the image height.

#include "detail/color_bar.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

#include "render/color.h"

namespace edgefront::render::detail {

namespace {

// One glyph: 7 rows of 5 pixels, the leftmost pixel in bit 4.
struct Glyph {
  char c;
  std::array<std::uint8_t, 7> rows;
};

constexpr std::array<Glyph, 14> kFont = {{
    {'0', {0x0E, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0E}},
    {'1', {0x04, 0x0C, 0x04, 0x04, 0x04, 0x04, 0x0E}},
    {'2', {0x0E, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1F}},
    {'3', {0x1F, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0E}},
    {'4', {0x02, 0x06, 0x0A, 0x12, 0x1F, 0x02, 0x02}},
    {'5', {0x1F, 0x10, 0x1E, 0x01, 0x01, 0x11, 0x0E}},
    {'6', {0x06, 0x08, 0x10, 0x1E, 0x11, 0x11, 0x0E}},
    {'7', {0x1F, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08}},
    {'8', {0x0E, 0x11, 0x11, 0x0E, 0x11, 0x11, 0x0E}},
    {'9', {0x0E, 0x11, 0x11, 0x0F, 0x01, 0x02, 0x0C}},
    {'.', {0x00, 0x00, 0x00, 0x00, 0x00, 0x0C, 0x0C}},
    {'-', {0x00, 0x00, 0x00, 0x1F, 0x00, 0x00, 0x00}},
    {'+', {0x00, 0x04, 0x04, 0x1F, 0x04, 0x04, 0x00}},
    {'e', {0x00, 0x00, 0x0E, 0x11, 0x1F, 0x10, 0x0E}},
}};

constexpr int kGlyphW = 5, kGlyphH = 7, kAdvance = 6;  // font pixels
constexpr int kMinWidth = 160, kMinHeight = 80;         // smaller images get no bar
constexpr int kMaxLabels = 6;                           // about this many ticks

int font_scale(int height) { return std::clamp(height / 250, 1, 4); }

// Ticks: multiples of a nice step within [lo, lo + span] (just lo for a constant field).
struct Ticks {
  double step = 0;
  std::vector<double> values;
};

Ticks ticks(double lo, double span) {
  Ticks t;
  t.step = nice_step(span, kMaxLabels - 1);
  if (!(t.step > 0)) {
    t.values.push_back(lo);
    return t;
  }
  const double hi = lo + span;
  for (double k = std::ceil(lo / t.step - 1e-9); k * t.step <= hi + 1e-9 * t.step; k += 1) {
    t.values.push_back(k * t.step);
  }
  if (t.values.empty()) t.values.push_back(lo);
  return t;
}

void fill_rect(Image& image, int x0, int y0, int x1, int y1, const Rgb& c) {
  for (int y = std::max(0, y0); y < std::min(image.height, y1); ++y) {
    for (int x = std::max(0, x0); x < std::min(image.width, x1); ++x) image.set(x, y, c);
  }
}

void draw_text(Image& image, int x, int y, const std::string& text, int s, const Rgb& c) {
  for (const char ch : text) {
    const auto g = std::find_if(kFont.begin(), kFont.end(), [ch](const Glyph& f) { return f.c == ch; });
    if (g != kFont.end()) {
      for (int r = 0; r < kGlyphH; ++r) {
        for (int col = 0; col < kGlyphW; ++col) {
          if (g->rows[static_cast<size_t>(r)] >> (kGlyphW - 1 - col) & 1) {
            fill_rect(image, x + col * s, y + r * s, x + (col + 1) * s, y + (r + 1) * s, c);
          }
        }
      }
    }
    x += kAdvance * s;
  }
}

// The bar's parts, in pixels, for an image of this height.
struct Layout {
  int s = 1;        // font scale
  int margin = 0;   // around everything
  int bar = 0;      // width of the colored strip
  int tick = 0;     // tick length
  int top = 0, bottom = 0;  // rows of the strip's high and low end
};

Layout layout(int height) {
  Layout l;
  l.s = font_scale(height);
  l.margin = 4 * l.s;
  l.bar = 4 * l.s + 6;
  l.tick = 2 * l.s;
  l.top = std::max(l.margin + kGlyphH * l.s, height / 8);
  l.bottom = height - l.top;
  return l;
}

size_t longest_label(double lo, double span) {
  const Ticks t = ticks(lo, span);
  size_t n = 1;
  for (const double v : t.values) n = std::max(n, tick_label(v, t.step).size());
  return n;
}

}  // namespace

std::string tick_label(double v, double step) {
  char buf[64];
  if (std::abs(v) < 1e-12 * std::max(1.0, step)) v = 0;  // no "-0"
  const double mag = std::max(std::abs(v), step);
  if (step > 0 && (mag >= 1e6 || step < 1e-4)) {
    std::snprintf(buf, sizeof buf, "%.3g", v);
  } else {
    const int decimals = step > 0 ? std::max(0, static_cast<int>(-std::floor(std::log10(step) + 1e-9))) : 3;
    std::snprintf(buf, sizeof buf, "%.*f", std::min(decimals, 12), v);
  }
  return buf;
}

int color_bar_width(int width, int height, double lo, double span) {
  if (width < kMinWidth || height < kMinHeight || !std::isfinite(lo) || !std::isfinite(span)) return 0;
  const Layout l = layout(height);
  const int text = static_cast<int>(longest_label(lo, span)) * kAdvance * l.s;
  const int w = l.margin + l.bar + l.tick + l.margin + text + 2 * l.margin;
  return w <= width / 3 ? w : 0;
}

void draw_color_bar(Image& image, int bar_width, double lo, double span, const Rgb& text_color) {
  const Layout l = layout(image.height);
  const int x0 = image.width - bar_width + l.margin;
  const int x1 = x0 + l.bar;
  const int h = l.bottom - l.top;
  if (h < 2) return;
  for (int y = l.top; y <= l.bottom; ++y) {
    const Rgb c = colormap(static_cast<double>(l.bottom - y) / h);
    fill_rect(image, x0, y, x1, y + 1, c);
  }
  // Outline.
  fill_rect(image, x0 - 1, l.top - 1, x1 + 1, l.top, text_color);
  fill_rect(image, x0 - 1, l.bottom + 1, x1 + 1, l.bottom + 2, text_color);
  fill_rect(image, x0 - 1, l.top - 1, x0, l.bottom + 2, text_color);
  fill_rect(image, x1, l.top - 1, x1 + 1, l.bottom + 2, text_color);
  const Ticks t = ticks(lo, span);
  for (const double v : t.values) {
    const double f = span > 0 ? (v - lo) / span : 0.5;
    const int y = l.bottom - static_cast<int>(std::lround(f * h));
    fill_rect(image, x1, y - l.s / 2, x1 + l.tick, y - l.s / 2 + std::max(1, l.s / 2), text_color);
    draw_text(image, x1 + l.tick + l.margin, y - kGlyphH * l.s / 2, tick_label(v, t.step), l.s, text_color);
  }
}

}  // namespace edgefront::render::detail
