#pragma once
/// \file edit_record.h
/// Edit records: what a twist repair (or the conversion before it) did to a mesh, in terms a host
/// replays on its own structure with nothing else.
///
/// Indices are the host's and are never compacted: a vertex or face keeps its index for as long
/// as it exists; new vertices and faces are appended (vertex `vertices_before + i` is
/// `vertices_added[i]`, face `faces_before + i` is `faces_added[i]`); a removed face leaves its
/// slot empty, a vertex the repair deleted is listed in `vertices_removed` (its index is not
/// reused by the record; the host may delete it). So the host's ids of everything that stays
/// remain valid, and no old -> new map is needed.
///
/// Replay, in this order (`apply` is the reference for plain arrays, a template for a host):
///  1. append `vertices_added` (each a copy of `original`: same position, the host copies its own
///     attributes; `original` is -1 for a new point, e.g. the centre of a re-grown patch);
///  2. move `vertices_moved` to their positions;
///  3. flip `faces_flipped`: reverse the corner order (a b c -> a c b);
///  4. in each `corners_replaced` face, the corner holding vertex `from` takes vertex `to` (how a
///     cut detaches a side: `to` is a copy appended in step 1); the replacements of one face
///     apply together, each to the corner that held `from` before any of them;
///  5. remove `faces_removed`;
///  6. append `faces_added`.
/// Faces not named keep their corners in their order. A record is all or nothing: the functions
/// returning one either return a complete record or throw and leave the host's data untouched.

#include <array>
#include <cstddef>
#include <vector>

namespace twist {

/// A vertex appended by the record.
struct VertexAdded {
  int original = -1;                    ///< the vertex it copies (same position when made), -1 for a new point
  std::array<double, 3> position{0, 0, 0};  ///< its position after the record
};

/// A vertex the record moves.
struct VertexMoved {
  int vertex = -1;                          ///< the host's vertex index
  std::array<double, 3> position{0, 0, 0};  ///< its new position (x, y, z)
};

/// In face `face`, the corner holding vertex `from` takes vertex `to`.
struct CornerReplaced {
  int face = -1;  ///< the host's face index (a live slot)
  int from = -1;  ///< the vertex the corner holds before the record
  int to = -1;    ///< the vertex it holds after (often a copy appended by `vertices_added`)
};

/// What one call did (see the file comment for the replay).
struct EditRecord {
  size_t vertices_before = 0;  ///< the host's vertex index space before (vertices and empty slots)
  size_t faces_before = 0;     ///< the host's face index space before (faces and empty slots)
  std::vector<VertexAdded> vertices_added;      ///< vertex vertices_before + i
  std::vector<VertexMoved> vertices_moved;      ///< by increasing vertex
  std::vector<int> faces_flipped;               ///< increasing
  std::vector<CornerReplaced> corners_replaced; ///< by increasing face
  std::vector<int> faces_removed;               ///< increasing
  std::vector<std::array<int, 3>> faces_added;  ///< face faces_before + i
  /// Vertices the repair deleted (increasing): no face uses them after the record; their indices
  /// stay (the host may delete them). Nothing to replay.
  std::vector<int> vertices_removed;

  /// The host's vertex index space after the replay.
  size_t vertices_after() const { return vertices_before + vertices_added.size(); }
  /// The host's face index space after the replay (removed faces leave empty slots).
  size_t faces_after() const { return faces_before + faces_added.size(); }
  /// True when the record changes nothing.
  bool empty() const {
    return vertices_added.empty() && vertices_moved.empty() && faces_flipped.empty() && corners_replaced.empty() &&
           faces_removed.empty() && faces_added.empty() && vertices_removed.empty();
  }
};

/// The reference replay on plain arrays: `vertices` holds 3 values per vertex, `faces` 3 indices
/// per face slot, an empty slot is -1 -1 -1 (what step 5 writes). The arrays must have
/// `record.vertices_before` rows and `record.faces_before` slots, and the record must fit them
/// (every face it names is a live slot, every corner it replaces holds `from`, every vertex exists).
/// \throws edgefront::InvalidInput naming the first mismatch; the arrays are then unchanged.
void apply(const EditRecord& record, std::vector<double>& vertices, std::vector<int>& faces);

/// Removes the empty face slots (-1 -1 -1) of plain arrays in place, keeping the order of the
/// rest; returns, per old slot, its new row (-1 for an empty slot).
std::vector<int> compact_faces(std::vector<int>& faces);

}  // namespace twist
