#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "edgefront/error.h"
#include "edgefront/mesh.h"
#include "edgefront/mesh_io.h"
#include "edgefront/point_cloud_io.h"

namespace fs = std::filesystem;
using namespace edgefront;

namespace {

const fs::path kData = EDGEFRONT_TEST_DATA_DIR;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void spit(const fs::path& p, const std::string& content) {
  std::ofstream out(p, std::ios::binary);
  out << content;
}

/// The face's vertex indices, starting at the to-vertex of its halfedge (the order add_face got).
std::vector<std::array<int, 3>> face_triples(const Mesh& m) {
  std::vector<std::array<int, 3>> out;
  for (size_t i = 0; i < m.n_faces(); ++i) {
    const FaceHandle f(static_cast<int>(i));
    if (m.status(f).deleted()) continue;
    HalfedgeHandle h = m.halfedge_handle(f);
    std::array<int, 3> t;
    for (int k = 0; k < 3; ++k) {
      t[k] = m.to_vertex_handle(h).idx();
      h = m.next_halfedge_handle(h);
    }
    out.push_back(t);
  }
  return out;
}

/// Six vertices with awkward coordinates, three faces, vertex 5 isolated.
Mesh sample_mesh() {
  Mesh m;
  const Vec3 pts[] = {{0, 0, 0},
                      {1, 0, 0},
                      {0.1, 1, 0},
                      {1.25, 1.5, -0.3},
                      {1e-17, -3.5e3, 0.3333333333333333},
                      {2, std::nextafter(2.0, 3.0), -0.0}};
  for (const Vec3& p : pts) m.add_vertex(p);
  m.add_face(VertexHandle(0), VertexHandle(1), VertexHandle(2));
  m.add_face(VertexHandle(1), VertexHandle(3), VertexHandle(2));
  m.add_face(VertexHandle(0), VertexHandle(4), VertexHandle(1));
  return m;
}

const std::vector<std::array<int, 3>> kSampleFaces = {{0, 1, 2}, {1, 3, 2}, {0, 4, 1}};

class MeshIoTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ =
        fs::temp_directory_path() / ("edgefront_meshio_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  fs::path dir_;
};

/// Big-endian bytes of `value`.
template <class T>
void put_be(std::string& out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  if constexpr (std::endian::native == std::endian::little) {
    for (size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(bytes[i], bytes[sizeof(T) - 1 - i]);
  }
  out.append(bytes, sizeof(T));
}
template <class T>
void put_le(std::string& out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  if constexpr (std::endian::native == std::endian::big) {
    for (size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(bytes[i], bytes[sizeof(T) - 1 - i]);
  }
  out.append(bytes, sizeof(T));
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Round trips

TEST_F(MeshIoTest, EveryFormatRoundTripsVerticesAndFacesInOrder) {
  const Mesh m = sample_mesh();
  ASSERT_EQ(face_triples(m), kSampleFaces) << "the face order convention of add_face changed";
  struct Case {
    const char* name;
    bool binary;
  };
  for (const Case c :
       {Case{"a.off", true}, Case{"a.obj", true}, Case{"a.ply", true}, Case{"ascii.ply", false}}) {
    SCOPED_TRACE(c.name);
    const fs::path path = dir_ / c.name;
    MeshWriteOptions options;
    options.binary = c.binary;
    write_mesh(m, path, options);
    const MeshReadResult r = read_mesh(path);
    ASSERT_EQ(r.mesh.n_vertices(), m.n_vertices());
    for (size_t i = 0; i < m.n_vertices(); ++i) {
      const VertexHandle v(static_cast<int>(i));
      EXPECT_EQ(r.mesh.point(v), m.point(v)) << "vertex " << i;  // bit-exact
    }
    EXPECT_EQ(face_triples(r.mesh), kSampleFaces);
    EXPECT_EQ(r.report.vertices, 6u);
    EXPECT_EQ(r.report.faces_in_file, 3u);
    EXPECT_EQ(r.report.triangles_added, 3u);
    EXPECT_EQ(r.report.isolated_vertices, 1u);
    EXPECT_EQ(r.report.faces_dropped_nonmanifold + r.report.faces_dropped_invalid, 0u);
    ASSERT_EQ(r.report.warnings.size(), 1u) << ::testing::PrintToString(r.report.warnings);
    EXPECT_NE(r.report.warnings[0].find("isolated"), std::string::npos) << r.report.warnings[0];
  }
}

TEST_F(MeshIoTest, StlRoundTripMergesCornersAndKeepsFloatGeometry) {
  Mesh m = sample_mesh();
  m.point(VertexHandle(4)) = Vec3(0.5, -1, 0.25);  // representable in float
  const fs::path path = dir_ / "a.stl";
  write_mesh(m, path);
  EXPECT_EQ(fs::file_size(path), 84u + 3u * 50u);
  EXPECT_NE(slurp(path).substr(0, 5), "solid");
  const MeshReadResult r = read_mesh(path);
  EXPECT_EQ(r.report.faces_in_file, 3u);
  EXPECT_EQ(r.report.triangles_added, 3u);
  ASSERT_EQ(r.mesh.n_vertices(), 5u);  // the isolated vertex cannot be stored in STL
  // Corners are numbered in order of first appearance: 0, 1, 2, 3, 4.
  const int order[] = {0, 1, 2, 3, 4};
  for (int i = 0; i < 5; ++i) {
    const Vec3 expected = m.point(VertexHandle(order[i]));
    const Vec3 got = r.mesh.point(VertexHandle(i));
    for (int k = 0; k < 3; ++k) EXPECT_EQ(got[k], static_cast<double>(static_cast<float>(expected[k])));
  }
  EXPECT_EQ(face_triples(r.mesh), kSampleFaces);
}

TEST_F(MeshIoTest, WritesOnlyLiveElementsAndRenumbers) {
  Mesh m = sample_mesh();
  m.delete_vertex(VertexHandle(3), true);  // removes face (1,3,2)
  MeshWriteOptions options;
  options.binary = false;
  options.vertex_scalars = {{"value", {0, 1, 2, 3, 4, 5}}};
  const fs::path path = dir_ / "live.ply";
  write_mesh(m, path, options);
  const MeshReadResult r = read_mesh(path);
  ASSERT_EQ(r.mesh.n_vertices(), 5u);
  EXPECT_EQ(r.mesh.point(VertexHandle(3)), m.point(VertexHandle(4)));
  EXPECT_EQ(r.mesh.point(VertexHandle(4)), m.point(VertexHandle(5)));
  const std::vector<std::array<int, 3>> expected = {{0, 1, 2}, {0, 3, 1}};
  EXPECT_EQ(face_triples(r.mesh), expected);
  // The scalar of old vertex 4 is on the fourth vertex line.
  const std::string text = slurp(path);
  std::istringstream in(text.substr(text.find("end_header\n") + 11));
  std::string line;
  for (int i = 0; i < 4; ++i) std::getline(in, line);
  EXPECT_EQ(line.substr(line.rfind(' ') + 1), "4") << line;
}

TEST_F(MeshIoTest, PlyScalarsAndColorsAreWrittenAndReadable) {
  const Mesh m = sample_mesh();
  const double inf = std::numeric_limits<double>::infinity();
  MeshWriteOptions options;
  options.vertex_scalars = {{"distance", {0, 1.5, inf, 2, 3, inf}}, {"curvature", {-1, 0, 1, 2, 3, 4}}};
  options.vertex_colors = {{{255, 0, 0}}, {{0, 255, 0}}, {{0, 0, 255}},
                           {{1, 2, 3}},   {{4, 5, 6}},   {{7, 8, 9}}};
  for (const bool binary : {true, false}) {
    SCOPED_TRACE(binary ? "binary" : "ascii");
    options.binary = binary;
    const fs::path path = dir_ / (binary ? "scalars_bin.ply" : "scalars_ascii.ply");
    write_mesh(m, path, options);

    // Our own reader accepts the file (extra properties are skipped) and gets the geometry back.
    const MeshReadResult r = read_mesh(path);
    ASSERT_EQ(r.mesh.n_vertices(), 6u);
    EXPECT_EQ(face_triples(r.mesh), kSampleFaces);
    EXPECT_EQ(r.mesh.point(VertexHandle(4)), m.point(VertexHandle(4)));

    // The header declares the properties in order.
    const std::string text = slurp(path);
    const size_t end = text.find("end_header\n");
    ASSERT_NE(end, std::string::npos);
    std::istringstream header(text.substr(0, end));
    std::vector<std::string> vertex_props;
    std::string line, current;
    while (std::getline(header, line)) {
      std::istringstream ls(line);
      std::string kw;
      ls >> kw;
      if (kw == "element") ls >> current;
      if (kw == "property" && current == "vertex") vertex_props.push_back(line);
    }
    const std::vector<std::string> expected = {
        "property double x",         "property double y",  "property double z",    "property double distance",
        "property double curvature", "property uchar red", "property uchar green", "property uchar blue"};
    EXPECT_EQ(vertex_props, expected);
    EXPECT_NE(text.find(binary ? "format binary_little_endian 1.0" : "format ascii 1.0"), std::string::npos);

    // The values: vertex 2 has distance +inf and color (0, 0, 255).
    const std::string body = text.substr(end + 11);
    if (binary) {
      const size_t stride = 5 * 8 + 3;
      double distance = 0;
      std::memcpy(&distance, body.data() + 2 * stride + 24, 8);
      EXPECT_EQ(distance, inf);
      EXPECT_EQ(static_cast<unsigned char>(body[2 * stride + 40 + 2]), 255);
    } else {
      std::istringstream in(body);
      for (int i = 0; i < 3; ++i) std::getline(in, line);
      EXPECT_EQ(line, "0.1 1 0 inf 1 0 0 255");
    }
  }
}

TEST_F(MeshIoTest, OffWithColorsIsCoff) {
  const Mesh m = sample_mesh();
  MeshWriteOptions options;
  options.vertex_colors.assign(6, {{10, 20, 30}});
  const fs::path path = dir_ / "colors.off";
  write_mesh(m, path, options);
  const std::string text = slurp(path);
  EXPECT_EQ(text.substr(0, 5), "COFF\n");
  EXPECT_NE(text.find("0 0 0 10 20 30 255\n"), std::string::npos);
  const MeshReadResult r = read_mesh(path);
  EXPECT_EQ(r.mesh.n_vertices(), 6u);
  EXPECT_EQ(face_triples(r.mesh), kSampleFaces);
}

TEST_F(MeshIoTest, WriteOptionErrorsAreInvalidInputAndWriteNothing) {
  const Mesh m = sample_mesh();
  const auto refused = [&](const fs::path& path, const MeshWriteOptions& options) {
    EXPECT_THROW(write_mesh(m, path, options), InvalidInput) << path;
    EXPECT_FALSE(fs::exists(path)) << path;
  };
  MeshWriteOptions colors_short;
  colors_short.vertex_colors.assign(5, {{0, 0, 0}});
  refused(dir_ / "a.ply", colors_short);
  MeshWriteOptions scalar_short;
  scalar_short.vertex_scalars = {{"d", {1, 2, 3}}};
  refused(dir_ / "a.ply", scalar_short);
  MeshWriteOptions scalar_ok;
  scalar_ok.vertex_scalars = {{"d", std::vector<double>(6, 1.0)}};
  refused(dir_ / "a.off", scalar_ok);
  refused(dir_ / "a.obj", scalar_ok);
  MeshWriteOptions colors_ok;
  colors_ok.vertex_colors.assign(6, {{0, 0, 0}});
  refused(dir_ / "a.obj", colors_ok);
  MeshWriteOptions bad_name;
  bad_name.vertex_scalars = {{"my distance", std::vector<double>(6, 1.0)}};
  refused(dir_ / "a.ply", bad_name);
  MeshWriteOptions clash;
  clash.vertex_scalars = {{"x", std::vector<double>(6, 1.0)}};
  refused(dir_ / "a.ply", clash);
  refused(dir_ / "a.xyz", {});

  Mesh nan_mesh = sample_mesh();
  nan_mesh.point(VertexHandle(2))[1] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(write_mesh(nan_mesh, dir_ / "nan.off"), InvalidInput);
}

TEST_F(MeshIoTest, WriteFailureIsIoErrorAndKeepsTheOldFile) {
  EXPECT_THROW(write_mesh(sample_mesh(), dir_ / "missing_dir" / "a.off"), IoError);
}

TEST_F(MeshIoTest, PolylineObjAndPly) {
  const std::vector<Vec3> pts = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {1, 1, 0.5}};
  write_polyline(pts, dir_ / "path.obj");
  const std::string obj = slurp(dir_ / "path.obj");
  EXPECT_NE(obj.find("v 1 1 0.5\n"), std::string::npos) << obj;
  EXPECT_NE(obj.find("\nl 1 2 3 4\n"), std::string::npos) << obj;
  // The vertices read back as a mesh without faces.
  const MeshReadResult r = read_mesh(dir_ / "path.obj");
  EXPECT_EQ(r.mesh.n_vertices(), 4u);
  EXPECT_EQ(r.mesh.n_faces(), 0u);

  write_polyline(pts, dir_ / "path.ply");
  const std::string ply = slurp(dir_ / "path.ply");
  EXPECT_NE(ply.find("element edge 3\nproperty int vertex1\nproperty int vertex2\n"), std::string::npos);
  const PointCloud cloud = read_points(dir_ / "path.ply");
  EXPECT_EQ(cloud.points, pts);

  write_polyline({{1, 2, 3}}, dir_ / "single.obj");
  EXPECT_EQ(slurp(dir_ / "single.obj").find("\nl"), std::string::npos);
  EXPECT_THROW(write_polyline(pts, dir_ / "path.off"), InvalidInput);
  EXPECT_THROW(write_polyline({{0, 0, std::numeric_limits<double>::infinity()}}, dir_ / "x.obj"),
               InvalidInput);
}

// ---------------------------------------------------------------------------------------------
// Reading valid files

TEST_F(MeshIoTest, ReadsTetrahedronOffAndLoadMesh) {
  const Mesh m = load_mesh(kData / "tetra.off");
  EXPECT_EQ(m.n_vertices(), 4u);
  EXPECT_EQ(m.n_faces(), 4u);
  EXPECT_EQ(m.point(VertexHandle(3)), Vec3(0, 0, 1));
  const std::vector<std::array<int, 3>> expected = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  EXPECT_EQ(face_triples(m), expected);
  // Face normals are up to date and point outward.
  EXPECT_NEAR(m.normal(FaceHandle(0))[2], -1.0, 1e-12);
}

TEST_F(MeshIoTest, ExtensionIsCaseInsensitiveAndCrlfIsAccepted) {
  std::string text = slurp(kData / "tetra.off");
  std::string crlf;
  for (const char c : text) {
    if (c == '\n') crlf += '\r';
    crlf += c;
  }
  spit(dir_ / "TETRA.OFF", crlf);
  const MeshReadResult r = read_mesh(dir_ / "TETRA.OFF");
  EXPECT_EQ(r.mesh.n_faces(), 4u);
  EXPECT_TRUE(r.report.warnings.empty());
}

TEST_F(MeshIoTest, OffVariants) {
  const std::string body = "0 0 0 1 0 0 1\n1 0 0 0 1 0 1\n0 1 0 0 0 1 1\n3 0 1 2 200 10 10\n";
  EXPECT_EQ(read_mesh_from_buffer("COFF\n3 1 0\n" + body, "c.off").mesh.n_faces(), 1u);
  EXPECT_EQ(read_mesh_from_buffer("NOFF\n3 1\n" + body, "n.off").mesh.n_faces(), 1u);
  EXPECT_EQ(read_mesh_from_buffer("OFF 3 1 0\n" + body, "same_line.off").mesh.n_faces(), 1u);
  EXPECT_EQ(read_mesh_from_buffer("# lead\nOFF # keyword\n\n3 1 0\n" + body, "comments.off").mesh.n_faces(),
            1u);
  const MeshReadResult trailing = read_mesh_from_buffer("OFF\n3 1 0\n" + body + "junk\n", "trailing.off");
  ASSERT_EQ(trailing.report.warnings.size(), 1u);
  EXPECT_NE(trailing.report.warnings[0].find("line 7"), std::string::npos) << trailing.report.warnings[0];
  EXPECT_THROW(read_mesh_from_buffer("4OFF\n3 1 0\n" + body, "four.off"), IoError);
  EXPECT_THROW(read_mesh_from_buffer("OFF BINARY\n", "binary.off"), IoError);
  EXPECT_THROW(read_mesh_from_buffer("OFF\n3 x 0\n" + body, "count.off"), IoError);
  EXPECT_THROW(read_mesh_from_buffer("OFF\n-3 1 0\n" + body, "negative.off"), IoError);
  EXPECT_THROW(read_mesh_from_buffer("OFF\n3\n" + body, "one_count.off"), IoError);
}

TEST_F(MeshIoTest, StlWithSeveralSolidsAndOddCase) {
  const std::string facet =
      "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n";
  const std::string facet2 =
      "FACET NORMAL 0 0 1\nOUTER LOOP\nVERTEX 1 0 0\nVERTEX 1 1 0\nVERTEX 0 1 0\nENDLOOP\nENDFACET\n";
  const MeshReadResult r = read_mesh_from_buffer(
      "solid a\n" + facet + "endsolid a\nsolid b\n" + facet2 + "endsolid b\n", "two.stl");
  EXPECT_EQ(r.mesh.n_vertices(), 4u);
  EXPECT_EQ(r.mesh.n_faces(), 2u);
  EXPECT_TRUE(r.report.warnings.empty());
  const MeshReadResult open = read_mesh_from_buffer("solid a\n" + facet, "open.stl");
  EXPECT_EQ(open.mesh.n_faces(), 1u);
  ASSERT_EQ(open.report.warnings.size(), 1u);
  EXPECT_NE(open.report.warnings[0].find("endsolid"), std::string::npos);
  EXPECT_THROW(
      read_mesh_from_buffer("solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nendloop\nendfacet\n",
                            "one_corner.stl"),
      IoError);
  EXPECT_THROW(read_mesh_from_buffer("solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 nan\n", "nan.stl"),
               IoError);
}

TEST_F(MeshIoTest, VerticesOnlyFileIsAMeshWithoutFaces) {
  const MeshReadResult r = read_mesh(kData / "vertices_only.off");
  EXPECT_EQ(r.mesh.n_vertices(), 5u);
  EXPECT_EQ(r.mesh.n_faces(), 0u);
  EXPECT_EQ(r.report.isolated_vertices, 5u);
  EXPECT_TRUE(r.report.warnings.empty());
}

TEST_F(MeshIoTest, PolygonsAreFanTriangulatedAndCounted) {
  const MeshReadResult r = read_mesh(kData / "bad" / "polygon.obj");
  EXPECT_EQ(r.report.faces_in_file, 2u);
  EXPECT_EQ(r.report.polygons_triangulated, 2u);
  EXPECT_EQ(r.report.triangles_added, 5u);
  EXPECT_EQ(r.mesh.n_faces(), 5u);
  ASSERT_FALSE(r.report.warnings.empty());
  EXPECT_EQ(r.report.warnings[0], "2 polygons were triangulated into 5 triangles");
  const std::vector<std::array<int, 3>> expected = {{0, 1, 2}, {0, 2, 3}, {1, 4, 5}, {1, 5, 6}, {1, 6, 2}};
  EXPECT_EQ(face_triples(r.mesh), expected);
}

TEST_F(MeshIoTest, NonManifoldFacesAreDroppedOrRefusedWithoutOpenMeshChatter) {
  const fs::path file = kData / "bad" / "nonmanifold.off";
  ::testing::internal::CaptureStderr();
  const MeshReadResult r = read_mesh(file);
  const std::string chatter = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(chatter, "");
  EXPECT_EQ(r.report.faces_in_file, 3u);
  EXPECT_EQ(r.report.triangles_added, 2u);
  EXPECT_EQ(r.report.faces_dropped_nonmanifold, 1u);
  EXPECT_EQ(r.report.isolated_vertices, 1u);  // vertex 4 belonged to the dropped face only
  bool mentioned = false;
  for (const std::string& w : r.report.warnings)
    mentioned |= w.find("non-manifold") != std::string::npos && w.find("line 11") != std::string::npos;
  EXPECT_TRUE(mentioned);

  MeshReadOptions strict;
  strict.drop_nonmanifold_faces = false;
  try {
    read_mesh(file, strict);
    FAIL() << "strict mode accepted a non-manifold file";
  } catch (const IoError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("nonmanifold.off"), std::string::npos) << what;
    EXPECT_NE(what.find("line 11"), std::string::npos) << what;
    EXPECT_NE(what.find("non-manifold"), std::string::npos) << what;
  }
}

TEST_F(MeshIoTest, RepeatedIndexDuplicateAndDegenerateFacesAreCounted) {
  const MeshReadResult r = read_mesh(kData / "bad" / "repeated_index.off");
  EXPECT_EQ(r.report.faces_dropped_invalid, 1u);
  EXPECT_EQ(r.report.triangles_added, 1u);
  EXPECT_EQ(r.report.isolated_vertices, 1u);

  // (0 1 2) and (0 2 1) close up and are both kept; (1 2 0) repeats an oriented face: refused.
  // (3 4 5) is collinear.
  spit(dir_ / "dup.off",
       "OFF\n6 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 5\n1 0 5\n2 0 5\n3 0 1 2\n3 0 2 1\n3 1 2 0\n3 3 4 5\n");
  const MeshReadResult d = read_mesh(dir_ / "dup.off");
  EXPECT_EQ(d.report.triangles_added, 3u);
  EXPECT_EQ(d.report.duplicate_faces, 2u);
  EXPECT_EQ(d.report.faces_dropped_nonmanifold, 1u);
  EXPECT_EQ(d.report.degenerate_faces, 1u);
}

TEST_F(MeshIoTest, ObjIndexFormsAndIgnoredRecords) {
  spit(dir_ / "forms.obj",
       "# comment\nmtllib x.mtl\no thing\nv 0 0 0\nv 1 0 0 1.0\nv 0 1 0 0.5 0.5 0.5\nvt 0 0\nvn 0 0 1\n"
       "g group\nusemtl m\ns off\nf 1/1/1 2/1/1 3/1/1\nv 5 5 5\nv 6 5 5\nv 5 6 5\nf -3//1 -2//1 -1//1\n"
       "l 1 2\nfrobnicate 1 2 3\n");
  const MeshReadResult r = read_mesh(dir_ / "forms.obj");
  EXPECT_EQ(r.mesh.n_vertices(), 6u);
  const std::vector<std::array<int, 3>> expected = {{0, 1, 2}, {3, 4, 5}};
  EXPECT_EQ(face_triples(r.mesh), expected);
  ASSERT_EQ(r.report.warnings.size(), 2u);
  EXPECT_NE(r.report.warnings[0].find("'frobnicate' at line 18"), std::string::npos) << r.report.warnings[0];
  EXPECT_NE(r.report.warnings[1].find("'l'"), std::string::npos) << r.report.warnings[1];

  spit(dir_ / "zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n");
  EXPECT_THROW(read_mesh(dir_ / "zero.obj"), IoError);
  spit(dir_ / "rel.obj", "v 0 0 0\nf -1 -2 -3\n");
  EXPECT_THROW(read_mesh(dir_ / "rel.obj"), IoError);
}

TEST_F(MeshIoTest, BigEndianPlyWithMixedTypesAndIgnoredProperties) {
  std::string d =
      "ply\nformat binary_big_endian 1.0\ncomment hand-made in the test\n"
      "element vertex 4\nproperty double x\nproperty float y\nproperty int z\nproperty uchar confidence\n"
      "property list uchar float texcoord\n"
      "element face 2\nproperty uchar flags\nproperty list ushort uint vertex_indices\nproperty list int "
      "short other\n"
      "element edge 1\nproperty int vertex1\nproperty int vertex2\n"
      "end_header\n";
  const double xs[] = {0.5, 1.5, 0, 0};
  const float ys[] = {0, 0, 2.25f, 0};
  const int32_t zs[] = {0, 0, 0, -7};
  for (int i = 0; i < 4; ++i) {
    put_be<double>(d, xs[i]);
    put_be<float>(d, ys[i]);
    put_be<int32_t>(d, zs[i]);
    put_be<uint8_t>(d, 200);
    put_be<uint8_t>(d, static_cast<uint8_t>(i));  // i texcoords to skip
    for (int k = 0; k < i; ++k) put_be<float>(d, 0.25f);
  }
  const uint32_t faces[2][4] = {{0, 1, 2, 3}, {1, 0, 3, 0}};
  for (int f = 0; f < 2; ++f) {
    put_be<uint8_t>(d, 9);
    put_be<uint16_t>(d, f == 0 ? 4 : 3);  // a quad, then a triangle
    for (int k = 0; k < (f == 0 ? 4 : 3); ++k) put_be<uint32_t>(d, faces[f][k]);
    put_be<int32_t>(d, 2);
    put_be<int16_t>(d, -1);
    put_be<int16_t>(d, -2);
  }
  put_be<int32_t>(d, 0);
  put_be<int32_t>(d, 1);
  spit(dir_ / "be.ply", d);

  const MeshReadResult r = read_mesh(dir_ / "be.ply");
  ASSERT_EQ(r.mesh.n_vertices(), 4u);
  EXPECT_EQ(r.mesh.point(VertexHandle(0)), Vec3(0.5, 0, 0));
  EXPECT_EQ(r.mesh.point(VertexHandle(2)), Vec3(0, 2.25, 0));
  EXPECT_EQ(r.mesh.point(VertexHandle(3)), Vec3(0, 0, -7));
  EXPECT_EQ(r.report.faces_in_file, 2u);
  EXPECT_EQ(r.report.polygons_triangulated, 1u);
  EXPECT_EQ(r.report.triangles_added, 3u);
  const std::vector<std::array<int, 3>> expected = {{0, 1, 2}, {0, 2, 3}, {1, 0, 3}};
  EXPECT_EQ(face_triples(r.mesh), expected);
  bool edge_warning = false;
  for (const std::string& w : r.report.warnings) edge_warning |= w.find("'edge'") != std::string::npos;
  EXPECT_TRUE(edge_warning);

  // Cut the file inside the last face: a truncation error naming the face.
  spit(dir_ / "be_cut.ply", d.substr(0, d.size() - 14));
  try {
    read_mesh(dir_ / "be_cut.ply");
    FAIL() << "truncated binary PLY accepted";
  } catch (const IoError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("be_cut.ply"), std::string::npos) << what;
    EXPECT_NE(what.find("truncated"), std::string::npos) << what;
  }
}

TEST_F(MeshIoTest, LittleEndianPlyWithVertexIndexNameAndAsciiUshortCounts) {
  std::string d =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list int int vertex_index\nend_header\n";
  for (const float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) put_le<float>(d, v);
  put_le<int32_t>(d, 3);
  for (const int32_t i : {2, 1, 0}) put_le<int32_t>(d, i);
  spit(dir_ / "le.ply", d);
  const MeshReadResult r = read_mesh(dir_ / "le.ply");
  const std::vector<std::array<int, 3>> expected = {{2, 1, 0}};
  EXPECT_EQ(face_triples(r.mesh), expected);

  spit(dir_ / "ascii.ply",
       "ply\nformat ascii 1.0\nobj_info made by hand\nelement vertex 3\nproperty uchar x\nproperty short y\n"
       "property double z\nelement face 1\nproperty list ushort uint vertex_indices\nproperty float quality\n"
       "end_header\n0 0 0\n1 0 0\n\n0 1 0\n3 0 1 2 0.5\n");
  const MeshReadResult a = read_mesh(dir_ / "ascii.ply");
  EXPECT_EQ(a.mesh.n_faces(), 1u);
  EXPECT_EQ(a.mesh.point(VertexHandle(2)), Vec3(0, 1, 0));
}

TEST_F(MeshIoTest, AsciiStlIsMergedInOrderOfFirstAppearance) {
  const MeshReadResult r = read_mesh(kData / "tetra_ascii.stl");
  ASSERT_EQ(r.mesh.n_vertices(), 4u);
  EXPECT_EQ(r.mesh.point(VertexHandle(0)), Vec3(0, 0, 0));
  EXPECT_EQ(r.mesh.point(VertexHandle(1)), Vec3(0, 1, 0));
  EXPECT_EQ(r.mesh.point(VertexHandle(2)), Vec3(1, 0, 0));
  EXPECT_EQ(r.mesh.point(VertexHandle(3)), Vec3(0, 0, 1));
  EXPECT_EQ(r.report.faces_in_file, 4u);
  EXPECT_EQ(r.report.triangles_added, 4u);
  EXPECT_EQ(r.report.isolated_vertices, 0u);
  EXPECT_TRUE(r.report.warnings.empty());
  for (const VertexHandle v : r.mesh.vertices()) EXPECT_FALSE(r.mesh.is_boundary(v));
}

TEST_F(MeshIoTest, BinaryStlWithSolidHeaderAndSignedZero) {
  std::string d = "solid this binary file's header starts with solid";
  d.resize(80, ' ');
  put_le<uint32_t>(d, 2);
  const float tris[2][3][3] = {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{1, -0.0f, 0}, {1, 1, 0}, {0, 1, -0.0f}}};
  for (const auto& t : tris) {
    for (int k = 0; k < 3; ++k) put_le<float>(d, 0);
    for (const auto& c : t) {
      for (const float x : c) put_le<float>(d, x);
    }
    put_le<uint16_t>(d, 0);
  }
  spit(dir_ / "bin.stl", d);
  const MeshReadResult r = read_mesh(dir_ / "bin.stl");
  EXPECT_EQ(r.mesh.n_vertices(), 4u);  // -0 and +0 merge
  EXPECT_EQ(r.mesh.n_faces(), 2u);
  const std::vector<std::array<int, 3>> expected = {{0, 1, 2}, {1, 3, 2}};
  EXPECT_EQ(face_triples(r.mesh), expected);
}

// ---------------------------------------------------------------------------------------------
// Bad input: every case has a file under tests/data/bad/; the message names the file and the
// problem.

struct BadFile {
  const char* file;
  std::vector<const char*> message_parts;
};

void PrintTo(const BadFile& b, std::ostream* os) { *os << b.file; }

class MeshIoBadFile : public ::testing::TestWithParam<BadFile> {};

TEST_P(MeshIoBadFile, IsRefusedWithAClearMessage) {
  const BadFile& c = GetParam();
  const fs::path path = kData / "bad" / c.file;
  try {
    read_mesh(path);
    FAIL() << c.file << " was accepted";
  } catch (const IoError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(c.file), std::string::npos) << "message does not name the file: " << what;
    for (const char* part : c.message_parts) {
      EXPECT_NE(what.find(part), std::string::npos) << "expected '" << part << "' in: " << what;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(
    MeshIo, MeshIoBadFile,
    ::testing::Values(
        BadFile{"does_not_exist.off", {"does not exist"}},
        BadFile{"unknown_extension.abc", {"unknown mesh file extension '.abc'"}},
        BadFile{"empty.off", {"file is empty"}}, BadFile{"empty.stl", {"file is empty"}},
        BadFile{"truncated.off", {"truncated", "4 vertices", "after 3"}},
        BadFile{"truncated_faces.off", {"truncated", "4 faces", "after 2"}},
        BadFile{"truncated.ply", {"line 10", "truncated"}},
        BadFile{"truncated_ascii.stl", {"truncated", "facet 0"}},
        BadFile{"truncated_binary.stl", {"truncated", "10 triangles"}},
        BadFile{"nan.obj", {"line 4", "non-finite coordinate (nan, 1, 0)"}},
        BadFile{"inf.off", {"line 4", "non-finite"}},
        BadFile{"malformed_number.off", {"line 4", "malformed number '1.2.3'"}},
        BadFile{"index_out_of_range.ply", {"line 15", "vertex index 7 is out of range", "4 vertices"}},
        BadFile{"negative_index.off", {"line 6", "negative vertex index -1"}},
        BadFile{"two_index_face.obj", {"line 4", "at least 3"}},
        BadFile{"two_index_face.off", {"line 6", "at least 3"}},
        BadFile{"short_face_list.ply", {"line 13", "declares 3 items"}},
        BadFile{"huge_count.ply", {"1000000000000", "truncated or corrupt"}},
        BadFile{"huge_count.off", {"line 2", "declares 1000000000000 vertices", "truncated or corrupt"}},
        BadFile{"bad_header.ply", {"line 4", "bad PLY header", "unknown type 'flaot'"}},
        BadFile{"no_end_header.ply", {"end_header"}},
        BadFile{"not_a_mesh.off", {"line 1", "not an OFF file"}},
        BadFile{"not_a_mesh.obj", {"line 1", "not an OBJ file"}}));

TEST_F(MeshIoTest, ReadFromBufferUsesTheNameForFormatAndMessages) {
  const MeshReadResult r = read_mesh_from_buffer(slurp(kData / "tetra.off"), "in_memory.OFF");
  EXPECT_EQ(r.mesh.n_faces(), 4u);
  try {
    read_mesh_from_buffer("OFF\n1 0 0\n0 0\n", "memory.off");
    FAIL() << "accepted";
  } catch (const IoError& e) {
    EXPECT_STREQ(e.what(), "memory.off: line 3: vertex 0: expected 3 coordinates, found 2");
  }
  EXPECT_THROW(read_mesh_from_buffer("", "memory.off"), IoError);
  EXPECT_THROW(read_mesh_from_buffer("OFF\n0 0 0\n", "memory.dat"), IoError);
}

TEST_F(MeshIoTest, DirectoryAndBinaryGarbageAreRefused) {
  EXPECT_THROW(read_mesh(dir_ / ".." / (dir_.filename().string() + ".off")), IoError);
  fs::create_directories(dir_ / "folder.off");
  EXPECT_THROW(read_mesh(dir_ / "folder.off"), IoError);
  spit(dir_ / "garbage.ply", std::string("\x7f"
                                         "ELF\0\0\0binary",
                                         13));
  EXPECT_THROW(read_mesh(dir_ / "garbage.ply"), IoError);
  spit(dir_ / "garbage.obj", std::string("v 0 0 0\0\0\0", 10));
  EXPECT_THROW(read_mesh(dir_ / "garbage.obj"), IoError);
  spit(dir_ / "tiny.stl", "abc");
  EXPECT_THROW(read_mesh(dir_ / "tiny.stl"), IoError);
  // A list count of 4 billion in a tiny binary file must not allocate.
  std::string d =
      "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uint int vertex_indices\nend_header\n";
  for (int k = 0; k < 3; ++k) put_le<float>(d, 0);
  put_le<uint32_t>(d, 4000000000u);
  spit(dir_ / "huge_list.ply", d);
  EXPECT_THROW(read_mesh(dir_ / "huge_list.ply"), IoError);
}

// ---------------------------------------------------------------------------------------------
// Robustness: damaged copies of valid files (every truncation, and pseudo-random byte changes)
// are read or refused with IoError; never another exception, a crash or a hang. In memory, as
// file system writes cost milliseconds each here.

TEST_F(MeshIoTest, DamagedFilesAreReadOrRefusedWithIoErrorOnly) {
  const Mesh m = sample_mesh();
  MeshWriteOptions ascii;
  ascii.binary = false;
  ascii.vertex_scalars = {{"d", {0, 1, 2, 3, 4, 5}}};
  write_mesh(m, dir_ / "src.off");
  write_mesh(m, dir_ / "src.obj");
  write_mesh(m, dir_ / "src.ply");
  write_mesh(m, dir_ / "src_ascii.ply", ascii);
  write_mesh(m, dir_ / "src.stl");
  fs::copy_file(kData / "tetra_ascii.stl", dir_ / "src_ascii.stl");

  uint64_t state = 12345;
  const auto next = [&state]() {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<uint32_t>(state >> 33);
  };
  const char replacements[] = {'\0', '9', '-', ' ', '\n', 'x', '.', '\xff', 'e', '#'};
  size_t reads = 0, refused = 0;
  for (const char* name : {"src.off", "src.obj", "src.ply", "src_ascii.ply", "src.stl", "src_ascii.stl"}) {
    const std::string original = slurp(dir_ / name);
    const fs::path damaged = dir_ / ("damaged" + fs::path(name).extension().string());
    const auto check = [&](const std::string& content, const std::string& what) {
      ++reads;
      try {
        read_mesh_from_buffer(content, damaged);
      } catch (const IoError&) {
        ++refused;
      } catch (const std::exception& e) {
        ADD_FAILURE() << name << " " << what << ": unexpected exception: " << e.what();
      }
    };
    for (size_t cut = 0; cut < original.size(); cut += 3)
      check(original.substr(0, cut), "cut at " + std::to_string(cut));
    for (int k = 0; k < 150; ++k) {
      std::string content = original;
      const size_t at = next() % content.size();
      content[at] = replacements[next() % sizeof(replacements)];
      check(content, "byte " + std::to_string(at) + " changed");
    }
  }
  EXPECT_GT(refused, reads / 4);  // most cuts are refused
}

// ---------------------------------------------------------------------------------------------
// Hostile input: non-regular files, huge sparse files, byte-order marks, extreme coordinates,
// numbers beyond double, miscounted PLY vertices.

namespace {

/// Creates a FIFO; a helper thread opens its writing end after `delay` and closes it again, so
/// that a reader that (wrongly) blocks on the FIFO is released instead of hanging the test.
class FifoWithLateWriter {
 public:
  FifoWithLateWriter(const fs::path& path, std::chrono::milliseconds delay) : path_(path) {
    EXPECT_EQ(::mkfifo(path.c_str(), 0600), 0);
    writer_ = std::thread([this, delay] {
      std::this_thread::sleep_for(delay);
      const int fd = ::open(path_.c_str(), O_WRONLY | O_NONBLOCK);
      if (fd >= 0) ::close(fd);
    });
  }
  ~FifoWithLateWriter() { writer_.join(); }

 private:
  fs::path path_;
  std::thread writer_;
};

/// `what()` of the IoError `f` throws, or "" (with a test failure) when it throws nothing or
/// something else.
template <class F>
std::string io_error_of(F&& f) {
  try {
    f();
  } catch (const IoError& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not an IoError: " << e.what();
    return "";
  }
  ADD_FAILURE() << "accepted";
  return "";
}

}  // namespace

TEST_F(MeshIoTest, FifosDevicesAndDirectoriesAreRefusedBeforeOpening) {
  for (const char* name : {"pipe.off", "pipe.ply", "pipe.xyz"}) {
    const fs::path fifo = dir_ / name;
    FifoWithLateWriter guard(fifo, std::chrono::milliseconds(300));
    const auto t0 = std::chrono::steady_clock::now();
    const std::string what = fifo.extension() == ".xyz" ? io_error_of([&] { read_points(fifo); })
                                                        : io_error_of([&] { read_mesh(fifo); });
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_NE(what.find("is a FIFO (named pipe), not a regular file"), std::string::npos) << what;
    EXPECT_LT(seconds, 1.0) << "the reader waited for a writer on " << name;
  }
  // A device through a name with a mesh extension: /dev/zero would be read without end.
  fs::create_symlink("/dev/zero", dir_ / "zero.ply");
  EXPECT_NE(io_error_of([&] { read_mesh(dir_ / "zero.ply"); }).find("is a character device, not a regular file"),
            std::string::npos);
  fs::create_symlink("/dev/urandom", dir_ / "random.xyz");
  EXPECT_NE(io_error_of([&] { read_points(dir_ / "random.xyz"); }).find("character device"), std::string::npos);
  fs::create_directories(dir_ / "folder.obj");
  EXPECT_NE(io_error_of([&] { read_mesh(dir_ / "folder.obj"); }).find("is a directory, not a regular file"),
            std::string::npos);
}

TEST_F(MeshIoTest, HugeSparseFilesAreRefusedAfterTheirFirstBytes) {
  // 2 GiB of zeros that take no disk space: every reader must refuse them at once, without
  // reading (or allocating) 2 GiB.
  for (const char* name : {"sparse.off", "sparse.obj", "sparse.ply", "sparse.stl", "sparse.xyz"}) {
    const fs::path file = dir_ / name;
    { std::ofstream touch(file); }
    fs::resize_file(file, uint64_t{2} << 30);
    const auto t0 = std::chrono::steady_clock::now();
    const std::string what = file.extension() == ".xyz" ? io_error_of([&] { read_points(file); })
                                                        : io_error_of([&] { read_mesh(file); });
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_NE(what.find(name), std::string::npos) << what;
    EXPECT_LT(seconds, 1.0) << name << ": " << what;
    fs::remove(file);
  }
}

TEST_F(MeshIoTest, BinaryStlWithMoreDataThanItsCountIsRefused) {
  std::string d(80, ' ');
  put_le<uint32_t>(d, 1);
  d.append(50, '\0');
  d.append(50 * 3, '\0');  // three more facets' worth the count does not declare
  spit(dir_ / "extra.stl", d);
  const std::string what = io_error_of([&] { read_mesh(dir_ / "extra.stl"); });
  EXPECT_NE(what.find("declares 1 triangle"), std::string::npos) << what;
  // A few bytes of padding after the last facet are still only a warning.
  std::string padded(80, ' ');
  put_le<uint32_t>(padded, 1);
  for (const float v : {0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) put_le<float>(padded, v);
  put_le<uint16_t>(padded, 0);
  padded.append(4, '\0');
  spit(dir_ / "padded.stl", padded);
  const MeshReadResult r = read_mesh(dir_ / "padded.stl");
  EXPECT_EQ(r.mesh.n_faces(), 1u);
  ASSERT_EQ(r.report.warnings.size(), 1u);
  EXPECT_NE(r.report.warnings[0].find("4 bytes after the last triangle"), std::string::npos);
}

TEST_F(MeshIoTest, Utf8ByteOrderMarkIsAcceptedByEveryTextReader) {
  const std::string bom = "\xEF\xBB\xBF";
  const std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 4 2\n";
  const std::string off = "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n3 0 3 1\n";
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty double x\nproperty double y\nproperty double z\n"
      "element face 2\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n"
      "3 0 1 2\n3 0 3 1\n";
  const std::string stl = slurp(kData / "tetra_ascii.stl");
  for (const auto& [name, text] : {std::pair<std::string, std::string>{"a.obj", obj}, {"a.off", off},
                                   {"a.ply", ply}, {"a.stl", stl}}) {
    spit(dir_ / name, text);
    spit(dir_ / ("bom_" + name), bom + text);
    const MeshReadResult plain = read_mesh(dir_ / name);
    const MeshReadResult marked = read_mesh(dir_ / ("bom_" + name));
    EXPECT_EQ(marked.mesh.n_vertices(), plain.mesh.n_vertices()) << name;
    EXPECT_EQ(face_triples(marked.mesh), face_triples(plain.mesh)) << name;
    EXPECT_EQ(marked.report.warnings, plain.report.warnings) << name;
    if (name != "a.stl") {
      EXPECT_EQ(read_points(dir_ / ("bom_" + name)).points, read_points(dir_ / name).points) << name;
    }
  }
  spit(dir_ / "bom.xyz", bom + "0 0 0\n1 0 0\n0 1 0\n");
  EXPECT_EQ(read_points(dir_ / "bom.xyz").size(), 3u);
  // UTF-16 is named, not called binary garbage.
  spit(dir_ / "utf16.obj", std::string("\xFF\xFEv\0 \0" "0\0", 8));
  EXPECT_NE(io_error_of([&] { read_mesh(dir_ / "utf16.obj"); }).find("UTF-16"), std::string::npos);
}

TEST_F(MeshIoTest, CoordinatesWhoseSquaresOverflowOrUnderflowAreRefused) {
  const auto off = [](const std::string& a, const std::string& b) {
    return "OFF\n3 1 0\n0 0 0\n" + a + " 0 0\n0 " + b + " 0\n3 0 1 2\n";
  };
  spit(dir_ / "huge.off", off("1e308", "1"));
  std::string what = io_error_of([&] { read_mesh(dir_ / "huge.off"); });
  EXPECT_NE(what.find("vertex 1 has the coordinate 1e308, beyond +-1e75"), std::string::npos) << what;
  EXPECT_NE(what.find("overflow"), std::string::npos) << what;
  EXPECT_EQ(io_error_of([&] { read_points(dir_ / "huge.off"); }), what) << "the cloud reader says the same";
  spit(dir_ / "tiny.off", off("1e-310", "2e-310"));
  what = io_error_of([&] { read_mesh(dir_ / "tiny.off"); });
  EXPECT_NE(what.find("span only 2e-310"), std::string::npos) << what;
  EXPECT_NE(what.find("underflow"), std::string::npos) << what;
  // Ordinary small and large scales are fine, and so is a single point.
  spit(dir_ / "fine.off", off("1e60", "1e-60"));
  EXPECT_NO_THROW(read_mesh(dir_ / "fine.off"));
  spit(dir_ / "point.xyz", "1e-300 0 0\n");
  EXPECT_NO_THROW(read_points(dir_ / "point.xyz"));
  spit(dir_ / "huge.xyz", "0 0 0\n1e200 0 0\n0 1 0\n");
  EXPECT_NE(io_error_of([&] { read_points(dir_ / "huge.xyz"); }).find("huge.xyz: point 1 has the coordinate 1e200"),
            std::string::npos);
}

TEST_F(MeshIoTest, NumbersBeyondDoubleAreOutOfRangeNotMalformed) {
  spit(dir_ / "big.off", "OFF\n1 0 0\n1e400 0 0\n");
  const std::string what = io_error_of([&] { read_mesh(dir_ / "big.off"); });
  EXPECT_NE(what.find("number '1e400' is out of the range of a double (+-1.8e308)"), std::string::npos) << what;
  spit(dir_ / "big.xyz", "0 0 -1e999\n");
  EXPECT_NE(io_error_of([&] { read_points(dir_ / "big.xyz"); }).find("'-1e999' is out of the range"),
            std::string::npos);
  spit(dir_ / "bad.xyz", "0 0 1e400x\n");
  EXPECT_NE(io_error_of([&] { read_points(dir_ / "bad.xyz"); }).find("malformed number '1e400x'"),
            std::string::npos);
}

TEST_F(MeshIoTest, PlyVertexCountOneOffIsReportedAsSuch) {
  // The same tetrahedron as binary and ascii PLY, with the vertex count one too high and one too
  // low: the mesh and the cloud reader both name the count.
  const Mesh tetra = load_mesh(kData / "tetra.off");
  MeshWriteOptions ascii;
  ascii.binary = false;
  for (const bool binary : {true, false}) {
    const fs::path good = dir_ / (binary ? "good_bin.ply" : "good_ascii.ply");
    write_mesh(tetra, good, binary ? MeshWriteOptions{} : ascii);
    const std::string text = slurp(good);
    for (const auto& [count, word] : {std::pair{"5", "high"}, std::pair{"3", "low"}}) {
      std::string bad = text;
      const size_t at = bad.find("element vertex 4");
      ASSERT_NE(at, std::string::npos);
      bad.replace(at, 16, std::string("element vertex ") + count);
      const fs::path file = dir_ / ("off_by_one_" + std::string(word) + (binary ? "_bin.ply" : "_ascii.ply"));
      spit(file, bad);
      const std::string what = io_error_of([&] { read_mesh(file); });
      EXPECT_NE(what.find(std::string("the header declares ") + count + " vertices but the data holds 4: the "
                          "vertex count is one too " + word),
                std::string::npos)
          << what;
      EXPECT_EQ(io_error_of([&] { read_points(file); }), what);
    }
  }
}

TEST_F(MeshIoTest, TheCloudReaderRefusesWhatTheMeshReaderRefusesWithTheSameMessage) {
  size_t compared = 0;
  for (const fs::directory_entry& entry : fs::directory_iterator(kData / "bad")) {
    const std::string ext = entry.path().extension().string();
    if (ext != ".off" && ext != ".obj" && ext != ".ply") continue;
    std::string mesh_error;
    try {
      read_mesh(entry.path());
    } catch (const IoError& e) {
      mesh_error = e.what();
    }
    if (mesh_error.empty()) continue;
    ++compared;
    std::string cloud_error;
    try {
      read_points(entry.path());
    } catch (const IoError& e) {
      cloud_error = e.what();
    }
    EXPECT_EQ(cloud_error, mesh_error) << entry.path().filename();
  }
  EXPECT_GE(compared, 15u);
  // An OFF whose face count promises more faces than it has.
  spit(dir_ / "bogus_faces.off", "OFF\n3 5 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  const std::string what = io_error_of([&] { read_points(dir_ / "bogus_faces.off"); });
  EXPECT_NE(what.find("declares 5 faces but the file ends after 1"), std::string::npos) << what;
}
