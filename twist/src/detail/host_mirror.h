#pragma once
// Private: a host's plain mesh (its vertex and face slots) next to the edgefront::Mesh that
// mirrors it, with index maps both ways, and the record that brings the host up to the mirror
// (what one-shot repairs and the RepairSession return).

#include <array>
#include <cstddef>
#include <vector>

#include "edgefront/arrays.h"
#include "edgefront/mesh.h"
#include "twist/edit_record.h"

namespace twist::detail {

struct HostMirror {
  // The host's state as it replays the records: 3 values per vertex slot, 3 indices per face
  // slot (-1 -1 -1: an empty slot).
  std::vector<double> vertices;
  std::vector<int> faces;
  // Index maps; -1 for none.
  std::vector<int> mirror_of_vertex;  ///< by host vertex
  std::vector<int> host_of_vertex;    ///< by mirror vertex
  std::vector<int> mirror_of_face;    ///< by host face slot
  std::vector<int> host_of_face;      ///< by mirror face
  /// By host face slot, 3 each: the corners (mirror vertices, in circulation order) its mirror face
  /// had when mapped; a face still showing them is unchanged (the record's quick test).
  std::vector<int> mirror_corners;
  // Mirror elements below these indices were there at the last record (mapped or gone); newer
  // unmapped ones are what the next record adds.
  size_t mirror_vertices_seen = 0;
  size_t mirror_faces_seen = 0;

  size_t vertex_slots() const { return vertices.size() / 3; }
  size_t face_slots() const { return faces.size() / 3; }
  /// Maps host face slot `slot` to mirror face `face` (-1: unmaps it), both ways, noting its corners.
  void map_face(size_t slot, int face, const edgefront::Mesh& mirror);
  /// Host vertex of a mirror vertex (-1 none).
  int host_vertex(int m) const {
    return m >= 0 && static_cast<size_t>(m) < host_of_vertex.size() ? host_of_vertex[static_cast<size_t>(m)] : -1;
  }
};

/// The host's arrays copied in, the mirror converted from them: the host side of a conversion
/// (`edgefront::mesh_from_arrays`). Adds the copy journal to the mirror and notes the pinched
/// copies in it. The record of the conversion's changes is `bring_up_to_date`'s first answer.
HostMirror host_of_conversion(const edgefront::VertexArrayView& vertices, const edgefront::FaceArrayView& faces,
                              edgefront::ArrayMesh& converted);

/// The record that takes the host's state to the mirror's, applied to `host` (state and maps).
/// Compares every host slot and every mirror element (O(mesh), a pass over flags and positions).
EditRecord bring_up_to_date(HostMirror& host, const edgefront::Mesh& mirror);

/// The host-index corners of a live mirror face, in its circulation order (-1 for an unmapped vertex).
std::array<int, 3> host_corners(const HostMirror& host, const edgefront::Mesh& mirror, edgefront::FaceHandle f);

}  // namespace twist::detail
