#include "shapes/twisted_shapes.h"

#include <cmath>
#include <string>
#include <vector>

#include "detail/geometry.h"
#include "edgefront/error.h"

namespace twist {

using edgefront::InvalidInput;
using edgefront::Mesh;
using edgefront::Vec3;
using edgefront::VertexHandle;

namespace {
constexpr double kPi = 3.14159265358979323846;

void require(bool ok, const std::string& msg) {
  if (!ok) throw InvalidInput(msg);
}

void add(Mesh& m, VertexHandle a, VertexHandle b, VertexHandle c) {
  EF_CHECK(m.add_face(a, b, c).is_valid(), "twisted shape: face refused");
}
}  // namespace

TwistedShape twisted_tube(const TwistedTubeOptions& o) {
  require(o.along >= 4 && o.along <= 4096 && o.along % 2 == 0, "twisted_tube: along must be even and in [4, 4096]");
  require(o.around >= 6 && o.around <= 4096, "twisted_tube: around must lie in [6, 4096]");
  require(std::isfinite(o.length) && o.length > 0, "twisted_tube: length must be finite and > 0");
  require(std::isfinite(o.width) && o.width > 0, "twisted_tube: width must be finite and > 0");
  require(std::isfinite(o.thickness) && o.thickness > 0 && o.thickness < o.width,
          "twisted_tube: thickness must be finite, > 0 and < width");
  const int twist = o.twist_segment < 0 ? o.along / 2 : o.twist_segment;
  require(twist >= 1 && twist < o.along - 1, "twisted_tube: twist_segment must lie in [1, along - 2]");
  const double w = o.width, h = o.thickness / 2, half = o.length / 2, dx = o.length / o.along;
  TwistedShape s;
  Mesh& m = s.mesh;
  std::vector<std::vector<VertexHandle>> ring(static_cast<size_t>(o.along + 1));
  for (int i = 0; i <= o.along; ++i) {
    const double x = -half + i * dx;
    const double sign = i <= twist ? 1.0 : -1.0;
    for (int j = 0; j < o.around; ++j) {
      const double phi = 2 * kPi * j / o.around;
      ring[static_cast<size_t>(i)].push_back(m.add_vertex(Vec3(x, w * std::cos(phi), sign * h * std::sin(phi))));
    }
  }
  const VertexHandle c0 = m.add_vertex(Vec3(-half, 0, 0));
  const VertexHandle c1 = m.add_vertex(Vec3(half, 0, 0));
  const auto at = [&](int i, int j) { return ring[static_cast<size_t>(i)][static_cast<size_t>((j + o.around) % o.around)]; };
  for (int i = 0; i < o.along; ++i) {
    for (int j = 0; j < o.around; ++j) {
      add(m, at(i, j), at(i, j + 1), at(i + 1, j + 1));
      add(m, at(i, j), at(i + 1, j + 1), at(i + 1, j));
      if (i > twist) s.twisted_faces += 2;
    }
  }
  for (int j = 0; j < o.around; ++j) {
    add(m, c0, at(0, j + 1), at(0, j));
    add(m, c1, at(o.along, j), at(o.along, j + 1));
    s.twisted_faces += 1;  // the far cap
  }
  m.update_face_normals();
  const double x_lo = -half + twist * dx, x_hi = x_lo + dx;
  s.truth = [=](const Vec3& c) -> std::optional<Vec3> {
    if (c[0] > x_lo && c[0] < x_hi) return std::nullopt;  // the twist line
    if (std::abs(c[0] + half) < 1e-9 * o.length) return Vec3(-1, 0, 0);
    if (std::abs(c[0] - half) < 1e-9 * o.length) return Vec3(1, 0, 0);
    Vec3 n(0, c[1] / (w * w), c[2] / (h * h));
    return n.normalize();
  };
  return s;
}

TwistedShape flipped_disk_plate(const FlippedDiskOptions& o) {
  require(o.rings >= 6 && o.rings <= 1024, "flipped_disk_plate: rings must lie in [6, 1024]");
  require(o.around >= 8 && o.around <= 4096 && o.around % 2 == 0, "flipped_disk_plate: around must be even and in [8, 4096]");
  require(std::isfinite(o.radius) && o.radius > 0, "flipped_disk_plate: radius must be finite and > 0");
  require(std::isfinite(o.thickness) && o.thickness > 0 && o.thickness < o.radius,
          "flipped_disk_plate: thickness must be finite, > 0 and < radius");
  require(o.fold_rings >= 1 && o.fold_rings <= 16, "flipped_disk_plate: fold_rings must lie in [1, 16]");
  require(o.disk_rings >= 1 && o.disk_rings <= o.rings - o.fold_rings - 2,
          "flipped_disk_plate: disk_rings must lie in [1, rings - fold_rings - 2]");
  require(std::isfinite(o.fold_height) && o.fold_height >= 0 && o.fold_height <= 1,
          "flipped_disk_plate: fold_height must lie in [0, 1]");
  const double h = o.thickness / 2, dr = o.radius / o.rings;
  TwistedShape s;
  Mesh& m = s.mesh;
  // Rotation angle of top ring k about the x axis (through the top plane): pi for the disk, 0 for
  // the plate, falling linearly across the fold band.
  auto angle = [&](int k) {
    if (k <= o.disk_rings) return kPi;
    if (k > o.disk_rings + o.fold_rings) return 0.0;
    return kPi * (1.0 - static_cast<double>(k - o.disk_rings) / (o.fold_rings + 1));
  };
  auto top_point = [&](double x, double y, double theta) {
    return Vec3(x, y * std::cos(theta), h + o.fold_height * y * std::sin(theta));
  };
  std::vector<std::vector<VertexHandle>> top(static_cast<size_t>(o.rings + 1)), bottom(static_cast<size_t>(o.rings + 1));
  top[0].push_back(m.add_vertex(Vec3(0, 0, h)));
  bottom[0].push_back(m.add_vertex(Vec3(0, 0, -h)));
  for (int k = 1; k <= o.rings; ++k) {
    for (int j = 0; j < o.around; ++j) {
      const double phi = 2 * kPi * j / o.around, r = k * dr;
      top[static_cast<size_t>(k)].push_back(m.add_vertex(top_point(r * std::cos(phi), r * std::sin(phi), angle(k))));
    }
  }
  for (int k = 1; k <= o.rings; ++k) {
    for (int j = 0; j < o.around; ++j) {
      const double phi = 2 * kPi * j / o.around, r = k * dr;
      bottom[static_cast<size_t>(k)].push_back(m.add_vertex(Vec3(r * std::cos(phi), r * std::sin(phi), -h)));
    }
  }
  const int n = o.around;
  auto T = [&](int k, int j) { return k == 0 ? top[0][0] : top[static_cast<size_t>(k)][static_cast<size_t>((j + n) % n)]; };
  auto B = [&](int k, int j) { return k == 0 ? bottom[0][0] : bottom[static_cast<size_t>(k)][static_cast<size_t>((j + n) % n)]; };
  for (int j = 0; j < n; ++j) {
    add(m, T(0, 0), T(1, j), T(1, j + 1));  // normal +z (before the flip)
    add(m, B(0, 0), B(1, j + 1), B(1, j));  // normal -z
    s.twisted_faces += 1;
  }
  for (int k = 1; k < o.rings; ++k) {
    for (int j = 0; j < n; ++j) {
      add(m, T(k, j), T(k + 1, j), T(k + 1, j + 1));
      add(m, T(k, j), T(k + 1, j + 1), T(k, j + 1));
      add(m, B(k, j), B(k + 1, j + 1), B(k + 1, j));
      add(m, B(k, j), B(k, j + 1), B(k + 1, j + 1));
      if (k < o.disk_rings) s.twisted_faces += 2;
    }
  }
  for (int j = 0; j < n; ++j) {  // the side wall, outward
    add(m, T(o.rings, j), B(o.rings, j), B(o.rings, j + 1));
    add(m, T(o.rings, j), B(o.rings, j + 1), T(o.rings, j + 1));
  }
  m.update_face_normals();
  const double r_lo = o.disk_rings * dr, r_hi = (o.disk_rings + o.fold_rings + 1) * dr;
  s.truth = [=](const Vec3& c) -> std::optional<Vec3> {
    const double r = std::hypot(c[0], c[1]);
    if (std::abs(c[2]) < h * (1 - 1e-9) && r > r_hi) return Vec3(c[0] / r, c[1] / r, 0);  // the side wall
    // The fold band: out of the top plane, or between the disk and the plate (centroids of chords
    // lie inside their rings, hence the half-ring margin on the disk side).
    if (c[2] > 0 && (std::abs(c[2] - h) > 1e-9 * h || (r > r_lo - 0.5 * dr && r < r_hi))) return std::nullopt;
    return Vec3(0, 0, c[2] > 0 ? 1.0 : -1.0);
  };
  return s;
}

edgefront::PointCloud truth_points(const TwistedShape& shape) {
  edgefront::PointCloud cloud;
  for (edgefront::FaceHandle f : shape.mesh.faces()) {
    const Vec3 c = shape.mesh.calc_face_centroid(f);
    if (const auto t = shape.truth(c)) {
      cloud.points.push_back(c);
      cloud.normals.push_back(*t);
    }
  }
  return cloud;
}

double truth_consistency(const Mesh& mesh, const TwistedShape& shape) {
  double total = 0, agree = 0;
  for (edgefront::FaceHandle f : mesh.faces()) {
    const auto p = detail::face_points(mesh, f);
    const auto t = shape.truth(detail::centroid(p));
    if (!t) continue;
    const double a = detail::area(p);
    total += a;
    if (OpenMesh::dot(detail::unit_normal(p), *t) > 0) agree += a;
  }
  if (!(total > 0)) throw InvalidInput("truth_consistency: no face of the mesh has a reference normal");
  return agree / total;
}

}  // namespace twist
