// The software rasterizer. Everything happens at sample resolution (the image size times the
// supersampling factor) and is box-filtered down at the end:
//   1. validate, fit the camera to the scene's bounding sphere, project every vertex;
//   2. triangles: bounding box scan with edge functions, perspective-correct barycentric
//      weights, z-buffer on the view depth, per-sample color (highlight, colormap + isolines of
//      constant screen width, or base color), back-face tint, Gouraud or flat Lambert + ambient
//      with a headlight;
//   3. polylines as capsules and points as discs, tested against the z-buffer with a small bias
//      so that lines lying on the surface show;
//   4. downsampling.
#include "render/render.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "detail/color_bar.h"
#include "edgefront/error.h"

namespace edgefront::render {

namespace {

constexpr double kPi = 3.14159265358979323846;

void require(bool ok, const std::string& message) {
  if (!ok) throw InvalidInput("render: " + message);
}

bool finite(const Vec3& p) { return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]); }

void validate_options(const RenderOptions& o) {
  require(o.width >= 1 && o.height >= 1,
          "the image size must be at least 1x1 pixels (got " + std::to_string(o.width) + "x" +
              std::to_string(o.height) + ")");
  require(o.width <= kMaxImageSide && o.height <= kMaxImageSide,
          "the image size " + std::to_string(o.width) + "x" + std::to_string(o.height) + " exceeds the limit of " +
              std::to_string(kMaxImageSide) + " pixels per side");
  require(o.supersample >= 1 && o.supersample <= 4,
          "supersample must be 1, 2, 3 or 4 (got " + std::to_string(o.supersample) + ")");
  const double samples = static_cast<double>(o.width) * o.height * o.supersample * o.supersample;
  require(samples <= kMaxSamples, "the image size times the supersampling (" + std::to_string(samples) +
                                      " samples) exceeds the limit of " + std::to_string(kMaxSamples));
  require(std::isfinite(o.azimuth_deg), "the azimuth must be a finite number of degrees");
  require(o.elevation_deg >= -90.0 && o.elevation_deg <= 90.0, "the elevation must lie within [-90, 90] degrees");
  require(o.field_of_view_deg >= 1.0 && o.field_of_view_deg <= 120.0,
          "the field of view must lie within [1, 120] degrees");
  require(o.fill > 0.0 && o.fill <= 10.0, "fill must lie within (0, 10]");
  require(o.ambient >= 0.0 && o.ambient <= 1.0, "ambient must lie within [0, 1]");
  require(o.back_face_tint >= 0.0 && o.back_face_tint <= 1.0, "back_face_tint must lie within [0, 1]");
  require(o.isoline_width_px >= 0.0 && o.isoline_width_px <= 100.0,
          "isoline_width_px must lie within [0, 100]");
}

void validate_scene(const Scene& scene) {
  bool anything = false;
  if (scene.mesh != nullptr) {
    const Mesh& mesh = *scene.mesh;
    size_t faces = 0;
    for (const auto f : mesh.faces()) {
      (void)f;
      ++faces;
    }
    require(faces > 0, "the mesh is empty (no faces)");
    anything = true;
    for (const auto v : mesh.vertices()) {
      require(finite(mesh.point(v)), "vertex " + std::to_string(v.idx()) + " has a non-finite coordinate");
    }
    if (scene.field) {
      const ScalarField& field = *scene.field;
      require(field.values.size() == mesh.n_vertices(),
              "the scalar field has " + std::to_string(field.values.size()) + " values for " +
                  std::to_string(mesh.n_vertices()) + " vertices");
      require(!field.min || std::isfinite(*field.min), "the field's min is not finite");
      require(!field.max || std::isfinite(*field.max), "the field's max is not finite");
      require(!(field.min && field.max) || *field.min <= *field.max, "the field's min exceeds its max");
      require(std::isfinite(field.isoline_step), "the isoline step is not finite");
      require(field.isoline_step != 0.0 || field.isoline_count >= 1, "isoline_count must be at least 1");
    }
    for (const FaceHighlight& h : scene.highlights) {
      for (const FaceHandle f : h.faces) {
        require(is_live(mesh, f), "highlighted face " + std::to_string(f.idx()) + " is not a face of the mesh");
      }
    }
  } else {
    require(!scene.field, "a scalar field needs a mesh");
    require(scene.highlights.empty(), "face highlights need a mesh");
  }
  // Lines and point sets: a size in pixels and finite points.
  const auto check = [&anything](const std::string& what, double size_px, const std::string& size_name,
                                 const std::vector<Vec3>& points) {
    require(std::isfinite(size_px) && size_px > 0 && size_px <= 100,
            what + ": the " + size_name + " must lie within (0, 100] pixels");
    for (size_t k = 0; k < points.size(); ++k) {
      require(finite(points[k]), what + ", point " + std::to_string(k) + " has a non-finite coordinate");
    }
    anything = anything || !points.empty();
  };
  for (size_t i = 0; i < scene.lines.size(); ++i) {
    check("line " + std::to_string(i), scene.lines[i].width_px, "width", scene.lines[i].points);
  }
  for (size_t i = 0; i < scene.points.size(); ++i) {
    check("point set " + std::to_string(i), scene.points[i].radius_px, "radius", scene.points[i].points);
  }
  require(anything, "nothing to draw (no mesh, lines or points)");
}

/// Camera fitted to the bounding sphere of the scene, in sample coordinates.
struct Camera {
  Vec3 eye, right, up, forward;
  bool perspective = true;
  double focal = 1.0;  ///< samples per unit of x/z (perspective) or per unit of x (orthographic)
  double cx = 0.0, cy = 0.0;
  double radius = 1.0;  ///< of the bounding sphere

  /// Screen x, y (samples) and view depth z (> 0 in front of the camera).
  Vec3 project(const Vec3& p) const {
    const Vec3 q = p - eye;
    const double x = OpenMesh::dot(q, right), y = OpenMesh::dot(q, up), z = OpenMesh::dot(q, forward);
    if (perspective) return Vec3(cx + focal * x / z, cy - focal * y / z, z);
    return Vec3(cx + focal * x, cy - focal * y, z);
  }
  /// Unit direction from `p` toward the light (a headlight at the eye).
  Vec3 light(const Vec3& p) const {
    if (!perspective) return -forward;
    Vec3 l = eye - p;
    const double n = l.norm();
    return n > 0 ? l / n : -forward;
  }
};

/// Calls `f` with every point that counts for the camera fit.
template <class F>
void for_each_scene_point(const Scene& scene, F&& f) {
  if (scene.mesh != nullptr) {
    for (const auto v : scene.mesh->vertices()) f(scene.mesh->point(v));
  }
  for (const Polyline& line : scene.lines) {
    for (const Vec3& p : line.points) f(p);
  }
  for (const PointSet& set : scene.points) {
    for (const Vec3& p : set.points) f(p);
  }
}

Camera fit_camera(const Scene& scene, const RenderOptions& o, int sw, int sh) {
  // The sphere around the bounding box's center through the farthest point (tighter than the
  // box's half diagonal: a sphere fills the picture as much as a cube seen along a diagonal).
  Vec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for_each_scene_point(scene, [&](const Vec3& p) {
    lo.minimize(p);
    hi.maximize(p);
  });
  const Vec3 center = (lo + hi) * 0.5;
  double radius2 = 0.0;
  for_each_scene_point(scene, [&](const Vec3& p) { radius2 = std::max(radius2, (p - center).sqrnorm()); });
  Camera cam;
  cam.radius = std::sqrt(radius2);
  if (!(cam.radius > 0)) cam.radius = 1.0;  // a single point
  const double az = o.azimuth_deg * kPi / 180.0, el = o.elevation_deg * kPi / 180.0;
  const Vec3 to_eye(std::cos(el) * std::sin(az), std::sin(el), std::cos(el) * std::cos(az));
  cam.forward = -to_eye;
  cam.right = Vec3(std::cos(az), 0.0, -std::sin(az));
  cam.up = OpenMesh::cross(cam.right, cam.forward);
  cam.perspective = o.perspective;
  cam.cx = 0.5 * sw;
  cam.cy = 0.5 * sh;
  const double half_side = 0.5 * std::min(sw, sh);
  if (o.perspective) {
    const double tan_half = std::tan(0.5 * o.field_of_view_deg * kPi / 180.0);
    // The sphere's silhouette (half-angle asin(r / D)) fills `fill` of the half field of view.
    const double distance = cam.radius / std::sin(std::atan(o.fill * tan_half));
    cam.eye = center + to_eye * std::max(distance, 1.001 * cam.radius);
    cam.focal = half_side / tan_half;
  } else {
    cam.eye = center + to_eye * (3.0 * cam.radius);
    cam.focal = o.fill * half_side / cam.radius;
  }
  return cam;
}

/// The sample buffers.
struct Target {
  int w = 0, h = 0;
  std::vector<float> depth;  ///< view depth; +inf where empty
  std::vector<std::uint8_t> rgb;

  void put(size_t i, const Rgb& c) {
    rgb[3 * i] = c[0];
    rgb[3 * i + 1] = c[1];
    rgb[3 * i + 2] = c[2];
  }
};

struct FieldInfo {
  const std::vector<double>* values = nullptr;
  double lo = 0.0, span = 1.0;  ///< colormap(t = (v - lo) / span)
  double step = 0.0;            ///< isoline spacing; 0 = none
};

FieldInfo field_info(const ScalarField& field) {
  FieldInfo info;
  info.values = &field.values;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const double v : field.values) {
    if (!std::isfinite(v)) continue;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  if (!std::isfinite(lo)) lo = hi = 0.0;  // no finite value at all
  if (field.min) lo = *field.min;
  if (field.max) hi = *field.max;
  info.lo = lo;
  info.span = hi > lo ? hi - lo : 0.0;
  if (field.isoline_step > 0) {
    info.step = field.isoline_step;
  } else if (field.isoline_step == 0.0) {
    info.step = nice_step(info.span, field.isoline_count);
  }
  return info;
}

/// What the shading pass needs of a face.
struct FaceShade {
  float light[3] = {0, 0, 0};  ///< per corner
  float value[3] = {0, 0, 0};  ///< field values per corner (when `use_field`)
  float grad = 0;              ///< |screen gradient| of the field, value per sample
  bool use_field = false;
  bool back = false;
  Rgb color = {0, 0, 0};  ///< when not `use_field`: the final unshaded color (tint applied)
};

/// The colormap at 1024 steps (a lookup per sample instead of the piecewise-linear evaluation).
struct ColormapTable {
  static constexpr int kSize = 1024;
  std::array<Rgb, kSize> colors{};
  ColormapTable() {
    for (int i = 0; i < kSize; ++i) colors[static_cast<size_t>(i)] = colormap(static_cast<double>(i) / (kSize - 1));
  }
  const Rgb& operator()(double t) const {
    const double x = std::clamp(t, 0.0, 1.0) * (kSize - 1) + 0.5;
    return colors[static_cast<size_t>(x >= 0 ? x : 0.0)];  // NaN: x fails the test: entry 0
  }
};

/// Triangles in two passes: visibility (z-buffer, face index and perspective-correct weights per
/// sample), then shading of the visible samples only.
void draw_triangles(const Scene& scene, const RenderOptions& o, const Camera& cam, const std::vector<Vec3>& screen,
                    Target& target) {
  const Mesh& mesh = *scene.mesh;
  const size_t nv = mesh.n_vertices();

  // Per-face highlight color index (-1: none).
  std::vector<int> highlight(mesh.n_faces(), -1);
  for (size_t i = 0; i < scene.highlights.size(); ++i) {
    for (const FaceHandle f : scene.highlights[i].faces) highlight[static_cast<size_t>(f.idx())] = static_cast<int>(i);
  }

  // Smooth shading: unit angle-weighted vertex normals (independent of how the faces around a
  // vertex are split into triangles). A corner whose face normal deviates from its vertex normal
  // by more than 45 degrees (a cube's corner) keeps the face normal, so that sharp edges stay
  // sharp.
  constexpr double kCosCrease = 0.7071;  // cos(45 degrees)
  std::vector<Vec3> vertex_normal;
  if (o.smooth_shading) {
    vertex_normal.assign(nv, Vec3(0, 0, 0));
    for (const auto f : mesh.faces()) {
      auto it = mesh.cfv_iter(f);
      const VertexHandle corner[3] = {*it, *++it, *++it};
      const Vec3 p[3] = {mesh.point(corner[0]), mesh.point(corner[1]), mesh.point(corner[2])};
      Vec3 n = OpenMesh::cross(p[1] - p[0], p[2] - p[0]);
      const double len = n.norm();
      if (!(len > 0)) continue;
      n /= len;
      for (int k = 0; k < 3; ++k) {
        const Vec3 a = p[(k + 1) % 3] - p[k], b = p[(k + 2) % 3] - p[k];
        const double angle = std::atan2(OpenMesh::cross(a, b).norm(), OpenMesh::dot(a, b));
        vertex_normal[static_cast<size_t>(corner[k].idx())] += n * angle;
      }
    }
    for (Vec3& n : vertex_normal) {
      const double len = n.norm();
      if (len > 0) n /= len;
    }
  }
  const double diffuse = 1.0 - o.ambient;
  const FieldInfo field = scene.field ? field_info(*scene.field) : FieldInfo{};

  // ---- pass 1: visibility ----
  const size_t samples = target.depth.size();
  std::vector<int> sample_face(samples, -1);
  std::vector<float> sample_w0(samples), sample_w1(samples);
  std::vector<FaceShade> shade(mesh.n_faces());
  for (const auto f : mesh.faces()) {
    auto it = mesh.cfv_iter(f);
    const VertexHandle vh[3] = {*it, *++it, *++it};
    size_t vi[3];
    Vec3 s[3];
    for (int k = 0; k < 3; ++k) {
      vi[k] = static_cast<size_t>(vh[k].idx());
      s[k] = screen[vi[k]];
    }
    if (!(s[0][2] > 0 && s[1][2] > 0 && s[2][2] > 0)) continue;  // behind the camera (not with a fitted camera)
    const double area = (s[1][0] - s[0][0]) * (s[2][1] - s[0][1]) - (s[2][0] - s[0][0]) * (s[1][1] - s[0][1]);
    if (!(std::abs(area) > 1e-12)) continue;  // edge-on or degenerate: covers no sample
    const int x0 = std::max(0, static_cast<int>(std::floor(std::min({s[0][0], s[1][0], s[2][0]}))));
    const int x1 = std::min(target.w - 1, static_cast<int>(std::ceil(std::max({s[0][0], s[1][0], s[2][0]}))));
    const int y0 = std::max(0, static_cast<int>(std::floor(std::min({s[0][1], s[1][1], s[2][1]}))));
    const int y1 = std::min(target.h - 1, static_cast<int>(std::ceil(std::max({s[0][1], s[1][1], s[2][1]}))));
    if (x0 > x1 || y0 > y1) continue;

    // What shading needs of this face.
    FaceShade& fs = shade[static_cast<size_t>(f.idx())];
    const Vec3& p0 = mesh.point(vh[0]);
    const Vec3 face_normal = OpenMesh::cross(mesh.point(vh[1]) - p0, mesh.point(vh[2]) - p0);
    fs.back = OpenMesh::dot(face_normal, cam.light(p0)) < 0;
    const double face_len = face_normal.norm();
    const Vec3 unit_face_normal = face_len > 0 ? face_normal / face_len : Vec3(0, 0, 0);
    for (int k = 0; k < 3; ++k) {  // Lambert with the headlight, on the side that is seen
      Vec3 n = unit_face_normal;
      if (o.smooth_shading && OpenMesh::dot(vertex_normal[vi[k]], unit_face_normal) > kCosCrease) n = vertex_normal[vi[k]];
      const double d = OpenMesh::dot(n, o.smooth_shading ? cam.light(mesh.point(vh[k])) : cam.light(p0));
      fs.light[k] = static_cast<float>(o.ambient + diffuse * std::max(0.0, fs.back ? -d : d));
    }
    const int hl = highlight[static_cast<size_t>(f.idx())];
    fs.color = scene.base_color;
    if (hl >= 0) {
      fs.color = scene.highlights[static_cast<size_t>(hl)].color;
    } else if (field.values != nullptr) {
      double value[3];
      for (int k = 0; k < 3; ++k) value[k] = (*field.values)[vi[k]];
      if (std::isfinite(value[0]) && std::isfinite(value[1]) && std::isfinite(value[2])) {
        fs.use_field = true;
        for (int k = 0; k < 3; ++k) fs.value[k] = static_cast<float>(value[k]);
        const double gx = ((value[1] - value[0]) * (s[2][1] - s[0][1]) - (value[2] - value[0]) * (s[1][1] - s[0][1])) / area;
        const double gy = ((value[2] - value[0]) * (s[1][0] - s[0][0]) - (value[1] - value[0]) * (s[2][0] - s[0][0])) / area;
        fs.grad = static_cast<float>(std::sqrt(gx * gx + gy * gy));
      } else {
        fs.color = scene.field->no_value_color;
      }
    }
    if (fs.back && !fs.use_field) fs.color = mix(fs.color, o.back_face_color, o.back_face_tint);

    // Barycentric weights from edge functions, stepped along each row; the sign of `area`
    // handles both windings. Perspective-correct weights through 1/z.
    const double inv_area = 1.0 / area;
    const double iz[3] = {1.0 / s[0][2], 1.0 / s[1][2], 1.0 / s[2][2]};
    const double db0 = -(s[2][1] - s[1][1]) * inv_area, db1 = -(s[0][1] - s[2][1]) * inv_area;
    const int face_index = f.idx();
    for (int y = y0; y <= y1; ++y) {
      const double py = y + 0.5, px = x0 + 0.5;
      double b0 = ((s[2][0] - s[1][0]) * (py - s[1][1]) - (s[2][1] - s[1][1]) * (px - s[1][0])) * inv_area;
      double b1 = ((s[0][0] - s[2][0]) * (py - s[2][1]) - (s[0][1] - s[2][1]) * (px - s[2][0])) * inv_area;
      size_t idx = static_cast<size_t>(y) * static_cast<size_t>(target.w) + static_cast<size_t>(x0);
      for (int x = x0; x <= x1; ++x, ++idx, b0 += db0, b1 += db1) {
        const double b2 = 1.0 - b0 - b1;
        if (b0 < 0 || b1 < 0 || b2 < 0) continue;
        double z, w0 = b0, w1 = b1;
        if (cam.perspective) {
          const double q0 = b0 * iz[0], q1 = b1 * iz[1], q2 = b2 * iz[2];
          z = 1.0 / (q0 + q1 + q2);
          w0 = q0 * z;
          w1 = q1 * z;
        } else {
          z = b0 * s[0][2] + b1 * s[1][2] + b2 * s[2][2];
        }
        if (!(z < target.depth[idx])) continue;
        target.depth[idx] = static_cast<float>(z);
        sample_face[idx] = face_index;
        sample_w0[idx] = static_cast<float>(w0);
        sample_w1[idx] = static_cast<float>(w1);
      }
    }
  }

  // ---- pass 2: shading of the visible samples ----
  static const ColormapTable table;
  const Rgb isoline_color = scene.field ? scene.field->isoline_color : Rgb{};
  const double iso_half_width = 0.5 * o.isoline_width_px * o.supersample;
  for (size_t idx = 0; idx < samples; ++idx) {
    const int face = sample_face[idx];
    if (face < 0) continue;
    const FaceShade& fs = shade[static_cast<size_t>(face)];
    const double w0 = sample_w0[idx], w1 = sample_w1[idx], w2 = 1.0 - w0 - w1;
    Rgb color = fs.color;
    if (fs.use_field) {
      const double v = w0 * fs.value[0] + w1 * fs.value[1] + w2 * fs.value[2];
      color = table(field.span > 0 ? (v - field.lo) / field.span : 0.0);
      if (field.step > 0 && fs.grad > 0) {
        const double nearest = std::round(v / field.step) * field.step;
        if (std::abs(v - nearest) < iso_half_width * fs.grad) color = isoline_color;
      }
      if (fs.back) color = mix(color, o.back_face_color, o.back_face_tint);
    }
    const double light = w0 * fs.light[0] + w1 * fs.light[1] + w2 * fs.light[2];
    target.put(idx, scale(color, light));
  }
}

/// Writes `color` where the sample passes the depth test (with `bias`) and lowers the depth.
inline void plot(Target& target, int x, int y, double z, double bias, const Rgb& color) {
  const size_t idx = static_cast<size_t>(y) * static_cast<size_t>(target.w) + static_cast<size_t>(x);
  if (!(z <= target.depth[idx] + bias)) return;
  target.depth[idx] = std::min(target.depth[idx], static_cast<float>(z));
  target.put(idx, color);
}

void draw_segment(Target& target, const Camera& cam, const Vec3& a, const Vec3& b, double radius, double bias,
                  const Rgb& color) {
  if (!(a[2] > 0 && b[2] > 0)) return;
  const int x0 = std::max(0, static_cast<int>(std::floor(std::min(a[0], b[0]) - radius)));
  const int x1 = std::min(target.w - 1, static_cast<int>(std::ceil(std::max(a[0], b[0]) + radius)));
  const int y0 = std::max(0, static_cast<int>(std::floor(std::min(a[1], b[1]) - radius)));
  const int y1 = std::min(target.h - 1, static_cast<int>(std::ceil(std::max(a[1], b[1]) + radius)));
  const double dx = b[0] - a[0], dy = b[1] - a[1];
  const double len2 = dx * dx + dy * dy;
  const double r2 = radius * radius;
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      const double px = x + 0.5 - a[0], py = y + 0.5 - a[1];
      const double t = len2 > 0 ? std::clamp((px * dx + py * dy) / len2, 0.0, 1.0) : 0.0;
      const double ex = px - t * dx, ey = py - t * dy;
      if (ex * ex + ey * ey > r2) continue;
      const double z = cam.perspective ? 1.0 / ((1.0 - t) / a[2] + t / b[2]) : (1.0 - t) * a[2] + t * b[2];
      plot(target, x, y, z, bias, color);
    }
  }
}

void draw_polyline(Target& target, const Camera& cam, const Polyline& line, int ss, double bias) {
  const size_t n = line.points.size();
  if (n == 0) return;
  const double radius = 0.5 * line.width_px * ss;
  std::vector<Vec3> s(n);
  for (size_t i = 0; i < n; ++i) s[i] = cam.project(line.points[i]);
  if (n == 1) {
    draw_segment(target, cam, s[0], s[0], radius, bias, line.color);
    return;
  }
  for (size_t i = 0; i + 1 < n; ++i) draw_segment(target, cam, s[i], s[i + 1], radius, bias, line.color);
  if (line.closed && n > 2) draw_segment(target, cam, s[n - 1], s[0], radius, bias, line.color);
}

}  // namespace

Image render(const Scene& scene, const RenderOptions& options) {
  validate_options(options);
  validate_scene(scene);
  if (options.color_bar && scene.field && scene.mesh != nullptr) {
    // The mesh in the image without the bar's columns, then the bar beside it.
    const FieldInfo info = field_info(*scene.field);
    const int bar = detail::color_bar_width(options.width, options.height, info.lo, info.span);
    if (bar > 0) {
      RenderOptions inner = options;
      inner.width = options.width - bar;
      inner.color_bar = false;
      const Image left = render(scene, inner);
      Image image(options.width, options.height, options.background);
      for (int y = 0; y < left.height; ++y) {
        for (int x = 0; x < left.width; ++x) image.set(x, y, left.at(x, y));
      }
      detail::draw_color_bar(image, bar, info.lo, info.span, Rgb{40, 40, 40});
      return image;
    }
  }
  const int ss = options.supersample;
  Target target;
  target.w = options.width * ss;
  target.h = options.height * ss;
  const size_t samples = static_cast<size_t>(target.w) * static_cast<size_t>(target.h);
  target.depth.assign(samples, std::numeric_limits<float>::infinity());
  target.rgb.resize(3 * samples);
  for (size_t i = 0; i < samples; ++i) target.put(i, options.background);

  const Camera cam = fit_camera(scene, options, target.w, target.h);
  // Lines and points on the surface must pass the depth test; parts behind it by more than this
  // must not.
  const double bias = 0.015 * cam.radius;

  std::vector<Polyline> borders;
  if (scene.mesh != nullptr) {
    const Mesh& mesh = *scene.mesh;
    std::vector<Vec3> screen(mesh.n_vertices(), Vec3(0, 0, 0));
    for (const auto v : mesh.vertices()) screen[static_cast<size_t>(v.idx())] = cam.project(mesh.point(v));
    draw_triangles(scene, options, cam, screen, target);
    if (scene.border_color) borders = border_polylines(mesh, *scene.border_color, scene.border_width_px);
  }
  for (const Polyline& line : scene.lines) draw_polyline(target, cam, line, ss, bias);
  for (const Polyline& line : borders) draw_polyline(target, cam, line, ss, bias);
  for (const PointSet& set : scene.points) {
    const double radius = set.radius_px * ss;
    for (const Vec3& p : set.points) {
      const Vec3 s = cam.project(p);
      draw_segment(target, cam, s, s, radius, bias, set.color);
    }
  }

  // Box filter down to the output size.
  Image image(options.width, options.height, options.background);
  const int n = ss * ss;
  for (int y = 0; y < options.height; ++y) {
    for (int x = 0; x < options.width; ++x) {
      int sum[3] = {0, 0, 0};
      for (int dy = 0; dy < ss; ++dy) {
        for (int dx = 0; dx < ss; ++dx) {
          const size_t i = static_cast<size_t>(y * ss + dy) * static_cast<size_t>(target.w) + static_cast<size_t>(x * ss + dx);
          for (int k = 0; k < 3; ++k) sum[k] += target.rgb[3 * i + static_cast<size_t>(k)];
        }
      }
      image.set(x, y, Rgb{static_cast<std::uint8_t>((sum[0] + n / 2) / n), static_cast<std::uint8_t>((sum[1] + n / 2) / n),
                          static_cast<std::uint8_t>((sum[2] + n / 2) / n)});
    }
  }
  return image;
}

void render_png(const Scene& scene, const RenderOptions& options, const std::filesystem::path& path) {
  write_png(render(scene, options), path);
}

}  // namespace edgefront::render
