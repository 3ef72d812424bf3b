#pragma once
/// \file scene.h
/// What the renderer draws: a mesh with an optional per-vertex scalar field (colormap and
/// isolines), highlighted faces, polylines (front loops, paths, border loops) and points.
///
/// \code
///   edgefront::render::Scene scene;
///   scene.mesh = &mesh;                                   // not owned; must outlive render()
///   scene.field = edgefront::render::ScalarField{.values = distances};
///   scene.lines.push_back(edgefront::render::polyline_from_halfedges(mesh, loop.halfedges));
///   edgefront::render::Image image = edgefront::render::render(scene, {});
/// \endcode

#include <optional>
#include <vector>

#include "edgefront/borrowed.h"
#include "edgefront/mesh.h"
#include "render/color.h"

namespace edgefront::render {

/// A per-vertex scalar shown through the colormap (render/color.h) with dark isolines.
struct ScalarField {
  /// One value per vertex index of the scene's mesh. Non-finite values (e.g. an unreached
  /// distance, +inf) mean "no value": faces touching such a vertex are drawn in `no_value_color`.
  std::vector<double> values = {};
  /// The values mapped to the two ends of the colormap; default: the smallest and largest finite
  /// value. Values outside are clamped to the end colors.
  std::optional<double> min = std::nullopt;  ///< (unset: smallest finite value); finite
  std::optional<double> max = std::nullopt;  ///< the value at the colormap's top end (see `min`); finite, >= min
  /// Spacing of the isolines in the field's units; 0 picks a nice step (1, 2 or 5 x 10^k) for
  /// about `isoline_count` lines over [min, max]; a negative value turns the isolines off.
  double isoline_step = 0.0;
  int isoline_count = 12;  ///< about this many isolines when `isoline_step` is 0; >= 1
  Rgb isoline_color = {25, 25, 25};      ///< color of the isolines (near black)
  Rgb no_value_color = {150, 150, 150};  ///< color of faces touching a vertex without a value (grey)
};

/// Faces drawn in one color instead of the field or base color (e.g. twisted regions).
struct FaceHighlight {
  std::vector<FaceHandle> faces = {};  ///< live faces of the scene's mesh
  Rgb color = {230, 40, 40};           ///< their color (default red)
};

/// A polyline drawn on top of the surface with a depth test (parts hidden behind the surface are
/// not drawn; parts lying on it are).
struct Polyline {
  std::vector<Vec3> points = {};   ///< the corners, in order; finite
  bool closed = false;             ///< also join the last point to the first
  Rgb color = {220, 30, 30};       ///< line color (default red)
  double width_px = 2.0;           ///< line width in output pixels, (0, 100]
};

/// Points drawn as discs with a depth test.
struct PointSet {
  std::vector<Vec3> points = {};  ///< disc centres; finite
  Rgb color = {20, 20, 20};       ///< disc color (default near black)
  double radius_px = 2.0;         ///< disc radius in output pixels, (0, 100]
};

/// The scene. Everything in it counts for the camera fit (render/render.h).
struct Scene {
  Borrowed<const Mesh> mesh = nullptr;  ///< the caller's; may be null for a scene of lines and points only
  Rgb base_color = {200, 200, 200};  ///< front faces without field or highlight
  std::optional<ScalarField> field = std::nullopt;  ///< a per-vertex field to color the mesh by (needs `mesh`)
  std::vector<FaceHighlight> highlights = {};  ///< later entries win where they overlap
  std::vector<Polyline> lines = {};   ///< polylines drawn over the surface
  std::vector<PointSet> points = {};  ///< point sets drawn over the surface
  /// When set, the mesh's border loops (cycles of boundary halfedges) are drawn as lines of this
  /// color, after `lines`.
  std::optional<Rgb> border_color = Rgb{40, 90, 230};
  double border_width_px = 2.0;  ///< width of the border lines in output pixels; > 0 (not range-checked)
};

/// The points of a vertex path of `mesh` as a polyline.
/// \throw InvalidInput if a vertex is not a live vertex of `mesh`.
Polyline polyline_from_vertices(const Mesh& mesh, const std::vector<VertexHandle>& vertices, bool closed,
                                const Rgb& color = {220, 30, 30});

/// A chain of halfedges (e.g. a front loop) as a polyline through their from-vertices, closed
/// when the last halfedge ends where the first starts.
/// \throw InvalidInput if a halfedge is not a live halfedge of `mesh`.
Polyline polyline_from_halfedges(const Mesh& mesh, const std::vector<HalfedgeHandle>& halfedges,
                                 const Rgb& color = {220, 30, 30});

/// The border loops of `mesh` (cycles of boundary halfedges), each as a closed polyline, in the
/// order of their lowest halfedge index.
std::vector<Polyline> border_polylines(const Mesh& mesh, const Rgb& color, double width_px);

}  // namespace edgefront::render
