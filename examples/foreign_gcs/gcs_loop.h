#pragma once
// A textbook growing-cell-structures loop (Ivrissimtzis, Jeong & Seidel, "Using Growing Cell
// Structures for Surface Reconstruction", SMI 2003) on the host's own mesh (host_mesh.h), with
// EdgeFront's twist repair and bounded geodesic queries called through the session / edit-record
// API only (twist/repair_session.h). See README.md next to this file for what it does and why.

#include <cstdint>
#include <string>
#include <vector>

#include "host_mesh.h"

namespace foreign {

struct Cloud {
  std::vector<Point> points;
  std::vector<Point> normals;  ///< empty or one unit normal per point
};

struct LoopOptions {
  size_t target_vertices = 2000;  ///< stop when the mesh has this many live vertices (>= 6)
  std::uint64_t seed = 1;         ///< the random samples; same seed, same mesh
  bool twist = true;              ///< repair twists after every batch and at the end
  size_t lambda = 100;            ///< basic steps per vertex split
  size_t batch_splits = 10;       ///< vertex splits per batch (a batch = lambda * batch_splits steps)
  double alpha_winner = 0.06;     ///< the winner moves this share of the way to the sample
  double alpha_neighbour = 0.05;  ///< tangential Laplacian smoothing of the winner's ring (5 rounds)
  double half_life = 6.0;         ///< signal counters halve every half_life * |V| basic steps
  double mu = 20.0;               ///< a vertex that has not won for mu * |V| steps is collapsed
  size_t min_repair_vertices = 200;  ///< no repair while the mesh is smaller (a coarse blob has no layers)
  size_t max_retwists = 2;        ///< twist::SessionOptions::max_retwists (a place repaired more often is cut out)
  bool heal = false;              ///< twist::SessionOptions::heal: the session re-joins borders after each repair (needs normals)
  double heal_gap_edges = 1.0;    ///< twist::HealOptions::max_gap_edges
  size_t heal_hole_vertices = 8;  ///< twist::HealOptions::max_hole_vertices
  size_t heal_grow_rows = 0;      ///< twist::HealOptions::grow_rows (border growth on the points)
  double heal_min_piece_share = 0;  ///< twist::HealOptions::min_piece_share (small pieces removed by the finish)
  size_t probes_per_batch = 16;   ///< "far along the surface?" queries per batch (0: none)
  bool verbose = false;           ///< one line per batch on stderr
};

struct LoopStats {
  size_t basic_steps = 0, batches = 0, splits = 0, edge_splits = 0, collapses = 0;
  size_t repair_calls = 0, record_vertices_added = 0, record_faces_flipped = 0, record_faces_removed = 0,
         record_corners_replaced = 0, record_faces_added = 0;
  size_t heal_strips = 0, heal_holes = 0, heal_grown = 0;  ///< what the session's heal added over all calls
  size_t probes = 0, probes_far = 0;  ///< nearest-two-vertex pairs probed, and those far along the surface
  bool step_limit = false;            ///< stopped by the step cap before reaching the target
  double seconds_loop = 0, seconds_session = 0;
};

/// Runs the loop from an octahedron around the cloud and returns the final mesh (live elements
/// only, compacted) in `out`. Throws std::runtime_error (or an edgefront::Error from the session)
/// on failure.
LoopStats run_gcs(const Cloud& cloud, const LoopOptions& options, std::vector<Point>& out_vertices,
                  std::vector<Tri>& out_faces);

}  // namespace foreign
