// Mesh generators of shapes/shapes.h.
//
// Most shapes are unions of parametric grid patches. A small builder welds coincident vertices
// (seams, poles, patch borders) within a tolerance, drops the triangles that welding made
// degenerate (a pole row, a cone apex), and hands the triangles to OpenMesh in generation order,
// so vertex order is deterministic. A grid triangle (i,j),(i+1,j),(i+1,j+1) is oriented along
// ∂u × ∂v; each patch picks its (u, v) order so that this is the outward normal.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <tuple>
#include <unordered_map>
#include <utility>
#include <vector>

#include "edgefront/error.h"
#include "shapes/shapes.h"
#include "edgefront/vertex_twins.h"
#include "shapes_detail.h"

namespace edgefront::shapes {

namespace {

using detail::kPi;
using detail::unit_circle;

constexpr long long kMaxCount = 1 << 16;   // per direction
constexpr long long kMaxCells = 40000000;  // per mesh, a guard against absurd requests

class MeshBuilder {
 public:
  explicit MeshBuilder(double tolerance) : tol_(tolerance) {}

  /// Index of a vertex at p, reusing an existing vertex within the tolerance.
  int vertex(const Vec3& p) {
    const Key k = key(p);
    for (long long dx = -1; dx <= 1; ++dx)
      for (long long dy = -1; dy <= 1; ++dy)
        for (long long dz = -1; dz <= 1; ++dz) {
          const auto it = cells_.find(Key{k[0] + dx, k[1] + dy, k[2] + dz});
          if (it == cells_.end()) continue;
          for (const int v : it->second)
            if ((points_[static_cast<std::size_t>(v)] - p).norm() <= tol_) return v;
        }
    const int v = unique_vertex(p);
    cells_[k].push_back(v);
    return v;
  }

  /// Index of a new vertex at p, never welded (and never welded to later).
  int unique_vertex(const Vec3& p) {
    EF_CHECK(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]), "non-finite shape vertex");
    points_.push_back(p);
    return static_cast<int>(points_.size()) - 1;
  }

  /// Adds a triangle; skipped when welding made it degenerate (two equal indices).
  void triangle(int a, int b, int c, bool flip = false) {
    if (a == b || b == c || a == c) return;
    if (flip) std::swap(b, c);
    tris_.push_back({a, b, c});
  }

  /// Grid patch: vertices pos(i, j) for i in [0, nu], j in [0, nv] (i-major order), two
  /// triangles per cell oriented along ∂u × ∂v (reversed with `flip`).
  void grid(int nu, int nv, const std::function<Vec3(int, int)>& pos, bool flip = false, bool weld = true) {
    std::vector<int> id(static_cast<std::size_t>(nu + 1) * static_cast<std::size_t>(nv + 1));
    auto at = [&](int i, int j) -> int& {
      return id[static_cast<std::size_t>(i) * static_cast<std::size_t>(nv + 1) + static_cast<std::size_t>(j)];
    };
    for (int i = 0; i <= nu; ++i)
      for (int j = 0; j <= nv; ++j) at(i, j) = weld ? vertex(pos(i, j)) : unique_vertex(pos(i, j));
    for (int i = 0; i < nu; ++i)
      for (int j = 0; j < nv; ++j) {
        const int a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
        triangle(a, b, c, flip);
        triangle(a, c, d, flip);
      }
  }

  /// The mesh: vertices in creation order (unused ones dropped), faces in insertion order.
  Mesh build() const {
    std::vector<int> remap(points_.size(), -1);
    for (const auto& t : tris_)
      for (const int v : t) remap[static_cast<std::size_t>(v)] = 0;
    Mesh mesh;
    int next = 0;
    for (std::size_t v = 0; v < points_.size(); ++v)
      if (remap[v] == 0) {
        remap[v] = next++;
        mesh.add_vertex(points_[v]);
      }
    for (const auto& t : tris_) {
      const FaceHandle f = mesh.add_face(VertexHandle(remap[static_cast<std::size_t>(t[0])]),
                                         VertexHandle(remap[static_cast<std::size_t>(t[1])]),
                                         VertexHandle(remap[static_cast<std::size_t>(t[2])]));
      EF_CHECK(f.is_valid(), "shape generator produced a non-manifold or inconsistently oriented face");
    }
    mesh.update_face_normals();
    return mesh;
  }

 private:
  using Key = std::array<long long, 3>;
  struct KeyHash {
    std::size_t operator()(const Key& k) const {
      std::uint64_t h = 0x9e3779b97f4a7c15ULL;
      for (const long long x : k) {
        h ^= static_cast<std::uint64_t>(x) + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2);
      }
      return static_cast<std::size_t>(h);
    }
  };
  Key key(const Vec3& p) const {
    return Key{static_cast<long long>(std::floor(p[0] / tol_)), static_cast<long long>(std::floor(p[1] / tol_)),
               static_cast<long long>(std::floor(p[2] / tol_))};
  }

  double tol_;
  std::vector<Vec3> points_;
  std::vector<std::array<int, 3>> tris_;
  std::unordered_map<Key, std::vector<int>, KeyHash> cells_;
};

/// Weld tolerance for a shape of characteristic size `scale`.
double weld_tolerance(double scale) { return 1e-9 * scale; }

void require_cells(const std::string& shape, long long nu, long long nv) {
  if (nu * nv > kMaxCells)
    detail::fail(shape, "too many cells (" + std::to_string(nu) + " x " + std::to_string(nv) + "), at most " +
                            std::to_string(kMaxCells));
}

// Cylinder and cone: counts around and along, positive radius and height, a sane cell count.
void require_revolution(const std::string& shape, int around, int along, double radius, double height) {
  detail::require_count(shape, "around", around, 3, kMaxCount);
  detail::require_count(shape, "along", along, 1, kMaxCount);
  detail::require_positive(shape, "radius", radius);
  detail::require_positive(shape, "height", height);
  require_cells(shape, around, along);
}

int clamp_count(double x, int lo) {
  const double r = std::round(x);
  if (!(r >= lo)) return lo;
  if (r > static_cast<double>(kMaxCount)) return static_cast<int>(kMaxCount);
  return static_cast<int>(r);
}

// ---- icosahedron ----------------------------------------------------------------------

struct Triangles {
  std::vector<Vec3> points;  // on the unit sphere
  std::vector<std::array<int, 3>> faces;
};

Triangles unit_icosphere(int subdivisions) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  Triangles tri;
  tri.points = {Vec3(-1, t, 0), Vec3(1, t, 0), Vec3(-1, -t, 0), Vec3(1, -t, 0), Vec3(0, -1, t), Vec3(0, 1, t),
                Vec3(0, -1, -t), Vec3(0, 1, -t), Vec3(t, 0, -1), Vec3(t, 0, 1), Vec3(-t, 0, -1), Vec3(-t, 0, 1)};
  for (auto& p : tri.points) p /= p.norm();
  tri.faces = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
               {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
               {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int s = 0; s < subdivisions; ++s) {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      const auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      Vec3 p = tri.points[static_cast<std::size_t>(a)] + tri.points[static_cast<std::size_t>(b)];
      p /= p.norm();
      tri.points.push_back(p);
      const int id = static_cast<int>(tri.points.size()) - 1;
      mid.emplace(key, id);
      return id;
    };
    std::vector<std::array<int, 3>> next;
    next.reserve(tri.faces.size() * 4);
    for (const auto& f : tri.faces) {
      const int ab = midpoint(f[0], f[1]), bc = midpoint(f[1], f[2]), ca = midpoint(f[2], f[0]);
      next.push_back({f[0], ab, ca});
      next.push_back({f[1], bc, ab});
      next.push_back({f[2], ca, bc});
      next.push_back({ab, bc, ca});
    }
    tri.faces = std::move(next);
  }
  return tri;
}

void add_sphere(MeshBuilder& b, const Triangles& tri, const std::function<Vec3(const Vec3&)>& place, bool flip) {
  std::vector<int> id;
  id.reserve(tri.points.size());
  for (const auto& u : tri.points) id.push_back(b.unique_vertex(place(u)));
  for (const auto& f : tri.faces)
    b.triangle(id[static_cast<std::size_t>(f[0])], id[static_cast<std::size_t>(f[1])],
               id[static_cast<std::size_t>(f[2])], flip);
}

void require_subdivisions(const std::string& shape, int s) { detail::require_count(shape, "subdivisions", s, 0, 8); }

}  // namespace

// ---- planar grids ---------------------------------------------------------------------

Mesh grid(const GridOptions& o) {
  const std::string shape = "grid";
  detail::require_count(shape, "cells", o.cells, 1, 4096);
  detail::require_positive(shape, "half_size", o.half_size);
  if (!std::isfinite(o.jitter) || o.jitter < 0.0 || !(o.jitter < 1.0 / 6.0))
    detail::fail(shape, "jitter must be in [0, 1/6), got " + detail::num(o.jitter));
  if (!std::isfinite(o.anisotropy) || o.anisotropy < 1.0 || o.anisotropy > 1000.0)
    detail::fail(shape, "anisotropy must be in [1, 1000], got " + detail::num(o.anisotropy));
  const double a = o.half_size;
  const bool jitter = o.variant == GridVariant::jittered;
  detail::Rng rng(o.seed);
  MeshBuilder b(weld_tolerance(a));

  if (o.outline == GridOutline::disk) {
    if (o.variant == GridVariant::anisotropic)
      detail::fail(shape, "the anisotropic variant supports the square and L outlines only");
    const int n = o.cells;
    const double h = a / n;
    // Ring k has 6k vertices (ring 0: the centre) at radius a k / n.
    std::vector<std::vector<int>> ring(static_cast<std::size_t>(n + 1));
    for (int k = 0; k <= n; ++k) {
      const int count = k == 0 ? 1 : 6 * k;
      for (int m = 0; m < count; ++m) {
        const auto cs = unit_circle(m, count);
        const double r = a * k / n;
        Vec3 p(r * cs[0], r * cs[1], 0.0);
        const double dx = rng.uniform(-1.0, 1.0), dy = rng.uniform(-1.0, 1.0);
        if (jitter && k < n) p += Vec3(0.5 * o.jitter * h * dx, 0.5 * o.jitter * h * dy, 0.0);
        ring[static_cast<std::size_t>(k)].push_back(b.unique_vertex(p));
      }
    }
    for (int k = 1; k <= n; ++k) {
      const auto& in = ring[static_cast<std::size_t>(k - 1)];
      const auto& out = ring[static_cast<std::size_t>(k)];
      const long long ni = static_cast<long long>(in.size()), no = static_cast<long long>(out.size());
      long long i = 0, j = 0;
      auto I = [&](long long x) { return in[static_cast<std::size_t>(x % ni)]; };
      auto O = [&](long long x) { return out[static_cast<std::size_t>(x % no)]; };
      // Merge the two rings by angle: advance the ring whose next vertex comes first.
      while (i < ni || j < no) {
        const bool advance_outer = (k == 1) ? true : (j < no && (i >= ni || (j + 1) * ni <= (i + 1) * no));
        if (advance_outer) {
          b.triangle(I(i), O(j), O(j + 1));
          ++j;
          if (k == 1 && j == no) break;
        } else {
          b.triangle(I(i), O(j), I(i + 1));
          ++i;
        }
      }
    }
    return b.build();
  }

  const bool l_shape = o.outline == GridOutline::l_shape;
  int ny = o.cells;
  int nx = o.cells;
  if (o.variant == GridVariant::anisotropic) nx = clamp_count(o.cells * o.anisotropy, 1);
  if (l_shape) {
    if (ny % 2 != 0) detail::fail(shape, "the L outline needs an even number of cells, got " + std::to_string(ny));
    if (nx % 2 != 0) ++nx;
  }
  require_cells(shape, nx, ny);
  const double hx = 2.0 * a / nx, hy = 2.0 * a / ny;
  auto removed = [&](int i, int j) { return l_shape && 2 * i >= nx && 2 * j >= ny; };  // cell (i, j)
  auto used = [&](int i, int j) {  // vertex (i, j) touches a kept cell
    for (int di = -1; di <= 0; ++di)
      for (int dj = -1; dj <= 0; ++dj) {
        const int ci = i + di, cj = j + dj;
        if (ci >= 0 && cj >= 0 && ci < nx && cj < ny && !removed(ci, cj)) return true;
      }
    return false;
  };
  auto on_border = [&](int i, int j) {
    if (i == 0 || j == 0 || i == nx || j == ny) return true;
    return l_shape && ((2 * i == nx && 2 * j >= ny) || (2 * j == ny && 2 * i >= nx));
  };
  std::vector<int> id(static_cast<std::size_t>(nx + 1) * static_cast<std::size_t>(ny + 1), -1);
  auto at = [&](int i, int j) -> int& {
    return id[static_cast<std::size_t>(j) * static_cast<std::size_t>(nx + 1) + static_cast<std::size_t>(i)];
  };
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      Vec3 p(a * (2 * i - nx) / nx, a * (2 * j - ny) / ny, 0.0);
      const double dx = rng.uniform(-1.0, 1.0), dy = rng.uniform(-1.0, 1.0);
      if (jitter && !on_border(i, j)) p += Vec3(o.jitter * hx * dx, o.jitter * hy * dy, 0.0);
      if (used(i, j)) at(i, j) = b.unique_vertex(p);
    }
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      if (removed(i, j)) continue;
      b.triangle(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      b.triangle(at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
  return b.build();
}

// ---- spheres ----------------------------------------------------------------------------

Mesh icosphere(int subdivisions, double radius) {
  require_subdivisions("icosphere", subdivisions);
  detail::require_positive("icosphere", "radius", radius);
  MeshBuilder b(weld_tolerance(radius));
  add_sphere(b, unit_icosphere(subdivisions), [&](const Vec3& u) { return radius * u; }, false);
  return b.build();
}

Mesh uv_sphere(int around, int rings, double radius) {
  const std::string shape = "uv-sphere";
  detail::require_count(shape, "around", around, 3, kMaxCount);
  detail::require_count(shape, "rings", rings, 2, kMaxCount);
  detail::require_positive(shape, "radius", radius);
  require_cells(shape, around, rings);
  MeshBuilder b(weld_tolerance(radius));
  b.grid(rings, around, [&](int i, int j) {
    const auto t = unit_circle(i, 2LL * rings);  // θ = π i / rings from the north pole
    const auto f = unit_circle(j, around);
    return Vec3(radius * t[1] * f[0], radius * t[1] * f[1], radius * t[0]);
  });
  return b.build();
}

Mesh hemisphere(int around, int rings, double radius) {
  const std::string shape = "hemisphere";
  detail::require_count(shape, "around", around, 3, kMaxCount);
  detail::require_count(shape, "rings", rings, 1, kMaxCount);
  detail::require_positive(shape, "radius", radius);
  require_cells(shape, around, rings);
  MeshBuilder b(weld_tolerance(radius));
  b.grid(rings, around, [&](int i, int j) {
    const auto t = unit_circle(i, 4LL * rings);  // θ = (π/2) i / rings
    const auto f = unit_circle(j, around);
    return Vec3(radius * t[1] * f[0], radius * t[1] * f[1], radius * t[0]);
  });
  return b.build();
}

Mesh nested_spheres(int subdivisions, double outer_radius, double inner_radius) {
  require_subdivisions("nested-spheres", subdivisions);
  detail::require_less("nested-spheres", "inner_radius", inner_radius, "radius", outer_radius);
  const Triangles tri = unit_icosphere(subdivisions);
  MeshBuilder b(weld_tolerance(outer_radius));
  add_sphere(b, tri, [&](const Vec3& u) { return outer_radius * u; }, false);
  add_sphere(b, tri, [&](const Vec3& u) { return inner_radius * u; }, true);
  return b.build();
}

Mesh bumpy_sphere(int subdivisions, double radius, double amplitude, double frequency) {
  const std::string shape = "bumpy-sphere";
  require_subdivisions(shape, subdivisions);
  detail::require_positive(shape, "radius", radius);
  detail::require_positive(shape, "frequency", frequency);
  if (!std::isfinite(amplitude) || amplitude < 0.0 || !(amplitude < 1.0))
    detail::fail(shape, "amplitude must be in [0, 1), got " + detail::num(amplitude));
  const detail::Bumpy bumpy{radius, amplitude, frequency};
  MeshBuilder b(weld_tolerance(radius));
  add_sphere(b, unit_icosphere(subdivisions), [&](const Vec3& u) { return bumpy.r(u) * u; }, false);
  return b.build();
}

// ---- surfaces of revolution ------------------------------------------------------------

Mesh open_cylinder(int around, int along, double radius, double height) {
  require_revolution("cylinder", around, along, radius, height);
  MeshBuilder b(weld_tolerance(std::max(radius, height)));
  b.grid(around, along, [&](int i, int j) {
    const auto f = unit_circle(i, around);
    return Vec3(radius * f[0], radius * f[1], height * j / along);
  });
  return b.build();
}

Mesh cone(int around, int along, double radius, double height) {
  require_revolution("cone", around, along, radius, height);
  MeshBuilder b(weld_tolerance(std::max(radius, height)));
  b.grid(around, along, [&](int i, int j) {
    const auto f = unit_circle(i, around);
    const double s = static_cast<double>(j) / along;
    const double r = j == along ? 0.0 : radius * (1.0 - s);
    return Vec3(r * f[0], r * f[1], j == along ? height : height * s);
  });
  return b.build();
}

Mesh torus(int major, int minor, double major_radius, double minor_radius) {
  const std::string shape = "torus";
  detail::require_count(shape, "major", major, 3, kMaxCount);
  detail::require_count(shape, "minor", minor, 3, kMaxCount);
  detail::require_less(shape, "minor_radius", minor_radius, "radius", major_radius);
  require_cells(shape, major, minor);
  MeshBuilder b(weld_tolerance(major_radius));
  b.grid(major, minor, [&](int i, int j) {
    const auto f = unit_circle(i, major);
    const auto p = unit_circle(j, minor);
    const double rho = major_radius + minor_radius * p[0];
    return Vec3(rho * f[0], rho * f[1], minor_radius * p[1]);
  });
  return b.build();
}

Mesh double_torus(int resolution, double major_radius, double minor_radius) {
  const std::string shape = "double-torus";
  detail::require_count(shape, "resolution", resolution, 3, kMaxCount);
  detail::require_less(shape, "minor_radius", minor_radius, "radius", major_radius);
  const int total_rays = std::max(8, resolution + (resolution % 2));
  const double A = kPi * major_radius, B = kPi * minor_radius;
  // Border points: the four corners (one point of the torus) and evenly spaced points on each
  // side, the same on opposite sides, so the identified sides weld vertex to vertex.
  // Each pair of identified sides is a circle of the torus: at least 3 segments.
  const int side_b = std::max(3, static_cast<int>(std::lround(total_rays * B / (2.0 * (A + B)))));
  const int side_a = std::max(3, total_rays / 2 - side_b);
  const int rays = 2 * (side_a + side_b);
  const int rings = std::max(2, rays / 8);
  require_cells(shape, 2LL * rays, rings);
  const double R = major_radius, r = minor_radius;
  // Half A: the torus centred at (-R, 0, 0), p(φ, ψ) = (-R + ρ cos φ, ρ sin φ, r sin ψ) with
  // ρ = R + r cos ψ, kept where x <= 0. Its parameter rectangle, scaled to (a, b) = (R φ, r ψ),
  // is [-A, A] x [-B, B] (opposite sides identified); the removed part x > 0 is an oval around
  // the origin, star-shaped from it. Rays from the origin to points along the rectangle's border
  // run from the oval (the cut, λ = 0) to the border (λ = 1); rings of constant λ follow the cut,
  // so the cells stay well shaped.
  auto border = [&](int k) {  // counter-clockwise from the corner (A, -B)
    if (k < side_b) return std::array<double, 2>{A, B * (2.0 * k - side_b) / side_b};
    k -= side_b;
    if (k < side_a) return std::array<double, 2>{A * (side_a - 2.0 * k) / side_a, B};
    k -= side_a;
    if (k < side_b) return std::array<double, 2>{-A, B * (side_b - 2.0 * k) / side_b};
    k -= side_b;
    return std::array<double, 2>{A * (2.0 * k - side_a) / side_a, -B};
  };
  auto x_of = [&](double a, double b) { return -R + (R + r * std::cos(b / r)) * std::cos(a / R); };
  auto point = [&](double a, double b) {
    const double phi = a / R, psi = b / r, rho = R + r * std::cos(psi);
    return Vec3(-R + rho * std::cos(phi), rho * std::sin(phi), r * std::sin(psi));
  };
  std::vector<std::array<double, 2>> outer(static_cast<std::size_t>(rays)), inner(outer.size());
  for (int k = 0; k < rays; ++k) {
    const auto q = border(k);
    double lo = 0.0, hi = 1.0;  // x(lo·q) > 0 (inside the oval), x(hi·q) <= 0
    for (int it = 0; it < 200 && hi - lo > 1e-15; ++it) {
      const double mid = 0.5 * (lo + hi);
      (x_of(mid * q[0], mid * q[1]) > 0.0 ? lo : hi) = mid;
    }
    outer[static_cast<std::size_t>(k)] = q;
    inner[static_cast<std::size_t>(k)] = {hi * q[0], hi * q[1]};
  }
  auto half_a = [&](int i, int j) {  // i: ring (λ = i / rings), j: ray
    const auto& in = inner[static_cast<std::size_t>(j % rays)];
    const auto& out = outer[static_cast<std::size_t>(j % rays)];
    const double l = static_cast<double>(i) / rings;
    Vec3 p = i == rings ? point(out[0], out[1]) : point(in[0] + l * (out[0] - in[0]), in[1] + l * (out[1] - in[1]));
    if (i == 0) p[0] = 0.0;  // on the cut plane exactly, so the two halves weld
    return p;
  };
  MeshBuilder b(weld_tolerance(R));
  b.grid(rings, rays, half_a);  // (λ, ray): outward
  b.grid(
      rings, rays,
      [&](int i, int j) {
        const Vec3 q = half_a(i, j);
        return Vec3(-q[0], q[1], q[2]);
      },
      true);
  return b.build();
}

// ---- strips -------------------------------------------------------------------------------

Mesh mobius_strip(int around, int across, double radius, double width) {
  const std::string shape = "mobius";
  detail::require_count(shape, "around", around, 3, kMaxCount);
  detail::require_count(shape, "across", across, 1, kMaxCount);
  detail::require_positive(shape, "width", width);
  detail::require_less(shape, "width/2", width / 2.0, "radius", radius);
  require_cells(shape, around, across);
  MeshBuilder b(weld_tolerance(radius));
  b.grid(
      around, across,
      [&](int i, int j) {
        const auto f = unit_circle(i, around);         // u
        const auto h = unit_circle(i, 2LL * around);   // u / 2
        const double v = width * (static_cast<double>(j) / across - 0.5);
        const double rho = radius + v * h[0];
        return Vec3(rho * f[0], rho * f[1], v * h[1]);
      },
      false, /*weld=*/false);
  return b.build();
}

Mesh half_twisted_ribbon(int along, int across, double length, double width) {
  const std::string shape = "ribbon";
  detail::require_count(shape, "along", along, 1, kMaxCount);
  detail::require_count(shape, "across", across, 1, kMaxCount);
  detail::require_positive(shape, "length", length);
  detail::require_positive(shape, "width", width);
  require_cells(shape, along, across);
  MeshBuilder b(weld_tolerance(std::max(length, width)));
  b.grid(along, across, [&](int i, int j) {
    const auto t = unit_circle(i, 2LL * along);  // angle π i / along
    const double v = width * (static_cast<double>(j) / across - 0.5);
    return Vec3(length * i / along, v * t[0], v * t[1]);
  });
  return b.build();
}

// ---- vaults -------------------------------------------------------------------------------

Mesh vault_shell(int arch, double radius, double thickness, double length) {
  const std::string shape = "vault-shell";
  detail::require_count(shape, "arch", arch, 3, kMaxCount);
  detail::require_less(shape, "thickness", thickness, "radius", radius);
  detail::require_positive(shape, "length", length);
  const double R = radius, t = thickness, L = length, Re = R + t;
  const double edge = kPi * R / arch;
  const int nl = clamp_count(L / edge, 1), nt = clamp_count(t / edge, 1);
  require_cells(shape, arch, nl);
  MeshBuilder b(weld_tolerance(R));
  auto Y = [&](int j) { return L * j / nl; };
  auto rho = [&](int k) { return k == nt ? Re : R + t * k / nt; };
  // extrados (outward: away from the axis), (y, θ)
  b.grid(nl, arch, [&](int j, int i) {
    const auto c = unit_circle(i, 2LL * arch);
    return Vec3(Re * c[0], Y(j), Re * c[1]);
  });
  // intrados (outward of the solid: toward the axis), (θ, y)
  b.grid(arch, nl, [&](int i, int j) {
    const auto c = unit_circle(i, 2LL * arch);
    return Vec3(R * c[0], Y(j), R * c[1]);
  });
  // feet in z = 0, normal -z, (y, x)
  b.grid(nl, nt, [&](int j, int k) { return Vec3(rho(k), Y(j), 0.0); });
  b.grid(nl, nt, [&](int j, int k) { return Vec3(-rho(nt - k), Y(j), 0.0); });
  // end arches: y = 0 (normal -y) in (ρ, θ), y = L (normal +y) in (θ, ρ)
  b.grid(nt, arch, [&](int k, int i) {
    const auto c = unit_circle(i, 2LL * arch);
    return Vec3(rho(k) * c[0], 0.0, rho(k) * c[1]);
  });
  b.grid(arch, nt, [&](int i, int k) {
    const auto c = unit_circle(i, 2LL * arch);
    return Vec3(rho(k) * c[0], L, rho(k) * c[1]);
  });
  return b.build();
}

Mesh vault_sheet(int arch, double radius, double length) {
  const std::string shape = "vault-sheet";
  detail::require_count(shape, "arch", arch, 3, kMaxCount);
  detail::require_positive(shape, "radius", radius);
  detail::require_positive(shape, "length", length);
  const int nl = clamp_count(length / (kPi * radius / arch), 1);
  require_cells(shape, arch, nl);
  MeshBuilder b(weld_tolerance(radius));
  b.grid(nl, arch, [&](int j, int i) {
    const auto c = unit_circle(i, 2LL * arch);
    return Vec3(radius * c[0], length * j / nl, radius * c[1]);
  });
  return b.build();
}

Mesh pointed_vault(int arch, double radius, double length) {
  const std::string shape = "pointed-vault";
  detail::require_count(shape, "arch", arch, 3, kMaxCount);
  detail::require_positive(shape, "radius", radius);
  detail::require_positive(shape, "length", length);
  const int n = arch + (arch % 2);
  const int half = n / 2;
  const double R = radius;
  const int nl = clamp_count(length / (2.0 * R * (kPi / 3.0) / half), 1);
  require_cells(shape, n, nl);
  MeshBuilder b(weld_tolerance(R));
  b.grid(nl, n, [&](int j, int t) {
    const double y = length * j / nl;
    if (t <= half) {  // right arc, centre (-R, 0), angle β = (π/3) t / half
      const auto c = unit_circle(t, 6LL * half);
      return Vec3(-R + 2.0 * R * c[0], y, 2.0 * R * c[1]);
    }
    // left arc, centre (R, 0), angle α = 2π/3 + (π/3)(t - half)/half
    const auto c = unit_circle(static_cast<long long>(half) + t, 6LL * half);
    return Vec3(R + 2.0 * R * c[0], y, 2.0 * R * c[1]);
  });
  return b.build();
}

Mesh groin_vault(int arch, double radius) {
  const std::string shape = "groin-vault";
  detail::require_count(shape, "arch", arch, 3, kMaxCount);
  detail::require_positive(shape, "radius", radius);
  const int n = arch + (arch % 2);
  const int m = n / 2;
  const double R = radius;
  require_cells(shape, 4LL * n, m);
  MeshBuilder b(weld_tolerance(R));
  // The +x quarter: the barrel along x, z = sqrt(R² - y²), where |y| <= x. (θ, s) with
  // y = R cos θ, z = R sin θ, x = R|cos θ| + s (R - R|cos θ|).
  for (int quarter = 0; quarter < 4; ++quarter) {
    b.grid(n, m, [&](int i, int j) {
      const auto c = unit_circle(i, 2LL * n);
      const double ac = std::abs(c[0]);
      const double x = j == m ? R : R * ac + (R - R * ac) * j / m;
      double px = x, py = R * c[0];
      for (int q = 0; q < quarter; ++q) {  // rotate by 90° about z
        const double tmp = px;
        px = -py;
        py = tmp;
      }
      return Vec3(px, py, R * c[1]);
    });
  }
  return b.build();
}

Mesh thin_plate(int cells, double half_size, double thickness) {
  const std::string shape = "thin-plate";
  detail::require_count(shape, "cells", cells, 1, kMaxCount);
  detail::require_positive(shape, "half_size", half_size);
  detail::require_less(shape, "thickness", thickness, "2 * half_size", 2.0 * half_size);
  const int n = cells;
  const int nt = clamp_count(thickness / (2.0 * half_size / n), 1);
  require_cells(shape, n, n);
  const double a = half_size, t = thickness;
  auto X = [&](int i) { return a * (2 * i - n) / n; };
  auto Z = [&](int k) { return t * (static_cast<double>(k) / nt - 0.5); };
  MeshBuilder b(weld_tolerance(a));
  b.grid(n, n, [&](int i, int j) { return Vec3(X(i), X(j), Z(nt)); });          // +z: (x, y)
  b.grid(n, n, [&](int j, int i) { return Vec3(X(i), X(j), Z(0)); });           // -z: (y, x)
  b.grid(n, nt, [&](int j, int k) { return Vec3(X(n), X(j), Z(k)); });          // +x: (y, z)
  b.grid(nt, n, [&](int k, int j) { return Vec3(X(0), X(j), Z(k)); });          // -x: (z, y)
  b.grid(nt, n, [&](int k, int i) { return Vec3(X(i), X(n), Z(k)); });          // +y: (z, x)
  b.grid(n, nt, [&](int i, int k) { return Vec3(X(i), X(0), Z(k)); });          // -y: (x, z)
  return b.build();
}

Mesh hairpin(int resolution, double arm_length, double width, double thickness, double gap) {
  const std::string shape = "hairpin";
  detail::require_count(shape, "resolution", resolution, 1, kMaxCount);
  detail::require_positive(shape, "arm_length", arm_length);
  detail::require_positive(shape, "width", width);
  detail::require_positive(shape, "thickness", thickness);
  detail::require_positive(shape, "gap", gap);
  const detail::HairpinFrame frame{arm_length, (gap + thickness) / 2.0};
  const double t = thickness, W = width;
  const int na = resolution;
  const double edge = arm_length / na;
  const int nb = std::max(4, clamp_count(kPi * (frame.c + t / 2.0) / edge, 4));
  const int nw = clamp_count(W / edge, 1), nt = clamp_count(t / edge, 1);
  const int ns = 2 * na + nb;
  require_cells(shape, ns, std::max(nw, nt));
  // Frames at the knots along the centre line.
  std::vector<detail::HairpinFrame::At> knot;
  for (int k = 0; k <= ns; ++k) {
    if (k <= na)
      knot.push_back(frame.at(arm_length * k / na));
    else if (k < na + nb)
      knot.push_back(frame.bend(k - na, nb));
    else
      knot.push_back(frame.at(frame.total() - arm_length * (ns - k) / na));
  }
  auto D = [&](int k) { return t * (static_cast<double>(k) / nt - 0.5); };
  auto Yw = [&](int k) { return W * (static_cast<double>(k) / nw - 0.5); };
  auto P = [&](int s, double d, double y) {
    const auto& f = knot[static_cast<std::size_t>(s)];
    return f.point + d * f.normal + Vec3(0, y, 0);
  };
  MeshBuilder b(weld_tolerance(std::max(arm_length, W)));
  b.grid(nw, ns, [&](int k, int s) { return P(s, D(nt), Yw(k)); });   // outer wall: (y, σ)
  b.grid(ns, nw, [&](int s, int k) { return P(s, D(0), Yw(k)); });    // inner wall: (σ, y)
  b.grid(ns, nt, [&](int s, int k) { return P(s, D(k), Yw(nw)); });   // side y = +W/2: (σ, d)
  b.grid(nt, ns, [&](int k, int s) { return P(s, D(k), Yw(0)); });    // side y = -W/2: (d, σ)
  b.grid(nw, nt, [&](int k, int l) { return P(0, D(l), Yw(k)); });    // top arm end: (y, d)
  b.grid(nt, nw, [&](int l, int k) { return P(ns, D(l), Yw(k)); });   // bottom arm end: (d, y)
  return b.build();
}

Mesh landscape(int cells, double half_size, double amplitude, double frequency, std::uint64_t terrain_seed) {
  const std::string shape = "landscape";
  detail::require_count(shape, "cells", cells, 1, kMaxCount);
  detail::require_positive(shape, "half_size", half_size);
  detail::require_positive(shape, "frequency", frequency);
  if (!std::isfinite(amplitude) || amplitude < 0.0)
    detail::fail(shape, "amplitude must be finite and >= 0, got " + detail::num(amplitude));
  require_cells(shape, cells, cells);
  const detail::Terrain terrain(half_size, amplitude, frequency, terrain_seed);
  const double a = half_size;
  const int n = cells;
  MeshBuilder b(weld_tolerance(a));
  b.grid(n, n, [&](int i, int j) { return terrain.point(a * (2 * i - n) / n, a * (2 * j - n) / n); });
  return b.build();
}

// ---- the neck and minimum pathways ------------------------------------------------------

NeckMesh neck(int around) {
  const std::string shape = "neck";
  detail::require_count(shape, "around", around, 6, 3072);
  int k = 0;
  while ((3 << k) < around) ++k;
  if ((3 << k) != around || k < 1) detail::fail(shape, "around must be 3·2^k with k >= 1, got " + std::to_string(around));
  // Profile (radius, z) of the upper blob, from the pole to the neck; the lower blob mirrors it.
  struct Ring {
    int count;
    double r, z;
  };
  const double centre = 1.1, neck_radius = 0.25, last_theta = 0.7 * kPi;
  const int full = std::max(2, around / 4);
  std::vector<Ring> upper;
  for (int j = 1; j <= full; ++j) {
    const double th = last_theta * j / full;
    upper.push_back({around, std::sin(th), centre + std::cos(th)});
  }
  const Ring last = upper.back();
  for (int h = 1; h <= k; ++h) {
    const double s = static_cast<double>(h) / k;
    upper.push_back({around >> h, (1.0 - s) * last.r + s * neck_radius, (1.0 - s) * last.z});
  }
  MeshBuilder b(weld_tolerance(1.0));
  auto make_ring = [&](const Ring& ring, double zsign) {
    std::vector<int> ids;
    for (int m = 0; m < ring.count; ++m) {
      const auto cs = unit_circle(m, ring.count);
      ids.push_back(b.unique_vertex(Vec3(ring.r * cs[0], ring.r * cs[1], zsign * ring.z)));
    }
    return ids;
  };
  std::vector<std::vector<int>> rings;  // from the north pole's first ring down to the south
  const int north = b.unique_vertex(Vec3(0, 0, centre + 1.0));
  for (const auto& ring : upper) rings.push_back(make_ring(ring, 1.0));
  const std::size_t neck_index = rings.size() - 1;
  for (auto it = upper.rbegin() + 1; it != upper.rend(); ++it) rings.push_back(make_ring(*it, -1.0));
  const int south = b.unique_vertex(Vec3(0, 0, -(centre + 1.0)));
  // Triangles, outward, for rings ordered top to bottom (angle increasing counter-clockwise).
  auto at = [](const std::vector<int>& ring, int i) {
    return ring[static_cast<std::size_t>(i % static_cast<int>(ring.size()))];
  };
  {
    const auto& a = rings.front();
    for (int i = 0; i < static_cast<int>(a.size()); ++i) b.triangle(north, at(a, i), at(a, i + 1));
  }
  for (std::size_t r = 0; r + 1 < rings.size(); ++r) {
    const auto& a = rings[r];
    const auto& c = rings[r + 1];
    const int na = static_cast<int>(a.size()), nc = static_cast<int>(c.size());
    if (na == nc) {
      for (int i = 0; i < na; ++i) {
        b.triangle(at(a, i), at(c, i), at(a, i + 1));
        b.triangle(at(a, i + 1), at(c, i), at(c, i + 1));
      }
    } else if (na == 2 * nc) {
      for (int i = 0; i < nc; ++i) {
        b.triangle(at(a, 2 * i), at(c, i), at(a, 2 * i + 1));
        b.triangle(at(a, 2 * i + 1), at(c, i), at(c, i + 1));
        b.triangle(at(a, 2 * i + 1), at(c, i + 1), at(a, 2 * i + 2));
      }
    } else {
      EF_CHECK(nc == 2 * na, "neck ring sizes must halve or double");
      for (int i = 0; i < na; ++i) {
        b.triangle(at(a, i), at(c, 2 * i), at(c, 2 * i + 1));
        b.triangle(at(a, i), at(c, 2 * i + 1), at(a, i + 1));
        b.triangle(at(a, i + 1), at(c, 2 * i + 1), at(c, 2 * i + 2));
      }
    }
  }
  {
    const auto& a = rings.back();
    for (int i = 0; i < static_cast<int>(a.size()); ++i) b.triangle(at(a, i), south, at(a, i + 1));
  }
  NeckMesh result;
  result.mesh = b.build();
  // All vertices are used, so builder indices are mesh indices.
  const auto& neck_ring = rings[neck_index];
  EF_CHECK(neck_ring.size() == 3, "the neck ring must have three vertices");
  for (std::size_t i = 0; i < 3; ++i) result.pathway[i] = VertexHandle(neck_ring[i]);
  return result;
}

bool is_minimum_pathway(const Mesh& mesh, VertexHandle v0, VertexHandle v1, VertexHandle v2) {
  for (const VertexHandle v : {v0, v1, v2})
    if (!is_live(mesh, v))
      throw InvalidInput("is_minimum_pathway: vertex " + std::to_string(v.idx()) + " is not a live vertex of the mesh");
  if (v0 == v1 || v1 == v2 || v0 == v2) throw InvalidInput("is_minimum_pathway: the three vertices must be distinct");
  const HalfedgeHandle h01 = mesh.find_halfedge(v0, v1);
  if (!h01.is_valid() || !mesh.find_halfedge(v1, v2).is_valid() || !mesh.find_halfedge(v2, v0).is_valid())
    return false;
  // A face with these three vertices contains the edge v0 v1: look at its (at most) two faces.
  for (const HalfedgeHandle h : {h01, mesh.opposite_halfedge_handle(h01)}) {
    if (mesh.is_boundary(h)) continue;
    if (mesh.to_vertex_handle(mesh.next_halfedge_handle(h)) == v2) return false;
  }
  return true;
}

std::vector<std::array<VertexHandle, 3>> find_minimum_pathways(const Mesh& mesh) {
  std::vector<std::array<VertexHandle, 3>> found;
  std::vector<int> ring;
  for (const auto a : mesh.vertices()) {
    if (mesh.status(a).deleted()) continue;
    ring.clear();
    for (const auto v : mesh.vv_range(a))
      if (v.idx() > a.idx()) ring.push_back(v.idx());
    std::sort(ring.begin(), ring.end());
    for (std::size_t i = 0; i < ring.size(); ++i)
      for (std::size_t j = i + 1; j < ring.size(); ++j) {
        const VertexHandle b(ring[i]), c(ring[j]);
        if (mesh.find_halfedge(b, c).is_valid() && is_minimum_pathway(mesh, a, b, c))
          found.push_back({a, b, c});
      }
  }
  std::sort(found.begin(), found.end(), [](const auto& x, const auto& y) {
    return std::make_tuple(x[0].idx(), x[1].idx(), x[2].idx()) < std::make_tuple(y[0].idx(), y[1].idx(), y[2].idx());
  });
  return found;
}

std::vector<VertexHandle> add_island(Mesh& mesh, const Vec3& corner, double spacing) {
  if (!(std::isfinite(corner[0]) && std::isfinite(corner[1]) && std::isfinite(corner[2])))
    throw InvalidInput("add_island: the corner must be finite");
  if (!(std::isfinite(spacing) && spacing > 0))
    throw InvalidInput("add_island: the spacing must be finite and > 0, got " + std::to_string(spacing));
  std::vector<VertexHandle> vs, top, bottom;
  for (int i = 0; i < 6; ++i) {
    top.push_back(mesh.add_vertex(corner + Vec3(spacing * i, spacing, 0)));
    bottom.push_back(mesh.add_vertex(corner + Vec3(spacing * i, 0, 0)));
    vs.push_back(top.back());
    vs.push_back(bottom.back());
  }
  for (size_t i = 0; i < 5; ++i) {
    mesh.add_face(bottom[i], bottom[i + 1], top[i + 1]);
    mesh.add_face(bottom[i], top[i + 1], top[i]);
  }
  return vs;
}

PinchedBody pinched_body(int around) {
  const std::string shape = "pinched-body";
  detail::require_count(shape, "around", around, 6, 1024);
  if (around % 2 != 0) detail::fail(shape, "around must be even, got " + std::to_string(around));
  const int n = around, rings = std::max(2, around / 4);
  // cos and sin of 2πk/m with sin(-a) exactly -sin(a): the body is mirror-symmetric in z.
  const auto circle = [](int k, int m) {
    k = ((k % m) + m) % m;
    if (2 * k <= m) return unit_circle(k, m);
    const auto c = unit_circle(m - k, m);
    return std::array<double, 2>{c[0], -c[1]};
  };
  std::vector<Vec3> points;
  using Tri = std::array<int, 3>;
  // Adds a closed part's triangles, flipped if needed so that its volume is positive (outward).
  std::vector<Tri> tris;
  const auto add_part = [&](std::vector<Tri> part) {
    double volume = 0;
    for (const Tri& t : part) {
      volume += OpenMesh::dot(points[static_cast<size_t>(t[0])],
                              OpenMesh::cross(points[static_cast<size_t>(t[1])], points[static_cast<size_t>(t[2])]));
    }
    for (Tri& t : part) {
      if (volume < 0) std::swap(t[1], t[2]);
      tris.push_back(t);
    }
  };

  // The horn torus: rows j of the tube angle v = 2πj/n (row n/2 is the origin, one vertex), n
  // vertices around z per row. The lower side's faces at the origin go to its copy (set below).
  std::vector<int> row(static_cast<size_t>(n), -1);
  for (int j = 0; j < n; ++j) {
    row[static_cast<size_t>(j)] = static_cast<int>(points.size());
    if (2 * j == n) {
      points.emplace_back(0, 0, 0);
      continue;
    }
    const auto v = circle(j, n);
    for (int i = 0; i < n; ++i) {
      const auto u = circle(i, n);
      points.emplace_back((1 + v[0]) * u[0], (1 + v[0]) * u[1], v[1]);
    }
  }
  const int centre = row[static_cast<size_t>(n / 2)];
  const auto torus_vertex = [&](int i, int j) {
    j = ((j % n) + n) % n;
    return 2 * j == n ? centre : row[static_cast<size_t>(j)] + ((i % n) + n) % n;
  };
  int centre_copy = -1;  // set once the input's vertices are all placed
  std::vector<Tri> torus;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const int a = torus_vertex(i, j), b = torus_vertex(i + 1, j), c = torus_vertex(i + 1, j + 1), d = torus_vertex(i, j + 1);
      if (2 * (j + 1) == n) {
        torus.push_back({a, b, centre});  // the upper side's fan at the origin
      } else if (2 * j == n) {
        torus.push_back({-1, c, d});  // the lower side's fan: the copy
      } else if (2 * j < n) {  // upper half: one diagonal; the lower half mirrors it
        torus.push_back({a, b, c});
        torus.push_back({a, c, d});
      } else {
        torus.push_back({a, b, d});
        torus.push_back({b, c, d});
      }
    }
  }

  // The cones: apex at the torus's outer equator, axis along ±x, lateral rings t = 1..rings on
  // the generators m (straight lines from the apex), a flat base with a centre vertex.
  constexpr double kHeight = 1.0, kBase = 0.4;
  std::array<std::vector<Tri>, 2> cones;
  std::array<int, 2> apex{torus_vertex(0, 0), torus_vertex(n / 2, 0)};
  PinchedBody body;
  for (int k = 0; k < 2; ++k) {
    const double ex = k == 0 ? 1.0 : -1.0;
    const Vec3 a = points[static_cast<size_t>(apex[static_cast<size_t>(k)])];
    const int first = static_cast<int>(points.size());
    const auto side = [&](int t, int m) { return first + (t - 1) * n + ((m % n) + n) % n; };
    for (int t = 1; t <= rings; ++t) {
      const double s = static_cast<double>(t) / rings;
      for (int m = 0; m < n; ++m) {
        const auto f = circle(m, n);
        points.push_back(a + Vec3(ex * kHeight * s, kBase * s * f[0], kBase * s * f[1]));
      }
    }
    const int base = static_cast<int>(points.size());
    points.push_back(a + Vec3(ex * kHeight, 0, 0));
    std::vector<Tri>& cone = cones[static_cast<size_t>(k)];
    for (int m = 0; m < n; ++m) {
      cone.push_back({-1, side(1, m), side(1, m + 1)});  // the apex: the copy (set below)
      for (int t = 1; t < rings; ++t) {
        const int p = side(t, m), q = side(t, m + 1), r = side(t + 1, m + 1), s = side(t + 1, m);
        if (2 * m < n) {  // z > 0: one diagonal; z < 0 mirrors it
          cone.push_back({q, p, r});
          cone.push_back({p, s, r});
        } else {
          cone.push_back({q, p, s});
          cone.push_back({q, s, r});
        }
      }
      cone.push_back({base, side(rings, m + 1), side(rings, m)});
    }
    for (int v = first; v < base; ++v) body.cone_sides[static_cast<size_t>(k)].emplace_back(v);
  }

  // The copies, appended after the input's vertices (as the mesh loader splits a pinched vertex).
  body.input_vertices = points.size();
  centre_copy = static_cast<int>(points.size());
  points.emplace_back(0, 0, 0);
  std::array<int, 2> apex_copy{};
  for (int k = 0; k < 2; ++k) {
    apex_copy[static_cast<size_t>(k)] = static_cast<int>(points.size());
    points.push_back(points[static_cast<size_t>(apex[static_cast<size_t>(k)])]);
  }
  for (Tri& t : torus) {
    if (t[0] < 0) t[0] = centre_copy;
  }
  add_part(std::move(torus));
  for (int k = 0; k < 2; ++k) {
    for (Tri& t : cones[static_cast<size_t>(k)]) {
      if (t[0] < 0) t[0] = apex_copy[static_cast<size_t>(k)];
    }
    add_part(std::move(cones[static_cast<size_t>(k)]));
  }

  Mesh& mesh = body.mesh;
  for (const Vec3& p : points) mesh.add_vertex(p);
  for (const Tri& t : tris) {
    EF_CHECK(mesh.add_face(VertexHandle(t[0]), VertexHandle(t[1]), VertexHandle(t[2])).is_valid(),
             "pinched body: a face was refused");
  }
  mesh.update_face_normals();
  body.pinches = {{{VertexHandle(apex[0]), VertexHandle(apex_copy[0])},
                   {VertexHandle(apex[1]), VertexHandle(apex_copy[1])},
                   {VertexHandle(centre), VertexHandle(centre_copy)}}};
  for (const auto& group : body.pinches) link_twins(mesh, {group[0], group[1]});
  return body;
}

}  // namespace edgefront::shapes
