// coordinate_range.h: the range of coordinates the library computes with, and the entry points
// that refuse input outside it (reconstructor, evaluation, distance fronts; the readers are
// tested in mesh_io_test.cpp).

#include <gtest/gtest.h>

#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "edgefront/coordinate_range.h"
#include "edgefront/error.h"
#include "edgefront/front_source.h"
#include "edgefront/minimal_distance_front.h"
#include "shapes/shapes.h"
#include "gcs/evaluation.h"
#include "gcs/reconstructor.h"

namespace {

using namespace edgefront;

std::string invalid_input_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InvalidInput& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not InvalidInput: " << e.what();
    return "";
  }
  ADD_FAILURE() << "accepted";
  return "";
}

shapes::SampleOptions points(size_t n) {
  shapes::SampleOptions o;
  o.points = n;
  return o;
}

/// `mesh` scaled by `s` about the origin.
Mesh scaled(Mesh mesh, double s) {
  for (const auto v : mesh.vertices()) mesh.set_point(v, mesh.point(v) * s);
  return mesh;
}

TEST(CoordinateRange, ProblemNamesThePointAndTheReason) {
  EXPECT_EQ(coordinate_range_problem(std::vector<Vec3>{}), "");
  EXPECT_EQ(coordinate_range_problem({Vec3(0, 0, 0), Vec3(1, 2, 3)}), "");
  EXPECT_EQ(coordinate_range_problem({Vec3(1e75, -1e75, 0), Vec3(0, 0, 0)}), "");  // the bounds themselves
  EXPECT_EQ(coordinate_range_problem({Vec3(1e-75, 0, 0), Vec3(0, 0, 0)}), "");
  EXPECT_EQ(coordinate_range_problem({Vec3(5, 5, 5), Vec3(5, 5, 5)}), "");  // all coincide: not this check's
  EXPECT_EQ(coordinate_range_problem({Vec3(0, 0, 0), Vec3(0, -1e308, 0)}),
            "point 1 has the coordinate -1e308, beyond +-1e75: squared lengths and areas would overflow "
            "(scale the data down)");
  EXPECT_EQ(coordinate_range_problem({Vec3(1e-310, 0, 0), Vec3(0, 0, 0)}),
            "the points span only 1e-310, less than 1e-75: squared lengths and areas would underflow to zero "
            "(scale the data up)");
  EXPECT_NE(coordinate_range_problem({Vec3(0, std::numeric_limits<double>::quiet_NaN(), 0)}).find("non-finite"),
            std::string::npos);
  // Far from the origin: the coordinate decides, not the extent.
  EXPECT_NE(coordinate_range_problem({Vec3(1e100, 0, 0), Vec3(1e100 + 1e85, 0, 0)}).find("point 0"),
            std::string::npos);
}

TEST(CoordinateRange, MeshVariantSkipsDeletedVerticesAndThrowsInvalidInput) {
  Mesh m = shapes::make("icosphere");
  EXPECT_EQ(coordinate_range_problem(m), "");
  const VertexHandle far = m.add_vertex(Vec3(1e80, 0, 0));
  EXPECT_NE(coordinate_range_problem(m).find("vertex " + std::to_string(far.idx())), std::string::npos);
  EXPECT_NE(invalid_input_of([&] { check_coordinate_range(m, "test"); }).rfind("test: vertex", 0), std::string::npos);
  m.delete_vertex(far);
  EXPECT_EQ(coordinate_range_problem(m), "");
  EXPECT_NO_THROW(check_coordinate_range(m, "test"));
}

TEST(CoordinateRange, TheReconstructorAndTheEvaluationRefuseOutOfRangeInput) {
  PointCloud cloud = shapes::sample("icosphere", points(200));
  for (Vec3& p : cloud.points) p *= 1e100;
  EXPECT_NE(invalid_input_of([&] { gcs::Reconstructor r(cloud); }).find("beyond +-1e75"), std::string::npos);
  cloud = shapes::sample("icosphere", points(200));
  for (Vec3& p : cloud.points) p *= 1e-310;
  EXPECT_NE(invalid_input_of([&] { gcs::Reconstructor r(cloud); }).find("underflow"), std::string::npos);

  const Mesh sphere = shapes::make("icosphere");
  const Mesh huge = scaled(sphere, 1e300);
  EXPECT_NE(invalid_input_of([&] { gcs::evaluate(huge, gcs::GroundTruth::from_mesh(sphere)); })
                .find("evaluation: the result mesh: vertex"),
            std::string::npos);
  EXPECT_NE(invalid_input_of([&] { gcs::evaluate(sphere, gcs::GroundTruth::from_mesh(huge)); }).find("overflow"),
            std::string::npos);
  PointCloud tiny = shapes::sample("icosphere", points(50));
  for (Vec3& p : tiny.points) p *= 1e-200;
  EXPECT_NE(invalid_input_of([&] { gcs::evaluate(sphere, gcs::GroundTruth::from_points(tiny)); }).find("underflow"),
            std::string::npos);
}

TEST(CoordinateRange, DistanceFrontsRefuseVerticesBeyondTheRangeTheyReach) {
  const Mesh sphere = shapes::make("icosphere");
  const Mesh huge = scaled(sphere, 1e200);
  for (const bool fast : {false, true}) {
    DistanceOptions o;
    o.method = fast ? edgefront::DistanceMethod::Fast : edgefront::DistanceMethod::Mdf;
    const std::string what = invalid_input_of(
        [&] { geodesic_distance(huge, FrontSource::from_vertices({VertexHandle(0)}), o); });
    EXPECT_NE(what.find("beyond +-1e75"), std::string::npos) << what;
  }
  // The same mesh at an ordinary scale is fine: the check is not a false alarm.
  EXPECT_NO_THROW(geodesic_distance(scaled(sphere, 1e70), FrontSource::from_vertices({VertexHandle(0)})));
}

}  // namespace
