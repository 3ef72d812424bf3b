#pragma once
// Private helpers of the shapes sources (shapes.cpp, shapes_mesh.cpp, shapes_sample.cpp):
// deterministic random numbers, exact angles, option validation and the closed-form surfaces
// that both the mesh generators and the samplers evaluate.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <sstream>
#include <string>

#include "edgefront/error.h"
#include "shapes/shapes.h"

namespace edgefront::shapes::detail {

inline constexpr double kPi = 3.14159265358979323846;

/// Deterministic random source: mt19937_64 with our own transforms (identical on every standard
/// library).
class Rng {
 public:
  explicit Rng(std::uint64_t seed) : gen_(seed) {}
  /// Uniform in [0, 1), 53 random bits.
  double uniform() { return static_cast<double>(gen_() >> 11) * 0x1.0p-53; }
  /// Uniform in [a, b).
  double uniform(double a, double b) { return a + (b - a) * uniform(); }
  /// Uniform integer in [0, n), n >= 1 (rejection, no modulo bias).
  std::uint64_t below(std::uint64_t n) {
    const std::uint64_t limit = ~std::uint64_t{0} - (~std::uint64_t{0} % n);
    std::uint64_t x = gen_();
    while (x >= limit) x = gen_();
    return x % n;
  }
  /// Standard normal (Box-Muller, one value per call).
  double normal() {
    double u1 = uniform();
    while (u1 <= 0.0) u1 = uniform();
    const double u2 = uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * kPi * u2);
  }
  /// Uniformly distributed unit vector.
  Vec3 unit_vector() {
    const double z = uniform(-1.0, 1.0);
    const double phi = uniform(0.0, 2.0 * kPi);
    const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
    return Vec3(s * std::cos(phi), s * std::sin(phi), z);
  }

 private:
  std::mt19937_64 gen_;
};

/// cos and sin of 2π·k/n, exact (0, ±1) at the quarter turns so that seams and symmetric
/// vertices weld exactly.
inline std::array<double, 2> unit_circle(long long k, long long n) {
  k %= n;
  if (k < 0) k += n;
  if (4 * k == 0) return {1.0, 0.0};
  if (4 * k == n) return {0.0, 1.0};
  if (2 * k == n) return {-1.0, 0.0};
  if (4 * k == 3 * n) return {0.0, -1.0};
  const double a = 2.0 * kPi * static_cast<double>(k) / static_cast<double>(n);
  return {std::cos(a), std::sin(a)};
}

// ---- validation -------------------------------------------------------------------------

[[noreturn]] inline void fail(const std::string& shape, const std::string& what) {
  throw InvalidInput("shapes: " + shape + ": " + what);
}

inline std::string num(double x) {
  std::ostringstream os;
  os.precision(6);
  os << x;
  return os.str();
}

inline void require_positive(const std::string& shape, const char* name, double x) {
  if (!std::isfinite(x) || !(x > 0.0)) fail(shape, std::string(name) + " must be a finite number > 0, got " + num(x));
}

inline void require_finite(const std::string& shape, const char* name, double x) {
  if (!std::isfinite(x)) fail(shape, std::string(name) + " must be finite, got " + num(x));
}

inline void require_count(const std::string& shape, const char* name, long long n, long long lo, long long hi) {
  if (n < lo || n > hi)
    fail(shape, std::string(name) + " must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " +
                    std::to_string(n));
}

/// 0 < small < big (used for thickness < radius, minor < major, inner < outer).
inline void require_less(const std::string& shape, const char* small_name, double small, const char* big_name,
                         double big) {
  require_positive(shape, small_name, small);
  require_positive(shape, big_name, big);
  if (!(small < big))
    fail(shape, std::string(small_name) + " (" + num(small) + ") must be smaller than " + big_name + " (" + num(big) +
                    ")");
}

/// Checks the fields of `p` that `shape` uses (defined in shapes.cpp). \throws InvalidInput
void validate(const std::string& shape, const ShapeParams& p);

// ---- closed-form surfaces shared by meshes and samplers ----------------------------------

/// Star-shaped bumpy sphere: g(u) = sin(f ux) sin(f uy) sin(f uz), r = R (1 + a g).
struct Bumpy {
  double radius, amplitude, frequency;
  double g(const Vec3& u) const {
    return std::sin(frequency * u[0]) * std::sin(frequency * u[1]) * std::sin(frequency * u[2]);
  }
  double r(const Vec3& u) const { return radius * (1.0 + amplitude * g(u)); }
  /// Gradient of g extended to R³.
  Vec3 grad_g(const Vec3& u) const {
    const double f = frequency;
    const double sx = std::sin(f * u[0]), sy = std::sin(f * u[1]), sz = std::sin(f * u[2]);
    const double cx = std::cos(f * u[0]), cy = std::cos(f * u[1]), cz = std::cos(f * u[2]);
    return Vec3(f * cx * sy * sz, f * sx * cy * sz, f * sx * sy * cz);
  }
  /// Surface gradient of r on the unit sphere at the unit vector u.
  Vec3 grad_r(const Vec3& u) const {
    const Vec3 gg = grad_g(u);
    return radius * amplitude * (gg - (gg | u) * u);
  }
  /// Outward unit normal at direction u: r u - grad_S r, normalized.
  Vec3 normal(const Vec3& u) const {
    Vec3 n = r(u) * u - grad_r(u);
    return n / n.norm();
  }
  /// Area element relative to the unit sphere: r sqrt(r² + |grad_S r|²).
  double jacobian(const Vec3& u) const {
    const double rr = r(u);
    return rr * std::sqrt(rr * rr + grad_r(u).sqrnorm());
  }
  /// Upper bound of `jacobian`: |grad_S g| <= |grad g| <= f sqrt(3).
  double jacobian_bound() const {
    const double rmax = radius * (1.0 + amplitude);
    const double gmax = radius * amplitude * frequency * std::sqrt(3.0);
    return rmax * std::sqrt(rmax * rmax + gmax * gmax);
  }
};

/// Heightfield h(x, y) = Σ c_i sin(k_i · (x, y) + φ_i), six waves from the terrain seed.
struct Terrain {
  std::array<double, 6> c{}, kx{}, ky{}, phase{};
  double half_size = 1.0;

  Terrain(double half, double amplitude, double frequency, std::uint64_t seed) : half_size(half) {
    Rng rng(seed ^ 0x7465727261696eULL);
    double total = 0.0;
    std::array<double, 6> w{};
    for (std::size_t i = 0; i < 6; ++i) {
      w[i] = rng.uniform(0.3, 1.0);
      total += w[i];
      const double k = frequency / half * rng.uniform(0.35, 1.0);
      const double dir = rng.uniform(0.0, 2.0 * kPi);
      kx[i] = k * std::cos(dir);
      ky[i] = k * std::sin(dir);
      phase[i] = rng.uniform(0.0, 2.0 * kPi);
    }
    for (std::size_t i = 0; i < 6; ++i) c[i] = amplitude * w[i] / total;
  }
  double h(double x, double y) const {
    double z = 0.0;
    for (std::size_t i = 0; i < 6; ++i) z += c[i] * std::sin(kx[i] * x + ky[i] * y + phase[i]);
    return z;
  }
  /// (dh/dx, dh/dy).
  std::array<double, 2> grad(double x, double y) const {
    double gx = 0.0, gy = 0.0;
    for (std::size_t i = 0; i < 6; ++i) {
      const double cs = c[i] * std::cos(kx[i] * x + ky[i] * y + phase[i]);
      gx += cs * kx[i];
      gy += cs * ky[i];
    }
    return {gx, gy};
  }
  /// Upper bound of |grad h|.
  double slope_bound() const {
    double s = 0.0;
    for (std::size_t i = 0; i < 6; ++i) s += std::abs(c[i]) * std::hypot(kx[i], ky[i]);
    return s;
  }
  Vec3 point(double x, double y) const { return Vec3(x, y, h(x, y)); }
  Vec3 normal(double x, double y) const {
    const auto g = grad(x, y);
    Vec3 n(-g[0], -g[1], 1.0);
    return n / n.norm();
  }
};

/// Centre line of the hairpin at arc length s in [0, total()], in the xz plane: top arm from
/// (L, c) to (0, c), half circle of radius c about the y axis through x < 0, bottom arm from
/// (0, -c) to (L, -c). `normal` is the unit normal pointing away from the U's inside.
struct HairpinFrame {
  double arm = 1.5, c = 0.075;
  double total() const { return 2.0 * arm + kPi * c; }
  struct At {
    Vec3 point, tangent, normal;
    double curvature;  // of the centre line, > 0 on the bend (normal points away from the centre)
  };
  At at(double s) const {
    if (s <= arm) return {Vec3(arm - s, 0, c), Vec3(-1, 0, 0), Vec3(0, 0, 1), 0.0};
    if (s >= arm + kPi * c) {
      const double x = s - arm - kPi * c;
      return {Vec3(x, 0, -c), Vec3(1, 0, 0), Vec3(0, 0, -1), 0.0};
    }
    const double a = kPi / 2.0 + (s - arm) / c;  // from π/2 to 3π/2
    const Vec3 n(std::cos(a), 0, std::sin(a));
    return {c * n, Vec3(-std::sin(a), 0, std::cos(a)), n, 1.0 / c};
  }
  /// Same at the bend angle index k of n (exact at the quarter turns): a = π/2 + π k / n.
  At bend(int k, int n) const {
    const auto cs = unit_circle(static_cast<long long>(n) + 2LL * k, 4LL * n);  // angle π/2 + π k/n
    const Vec3 nn(cs[0], 0, cs[1]);
    return {c * nn, Vec3(-cs[1], 0, cs[0]), nn, 1.0 / c};
  }
};

}  // namespace edgefront::shapes::detail
