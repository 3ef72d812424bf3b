#pragma once
/// \file arrays.h
/// The twist detector and repair for a host that keeps its mesh as plain arrays (see
/// `edgefront/arrays.h` for the views and the conversion): stateless, arrays in, edit record or
/// labels out, O(mesh) per call. A host that calls the repair again and again (a refinement
/// loop) keeps a `RepairSession` instead (twist/repair_session.h).
///
/// \code
///   twist::ArrayRepair r = twist::repair_arrays(V, F);    // V: 3n doubles, F: 3m ints
///   twist::apply(r.record, V, F);                          // the host's arrays, repaired
///   twist::compact_faces(F);                               // drop the removed face slots
/// \endcode

#include <cstddef>
#include <vector>

#include "edgefront/arrays.h"
#include "twist/detect.h"
#include "twist/edit_record.h"
#include "twist/reference_normals.h"
#include "twist/repair.h"

namespace twist {

/// Oriented reference points from arrays: `points` and `normals` n x 3 (float or double).
/// \throws edgefront::InvalidInput for a wrong shape, different row counts, or as
///         `ReferenceNormals` (non-finite points, zero normals; naming the row).
ReferenceNormals reference_from_arrays(const edgefront::VertexArrayView& points, const edgefront::VertexArrayView& normals);

/// Twisted regions of a mesh given as arrays.
struct ArrayDetection {
  /// Per input face row: the region it belongs to (0 = the largest), -1 for none (and for rows
  /// the conversion dropped).
  std::vector<int> face_region;
  std::vector<size_t> region_faces;    ///< per region: its faces
  std::vector<size_t> region_flagged;  ///< per region: its faces with evidence
  DetectStats stats;                   ///< the detector's counts (as `detect_regions` reports them)
  edgefront::ConversionReport conversion;  ///< what the conversion changed
};

/// `detect_regions` on the converted arrays. \throws edgefront::InvalidInput for bad arrays (as
/// `edgefront::mesh_from_arrays`) or options; TopologyError as `detect_regions`.
ArrayDetection detect_arrays(const edgefront::VertexArrayView& vertices, const edgefront::FaceArrayView& faces,
                             const DetectOptions& options = {});

/// A one-shot repair of arrays.
struct ArrayRepair {
  /// The conversion's changes (dropped faces removed, pinched vertices split) and the repair's,
  /// as one record on the input arrays (`vertices_before` = input vertices, `faces_before` =
  /// input faces).
  EditRecord record;
  RepairReport report;                     ///< what the repair found and did
  edgefront::ConversionReport conversion;  ///< what the conversion changed (also in `record`)
};

/// `repair` on the converted arrays (`RepairOptions::garbage_collect` is ignored: the record never
/// compacts the host's indices). The repaired mesh is the record applied to the input.
/// \throws as `edgefront::mesh_from_arrays` and `repair`; nothing is returned then.
ArrayRepair repair_arrays(const edgefront::VertexArrayView& vertices, const edgefront::FaceArrayView& faces,
                          const RepairOptions& options = {});

/// The global orientation of arrays (`orient`: a closed component faces outward, or into the
/// cavity it bounds, an open one is left; with reference normals, each component follows their
/// vote), as a record: the faces flipped. Faces wound against a neighbour cannot join the mesh and
/// are removed by the record (see `edgefront::mesh_from_arrays`; orient a soup with `orient_soup`).
/// \throws as `edgefront::mesh_from_arrays`.
ArrayRepair orient_arrays(const edgefront::VertexArrayView& vertices, const edgefront::FaceArrayView& faces,
                          const RepairOptions& options = {});

}  // namespace twist
