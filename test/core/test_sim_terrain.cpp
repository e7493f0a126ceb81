// Stairs in the simulator (issue 22): the ground under a walked path, the body's height and
// pitch on a flight, the flights walked slower, the walk check on an incline, and the
// odometry's height error per climb.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "is_graphs/sim/embree_scene.h"
#include "is_graphs/sim/gait.h"
#include "is_graphs/sim/odometry_drift.h"
#include "is_graphs/sim/simulation.h"
#include "is_graphs/sim/terrain.h"
#include "is_graphs/sim/trajectory.h"

namespace is_graphs {
namespace sim {
namespace {

constexpr double kRise = 0.15, kRun = 0.3;
constexpr int kSteps = 10;  // 1.5 m up over 3 m, from x = 4 to x = 7

// A floor at z = 0 from x = 0 to 4, a straight flight of 10 steps up +x, and an upper floor at
// z = 1.5 from x = 7 to 11; all 2 m wide (y in [-1, 1]).
SceneMesh Stair() {
  SceneMesh m;
  m.AddBox({2.0, 0.0}, -0.2, {4.0, 2.0, 0.2}, 0.0, 0.3f);
  for (int i = 0; i < kSteps; ++i)
    m.AddBox({4.0 + (i + 0.5) * kRun, 0.0}, 0.0, {kRun, 2.0, (i + 1) * kRise}, 0.0, 0.3f);
  m.AddBox({9.0, 0.0}, 1.5 - 0.2, {4.0, 2.0, 0.2}, 0.0, 0.3f);
  return m;
}

Trajectory Walk(double to_x, const LegSpeed& speed = nullptr) {
  TrajectoryConfig c;
  c.waypoints = {{}};
  c.pause = 0.0;
  c.speed = 0.6;
  return std::move(Trajectory::Build({1.0, 0.0, 0.0}, {{{to_x, 0.0}, std::nullopt, false}}, c, 0.0,
                                     speed))
      .value();
}

TEST(SimTerrain, TheGroundRisesWithTheFlightAndTheBodyPitchesOnIt) {
  const SceneMesh mesh = Stair();
  const auto scene = std::move(EmbreeScene::Create(mesh)).value();
  const Trajectory walk = Walk(10.0);
  const Result<TerrainProfile> t = TerrainProfile::Build(*scene, walk, 0.0, TerrainConfig());
  ASSERT_TRUE(t.ok()) << t.error();
  EXPECT_NEAR(t.value().GroundAt(1.0), 0.0, 1e-4);         // x = 2: the lower floor
  EXPECT_NEAR(t.value().GroundAt(3.0 + 0.1), 0.15, 1e-4);  // x = 4.1: the first tread
  EXPECT_NEAR(t.value().GroundAt(8.0), 1.5, 1e-4);         // x = 9: the upper floor
  // Mid-flight the body rests on treads about 0.8 m apart: on the flight's incline.
  const double slope = std::atan2(kRise, kRun);
  EXPECT_NEAR(t.value().BodyPitch(4.5), -slope, 0.12);  // nose up: negative about y
  EXPECT_NEAR(t.value().BodyPitch(0.5), 0.0, 1e-9);
  EXPECT_GT(t.value().HeightChange(3.0, 6.0), 1.2);
  EXPECT_LT(t.value().HeightChange(0.0, 2.5), 1e-6);
  // The motion follows it: base_link 1.5 m higher at the end, pitched on the way.
  GaitConfig gait;
  gait.bob_amplitude = 0.0;
  gait.pitch_amplitude_deg = 0.0;
  gait.roll_amplitude_deg = 0.0;
  RobotMotion motion(walk, gait, 0.0, t.value());
  const double end = motion.Duration();
  EXPECT_NEAR(motion.BasePose(end).translation().z() - motion.BasePose(0.0).translation().z(), 1.5,
              1e-3);
  double steepest = 0.0;
  for (double s = 0.0; s < end; s += 0.1) {
    const Eigen::Vector3d x_axis = motion.BasePose(s).linear().col(0);
    steepest = std::max(steepest, std::asin(x_axis.z()));
  }
  EXPECT_NEAR(steepest, slope, 0.12) << "the nose rises by the flight's slope";
}

TEST(SimTerrain, FlightsAreWalkedAtTheStairsSpeed) {
  const SceneMesh mesh = Stair();
  const auto scene = std::move(EmbreeScene::Create(mesh)).value();
  TrajectoryConfig c;
  c.waypoints = {{}};
  c.pause = 0.0;
  c.speed = 0.6;
  const std::vector<PlanarWaypoint> route = {{{3.5, 0.0}, std::nullopt, false},
                                             {{7.5, 0.0}, std::nullopt, false},
                                             {{10.0, 0.0}, std::nullopt, false}};
  const Trajectory fast = std::move(Trajectory::Build({1.0, 0.0, 0.0}, route, c)).value();
  const TerrainConfig tc;
  const TerrainProfile ground = std::move(TerrainProfile::Build(*scene, fast, 0.0, tc)).value();
  const LegSpeed slow = StairLegSpeed(fast, ground, tc, 0.6, 0.3);
  EXPECT_DOUBLE_EQ(slow({3.5, 0.0}, {7.5, 0.0}), 0.5);  // the flight, either way
  EXPECT_DOUBLE_EQ(slow({7.5, 0.0}, {3.5, 0.0}), 0.5);
  EXPECT_DOUBLE_EQ(slow({1.0, 0.0}, {3.5, 0.0}), 1.0);  // the floors
  EXPECT_DOUBLE_EQ(slow({7.5, 0.0}, {10.0, 0.0}), 1.0);
  const Trajectory climbed =
      std::move(Trajectory::Build({1.0, 0.0, 0.0}, route, c, 0.0, slow)).value();
  EXPECT_DOUBLE_EQ(climbed.PathLength(), fast.PathLength());
  // 4 m at 0.3 instead of 0.6 m/s: 6.7 s more at cruise, a little less with the ramps.
  EXPECT_GT(climbed.Duration(), fast.Duration() + 5.5);
}

// A looped route (trajectory.loop, as bags/long/L2_tower_hour.yaml walks the tower for an hour)
// goes back DOWN the flight it climbed: the ground falls tread by tread, the nose points down,
// the flight is walked at the stairs speed both ways, and the loop ends on the start's floor.
TEST(SimTerrain, ALoopWalksTheFlightBackDownToTheStart) {
  const SceneMesh mesh = Stair();
  const auto scene = std::move(EmbreeScene::Create(mesh)).value();
  TrajectoryConfig c;
  c.waypoints = {{}};
  c.pause = 0.5;
  c.speed = 0.6;
  c.loop = true;
  const Eigen::Vector3d start(1.0, 0.0, 0.0);
  const std::vector<PlanarWaypoint> route = {{{3.5, 0.0}, std::nullopt, false},
                                             {{7.5, 0.0}, std::nullopt, false},
                                             {{10.0, 0.0}, std::nullopt, false}};
  // As BuildMotion does: the ground under the looped path, then the flights walked slower.
  const TerrainConfig tc;
  const Trajectory fast = std::move(Trajectory::Build(start, route, c, 60.0)).value();
  const Result<TerrainProfile> fast_ground = TerrainProfile::Build(*scene, fast, 0.0, tc);
  ASSERT_TRUE(fast_ground.ok()) << fast_ground.error();
  const LegSpeed slow = StairLegSpeed(fast, fast_ground.value(), tc, 0.6, 0.3);
  c.loop = false;
  const double one_way =
      std::move(Trajectory::Build(start, route, c, 0.0, slow)).value().Duration();
  c.loop = true;
  const Trajectory walk =
      std::move(Trajectory::Build(start, route, c, 2.5 * one_way, slow)).value();
  const Result<TerrainProfile> t = TerrainProfile::Build(*scene, walk, 0.0, tc);
  ASSERT_TRUE(t.ok()) << t.error();
  // 9 m out (x = 1 to 10, the flight from x = 4 to 7), then back: on the way back at x the path
  // has walked there + 10 - x, and the ground falls tread by tread.
  const double there = 9.0;
  auto back_at = [&](double x) { return t.value().GroundAt(there + 10.0 - x); };
  EXPECT_NEAR(t.value().GroundAt(there - 1.0), 1.5, 1e-4);        // x = 9 out: the upper floor
  EXPECT_NEAR(back_at(7.5), 1.5, 1e-4);                           // the upper floor
  EXPECT_NEAR(back_at(6.55), 1.5 - kRise, 1e-4);                  // the second tread down
  EXPECT_NEAR(back_at(4.15), kRise, 1e-4);                        // the bottom tread
  EXPECT_NEAR(back_at(3.5), 0.0, 1e-4);                           // the lower floor
  EXPECT_NEAR(t.value().GroundAt(2.0 * there - 0.5), 0.0, 1e-4);  // x = 1.5
  GaitConfig gait;
  gait.bob_amplitude = 0.0;
  gait.pitch_amplitude_deg = 0.0;
  gait.roll_amplitude_deg = 0.0;
  RobotMotion motion(walk, gait, 0.0, t.value());
  const double z0 = motion.BasePose(0.0).translation().z();
  double back = -1.0, highest = z0, nose_down = 0.0;
  for (double s = 0.0; s < motion.Duration() && back < 0.0; s += 0.05) {
    const Eigen::Isometry3d pose = motion.BasePose(s);
    highest = std::max(highest, pose.translation().z());
    if (s > one_way) {
      nose_down = std::min(nose_down, std::asin(pose.linear().col(0).z()));
      if ((pose.translation().head<2>() - start.head<2>()).norm() < 1e-6) back = s;
    }
  }
  ASSERT_GT(back, one_way) << "the loop came back to the start";
  EXPECT_NEAR(highest - z0, 1.5, 1e-3);
  EXPECT_NEAR(motion.BasePose(back).translation().z(), z0, 1e-3) << "on the start's floor again";
  EXPECT_NEAR(nose_down, -std::atan2(kRise, kRun), 0.12) << "the nose dips by the flight's slope";
  // The way back takes as long as the way there (the flight at the stairs speed both ways, not
  // at cruise), plus the turn about at the far end, less the pause at the start.
  const double turn_about = TrapezoidDuration(M_PI, c.turn_rate_deg * M_PI / 180.0,
                                              c.turn_acceleration_deg * M_PI / 180.0);
  EXPECT_NEAR(back - one_way, one_way + turn_about - c.pause, 0.1);
}

TEST(SimTerrain, ADropOrAWallIsNamed) {
  SceneMesh mesh;
  mesh.AddBox({2.0, 0.0}, -0.2, {4.0, 2.0, 0.2}, 0.0, 0.3f);  // the floor ends at x = 4
  const auto scene = std::move(EmbreeScene::Create(mesh)).value();
  const Result<TerrainProfile> t = TerrainProfile::Build(*scene, Walk(6.0), 0.0, TerrainConfig());
  ASSERT_FALSE(t.ok());
  EXPECT_NE(t.error().find("no ground"), std::string::npos) << t.error();
  EXPECT_NE(t.error().find("(4.0"), std::string::npos) << t.error();
}

TEST(SimTerrain, TheWalkCheckRisesWithTheFlight) {
  const SceneMesh mesh = Stair();
  const auto scene = std::move(EmbreeScene::Create(mesh)).value();
  // Level at the lower floor's height, the flight blocks the walk; on the incline it does not.
  EXPECT_FALSE(CheckWalkable(*scene, {3.5, 0.0}, {7.5, 0.0}, 0.0).empty());
  EXPECT_EQ(CheckWalkable(*scene, {3.5, 0.0}, {7.5, 0.0}, 0.0, 1.5), "");
}

TEST(SimTerrain, OdometryMisjudgesEachRiseByItsScaleError) {
  OdometryConfig c;
  c.z_scale_error = 0.02;
  OdometryDrift odometry(c, 1, 0.0);
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation().z() = 0.5;
  EXPECT_NEAR(odometry.Step(0.0, pose).odom_T_base.translation().z(), 0.5, 1e-12);
  for (int k = 1; k <= 30; ++k) {  // 3 m up in 0.1 m steps
    pose.translation() = Eigen::Vector3d(0.1 * k, 0.0, 0.5 + 0.1 * k);
    odometry.Step(0.02 * k, pose);
  }
  pose.translation().z() = 3.5;
  EXPECT_NEAR(odometry.Step(1.0, pose).odom_T_base.translation().z(), 0.5 + 3.0 * 1.02, 1e-9);
  OdometryDrift exact(OdometryConfig(), 1, 0.0);  // without it: the true height
  exact.Step(0.0, Eigen::Isometry3d::Identity());
  EXPECT_NEAR(exact.Step(1.0, pose).odom_T_base.translation().z(), 3.5, 1e-12);
}

}  // namespace
}  // namespace sim
}  // namespace is_graphs
