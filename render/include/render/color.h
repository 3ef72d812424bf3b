#pragma once
/// \file color.h
/// Colors of the renderer: an 8-bit RGB triple, the colormap used for scalar fields, and "nice"
/// isoline intervals.

#include <array>
#include <cstdint>

namespace edgefront::render {

/// An 8-bit sRGB color (red, green, blue). The same type as mesh_io's per-vertex colors.
using Rgb = std::array<std::uint8_t, 3>;

/// A color for `t` in [0, 1] (clamped; NaN counts as 0): piecewise-linear through five stops from
/// dark violet (t = 0) over blue and teal to green and yellow (t = 1). Perceptually ordered and
/// readable on a light background; the lightness grows with `t`.
Rgb colormap(double t);

/// A "nice" spacing for about `target_count` isolines over a range of length `range`: 1, 2 or 5
/// times a power of ten, the one for which range / step is closest to `target_count` (by ratio;
/// always within a factor of 1.6). 0 when `range` is not a positive finite number or
/// `target_count` < 1.
double nice_step(double range, int target_count);

/// `a` and `b` mixed: (1 - w) * a + w * b per channel, `w` clamped to [0, 1].
Rgb mix(const Rgb& a, const Rgb& b, double w);

/// `c` scaled by `factor` per channel (clamped to [0, 255]).
Rgb scale(const Rgb& c, double factor);

}  // namespace edgefront::render
