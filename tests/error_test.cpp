#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "edgefront/error.h"
#include "edgefront/mesh.h"

TEST(Error, CheckThrowsWithFileAndLine) {
  try {
    EF_CHECK(1 + 1 == 3, "arithmetic");
    FAIL() << "EF_CHECK did not throw";
  } catch (const edgefront::InternalError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("error_test.cpp"), std::string::npos) << what;
    EXPECT_NE(what.find("arithmetic"), std::string::npos) << what;
  }
  EXPECT_NO_THROW(EF_CHECK(true, "never"));
}

TEST(Mesh, LiveHandles) {
  edgefront::Mesh m;
  auto a = m.add_vertex({0, 0, 0});
  auto b = m.add_vertex({1, 0, 0});
  auto c = m.add_vertex({0, 1, 0});
  auto f = m.add_face(a, b, c);
  EXPECT_TRUE(edgefront::is_live(m, a));
  EXPECT_TRUE(edgefront::is_live(m, f));
  EXPECT_FALSE(edgefront::is_live(m, edgefront::VertexHandle(7)));
  EXPECT_FALSE(edgefront::is_live(m, edgefront::VertexHandle()));
  m.delete_face(f, true);
  EXPECT_FALSE(edgefront::is_live(m, a));
}

TEST(Error, NumbersForMessagesAreShortAndReadable) {
  using edgefront::number_for_message;
  EXPECT_EQ(number_for_message(std::numeric_limits<double>::max()), "1.8e308");
  EXPECT_EQ(number_for_message(-std::numeric_limits<double>::max()), "-1.8e308");
  EXPECT_EQ(number_for_message(std::numeric_limits<double>::min()), "2.2e-308");
  EXPECT_EQ(number_for_message(1e75), "1e75");
  EXPECT_EQ(number_for_message(1e-75), "1e-75");
  EXPECT_EQ(number_for_message(0.0), "0");
  EXPECT_EQ(number_for_message(0.5), "0.5");
  EXPECT_EQ(number_for_message(-3), "-3");
  EXPECT_EQ(number_for_message(100000000), "1e8");
  EXPECT_EQ(number_for_message(123456), "123456");
  EXPECT_EQ(number_for_message(1.5e-5), "1.5e-5");
  EXPECT_EQ(number_for_message(0.1 + 0.2), "0.3");  // not 0.30000000000000004
  EXPECT_EQ(number_for_message(std::numeric_limits<double>::infinity()), "inf");
  EXPECT_EQ(number_for_message(std::nan("")), "nan");
}
