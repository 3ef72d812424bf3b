// Labelling every face keep/flip by the reference normals with a minimum cut (see repair.h,
// `label_by_reference`).

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "detail/geometry.h"
#include "edgefront/error.h"
#include "twist/repair.h"

namespace twist {

using edgefront::EdgeHandle;
using edgefront::FaceHandle;
using edgefront::HalfedgeHandle;
using edgefront::InvalidInput;
using edgefront::Mesh;
using edgefront::Vec3;

namespace {

/// Maximum flow / minimum cut on a graph with real capacities (Dinic: shortest augmenting paths
/// in level graphs, the depth-first search iterative so long paths cannot exhaust the stack).
/// Deterministic: the edge order fixes the result.
class MaxFlow {
 public:
  MaxFlow(size_t nodes, double eps) : head_(nodes, -1), eps_(eps) {}
  /// An edge u -> v with capacity `forward` and v -> u with capacity `backward`.
  void add(int u, int v, double forward, double backward) {
    push(u, v, forward);
    push(v, u, backward);
  }
  double run(int s, int t) {
    double total = 0;
    while (levels(s, t)) total += blocking_flow(s, t);
    return total;
  }
  /// Nodes from which `t` is reachable in the residual graph (after `run`).
  std::vector<char> reaches(int t) const {
    std::vector<char> mark(head_.size(), 0);
    std::vector<int> queue{t};
    mark[static_cast<size_t>(t)] = 1;
    for (size_t q = 0; q < queue.size(); ++q) {
      const int v = queue[q];
      for (int e = head_[static_cast<size_t>(v)]; e >= 0; e = next_[static_cast<size_t>(e)]) {
        // e runs v -> w; its pair runs w -> v: w reaches v when the pair has capacity left.
        const int w = to_[static_cast<size_t>(e)];
        if (mark[static_cast<size_t>(w)] || cap_[static_cast<size_t>(e ^ 1)] <= eps_) continue;
        mark[static_cast<size_t>(w)] = 1;
        queue.push_back(w);
      }
    }
    return mark;
  }

 private:
  void push(int u, int v, double cap) {
    to_.push_back(v);
    cap_.push_back(cap);
    next_.push_back(head_[static_cast<size_t>(u)]);
    head_[static_cast<size_t>(u)] = static_cast<int>(to_.size()) - 1;
  }
  bool levels(int s, int t) {
    level_.assign(head_.size(), -1);
    std::vector<int> queue{s};
    level_[static_cast<size_t>(s)] = 0;
    for (size_t q = 0; q < queue.size(); ++q) {
      const int u = queue[q];
      for (int e = head_[static_cast<size_t>(u)]; e >= 0; e = next_[static_cast<size_t>(e)]) {
        const int v = to_[static_cast<size_t>(e)];
        if (level_[static_cast<size_t>(v)] >= 0 || cap_[static_cast<size_t>(e)] <= eps_) continue;
        level_[static_cast<size_t>(v)] = level_[static_cast<size_t>(u)] + 1;
        queue.push_back(v);
      }
    }
    return level_[static_cast<size_t>(t)] >= 0;
  }
  double blocking_flow(int s, int t) {
    std::vector<int> it(head_);
    std::vector<int> path;  // edges from s
    double total = 0;
    int u = s;
    for (;;) {
      if (u == t) {
        double b = std::numeric_limits<double>::infinity();
        for (int e : path) b = std::min(b, cap_[static_cast<size_t>(e)]);
        for (int e : path) {
          cap_[static_cast<size_t>(e)] -= b;
          cap_[static_cast<size_t>(e ^ 1)] += b;
        }
        total += b;
        size_t k = 0;
        while (k < path.size() && cap_[static_cast<size_t>(path[k])] > eps_) ++k;
        path.resize(k);
        u = k == 0 ? s : to_[static_cast<size_t>(path.back())];
        continue;
      }
      int& e = it[static_cast<size_t>(u)];
      while (e >= 0 && (cap_[static_cast<size_t>(e)] <= eps_ ||
                        level_[static_cast<size_t>(to_[static_cast<size_t>(e)])] != level_[static_cast<size_t>(u)] + 1)) {
        e = next_[static_cast<size_t>(e)];
      }
      if (e >= 0) {
        path.push_back(e);
        u = to_[static_cast<size_t>(e)];
        continue;
      }
      level_[static_cast<size_t>(u)] = -1;  // dead end
      if (u == s) break;
      const int back = path.back();
      path.pop_back();
      u = to_[static_cast<size_t>(back ^ 1)];
      it[static_cast<size_t>(u)] = next_[static_cast<size_t>(it[static_cast<size_t>(u)])];
    }
    return total;
  }

  std::vector<int> head_, next_, to_, level_;
  std::vector<double> cap_;
  double eps_;
};

}  // namespace

ReferenceLabelling label_by_reference(const Mesh& mesh, const RepairOptions& o) {
  detail::check_mesh(mesh, "twist::label_by_reference");
  if (!o.detect.reference) throw InvalidInput("twist::label_by_reference: no reference normals (options.detect.reference)");
  if (!(o.cuts.cut_cost >= 0 && o.cuts.cut_cost <= 100))
    throw InvalidInput("twist::label_by_reference: option cuts.cut_cost must lie in [0, 100]");
  if (o.cuts.min_component_faces < 1)
    throw InvalidInput("twist::label_by_reference: option cuts.min_component_faces must be >= 1");
  DetectOptions d = o.detect;
  d.incremental.restrict_to.reset();
  d.incremental.face_grid = nullptr;
  validate_detect_options(mesh, d);
  const ReferenceNormals& reference = *o.detect.reference;
  const double h = d.mean_edge_length > 0 ? d.mean_edge_length : detail::mean_edge_length(mesh);

  ReferenceLabelling out;
  const size_t nf = mesh.n_faces();
  std::vector<double> weight(nf, 0.0);  // area x vote: > 0 agrees, < 0 disagrees
  double total_area = 0;
  for (FaceHandle f : mesh.faces()) {
    if (mesh.status(f).deleted()) continue;
    const auto p = detail::face_points(mesh, f);
    const double a = detail::area(p);
    total_area += a;
    const Vec3 n = detail::unit_normal(p);
    const int vote = n.sqrnorm() > 0 ? reference_vote(reference, d, detail::centroid(p), n, h) : 0;
    weight[static_cast<size_t>(f.idx())] = a * vote;
    if (vote < 0) out.wrong_area_before += a;
    if (vote == 0) out.undecided_area += a;
    ++out.faces_voted;
  }
  out.total_area = total_area;

  // Nodes: faces by index, then the source (keep) and the sink (flip).
  const int s = static_cast<int>(nf), t = static_cast<int>(nf) + 1;
  MaxFlow flow(nf + 2, 1e-12 * std::max(total_area, std::numeric_limits<double>::min()));
  for (FaceHandle f : mesh.faces()) {
    if (mesh.status(f).deleted()) continue;
    const double w = weight[static_cast<size_t>(f.idx())];
    if (w > 0) flow.add(s, f.idx(), w, 0);
    if (w < 0) flow.add(f.idx(), t, -w, 0);
  }
  const double per_length = o.cuts.cut_cost * h;
  for (EdgeHandle e : mesh.edges()) {
    if (mesh.status(e).deleted() || mesh.is_boundary(e)) continue;
    const HalfedgeHandle he = mesh.halfedge_handle(e, 0);
    const double c = per_length * mesh.calc_edge_length(e);
    flow.add(mesh.face_handle(he).idx(), mesh.opposite_face_handle(he).idx(), c, c);
  }
  flow.run(s, t);
  // Flip the faces that still reach the sink: the smallest flip set of a minimum cut (faces no
  // vote decides and no cut needs stay as they are).
  const std::vector<char> flip = flow.reaches(t);

  // Regions: edge-connected flip faces, lowest face index first.
  std::vector<int> region_of(nf, -1);
  for (FaceHandle f : mesh.faces()) {
    if (mesh.status(f).deleted() || !flip[static_cast<size_t>(f.idx())] || region_of[static_cast<size_t>(f.idx())] >= 0) continue;
    const int r = static_cast<int>(out.regions.size());
    std::vector<FaceHandle> faces{f};
    region_of[static_cast<size_t>(f.idx())] = r;
    size_t cut = 0;
    double vote = 0;
    for (size_t q = 0; q < faces.size(); ++q) {
      vote += weight[static_cast<size_t>(faces[q].idx())];
      for (HalfedgeHandle hh : mesh.fh_range(faces[q])) {
        const FaceHandle g = mesh.opposite_face_handle(hh);
        if (!g.is_valid()) continue;
        if (!flip[static_cast<size_t>(g.idx())]) {
          ++cut;
          continue;
        }
        if (region_of[static_cast<size_t>(g.idx())] >= 0) continue;
        region_of[static_cast<size_t>(g.idx())] = r;
        faces.push_back(g);
      }
    }
    out.regions.push_back(std::move(faces));
    out.cut_edges.push_back(cut);
    out.votes.push_back(vote);
  }
  // A region that would stand alone as a tiny piece (it needs a cut and has fewer than
  // min_component_faces faces) stays as it is: a tiny component is worse than a small wrong patch.
  size_t kept = 0;
  for (size_t r = 0; r < out.regions.size(); ++r) {
    if (out.cut_edges[r] > 0 && out.regions[r].size() < o.cuts.min_component_faces) {
      ++out.regions_too_small;
      continue;
    }
    if (kept != r) {
      out.regions[kept] = std::move(out.regions[r]);
      out.cut_edges[kept] = out.cut_edges[r];
      out.votes[kept] = out.votes[r];
    }
    ++kept;
  }
  out.regions.resize(kept);
  out.cut_edges.resize(kept);
  out.votes.resize(kept);
  // The wrong area once the regions are flipped.
  std::vector<char> flipped(nf, 0);
  for (const auto& region : out.regions)
    for (FaceHandle f : region) flipped[static_cast<size_t>(f.idx())] = 1;
  for (FaceHandle f : mesh.faces()) {
    if (mesh.status(f).deleted()) continue;
    const double w = weight[static_cast<size_t>(f.idx())];
    if (flipped[static_cast<size_t>(f.idx())] ? w > 0 : w < 0) out.wrong_area_after += std::abs(w);
  }
  return out;
}

}  // namespace twist
