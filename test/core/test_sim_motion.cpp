// Trajectory (trapezoidal walk + turn in place), gait sway and odometry drift statistics.
#include <gtest/gtest.h>

#include <cmath>

#include "is_graphs/geometry/se3.h"
#include "is_graphs/sim/gait.h"
#include "is_graphs/sim/odometry_drift.h"
#include "is_graphs/sim/trajectory.h"

namespace is_graphs {
namespace sim {
namespace {

TrajectoryConfig Config(double speed = 1.0) {
  TrajectoryConfig c;
  c.waypoints = {{}};  // (Build validates the config; the waypoints are passed separately)
  c.speed = speed;
  c.pause = 0.5;
  return c;
}

TEST(SimTrajectory, TrapezoidIsContinuousAndReachesTheEnd) {
  for (double amount : {0.1, 1.0, 10.0}) {
    const double total = TrapezoidDuration(amount, 1.0, 0.5);
    double prev_pos = 0.0, prev_speed = 0.0;
    for (int i = 1; i <= 1000; ++i) {
      double pos, speed;
      TrapezoidAt(amount, 1.0, 0.5, total * i / 1000.0, &pos, &speed);
      EXPECT_LE(speed, 1.0 + 1e-12);
      EXPECT_NEAR(speed, prev_speed, 0.5 * total / 1000.0 + 1e-9);  // |accel| <= 0.5
      EXPECT_GE(pos, prev_pos - 1e-12);
      prev_pos = pos;
      prev_speed = speed;
    }
    EXPECT_NEAR(prev_pos, amount, 1e-9);
    EXPECT_NEAR(prev_speed, 0.0, 1e-9);
  }
}

TEST(SimTrajectory, TurnsInPlaceThenWalksStraight) {
  const Result<Trajectory> r = Trajectory::Build(
      {0, 0, 0}, {{{0.0, 3.0}, std::nullopt, true}, {{4.0, 3.0}, M_PI, true}}, Config(), 0.0);
  ASSERT_TRUE(r.ok()) << r.error();
  const Trajectory& t = r.value();
  EXPECT_NEAR(t.PathLength(), 7.0, 1e-9);
  bool turned_in_place = false;
  for (double time = 0.0; time <= t.Duration(); time += 0.01) {
    const PlanarState s = t.StateAt(time);
    EXPECT_LE(s.speed, 1.0 + 1e-9);
    if (std::abs(s.yaw_rate) > 1e-6) {
      EXPECT_EQ(s.speed, 0.0);  // no walking while turning
      turned_in_place = true;
    }
    if (s.speed > 0.0) {  // walking: along the heading, towards the next waypoint
      const bool first_leg = s.pose.x() < 1e-6;  // the first leg runs along x = 0
      EXPECT_NEAR(s.pose.z(), first_leg ? M_PI / 2 : 0.0, 1e-9);
    }
  }
  EXPECT_TRUE(turned_in_place);
  const PlanarState end = t.StateAt(t.Duration());
  EXPECT_NEAR(end.pose.x(), 4.0, 1e-9);
  EXPECT_NEAR(end.pose.y(), 3.0, 1e-9);
  EXPECT_NEAR(std::abs(end.pose.z()), M_PI, 1e-9);
}

TEST(SimTrajectory, LoopsUntilTheDuration) {
  TrajectoryConfig c = Config();
  c.loop = true;
  const Result<Trajectory> r =
      Trajectory::Build({0, 0, 0}, {{{3.0, 0.0}, std::nullopt, true}}, c, 60.0);
  ASSERT_TRUE(r.ok());
  EXPECT_GE(r.value().Duration(), 60.0);
  EXPECT_GT(r.value().PathLength(), 20.0);
}

TEST(SimGait, SwayHasTheConfiguredAmplitudesOnlyWhenMoving) {
  GaitConfig g;
  const GaitModel gait(g);
  PlanarState walking;
  walking.speed = 0.8;
  PlanarState standing;
  EXPECT_DOUBLE_EQ(gait.Activity(walking), 1.0);
  EXPECT_DOUBLE_EQ(gait.Activity(standing), 0.0);
  Eigen::Vector3d peak = Eigen::Vector3d::Zero();
  for (double t = 0.0; t < 2.0; t += 0.001) {
    peak = peak.cwiseMax(gait.Sway(t, 1.0).cwiseAbs());
    EXPECT_EQ(gait.Sway(t, 0.0).norm(), 0.0);
  }
  EXPECT_NEAR(peak.x(), g.roll_amplitude_deg * M_PI / 180.0, 1e-4);
  EXPECT_NEAR(peak.y(), g.pitch_amplitude_deg * M_PI / 180.0, 1e-4);
  EXPECT_NEAR(peak.z(), g.bob_amplitude, 1e-5);
}

// Odometry of a straight walk of `length` m at 1 m/s along x, sampled at 50 Hz.
OdometrySample WalkStraight(const OdometryConfig& config, std::uint64_t seed, double length) {
  OdometryDrift odom(config, seed, 0.0);
  OdometrySample last;
  const int steps = static_cast<int>(length * 50.0);
  for (int i = 0; i <= steps; ++i) {
    const double t = i / 50.0;
    Eigen::Isometry3d pose = geometry::IsometryFromXYYaw(t * 1.0 + 1.0, 2.0, 0.0, 0.525);
    last = odom.Step(t, pose);
  }
  return last;
}

TEST(SimOdometry, ScaleErrorAndYawBiasAreDeterministic) {
  OdometryConfig c;
  c.scale_error = 0.02;
  OdometrySample s = WalkStraight(c, 1, 50.0);
  EXPECT_NEAR(s.odom_T_base.translation().x(), 51.0, 1e-6);
  EXPECT_NEAR(s.odom_T_base.translation().z(), 0.525, 1e-9);
  EXPECT_NEAR(s.linear_velocity.x(), 1.02, 1e-6);

  OdometryConfig y;
  y.yaw_bias_per_m = 0.002;
  y.yaw_bias_per_s = 0.001;
  s = WalkStraight(y, 1, 50.0);
  EXPECT_NEAR(geometry::Yaw(s.odom_T_base), 0.002 * 50.0 + 0.001 * 50.0, 1e-6);
}

TEST(SimOdometry, RandomWalkHasTheConfiguredVariance) {
  OdometryConfig c;
  c.translation_random_walk = 0.02;  // m / sqrt(m)
  c.yaw_random_walk = 0.0;
  const double length = 25.0;
  const int runs = 400;
  double sum_x = 0.0, sum2_x = 0.0, sum2_y = 0.0;
  for (int seed = 0; seed < runs; ++seed) {
    const OdometrySample s = WalkStraight(c, seed, length);
    const double ex = s.odom_T_base.translation().x() - length;
    const double ey = s.odom_T_base.translation().y();
    sum_x += ex;
    sum2_x += ex * ex;
    sum2_y += ey * ey;
    if (seed == 0) {
      EXPECT_NEAR(s.variance_xy, 0.02 * 0.02 * length, 1e-9);
    }
  }
  const double expected = 0.02 * 0.02 * length;  // variance per axis
  EXPECT_NEAR(sum_x / runs, 0.0, 4.0 * std::sqrt(expected / runs));
  // Sample variance of 400 draws: relative standard error sqrt(2/400) = 7 %.
  EXPECT_NEAR(sum2_x / runs / expected, 1.0, 0.25);
  EXPECT_NEAR(sum2_y / runs / expected, 1.0, 0.25);
  // Same seed, same odometry.
  const OdometrySample a = WalkStraight(c, 9, length), b = WalkStraight(c, 9, length);
  EXPECT_TRUE(a.odom_T_base.isApprox(b.odom_T_base, 0.0));
}

TEST(SimOdometry, YawRandomWalkVariance) {
  OdometryConfig c;
  c.yaw_random_walk = 0.01;  // rad / sqrt(m)
  const double length = 16.0;
  const int runs = 400;
  double sum2 = 0.0;
  for (int seed = 0; seed < runs; ++seed) {
    const double yaw = geometry::Yaw(WalkStraight(c, 1000 + seed, length).odom_T_base);
    sum2 += yaw * yaw;
  }
  EXPECT_NEAR(sum2 / runs / (0.01 * 0.01 * length), 1.0, 0.25);
}

}  // namespace
}  // namespace sim
}  // namespace is_graphs
