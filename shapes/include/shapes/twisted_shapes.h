#pragma once
/// \file twisted_shapes.h
/// Deterministic twisted meshes with analytic reference normals, for tests and benchmarks: what a
/// refinement reconstructor produces when a closed estimate meets a thin structure, built
/// directly (no randomness).

#include <functional>
#include <optional>

#include "edgefront/mesh.h"
#include "edgefront/point_cloud.h"

namespace twist {

/// A twisted mesh and the surface it should approximate.
struct TwistedShape {
  edgefront::Mesh mesh;  ///< combinatorially oriented, manifold, geometrically twisted
  /// The outward unit normal of the intended surface at a face centroid, or nothing where the
  /// mesh does not approximate the surface (the twist line or fold band itself).
  std::function<std::optional<edgefront::Vec3>(const edgefront::Vec3&)> truth;
  size_t twisted_faces = 0;  ///< faces built with the wrong orientation
};

/// Options of `twisted_tube`.
struct TwistedTubeOptions {
  int along = 40;          ///< segments along x, even, in [4, 4096]
  int around = 24;         ///< segments around the cross-section, in [6, 4096]
  double length = 2.0;     ///< the tube spans x in [-length/2, length/2]; finite, > 0
  double width = 0.5;      ///< half width of the flattened cross-section (y); finite, > 0
  double thickness = 0.1;  ///< full thickness (z); > 0, < width
  int twist_segment = -1;  ///< index of the segment holding the twist line; -1: the middle one
};

/// A flattened closed tube (an elliptic cylinder along x, half axes `width` and `thickness`/2,
/// closed by flat fan caps) whose cross-section is mirrored (z -> -z) beyond one segment: the
/// two layers cross there (the twist line) and swap sides, so everything beyond it is inside
/// out. The truth is the untwisted tube with outward normals; the crossing segment has none.
/// \throws edgefront::InvalidInput for options out of range.
TwistedShape twisted_tube(const TwistedTubeOptions& options = {});

/// Options of `flipped_disk_plate`.
struct FlippedDiskOptions {
  int rings = 12;             ///< rings of the top and bottom disks, in [6, 1024]
  int around = 32;            ///< vertices per ring, even, in [8, 4096]
  double radius = 1.0;        ///< plate radius; finite, > 0
  double thickness = 0.1;     ///< full thickness; > 0, < radius
  int disk_rings = 3;         ///< rings of the flipped disk, in [1, rings - fold_rings - 2]
  int fold_rings = 2;         ///< rings of the fold band between disk and plate, in [1, 16]
  double fold_height = 0.1;   ///< out-of-plane excursion of the fold band, relative to its radius; in [0, 1]
};

/// A closed thin round plate (pillbox, outward) whose top carries a disk turned over like a coin
/// (rotated by pi about the x axis, so it lies in the top plane facing down), joined to the rest
/// by a twisted fold band. The truth is the pillbox; the band has none.
/// \throws edgefront::InvalidInput for options out of range.
TwistedShape flipped_disk_plate(const FlippedDiskOptions& options = {});

/// Oriented reference points of the intended surface: the centroid of every face that has a
/// truth, with the truth normal (for reference-normal detection and tests).
edgefront::PointCloud truth_points(const TwistedShape& shape);

/// Area-weighted share of the faces with a truth (see `TwistedShape::truth`) whose normal agrees
/// with it. \throws edgefront::InvalidInput when no face has a truth.
double truth_consistency(const edgefront::Mesh& mesh, const TwistedShape& shape);

}  // namespace twist
