#pragma once
// The color bar of a scalar field (RenderOptions::color_bar): a vertical strip of the colormap
// with tick labels, drawn in output pixels on the right edge of an image.

#include <string>

#include "render/image.h"

namespace edgefront::render::detail {

/// Width in pixels the color bar takes at the right edge of a `width` x `height` image for values
/// in [lo, lo + span], or 0 when the image is too small to hold one.
int color_bar_width(int width, int height, double lo, double span);

/// Draws the bar (colormap from lo at the bottom to lo + span at the top, ticks and labels) into
/// the rightmost `bar_width` columns of `image`, over whatever is there.
void draw_color_bar(Image& image, int bar_width, double lo, double span, const Rgb& text_color);

/// The label of tick value `v` for ticks `step` apart: as many decimals as the step needs, or
/// scientific notation for very large or small magnitudes ("0.25", "-3", "1.5e-06").
std::string tick_label(double v, double step);

}  // namespace edgefront::render::detail
