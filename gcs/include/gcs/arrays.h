#pragma once
/// \file arrays.h
/// Reconstruction for a host with plain arrays: points (n x 3, float or double) and optional
/// normals in, a triangle mesh as arrays out (see `edgefront/arrays.h` for the views).
///
/// \code
///   edgefront::MeshArrays m = gcs::reconstruct_arrays(P, {}, {.target_vertices = 2000});
/// \endcode

#include "edgefront/arrays.h"
#include "gcs/reconstructor.h"

namespace gcs {

/// A reconstruction as arrays.
struct ArrayReconstruction {
  edgefront::MeshArrays mesh;  ///< vertices n x 3, faces m x 3 (the result's `mesh`, as arrays)
  StopReason stop_reason = StopReason::target_reached;  ///< why the reconstruction stopped
  std::size_t basic_steps = 0;  ///< basic steps run (the result's `basic_steps`)
  std::size_t batches = 0;      ///< split batches run (the result's `batches`)
};

/// `reconstruct` on points given as arrays; `normals` is empty (no normals) or one unit normal per
/// point (n x 3). The same bytes as `reconstruct` on the same points and options.
/// \throws edgefront::InvalidInput for a wrong shape, row counts that differ, non-finite values
///         (naming the row), and as `reconstruct`.
ArrayReconstruction reconstruct_arrays(const edgefront::VertexArrayView& points,
                                       const edgefront::VertexArrayView& normals = {},
                                       const ReconstructOptions& options = {});

}  // namespace gcs
