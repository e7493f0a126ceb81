#include <gtest/gtest.h>

#include <sstream>

#include "is_graphs/geometry/surface_sampling.h"

namespace is_graphs {
namespace geometry {
namespace {

// A 4 m × 3 m wall (x–z, y = 0) as two triangles, and a 1 m × 2 m door panel at y = 1.
TriangleMesh WallAndDoor() {
  std::istringstream obj(
      "o IfcWall#1\nv 0 0 0\nv 4 0 0\nv 4 0 3\nv 0 0 3\nf 1 2 3 4\n"
      "o IfcDoor#2\nv 0 1 0\nv 1 1 0\nv 1 1 2\nv 0 1 2\nf 5 6 7 8\n");
  return ParseObj(obj, "wall_and_door.obj").value();
}

TEST(SurfaceSampling, ConfigValidate) {
  EXPECT_EQ(SurfaceSamplingConfig().Validate(), "");
  SurfaceSamplingConfig config;
  config.points_per_square_metre = 0.0;
  EXPECT_NE(config.Validate().find("points_per_square_metre"), std::string::npos);
}

TEST(SurfaceSampling, DensityAndSurface) {
  const TriangleMesh mesh = WallAndDoor();
  SurfaceSamplingConfig config;
  config.points_per_square_metre = 50.0;  // 14 m² -> 700 expected (each triangle: 150 or 50)
  const SurfaceSamples samples = SampleSurface(mesh, config);
  // Every triangle's expected count is an integer here: exactly 12·50 + 2·50.
  EXPECT_EQ(samples.points.size(), 700u);
  ASSERT_EQ(samples.object.size(), samples.points.size());
  int on_wall = 0;
  for (size_t i = 0; i < samples.points.size(); ++i) {
    const Eigen::Vector3d& p = samples.points[i];
    if (samples.object[i] == 0) {
      ++on_wall;
      EXPECT_NEAR(p.y(), 0.0, 1e-12);
      EXPECT_GE(p.x(), -1e-12);
      EXPECT_LE(p.x(), 4.0 + 1e-12);
      EXPECT_GE(p.z(), -1e-12);
      EXPECT_LE(p.z(), 3.0 + 1e-12);
    } else {
      EXPECT_NEAR(p.y(), 1.0, 1e-12);
    }
  }
  EXPECT_EQ(on_wall, 600);
}

TEST(SurfaceSampling, FractionalCountsAverageOut) {
  const TriangleMesh mesh = WallAndDoor();
  SurfaceSamplingConfig config;
  config.points_per_square_metre = 10.3;  // 144.2 expected
  const size_t n = SampleSurface(mesh, config).points.size();
  EXPECT_GE(n, 144u);  // floor of every triangle's count, plus at most one each
  EXPECT_LE(n, 148u);
}

TEST(SurfaceSampling, DeterministicForASeed) {
  const TriangleMesh mesh = WallAndDoor();
  SurfaceSamplingConfig config;
  config.points_per_square_metre = 7.7;
  const SurfaceSamples a = SampleSurface(mesh, config);
  const SurfaceSamples b = SampleSurface(mesh, config);
  ASSERT_EQ(a.points.size(), b.points.size());
  for (size_t i = 0; i < a.points.size(); ++i) EXPECT_EQ(a.points[i], b.points[i]);
  config.seed += 1;
  const SurfaceSamples c = SampleSurface(mesh, config);
  EXPECT_FALSE(c.points.size() == a.points.size() && c.points[0] == a.points[0]);
}

TEST(SurfaceSampling, ExcludedClasses) {
  const TriangleMesh mesh = WallAndDoor();
  SurfaceSamplingConfig config;
  config.points_per_square_metre = 20.0;
  config.excluded_classes = {"IfcDoor"};
  const SurfaceSamples samples = SampleSurface(mesh, config);
  EXPECT_EQ(samples.points.size(), 240u);  // 12 m² of wall only
  for (int object : samples.object) EXPECT_EQ(object, 0);
}

}  // namespace
}  // namespace geometry
}  // namespace is_graphs
