#pragma once
// The steps of twist::repair that its parts share. Internal. The parts:
//   repair.cpp          cut and flip: the detect-and-repair loop (repair_impl), one region cut off
//                       and its smaller side flipped, regions cut out and re-grown, the repair by
//                       labelling; twist::repair;
//   repair_orient.cpp   global orientation (orient_globally) and pieces flipped across reversed
//                       seams (flip_seam_pieces); twist::orient;
//   repair_cleanup.cpp  cleanup: tiny pieces, small cut pieces, border flaps, turned patches, and
//                       the smoothing moves they and the stacked layers use;
//   repair_mend.cpp     small rejected patches mended after a repair by labelling (edge swaps,
//                       vertex moves, cut-outs re-grown as fans);
//   stacked_layers.cpp  twist::remove_stacked_layers;
//   twist_repairer.cpp  TwistRepairer, the incremental repair.
// Each step is documented where it is defined.

#include <functional>
#include <initializer_list>
#include <optional>
#include <utility>
#include <vector>

#include "edgefront/mesh.h"
#include "twist/detect.h"
#include "twist/repair.h"

namespace twist::detail {

/// Vertex pairs (copy, original) that the cuts made.
using DupList = std::vector<std::pair<edgefront::VertexHandle, edgefront::VertexHandle>>;
/// Decides, for a region about to be repaired, whether it is cut out instead (re-twist guard).
using CutOutRule = std::function<bool(const edgefront::Mesh&, const TwistRegion&)>;
/// Builds, for the vertices about to be moved, the test `smooth_until` applies after a round
/// (it may note what it needs before the move).
using MoveTest = std::function<std::function<bool()>(const std::vector<edgefront::VertexHandle>&)>;

// repair.cpp
RepairReport repair_impl(edgefront::Mesh& mesh, const RepairOptions& o, const CutOutRule& cut_out, DupList& dups,
                         FaceGrid* grid = nullptr);

// repair_orient.cpp
void orient_globally(edgefront::Mesh& mesh, const RepairOptions& o, const DupList& dups, RepairReport& report);
void flip_seam_pieces(edgefront::Mesh& mesh, DupList& dups, RepairReport& report);

// repair_cleanup.cpp
size_t remove_tiny_pieces(edgefront::Mesh& mesh, const std::vector<edgefront::VertexHandle>& around,
                          size_t min_faces);
size_t remove_faces(edgefront::Mesh& mesh, const std::vector<edgefront::FaceHandle>& faces, size_t min_faces);
size_t remove_small_cut_pieces(edgefront::Mesh& mesh, const RepairOptions& o, const DupList& dups, size_t& spared);
size_t peel_flaps(edgefront::Mesh& mesh, const RepairOptions& o, const DupList& dups, size_t& spared);
bool smooth_until(edgefront::Mesh& mesh, const std::vector<edgefront::VertexHandle>& vs, int rounds,
                  const std::function<bool()>& accept);
std::optional<size_t> folds_around(const edgefront::Mesh& mesh, const std::vector<edgefront::VertexHandle>& vs);
std::vector<edgefront::VertexHandle> interior_vertices_around(const edgefront::Mesh& mesh,
                                                              std::initializer_list<edgefront::FaceHandle> faces);
bool straighten_face(edgefront::Mesh& mesh, edgefront::FaceHandle f, const MoveTest& test);
void drop_turned_patches(edgefront::Mesh& mesh, const RepairOptions& o, RepairReport& report);

// repair_mend.cpp
void mend_patches(edgefront::Mesh& mesh, const RepairOptions& o, RepairReport& report);

// sole_cover.cpp
/// The faces of `faces` that alone cover a point of `reference`: a point within `radius` of the
/// face and farther than `radius` from every live face of `mesh` not in `faces` (see
/// `CutOptions::support_radius`). In the order of `faces`; deleted handles are skipped. Empty for
/// `radius` <= 0. Cost: a hierarchy over the staying faces and a k-d tree over the points.
std::vector<edgefront::FaceHandle> sole_cover(const edgefront::Mesh& mesh, const std::vector<edgefront::FaceHandle>& faces,
                                              const ReferenceNormals& reference, double radius);
/// `faces` without those that `sole_cover` finds under `o.cuts.support_radius` and the reference
/// confirms (no reference or radius 0: `faces` as given); `spared` counts the faces kept.
std::vector<edgefront::FaceHandle> without_sole_cover(const edgefront::Mesh& mesh, const std::vector<edgefront::FaceHandle>& faces,
                                                      const RepairOptions& o, size_t& spared);

}  // namespace twist::detail
