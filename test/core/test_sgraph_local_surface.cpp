// The shape check on wall inliers (local_surface.h): points that only pass through a wall's
// distance band (a perpendicular wall at a corner, a door's reveal) are kept off the wall.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "is_graphs/sgraph/cloud_filter.h"
#include "is_graphs/sgraph/frontend_config.h"
#include "is_graphs/sgraph/local_surface.h"
#include "is_graphs/sgraph/plane_fit.h"
#include "sgraph_test_helpers.h"

namespace is_graphs {
namespace sgraph {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

std::vector<int> All(const PointList& points) {
  std::vector<int> all(points.size());
  for (size_t i = 0; i < all.size(); ++i) all[i] = static_cast<int>(i);
  return all;
}

TEST(LocalSurfaces, KeepsAWallAndDropsAPerpendicularOne) {
  std::mt19937 rng(11);
  PointList points;
  testing::AddWall(points, Vector2d(2, -2), Vector2d(2, 2), 0.0, 2.0, 0.05, 0.005, rng);
  const size_t on_wall = points.size();
  testing::AddWall(points, Vector2d(-2, 3), Vector2d(2, 3), 0.0, 2.0, 0.05, 0.005, rng);
  LocalSurfaces surfaces(points, 0.15);
  const auto kept = surfaces.OnPlane(All(points), Vector3d::UnitX(), 30.0 * M_PI / 180.0);
  EXPECT_EQ(kept.size(), on_wall);
  for (int i : kept) EXPECT_NEAR(points[i].x(), 2.0, 0.05);
}

TEST(LocalSurfaces, JudgesAScanRingByItsDirection) {
  // One ring each: along the wall x = 2 (in the plane) and across it (a perpendicular wall).
  PointList points;
  for (double y = -1.0; y <= 1.0; y += 0.04) points.emplace_back(2.0f, static_cast<float>(y), 1.0f);
  const size_t along = points.size();
  for (double x = 0.0; x <= 1.9; x += 0.04) points.emplace_back(static_cast<float>(x), 4.0f, 1.0f);
  LocalSurfaces surfaces(points, 0.15);
  const auto kept = surfaces.OnPlane(All(points), Vector3d::UnitX(), 30.0 * M_PI / 180.0);
  EXPECT_EQ(kept.size(), along);
}

TEST(LocalSurfaces, KeepsIsolatedPoints) {
  const PointList points = {{2.0f, 0.0f, 1.0f}, {2.0f, 1.0f, 1.0f}, {0.0f, 3.0f, 1.0f}};
  LocalSurfaces surfaces(points, 0.15);
  EXPECT_EQ(surfaces.OnPlane(All(points), Vector3d::UnitX(), 0.5).size(), points.size());
}

// A wall piece between a corner and a door's reveal (D2's foyer had one), as RANSAC hands it
// over: every point within 5 cm of the wall. The corner wall's points in that band pull one end
// in, the reveal's the other end out.
TEST(LocalSurfaces, AWallPieceBetweenACornerAndARevealIsNotTilted) {
  std::mt19937 rng(12);
  // Sampled like a scan from near the corner: the piece, seen obliquely, sparser than the walls
  // across it.
  PointList points;
  testing::AddWall(points, Vector2d(1.3, -0.5), Vector2d(1.3, 0.5), -0.5, 1.5, 0.08, 0.015, rng);
  testing::AddWall(points, Vector2d(-1.0, 0.5), Vector2d(1.3, 0.5), -0.5, 1.5, 0.02, 0.015, rng);
  testing::AddWall(points, Vector2d(1.3, -0.5), Vector2d(1.7, -0.5), -0.5, 1.5, 0.02, 0.015, rng);
  FrontendConfig config;
  std::vector<int> band;
  for (size_t i = 0; i < points.size(); ++i)
    if (std::abs(points[i].x() - 1.3) < config.plane_distance_threshold)
      band.push_back(static_cast<int>(i));
  const auto angle_deg = [&](const std::vector<int>& indices) {
    const auto fit = FitPlane(points, indices, config.point_sigma, config.max_effective_points,
                              Vector3d::UnitZ());
    EXPECT_TRUE(fit);
    return fit ? std::acos(std::min(1.0, std::abs(fit->plane.normal.x()))) * 180.0 / M_PI : 90.0;
  };
  LocalSurfaces surfaces(points, config.wall_normal_cell);
  const auto kept =
      surfaces.OnPlane(band, Vector3d::UnitX(), config.wall_normal_max_angle_deg * M_PI / 180.0);
  const double unchecked = angle_deg(band), checked = angle_deg(kept);
  std::printf("band %zu points, kept %zu; angle error %.2f deg unchecked, %.2f deg checked\n",
              band.size(), kept.size(), unchecked, checked);
  EXPECT_GT(unchecked, 1.0);  // the tilt the check is there for
  EXPECT_LT(checked, 0.3);
  for (int i : kept) EXPECT_LT(std::abs(points[i].y()), 0.5);  // none of the corner or reveal
}

TEST(LocalSurfaces, BadConfigValuesAreNamed) {
  FrontendConfig c;
  EXPECT_EQ(c.Validate(), "");
  c.wall_normal_cell = 0.0;
  EXPECT_NE(c.Validate().find("wall_normal_cell"), std::string::npos) << c.Validate();
  c = FrontendConfig();
  c.wall_normal_max_angle_deg = 0.5;
  EXPECT_NE(c.Validate().find("wall_normal_max_angle_deg"), std::string::npos) << c.Validate();
  c.wall_normal_max_angle_deg = 90.0;  // no check
  EXPECT_EQ(c.Validate(), "");
}

}  // namespace
}  // namespace sgraph
}  // namespace is_graphs
