// Tests of shapes/shapes.h: topology and orientation of every mesh, points on the analytic
// surface with the analytic normals, area uniformity, determinism, option checking, the neck's
// minimum pathway and the Möbius strip. The analytic surfaces are restated here independently
// of the library (as implicit functions or parametric inversions).

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <queue>
#include <set>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "edgefront/error.h"
#include "edgefront/mesh.h"
#include "edgefront/mesh_io.h"
#include "edgefront/point_cloud.h"
#include "edgefront/point_cloud_io.h"
#include "shapes/shapes.h"

namespace {

namespace sh = edgefront::shapes;
using edgefront::InvalidInput;
using edgefront::Mesh;
using edgefront::PointCloud;
using edgefront::Vec3;
using edgefront::VertexHandle;

constexpr double kPi = 3.14159265358979323846;

// ---- topology, computed here from the half-edge structure ----------------------------------

struct Topology {
  long long V = 0, E = 0, F = 0;
  long long chi() const { return V - E + F; }
  int border_loops = 0;
  int components = 0;
  bool manifold = true;
  std::string why;
  double signed_volume = 0.0;
};

Topology topology(const Mesh& m) {
  Topology t;
  t.V = static_cast<long long>(m.n_vertices());
  t.E = static_cast<long long>(m.n_edges());
  t.F = static_cast<long long>(m.n_faces());
  // Vertex manifoldness: at most one outgoing border half-edge, and the faces met by circulating
  // are all the faces that reference the vertex.
  std::vector<int> face_refs(m.n_vertices(), 0);
  for (const auto f : m.faces())
    for (const auto v : m.fv_range(f)) ++face_refs[static_cast<std::size_t>(v.idx())];
  for (const auto v : m.vertices()) {
    int border_out = 0, fans = 0;
    for (const auto h : m.voh_range(v)) {
      if (m.is_boundary(h)) ++border_out;
      if (!m.is_boundary(h)) ++fans;
    }
    if (border_out > 1 || fans != face_refs[static_cast<std::size_t>(v.idx())]) {
      t.manifold = false;
      t.why = "vertex " + std::to_string(v.idx()) + " is not manifold";
    }
    if (fans == 0) {
      t.manifold = false;
      t.why = "isolated vertex " + std::to_string(v.idx());
    }
  }
  // Border loops by walking border half-edges.
  std::vector<char> seen(m.n_halfedges(), 0);
  for (const auto h : m.halfedges()) {
    if (!m.is_boundary(h) || seen[static_cast<std::size_t>(h.idx())]) continue;
    ++t.border_loops;
    auto g = h;
    int guard = 0;
    do {
      seen[static_cast<std::size_t>(g.idx())] = 1;
      g = m.next_halfedge_handle(g);
    } while (g != h && ++guard < 10000000);
  }
  // Components by breadth-first search over edges.
  std::vector<int> comp(m.n_vertices(), -1);
  for (const auto s : m.vertices()) {
    if (comp[static_cast<std::size_t>(s.idx())] >= 0) continue;
    std::queue<VertexHandle> q;
    q.push(s);
    comp[static_cast<std::size_t>(s.idx())] = t.components;
    while (!q.empty()) {
      const auto v = q.front();
      q.pop();
      for (const auto w : m.vv_range(v))
        if (comp[static_cast<std::size_t>(w.idx())] < 0) {
          comp[static_cast<std::size_t>(w.idx())] = t.components;
          q.push(w);
        }
    }
    ++t.components;
  }
  for (const auto f : m.faces()) {
    std::vector<Vec3> p;
    for (const auto v : m.fv_range(f)) p.push_back(m.point(v));
    t.signed_volume += (p[0] | (p[1] % p[2])) / 6.0;
  }
  return t;
}

// ---- the analytic surfaces, restated -------------------------------------------------------

/// One smooth piece of a surface: F ~ signed distance (zero on the surface), the piece's extent,
/// and the side of grad F the normal is on. When `param_normal` is set, F is an unsigned
/// distance and the normal comes from `param_normal` instead (up to sign if `either_sign`).
struct Piece {
  std::function<double(const Vec3&)> F;
  std::function<bool(const Vec3&)> domain;
  double sign = 1.0;
  std::function<Vec3(const Vec3&)> param_normal = nullptr;
  bool either_sign = false;
};

constexpr double kEps = 1e-9;

Vec3 gradient(const std::function<double(const Vec3&)>& F, const Vec3& p) {
  const double h = 1e-6;
  Vec3 g;
  for (int i = 0; i < 3; ++i) {
    Vec3 a = p, b = p;
    a[i] += h;
    b[i] -= h;
    g[i] = (F(a) - F(b)) / (2 * h);
  }
  return g;
}

bool all(const Vec3&) { return true; }

std::vector<Piece> analytic(const std::string& name, const sh::ShapeParams& sp) {
  const double R = sp.radius, t = sp.thickness, L = sp.length, w = sp.width;
  auto plane_z = [](double z0, double sign, std::function<bool(const Vec3&)> dom) {
    return Piece{[z0](const Vec3& p) { return p[2] - z0; }, std::move(dom), sign};
  };
  if (name == "grid" || name == "grid-jittered" || name == "grid-anisotropic")
    return {plane_z(0, 1, [R](const Vec3& p) { return std::abs(p[0]) <= R + kEps && std::abs(p[1]) <= R + kEps; })};
  if (name == "disk")
    return {plane_z(0, 1, [R](const Vec3& p) { return std::hypot(p[0], p[1]) <= R + kEps; })};
  if (name == "l-shape")
    return {plane_z(0, 1, [R](const Vec3& p) {
      return std::abs(p[0]) <= R + kEps && std::abs(p[1]) <= R + kEps && !(p[0] > kEps && p[1] > kEps);
    })};
  auto sphere = [](double r, double sign, std::function<bool(const Vec3&)> dom) {
    return Piece{[r](const Vec3& p) { return p.norm() - r; }, std::move(dom), sign};
  };
  if (name == "icosphere" || name == "uv-sphere") return {sphere(R, 1, all)};
  if (name == "hemisphere") return {sphere(R, 1, [](const Vec3& p) { return p[2] >= -kEps; })};
  if (name == "nested-spheres") return {sphere(R, 1, all), sphere(sp.inner_radius, -1, all)};
  if (name == "bumpy-sphere") {
    const double a = sp.amplitude, f = sp.frequency;
    return {Piece{[=](const Vec3& p) {
                    const Vec3 u = p / p.norm();
                    return p.norm() - R * (1 + a * std::sin(f * u[0]) * std::sin(f * u[1]) * std::sin(f * u[2]));
                  },
                  all, 1}};
  }
  if (name == "cylinder")
    return {Piece{[R](const Vec3& p) { return std::hypot(p[0], p[1]) - R; },
                  [L](const Vec3& p) { return p[2] >= -kEps && p[2] <= L + kEps; }, 1}};
  if (name == "cone") {
    const double slant = std::hypot(R, L);
    return {Piece{[=](const Vec3& p) { return (std::hypot(p[0], p[1]) - R * (1 - p[2] / L)) * L / slant; },
                  [L](const Vec3& p) { return p[2] >= -kEps && p[2] <= L + kEps; }, 1}};
  }
  auto torus_at = [](double cx, double RR, double r, std::function<bool(const Vec3&)> dom) {
    return Piece{[=](const Vec3& p) { return std::hypot(std::hypot(p[0] - cx, p[1]) - RR, p[2]) - r; }, std::move(dom),
                 1};
  };
  if (name == "torus") return {torus_at(0, R, sp.minor_radius, all)};
  if (name == "double-torus")
    return {torus_at(-R, R, sp.minor_radius, [](const Vec3& p) { return p[0] <= kEps; }),
            torus_at(R, R, sp.minor_radius, [](const Vec3& p) { return p[0] >= -kEps; })};
  if (name == "mobius") {
    auto P = [=](double u, double v) {
      const double rho = R + v * std::cos(u / 2);
      return Vec3(rho * std::cos(u), rho * std::sin(u), v * std::sin(u / 2));
    };
    auto inv = [=](const Vec3& p) {
      const double u = std::atan2(p[1], p[0]);
      const double v = (std::hypot(p[0], p[1]) - R) * std::cos(u / 2) + p[2] * std::sin(u / 2);
      return std::array<double, 2>{u, v};
    };
    Piece piece;
    piece.F = [=](const Vec3& p) {
      const auto uv = inv(p);
      return (p - P(uv[0], uv[1])).norm();
    };
    piece.domain = [=](const Vec3& p) { return std::abs(inv(p)[1]) <= w / 2 + kEps; };
    piece.param_normal = [=](const Vec3& p) {
      const auto uv = inv(p);
      const double h = 1e-6;
      const Vec3 du = (P(uv[0] + h, uv[1]) - P(uv[0] - h, uv[1])) / (2 * h);
      const Vec3 dv = (P(uv[0], uv[1] + h) - P(uv[0], uv[1] - h)) / (2 * h);
      return (du % dv).normalized();
    };
    piece.either_sign = true;
    return {piece};
  }
  if (name == "ribbon") {
    const double k = kPi / L;
    auto P = [=](double u, double v) { return Vec3(u, v * std::cos(k * u), v * std::sin(k * u)); };
    auto inv = [=](const Vec3& p) {
      return std::array<double, 2>{p[0], p[1] * std::cos(k * p[0]) + p[2] * std::sin(k * p[0])};
    };
    Piece piece;
    piece.F = [=](const Vec3& p) {
      const auto uv = inv(p);
      return (p - P(uv[0], uv[1])).norm();
    };
    piece.domain = [=](const Vec3& p) {
      const auto uv = inv(p);
      return uv[0] >= -kEps && uv[0] <= L + kEps && std::abs(uv[1]) <= w / 2 + kEps;
    };
    piece.param_normal = [=](const Vec3& p) {
      const auto uv = inv(p);
      const double h = 1e-6;
      const Vec3 du = (P(uv[0] + h, uv[1]) - P(uv[0] - h, uv[1])) / (2 * h);
      const Vec3 dv = (P(uv[0], uv[1] + h) - P(uv[0], uv[1] - h)) / (2 * h);
      return (du % dv).normalized();
    };
    return {piece};
  }
  auto y_cyl = [L](double cx, double r, double sign, std::function<bool(const Vec3&)> dom) {
    return Piece{[=](const Vec3& p) { return std::hypot(p[0] - cx, p[2]) - r; },
                 [=](const Vec3& p) { return p[1] >= -kEps && p[1] <= L + kEps && p[2] >= -kEps && dom(p); }, sign};
  };
  if (name == "vault-shell") {
    const double Re = R + t;
    auto in_ring = [=](const Vec3& p) {
      const double r = std::hypot(p[0], p[2]);
      return r >= R - kEps && r <= Re + kEps && p[2] >= -kEps;
    };
    auto foot = [=](const Vec3& p) {
      return std::abs(p[0]) >= R - kEps && std::abs(p[0]) <= Re + kEps && p[1] >= -kEps && p[1] <= L + kEps;
    };
    return {y_cyl(0, Re, 1, all), y_cyl(0, R, -1, all), plane_z(0, -1, foot),
            Piece{[](const Vec3& p) { return p[1]; }, in_ring, -1},
            Piece{[L](const Vec3& p) { return p[1] - L; }, in_ring, 1}};
  }
  if (name == "vault-sheet") return {y_cyl(0, R, 1, all)};
  if (name == "pointed-vault")
    return {y_cyl(-R, 2 * R, 1, [](const Vec3& p) { return p[0] >= -kEps; }),
            y_cyl(R, 2 * R, 1, [](const Vec3& p) { return p[0] <= kEps; })};
  if (name == "groin-vault")
    return {Piece{[R](const Vec3& p) { return std::hypot(p[1], p[2]) - R; },
                  [R](const Vec3& p) {
                    return std::abs(p[1]) <= std::abs(p[0]) + kEps && std::abs(p[0]) <= R + kEps && p[2] >= -kEps;
                  },
                  1},
            Piece{[R](const Vec3& p) { return std::hypot(p[0], p[2]) - R; },
                  [R](const Vec3& p) {
                    return std::abs(p[0]) <= std::abs(p[1]) + kEps && std::abs(p[1]) <= R + kEps && p[2] >= -kEps;
                  },
                  1}};
  if (name == "thin-plate") {
    const double a = R, h = t / 2;
    auto in_box = [=](const Vec3& p) {
      return std::abs(p[0]) <= a + kEps && std::abs(p[1]) <= a + kEps && std::abs(p[2]) <= h + kEps;
    };
    std::vector<Piece> pieces;
    for (int axis = 0; axis < 3; ++axis)
      for (const double s : {1.0, -1.0}) {
        const double off = axis == 2 ? h : a;
        pieces.push_back(Piece{[=](const Vec3& p) { return p[axis] - s * off; }, in_box, s});
      }
    return pieces;
  }
  if (name == "hairpin") {
    const double c = (sp.gap + t) / 2, W = w;
    auto in_y = [=](const Vec3& p) { return std::abs(p[1]) <= W / 2 + kEps; };
    auto arm = [=](const Vec3& p) { return p[0] >= -kEps && p[0] <= L + kEps && in_y(p); };
    auto bend = [=](const Vec3& p) { return p[0] <= kEps && in_y(p); };
    auto wall = [=](const Vec3& p) {  // inside the wall's cross-section, any y
      const double r = p[0] >= 0 ? std::abs(p[2]) : std::hypot(p[0], p[2]);
      return r >= c - t / 2 - kEps && r <= c + t / 2 + kEps && p[0] <= L + kEps;
    };
    auto zplane = [=](double z0, double sign) {
      return Piece{[=](const Vec3& p) { return p[2] - z0; }, arm, sign};
    };
    return {zplane(c + t / 2, 1),
            zplane(c - t / 2, -1),
            zplane(-c - t / 2, -1),
            zplane(-c + t / 2, 1),
            Piece{[=](const Vec3& p) { return std::hypot(p[0], p[2]) - (c + t / 2); }, bend, 1},
            Piece{[=](const Vec3& p) { return std::hypot(p[0], p[2]) - (c - t / 2); }, bend, -1},
            Piece{[=](const Vec3& p) { return p[1] - W / 2; }, wall, 1},
            Piece{[=](const Vec3& p) { return p[1] + W / 2; }, wall, -1},
            Piece{[=](const Vec3& p) { return p[0] - L; },
                  [=](const Vec3& p) {
                    return in_y(p) && std::abs(p[2]) >= c - t / 2 - kEps && std::abs(p[2]) <= c + t / 2 + kEps;
                  },
                  1}};
  }
  return {};  // landscape, neck: no closed form here
}

struct Match {
  double distance = std::numeric_limits<double>::infinity();
  bool normal_ok = false;
};

/// Distance of p to the nearest piece whose domain holds p, and whether n is that piece's
/// normal (any piece within 1e-9 whose normal agrees counts: creases).
Match match(const std::vector<Piece>& pieces, const Vec3& p, const Vec3& n, double cos_tol = 1e-6) {
  Match m;
  for (const auto& piece : pieces) {
    if (!piece.domain(p)) continue;
    const double d = std::abs(piece.F(p));
    m.distance = std::min(m.distance, d);
    if (d > 1e-9) continue;
    Vec3 ref = piece.param_normal ? piece.param_normal(p) : piece.sign * gradient(piece.F, p).normalized();
    double dot = n | ref;
    if (piece.either_sign) dot = std::abs(dot);
    if (dot >= 1 - cos_tol) m.normal_ok = true;
  }
  return m;
}

struct Expect {
  std::string name;
  long long chi;
  int borders;
  int components;
  bool closed;
};

const std::vector<Expect>& expectations() {
  static const std::vector<Expect> e = {
      {"grid", 1, 1, 1, false},          {"grid-jittered", 1, 1, 1, false}, {"grid-anisotropic", 1, 1, 1, false},
      {"disk", 1, 1, 1, false},          {"l-shape", 1, 1, 1, false},       {"icosphere", 2, 0, 1, true},
      {"uv-sphere", 2, 0, 1, true},      {"hemisphere", 1, 1, 1, false},    {"nested-spheres", 4, 0, 2, true},
      {"bumpy-sphere", 2, 0, 1, true},   {"cylinder", 0, 2, 1, false},      {"cone", 1, 1, 1, false},
      {"torus", 0, 0, 1, true},          {"double-torus", -2, 0, 1, true},  {"mobius", 1, 1, 1, false},
      {"ribbon", 1, 1, 1, false},        {"vault-shell", 2, 0, 1, true},    {"vault-sheet", 1, 1, 1, false},
      {"pointed-vault", 1, 1, 1, false}, {"groin-vault", 1, 1, 1, false},   {"thin-plate", 2, 0, 1, true},
      {"hairpin", 2, 0, 1, true},        {"landscape", 1, 1, 1, false},     {"neck", 2, 0, 1, true},
  };
  return e;
}

Mesh make(const std::string& name, int resolution) {
  sh::MeshOptions o;
  o.resolution = resolution;
  if (name == "grid-anisotropic") o.resolution = 4;  // 80 x 4 cells
  return sh::make(name, o);
}

PointCloud sample(const std::string& name, std::size_t n, std::uint64_t seed = 1) {
  sh::SampleOptions o;
  o.points = n;
  o.seed = seed;
  return sh::sample(name, o);
}

// ---- tests ----------------------------------------------------------------------------------

TEST(ShapesCatalogue, NamesAreTheTestedOnesAndDescribed) {
  std::vector<std::string> expected;
  for (const auto& e : expectations()) expected.push_back(e.name);
  EXPECT_EQ(sh::shape_names(), expected);
  for (const auto& n : sh::shape_names()) EXPECT_FALSE(sh::describe(n).empty()) << n;
  EXPECT_THROW(sh::describe("teapot"), InvalidInput);
}

TEST(ShapesMesh, EveryShapeIsManifoldWithTheRightTopology) {
  for (const auto& e : expectations()) {
    for (const int res : {5, 12}) {
      SCOPED_TRACE(e.name + " at resolution " + std::to_string(res));
      const Mesh m = make(e.name, res);
      ASSERT_GT(m.n_faces(), 0u);
      const Topology t = topology(m);
      EXPECT_TRUE(t.manifold) << t.why;
      EXPECT_EQ(t.chi(), e.chi);
      EXPECT_EQ(t.border_loops, e.borders);
      EXPECT_EQ(t.components, e.components);
      if (e.closed) {
        EXPECT_GT(t.signed_volume, 0.0) << "closed shapes are oriented outward";
      }
    }
  }
}

TEST(ShapesMesh, VerticesOnTheSurfaceAndFacesOrientedLikeTheAnalyticNormal) {
  const sh::ShapeParams sp;
  for (const auto& e : expectations()) {
    const auto pieces = analytic(e.name, sp);
    if (pieces.empty()) continue;
    SCOPED_TRACE(e.name);
    const Mesh m = make(e.name, 16);
    double worst = 0.0;
    for (const auto v : m.vertices()) worst = std::max(worst, match(pieces, m.point(v), Vec3(0, 0, 1)).distance);
    EXPECT_LT(worst, 1e-9);
    if (e.name == "mobius") continue;  // not orientable: no global side to compare with
    int wrong = 0;
    for (const auto f : m.faces()) {
      std::vector<Vec3> p;
      for (const auto v : m.fv_range(f)) p.push_back(m.point(v));
      const Vec3 n = ((p[1] - p[0]) % (p[2] - p[0])).normalized();
      // Compare with the normal of the closest piece at the centroid (a chord off the surface).
      const Vec3 c = (p[0] + p[1] + p[2]) / 3.0;
      double best = std::numeric_limits<double>::infinity();
      Vec3 ref(0, 0, 0);
      for (const auto& piece : pieces) {
        if (!piece.domain(c)) continue;
        const double d = std::abs(piece.F(c));
        if (d < best) {
          best = d;
          ref = piece.param_normal ? piece.param_normal(c) : piece.sign * gradient(piece.F, c).normalized();
        }
      }
      if (!((n | ref) > 0.5)) ++wrong;
    }
    EXPECT_EQ(wrong, 0);
  }
}

TEST(ShapesMesh, LandscapeAndNeckFacesPointUpOrOut) {
  const Mesh land = make("landscape", 24);
  for (const auto f : land.faces()) EXPECT_GT(land.normal(f)[2], 0.0);
  const auto neck = sh::neck(24);
  EXPECT_GT(topology(neck.mesh).signed_volume, 0.0);
}

TEST(ShapesMesh, SameOptionsGiveTheSameMesh) {
  for (const auto& name : sh::shape_names()) {
    const Mesh a = make(name, 9), b = make(name, 9);
    ASSERT_EQ(a.n_vertices(), b.n_vertices()) << name;
    ASSERT_EQ(a.n_faces(), b.n_faces()) << name;
    for (const auto v : a.vertices()) ASSERT_EQ(a.point(v), b.point(VertexHandle(v.idx()))) << name;
    for (const auto f : a.faces()) {
      auto ia = a.cfv_iter(f);
      auto ib = b.cfv_iter(f);
      for (int k = 0; k < 3; ++k, ++ia, ++ib) ASSERT_EQ(ia->idx(), ib->idx()) << name;
    }
  }
}

TEST(ShapesMesh, IcosphereCountsAndEdgeLengthsShrink) {
  double previous = 10;
  for (int s = 0; s <= 3; ++s) {
    const Mesh m = sh::icosphere(s, 2.0);
    EXPECT_EQ(m.n_faces(), 20u << (2 * s));
    EXPECT_EQ(m.n_vertices(), 10u * (1u << (2 * s)) + 2u);
    double longest = 0;
    for (const auto e : m.edges()) longest = std::max(longest, m.calc_edge_length(e));
    EXPECT_LT(longest, previous);
    previous = longest;
  }
}

TEST(ShapesMesh, GridVariants) {
  sh::GridOptions g;
  g.cells = 6;
  g.half_size = 2.0;
  // Every planar grid covers its outline's area exactly (polygonal disk: slightly less).
  auto area = [](const Mesh& m) {
    double a = 0;
    for (const auto f : m.faces()) {
      std::vector<Vec3> p;
      for (const auto v : m.fv_range(f)) p.push_back(m.point(v));
      const Vec3 n = (p[1] - p[0]) % (p[2] - p[0]);
      EXPECT_GT(n[2], 0.0) << "face flipped";
      a += 0.5 * n[2];
    }
    return a;
  };
  EXPECT_NEAR(area(sh::grid(g)), 16.0, 1e-12);
  g.outline = sh::GridOutline::l_shape;
  EXPECT_NEAR(area(sh::grid(g)), 12.0, 1e-12);
  g.variant = sh::GridVariant::jittered;
  EXPECT_NEAR(area(sh::grid(g)), 12.0, 1e-12);
  g.outline = sh::GridOutline::disk;
  const double disk = area(sh::grid(g));
  EXPECT_LT(disk, kPi * 4);
  EXPECT_GT(disk, 0.97 * kPi * 4);
  // Jitter: deterministic per seed, different across seeds, border fixed.
  g.outline = sh::GridOutline::square;
  const Mesh j1 = sh::grid(g), j1b = sh::grid(g);
  g.seed = 2;
  const Mesh j2 = sh::grid(g);
  int moved = 0;
  for (const auto v : j1.vertices()) {
    EXPECT_EQ(j1.point(v), j1b.point(v));
    if (j1.point(v) != j2.point(v)) ++moved;
    if (j1.is_boundary(v)) {
      EXPECT_EQ(j1.point(v), j2.point(v));
    }
  }
  EXPECT_EQ(moved, 25);  // the 5 x 5 interior vertices
  // Anisotropic: cells 20 times longer in y than in x.
  g.variant = sh::GridVariant::anisotropic;
  const Mesh an = sh::grid(g);
  double shortest = 1e9, longest = 0;
  for (const auto e : an.edges()) {
    const double l = an.calc_edge_length(e);
    shortest = std::min(shortest, l);
    longest = std::max(longest, l);
  }
  EXPECT_EQ(an.n_vertices(), 121u * 7u);
  EXPECT_NEAR(longest / shortest, std::hypot(20.0, 1.0), 1e-9);  // the cell diagonal
}

TEST(ShapesSample, PointsOnTheAnalyticSurfaceWithItsNormals) {
  const sh::ShapeParams sp;
  for (const auto& name : sh::shape_names()) {
    const auto pieces = analytic(name, sp);
    if (pieces.empty()) continue;
    SCOPED_TRACE(name);
    const PointCloud pc = sample(name, 1500, 3);
    ASSERT_EQ(pc.size(), 1500u);
    ASSERT_TRUE(pc.has_normals());
    int off = 0, bad_normal = 0;
    for (std::size_t i = 0; i < pc.size(); ++i) {
      EXPECT_NEAR(pc.normals[i].norm(), 1.0, 1e-12);
      const Match m = match(pieces, pc.points[i], pc.normals[i]);
      if (!(m.distance < 1e-9)) ++off;
      if (!m.normal_ok) ++bad_normal;
    }
    EXPECT_EQ(off, 0);
    EXPECT_EQ(bad_normal, 0);
  }
}

TEST(ShapesSample, LandscapeAndNeckSamplesLieOnTheirMeshes) {
  // The landscape's closed form is private: compare with a fine mesh (chord error ~1e-5).
  sh::MeshOptions mo;
  mo.resolution = 100;
  const Mesh land = sh::make("landscape", mo);
  const PointCloud pc = sample("landscape", 300);
  const int n = 100;
  for (std::size_t i = 0; i < pc.size(); ++i) {
    const Vec3 p = pc.points[i];
    // Cell of the regular grid holding (x, y): the mesh vertex (i, j) is index i*(n+1)+j.
    const double gx = (p[0] + 1) / 2 * n, gy = (p[1] + 1) / 2 * n;
    const int ci = std::min(n - 1, static_cast<int>(gx)), cj = std::min(n - 1, static_cast<int>(gy));
    const double fx = gx - ci, fy = gy - cj;
    auto z = [&](int xi, int yj) { return land.point(VertexHandle(xi * (n + 1) + yj))[2]; };
    const double bilinear = (1 - fx) * (1 - fy) * z(ci, cj) + fx * (1 - fy) * z(ci + 1, cj) +
                            (1 - fx) * fy * z(ci, cj + 1) + fx * fy * z(ci + 1, cj + 1);
    EXPECT_NEAR(p[2], bilinear, 1e-3);
    EXPECT_GT(pc.normals[i][2], 0.0);
  }
  // Neck: every sample inside one of the mesh's triangles, with its normal.
  const Mesh neck = sh::neck(12).mesh;
  const PointCloud nk = sample("neck", 400);
  for (std::size_t i = 0; i < nk.size(); ++i) {
    bool found = false;
    for (const auto f : neck.faces()) {
      std::vector<Vec3> q;
      for (const auto v : neck.fv_range(f)) q.push_back(neck.point(v));
      const Vec3 nn = ((q[1] - q[0]) % (q[2] - q[0])).normalized();
      if (std::abs((nk.points[i] - q[0]) | nn) > 1e-9) continue;
      bool inside = true;
      for (int k = 0; k < 3; ++k)
        if ((((q[(k + 1) % 3] - q[k]) % (nk.points[i] - q[k])) | nn) < -1e-9) inside = false;
      if (inside && (nn | nk.normals[i]) > 1 - 1e-9) found = true;
    }
    EXPECT_TRUE(found) << i;
  }
}

/// Area-weighted first and second moments of a mesh (exact for the piecewise linear surface).
std::array<double, 6> mesh_moments(const Mesh& m) {
  std::array<double, 6> s{};
  double total = 0;
  for (const auto f : m.faces()) {
    std::vector<Vec3> p;
    for (const auto v : m.fv_range(f)) p.push_back(m.point(v));
    const double a = 0.5 * ((p[1] - p[0]) % (p[2] - p[0])).norm();
    total += a;
    for (int k = 0; k < 3; ++k) {
      s[static_cast<std::size_t>(k)] += a * (p[0][k] + p[1][k] + p[2][k]) / 3;
      s[static_cast<std::size_t>(3 + k)] += a / 6 *
                                            (p[0][k] * p[0][k] + p[1][k] * p[1][k] + p[2][k] * p[2][k] +
                                             p[0][k] * p[1][k] + p[1][k] * p[2][k] + p[2][k] * p[0][k]);
    }
  }
  for (auto& x : s) x /= total;
  return s;
}

TEST(ShapesSample, MomentsMatchTheMeshAreaDistribution) {
  // Uniform-by-area samples have the mean and second moments of the surface's area measure.
  for (const auto& name : sh::shape_names()) {
    SCOPED_TRACE(name);
    const Mesh m = name == "neck" ? sh::neck(12).mesh : make(name, name == "grid-anisotropic" ? 4 : 48);
    const auto expected = mesh_moments(m);
    const PointCloud pc = sample(name, 10000, 5);
    std::array<double, 6> got{};
    for (const auto& p : pc.points)
      for (int k = 0; k < 3; ++k) {
        got[static_cast<std::size_t>(k)] += p[k] / static_cast<double>(pc.size());
        got[static_cast<std::size_t>(3 + k)] += p[k] * p[k] / static_cast<double>(pc.size());
      }
    for (std::size_t k = 0; k < 6; ++k) EXPECT_NEAR(got[k], expected[k], 0.03) << "moment " << k;
  }
}

/// |fraction - p| within 3 binomial standard deviations.
void expect_fraction(std::size_t hits, std::size_t n, double p, const std::string& what) {
  const double f = static_cast<double>(hits) / static_cast<double>(n);
  const double sigma = std::sqrt(p * (1 - p) / static_cast<double>(n));
  EXPECT_NEAR(f, p, 3 * sigma) << what;
}

TEST(ShapesSample, AreaUniformOnKnownFractions) {
  const std::size_t n = 20000;
  const sh::ShapeParams sp;
  auto count = [](const PointCloud& pc, const std::function<bool(const Vec3&)>& pred) {
    return static_cast<std::size_t>(std::count_if(pc.points.begin(), pc.points.end(), pred));
  };
  expect_fraction(count(sample("cylinder", n), [&](const Vec3& p) { return p[2] < sp.length / 2; }), n, 0.5,
                  "cylinder lower half");
  expect_fraction(count(sample("icosphere", n), [](const Vec3& p) { return p[2] > 0.5; }), n, 0.25,
                  "sphere cap above z = R/2 (Archimedes)");
  expect_fraction(count(sample("hemisphere", n), [](const Vec3& p) { return p[2] < 0.5; }), n, 0.5,
                  "hemisphere zone below R/2");
  expect_fraction(count(sample("cone", n), [&](const Vec3& p) { return p[2] < sp.length / 2; }), n, 0.75,
                  "cone lower half");
  expect_fraction(count(sample("torus", n), [&](const Vec3& p) { return std::hypot(p[0], p[1]) > sp.radius; }), n,
                  0.5 + sp.minor_radius / (kPi * sp.radius), "torus outer half");
  expect_fraction(count(sample("disk", n), [](const Vec3& p) { return std::hypot(p[0], p[1]) < 0.5; }), n, 0.25,
                  "disk inner half radius");
  expect_fraction(count(sample("l-shape", n), [](const Vec3& p) { return p[0] < 0 && p[1] < 0; }), n, 1.0 / 3,
                  "L-shape quadrant");
  const double ri = sp.inner_radius;
  expect_fraction(count(sample("nested-spheres", n), [&](const Vec3& p) { return p.norm() < 0.75; }), n,
                  ri * ri / (1 + ri * ri), "inner sphere share");
  // Vault shell: every part gets its share of the area.
  const double R = sp.radius, t = sp.thickness, L = sp.length, Re = R + t;
  const double ext = kPi * Re * L, intr = kPi * R * L, feet = 2 * t * L, caps = kPi * (Re * Re - R * R);
  const double total = ext + intr + feet + caps;
  const PointCloud vs = sample("vault-shell", n);
  const double mid = R + t / 2;
  expect_fraction(count(vs, [&](const Vec3& p) { return std::abs(std::hypot(p[0], p[2]) - Re) < 1e-9; }), n,
                  ext / total, "extrados");
  expect_fraction(count(vs, [&](const Vec3& p) { return std::abs(std::hypot(p[0], p[2]) - R) < 1e-9; }), n,
                  intr / total, "intrados");
  expect_fraction(count(vs, [&](const Vec3& p) { return p[2] == 0.0; }), n, feet / total, "feet");
  expect_fraction(count(vs,
                        [&](const Vec3& p) {
                          return (p[1] == 0.0 || p[1] == L) && std::abs(std::hypot(p[0], p[2]) - mid) < t / 2 - 1e-9;
                        }),
                  n, caps / total, "end arches");
  // Bumpy sphere: compare the share of the upper half with the fine mesh's.
  const Mesh bumpy = make("bumpy-sphere", 160);
  double up = 0, all_area = 0;
  for (const auto f : bumpy.faces()) {
    const double a = bumpy.calc_face_area(f);
    all_area += a;
    if (bumpy.calc_face_centroid(f)[2] > 0.3) up += a;
  }
  expect_fraction(count(sample("bumpy-sphere", n), [](const Vec3& p) { return p[2] > 0.3; }), n, up / all_area,
                  "bumpy sphere above z = 0.3");
}

TEST(ShapesSample, SameSeedSameOutputOtherSeedDiffers) {
  for (const auto& name : sh::shape_names()) {
    sh::SampleOptions o;
    o.points = 200;
    o.seed = 11;
    o.noise_sigma = 0.01;
    o.outlier_fraction = 0.05;
    const PointCloud a = sh::sample(name, o), b = sh::sample(name, o);
    o.seed = 12;
    const PointCloud c = sh::sample(name, o);
    EXPECT_EQ(a.points, b.points) << name;
    EXPECT_EQ(a.normals, b.normals) << name;
    EXPECT_NE(a.points, c.points) << name;
  }
}

TEST(ShapesSample, NoiseAlongTheNormalOrIsotropic) {
  sh::SampleOptions o;
  o.points = 5000;
  o.seed = 4;
  const PointCloud clean = sh::sample("icosphere", o);
  o.noise_sigma = 0.01;
  const PointCloud along = sh::sample("icosphere", o);
  o.noise = sh::NoiseKind::isotropic;
  const PointCloud iso = sh::sample("icosphere", o);
  double s_along = 0, s_radial = 0, s_tangent = 0;
  for (std::size_t i = 0; i < clean.size(); ++i) {
    const Vec3 d = along.points[i] - clean.points[i];
    EXPECT_LT((d % clean.normals[i]).norm(), 1e-12) << "displacement along the normal";
    EXPECT_EQ(along.normals[i], clean.normals[i]) << "normals are not perturbed";
    s_along += d.sqrnorm();
    const Vec3 e = iso.points[i] - clean.points[i];
    s_radial += (e | clean.normals[i]) * (e | clean.normals[i]);
    s_tangent += (e % clean.normals[i]).sqrnorm();
  }
  const double n = static_cast<double>(clean.size());
  EXPECT_NEAR(std::sqrt(s_along / n), 0.01, 0.0005);
  EXPECT_NEAR(std::sqrt(s_radial / n), 0.01, 0.0005);
  EXPECT_NEAR(std::sqrt(s_tangent / n / 2), 0.01, 0.0005);
}

TEST(ShapesSample, OutliersAreCountedAndSpread) {
  sh::SampleOptions o;
  o.points = 4000;
  o.outlier_fraction = 0.1;
  const PointCloud pc = sh::sample("torus", o);
  const auto pieces = analytic("torus", o.shape);
  std::size_t off = 0, off_first_half = 0;
  for (std::size_t i = 0; i < pc.size(); ++i) {
    EXPECT_NEAR(pc.normals[i].norm(), 1.0, 1e-12);
    if (match(pieces, pc.points[i], pc.normals[i]).distance > 1e-9) {
      ++off;
      if (i < pc.size() / 2) ++off_first_half;
    }
  }
  EXPECT_EQ(off, 400u);  // an outlier exactly on the torus has probability 0
  EXPECT_GT(off_first_half, 150u);
  EXPECT_LT(off_first_half, 250u);
  o.outlier_fraction = 1.0;
  EXPECT_NO_THROW(sh::sample("vault-sheet", o));
}

TEST(ShapesSample, SampleMeshIsAreaUniform) {
  sh::GridOptions g;
  g.cells = 8;
  g.variant = sh::GridVariant::jittered;
  const Mesh m = sh::grid(g);
  sh::SampleOptions o;
  o.points = 20000;
  const PointCloud pc = sh::sample_mesh(m, o);
  std::size_t left = 0;
  for (std::size_t i = 0; i < pc.size(); ++i) {
    EXPECT_NEAR(pc.points[i][2], 0.0, 1e-12);
    EXPECT_EQ(pc.normals[i], Vec3(0, 0, 1));
    if (pc.points[i][0] < 0) ++left;
  }
  expect_fraction(left, pc.size(), 0.5, "left half of a jittered grid");
  EXPECT_THROW(sh::sample_mesh(Mesh(), o), InvalidInput);
}

TEST(ShapesOptions, BadOptionsThrowInvalidInput) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto bad_mesh = [](const std::string& name, const std::function<void(sh::MeshOptions&)>& edit) {
    sh::MeshOptions o;
    o.resolution = 8;
    edit(o);
    EXPECT_THROW(sh::make(name, o), InvalidInput) << name;
  };
  auto bad_sample = [](const std::string& name, const std::function<void(sh::SampleOptions&)>& edit) {
    sh::SampleOptions o;
    o.points = 10;
    edit(o);
    EXPECT_THROW(sh::sample(name, o), InvalidInput) << name;
  };
  bad_mesh("teapot", [](auto&) {});
  bad_sample("teapot", [](auto&) {});
  for (const auto& name : sh::shape_names()) {
    bad_mesh(name, [](auto& o) { o.resolution = 2; });
    bad_mesh(name, [](auto& o) { o.resolution = 5000; });
    if (name == "neck") continue;
    bad_mesh(name, [&](auto& o) {
      o.shape.radius = -1;
      o.shape.minor_radius = -1;
      o.shape.inner_radius = -1;
    });
    bad_sample(name, [&](auto& o) {
      o.shape.radius = nan;
      o.shape.minor_radius = nan;
      o.shape.inner_radius = nan;
    });
  }
  bad_mesh("vault-shell", [](auto& o) { o.shape.thickness = 1.0; });
  bad_sample("vault-shell", [](auto& o) { o.shape.thickness = 1.5; });
  bad_sample("vault-shell", [](auto& o) { o.shape.thickness = 0.0; });
  bad_sample("vault-shell", [&](auto& o) { o.shape.length = nan; });
  bad_sample("thin-plate", [](auto& o) { o.shape.thickness = 1.0; });
  bad_sample("hairpin", [](auto& o) { o.shape.gap = -0.1; });
  bad_sample("torus", [](auto& o) { o.shape.minor_radius = 1.0; });
  bad_sample("nested-spheres", [](auto& o) { o.shape.inner_radius = 2.0; });
  bad_sample("mobius", [](auto& o) { o.shape.width = 2.5; });
  bad_sample("bumpy-sphere", [](auto& o) { o.shape.amplitude = 1.0; });
  bad_sample("cylinder", [](auto& o) { o.shape.length = -2; });
  bad_mesh("grid-jittered", [](auto& o) { o.shape.jitter = 0.2; });
  bad_mesh("grid", [](auto& o) {
    o.shape.grid_outline = sh::GridOutline::disk;
    o.shape.grid_variant = sh::GridVariant::anisotropic;
  });
  bad_sample("icosphere", [](auto& o) { o.points = 0; });
  bad_sample("icosphere", [](auto& o) { o.noise_sigma = -1; });
  bad_sample("icosphere", [&](auto& o) { o.noise_sigma = nan; });
  bad_sample("icosphere", [](auto& o) { o.outlier_fraction = 1.5; });
  EXPECT_THROW(sh::icosphere(9), InvalidInput);
  EXPECT_THROW(sh::icosphere(-1), InvalidInput);
  EXPECT_THROW(sh::torus(2, 8), InvalidInput);
  EXPECT_THROW(sh::uv_sphere(8, 1), InvalidInput);
  EXPECT_THROW(sh::vault_shell(8, 1.0, 1.0), InvalidInput);
  EXPECT_THROW(sh::open_cylinder(8, 2, 1.0, nan), InvalidInput);
  EXPECT_THROW(sh::neck(7), InvalidInput);
  EXPECT_THROW(sh::neck(3), InvalidInput);
  sh::GridOptions g;
  g.outline = sh::GridOutline::l_shape;
  g.cells = 5;
  EXPECT_THROW(sh::grid(g), InvalidInput);
  g.cells = 0;
  EXPECT_THROW(sh::grid(g), InvalidInput);
  try {
    sh::vault_shell(8, 1.0, 1.2);
    FAIL();
  } catch (const InvalidInput& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("vault-shell"), std::string::npos) << what;
    EXPECT_NE(what.find("thickness"), std::string::npos) << what;
  }
}

TEST(ShapesNeck, HasExactlyOneMinimumPathway) {
  for (const int around : {6, 12, 48}) {
    const auto neck = sh::neck(around);
    const auto& [a, b, c] = neck.pathway;
    EXPECT_TRUE(sh::is_minimum_pathway(neck.mesh, a, b, c));
    EXPECT_TRUE(sh::is_minimum_pathway(neck.mesh, c, a, b));
    // The three vertices form a 3-edge cycle...
    EXPECT_TRUE(neck.mesh.find_halfedge(a, b).is_valid());
    EXPECT_TRUE(neck.mesh.find_halfedge(b, c).is_valid());
    EXPECT_TRUE(neck.mesh.find_halfedge(c, a).is_valid());
    // ... that is no face, and it is the only such cycle.
    for (const auto f : neck.mesh.faces()) {
      std::set<int> fv;
      for (const auto v : neck.mesh.fv_range(f)) fv.insert(v.idx());
      EXPECT_NE(fv, (std::set<int>{a.idx(), b.idx(), c.idx()}));
    }
    const auto all_paths = sh::find_minimum_pathways(neck.mesh);
    ASSERT_EQ(all_paths.size(), 1u) << around;
    std::array<int, 3> got{all_paths[0][0].idx(), all_paths[0][1].idx(), all_paths[0][2].idx()};
    std::array<int, 3> want{a.idx(), b.idx(), c.idx()};
    std::sort(want.begin(), want.end());
    EXPECT_EQ(got, want);
    // It separates the mesh: removing its three vertices leaves two components.
    std::vector<int> comp(neck.mesh.n_vertices(), -1);
    int components = 0;
    for (const auto s : neck.mesh.vertices()) {
      if (s == a || s == b || s == c || comp[static_cast<std::size_t>(s.idx())] >= 0) continue;
      std::vector<VertexHandle> stack{s};
      comp[static_cast<std::size_t>(s.idx())] = components;
      while (!stack.empty()) {
        const auto v = stack.back();
        stack.pop_back();
        for (const auto w : neck.mesh.vv_range(v))
          if (w != a && w != b && w != c && comp[static_cast<std::size_t>(w.idx())] < 0) {
            comp[static_cast<std::size_t>(w.idx())] = components;
            stack.push_back(w);
          }
      }
      ++components;
    }
    EXPECT_EQ(components, 2);
  }
}

TEST(ShapesNeck, MinimumPathwayQueriesOnOtherMeshes) {
  const Mesh ico = sh::icosphere(2);
  EXPECT_TRUE(sh::find_minimum_pathways(ico).empty());
  EXPECT_TRUE(sh::find_minimum_pathways(sh::torus(10, 5)).empty());
  // A torus whose tube has three segments has a 3-cycle around the tube at each of its rings.
  EXPECT_EQ(sh::find_minimum_pathways(sh::torus(10, 3)).size(), 10u);
  // A face is not a minimum pathway; vertices that are not pairwise adjacent are not either.
  const auto f = *ico.faces().begin();
  std::vector<VertexHandle> fv;
  for (const auto v : ico.fv_range(f)) fv.push_back(v);
  EXPECT_FALSE(sh::is_minimum_pathway(ico, fv[0], fv[1], fv[2]));
  EXPECT_FALSE(sh::is_minimum_pathway(ico, VertexHandle(0), VertexHandle(3), VertexHandle(7)));
  EXPECT_THROW(sh::is_minimum_pathway(ico, fv[0], fv[0], fv[1]), InvalidInput);
  EXPECT_THROW(sh::is_minimum_pathway(ico, fv[0], fv[1], VertexHandle(100000)), InvalidInput);
}

TEST(ShapesMobius, CutOpenAlongOneSeamBecauseOpenMeshCannotCloseIt) {
  const int around = 24, across = 3;
  const Mesh m = sh::mobius_strip(around, across);
  const Topology t = topology(m);
  EXPECT_TRUE(t.manifold);
  EXPECT_EQ(t.chi(), 1);
  EXPECT_EQ(t.border_loops, 1);
  long long border_edges = 0;
  for (const auto e : m.edges())
    if (m.is_boundary(e)) ++border_edges;
  EXPECT_EQ(border_edges, 2 * around + 2 * across);
  // The seam's duplicated vertices coincide in pairs; welding them is refused by OpenMesh.
  std::vector<int> canonical(m.n_vertices());
  std::map<std::array<long long, 3>, int> first;
  int pairs = 0;
  for (const auto v : m.vertices()) {
    const Vec3 p = m.point(v);
    const std::array<long long, 3> key{std::llround(p[0] * 1e9), std::llround(p[1] * 1e9), std::llround(p[2] * 1e9)};
    const auto [it, inserted] = first.emplace(key, v.idx());
    canonical[static_cast<std::size_t>(v.idx())] = it->second;
    if (!inserted) ++pairs;
  }
  EXPECT_EQ(pairs, across + 1);
  Mesh welded;
  for (const auto v : m.vertices()) welded.add_vertex(m.point(v));
  int refused = 0;
  for (const auto f : m.faces()) {
    std::vector<VertexHandle> vs;
    for (const auto v : m.fv_range(f)) vs.push_back(VertexHandle(canonical[static_cast<std::size_t>(v.idx())]));
    if (!welded.add_face(vs).is_valid()) ++refused;
  }
  EXPECT_GT(refused, 0);
}

TEST(ShapesMesh, DoubleTorusHalvesMeetOnTheCutPlane) {
  const Mesh m = sh::double_torus(32);
  int on_cut = 0;
  for (const auto v : m.vertices()) {
    if (m.point(v)[0] == 0.0) ++on_cut;
    // Mirror symmetry in x: every vertex has its mirror image.
  }
  EXPECT_GT(on_cut, 4);
  const auto t = topology(m);
  EXPECT_EQ(t.chi(), -2);
  EXPECT_EQ(t.border_loops, 0);
}

TEST(ShapesData, BundledFilesAreTheDocumentedShapes) {
  const std::filesystem::path dir = EDGEFRONT_DATA_DIR;
  const sh::ShapeParams sp;  // the files use the default sizes (vault: R = 1, t = 0.1, length 2)
  struct Cloud {
    const char* file;
    const char* shape;
    std::size_t points;
  };
  for (const Cloud& c : {Cloud{"vault-shell.xyz", "vault-shell", 4000}, Cloud{"vault-sheet.xyz", "vault-sheet", 3000}}) {
    SCOPED_TRACE(c.file);
    const PointCloud pc = edgefront::read_points(dir / c.file);
    ASSERT_EQ(pc.size(), c.points);
    ASSERT_TRUE(pc.has_normals());
    const auto pieces = analytic(c.shape, sp);
    for (std::size_t i = 0; i < pc.size(); ++i) {
      // Written with 4 decimals: within 1e-4 of the surface, normals within about 1e-3 rad.
      double best = 1e9;
      bool normal_ok = false;
      for (const auto& piece : pieces) {
        if (!piece.domain(pc.points[i]) && !piece.domain(pc.points[i] * (1 - 1e-4))) continue;
        const double d = std::abs(piece.F(pc.points[i]));
        best = std::min(best, d);
        if (d < 2e-4 && (pc.normals[i] | (piece.sign * gradient(piece.F, pc.points[i]).normalized())) > 0.999)
          normal_ok = true;
      }
      ASSERT_LT(best, 2e-4) << i;
      ASSERT_TRUE(normal_ok) << i;
    }
  }
  const auto neck = edgefront::read_mesh(dir / "neck.off").mesh;
  const auto paths = sh::find_minimum_pathways(neck);
  ASSERT_EQ(paths.size(), 1u);
  EXPECT_EQ(paths[0][0].idx(), 43);  // as data/README.md says
  const Topology tn = topology(neck);
  EXPECT_EQ(tn.chi(), 2);
  EXPECT_GT(tn.signed_volume, 0);
  const Topology tt = topology(edgefront::read_mesh(dir / "torus.off").mesh);
  EXPECT_EQ(tt.chi(), 0);
  EXPECT_EQ(tt.border_loops, 0);
  const Topology tb = topology(edgefront::read_mesh(dir / "bumpy-sphere.off").mesh);
  EXPECT_EQ(tb.chi(), 2);
  EXPECT_GT(tb.signed_volume, 0);
}

/// Runs a command through the shell; returns its exit code and its stderr.
std::pair<int, std::string> run(const std::string& command, const std::filesystem::path& err) {
  const int status = std::system((command + " 2>" + err.string()).c_str());
  std::ifstream in(err);
  std::stringstream text;
  text << in.rdbuf();
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, text.str()};
}

TEST(ShapesCli, WritesPointsAndMeshesWithDocumentedExitCodes) {
  const std::filesystem::path app = std::filesystem::path(EDGEFRONT_APP_DIR) / "ef-shapes";
  ASSERT_TRUE(std::filesystem::exists(app)) << "ef-shapes not built at " << app;
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("ef-shapes-test-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string exe = "'" + app.string() + "'";
  const auto err = dir / "stderr.txt";

  auto [code, text] = run(exe + " cylinder --points 500 --seed 3 -o '" + (dir / "c.xyz").string() + "' >/dev/null", err);
  EXPECT_EQ(code, 0) << text;
  const PointCloud pc = edgefront::read_points(dir / "c.xyz");
  EXPECT_EQ(pc.size(), 500u);
  EXPECT_TRUE(pc.has_normals());
  std::ifstream first(dir / "c.xyz");
  std::string line;
  std::getline(first, line);
  std::istringstream cols(line);
  int columns = 0;
  for (double x; cols >> x;) ++columns;
  EXPECT_EQ(columns, 6);
  sh::SampleOptions o;
  o.points = 500;
  o.seed = 3;
  const PointCloud direct = sh::sample("cylinder", o);
  for (std::size_t i = 0; i < pc.size(); ++i) EXPECT_LT((pc.points[i] - direct.points[i]).norm(), 1e-12);

  std::tie(code, text) = run(exe + " torus --mesh --resolution 12 -o '" + (dir / "t.off").string() + "' >/dev/null", err);
  EXPECT_EQ(code, 0) << text;
  EXPECT_EQ(topology(edgefront::read_mesh(dir / "t.off").mesh).chi(), 0);

  std::tie(code, text) = run(exe + " --list >/dev/null", err);
  EXPECT_EQ(code, 0);
  // Errors: exit 1 and exactly one line "ef-shapes: error: ...".
  std::tie(code, text) = run(exe + " vault-shell --thickness 1.5 -o '" + (dir / "v.xyz").string() + "' >/dev/null", err);
  EXPECT_EQ(code, 1);
  EXPECT_EQ(text.rfind("ef-shapes: error: ", 0), 0u) << text;
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1) << text;
  EXPECT_FALSE(std::filesystem::exists(dir / "v.xyz"));
  // Usage errors: exit 2 (an unknown shape is refused at parse time).
  std::tie(code, text) = run(exe + " teapot -o '" + (dir / "x.xyz").string() + "' >/dev/null", err);
  EXPECT_EQ(code, 2) << text;
  std::tie(code, text) = run(exe + " torus --mesh --points 5 -o '" + (dir / "x.off").string() + "' >/dev/null", err);
  EXPECT_EQ(code, 2) << text;
  std::tie(code, text) = run(exe + " torus >/dev/null", err);
  EXPECT_EQ(code, 2) << text;
  std::tie(code, text) = run(exe + " torus --bogus -o x.xyz >/dev/null", err);
  EXPECT_EQ(code, 2) << text;
  std::filesystem::remove_all(dir);
}

}  // namespace
