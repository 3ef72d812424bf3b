#pragma once
// The foreign host's own mesh: plain arrays of positions and triangles, per-vertex incident face
// lists, nothing from EdgeFront's mesh type. Face slots and vertex indices are never compacted
// while the loop runs (a removed face leaves an empty slot, a removed vertex a dead index), which
// is exactly how EdgeFront's edit records address them, so a record replays without maps.

#include <array>
#include <cstddef>
#include <vector>

#include "twist/edit_record.h"

namespace foreign {

using Point = std::array<double, 3>;
using Tri = std::array<int, 3>;

/// What changed since the last call to the session (the host tells it these, and only these).
struct DirtySet {
  std::vector<int> vertices;          ///< moved or added (deduplicated by the flag below)
  std::vector<int> faces;             ///< added, re-connected or removed
  std::vector<int> removed_vertices;  ///< vertices the host's own collapses deleted
  std::vector<char> vertex_flag, face_flag;
  void mark_vertex(int v);
  void mark_face(int f);
  void clear();
};

struct HostMesh {
  std::vector<Point> pos;
  std::vector<char> alive;               ///< per vertex index
  std::vector<Tri> faces;                ///< per face slot; {-1, -1, -1} = empty slot
  std::vector<std::vector<int>> vfaces;  ///< per vertex: the live faces using it (unordered)
  DirtySet dirty;

  size_t vertex_slots() const { return pos.size(); }
  size_t face_slots() const { return faces.size(); }
  size_t live_vertices() const { return live_v_; }
  size_t live_faces() const { return live_f_; }
  bool face_live(int f) const { return faces[static_cast<size_t>(f)][0] >= 0; }

  int add_vertex(const Point& p);
  /// Marks a vertex dead (no face may use it).
  void remove_vertex(int v);
  int add_face(const Tri& t);
  void set_face(int f, const Tri& t);
  void remove_face(int f);

  /// Ordered neighbours of `v`: face i of the fan is (v, ring[i], ring[i+1]) (counter-clockwise
  /// for an outward mesh); `closed` when the fan goes all around. Returns false when the faces at
  /// `v` do not form a single fan (never for the meshes this loop keeps; then nothing is done).
  bool ring(int v, std::vector<int>& out, bool& closed) const;
  /// Area-weighted vertex normal (unit; zero when degenerate).
  Point vertex_normal(int v) const;
  /// Unit face normal times twice the area.
  Point face_cross(int f) const;
  double mean_edge_length() const;

  /// Replays an EdgeFront edit record (twist/edit_record.h, in its documented order) on this
  /// structure; `copy_attributes(copy, original)` is called for each appended copy so that the
  /// caller can copy its own per-vertex data. Throws std::runtime_error when the record does not
  /// fit (index spaces differ), before changing anything.
  template <class CopyAttributes>
  void replay(const twist::EditRecord& r, CopyAttributes&& copy_attributes);

 private:
  void attach(int f);
  void detach(int f);
  void check_record(const twist::EditRecord& r) const;
  void replay_geometry(const twist::EditRecord& r);
  size_t live_v_ = 0, live_f_ = 0;
};

template <class CopyAttributes>
void HostMesh::replay(const twist::EditRecord& r, CopyAttributes&& copy_attributes) {
  check_record(r);
  const size_t first_new = pos.size();
  replay_geometry(r);
  for (size_t i = 0; i < r.vertices_added.size(); ++i)
    copy_attributes(static_cast<int>(first_new + i), r.vertices_added[i].original);
}

}  // namespace foreign
