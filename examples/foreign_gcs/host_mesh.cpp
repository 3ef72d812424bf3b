#include "host_mesh.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace foreign {

namespace {

Point sub(const Point& a, const Point& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Point cross(const Point& a, const Point& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

}  // namespace

void DirtySet::mark_vertex(int v) {
  const size_t i = static_cast<size_t>(v);
  if (vertex_flag.size() <= i) vertex_flag.resize(2 * i + 16, 0);
  if (!vertex_flag[i]) {
    vertex_flag[i] = 1;
    vertices.push_back(v);
  }
}

void DirtySet::mark_face(int f) {
  const size_t i = static_cast<size_t>(f);
  if (face_flag.size() <= i) face_flag.resize(2 * i + 16, 0);
  if (!face_flag[i]) {
    face_flag[i] = 1;
    faces.push_back(f);
  }
}

void DirtySet::clear() {
  for (int v : vertices) vertex_flag[static_cast<size_t>(v)] = 0;
  for (int f : faces) face_flag[static_cast<size_t>(f)] = 0;
  vertices.clear();
  faces.clear();
  removed_vertices.clear();
}

int HostMesh::add_vertex(const Point& p) {
  pos.push_back(p);
  alive.push_back(1);
  vfaces.emplace_back();
  ++live_v_;
  const int v = static_cast<int>(pos.size() - 1);
  dirty.mark_vertex(v);
  return v;
}

void HostMesh::remove_vertex(int v) {
  if (!vfaces[static_cast<size_t>(v)].empty()) throw std::logic_error("removing a vertex that faces still use");
  alive[static_cast<size_t>(v)] = 0;
  --live_v_;
  dirty.removed_vertices.push_back(v);
}

void HostMesh::attach(int f) {
  for (int v : faces[static_cast<size_t>(f)]) vfaces[static_cast<size_t>(v)].push_back(f);
}

void HostMesh::detach(int f) {
  for (int v : faces[static_cast<size_t>(f)]) {
    std::vector<int>& l = vfaces[static_cast<size_t>(v)];
    l.erase(std::find(l.begin(), l.end(), f));
  }
}

int HostMesh::add_face(const Tri& t) {
  faces.push_back(t);
  const int f = static_cast<int>(faces.size() - 1);
  attach(f);
  ++live_f_;
  dirty.mark_face(f);
  return f;
}

void HostMesh::set_face(int f, const Tri& t) {
  detach(f);
  faces[static_cast<size_t>(f)] = t;
  attach(f);
  dirty.mark_face(f);
}

void HostMesh::remove_face(int f) {
  detach(f);
  faces[static_cast<size_t>(f)] = {-1, -1, -1};
  --live_f_;
  dirty.mark_face(f);
}

bool HostMesh::ring(int v, std::vector<int>& out, bool& closed) const {
  out.clear();
  const std::vector<int>& fan = vfaces[static_cast<size_t>(v)];
  if (fan.empty()) return false;
  // Each face as (v, a, b): the fan links a face's b to the next face's a.
  auto corners = [&](int f) {
    const Tri& t = faces[static_cast<size_t>(f)];
    const int k = t[0] == v ? 0 : t[1] == v ? 1 : 2;
    return std::array<int, 2>{t[(k + 1) % 3], t[(k + 2) % 3]};
  };
  // Start at a face whose a has no face before it (a border), else anywhere.
  int start = fan[0];
  for (int f : fan) {
    const int a = corners(f)[0];
    bool has_before = false;
    for (int g : fan)
      if (corners(g)[1] == a) has_before = true;
    if (!has_before) {
      start = f;
      break;
    }
  }
  size_t visited = 0;
  int f = start;
  out.push_back(corners(f)[0]);
  closed = false;
  for (;;) {
    const int b = corners(f)[1];
    ++visited;
    if (visited > fan.size()) return false;
    int next = -1;
    for (int g : fan)
      if (corners(g)[0] == b) next = g;
    if (next == start) {
      closed = true;
      break;
    }
    out.push_back(b);
    if (next < 0) break;
    f = next;
  }
  return visited == fan.size();
}

Point HostMesh::face_cross(int f) const {
  const Tri& t = faces[static_cast<size_t>(f)];
  const Point& a = pos[static_cast<size_t>(t[0])];
  return cross(sub(pos[static_cast<size_t>(t[1])], a), sub(pos[static_cast<size_t>(t[2])], a));
}

Point HostMesh::vertex_normal(int v) const {
  Point n{0, 0, 0};
  for (int f : vfaces[static_cast<size_t>(v)]) {
    const Point c = face_cross(f);
    for (int k = 0; k < 3; ++k) n[static_cast<size_t>(k)] += c[static_cast<size_t>(k)];
  }
  const double l = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (!(l > 0)) return {0, 0, 0};
  return {n[0] / l, n[1] / l, n[2] / l};
}

double HostMesh::mean_edge_length() const {
  double sum = 0;
  size_t count = 0;
  for (const Tri& t : faces) {
    if (t[0] < 0) continue;
    for (int k = 0; k < 3; ++k) {
      const Point d = sub(pos[static_cast<size_t>(t[static_cast<size_t>(k)])], pos[static_cast<size_t>(t[static_cast<size_t>((k + 1) % 3)])]);
      sum += std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      ++count;
    }
  }
  return count ? sum / static_cast<double>(count) : 0.0;
}

void HostMesh::check_record(const twist::EditRecord& r) const {
  auto bad = [](const std::string& what) { throw std::runtime_error("edit record does not fit the host mesh: " + what); };
  if (r.vertices_before != pos.size()) bad("vertex index space " + std::to_string(r.vertices_before) + ", host " + std::to_string(pos.size()));
  if (r.faces_before != faces.size()) bad("face index space " + std::to_string(r.faces_before) + ", host " + std::to_string(faces.size()));
  const size_t nv = r.vertices_after();
  auto live_face = [&](int f) { return f >= 0 && static_cast<size_t>(f) < faces.size() && faces[static_cast<size_t>(f)][0] >= 0; };
  for (const twist::VertexAdded& a : r.vertices_added)
    if (a.original >= static_cast<int>(pos.size())) bad("copy of vertex " + std::to_string(a.original));
  for (const twist::VertexMoved& m : r.vertices_moved)
    if (m.vertex < 0 || static_cast<size_t>(m.vertex) >= nv) bad("moved vertex " + std::to_string(m.vertex));
  for (int f : r.faces_flipped)
    if (!live_face(f)) bad("flipped face " + std::to_string(f));
  for (const twist::CornerReplaced& c : r.corners_replaced) {
    if (!live_face(c.face)) bad("re-connected face " + std::to_string(c.face));
    const Tri& t = faces[static_cast<size_t>(c.face)];
    if (std::find(t.begin(), t.end(), c.from) == t.end()) bad("face " + std::to_string(c.face) + " has no corner " + std::to_string(c.from));
    if (c.to < 0 || static_cast<size_t>(c.to) >= nv) bad("corner vertex " + std::to_string(c.to));
  }
  for (int f : r.faces_removed)
    if (!live_face(f)) bad("removed face " + std::to_string(f));
  for (const std::array<int, 3>& t : r.faces_added)
    for (int v : t)
      if (v < 0 || static_cast<size_t>(v) >= nv) bad("added face with vertex " + std::to_string(v));
}

void HostMesh::replay_geometry(const twist::EditRecord& r) {
  // 1. copies appended (the caller copies its attributes), 2. moves.
  for (const twist::VertexAdded& a : r.vertices_added) {
    pos.push_back(a.position);
    alive.push_back(1);
    vfaces.emplace_back();
    ++live_v_;
  }
  for (const twist::VertexMoved& m : r.vertices_moved) pos[static_cast<size_t>(m.vertex)] = m.position;
  // 3. flips: a b c -> a c b (the incident lists do not change).
  for (int f : r.faces_flipped) std::swap(faces[static_cast<size_t>(f)][1], faces[static_cast<size_t>(f)][2]);
  // 4. corner replacements, all of one face against the corners it had before them.
  for (size_t i = 0; i < r.corners_replaced.size();) {
    const int f = r.corners_replaced[i].face;
    const Tri before = faces[static_cast<size_t>(f)];
    Tri after = before;
    for (; i < r.corners_replaced.size() && r.corners_replaced[i].face == f; ++i)
      for (size_t k = 0; k < 3; ++k)
        if (before[k] == r.corners_replaced[i].from) after[k] = r.corners_replaced[i].to;
    detach(f);
    faces[static_cast<size_t>(f)] = after;
    attach(f);
  }
  // 5. removals, 6. appended faces.
  for (int f : r.faces_removed) {
    detach(f);
    faces[static_cast<size_t>(f)] = {-1, -1, -1};
    --live_f_;
  }
  for (const std::array<int, 3>& t : r.faces_added) {
    faces.push_back(t);
    attach(static_cast<int>(faces.size() - 1));
    ++live_f_;
  }
  // Vertices the repair deleted: dead for the host too (the session knows already).
  for (int v : r.vertices_removed) {
    if (alive[static_cast<size_t>(v)] && vfaces[static_cast<size_t>(v)].empty()) {
      alive[static_cast<size_t>(v)] = 0;
      --live_v_;
    }
  }
}

}  // namespace foreign
