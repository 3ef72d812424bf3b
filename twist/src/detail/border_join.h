#pragma once
// Joining border chains by strips of triangles, and closing small holes by a fan: the border
// operations that re-join a cut once both sides face the same way. Shared by the twist session's
// heal (heal.h) and the GCS loop's own border topology (gcs/src/detail/border_topology.h, which
// builds its trimming and whole-loop merges on these). Every function leaves a valid manifold
// oriented triangle mesh (deleted elements not collected) and changes nothing when it refuses.

#include <array>
#include <cstddef>
#include <functional>
#include <vector>

#include <OpenMesh/Core/System/omstream.hh>

#include "edgefront/mesh.h"

namespace twist::detail {

/// The distance from a point to the reference cloud (a surface sample) the joins must lie on.
using CloudDistance = std::function<double(const edgefront::Vec3&)>;

/// Mutes OpenMesh's omerr() (add_face reports refused faces there) while alive.
class MuteOpenMeshErrors {
 public:
  MuteOpenMeshErrors() : was_enabled_(omerr().is_enabled()) { omerr().disable(); }
  ~MuteOpenMeshErrors() {
    if (was_enabled_) omerr().enable();
  }
  MuteOpenMeshErrors(const MuteOpenMeshErrors&) = delete;
  MuteOpenMeshErrors& operator=(const MuteOpenMeshErrors&) = delete;

 private:
  bool was_enabled_;
};

/// One border loop: its boundary halfedges in order (vertex k = from(halfedges[k])) and length.
struct BorderLoop {
  std::vector<edgefront::HalfedgeHandle> halfedges;
  std::vector<edgefront::VertexHandle> vertices;
  double length = 0;
};

/// The border loops of the mesh, in halfedge index order of their first halfedge.
std::vector<BorderLoop> border_loops(const edgefront::Mesh& mesh);
/// True when no vertex occurs twice on the loop.
bool is_simple(const BorderLoop& loop);
/// Vertex k of a loop, k taken cyclically (may be negative).
edgefront::VertexHandle loop_vertex(const BorderLoop& loop, long k);
/// Boundary halfedge k of a loop (from vertex k to vertex k + 1), k taken cyclically.
edgefront::HalfedgeHandle loop_halfedge(const BorderLoop& loop, long k);

/// A strip of triangles between two border chains that run opposite: chain A is a(0..nA) along its
/// loop's direction, chain B is b(0..nB) against its loop's direction; ha(i) is the boundary
/// halfedge a(i) -> a(i+1), hb(j) the boundary halfedge b(j+1) -> b(j). For whole loops a(nA) =
/// a(0) and b(nB) = b(0) (the strip closes into a ring).
struct Strip {
  std::function<edgefront::VertexHandle(std::size_t)> a, b;
  std::function<edgefront::HalfedgeHandle(std::size_t)> ha, hb;
  std::size_t nA = 0, nB = 0;
};

/// Adds the faces in order; when OpenMesh refuses one, removes those added and returns false (the
/// mesh is then as before, up to the deleted faces' garbage).
bool add_all_or_none(edgefront::Mesh& mesh, const std::vector<std::array<edgefront::VertexHandle, 3>>& faces);

/// Plans the zipper triangles of a strip (advancing on the side whose next diagonal is shorter),
/// checks that every triangle is non-degenerate, lies within `max_support_distance` of the cloud and
/// that the triangles agree with the faces they border (mean cosine >= min_normal_agreement), then
/// adds them. Leaves the mesh unchanged and returns false when a check fails or OpenMesh refuses a
/// face (a non-manifold result).
bool zip_strip(edgefront::Mesh& mesh, const CloudDistance& cloud, const Strip& strip, double max_support_distance,
               double min_normal_agreement);

/// True when the fan around the centroid of the simple loop `loop` (its own triangle for 3
/// vertices) would close it: the centroid (written to `center`) lies within max_support_distance of
/// the cloud and the fan agrees with the faces around (mean cosine >= min_normal_agreement; for 3
/// vertices > min(0, min_normal_agreement): it must not fold back).
bool fan_fits(const edgefront::Mesh& mesh, const CloudDistance& cloud, const BorderLoop& loop,
              double max_support_distance, double min_normal_agreement, edgefront::Vec3& center);

/// Fills one simple border loop by that fan (one new vertex at the centroid; a triangle for 3
/// vertices) when `fan_fits`; false (mesh unchanged) otherwise.
bool fill_loop(edgefront::Mesh& mesh, const CloudDistance& cloud, const BorderLoop& loop, double max_support_distance,
               double min_normal_agreement);

/// Parameters of zip_border_slits.
struct ZipParams {
  double mean_edge_length = 0;
  double max_support_distance = 0;    ///< strip face centroids must be this close to the cloud
  double max_gap_edges = 2.0;         ///< seed pairs closer than this many mean edge lengths
  double min_opposite_cos = 0.3;      ///< the two borders' directions make a cosine below -this
  std::size_t min_loop_separation = 5;  ///< same loop: seed vertices at least this many loop steps apart
  double min_normal_agreement = 0.2;  ///< mean cosine between strip faces and the faces they border
  std::size_t max_zips = 32;          ///< strips added per call
  bool across_loops = false;          ///< also zip chains of two different loops (joins them)
  bool only_across_components = false;  ///< only zip chains of loops in two different components
};

/// Closes slits: where two border chains (of the same loop or of two loops) run close to each other
/// (within max_gap_edges mean edge lengths) in opposite directions, the gap between them is closed
/// by a strip of triangles, seeded at the closest pair and extended both ways while the chains stay
/// within max_gap_edges. A slit within one loop splits it in two; between two loops it joins
/// them. Strips must lie on the cloud and agree with the faces they border (zip_strip). Returns
/// the number of strips added.
std::size_t zip_border_slits(edgefront::Mesh& mesh, const CloudDistance& cloud, const ZipParams& params);

}  // namespace twist::detail
