// Shape catalogue of shapes/shapes.h: names, descriptions, option validation, and `make`,
// which maps a name, a resolution and the shape parameters onto the mesh generators.

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "edgefront/error.h"
#include "shapes/shapes.h"
#include "shapes_detail.h"

namespace edgefront::shapes {

namespace {

using detail::kPi;

struct Entry {
  const char* name;
  const char* description;
};

constexpr Entry kCatalogue[] = {
    {"grid", "planar grid in z = 0 (outline and variant from the shape parameters), 1 border"},
    {"grid-jittered", "square planar grid with seeded jittered interior vertices, 1 border"},
    {"grid-anisotropic", "square planar grid of 1:anisotropy cells, 1 border"},
    {"disk", "planar disk meshed by concentric rings, 1 border"},
    {"l-shape", "planar L-shaped grid (square minus a quadrant), 1 border"},
    {"icosphere", "sphere of radius R, subdivided icosahedron, closed"},
    {"uv-sphere", "sphere of radius R, latitude/longitude rings, closed"},
    {"hemisphere", "open upper hemisphere of radius R, 1 border"},
    {"nested-spheres", "hollow ball: outer sphere R outward, inner sphere inner_radius inward, 2 components"},
    {"bumpy-sphere", "star-shaped sphere with smooth bumps (amplitude, frequency), closed"},
    {"cylinder", "open cylinder of radius R and height length, 2 borders"},
    {"cone", "cone of base radius R (open) and height length, apex a vertex, 1 border"},
    {"torus", "torus of major radius R and tube radius minor_radius, genus 1"},
    {"double-torus", "two tori glued at x = 0 (a crease), genus 2, Euler characteristic -2"},
    {"mobius", "Moebius strip (radius R, width); the mesh is cut open along one seam"},
    {"ribbon", "strip of length and width with half a twist, 1 border"},
    {"vault-shell", "closed barrel vault shell: extrados R+thickness, intrados R, feet, end arches"},
    {"vault-sheet", "open barrel vault sheet: half cylinder of radius R and length, 1 border"},
    {"pointed-vault", "open pointed (gothic) arch vault sheet, span 2R, 1 border"},
    {"groin-vault", "open groin vault sheet: two crossing barrel vaults over a 2R square, 1 border"},
    {"thin-plate", "closed thin box [-R,R]^2 x [-thickness/2, thickness/2]"},
    {"hairpin", "closed thin wall bent into a U with a narrow gap between the arms"},
    {"landscape", "smooth seeded heightfield over [-R,R]^2, 1 border"},
    {"neck", "two blobs joined through a 3-vertex minimum pathway (mesh; samples from the mesh)"},
};

const Entry* find(const std::string& name) {
  for (const auto& e : kCatalogue)
    if (name == e.name) return &e;
  return nullptr;
}

/// Smallest subdivision level s with 5·2^s >= resolution, at most 8.
int level_for(int resolution) {
  int s = 0;
  while (s < 8 && (5 << s) < resolution) ++s;
  return s;
}

int at_least(double x, int lo) {
  const double r = std::round(x);
  return r >= lo ? static_cast<int>(std::min(r, 65536.0)) : lo;
}

}  // namespace

namespace detail {

void validate(const std::string& shape, const ShapeParams& p) {
  if (!find(shape)) {
    std::string names;
    for (const auto& e : kCatalogue) names += std::string(names.empty() ? "" : ", ") + e.name;
    throw InvalidInput("shapes: unknown shape '" + shape + "' (known: " + names + ")");
  }
  const std::string& s = shape;
  if (s == "neck") return;
  if (s == "torus" || s == "double-torus") return require_less(s, "minor_radius", p.minor_radius, "radius", p.radius);
  if (s == "nested-spheres") return require_less(s, "inner_radius", p.inner_radius, "radius", p.radius);
  require_positive(s, "radius", p.radius);
  if (s == "grid" || s == "grid-jittered" || s == "grid-anisotropic" || s == "disk" || s == "l-shape") {
    if (!std::isfinite(p.jitter) || p.jitter < 0.0 || !(p.jitter < 1.0 / 6.0))
      fail(s, "jitter must be in [0, 1/6), got " + num(p.jitter));
    if (!std::isfinite(p.anisotropy) || p.anisotropy < 1.0 || p.anisotropy > 1000.0)
      fail(s, "anisotropy must be in [1, 1000], got " + num(p.anisotropy));
    return;
  }
  if (s == "bumpy-sphere") {
    require_positive(s, "frequency", p.frequency);
    if (!std::isfinite(p.amplitude) || p.amplitude < 0.0 || !(p.amplitude < 1.0))
      fail(s, "amplitude must be in [0, 1), got " + num(p.amplitude));
    return;
  }
  if (s == "cylinder" || s == "cone" || s == "vault-sheet" || s == "pointed-vault")
    return require_positive(s, "length", p.length);
  if (s == "mobius") {
    require_positive(s, "width", p.width);
    return require_less(s, "width/2", p.width / 2.0, "radius", p.radius);
  }
  if (s == "ribbon") {
    require_positive(s, "length", p.length);
    return require_positive(s, "width", p.width);
  }
  if (s == "vault-shell") {
    require_positive(s, "length", p.length);
    return require_less(s, "thickness", p.thickness, "radius", p.radius);
  }
  if (s == "thin-plate") return require_less(s, "thickness", p.thickness, "radius", p.radius);
  if (s == "hairpin") {
    require_positive(s, "length", p.length);
    require_positive(s, "width", p.width);
    require_positive(s, "thickness", p.thickness);
    return require_positive(s, "gap", p.gap);
  }
  if (s == "landscape") {
    require_positive(s, "frequency", p.frequency);
    if (!std::isfinite(p.amplitude) || p.amplitude < 0.0)
      fail(s, "amplitude must be finite and >= 0, got " + num(p.amplitude));
    return;
  }
  // icosphere, uv-sphere, hemisphere, groin-vault: the radius only.
}

}  // namespace detail

std::vector<std::string> shape_names() {
  std::vector<std::string> names;
  for (const auto& e : kCatalogue) names.emplace_back(e.name);
  return names;
}

std::string describe(const std::string& shape) {
  const Entry* e = find(shape);
  if (!e) detail::validate(shape, {});  // throws the unknown-shape message
  return e->description;
}

Mesh make(const std::string& name, const MeshOptions& o) {
  detail::validate(name, o.shape);
  detail::require_count(name, "resolution", o.resolution, 3, 4096);
  const ShapeParams& p = o.shape;
  const int n = o.resolution;
  const double R = p.radius;
  if (name == "grid" || name == "grid-jittered" || name == "grid-anisotropic" || name == "disk" || name == "l-shape") {
    GridOptions g;
    g.cells = n;
    g.half_size = R;
    g.variant = p.grid_variant;
    g.outline = p.grid_outline;
    g.jitter = p.jitter;
    g.anisotropy = p.anisotropy;
    g.seed = p.surface_seed;
    if (name == "grid-jittered") g = GridOptions{n, R, GridVariant::jittered, GridOutline::square, p.jitter, p.anisotropy, p.surface_seed};
    if (name == "grid-anisotropic")
      g = GridOptions{n, R, GridVariant::anisotropic, GridOutline::square, p.jitter, p.anisotropy, p.surface_seed};
    if (name == "disk") g.outline = GridOutline::disk;
    if (name == "l-shape") g.outline = GridOutline::l_shape;
    if (name == "disk" || name == "l-shape") g.variant = GridVariant::regular;
    if (g.outline == GridOutline::l_shape && g.cells % 2 != 0) ++g.cells;
    return grid(g);
  }
  if (name == "icosphere") return icosphere(level_for(n), R);
  if (name == "uv-sphere") return uv_sphere(n, std::max(2, n / 2), R);
  if (name == "hemisphere") return hemisphere(n, std::max(1, n / 4), R);
  if (name == "nested-spheres") return nested_spheres(level_for(n), R, p.inner_radius);
  if (name == "bumpy-sphere") return bumpy_sphere(level_for(n), R, p.amplitude, p.frequency);
  if (name == "cylinder") return open_cylinder(n, at_least(n * p.length / (2 * kPi * R), 1), R, p.length);
  if (name == "cone")
    return cone(n, at_least(n * std::hypot(R, p.length) / (2 * kPi * R), 1), R, p.length);
  if (name == "torus") return torus(n, at_least(n * p.minor_radius / R, 3), R, p.minor_radius);
  if (name == "double-torus") return double_torus(2 * n, R, p.minor_radius);
  if (name == "mobius") return mobius_strip(n, at_least(n * p.width / (2 * kPi * R), 1), R, p.width);
  if (name == "ribbon") return half_twisted_ribbon(n, at_least(n * p.width / p.length, 1), p.length, p.width);
  if (name == "vault-shell") return vault_shell(n, R, p.thickness, p.length);
  if (name == "vault-sheet") return vault_sheet(n, R, p.length);
  if (name == "pointed-vault") return pointed_vault(n, R, p.length);
  if (name == "groin-vault") return groin_vault(n, R);
  if (name == "thin-plate") return thin_plate(n, R, p.thickness);
  if (name == "hairpin") return hairpin(n, p.length, p.width, p.thickness, p.gap);
  if (name == "landscape") return landscape(n, R, p.amplitude, p.frequency, p.surface_seed);
  if (name == "neck") {
    int around = 6;
    while (around < n && around < 3072) around *= 2;
    return neck(around).mesh;
  }
  detail::fail(name, "no mesh generator");  // unreachable: validate() knows every name
}

}  // namespace edgefront::shapes
