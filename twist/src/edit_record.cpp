// Edit records: the reference replay on plain arrays, and the record that brings a host's plain
// mesh up to the mirror a repair worked on (diffing the two, with the copy journal).

#include "twist/edit_record.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "detail/geometry.h"
#include "detail/host_mirror.h"
#include "edgefront/error.h"

namespace twist {

using edgefront::FaceHandle;
using edgefront::HalfedgeHandle;
using edgefront::InvalidInput;
using edgefront::Mesh;
using edgefront::VertexHandle;

namespace {

[[noreturn]] void refuse(const std::string& what) { throw InvalidInput("twist::apply: " + what + " (nothing applied)"); }

std::string face_name(int f) { return "face " + std::to_string(f); }

}  // namespace

void apply(const EditRecord& r, std::vector<double>& vertices, std::vector<int>& faces) {
  if (vertices.size() != 3 * r.vertices_before) {
    refuse("the record expects " + std::to_string(r.vertices_before) + " vertices, the array has " +
           std::to_string(vertices.size()) + " values");
  }
  if (faces.size() != 3 * r.faces_before) {
    refuse("the record expects " + std::to_string(r.faces_before) + " face slots, the array has " + std::to_string(faces.size()) +
           " values");
  }
  const long nv_after = static_cast<long>(r.vertices_after());
  auto vertex_ok = [&](int v) { return v >= 0 && v < nv_after; };
  auto live_face = [&](int f, const char* what) {
    if (f < 0 || static_cast<size_t>(f) >= r.faces_before || faces[3 * static_cast<size_t>(f)] < 0) {
      refuse(std::string(what) + " " + face_name(f) + " is not a face of the arrays");
    }
  };
  for (size_t i = 0; i < r.vertices_added.size(); ++i) {
    const VertexAdded& a = r.vertices_added[i];
    if (a.original < -1 || a.original >= static_cast<long>(r.vertices_before + i)) {
      refuse("added vertex " + std::to_string(r.vertices_before + i) + " copies vertex " + std::to_string(a.original) +
             ", which does not exist before it");
    }
    for (double x : a.position) {
      if (!std::isfinite(x)) refuse("added vertex " + std::to_string(r.vertices_before + i) + " has a non-finite position");
    }
  }
  for (const VertexMoved& m : r.vertices_moved) {
    if (!vertex_ok(m.vertex)) refuse("moved vertex " + std::to_string(m.vertex) + " does not exist");
    for (double x : m.position) {
      if (!std::isfinite(x)) refuse("vertex " + std::to_string(m.vertex) + " is moved to a non-finite position");
    }
  }
  std::vector<char> flipped(r.faces_before, 0);
  for (int f : r.faces_flipped) {
    live_face(f, "flipped");
    flipped[static_cast<size_t>(f)] = 1;
  }
  for (int f : r.faces_removed) live_face(f, "removed");
  auto row_after_flip = [&](int f) {
    const size_t base = 3 * static_cast<size_t>(f);
    return flipped[static_cast<size_t>(f)] ? std::array<int, 3>{faces[base], faces[base + 2], faces[base + 1]}
                                           : std::array<int, 3>{faces[base], faces[base + 1], faces[base + 2]};
  };
  // The replacements of one face apply together, each to the corner that held `from`.
  struct Rewired {
    std::array<int, 3> before, after;
    std::array<bool, 3> done{false, false, false};
  };
  std::map<int, Rewired> rewired;
  for (const CornerReplaced& c : r.corners_replaced) {
    live_face(c.face, "re-connected");
    if (!vertex_ok(c.to)) refuse(face_name(c.face) + ": vertex " + std::to_string(c.to) + " does not exist");
    auto it = rewired.find(c.face);
    if (it == rewired.end()) {
      const std::array<int, 3> row = row_after_flip(c.face);
      it = rewired.emplace(c.face, Rewired{row, row}).first;
    }
    Rewired& w = it->second;
    size_t k = 0;
    while (k < 3 && (w.done[k] || w.before[k] != c.from)) ++k;
    if (k == 3) refuse(face_name(c.face) + " has no corner " + std::to_string(c.from) + " to replace");
    w.after[k] = c.to;
    w.done[k] = true;
  }
  for (const auto& [f, w] : rewired) {
    const auto& t = w.after;
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) refuse(face_name(f) + " would repeat a vertex");
  }
  for (size_t i = 0; i < r.faces_added.size(); ++i) {
    const auto& t = r.faces_added[i];
    for (int v : t) {
      if (!vertex_ok(v)) refuse("added " + face_name(static_cast<int>(r.faces_before + i)) + " uses vertex " + std::to_string(v));
    }
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
      refuse("added " + face_name(static_cast<int>(r.faces_before + i)) + " repeats a vertex");
    }
  }

  // Checked: apply in the documented order.
  vertices.reserve(3 * r.vertices_after());
  for (const VertexAdded& a : r.vertices_added) vertices.insert(vertices.end(), a.position.begin(), a.position.end());
  for (const VertexMoved& m : r.vertices_moved) {
    std::copy(m.position.begin(), m.position.end(), vertices.begin() + 3 * static_cast<std::ptrdiff_t>(m.vertex));
  }
  for (int f : r.faces_flipped) std::swap(faces[3 * static_cast<size_t>(f) + 1], faces[3 * static_cast<size_t>(f) + 2]);
  for (const auto& [f, w] : rewired) std::copy(w.after.begin(), w.after.end(), faces.begin() + 3 * static_cast<std::ptrdiff_t>(f));
  for (int f : r.faces_removed) std::fill_n(faces.begin() + 3 * static_cast<std::ptrdiff_t>(f), 3, -1);
  faces.reserve(3 * r.faces_after());
  for (const auto& t : r.faces_added) faces.insert(faces.end(), t.begin(), t.end());
}

std::vector<int> compact_faces(std::vector<int>& faces) {
  std::vector<int> row(faces.size() / 3, -1);
  size_t out = 0;
  for (size_t i = 0; i < row.size(); ++i) {
    if (faces[3 * i] < 0) continue;
    row[i] = static_cast<int>(out);
    for (size_t k = 0; k < 3; ++k) faces[3 * out + k] = faces[3 * i + k];
    ++out;
  }
  faces.resize(3 * out);
  return row;
}

// ---------------------------------------------------------------------------------------------
// The host next to its mirror

namespace detail {

void HostMirror::map_face(size_t slot, int face, const Mesh& mirror) {
  if (slot >= mirror_of_face.size()) {
    mirror_of_face.resize(slot + 1, -1);
    mirror_corners.resize(3 * (slot + 1), -1);
  }
  const int old = mirror_of_face[slot];
  if (old >= 0 && static_cast<size_t>(old) < host_of_face.size() && host_of_face[static_cast<size_t>(old)] == static_cast<int>(slot)) {
    host_of_face[static_cast<size_t>(old)] = -1;
  }
  mirror_of_face[slot] = face;
  if (face < 0) {
    std::fill_n(mirror_corners.begin() + 3 * static_cast<std::ptrdiff_t>(slot), 3, -1);
    return;
  }
  if (host_of_face.size() < mirror.n_faces()) host_of_face.resize(mirror.n_faces(), -1);
  host_of_face[static_cast<size_t>(face)] = static_cast<int>(slot);
  HalfedgeHandle he = mirror.halfedge_handle(FaceHandle(face));
  for (size_t k = 0; k < 3; ++k) {
    mirror_corners[3 * slot + k] = mirror.to_vertex_handle(he).idx();
    he = mirror.next_halfedge_handle(he);
  }
}

HostMirror host_of_conversion(const edgefront::VertexArrayView& vertices, const edgefront::FaceArrayView& faces,
                              edgefront::ArrayMesh& converted) {
  HostMirror h;
  const size_t n = vertices.rows();
  h.vertices.resize(3 * n);
  for (size_t i = 0; i < n; ++i) {
    for (size_t k = 0; k < 3; ++k) h.vertices[3 * i + k] = vertices.at(i, k);
  }
  h.faces.resize(faces.size());
  for (size_t r = 0; r < faces.rows(); ++r) {
    for (size_t k = 0; k < 3; ++k) h.faces[3 * r + k] = static_cast<int>(faces.at(r, k));
  }
  Mesh& mesh = converted.mesh;
  h.mirror_of_vertex.resize(n);
  h.host_of_vertex.assign(mesh.n_vertices(), -1);
  for (size_t i = 0; i < n; ++i) h.mirror_of_vertex[i] = h.host_of_vertex[i] = static_cast<int>(i);
  h.mirror_of_face.assign(converted.face_of_row.size(), -1);
  h.mirror_corners.assign(3 * converted.face_of_row.size(), -1);
  h.host_of_face.assign(mesh.n_faces(), -1);
  for (size_t r = 0; r < converted.face_of_row.size(); ++r) {
    h.map_face(r, converted.face_of_row[r], mesh);
    // A face with a pinched vertex's copy differs from the host's row: the first record says so.
    for (size_t k = 0; k < 3; ++k) {
      if (h.mirror_corners[3 * r + k] >= static_cast<int>(n)) std::fill_n(h.mirror_corners.begin() + 3 * static_cast<std::ptrdiff_t>(r), 3, -1);
    }
  }
  OpenMesh::VPropHandleT<int> journal;
  if (!mesh.get_property_handle(journal, kCopyJournal)) mesh.add_property(journal, kCopyJournal);
  for (size_t i = n; i < mesh.n_vertices(); ++i) {
    mesh.property(journal, VertexHandle(static_cast<int>(i))) = converted.vertex_row[i] + 1;
  }
  h.mirror_vertices_seen = n;  // the pinched copies are new to the host
  h.mirror_faces_seen = mesh.n_faces();
  return h;
}

std::array<int, 3> host_corners(const HostMirror& host, const Mesh& mirror, FaceHandle f) {
  std::array<int, 3> t{-1, -1, -1};
  HalfedgeHandle h = mirror.halfedge_handle(f);
  for (size_t k = 0; k < 3; ++k) {
    t[k] = host.host_vertex(mirror.to_vertex_handle(h).idx());
    h = mirror.next_halfedge_handle(h);
  }
  return t;
}

namespace {

/// How the host's corners `a` become the mirror's `x`: flip or not, then which corners change.
/// The alignment matching most of `y` (x's roots: a copy counts as its original) wins; ties keep
/// the orientation.
void align(int slot, const std::array<int, 3>& a, const std::array<int, 3>& x, const std::array<int, 3>& y, EditRecord& r) {
  int best = -1, best_k = 0;
  bool best_flip = false;
  for (int flip = 0; flip < 2; ++flip) {
    const std::array<int, 3> b = flip ? std::array<int, 3>{a[0], a[2], a[1]} : a;
    for (int k = 0; k < 3; ++k) {
      int matches = 0;
      for (int i = 0; i < 3; ++i) matches += b[static_cast<size_t>(i)] == y[static_cast<size_t>((i + k) % 3)];
      if (matches > best) {
        best = matches;
        best_k = k;
        best_flip = flip;
      }
    }
  }
  const std::array<int, 3> b = best_flip ? std::array<int, 3>{a[0], a[2], a[1]} : a;
  if (best_flip) r.faces_flipped.push_back(slot);
  for (size_t i = 0; i < 3; ++i) {
    const int to = x[(i + static_cast<size_t>(best_k)) % 3];
    if (b[i] != to) r.corners_replaced.push_back(CornerReplaced{slot, b[i], to});
  }
}

}  // namespace

EditRecord bring_up_to_date(HostMirror& h, const Mesh& mirror) {
  EditRecord r;
  r.vertices_before = h.vertex_slots();
  r.faces_before = h.face_slots();
  const size_t nvm = mirror.n_vertices(), nfm = mirror.n_faces();
  std::vector<int> host_of_vertex = h.host_of_vertex;
  host_of_vertex.resize(nvm, -1);
  std::vector<int> root(nvm, -1);  // per new mirror vertex: the old host vertex it copies, or -1

  // 1. New vertices (appended in mirror order), each with the host vertex it copies: the copy
  // journal leads from a copy to its original (always an older vertex), through copies the host
  // never saw, to a vertex of the host.
  OpenMesh::VPropHandleT<int> journal;
  const bool has_journal = mirror.get_property_handle(journal, kCopyJournal);
  auto original_of = [&](size_t m) { return has_journal ? mirror.property(journal, VertexHandle(static_cast<int>(m))) - 1 : -1; };
  for (size_t m = h.mirror_vertices_seen; m < nvm; ++m) {
    if (host_of_vertex[m] >= 0) continue;
    int j = original_of(m);
    while (j >= 0 && static_cast<size_t>(j) < m) {
      const size_t uj = static_cast<size_t>(j);
      const int hv = host_of_vertex[uj];
      if (hv >= 0 && static_cast<size_t>(hv) < r.vertices_before) {
        root[m] = hv;
        break;
      }
      if (uj >= h.mirror_vertices_seen) {  // new here too: its root is known
        root[m] = root[uj];
        break;
      }
      j = original_of(uj);
    }
    const VertexHandle v(static_cast<int>(m));
    if (mirror.status(v).deleted()) continue;
    host_of_vertex[m] = static_cast<int>(r.vertices_before + r.vertices_added.size());
    const edgefront::Vec3& p = mirror.point(v);
    r.vertices_added.push_back(VertexAdded{root[m], {p[0], p[1], p[2]}});
  }

  // 2. Moved and deleted vertices of the host (the mirror's status and points read as arrays).
  const OpenMesh::Attributes::StatusInfo* vertex_status = nvm ? &mirror.status(VertexHandle(0)) : nullptr;
  const edgefront::Vec3* point = nvm ? &mirror.point(VertexHandle(0)) : nullptr;
  std::vector<int> unmapped_vertices;
  for (size_t i = 0; i < r.vertices_before; ++i) {
    const int m = h.mirror_of_vertex[i];
    if (m < 0) continue;
    if (vertex_status[m].deleted()) {
      r.vertices_removed.push_back(static_cast<int>(i));
      unmapped_vertices.push_back(static_cast<int>(i));
      continue;
    }
    const edgefront::Vec3& p = point[m];
    if (p[0] != h.vertices[3 * i] || p[1] != h.vertices[3 * i + 1] || p[2] != h.vertices[3 * i + 2]) {
      r.vertices_moved.push_back(VertexMoved{static_cast<int>(i), {p[0], p[1], p[2]}});
    }
  }

  // A live mirror face's corners in host indices (x), and with copies counted as the host vertex
  // they copy (y, -1 for a new point).
  auto corners = [&](FaceHandle f) {
    std::array<int, 3> x{};
    HalfedgeHandle he = mirror.halfedge_handle(f);
    for (size_t k = 0; k < 3; ++k) {
      x[k] = host_of_vertex[static_cast<size_t>(mirror.to_vertex_handle(he).idx())];
      he = mirror.next_halfedge_handle(he);
    }
    EF_CHECK(x[0] >= 0 && x[1] >= 0 && x[2] >= 0, "edit record: a live mirror face uses a vertex the host does not know");
    return x;
  };
  auto roots = [&](FaceHandle f) {
    std::array<int, 3> y{};
    HalfedgeHandle he = mirror.halfedge_handle(f);
    for (size_t k = 0; k < 3; ++k) {
      const size_t m = static_cast<size_t>(mirror.to_vertex_handle(he).idx());
      y[k] = static_cast<size_t>(host_of_vertex[m]) < r.vertices_before ? host_of_vertex[m] : root[m];
      he = mirror.next_halfedge_handle(he);
    }
    return y;
  };
  auto key_of = [](std::array<int, 3> t) {
    std::sort(t.begin(), t.end());
    return t;
  };

  // 3. Host faces: unchanged, changed in place, or gone (then perhaps re-added as a new face).
  std::vector<std::pair<int, int>> face_maps;  // (host slot, mirror face; -1 none)
  std::map<std::array<int, 3>, std::vector<int>> gone;  // by sorted corners, in slot order
  const OpenMesh::Attributes::StatusInfo* face_status = nfm ? &mirror.status(FaceHandle(0)) : nullptr;
  for (size_t s = 0; s < r.faces_before; ++s) {
    const std::array<int, 3> a{h.faces[3 * s], h.faces[3 * s + 1], h.faces[3 * s + 2]};
    if (a[0] < 0) continue;
    const int m = h.mirror_of_face[s];
    if (m < 0) {  // never in the mirror (a row the conversion dropped)
      r.faces_removed.push_back(static_cast<int>(s));
      continue;
    }
    const FaceHandle f(m);
    if (face_status[m].deleted()) {
      gone[key_of(a)].push_back(static_cast<int>(s));
      continue;
    }
    HalfedgeHandle he = mirror.halfedge_handle(f);
    bool as_mapped = true;  // the quick test: the corners it had when mapped
    for (size_t k = 0; k < 3; ++k) {
      as_mapped = as_mapped && mirror.to_vertex_handle(he).idx() == h.mirror_corners[3 * s + k];
      he = mirror.next_halfedge_handle(he);
    }
    if (as_mapped) continue;
    face_maps.emplace_back(static_cast<int>(s), m);  // note its corners again
    const std::array<int, 3> x = corners(f);
    const bool same = (x[0] == a[0] && x[1] == a[1] && x[2] == a[2]) || (x[1] == a[0] && x[2] == a[1] && x[0] == a[2]) ||
                      (x[2] == a[0] && x[0] == a[1] && x[1] == a[2]);
    if (!same) align(static_cast<int>(s), a, x, roots(f), r);
  }
  // New mirror faces: the continuation of a gone host face with the same corners (copies counted
  // as their originals), or added.
  std::vector<std::pair<int, int>> matched;  // (slot, mirror face)
  for (size_t m = h.mirror_faces_seen; m < nfm; ++m) {
    const FaceHandle f(static_cast<int>(m));
    if (mirror.status(f).deleted() || (m < h.host_of_face.size() && h.host_of_face[m] >= 0)) continue;
    const std::array<int, 3> x = corners(f), y = roots(f);
    auto it = y[0] >= 0 && y[1] >= 0 && y[2] >= 0 ? gone.find(key_of(y)) : gone.end();
    if (it != gone.end() && !it->second.empty()) {
      const int s = it->second.front();
      it->second.erase(it->second.begin());
      const std::array<int, 3> a{h.faces[3 * static_cast<size_t>(s)], h.faces[3 * static_cast<size_t>(s) + 1],
                                 h.faces[3 * static_cast<size_t>(s) + 2]};
      align(s, a, x, y, r);
      face_maps.emplace_back(s, static_cast<int>(m));
    } else {
      face_maps.emplace_back(static_cast<int>(r.faces_before + r.faces_added.size()), static_cast<int>(m));
      r.faces_added.push_back(x);
    }
  }
  for (const auto& [key, slots] : gone) {
    for (int s : slots) {
      r.faces_removed.push_back(s);
      face_maps.emplace_back(s, -1);
    }
  }
  std::sort(r.faces_removed.begin(), r.faces_removed.end());
  std::sort(r.faces_flipped.begin(), r.faces_flipped.end());
  std::stable_sort(r.corners_replaced.begin(), r.corners_replaced.end(),
                   [](const CornerReplaced& a, const CornerReplaced& b) { return a.face < b.face; });

  // 4. Replay on the host's state (checks the record), then the maps.
  apply(r, h.vertices, h.faces);
  h.host_of_vertex = std::move(host_of_vertex);
  h.mirror_of_vertex.resize(r.vertices_after(), -1);
  for (size_t m = h.mirror_vertices_seen; m < nvm; ++m) {
    const int v = h.host_of_vertex[m];
    if (v >= 0 && static_cast<size_t>(v) >= r.vertices_before) h.mirror_of_vertex[static_cast<size_t>(v)] = static_cast<int>(m);
  }
  for (int v : unmapped_vertices) {
    h.host_of_vertex[static_cast<size_t>(h.mirror_of_vertex[static_cast<size_t>(v)])] = -1;
    h.mirror_of_vertex[static_cast<size_t>(v)] = -1;
  }
  h.host_of_face.resize(nfm, -1);
  for (int s : r.faces_removed) h.map_face(static_cast<size_t>(s), -1, mirror);
  for (const auto& [s, m] : face_maps) h.map_face(static_cast<size_t>(s), m, mirror);
  h.mirror_vertices_seen = nvm;
  h.mirror_faces_seen = nfm;
  return r;
}

}  // namespace detail

}  // namespace twist
