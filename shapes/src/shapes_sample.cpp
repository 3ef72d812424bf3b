// Area-uniform oriented samplers of shapes/shapes.h.
//
// Every shape is a list of parametric patches (u, v) -> (point, unit normal, area element dA).
// Sampling is exact rejection: a patch is chosen with probability proportional to
// (u-range)·(v-range)·dA_max, (u, v) uniformly, and the draw is kept with probability
// dA / dA_max. The accepted points are then uniform by area over the union of the patches,
// without having to know any patch's area. Trimmed patches (the L outline, the cut tori of the
// double torus) return dA = 0 outside their domain.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <numeric>
#include <string>
#include <vector>

#include "edgefront/error.h"
#include "shapes/shapes.h"
#include "shapes_detail.h"

namespace edgefront::shapes {

namespace {

using detail::kPi;

struct Eval {
  Vec3 p, n;
  double dA;
};

struct Patch {
  double u0, u1, v0, v1;
  double dA_max;
  std::function<Eval(double, double)> eval;
};

using Surface = std::vector<Patch>;

/// A flat rectangle origin + u·U + v·V, (u, v) in [0, 1]², normal U × V normalized.
Patch rectangle(const Vec3& origin, const Vec3& U, const Vec3& V) {
  const Vec3 n = (U % V).normalized();
  const double area = (U % V).norm();
  return {0, 1, 0, 1, area, [=](double u, double v) { return Eval{origin + u * U + v * V, n, area}; }};
}

/// Sphere of radius r about the origin, by (φ, z): the map is area preserving (Archimedes).
/// `z0` cuts it to z >= z0·r. `sign` -1 points the normals inward.
Patch sphere(double r, double z0 = -1.0, double sign = 1.0) {
  return {0, 2 * kPi, z0 * r, r, r, [=](double phi, double z) {
            const double s = std::sqrt(std::max(0.0, r * r - z * z));
            const Vec3 p(s * std::cos(phi), s * std::sin(phi), z);
            return Eval{p, sign * p / r, r};
          }};
}

/// Cylinder patch along y about the axis (cx, ·, cz): x = cx + r cos θ, z = cz + r sin θ,
/// θ in [a0, a1], y in [0, L]. `sign` +1: normals away from the axis.
Patch y_cylinder(double cx, double cz, double r, double a0, double a1, double L, double sign) {
  return {a0, a1, 0, L, r, [=](double th, double y) {
            const Vec3 d(std::cos(th), 0, std::sin(th));
            return Eval{Vec3(cx, y, cz) + r * d, sign * d, r};
          }};
}

/// Half annulus in the plane y = y0: (ρ cos θ, y0, ρ sin θ), ρ in [r0, r1], θ in [0, π].
Patch half_annulus(double r0, double r1, double y0, double ny) {
  return {r0, r1, 0, kPi, r1, [=](double rho, double th) {
            return Eval{Vec3(rho * std::cos(th), y0, rho * std::sin(th)), Vec3(0, ny, 0), rho};
          }};
}

Surface torus_half(double R, double r, bool mirrored) {
  // Torus centred at (-R, 0, 0), kept where x <= 0; mirrored in x for the second half.
  const double m = mirrored ? -1.0 : 1.0;
  return {Patch{0, 2 * kPi, 0, 2 * kPi, r * (R + r), [=](double phi, double psi) {
                  const double rho = R + r * std::cos(psi);
                  const Vec3 n(std::cos(psi) * std::cos(phi), std::cos(psi) * std::sin(phi), std::sin(psi));
                  const Vec3 p(-R + rho * std::cos(phi), rho * std::sin(phi), r * std::sin(psi));
                  if (p[0] > 0.0) return Eval{p, n, 0.0};
                  return Eval{Vec3(m * p[0], p[1], p[2]), Vec3(m * n[0], n[1], n[2]), r * rho};
                }}};
}

Surface surface_of(const std::string& name, const ShapeParams& sp) {
  const double R = sp.radius;
  if (name == "grid" || name == "grid-jittered" || name == "grid-anisotropic" || name == "disk" || name == "l-shape") {
    GridOutline outline = sp.grid_outline;
    if (name == "disk") outline = GridOutline::disk;
    if (name == "l-shape") outline = GridOutline::l_shape;
    if (name == "grid-jittered" || name == "grid-anisotropic") outline = GridOutline::square;
    return {Patch{-R, R, -R, R, 1.0, [=](double x, double y) {
                    double dA = 1.0;
                    if (outline == GridOutline::disk && x * x + y * y > R * R) dA = 0.0;
                    if (outline == GridOutline::l_shape && x > 0.0 && y > 0.0) dA = 0.0;
                    return Eval{Vec3(x, y, 0), Vec3(0, 0, 1), dA};
                  }}};
  }
  if (name == "icosphere" || name == "uv-sphere") return {sphere(R)};
  if (name == "hemisphere") return {sphere(R, 0.0)};
  if (name == "nested-spheres") return {sphere(R), sphere(sp.inner_radius, -1.0, -1.0)};
  if (name == "bumpy-sphere") {
    const detail::Bumpy bumpy{R, sp.amplitude, sp.frequency};
    return {Patch{0, 2 * kPi, -1, 1, bumpy.jacobian_bound(), [=](double phi, double z) {
                    const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
                    const Vec3 u(s * std::cos(phi), s * std::sin(phi), z);
                    return Eval{bumpy.r(u) * u, bumpy.normal(u), bumpy.jacobian(u)};
                  }}};
  }
  if (name == "cylinder")
    return {Patch{0, 2 * kPi, 0, sp.length, R, [=](double phi, double z) {
                    const Vec3 d(std::cos(phi), std::sin(phi), 0);
                    return Eval{R * d + Vec3(0, 0, z), d, R};
                  }}};
  if (name == "cone") {
    const double h = sp.length, slant = std::sqrt(R * R + h * h);
    return {Patch{0, 2 * kPi, 0, 1, R * slant, [=](double phi, double s) {
                    const double c = std::cos(phi), sn = std::sin(phi);
                    return Eval{Vec3((1 - s) * R * c, (1 - s) * R * sn, s * h), Vec3(h * c, h * sn, R) / slant,
                                (1 - s) * R * slant};
                  }}};
  }
  if (name == "torus") {
    const double r = sp.minor_radius;
    return {Patch{0, 2 * kPi, 0, 2 * kPi, r * (R + r), [=](double phi, double psi) {
                    const double rho = R + r * std::cos(psi);
                    const Vec3 n(std::cos(psi) * std::cos(phi), std::cos(psi) * std::sin(phi), std::sin(psi));
                    return Eval{Vec3(rho * std::cos(phi), rho * std::sin(phi), r * std::sin(psi)), n, r * rho};
                  }}};
  }
  if (name == "double-torus") {
    Surface s = torus_half(R, sp.minor_radius, false);
    Surface t = torus_half(R, sp.minor_radius, true);
    s.insert(s.end(), t.begin(), t.end());
    return s;
  }
  if (name == "mobius") {
    const double w = sp.width;
    const double bound = std::sqrt((R + w / 2) * (R + w / 2) + w * w / 16);
    return {Patch{0, 2 * kPi, -w / 2, w / 2, bound, [=](double u, double v) {
                    const double cu = std::cos(u), su = std::sin(u), ch = std::cos(u / 2), sh = std::sin(u / 2);
                    const double rho = R + v * ch;
                    const Vec3 p(rho * cu, rho * su, v * sh);
                    const Vec3 du(-rho * su - 0.5 * v * sh * cu, rho * cu - 0.5 * v * sh * su, 0.5 * v * ch);
                    const Vec3 dv(ch * cu, ch * su, sh);
                    const Vec3 c = du % dv;
                    const double a = c.norm();
                    return Eval{p, c / a, a};
                  }}};
  }
  if (name == "ribbon") {
    const double L = sp.length, w = sp.width, k = kPi / L;
    return {Patch{0, L, -w / 2, w / 2, std::sqrt(1 + (w * k / 2) * (w * k / 2)), [=](double u, double v) {
                    const double c = std::cos(k * u), s = std::sin(k * u);
                    const Vec3 n(-v * k, -s, c);
                    const double a = n.norm();
                    return Eval{Vec3(u, v * c, v * s), n / a, a};
                  }}};
  }
  if (name == "vault-shell") {
    const double t = sp.thickness, L = sp.length, Re = R + t;
    return {y_cylinder(0, 0, Re, 0, kPi, L, 1.0),
            y_cylinder(0, 0, R, 0, kPi, L, -1.0),
            rectangle(Vec3(R, 0, 0), Vec3(0, L, 0), Vec3(t, 0, 0)),    // right foot, -z
            rectangle(Vec3(-Re, 0, 0), Vec3(0, L, 0), Vec3(t, 0, 0)),  // left foot, -z
            half_annulus(R, Re, 0.0, -1.0),
            half_annulus(R, Re, L, 1.0)};
  }
  if (name == "vault-sheet") return {y_cylinder(0, 0, R, 0, kPi, sp.length, 1.0)};
  if (name == "pointed-vault")
    return {y_cylinder(-R, 0, 2 * R, 0, kPi / 3, sp.length, 1.0),
            y_cylinder(R, 0, 2 * R, 2 * kPi / 3, kPi, sp.length, 1.0)};
  if (name == "groin-vault") {
    Surface s;
    for (int quarter = 0; quarter < 4; ++quarter) {
      s.push_back(Patch{0, kPi, 0, 1, R * R, [=](double th, double u) {
                          const double c = std::cos(th), sn = std::sin(th), ac = std::abs(c);
                          double px = R * ac + u * (R - R * ac), py = R * c;
                          double nx = 0, ny = c;
                          for (int q = 0; q < quarter; ++q) {
                            const double tp = px, tn = nx;
                            px = -py;
                            py = tp;
                            nx = -ny;
                            ny = tn;
                          }
                          return Eval{Vec3(px, py, R * sn), Vec3(nx, ny, sn), R * R * (1 - ac)};
                        }});
    }
    return s;
  }
  if (name == "thin-plate") {
    const double a = R, t = sp.thickness, h = t / 2;
    return {rectangle(Vec3(-a, -a, h), Vec3(2 * a, 0, 0), Vec3(0, 2 * a, 0)),   // +z
            rectangle(Vec3(-a, -a, -h), Vec3(0, 2 * a, 0), Vec3(2 * a, 0, 0)),  // -z
            rectangle(Vec3(a, -a, -h), Vec3(0, 2 * a, 0), Vec3(0, 0, t)),       // +x
            rectangle(Vec3(-a, -a, -h), Vec3(0, 0, t), Vec3(0, 2 * a, 0)),      // -x
            rectangle(Vec3(-a, a, -h), Vec3(0, 0, t), Vec3(2 * a, 0, 0)),       // +y
            rectangle(Vec3(-a, -a, -h), Vec3(2 * a, 0, 0), Vec3(0, 0, t))};     // -y
  }
  if (name == "hairpin") {
    const detail::HairpinFrame frame{sp.length, (sp.gap + sp.thickness) / 2.0};
    const double t = sp.thickness, W = sp.width, total = frame.total();
    const double stretch = 1.0 + t / (2.0 * frame.c);
    // Walls along the centre line: the offset d along the normal stretches arc length by 1 + κ d.
    auto wall = [=](double d, double sign) {
      return Patch{0, total, -W / 2, W / 2, stretch, [=](double s, double y) {
                     const auto f = frame.at(s);
                     return Eval{f.point + d * f.normal + Vec3(0, y, 0), sign * f.normal, 1.0 + f.curvature * d};
                   }};
    };
    auto side = [=](double y) {
      return Patch{0, total, -t / 2, t / 2, stretch, [=](double s, double d) {
                     const auto f = frame.at(s);
                     return Eval{f.point + d * f.normal + Vec3(0, y, 0), Vec3(0, y > 0 ? 1.0 : -1.0, 0),
                                 1.0 + f.curvature * d};
                   }};
    };
    const double L = sp.length, c = frame.c;
    return {wall(t / 2, 1.0), wall(-t / 2, -1.0), side(W / 2), side(-W / 2),
            rectangle(Vec3(L, -W / 2, c - t / 2), Vec3(0, W, 0), Vec3(0, 0, t)),
            rectangle(Vec3(L, -W / 2, -c - t / 2), Vec3(0, W, 0), Vec3(0, 0, t))};
  }
  if (name == "landscape") {
    const detail::Terrain terrain(R, sp.amplitude, sp.frequency, sp.surface_seed);
    const double g = terrain.slope_bound();
    return {Patch{-R, R, -R, R, std::sqrt(1 + g * g), [=](double x, double y) {
                    const auto gr = terrain.grad(x, y);
                    return Eval{terrain.point(x, y), terrain.normal(x, y), std::sqrt(1 + gr[0] * gr[0] + gr[1] * gr[1])};
                  }}};
  }
  detail::fail(name, "unknown shape");
}

void validate_sampling(const SampleOptions& o) {
  if (o.points < 1 || o.points > 100000000)
    throw InvalidInput("shapes: sample: points must be in [1, 1e8], got " + std::to_string(o.points));
  if (!std::isfinite(o.noise_sigma) || o.noise_sigma < 0.0)
    throw InvalidInput("shapes: sample: noise_sigma must be finite and >= 0, got " + detail::num(o.noise_sigma));
  if (!std::isfinite(o.outlier_fraction) || o.outlier_fraction < 0.0 || o.outlier_fraction > 1.0)
    throw InvalidInput("shapes: sample: outlier_fraction must be in [0, 1], got " + detail::num(o.outlier_fraction));
}

/// Noise on the clean samples, then outliers at random positions.
void perturb(PointCloud& cloud, const SampleOptions& o, detail::Rng& rng) {
  if (o.noise_sigma > 0.0) {
    for (std::size_t i = 0; i < cloud.size(); ++i) {
      if (o.noise == NoiseKind::along_normal)
        cloud.points[i] += o.noise_sigma * rng.normal() * cloud.normals[i];
      else {
        const double x = rng.normal(), y = rng.normal(), z = rng.normal();
        cloud.points[i] += o.noise_sigma * Vec3(x, y, z);
      }
    }
  }
  const auto n_out = static_cast<std::size_t>(std::llround(o.outlier_fraction * static_cast<double>(o.points)));
  if (n_out == 0) return;
  Vec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (const auto& p : cloud.points) {
    lo.minimize(p);
    hi.maximize(p);
  }
  const double grow = 0.1 * (hi - lo).norm();
  lo -= Vec3(grow);
  hi += Vec3(grow);
  // Partial Fisher-Yates: the first n_out entries of `index` are distinct random positions.
  std::vector<std::size_t> index(cloud.size());
  std::iota(index.begin(), index.end(), std::size_t{0});
  for (std::size_t i = 0; i < n_out; ++i) {
    const std::size_t j = i + static_cast<std::size_t>(rng.below(index.size() - i));
    std::swap(index[i], index[j]);
    const std::size_t k = index[i];
    cloud.points[k] = Vec3(rng.uniform(lo[0], hi[0]), rng.uniform(lo[1], hi[1]), rng.uniform(lo[2], hi[2]));
    cloud.normals[k] = rng.unit_vector();
  }
}

}  // namespace

PointCloud sample(const std::string& shape, const SampleOptions& o) {
  detail::validate(shape, o.shape);
  validate_sampling(o);
  if (shape == "neck") return sample_mesh(neck(12).mesh, o);
  const Surface surface = surface_of(shape, o.shape);
  std::vector<double> cumulative;
  double total = 0.0;
  for (const auto& p : surface) {
    total += (p.u1 - p.u0) * (p.v1 - p.v0) * p.dA_max;
    cumulative.push_back(total);
  }
  EF_CHECK(total > 0.0 && std::isfinite(total), "shape surface has no area");
  detail::Rng rng(o.seed);
  PointCloud cloud;
  cloud.points.reserve(o.points);
  cloud.normals.reserve(o.points);
  constexpr int kMaxAttempts = 1000000;
  for (std::size_t i = 0; i < o.points; ++i) {
    int attempts = 0;
    for (;;) {
      EF_CHECK(++attempts < kMaxAttempts, "rejection sampling does not accept: bad area bound");
      const double pick = rng.uniform() * total;
      const auto it = std::upper_bound(cumulative.begin(), cumulative.end(), pick);
      const Patch& patch = surface[static_cast<std::size_t>(
          std::min<std::ptrdiff_t>(it - cumulative.begin(), static_cast<std::ptrdiff_t>(surface.size()) - 1))];
      const double u = rng.uniform(patch.u0, patch.u1), v = rng.uniform(patch.v0, patch.v1);
      const double accept = rng.uniform() * patch.dA_max;
      const Eval e = patch.eval(u, v);
      EF_CHECK(e.dA <= patch.dA_max * (1.0 + 1e-9), "area element above its bound");
      if (accept < e.dA) {
        cloud.points.push_back(e.p);
        cloud.normals.push_back(e.n);
        break;
      }
    }
  }
  perturb(cloud, o, rng);
  return cloud;
}

PointCloud sample_mesh(const Mesh& mesh, const SampleOptions& o) {
  validate_sampling(o);
  std::vector<FaceHandle> faces;
  std::vector<double> cumulative;
  double total = 0.0;
  for (const auto f : mesh.faces()) {
    if (mesh.status(f).deleted()) continue;
    auto it = mesh.cfv_iter(f);
    const Vec3 a = mesh.point(*it), b = mesh.point(*++it), c = mesh.point(*++it);
    const double area = 0.5 * ((b - a) % (c - a)).norm();
    if (!(area > 0.0) || !std::isfinite(area)) continue;
    total += area;
    faces.push_back(f);
    cumulative.push_back(total);
  }
  if (faces.empty()) throw InvalidInput("shapes: sample_mesh: the mesh has no face of positive area");
  detail::Rng rng(o.seed);
  PointCloud cloud;
  cloud.points.reserve(o.points);
  cloud.normals.reserve(o.points);
  for (std::size_t i = 0; i < o.points; ++i) {
    const auto it = std::upper_bound(cumulative.begin(), cumulative.end(), rng.uniform() * total);
    const FaceHandle f =
        faces[static_cast<std::size_t>(std::min<std::ptrdiff_t>(it - cumulative.begin(),
                                                                static_cast<std::ptrdiff_t>(faces.size()) - 1))];
    auto fv = mesh.cfv_iter(f);
    const Vec3 a = mesh.point(*fv), b = mesh.point(*++fv), c = mesh.point(*++fv);
    const double r1 = std::sqrt(rng.uniform()), r2 = rng.uniform();
    cloud.points.push_back((1 - r1) * a + r1 * (1 - r2) * b + r1 * r2 * c);
    cloud.normals.push_back(((b - a) % (c - a)).normalized());
  }
  perturb(cloud, o, rng);
  return cloud;
}

}  // namespace edgefront::shapes
