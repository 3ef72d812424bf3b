// Global orientation (twist::orient and the repair's last step) and pieces flipped across reversed
// seams. Shared steps: detail/repair_steps.h.
#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <map>
#include <numbers>
#include <numeric>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

#include "detail/geometry.h"
#include "detail/repair_steps.h"
#include "edgefront/mesh_stats.h"
#include "edgefront/union_find.h"
#include "twist/repair.h"

namespace twist {

using edgefront::FaceHandle;
using edgefront::HalfedgeHandle;
using edgefront::Mesh;
using edgefront::Vec3;

using detail::DupList;

namespace {

using edgefront::UnionFind;

/// The winding number of a closed surface given by its faces around p: the sum of the faces'
/// signed solid angles seen from p over 4 pi (Van Oosterom & Strackee's formula), +-1 inside
/// (the sign of the surface's orientation), 0 outside.
double winding_number(const Mesh& mesh, const std::vector<FaceHandle>& faces, const Vec3& p) {
  double sum = 0;
  for (FaceHandle f : faces) {
    const auto q = detail::face_points(mesh, f);
    const Vec3 a = q[0] - p, b = q[1] - p, c = q[2] - p;
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    const double num = OpenMesh::dot(a, OpenMesh::cross(b, c));
    const double den = la * lb * lc + OpenMesh::dot(a, b) * lc + OpenMesh::dot(b, c) * la + OpenMesh::dot(c, a) * lb;
    sum += 2 * std::atan2(num, den);
  }
  return sum / (4 * std::numbers::pi);
}

/// For each closed group (key: group root), how many other closed groups enclose it: a group
/// whose bounding box lies in another's and one of whose vertices that other surrounds (winding
/// number above 1/2 in magnitude). O(faces of the enclosing candidates) per group.
std::unordered_map<size_t, int> nesting_depths(const Mesh& mesh,
                                               const std::unordered_map<size_t, std::vector<FaceHandle>>& closed) {
  struct Box {
    Vec3 lo{std::numeric_limits<double>::infinity()}, hi{-std::numeric_limits<double>::infinity()};
    bool inside(const Box& o) const {
      for (int k = 0; k < 3; ++k)
        if (lo[k] < o.lo[k] || hi[k] > o.hi[k]) return false;
      return true;
    }
  };
  std::unordered_map<size_t, Box> box;
  for (const auto& [g, faces] : closed)
    for (FaceHandle f : faces)
      for (const Vec3& q : detail::face_points(mesh, f)) {
        box[g].lo.minimize(q);
        box[g].hi.maximize(q);
      }
  std::unordered_map<size_t, int> depth;
  for (const auto& [g, faces] : closed) {
    const Vec3 p = mesh.point(*mesh.cfv_begin(faces.front()));
    int d = 0;
    for (const auto& [h, other] : closed)
      if (h != g && box[g].inside(box[h]) && std::abs(winding_number(mesh, other, p)) > 0.5) ++d;
    depth[g] = d;
  }
  return depth;
}

}  // namespace

namespace detail {

/// The global orientation convention (see repair.h).
void orient_globally(Mesh& mesh, const RepairOptions& o, const DupList& dups, RepairReport& report) {
  const size_t nv = mesh.n_vertices();
  // Groups: components before the cuts (vertex copies joined to their originals).
  UnionFind group(nv);
  UnionFind comp(nv);
  for (FaceHandle f : mesh.faces()) {
    auto it = mesh.fv_begin(f);
    const size_t v0 = static_cast<size_t>((*it).idx());
    ++it;
    for (; it.is_valid(); ++it) {
      group.unite(v0, static_cast<size_t>((*it).idx()));
      comp.unite(v0, static_cast<size_t>((*it).idx()));
    }
  }
  std::unordered_set<int> cut_vertex;
  for (const auto& [copy, original] : dups) {
    if (!edgefront::is_live(mesh, copy) || !edgefront::is_live(mesh, original)) continue;
    group.unite(static_cast<size_t>(copy.idx()), static_cast<size_t>(original.idx()));
    cut_vertex.insert(copy.idx());
    cut_vertex.insert(original.idx());
  }
  struct Acc {
    std::vector<FaceHandle> faces;
    double volume = 0, vote = 0;
    size_t group = 0;
  };
  std::unordered_map<size_t, Acc> comps;
  std::unordered_map<size_t, double> group_volume;
  std::unordered_map<size_t, bool> group_open;
  for (FaceHandle f : mesh.faces()) {
    const auto p = detail::face_points(mesh, f);
    const size_t root = comp.find(static_cast<size_t>((*mesh.fv_begin(f)).idx()));
    Acc& acc = comps[root];
    acc.faces.push_back(f);
    acc.group = group.find(root);
    const double vol = OpenMesh::dot(p[0], OpenMesh::cross(p[1], p[2])) / 6.0;
    acc.volume += vol;
    group_volume[acc.group] += vol;
    if (o.detect.reference) {
      const Vec3 n = detail::unit_normal(p);
      acc.vote += detail::area(p) * reference_vote(*o.detect.reference, o.detect, detail::centroid(p), n);
    }
  }
  for (HalfedgeHandle h : mesh.halfedges()) {
    if (!mesh.is_boundary(h)) continue;
    const bool on_cut = cut_vertex.count(mesh.from_vertex_handle(h).idx()) && cut_vertex.count(mesh.to_vertex_handle(h).idx());
    if (!on_cut) group_open[group.find(static_cast<size_t>(mesh.to_vertex_handle(h).idx()))] = true;
  }
  std::vector<size_t> roots;
  for (const auto& [root, acc] : comps) roots.push_back(root);
  std::sort(roots.begin(), roots.end());
  // Without reference normals, how deep each closed group lies inside others: a closed surface
  // inside an odd number of others bounds a cavity (the inner sphere of a hollow ball) and faces
  // into it (negative volume); the others face outward.
  std::unordered_map<size_t, int> depth;
  if (!o.detect.reference) {
    std::unordered_map<size_t, std::vector<FaceHandle>> closed;
    for (size_t root : roots)
      if (!group_open[comps[root].group]) {
        auto& faces = closed[comps[root].group];
        faces.insert(faces.end(), comps[root].faces.begin(), comps[root].faces.end());
      }
    if (closed.size() > 1) depth = nesting_depths(mesh, closed);
  }
  for (size_t root : roots) {
    Acc& acc = comps[root];
    bool flip = false;
    if (o.detect.reference) {
      flip = acc.vote < 0;
    } else if (!group_open[acc.group]) {
      const bool cavity = depth[acc.group] % 2 == 1;
      flip = cavity ? group_volume[acc.group] > 0 : group_volume[acc.group] < 0;
    }
    if (!flip) continue;
    detail::cut_and_reverse(mesh, acc.faces, true, nullptr);
    ++report.components_flipped;
    report.faces_flipped_globally += acc.faces.size();
  }
}

/// Pieces that meet another piece along a reversed seam (their border halfedges lie on top of
/// each other running the same way: a region turned over by hand, wound the other way in a file,
/// its vertices split from the rest) are flipped so the seams become compatible: per group of
/// pieces joined by such seams, the pieces get two classes (a piece and a piece it meets along a
/// reversed seam are in different classes) and the class with fewer faces is flipped whole. A
/// seam within one piece (a Moebius band cut open) or a group that cannot be split in two classes
/// is left. The seam vertex pairs join `dups` so the global orientation treats the group as one
/// surface. O(F + border halfedges log).
void flip_seam_pieces(Mesh& mesh, DupList& dups, RepairReport& report) {
  const std::vector<std::vector<HalfedgeHandle>> coincident = detail::coincident_border_halfedges(mesh);
  if (coincident.empty()) return;
  const edgefront::ComponentLabels labels = edgefront::connected_components(mesh);
  auto piece = [&](HalfedgeHandle h) { return labels.vertex_component[static_cast<size_t>(mesh.from_vertex_handle(h).idx())]; };
  std::map<std::pair<int, int>, DupList> seams;  // (piece, piece) -> coincident vertex pairs
  std::map<std::pair<int, int>, std::pair<double, size_t>> turn;  // (piece, piece) -> (sum of n.n' across the seam, edges)
  for (const std::vector<HalfedgeHandle>& hs : coincident) {
    for (size_t i = 0; i < hs.size(); ++i)
      for (size_t j = i + 1; j < hs.size(); ++j) {
        const int a = piece(hs[i]), b = piece(hs[j]);
        if (a == b) continue;
        DupList& pairs = seams[{std::min(a, b), std::max(a, b)}];
        pairs.emplace_back(mesh.from_vertex_handle(hs[j]), mesh.from_vertex_handle(hs[i]));
        pairs.emplace_back(mesh.to_vertex_handle(hs[j]), mesh.to_vertex_handle(hs[i]));
        const FaceHandle fa = mesh.opposite_face_handle(hs[i]), fb = mesh.opposite_face_handle(hs[j]);
        auto& t = turn[{std::min(a, b), std::max(a, b)}];
        t.first += OpenMesh::dot(detail::unit_normal(detail::face_points(mesh, fa)), detail::unit_normal(detail::face_points(mesh, fb)));
        ++t.second;
      }
  }
  // Only seams across which the surface runs on smoothly but turned over (the faces on the two
  // sides face opposite ways: n.n' < -0.5 on average) are flipped; a seam across which they face
  // the same way, or fold, is what a twist repair's cut leaves (the layers cross there) and stays.
  for (auto it = seams.begin(); it != seams.end();) {
    const auto& t = turn[it->first];
    it = t.first < -0.5 * static_cast<double>(t.second) ? std::next(it) : seams.erase(it);
  }
  if (seams.empty()) return;
  std::vector<std::vector<int>> adjacent(labels.count);
  for (const auto& entry : seams) {
    adjacent[static_cast<size_t>(entry.first.first)].push_back(entry.first.second);
    adjacent[static_cast<size_t>(entry.first.second)].push_back(entry.first.first);
  }
  std::vector<std::vector<FaceHandle>> faces(labels.count);
  for (FaceHandle f : mesh.faces()) {
    if (!mesh.status(f).deleted()) faces[static_cast<size_t>(labels.vertex_component[static_cast<size_t>((*mesh.fv_begin(f)).idx())])].push_back(f);
  }
  std::vector<int> colour(labels.count, -1);
  std::vector<FaceHandle> flip;
  std::vector<int> resolved;  // pieces of groups that could be split in two classes
  for (size_t start = 0; start < labels.count; ++start) {
    if (colour[start] >= 0 || adjacent[start].empty()) continue;
    std::vector<int> group{static_cast<int>(start)};
    colour[start] = 0;
    bool two_classes = true;
    size_t class_faces[2] = {0, 0};
    for (size_t k = 0; k < group.size(); ++k) {
      const int c = group[k];
      class_faces[colour[static_cast<size_t>(c)]] += faces[static_cast<size_t>(c)].size();
      for (int d : adjacent[static_cast<size_t>(c)]) {
        if (colour[static_cast<size_t>(d)] < 0) {
          colour[static_cast<size_t>(d)] = 1 - colour[static_cast<size_t>(c)];
          group.push_back(d);
        } else if (colour[static_cast<size_t>(d)] == colour[static_cast<size_t>(c)]) {
          two_classes = false;
        }
      }
    }
    if (!two_classes) continue;
    const int flipped = class_faces[1] <= class_faces[0] ? 1 : 0;
    for (int c : group) {
      resolved.push_back(c);
      if (colour[static_cast<size_t>(c)] != flipped) continue;
      flip.insert(flip.end(), faces[static_cast<size_t>(c)].begin(), faces[static_cast<size_t>(c)].end());
      ++report.seam_pieces_flipped;
    }
  }
  std::sort(resolved.begin(), resolved.end());
  for (const auto& entry : seams) {
    if (std::binary_search(resolved.begin(), resolved.end(), entry.first.first)) dups.insert(dups.end(), entry.second.begin(), entry.second.end());
  }
  if (flip.empty()) return;
  report.seam_faces_flipped += flip.size();
  detail::cut_and_reverse(mesh, flip, true, nullptr);
}

}  // namespace detail

using detail::orient_globally;

RepairReport orient(Mesh& mesh, const RepairOptions& options) {
  detail::check_mesh(mesh, "twist::orient");
  RepairReport report;
  orient_globally(mesh, options, DupList{}, report);
  if (options.garbage_collect) mesh.garbage_collection();
  return report;
}

}  // namespace twist
