#pragma once
// Spatial (Morton, Z-order) ordering of points and of a mesh's elements, for memory locality:
// elements that are close in space get close indices, so a walk over a vertex's 2-ring or a
// nearest-point query touches a few cache lines instead of one per element. The GCS loop
// renumbers its mesh this way now and then (new vertices are appended at the end by splits, so
// the order decays as the mesh grows) and sorts the input cloud once.
//
// Deterministic: ties (equal codes) are broken by the old index.

#include <cstdint>
#include <vector>

#include "edgefront/mesh.h"
#include "gcs/operation.h"

namespace gcs::detail {

/// The permutation that sorts `points` by their Morton code over the points' bounding box (21
/// bits per axis), ties by index: result[k] is the index of the k-th point in Morton order.
std::vector<std::size_t> morton_order(const std::vector<edgefront::Vec3>& points);

/// A spatially even subsample of n points that are in spatial (e.g. coarse Morton) order: one index out of
/// every run of k = ceil(n / max_points) consecutive indices, at the same seed-chosen position
/// (in [0, k)) in every run; increasing, at most max_points of them (a shorter last run may give
/// none). All of 0 .. n-1 when n <= max_points. Deterministic for a seed. max_points >= 1.
std::vector<std::size_t> stride_subsample(std::size_t n, std::size_t max_points, std::uint64_t seed);

/// The permutation that sorts `points` (fewer than 2^32) by a coarse Morton code (10 bits per
/// axis over their bounding box), ties by index: cheaper than morton_order (8-byte keys, three
/// radix passes), and spatially ordered down to 1/1024 of the box (memory locality, and what
/// stride_subsample needs to be spatially even).
std::vector<std::size_t> coarse_morton_order(const std::vector<edgefront::Vec3>& points);

/// Rebuilds `mesh` with the same connectivity, positions, face normals and circulation starts
/// (each vertex keeps its outgoing halfedge, each face its halfedge, so circulators visit the same
/// elements in the same order), without the deleted elements, numbered in spatial order:
/// vertices by the Morton code of their position, edges by their two new vertex indices, faces by
/// their three. Other properties and status flags are not carried over (the caller must not have
/// any that matter). Returns the maps from old to new indices (edges keep their direction).
MeshRenumbering renumber_spatially(edgefront::Mesh& mesh);

}  // namespace gcs::detail
