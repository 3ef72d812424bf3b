#pragma once
// Shared helpers of the edge-front tests: reference breadth-first levels, the generated shapes
// the properties are checked on, and random source picking.

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <functional>
#include <queue>
#include <random>
#include <string>
#include <vector>

#include "edgefront/front_source.h"
#include "edgefront/mesh.h"
#include "shapes/shapes.h"

namespace eftest {

using namespace edgefront;

/// Continues a breadth-first search: every vertex in `q` has its level in `d`; unreached are -1.
inline void spread_levels(const Mesh& mesh, std::vector<int>& d, std::queue<VertexHandle>& q) {
  while (!q.empty()) {
    const VertexHandle x = q.front();
    q.pop();
    for (VertexHandle y : mesh.vv_range(x)) {
      if (d[y.idx()] < 0) {
        d[y.idx()] = d[x.idx()] + 1;
        q.push(y);
      }
    }
  }
}

/// Breadth-first hop distance from a vertex set (-1 where unreachable).
inline std::vector<int> bfs_levels(const Mesh& mesh, const std::vector<VertexHandle>& sources) {
  std::vector<int> d(mesh.n_vertices(), -1);
  std::queue<VertexHandle> q;
  for (VertexHandle s : sources) {
    d[s.idx()] = 0;
    q.push(s);
  }
  spread_levels(mesh, d, q);
  return d;
}

/// Breadth-first levels from a loop source on its ahead side: the loop's vertices are 0, their
/// neighbours inside the ahead wedges 1, and the loop is never crossed.
inline std::vector<int> loop_bfs_levels(const Mesh& mesh, const std::vector<HalfedgeHandle>& loop) {
  std::vector<int> d(mesh.n_vertices(), -1);
  std::queue<VertexHandle> q;
  for (HalfedgeHandle h : loop) d[mesh.to_vertex_handle(h).idx()] = 0;
  const size_t n = loop.size();
  for (size_t i = 0; i < n; ++i) {
    HalfedgeHandle g = mesh.next_halfedge_handle(loop[i]);
    while (true) {
      const VertexHandle y = mesh.to_vertex_handle(g);
      if (d[y.idx()] < 0) {
        d[y.idx()] = 1;
        q.push(y);
      }
      if (g == loop[(i + 1) % n]) break;
      g = mesh.next_halfedge_handle(mesh.opposite_halfedge_handle(g));
    }
  }
  spread_levels(mesh, d, q);
  return d;
}

struct NamedMesh {
  std::string name;
  std::function<Mesh()> make;
};

inline void PrintTo(const NamedMesh& shape, std::ostream* os) { *os << shape.name; }

/// Small generated shapes (a few hundred vertices each) covering open and closed surfaces,
/// genus 0, 1 and 2, anisotropic and jittered triangulations, several components and a neck.
inline std::vector<NamedMesh> small_shapes() {
  using namespace edgefront::shapes;
  return {
      {"grid", [] { return grid(GridOptions{.cells = 12}); }},
      {"grid-jittered",
       [] { return grid(GridOptions{.cells = 12, .variant = GridVariant::jittered, .seed = 3}); }},
      {"grid-anisotropic",
       [] { return grid(GridOptions{.cells = 4, .variant = GridVariant::anisotropic, .anisotropy = 12}); }},
      {"disk", [] { return grid(GridOptions{.cells = 8, .outline = GridOutline::disk}); }},
      {"l-shape", [] { return grid(GridOptions{.cells = 12, .outline = GridOutline::l_shape}); }},
      {"icosphere", [] { return icosphere(2); }},
      {"uv-sphere", [] { return uv_sphere(16, 10); }},
      {"hemisphere", [] { return hemisphere(16, 6); }},
      {"cylinder", [] { return open_cylinder(16, 8); }},
      {"cone", [] { return cone(16, 6); }},
      {"torus", [] { return torus(20, 8); }},
      {"double-torus", [] { return double_torus(12); }},
      {"nested-spheres", [] { return nested_spheres(1); }},
      {"vault-shell", [] { return vault_shell(12); }},
      {"vault-sheet", [] { return vault_sheet(12); }},
      {"pointed-vault", [] { return pointed_vault(12); }},
      {"groin-vault", [] { return groin_vault(8); }},
      {"thin-plate", [] { return thin_plate(6); }},
      {"hairpin", [] { return hairpin(6); }},
      {"ribbon", [] { return half_twisted_ribbon(16, 4); }},
      {"neck", [] { return neck(12).mesh; }},
  };
}

/// Test-name suffix for a shape parameter (gtest names allow only alphanumerics and '_').
inline std::string shape_test_name(const ::testing::TestParamInfo<NamedMesh>& param_info) {
  std::string n = param_info.param.name;
  for (char& c : n) c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return n;
}

/// `count` distinct random live vertices.
inline std::vector<VertexHandle> random_vertices(const Mesh& mesh, std::mt19937_64& rng, size_t count) {
  std::vector<VertexHandle> out;
  std::uniform_int_distribution<int> pick(0, static_cast<int>(mesh.n_vertices()) - 1);
  while (out.size() < count) {
    const VertexHandle v(pick(rng));
    if (std::find(out.begin(), out.end(), v) == out.end()) out.push_back(v);
  }
  return out;
}

}  // namespace eftest
