// Mesh and point-cloud files and pictures for Python.

#include <pybind11/stl.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "bindings.h"
#include "convert.h"
#include "edgefront/arrays.h"
#include "edgefront/error.h"
#include "edgefront/mesh_io.h"
#include "edgefront/point_cloud_io.h"
#include "render/color.h"
#include "render/render.h"

namespace efpy {

namespace {

// Per mesh vertex of `m` (input vertices, then pinched copies), the value of its input row.
std::vector<double> per_mesh_vertex(const edgefront::ArrayMesh& m, const std::vector<double>& per_input) {
  std::vector<double> out(m.vertex_row.size());
  for (size_t i = 0; i < out.size(); ++i) out[i] = per_input[static_cast<size_t>(m.vertex_row[i])];
  return out;
}

// The renderer's colormap over the finite range of `values`, grey where not finite.
std::vector<std::array<std::uint8_t, 3>> colors_of(const std::vector<double>& values) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const double x : values) {
    if (std::isfinite(x)) lo = std::min(lo, x), hi = std::max(hi, x);
  }
  std::vector<std::array<std::uint8_t, 3>> out(values.size(), {150, 150, 150});
  for (size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i])) continue;
    const double t = hi > lo ? (values[i] - lo) / (hi - lo) : 0.0;
    const edgefront::render::Rgb c = edgefront::render::colormap(t);
    out[i] = {c[0], c[1], c[2]};
  }
  return out;
}

std::string path_text(const py::handle& path) {
  return py::str(py::module_::import("os").attr("fspath")(path)).cast<std::string>();
}

}  // namespace

void register_io(py::module_& m) {
  m.def(
      "read_mesh",
      [](const py::handle& path) {
        const std::string p = path_text(path);
        edgefront::MeshArrays a;
        {
          py::gil_scoped_release release;
          a = edgefront::mesh_to_arrays(edgefront::read_mesh(p).mesh);
        }
        return mesh_tuple(std::move(a));
      },
      py::arg("path"),
      "read_mesh(path) -> (V, F)\n\n"
      "Reads a triangle mesh (.off, .obj, .ply, .stl; by extension). Returns V, float64 (n, 3), and F, int32\n"
      "(m, 3). Polygons are fan-triangulated; faces a half-edge mesh cannot hold are dropped; a pinched\n"
      "vertex (several fans meeting at one vertex) is split, its copies appended after the file's vertices.\n"
      "Raises OSError naming the file and line for a missing, unreadable or malformed file.");

  m.def(
      "write_mesh",
      [](const py::handle& path, const py::handle& V, const py::handle& F, const py::handle& scalars, bool binary) {
        const std::string p = path_text(path);
        // Refuse, rather than silently drop, faces a half-edge mesh cannot hold.
        const edgefront::ArrayMesh am = array_mesh(V, F, /*drop_nonmanifold_faces=*/false);
        const long n = static_cast<long>(am.report.input_vertices);
        edgefront::MeshWriteOptions o;
        o.binary = binary;
        if (py::isinstance<py::dict>(scalars)) {
          for (const auto item : py::reinterpret_borrow<py::dict>(scalars)) {
            const std::string name = py::str(item.first).cast<std::string>();
            o.vertex_scalars.emplace_back(name, per_mesh_vertex(am, double_list(item.second, ("scalars['" + name + "']").c_str(), n)));
          }
        } else if (!scalars.is_none()) {
          std::vector<double> q = per_mesh_vertex(am, double_list(scalars, "scalars", n));
          o.vertex_colors = colors_of(q);
          o.vertex_scalars.emplace_back("quality", std::move(q));
        }
        py::gil_scoped_release release;
        edgefront::write_mesh(am.mesh, p, o);
      },
      py::arg("path"), py::arg("V"), py::arg("F"), py::arg("scalars") = py::none(), py::arg("binary") = true,
      "write_mesh(path, V, F, scalars=None, binary=True)\n\n"
      "Writes the mesh (V, F) to path (.off, .obj, .ply, .stl; by extension), atomically: a failed write\n"
      "leaves no half-written file. scalars (PLY only): a 1-D array of n per-vertex values, written as the\n"
      "vertex property \"quality\" (MeshLab's per-vertex quality) with colors of the renderer's colormap over\n"
      "its finite range (grey where not finite); or a dict {name: array} of named double properties.\n"
      "binary: binary little-endian PLY (default) or ascii PLY.\n"
      "Pinched vertices are written split (copies appended, as read_mesh would split them).\n"
      "Raises ValueError for bad arrays, a face a half-edge mesh cannot hold (naming the row and edge),\n"
      "scalars of the wrong length or with another format than PLY; OSError when the file cannot be written.");

  m.def(
      "read_points",
      [](const py::handle& path) {
        const std::string p = path_text(path);
        edgefront::PointCloud c;
        {
          py::gil_scoped_release release;
          c = edgefront::read_points(p);
        }
        auto flat = [](const std::vector<edgefront::Vec3>& v) {
          std::vector<double> out;
          out.reserve(3 * v.size());
          for (const edgefront::Vec3& q : v) out.insert(out.end(), {q[0], q[1], q[2]});
          return out;
        };
        py::object normals = py::none();
        if (c.has_normals()) normals = to_numpy_rows(flat(c.normals));
        return py::make_tuple(to_numpy_rows(flat(c.points)), normals);
      },
      py::arg("path"),
      "read_points(path) -> (P, N or None)\n\n"
      "Reads a point cloud (.xyz/.txt/.pts with 3 or 6 numbers per line, .ply, .off, .obj). Returns P,\n"
      "float64 (n, 3), and N, float64 (n, 3) unit normals, or None when the file has none.\n"
      "Raises OSError naming the file and line for a missing, unreadable or malformed file.");

  m.def(
      "write_points",
      [](const py::handle& path, const py::handle& P, const py::handle& N) {
        const std::string p = path_text(path);
        edgefront::PointCloud c = point_cloud(P, N);
        py::gil_scoped_release release;
        edgefront::write_points(c, p);
      },
      py::arg("path"), py::arg("P"), py::arg("N") = py::none(),
      "write_points(path, P, N=None)\n\n"
      "Writes points (and normals) as .xyz/.txt/.pts or binary .ply, atomically.\n"
      "Raises ValueError for bad arrays, OSError when the file cannot be written.");

  m.def(
      "render_png",
      [](const py::handle& V, const py::handle& F, const py::handle& scalars, const py::handle& path, int width,
         int height, double azimuth, double elevation, bool color_bar) -> py::object {
        const edgefront::ArrayMesh am = array_mesh(V, F);
        edgefront::render::Scene scene{.mesh = &am.mesh};
        if (!scalars.is_none()) {
          scene.field = edgefront::render::ScalarField{
              .values = per_mesh_vertex(am, double_list(scalars, "scalars", static_cast<long>(am.report.input_vertices)))};
        }
        edgefront::render::RenderOptions o;
        o.width = width;
        o.height = height;
        o.azimuth_deg = azimuth;
        o.elevation_deg = elevation;
        o.color_bar = color_bar;
        if (!path.is_none()) {
          const std::string p = path_text(path);
          py::gil_scoped_release release;
          edgefront::render::render_png(scene, o, p);
          return py::none();
        }
        edgefront::render::Image image;
        {
          py::gil_scoped_release release;
          image = edgefront::render::render(scene, o);
        }
        return to_numpy<std::uint8_t>(std::move(image.rgb), {image.height, image.width, 3});
      },
      py::arg("V"), py::arg("F"), py::arg("scalars") = py::none(), py::arg("path") = py::none(), py::arg("width") = 800,
      py::arg("height") = 600, py::arg("azimuth") = 30.0, py::arg("elevation") = 20.0, py::arg("color_bar") = false,
      "render_png(V, F, scalars=None, path=None, width=800, height=600, azimuth=30, elevation=20, color_bar=False)\n\n"
      "Renders the mesh offscreen (the project's software rasterizer: Lambert shading with a headlight, back\n"
      "faces tinted orange, border loops in blue). scalars: n per-vertex values shown with a colormap and\n"
      "isolines (non-finite values grey). The camera looks at the bounding box's centre from azimuth degrees\n"
      "around +y (0 = from +z) and elevation degrees above the xz plane. With path: writes a PNG atomically\n"
      "and returns None; without: returns the image as a (height, width, 3) uint8 array.\n"
      "Raises ValueError for bad arrays or options, OSError when the file cannot be written.");
}

}  // namespace efpy
