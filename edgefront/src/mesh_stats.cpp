#include "edgefront/mesh_stats.h"

#include <algorithm>
#include <array>
#include <iomanip>
#include <limits>
#include <numeric>
#include <sstream>

#include "edgefront/error.h"
#include "edgefront/union_find.h"

namespace edgefront {

ComponentLabels connected_components(const Mesh& mesh) {
  const size_t nv = mesh.n_vertices();
  UnionFind sets(nv);
  for (size_t i = 0; i < mesh.n_edges(); ++i) {
    const EdgeHandle e(static_cast<int>(i));
    if (mesh.status(e).deleted()) continue;
    const HalfedgeHandle h = mesh.halfedge_handle(e, 0);
    sets.unite(static_cast<size_t>(mesh.from_vertex_handle(h).idx()),
               static_cast<size_t>(mesh.to_vertex_handle(h).idx()));
  }
  ComponentLabels labels;
  labels.vertex_component.assign(nv, -1);
  std::vector<int> label_of_root(nv, -1);
  for (size_t i = 0; i < nv; ++i) {
    if (mesh.status(VertexHandle(static_cast<int>(i))).deleted()) continue;
    const size_t root = sets.find(i);
    if (label_of_root[root] < 0) label_of_root[root] = static_cast<int>(labels.count++);
    labels.vertex_component[i] = label_of_root[root];
  }
  return labels;
}

MeshStats compute_stats(const Mesh& mesh) {
  MeshStats s;
  const ComponentLabels labels = connected_components(mesh);
  s.components = labels.count;
  s.per_component.resize(labels.count);
  std::vector<long> component_edges(labels.count, 0);

  // Vertices: counts, bounding box, valences, manifoldness.
  bool first = true;
  for (size_t i = 0; i < mesh.n_vertices(); ++i) {
    const VertexHandle v(static_cast<int>(i));
    if (mesh.status(v).deleted()) continue;
    ++s.vertices;
    ++s.per_component[labels.vertex_component[i]].vertices;
    const Vec3& p = mesh.point(v);
    if (first) {
      s.bbox_min = s.bbox_max = p;
      first = false;
    } else {
      s.bbox_min.minimize(p);
      s.bbox_max.maximize(p);
    }
    size_t valence = 0, boundary_out = 0;
    if (mesh.is_isolated(v)) {
      ++s.isolated_vertices;
    } else {
      for (const HalfedgeHandle h : mesh.voh_range(v)) {
        ++valence;
        if (mesh.is_boundary(h)) ++boundary_out;
      }
    }
    if (boundary_out > 1) ++s.nonmanifold_vertices;
    if (s.valence_histogram.size() <= valence) s.valence_histogram.resize(valence + 1, 0);
    ++s.valence_histogram[valence];
  }
  s.bbox_diagonal = (s.bbox_max - s.bbox_min).norm();

  // Edges: lengths and per-component counts.
  double length_sum = 0;
  for (size_t i = 0; i < mesh.n_edges(); ++i) {
    const EdgeHandle e(static_cast<int>(i));
    if (mesh.status(e).deleted()) continue;
    const double length = mesh.calc_edge_length(e);
    if (s.edges == 0) {
      s.min_edge_length = s.max_edge_length = length;
    } else {
      s.min_edge_length = std::min(s.min_edge_length, length);
      s.max_edge_length = std::max(s.max_edge_length, length);
    }
    ++s.edges;
    length_sum += length;
    const int c = labels.vertex_component[mesh.from_vertex_handle(mesh.halfedge_handle(e, 0)).idx()];
    EF_CHECK(c >= 0, "a live edge has a deleted vertex");
    ++component_edges[c];
  }
  if (s.edges > 0) s.mean_edge_length = length_sum / static_cast<double>(s.edges);

  // Faces: degenerate and duplicate faces, per-component counts.
  const double degenerate_area = kDegenerateAreaFactor * s.bbox_diagonal * s.bbox_diagonal;
  std::vector<std::array<int, 3>> keys;  // sorted vertex triples, for counting duplicates
  keys.reserve(mesh.n_faces());
  for (size_t i = 0; i < mesh.n_faces(); ++i) {
    const FaceHandle f(static_cast<int>(i));
    if (mesh.status(f).deleted()) continue;
    ++s.faces;
    std::array<int, 3> key{};
    Vec3 corner[3];
    HalfedgeHandle h = mesh.halfedge_handle(f);
    for (int k = 0; k < 3; ++k) {
      const VertexHandle v = mesh.to_vertex_handle(h);
      key[k] = v.idx();
      corner[k] = mesh.point(v);
      h = mesh.next_halfedge_handle(h);
    }
    const int c = labels.vertex_component[key[0]];
    EF_CHECK(c >= 0, "a live face has a deleted vertex");
    ++s.per_component[c].faces;
    const double area = 0.5 * cross(corner[1] - corner[0], corner[2] - corner[0]).norm();
    if (area <= degenerate_area) ++s.degenerate_faces;
    std::sort(key.begin(), key.end());
    keys.push_back(key);
  }

  std::sort(keys.begin(), keys.end());
  for (size_t i = 1; i < keys.size(); ++i) s.duplicate_faces += keys[i] == keys[i - 1] ? 1 : 0;

  // Border loops: cycles of boundary halfedges.
  std::vector<char> visited(mesh.n_halfedges(), 0);
  for (size_t i = 0; i < mesh.n_halfedges(); ++i) {
    const HalfedgeHandle start(static_cast<int>(i));
    if (visited[i] || mesh.status(start).deleted() || !mesh.is_boundary(start)) continue;
    HalfedgeHandle h = start;
    size_t steps = 0;
    do {
      visited[h.idx()] = 1;
      h = mesh.next_halfedge_handle(h);
      EF_CHECK(++steps <= mesh.n_halfedges(), "a boundary halfedge cycle does not close");
      EF_CHECK(h.is_valid() && mesh.is_boundary(h),
               "the next halfedge of a boundary halfedge is not on the boundary");
    } while (h != start);
    ++s.border_loops;
    const int c = labels.vertex_component[mesh.from_vertex_handle(start).idx()];
    EF_CHECK(c >= 0, "a boundary halfedge starts at a deleted vertex");
    ++s.per_component[c].border_loops;
  }

  s.euler_characteristic =
      static_cast<long>(s.vertices) - static_cast<long>(s.edges) + static_cast<long>(s.faces);
  for (size_t c = 0; c < labels.count; ++c) {
    MeshStats::Component& comp = s.per_component[c];
    comp.euler = static_cast<long>(comp.vertices) - component_edges[c] + static_cast<long>(comp.faces);
    comp.genus = (2.0 - static_cast<double>(comp.euler) - static_cast<double>(comp.border_loops)) / 2.0;
  }
  return s;
}

std::string format_stats(const MeshStats& s) {
  std::ostringstream out;
  out << std::setprecision(6);
  const auto row = [&](const char* label) -> std::ostream& {
    return out << std::left << std::setw(22) << label;
  };
  const auto point = [&](const Vec3& p) {
    std::ostringstream o;
    o << std::setprecision(6) << "(" << p[0] << ", " << p[1] << ", " << p[2] << ")";
    return o.str();
  };
  row("vertices:") << s.vertices << " (" << s.isolated_vertices << " isolated, " << s.nonmanifold_vertices
                   << " non-manifold)\n";
  row("faces:") << s.faces << " (" << s.degenerate_faces << " degenerate, " << s.duplicate_faces
                << " duplicate)\n";
  row("edges:") << s.edges << "\n";
  row("euler characteristic:") << s.euler_characteristic << "\n";
  row("components:") << s.components << "\n";
  row("border loops:") << s.border_loops << "\n";
  row("bounding box:") << point(s.bbox_min) << " to " << point(s.bbox_max) << ", diagonal " << s.bbox_diagonal
                       << "\n";
  row("edge length:") << "mean " << s.mean_edge_length << ", min " << s.min_edge_length << ", max "
                      << s.max_edge_length << "\n";
  row("valence histogram:");
  bool any = false;
  for (size_t k = 0; k < s.valence_histogram.size(); ++k) {
    if (s.valence_histogram[k] == 0) continue;
    out << (any ? ", " : "") << k << ": " << s.valence_histogram[k];
    any = true;
  }
  out << (any ? "" : "(none)") << "\n";
  constexpr size_t kMaxListed = 10;
  for (size_t c = 0; c < s.per_component.size() && c < kMaxListed; ++c) {
    const MeshStats::Component& comp = s.per_component[c];
    out << "  component " << c << ": " << comp.vertices << " vertices, " << comp.faces << " faces, "
        << comp.border_loops << " border loops, euler " << comp.euler;
    // Genus is a surface property: an isolated vertex (a point of a cloud) has none.
    if (comp.faces > 0) {
      out << ", genus " << comp.genus;
    } else {
      out << ", no faces";
    }
    out << "\n";
  }
  if (s.per_component.size() > kMaxListed) {
    out << "  ... and " << (s.per_component.size() - kMaxListed) << " more components\n";
  }
  return out.str();
}

}  // namespace edgefront
