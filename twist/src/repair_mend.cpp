// Mending small patches the reference still rejects after a repair by labelling (see repair.h,
// `RepairOptions::mend_patches`): such patches are folds and turned flaps of the geometry, which
// no flip fixes without leaving a tiny piece. Shared steps: detail/repair_steps.h.
#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

#include "detail/border_join.h"
#include "detail/geometry.h"
#include "detail/repair_steps.h"
#include "edgefront/error.h"
#include "twist/repair.h"

namespace twist::detail {

using edgefront::EdgeHandle;
using edgefront::FaceHandle;
using edgefront::HalfedgeHandle;
using edgefront::Mesh;
using edgefront::Vec3;
using edgefront::VertexHandle;

namespace {

using Tri = std::array<Vec3, 3>;

class Mender {
 public:
  Mender(Mesh& mesh, const RepairOptions& o, double edge)
      : mesh_(mesh), o_(o), ref_(*o.detect.reference), edge_(edge), min_area_(1e-4 * edge * edge) {}

  /// How badly the reference judges a triangle: 1 rejected (`reference_vote` -1, thin-wall rule
  /// on), 0.5 standing across the surface (undecided because nearly perpendicular to its nearest
  /// normal, and turned away from it), else 0 (agreeing, degenerate, or on a wall thinner than the
  /// faces, where the verdict is noise).
  double misfit(const Tri& p) const {
    const Vec3 n = unit_normal(p);
    if (n.sqrnorm() == 0) return 0;
    const Vec3 c = centroid(p);
    const int v = reference_vote(ref_, o_.detect, c, n, edge_);
    if (v != 0) return v < 0 ? 1.0 : 0.0;
    const double cos = OpenMesh::dot(n, ref_.nearest_normal(c));
    return cos < 0 && cos > o_.detect.vote.reference_cos ? 0.5 : 0.0;
  }
  bool misfits(FaceHandle f) const { return misfit(face_points(mesh_, f)) > 0; }
  /// The triangles' areas weighted by their misfit.
  double misfit_area(const std::vector<Tri>& ts) const {
    double a = 0;
    for (const Tri& t : ts) a += misfit(t) * area(t);
    return a;
  }
  bool degenerate(const Tri& t) const { return area(t) < min_area_ || unit_normal(t).sqrnorm() == 0; }
  double cloud_distance(const Vec3& p) const { return (p - ref_.cloud().points[ref_.nearest(p)]).norm(); }
  /// Accepts a change of `before` into `after` (triangles; `folds_*` the folded edges around):
  /// no degenerate triangle, less rejected area (by more than rounding), no more folds.
  bool better(const std::vector<Tri>& before, const std::vector<Tri>& after, size_t folds_before,
              size_t folds_after) const {
    for (const Tri& t : after)
      if (degenerate(t)) return false;
    const double b = misfit_area(before), a = misfit_area(after);
    return a < b - 1e-9 * edge_ * edge_ && folds_after <= folds_before;
  }

  /// Tries to swap the edge between rejected face f and its neighbour across `h` (a halfedge of
  /// f) for the quad's other diagonal; keeps it when `better`. Returns whether it was kept.
  bool flip_edge(HalfedgeHandle h) {
    const HalfedgeHandle o = mesh_.opposite_halfedge_handle(h);
    const FaceHandle f = mesh_.face_handle(h), g = mesh_.face_handle(o);
    if (!f.is_valid() || !g.is_valid() || !mesh_.is_flip_ok(mesh_.edge_handle(h))) return false;
    // f = (a, b, c) with h = a -> b; g = (b, a, d). The quad runs a, d, b, c; the new faces are
    // (a, d, c) and (d, b, c), wound like f and g.
    const VertexHandle a = mesh_.from_vertex_handle(h), b = mesh_.to_vertex_handle(h);
    const VertexHandle c = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(h));
    const VertexHandle d = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(o));
    const std::array<VertexHandle, 3> n1{a, d, c}, n2{d, b, c};
    const Tri t1 = points(n1), t2 = points(n2);
    const Tri tf = face_points(mesh_, f), tg = face_points(mesh_, g);
    // Folds: across the quad's four outer edges and its diagonal.
    const std::array<HalfedgeHandle, 4> outer{mesh_.next_halfedge_handle(o), mesh_.prev_halfedge_handle(o),
                                              mesh_.next_halfedge_handle(h), mesh_.prev_halfedge_handle(h)};
    // outer[0] = a -> d (g), outer[1] = d -> b (g), outer[2] = b -> c (f), outer[3] = c -> a (f).
    size_t folds_before = folded(tf, tg), folds_after = folded(t1, t2);
    for (size_t k = 0; k < 4; ++k) {
      const FaceHandle out = mesh_.opposite_face_handle(outer[k]);
      if (!out.is_valid()) continue;
      const Tri to = face_points(mesh_, out);
      folds_before += folded(k < 2 ? tg : tf, to);
      folds_after += folded(k == 0 || k == 3 ? t1 : t2, to);
    }
    if (!better({tf, tg}, {t1, t2}, folds_before, folds_after)) return false;
    mesh_.delete_face(f, false);
    mesh_.delete_face(g, false);
    if (!add_all_or_none(mesh_, {n1, n2})) {
      const bool restored = add_all_or_none(mesh_, {{a, b, c}, {b, a, d}});
      EF_CHECK(restored, "mend: the faces of a refused edge flip could not be restored");
      renormal_last(2);
      return false;
    }
    renormal_last(2);
    return true;
  }

  /// Tries to move vertex v to each of `targets`, keeps the one that lowers the rejected area of
  /// the faces around v most when `better` and the new position lies no farther from the cloud
  /// than max(its old distance, half an edge). Returns whether v moved.
  bool move_vertex(VertexHandle v, const std::vector<Vec3>& targets) {
    const Vec3 old = mesh_.point(v);
    const std::vector<VertexHandle> vs{v};
    const std::optional<size_t> folds_before = folds_around(mesh_, vs);
    if (!folds_before) return false;
    const std::vector<Tri> before = around(v);
    const double before_rejected = misfit_area(before);
    const double reach = std::max(cloud_distance(old), 0.5 * edge_);
    std::optional<Vec3> best;
    double best_rejected = before_rejected;
    for (const Vec3& p : targets) {
      if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]) || cloud_distance(p) > reach)
        continue;
      mesh_.set_point(v, p);
      const std::vector<Tri> after = around(v);
      const std::optional<size_t> folds_after = folds_around(mesh_, vs);
      if (folds_after && better(before, after, *folds_before, *folds_after)) {
        const double r = misfit_area(after);
        if (r < best_rejected) {
          best_rejected = r;
          best = p;
        }
      }
      mesh_.set_point(v, old);
    }
    if (!best) return false;
    mesh_.set_point(v, *best);
    for (FaceHandle f : mesh_.vf_range(v)) mesh_.set_normal(f, mesh_.calc_face_normal(f));
    return true;
  }

  /// Where v may go to unfold rejected face f: v turned about each edge of a rejected face around
  /// it that does not hold v (a page folded over its hinge, turned back flat), and for an
  /// interior vertex the centroid of its neighbours.
  std::vector<Vec3> unfold_targets(VertexHandle v) const {
    std::vector<Vec3> out;
    const Vec3 p = mesh_.point(v);
    for (HalfedgeHandle h : mesh_.voh_range(v)) {
      const FaceHandle f = mesh_.face_handle(h);
      if (!f.is_valid() || !misfits(f)) continue;
      const HalfedgeHandle hinge = mesh_.next_halfedge_handle(h);  // the edge of f opposite v
      const Vec3 a = mesh_.point(mesh_.from_vertex_handle(hinge)),
                 b = mesh_.point(mesh_.to_vertex_handle(hinge));
      const Vec3 ab = b - a;
      const double len2 = ab.sqrnorm();
      if (len2 <= 0) continue;
      const Vec3 foot = a + ab * (OpenMesh::dot(p - a, ab) / len2);
      out.push_back(2 * foot - p);
    }
    // The nearest reference point of the wall the accepted faces around v face: a corner that
    // reached across to the other wall of a thin shell goes back onto its own.
    // (A corner all of whose faces are wrong, the tip of a flap, takes the faces around its
    // neighbours.)
    Vec3 facing(0, 0, 0);
    auto add_agreeing = [&](VertexHandle w) {
      for (FaceHandle f : mesh_.vf_range(w)) {
        const Tri t = face_points(mesh_, f);
        const Vec3 n = unit_normal(t);
        if (n.sqrnorm() > 0 && reference_vote(ref_, o_.detect, centroid(t), n, edge_) > 0)
          facing += area(t) * n;
      }
    };
    add_agreeing(v);
    if (facing.sqrnorm() == 0) {
      for (VertexHandle w : mesh_.vv_range(v)) add_agreeing(w);
    }
    if (facing.sqrnorm() > 0) {
      if (const std::optional<size_t> q = ref_.nearest_facing(p, facing.normalized()))
        out.push_back(ref_.cloud().points[*q]);
    }
    if (!mesh_.is_boundary(v)) {
      Vec3 sum(0, 0, 0);
      size_t k = 0;
      for (VertexHandle w : mesh_.vv_range(v)) {
        sum += mesh_.point(w);
        ++k;
      }
      if (k > 0) out.push_back(sum / static_cast<double>(k));
    }
    return out;
  }

  /// Cuts `patch` (an edge-connected set of faces away from the mesh border, whose rim is one
  /// simple loop of at least 4 edges) out and re-grows it as a fan around the rim's centroid,
  /// wound like the faces around (the rim's own winding), when the fan is `better` than the patch
  /// and its centre lies within an edge of the cloud. Returns the faces added (0: unchanged).
  size_t regrow(const std::vector<FaceHandle>& patch) {
    std::unordered_set<int> in_patch;
    for (FaceHandle f : patch) in_patch.insert(f.idx());
    std::unordered_map<int, HalfedgeHandle> rim_from;  // from-vertex -> rim halfedge (inside the patch)
    std::vector<VertexHandle> verts;
    for (FaceHandle f : patch) {
      for (HalfedgeHandle h : mesh_.fh_range(f)) {
        const VertexHandle v = mesh_.from_vertex_handle(h);
        if (mesh_.is_boundary(v)) return 0;  // touches the mesh border: the hole would not be a loop
        verts.push_back(v);
        const FaceHandle g = mesh_.opposite_face_handle(h);
        if (in_patch.count(g.idx())) continue;
        if (!rim_from.emplace(v.idx(), h).second) return 0;  // the rim passes a vertex twice
      }
    }
    if (rim_from.size() < 4) return 0;
    std::vector<HalfedgeHandle> rim{rim_from.begin()->second};
    // Start at the rim halfedge of the lowest from-vertex (deterministic), then follow the loop.
    for (const auto& [v, h] : rim_from)
      if (v < mesh_.from_vertex_handle(rim.front()).idx()) rim.front() = h;
    while (rim.size() <= rim_from.size()) {
      const auto it = rim_from.find(mesh_.to_vertex_handle(rim.back()).idx());
      if (it == rim_from.end()) return 0;
      if (it->second == rim.front()) break;
      rim.push_back(it->second);
    }
    if (rim.size() != rim_from.size()) return 0;  // more than one loop: an annulus
    Vec3 centre(0, 0, 0);
    for (HalfedgeHandle h : rim) centre += mesh_.point(mesh_.from_vertex_handle(h));
    centre /= static_cast<double>(rim.size());
    if (cloud_distance(centre) > edge_) return 0;
    std::vector<Tri> before, after;
    size_t folds_before = 0, folds_after = 0;
    for (FaceHandle f : patch) {
      before.push_back(face_points(mesh_, f));
      for (FaceHandle g : mesh_.ff_range(f))
        folds_before += folded(before.back(), face_points(mesh_, g)) * (in_patch.count(g.idx()) ? 1 : 2);
    }
    for (size_t k = 0; k < rim.size(); ++k) {
      const HalfedgeHandle h = rim[k];
      after.push_back(
          {mesh_.point(mesh_.from_vertex_handle(h)), mesh_.point(mesh_.to_vertex_handle(h)), centre});
      folds_after += 2 * folded(after.back(), face_points(mesh_, mesh_.opposite_face_handle(h)));
    }
    for (size_t k = 0; k < after.size(); ++k)
      folds_after += 2 * folded(after[k], after[(k + 1) % after.size()]);
    if (!better(before, after, folds_before, folds_after)) return 0;
    std::vector<std::array<VertexHandle, 3>> old_faces;
    for (FaceHandle f : patch) {
      auto it = mesh_.fv_begin(f);
      const VertexHandle x = *it++, y = *it++, z = *it;
      old_faces.push_back({x, y, z});
    }
    std::vector<std::array<VertexHandle, 3>> fan;
    for (FaceHandle f : patch) mesh_.delete_face(f, false);
    const VertexHandle c = mesh_.add_vertex(centre);
    for (HalfedgeHandle h : rim) fan.push_back({mesh_.from_vertex_handle(h), mesh_.to_vertex_handle(h), c});
    if (!add_all_or_none(mesh_, fan)) {
      mesh_.delete_vertex(c, false);
      const bool restored = add_all_or_none(mesh_, old_faces);
      EF_CHECK(restored, "mend: the faces of a refused re-growth could not be restored");
      renormal_last(old_faces.size());
      return 0;
    }
    renormal_last(fan.size());
    for (VertexHandle v : verts)
      if (!mesh_.status(v).deleted() && mesh_.is_isolated(v)) mesh_.delete_vertex(v, false);
    return fan.size();
  }

 private:
  static size_t folded(const Tri& x, const Tri& y) {
    return OpenMesh::dot(unit_normal(x), unit_normal(y)) < 0 ? 1 : 0;
  }
  Tri points(const std::array<VertexHandle, 3>& t) const {
    return {mesh_.point(t[0]), mesh_.point(t[1]), mesh_.point(t[2])};
  }
  std::vector<Tri> around(VertexHandle v) const {
    std::vector<Tri> ts;
    for (FaceHandle f : mesh_.vf_range(v)) ts.push_back(face_points(mesh_, f));
    return ts;
  }
  void renormal_last(size_t n) {
    for (size_t i = mesh_.n_faces() - n; i < mesh_.n_faces(); ++i) {
      const FaceHandle f(static_cast<int>(i));
      if (edgefront::is_live(mesh_, f)) mesh_.set_normal(f, mesh_.calc_face_normal(f));
    }
  }

  Mesh& mesh_;
  const RepairOptions& o_;
  const ReferenceNormals& ref_;
  double edge_;
  double min_area_;
};

/// True when the geometry itself shows that `patch` is wrong, not only the reference: one of its
/// faces is folded against a neighbour (n.n' < 0) or lies on the mesh border (a flap). A smooth
/// patch inside the surface that the reference rejects is left: there the reference may be the
/// one that is wrong (noise, a wall thinner than its sampling), and re-shaping the mesh to please
/// it would distort a right surface.
bool shows_a_defect(const Mesh& mesh, const std::vector<FaceHandle>& patch) {
  for (FaceHandle f : patch) {
    const Vec3 n = unit_normal(face_points(mesh, f));
    for (HalfedgeHandle h : mesh.fh_range(f)) {
      const FaceHandle g = mesh.opposite_face_handle(h);
      if (!g.is_valid() || OpenMesh::dot(n, unit_normal(face_points(mesh, g))) < 0) return true;
    }
  }
  return false;
}

/// The edge-connected groups of misfit faces that show a defect (`shows_a_defect`) of at most `max_faces`
/// faces, by lowest face.
std::vector<std::vector<FaceHandle>> small_rejected_patches(const Mesh& mesh, const Mender& m,
                                                            size_t max_faces) {
  std::vector<char> bad(mesh.n_faces(), 0), seen(mesh.n_faces(), 0);
  for (FaceHandle f : mesh.faces()) bad[static_cast<size_t>(f.idx())] = m.misfits(f);
  std::vector<std::vector<FaceHandle>> out;
  for (FaceHandle f : mesh.faces()) {
    if (!bad[static_cast<size_t>(f.idx())] || seen[static_cast<size_t>(f.idx())]) continue;
    std::vector<FaceHandle> patch{f};
    seen[static_cast<size_t>(f.idx())] = 1;
    for (size_t q = 0; q < patch.size(); ++q) {
      for (FaceHandle g : mesh.ff_range(patch[q])) {
        if (!bad[static_cast<size_t>(g.idx())] || seen[static_cast<size_t>(g.idx())]) continue;
        seen[static_cast<size_t>(g.idx())] = 1;
        patch.push_back(g);
      }
    }
    if (patch.size() <= max_faces && shows_a_defect(mesh, patch)) out.push_back(std::move(patch));
  }
  return out;
}

}  // namespace

void mend_patches(Mesh& mesh, const RepairOptions& o, RepairReport& report) {
  if (!o.detect.reference || o.mend_patches == 0 || mesh.faces().begin() == mesh.faces().end()) return;
  Mender m(mesh, o, mean_edge_length(mesh));
  constexpr int kRounds = 3;  // each round can expose a neighbour's fold; 3 settle the vault meshes
  for (int round = 0; round < kRounds; ++round) {
    bool changed = false;
    for (const std::vector<FaceHandle>& patch : small_rejected_patches(mesh, m, o.mend_patches)) {
      // 1. Re-triangulate: swap an edge of a rejected face for the other diagonal of its quad.
      std::vector<FaceHandle> live;
      for (FaceHandle f : patch) {
        if (!edgefront::is_live(mesh, f) || !m.misfits(f)) continue;
        bool flipped = false;
        for (HalfedgeHandle h : mesh.fh_range(f)) {
          if (m.flip_edge(h)) {
            ++report.mend_edges_flipped;
            changed = flipped = true;
            break;  // f is gone
          }
        }
        if (!flipped) live.push_back(f);
      }
      // 2. Move a vertex: turn a folded page back about its hinge, or smooth an interior one.
      for (FaceHandle f : live) {
        if (!edgefront::is_live(mesh, f) || !m.misfits(f)) continue;
        std::vector<VertexHandle> corners(mesh.fv_range(f).begin(), mesh.fv_range(f).end());
        for (VertexHandle v : corners) {
          if (m.move_vertex(v, m.unfold_targets(v))) {
            ++report.mend_vertices_moved;
            changed = true;
            break;
          }
        }
      }
      // 3. Cut what is still rejected out and re-grow it from its rim.
      std::vector<FaceHandle> rest;
      for (FaceHandle f : patch)
        if (edgefront::is_live(mesh, f) && m.misfits(f)) rest.push_back(f);
      if (rest.size() < 2 || rest.size() != patch.size())
        continue;  // a single face is its own fan; a changed patch waits for the next round
      const size_t added = m.regrow(rest);
      if (added > 0) {
        report.mend_faces_cut_out += rest.size();
        report.faces_removed += rest.size();
        report.mend_faces_added += added;
        changed = true;
      }
    }
    if (!changed) break;
  }
}

}  // namespace twist::detail
