// The S-Graph back end estimates the odometry's distance scale from the planes it observes.
#include <gtest/gtest.h>

#include <cmath>

#include "is_graphs/sgraph/sgraph_backend.h"

namespace is_graphs {
namespace sgraph {
namespace {

// A 9 m × 3 m room (walls x = −1, x = 8, y = ±1.5, normals inwards). The robot walks along x
// from 0 to 6 m in 0.5 m steps; its odometry reads every step `1 / true_scale` as long, and
// each keyframe observes every wall exactly. Initial poses: dead reckoning on the odometry.
BackendProblem WalkOfReadScale(double true_scale) {
  BackendProblem problem;
  const geometry::Plane walls[] = {geometry::Plane(Eigen::Vector3d::UnitX(), -1.0),
                                   geometry::Plane(-Eigen::Vector3d::UnitX(), -8.0),
                                   geometry::Plane(Eigen::Vector3d::UnitY(), -1.5),
                                   geometry::Plane(-Eigen::Vector3d::UnitY(), -1.5)};
  for (int i = 0; i < 4; ++i) {
    Plane p;
    p.id = i;
    p.plane = walls[i];
    problem.planes.push_back(p);
  }
  const double step = 0.5;
  for (int k = 0; k <= 12; ++k) {
    Keyframe kf;
    kf.id = k;
    kf.stamp = k;
    Eigen::Isometry3d truth = Eigen::Isometry3d::Identity();
    truth.translation() = Eigen::Vector3d(k * step, 0.1 * std::sin(k), 0.5);
    kf.odom_pose = Eigen::Isometry3d::Identity();
    kf.odom_pose.translation() = truth.translation() / true_scale;
    kf.odom_pose.translation().z() = 0.5;
    if (k > 0) {
      const Keyframe& prev = problem.keyframes.back();
      kf.previous = prev.id;
      kf.relative_odom = prev.odom_pose.inverse() * kf.odom_pose;
      Eigen::Matrix<double, 6, 1> sigma;
      sigma << 0.01, 0.01, 0.005, 0.002, 0.002, 0.005;  // m, rad per step
      kf.odom_information = sigma.cwiseInverse().cwiseAbs2().asDiagonal();
    }
    kf.pose = kf.odom_pose;  // dead reckoning from the first keyframe (the gauge, at the truth)
    problem.keyframes.push_back(kf);
    for (int i = 0; i < 4; ++i) {
      PlaneObservation o;
      o.keyframe = k;
      o.plane = i;
      o.local = walls[i].Transformed(truth.inverse());
      o.information = Eigen::Vector3d(1e4, 1e4, 1e4).asDiagonal();  // 1 cm, 0.01 rad
      problem.observations.push_back(o);
    }
  }
  return problem;
}

BackendConfig Generous() {
  BackendConfig config;
  config.max_iterations = 100;
  config.max_solver_time = 10.0;
  return config;
}

TEST(OdometryScale, RecoveredFromWallsWhenOdometryUnderReadsBySixPerCent) {
  BackendProblem problem = WalkOfReadScale(1.06);
  const BackendSummary summary = OptimizeSGraph(problem, Generous());
  ASSERT_TRUE(summary.usable) << summary.message;
  // The prior (σ 0.05) pulls a little towards 1; the 13 keyframes' walls outweigh it.
  EXPECT_NEAR(problem.odometry_scale, 1.06, 0.005);
  EXPECT_NEAR(problem.keyframes.back().pose.translation().x(), 6.0, 0.01);
}

TEST(OdometryScale, StaysAtOneWhenOdometryReadsRight) {
  BackendProblem problem = WalkOfReadScale(1.0);
  ASSERT_TRUE(OptimizeSGraph(problem, Generous()).usable);
  EXPECT_NEAR(problem.odometry_scale, 1.0, 1e-3);
}

TEST(OdometryScale, HeldAtOneWhenSigmaIsZero) {
  BackendProblem problem = WalkOfReadScale(1.06);
  BackendConfig config = Generous();
  config.odometry_scale_sigma = 0.0;
  ASSERT_TRUE(OptimizeSGraph(problem, config).usable);
  EXPECT_EQ(problem.odometry_scale, 1.0);
}

TEST(OdometryScale, KeptWithinTheConfiguredBound) {
  BackendProblem problem = WalkOfReadScale(1.5);  // beyond 1 ± 0.2
  ASSERT_TRUE(OptimizeSGraph(problem, Generous()).usable);
  EXPECT_LE(problem.odometry_scale, 1.2 + 1e-9);
  EXPECT_GE(problem.odometry_scale, 1.0);
}

TEST(OdometryScale, ConfigRejectsANegativeSigma) {
  BackendConfig config;
  config.odometry_scale_sigma = -0.1;
  EXPECT_NE(config.Validate().find("odometry_scale_sigma"), std::string::npos);
}

}  // namespace
}  // namespace sgraph
}  // namespace is_graphs
