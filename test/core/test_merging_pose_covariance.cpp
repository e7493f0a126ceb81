// merging::RobotPoseCovariance: B_x_M's covariance moved to the robot, plus the floors.
#include <gtest/gtest.h>

#include <cmath>

#include "is_graphs/geometry/se3.h"
#include "is_graphs/merging/pose_covariance.h"

namespace is_graphs {
namespace merging {
namespace {

constexpr double kDeg = M_PI / 180.0;

MergerConfig Floors() {
  MergerConfig c;
  c.pose_sigma_xy = 0.02;
  c.pose_sigma_z = 0.05;
  c.pose_sigma_roll_pitch_deg = 1.0;
  c.pose_sigma_yaw_deg = 0.5;
  return c;
}

TEST(RobotPoseCovariance, NoMergeUncertaintyLeavesTheFloors) {
  const MergerConfig c = Floors();
  const auto cov =
      RobotPoseCovariance(Eigen::Matrix3d::Zero(), geometry::IsometryFromXYYaw(3.0, -2.0, 0.7),
                          Eigen::Vector3d(5.0, 1.0, 0.3), c);
  Eigen::Matrix<double, 6, 1> floors;
  floors << 0.0004, 0.0004, 0.0025, std::pow(1.0 * kDeg, 2), std::pow(1.0 * kDeg, 2),
      std::pow(0.5 * kDeg, 2);
  EXPECT_TRUE(cov.diagonal().isApprox(floors, 1e-12)) << cov.diagonal().transpose();
  EXPECT_NEAR((cov - Eigen::Matrix<double, 6, 6>(cov.diagonal().asDiagonal())).norm(), 0.0, 1e-15);
}

TEST(RobotPoseCovariance, AYawErrorMovesTheRobotByItsLeverArm) {
  MergerConfig c;
  c.pose_sigma_xy = c.pose_sigma_z = c.pose_sigma_roll_pitch_deg = c.pose_sigma_yaw_deg = 0.0;
  Eigen::Matrix3d xi = Eigen::Matrix3d::Zero();
  xi(2, 2) = 0.01;  // yaw variance only
  // M turned 90 deg in B: the robot 2 m along M's x is 2 m along B's y; a yaw error moves it in -x.
  const auto cov = RobotPoseCovariance(xi, geometry::IsometryFromXYYaw(1.0, 1.0, M_PI / 2),
                                       Eigen::Vector3d(2.0, 0.0, 0.0), c);
  EXPECT_NEAR(cov(0, 0), 4.0 * 0.01, 1e-12);
  EXPECT_NEAR(cov(1, 1), 0.0, 1e-12);
  EXPECT_NEAR(cov(0, 5), -2.0 * 0.01, 1e-12);
  EXPECT_NEAR(cov(5, 0), -2.0 * 0.01, 1e-12);
  EXPECT_NEAR(cov(5, 5), 0.01, 1e-12);
  // Translation variance passes through unchanged; z, roll, pitch get nothing from B_x_M.
  xi = Eigen::Matrix3d::Zero();
  xi(0, 0) = 0.04;
  xi(1, 1) = 0.09;
  const auto t = RobotPoseCovariance(xi, geometry::IsometryFromXYYaw(1.0, 1.0, M_PI / 2),
                                     Eigen::Vector3d(2.0, 0.0, 0.0), c);
  EXPECT_NEAR(t(0, 0), 0.04, 1e-12);
  EXPECT_NEAR(t(1, 1), 0.09, 1e-12);
  EXPECT_NEAR((t.block<3, 3>(2, 2).norm()), 0.0, 1e-15);
}

TEST(GrowWithOdometry, AddsTheOdometrysErrorOverTheDistanceWalked) {
  WatchdogConfig w;
  w.degraded_sigma_per_m = 0.05;
  w.degraded_yaw_sigma_deg_per_m = 1.0;
  Eigen::Matrix<double, 6, 6> cov = Eigen::Matrix<double, 6, 6>::Identity() * 1e-4;
  const auto grown = GrowWithOdometry(cov, 4.0, w);
  EXPECT_NEAR(grown(0, 0), 1e-4 + 0.2 * 0.2, 1e-12);
  EXPECT_NEAR(grown(1, 1), 1e-4 + 0.2 * 0.2, 1e-12);
  EXPECT_NEAR(grown(2, 2), 1e-4, 1e-15);
  const double yaw = 4.0 * M_PI / 180.0;
  EXPECT_NEAR(grown(5, 5), 1e-4 + yaw * yaw, 1e-12);
  EXPECT_EQ(GrowWithOdometry(cov, 0.0, w), cov);
  EXPECT_EQ(GrowWithOdometry(cov, -1.0, w), cov);
}

}  // namespace
}  // namespace merging
}  // namespace is_graphs
