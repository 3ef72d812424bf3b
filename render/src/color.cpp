#include "render/color.h"

#include <algorithm>
#include <cmath>

namespace edgefront::render {

Rgb colormap(double t) {
  static constexpr std::array<std::array<double, 3>, 5> kStops = {{
      {68, 1, 84}, {59, 82, 139}, {33, 145, 140}, {94, 201, 98}, {253, 231, 37}}};
  if (!(t > 0.0)) t = 0.0;  // also NaN
  t = std::min(t, 1.0);
  const double x = t * static_cast<double>(kStops.size() - 1);
  const size_t i = std::min(static_cast<size_t>(x), kStops.size() - 2);
  const double f = x - static_cast<double>(i);
  Rgb c{};
  for (size_t k = 0; k < 3; ++k) {
    c[k] = static_cast<std::uint8_t>(std::lround((1.0 - f) * kStops[i][k] + f * kStops[i + 1][k]));
  }
  return c;
}

double nice_step(double range, int target_count) {
  if (!(range > 0.0) || !std::isfinite(range) || target_count < 1) return 0.0;
  const double raw = range / target_count;
  const double decade = std::pow(10.0, std::floor(std::log10(raw)));
  double best = decade;
  double best_error = std::abs(std::log(range / decade / target_count));
  for (const double mantissa : {2.0, 5.0, 10.0}) {
    const double step = mantissa * decade;
    const double error = std::abs(std::log(range / step / target_count));
    if (error < best_error) {
      best = step;
      best_error = error;
    }
  }
  return best;
}

Rgb mix(const Rgb& a, const Rgb& b, double w) {
  w = std::clamp(w, 0.0, 1.0);
  Rgb c{};
  for (size_t k = 0; k < 3; ++k) {
    c[k] = static_cast<std::uint8_t>((1.0 - w) * a[k] + w * b[k] + 0.5);  // non-negative: rounds
  }
  return c;
}

Rgb scale(const Rgb& c, double factor) {
  Rgb out{};
  for (size_t k = 0; k < 3; ++k) {
    out[k] = static_cast<std::uint8_t>(std::clamp(c[k] * factor, 0.0, 255.0) + 0.5);
  }
  return out;
}

}  // namespace edgefront::render
