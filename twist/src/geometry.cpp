#include "detail/geometry.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "edgefront/error.h"

namespace twist::detail {

using edgefront::HalfedgeHandle;
using edgefront::InternalError;
using edgefront::InvalidInput;

std::vector<std::vector<HalfedgeHandle>> coincident_border_halfedges(const Mesh& mesh) {
  std::vector<std::vector<HalfedgeHandle>> out;
  if (mesh.n_vertices() == 0) return out;
  Vec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (VertexHandle v : mesh.vertices()) {
    lo.minimize(mesh.point(v));
    hi.maximize(mesh.point(v));
  }
  const double tol = std::max(1e-300, 1e-9 * (hi - lo).norm());
  using Key = std::array<long long, 6>;
  auto q = [&](double x) { return static_cast<long long>(std::llround(x / tol)); };
  std::map<Key, std::vector<HalfedgeHandle>> by_key;
  const bool status = mesh.has_halfedge_status();
  for (HalfedgeHandle h : mesh.halfedges()) {
    if ((status && mesh.status(h).deleted()) || !mesh.is_boundary(h)) continue;
    const Vec3& a = mesh.point(mesh.from_vertex_handle(h));
    const Vec3& b = mesh.point(mesh.to_vertex_handle(h));
    by_key[Key{q(a[0]), q(a[1]), q(a[2]), q(b[0]), q(b[1]), q(b[2])}].push_back(h);
  }
  for (auto& entry : by_key) {
    if (entry.second.size() >= 2) out.push_back(std::move(entry.second));
  }
  return out;
}

std::array<Vec3, 3> face_points(const Mesh& mesh, FaceHandle f) {
  std::array<Vec3, 3> p;
  int i = 0;
  for (VertexHandle v : mesh.fv_range(f)) {
    if (i < 3) p[static_cast<size_t>(i)] = mesh.point(v);
    ++i;
  }
  EF_CHECK(i == 3, "face " + std::to_string(f.idx()) + " is not a triangle");
  return p;
}

Vec3 unit_normal(const std::array<Vec3, 3>& p) {
  const Vec3 n = OpenMesh::cross(p[1] - p[0], p[2] - p[0]);
  const double len = n.norm();
  if (!(len > 0) || !std::isfinite(len)) return Vec3(0, 0, 0);
  return n / len;
}

double area(const std::array<Vec3, 3>& p) { return 0.5 * OpenMesh::cross(p[1] - p[0], p[2] - p[0]).norm(); }

Vec3 centroid(const std::array<Vec3, 3>& p) { return (p[0] + p[1] + p[2]) / 3.0; }

bool segment_crosses(const Vec3& p, const Vec3& q, const std::array<Vec3, 3>& t, double eps) {
  const Vec3 n = unit_normal(t);
  if (n.sqrnorm() == 0) return false;
  const double dp = OpenMesh::dot(p - t[0], n);
  const double dq = OpenMesh::dot(q - t[0], n);
  if (!((dp > eps && dq < -eps) || (dp < -eps && dq > eps))) return false;
  const Vec3 x = p + (q - p) * (dp / (dp - dq));
  // Barycentric sign test against each edge, with a margin so touching at an edge does not count.
  for (int i = 0; i < 3; ++i) {
    const Vec3& a = t[static_cast<size_t>(i)];
    const Vec3& b = t[static_cast<size_t>((i + 1) % 3)];
    const Vec3 edge = b - a;
    const double len = edge.norm();
    if (!(len > 0)) return false;
    const double side = OpenMesh::dot(OpenMesh::cross(edge, x - a), n) / len;  // distance inside
    if (side <= eps) return false;
  }
  return true;
}

bool stacked_layers(const std::array<Vec3, 3>& a, const Vec3& na, double la, const std::array<Vec3, 3>& b,
                    const Vec3& nb, double lb) {
  constexpr double kStackedOverlap = 0.1;  // of the shorter longest edge (see LayerRule::Stacked)
  return projected_overlap(a, b, (na + nb).normalized()) > kStackedOverlap * std::min(la, lb);
}

double projected_overlap(const std::array<Vec3, 3>& a, const std::array<Vec3, 3>& b, const Vec3& direction) {
  // An in-plane basis (u, v) perpendicular to the direction.
  const Vec3 helper = std::abs(direction[0]) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
  const Vec3 u = OpenMesh::cross(direction, helper).normalized();
  const Vec3 v = OpenMesh::cross(direction, u);
  std::array<std::array<double, 2>, 6> p{};
  for (size_t i = 0; i < 3; ++i) {
    p[i] = {OpenMesh::dot(a[i], u), OpenMesh::dot(a[i], v)};
    p[i + 3] = {OpenMesh::dot(b[i], u), OpenMesh::dot(b[i], v)};
  }
  double depth = std::numeric_limits<double>::infinity();
  for (size_t t = 0; t < 2; ++t) {
    for (size_t i = 0; i < 3; ++i) {
      const auto& s = p[3 * t + i];
      const auto& e = p[3 * t + (i + 1) % 3];
      const double ax = -(e[1] - s[1]), ay = e[0] - s[0];
      const double len = std::hypot(ax, ay);
      if (!(len > 0)) continue;  // a degenerate projected edge separates nothing
      double lo[2] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
      double hi[2] = {-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
      for (size_t k = 0; k < 6; ++k) {
        const double x = (p[k][0] * ax + p[k][1] * ay) / len;
        lo[k / 3] = std::min(lo[k / 3], x);
        hi[k / 3] = std::max(hi[k / 3], x);
      }
      depth = std::min(depth, std::min(hi[0], hi[1]) - std::max(lo[0], lo[1]));
    }
  }
  return std::isfinite(depth) ? depth : 0.0;
}

// ---------------------------------------------------------------------------------------------
// Surgery

VertexHandle copy_vertex(Mesh& mesh, VertexHandle v) {
  const VertexHandle copy = mesh.add_vertex(edgefront::Vec3(mesh.point(v)));  // a copy: add_vertex may reallocate the points
  OpenMesh::VPropHandleT<int> journal;
  if (mesh.get_property_handle(journal, kCopyJournal)) mesh.property(journal, copy) = v.idx() + 1;
  return copy;
}

size_t cut_and_reverse(Mesh& mesh, const std::vector<FaceHandle>& side, bool reverse,
                       std::vector<std::pair<VertexHandle, VertexHandle>>* duplicates) {
  std::unordered_set<int> in_side;
  in_side.reserve(side.size() * 2);
  for (FaceHandle f : side) in_side.insert(f.idx());

  // Per (face, vertex) corner of a side face at a cut vertex: the vertex copy it gets.
  std::unordered_map<std::uint64_t, VertexHandle> corner_copy;
  auto key = [](FaceHandle f, VertexHandle v) {
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(f.idx())) << 32) |
           static_cast<std::uint32_t>(v.idx());
  };
  std::unordered_set<int> seen_vertex;
  size_t duplicated = 0;
  std::vector<FaceHandle> ring;
  std::vector<FaceHandle> others;  // faces outside the side that get a vertex copy too
  std::unordered_set<int> other_seen;
  for (FaceHandle f : side) {
    for (VertexHandle v : mesh.fv_range(f)) {
      if (!seen_vertex.insert(v.idx()).second) continue;
      // Faces around v in circulation order (invalid handles at border gaps).
      ring.clear();
      bool has_other = false;
      for (HalfedgeHandle h : mesh.voh_range(v)) {
        const FaceHandle g = mesh.face_handle(h);
        ring.push_back(g);
        if (g.is_valid() && !in_side.count(g.idx())) has_other = true;
      }
      if (!has_other) continue;
      const size_t n = ring.size();
      // Runs of side faces each get a copy of v; of the runs of other faces the first keeps v and
      // every further one gets a copy too (else v would join several fans: non-manifold).
      for (int pass = 0; pass < 2; ++pass) {
        const bool want_side = pass == 0;
        auto member = [&](FaceHandle g) { return g.is_valid() && (in_side.count(g.idx()) > 0) == want_side; };
        size_t start = n;  // just after a separator, so no run wraps around
        for (size_t i = 0; i < n; ++i) {
          if (!member(ring[i])) {
            start = (i + 1) % n;
            break;
          }
        }
        if (start == n) continue;  // v is surrounded by this kind only (cannot happen for both)
        VertexHandle copy;
        bool first_run = true;
        bool in_run = false;
        for (size_t k = 0; k < n; ++k) {
          const FaceHandle g = ring[(start + k) % n];
          if (!member(g)) {
            if (in_run) first_run = false;
            in_run = false;
            copy = VertexHandle();
            continue;
          }
          in_run = true;
          if (!want_side && first_run) continue;  // the first run of other faces keeps v
          if (!copy.is_valid()) {
            copy = copy_vertex(mesh, v);
            ++duplicated;
            if (duplicates) duplicates->emplace_back(copy, v);
          }
          corner_copy[key(g, v)] = copy;
          if (!want_side && other_seen.insert(g.idx()).second) others.push_back(g);
        }
      }
    }
  }

  std::vector<std::array<VertexHandle, 3>> tris;
  tris.reserve(side.size() + others.size());
  auto record = [&](FaceHandle f, bool rev) {
    std::array<VertexHandle, 3> t;
    int i = 0;
    for (VertexHandle v : mesh.fv_range(f)) {
      const auto it = corner_copy.find(key(f, v));
      t[static_cast<size_t>(i++)] = it == corner_copy.end() ? v : it->second;
    }
    if (rev) std::swap(t[1], t[2]);
    tris.push_back(t);
  };
  for (FaceHandle f : side) record(f, reverse);
  for (FaceHandle f : others) record(f, false);
  for (FaceHandle f : others) mesh.delete_face(f, false);
  for (FaceHandle f : side) mesh.delete_face(f, false);
  for (const auto& t : tris) {
    const FaceHandle nf = mesh.add_face(t[0], t[1], t[2]);
    if (!nf.is_valid()) {
      throw InternalError("twist: OpenMesh refused to re-add a face (vertices " + std::to_string(t[0].idx()) + ", " +
                          std::to_string(t[1].idx()) + ", " + std::to_string(t[2].idx()) + ")");
    }
    mesh.set_normal(nf, mesh.calc_face_normal(nf));
  }
  return duplicated;
}

size_t split_fans(Mesh& mesh, VertexHandle v) {
  // Fans: runs of faces between border gaps, found by walking the outgoing border halfedges.
  std::vector<std::vector<FaceHandle>> fans;
  for (HalfedgeHandle h : mesh.voh_range(v)) {
    if (!mesh.is_boundary(h)) continue;
    // Walk from the gap: h is outgoing with no face; rotate until the next gap.
    std::vector<FaceHandle> fan;
    HalfedgeHandle g = mesh.cw_rotated_halfedge_handle(h);
    while (!mesh.is_boundary(g) && g != h) {
      fan.push_back(mesh.face_handle(g));
      g = mesh.cw_rotated_halfedge_handle(g);
    }
    if (!fan.empty()) fans.push_back(std::move(fan));
  }
  if (fans.size() < 2) return 0;
  std::vector<std::array<VertexHandle, 3>> tris;
  std::vector<FaceHandle> redo;
  for (size_t k = 1; k < fans.size(); ++k) {
    const VertexHandle copy = copy_vertex(mesh, v);
    for (FaceHandle f : fans[k]) {
      std::array<VertexHandle, 3> t;
      int i = 0;
      for (VertexHandle u : mesh.fv_range(f)) t[static_cast<size_t>(i++)] = u == v ? copy : u;
      tris.push_back(t);
      redo.push_back(f);
    }
  }
  for (FaceHandle f : redo) mesh.delete_face(f, false);
  for (const auto& t : tris) {
    const FaceHandle nf = mesh.add_face(t[0], t[1], t[2]);
    if (!nf.is_valid()) throw InternalError("twist: OpenMesh refused a face while splitting a non-manifold vertex");
    mesh.set_normal(nf, mesh.calc_face_normal(nf));
  }
  return fans.size() - 1;
}

void check_mesh(const Mesh& mesh, const char* what) {
  edgefront::require_attributes(mesh, what);
  size_t live = 0;
  for (FaceHandle f : mesh.faces()) {
    if (!mesh.status(f).deleted()) ++live;
  }
  if (live == 0) throw InvalidInput(std::string(what) + ": the mesh has no faces");
  for (VertexHandle v : mesh.vertices()) {
    const Vec3& p = mesh.point(v);
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
      throw InvalidInput(std::string(what) + ": vertex " + std::to_string(v.idx()) + " has a non-finite coordinate");
    }
  }
}

double mean_edge_length(const Mesh& mesh) {
  double sum = 0;
  size_t n = 0;
  for (edgefront::EdgeHandle e : mesh.edges()) {
    if (mesh.status(e).deleted()) continue;
    sum += mesh.calc_edge_length(e);
    ++n;
  }
  return n ? sum / static_cast<double>(n) : 0.0;
}

}  // namespace twist::detail
