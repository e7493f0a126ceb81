// ScanSlice: a keyframe's points in a horizontal band, thinned to one per cell, capped.
#include <gtest/gtest.h>

#include <cmath>

#include "is_graphs/sgraph/frontend_config.h"
#include "is_graphs/sgraph/scan_slice.h"

namespace is_graphs {
namespace sgraph {
namespace {

TEST(ScanSlice, KeepsTheBandOnlyOnePointPerCell) {
  FrontendConfig c;  // band 0.4..1.6 m above base_link, 0.05 m cells
  PointList cloud;
  for (int i = 0; i < 100; ++i) {
    const float x = 3.0f, y = -1.0f + 0.02f * i;  // 2 m of wall, a point every 2 cm
    cloud.emplace_back(x, y, 1.0f);               // in the band
    cloud.emplace_back(x, y, 0.2f);               // below it (furniture height)
    cloud.emplace_back(x, y, 1.9f);               // above it
  }
  const auto slice = ScanSlice(cloud, Eigen::Vector3d::UnitZ(), c);
  // 2 m at one point per 5 cm: 40 (41 with a cell boundary at each end).
  EXPECT_GE(slice.size(), 39u);
  EXPECT_LE(slice.size(), 41u);
  for (const auto& p : slice) EXPECT_FLOAT_EQ(p.z(), 1.0f);
}

TEST(ScanSlice, FollowsGravityNotTheBaseFrame) {
  FrontendConfig c;
  // The robot pitched by 20 deg: a point 1 m up along gravity sits at z' < 1 in base_link.
  const double pitch = 20.0 * M_PI / 180.0;
  const Eigen::Vector3d up(-std::sin(pitch), 0.0, std::cos(pitch));  // gravity's up in base_link
  PointList cloud;
  cloud.push_back((1.0 * up + Eigen::Vector3d(0.0, 2.0, 0.0)).cast<float>());   // 1 m up: in
  cloud.push_back((0.2 * up + Eigen::Vector3d(0.0, -2.0, 0.0)).cast<float>());  // 0.2 m: out
  const auto slice = ScanSlice(cloud, up, c);
  ASSERT_EQ(slice.size(), 1u);
  EXPECT_NEAR(slice[0].y(), 2.0f, 1e-5);
}

TEST(ScanSlice, CapsThePointsEvenlyAndIsDeterministic) {
  FrontendConfig c;
  c.slice_max_points = 100;
  PointList cloud;
  for (int i = 0; i < 1000; ++i) {
    const double a = 2.0 * M_PI * i / 1000.0;
    cloud.emplace_back(static_cast<float>(5.0 * std::cos(a)), static_cast<float>(5.0 * std::sin(a)),
                       1.0f);
  }
  const auto slice = ScanSlice(cloud, Eigen::Vector3d::UnitZ(), c);
  ASSERT_EQ(slice.size(), 100u);
  // Spread around the circle, not the first 100.
  int left = 0;
  for (const auto& p : slice) left += p.x() < 0.0f;
  EXPECT_GT(left, 40);
  EXPECT_LT(left, 60);
  EXPECT_EQ(slice, ScanSlice(cloud, Eigen::Vector3d::UnitZ(), c));
}

TEST(ScanSlice, NoneWhenNoKeyframeKeepsOne) {
  FrontendConfig c;
  c.slice_keyframes = 0;
  PointList cloud{{1.0f, 0.0f, 1.0f}};
  EXPECT_TRUE(ScanSlice(cloud, Eigen::Vector3d::UnitZ(), c).empty());
  EXPECT_TRUE(FrontendConfig{}.Validate().empty());
  c = FrontendConfig{};
  c.slice_low = 2.0;
  EXPECT_NE(c.Validate().find("slice_low"), std::string::npos) << c.Validate();
  c = FrontendConfig{};
  c.slice_cell = 0.0;
  EXPECT_NE(c.Validate().find("slice_cell"), std::string::npos) << c.Validate();
}

}  // namespace
}  // namespace sgraph
}  // namespace is_graphs
