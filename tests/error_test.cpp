#include <gtest/gtest.h>

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
