#include <gtest/gtest.h>

#include <sstream>

#include "fixtures.h"
#include "is_graphs/geometry/triangle_mesh.h"

namespace is_graphs {
namespace geometry {
namespace {

Result<TriangleMesh> Parse(const std::string& text) {
  std::istringstream input(text);
  return ParseObj(input, "test.obj");
}

TEST(TriangleMesh, ObjectsVerticesTriangles) {
  const Result<TriangleMesh> mesh = Parse(
      "# comment\n"
      "mtllib x.mtl\n"
      "o IfcWall#12\n"
      "v 0 0 0\nv 2 0 0\nv 2 0 3\nv 0 0 3\n"
      "vn 0 1 0\n"
      "f 1 2 3\nf 1 3 4\n"
      "o IfcDoor#7\r\n"
      "v 0 1 0\nv 1 1 0\nv 1 1 2\n"
      "s off\n"
      "f -3 -2 -1\n");
  ASSERT_TRUE(mesh.ok()) << mesh.error();
  const TriangleMesh& m = mesh.value();
  EXPECT_EQ(m.vertices.size(), 7u);
  ASSERT_EQ(m.triangles.size(), 3u);
  EXPECT_EQ(m.triangles[2], Eigen::Vector3i(4, 5, 6));  // negative: relative to the end
  EXPECT_EQ(m.triangle_object, (std::vector<int>{0, 0, 1}));
  EXPECT_EQ(m.object_names, (std::vector<std::string>{"IfcWall#12", "IfcDoor#7"}));
  EXPECT_EQ(m.ObjectClass(0), "IfcWall");
  EXPECT_EQ(m.ObjectClass(1), "IfcDoor");
  EXPECT_DOUBLE_EQ(m.TriangleArea(0), 3.0);
  EXPECT_DOUBLE_EQ(m.TotalArea(), 6.0 + 1.0);
}

TEST(TriangleMesh, SlashesAndPolygons) {
  const Result<TriangleMesh> mesh = Parse(
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 1.5 0\n"
      "vt 0 0\n"
      "f 1/1/1 2/1/1 3/1/1 4/1/1 5/1/1\n"  // a pentagon: three triangles
      "f 1//1 2//1 3//1\n");
  ASSERT_TRUE(mesh.ok()) << mesh.error();
  const TriangleMesh& m = mesh.value();
  ASSERT_EQ(m.triangles.size(), 4u);
  EXPECT_EQ(m.triangles[0], Eigen::Vector3i(0, 1, 2));
  EXPECT_EQ(m.triangles[1], Eigen::Vector3i(0, 2, 3));
  EXPECT_EQ(m.triangles[2], Eigen::Vector3i(0, 3, 4));
  EXPECT_EQ(m.object_names, (std::vector<std::string>{""}));  // faces before any `o`
  EXPECT_DOUBLE_EQ(m.TotalArea(), 1.0 + 0.25 + 0.5);
}

TEST(TriangleMesh, ErrorsNameFileAndLine) {
  struct Case {
    std::string text;
    std::string expected;
  };
  const std::vector<Case> cases = {
      {"v 0 0 0\nv 1 0\n", "test.obj:2: vertex needs three finite numbers"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", "test.obj:4: face vertex 4 out of range"},
      {"v 0 0 0\nf 0 1 1\n", "test.obj:2: face vertex 0 out of range"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf -4 1 2\n", "test.obj:4: face vertex -4 out of range"},
      {"v 0 0 0\nv 1 0 0\nf 1 2\n", "test.obj:3: face needs at least 3 vertices"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 x 3\n", "test.obj:5: bad face vertex \"x\""},
      {"v 0 0 nan\n", "test.obj:1: vertex needs three finite numbers"},
  };
  for (const Case& c : cases) {
    const Result<TriangleMesh> mesh = Parse(c.text);
    ASSERT_FALSE(mesh.ok()) << c.text;
    EXPECT_NE(mesh.error().find(c.expected), std::string::npos) << mesh.error();
  }
  const Result<TriangleMesh> missing = LoadObj("/nonexistent/b.obj");
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.error().find("/nonexistent/b.obj: cannot open"), std::string::npos);
}

TEST(TriangleMesh, LoadsTheFixtureMesh) {
  const Result<TriangleMesh> mesh = LoadObj(testing::DataPath("two_rooms.obj"));
  ASSERT_TRUE(mesh.ok()) << mesh.error();
  EXPECT_EQ(mesh.value().object_names.size(), 6u);  // 5 walls + 1 door
  EXPECT_EQ(mesh.value().triangles.size(), 6u * 12u);
  EXPECT_EQ(mesh.value().ObjectClass(5), "IfcDoor");
}

}  // namespace
}  // namespace geometry
}  // namespace is_graphs
