// Robustness scenarios: a kidnapped robot (carried to a second route: the ground truth jumps,
// the odometry holds its pose) and sensor dropouts (no scans in a window, odometry runs on), on
// synthetic motion and through the whole simulation of bim/office.ifc; determinism.
#include <gtest/gtest.h>

#include <fstream>

#include "is_graphs/geometry/se3.h"
#include "is_graphs/sim/scenario_yaml.h"
#include "is_graphs/sim/simulation.h"
#include "is_graphs/sim/simulation_runner.h"
#include "sim_office_helpers.h"
#include "sim_test_helpers.h"

namespace is_graphs {
namespace sim {
namespace {

Trajectory Walk(const Eigen::Vector3d& start, const Eigen::Vector2d& to) {
  TrajectoryConfig c;
  c.waypoints = {{}};  // validation only
  c.pause = 0.5;
  return std::move(Trajectory::Build(start, {{to, std::nullopt, true}}, c, 0.0)).value();
}

TEST(SimKidnap, MotionJumpsToTheSecondRouteAtTheCarry) {
  RobotMotion motion(Walk({0, 0, 0}, {6, 0}), GaitConfig(), 0.0);
  motion.Carry(4.0, Walk({10, 5, 1.0}, {10, 9}));
  EXPECT_EQ(motion.LegAt(3.99), 0);
  EXPECT_EQ(motion.LegAt(4.0), 1);
  EXPECT_EQ(motion.LegAt(4.0 - 1e-12), 1);  // k * period rounding below the carry
  EXPECT_DOUBLE_EQ(motion.Duration(), 4.0 + motion.trajectory(1).Duration());
  // At the carry the robot stands at the second route's start (its first pause: no sway).
  const Eigen::Isometry3d after = motion.BasePose(4.0);
  EXPECT_NEAR(after.translation().x(), 10.0, 1e-12);
  EXPECT_NEAR(after.translation().y(), 5.0, 1e-12);
  EXPECT_NEAR(geometry::Yaw(after), 1.0, 1e-12);
  EXPECT_LT(motion.BasePose(3.98).translation().x(), 6.0 + 1e-9);
  EXPECT_GT(motion.BasePose(3.98).translation().x(), 2.0);
}

TEST(SimKidnap, OdometryHoldsAcrossTheCarryThenIntegratesTheNewWalk) {
  RobotMotion motion(Walk({0, 0, 0}, {6, 0}), GaitConfig(), 0.0);
  motion.Carry(4.0, Walk({10, 5, 0.0}, {10, 9}));
  OdometryDrift odometry(OdometryConfig(), 1, 0.0);  // no drift: odometry = true increments
  OdometrySample before;
  Eigen::Isometry3d bim_T_odom_after = Eigen::Isometry3d::Identity();
  int leg = 0;
  for (int i = 0; i <= 500; ++i) {
    const double t = i / 50.0;
    const Eigen::Isometry3d truth = motion.BasePose(t);
    if (motion.LegAt(t) != leg) odometry.Carried();
    const OdometrySample s = odometry.Step(t, truth);
    if (motion.LegAt(t) != leg) {  // the sample at the jump: the planar pose holds
      EXPECT_EQ(i, 200);
      EXPECT_NEAR((s.odom_T_base.translation() - before.odom_T_base.translation()).head<2>().norm(),
                  0.0, 1e-12);
      EXPECT_NEAR(geometry::Yaw(s.odom_T_base), geometry::Yaw(before.odom_T_base), 1e-12);
      EXPECT_EQ(s.linear_velocity.norm(), 0.0);
      bim_T_odom_after = truth * s.odom_T_base.inverse();
      leg = motion.LegAt(t);
    } else if (leg == 1) {  // after it, the odometry follows the truth from the new place
      EXPECT_TRUE((truth * s.odom_T_base.inverse()).isApprox(bim_T_odom_after, 1e-9)) << t;
    } else {  // before it, from the start
      EXPECT_TRUE((truth * s.odom_T_base.inverse()).isApprox(odometry.bim_T_odom(), 1e-9)) << t;
    }
    before = s;
  }
  EXPECT_EQ(leg, 1);
  EXPECT_GT(motion.BasePose(10.0).translation().y(), 6.0);  // it did walk the second route
}

// The whole simulation on the office building (skipped without the IFC converter).
const std::string& kRoot = testing::kSourceRoot;

using testing::HaveConverter;
using testing::Prepare;
using testing::SameScan;

// What a run delivers, in order.
struct Recorder : SimulationSink {
  struct Odometry {
    double t;
    Eigen::Isometry3d truth;
    OdometrySample odometry;
  };
  void OnOdometry(double t, const Eigen::Isometry3d& truth, const OdometrySample& s) override {
    odometry.push_back({t, truth, s});
  }
  void OnScan(const LidarScan& scan, double publish_time) override {
    scans.push_back(scan);
    publish_times.push_back(publish_time);
  }
  std::vector<Odometry> odometry;
  std::vector<LidarScan> scans;
  std::vector<double> publish_times;
};

// 8 s in the office: Corridor -> 102, carried at 5 s to the meeting room, then towards the
// corridor; scans dropped in [2, 3.05) with kDropout. Perfect odometry, so the carry is all it
// misses.
const std::string kScenario = R"(
building: bim/office.ifc
seed: 3
duration: 8
trajectory: {rooms: [Corridor, "102"], speed: 1.0, pause: 0.2}
kidnap: {time: 5, rooms: [Meeting, Corridor]}
)";
const std::string kDropout = "sensor: {dropouts: [[2, 3.05]]}\n";

TEST(SimRobustness, DropoutsLeaveNoScansWhileTheOdometryRuns) {
  if (!HaveConverter()) GTEST_SKIP() << "bim/office.ifc or the converter's venv is missing";
  const auto sim = Prepare(kScenario + kDropout);
  ASSERT_TRUE(sim);
  Recorder out;
  const RunStats stats = RunSimulation(*sim, out);
  EXPECT_EQ(sim->NumScans(), 80);
  EXPECT_EQ(stats.dropped_scans, 11);  // sweeps starting at 2.0 .. 3.0 s
  EXPECT_EQ(stats.scans, 69);
  ASSERT_EQ(out.scans.size(), 69u);
  for (std::size_t i = 0; i < out.scans.size(); ++i) {
    const double begin = out.scans[i].stamp, end = out.publish_times[i];
    EXPECT_TRUE(end <= 2.0 + 1e-9 || begin >= 3.05 - 1e-9) << "scan at " << begin;
  }
  EXPECT_EQ(out.odometry.size(), 401u);  // 50 Hz throughout
  for (std::size_t i = 1; i < out.odometry.size(); ++i) {
    EXPECT_NEAR(out.odometry[i].t - out.odometry[i - 1].t, 0.02, 1e-9);
  }
  // The scans kept are those of the same scenario without the dropout (own random streams).
  const auto full = Prepare(kScenario);
  ASSERT_TRUE(full);
  for (const LidarScan& scan : out.scans) {
    const int k = static_cast<int>(std::lround(scan.stamp * 10.0));
    EXPECT_TRUE(SameScan(scan, full->scans->Simulate(k, scan.stamp))) << k;
  }
}

TEST(SimRobustness, KidnapJumpsTheTruthNotTheOdometry) {
  if (!HaveConverter()) GTEST_SKIP() << "bim/office.ifc or the converter's venv is missing";
  const auto sim = Prepare(kScenario + kDropout);
  ASSERT_TRUE(sim && sim->kidnap_route);
  Recorder out;
  RunSimulation(*sim, out);
  std::size_t jump = 0;
  while (jump < out.odometry.size() && out.odometry[jump].t < 5.0 - 1e-9) ++jump;
  ASSERT_EQ(jump, 250u);
  const Recorder::Odometry& a = out.odometry[jump - 1];
  const Recorder::Odometry& b = out.odometry[jump];
  // The truth jumps from where the first route was to the second route's start.
  const Eigen::Vector3d was = sim->motion->trajectory(0).StateAt(a.t).pose;
  const Eigen::Vector3d& start = sim->kidnap_route->start;
  EXPECT_NEAR((a.truth.translation().head<2>() - was.head<2>()).norm(), 0.0, 1e-9);
  EXPECT_NEAR((b.truth.translation().head<2>() - start.head<2>()).norm(), 0.0, 1e-9);
  EXPECT_NEAR(geometry::Yaw(b.truth), start.z(), 1e-9);
  EXPECT_GT((b.truth.translation() - a.truth.translation()).norm(), 3.0);
  // The odometry does not see it: same planar pose, zero velocity.
  EXPECT_NEAR((b.odometry.odom_T_base.translation().head<2>() -
               a.odometry.odom_T_base.translation().head<2>())
                  .norm(),
              0.0, 1e-12);
  EXPECT_NEAR(geometry::Yaw(b.odometry.odom_T_base), geometry::Yaw(a.odometry.odom_T_base), 1e-12);
  // Elsewhere it steps as the truth does (no drift configured: exactly).
  for (std::size_t i = 1; i < out.odometry.size(); ++i) {
    if (i == jump) continue;
    const Recorder::Odometry& p = out.odometry[i - 1];
    const Recorder::Odometry& q = out.odometry[i];
    const double true_step = (q.truth.translation() - p.truth.translation()).head<2>().norm();
    const double odom_step =
        (q.odometry.odom_T_base.translation() - p.odometry.odom_T_base.translation())
            .head<2>()
            .norm();
    EXPECT_NEAR(odom_step, true_step, 1e-9) << q.t;
  }
  // The walk after the carry happens (the robot leaves the start).
  EXPECT_GT((out.odometry.back().truth.translation().head<2>() - start.head<2>()).norm(), 0.5);
}

TEST(SimRobustness, SameScenarioSameOutputPipelinedOrNot) {
  if (!HaveConverter()) GTEST_SKIP() << "bim/office.ifc or the converter's venv is missing";
  const std::string yaml =
      kScenario + kDropout +
      "odometry: {scale_error: 0.02, translation_random_walk: 0.01, yaw_random_walk: 0.002}\n";
  const auto a = Prepare(yaml);
  const auto b = Prepare(yaml);
  ASSERT_TRUE(a && b);
  Recorder x, y;
  RunSimulation(*a, x, true);
  RunSimulation(*b, y, false);
  ASSERT_EQ(x.scans.size(), y.scans.size());
  for (std::size_t i = 0; i < x.scans.size(); ++i) {
    EXPECT_TRUE(SameScan(x.scans[i], y.scans[i])) << i;
    EXPECT_EQ(x.publish_times[i], y.publish_times[i]);
  }
  ASSERT_EQ(x.odometry.size(), y.odometry.size());
  for (std::size_t i = 0; i < x.odometry.size(); ++i) {
    EXPECT_TRUE(x.odometry[i].truth.isApprox(y.odometry[i].truth, 0.0));
    EXPECT_TRUE(
        x.odometry[i].odometry.odom_T_base.isApprox(y.odometry[i].odometry.odom_T_base, 0.0));
  }
}

TEST(SimRobustness, KidnapRouteErrorsNameTheKidnapField) {
  if (!HaveConverter()) GTEST_SKIP() << "bim/office.ifc or the converter's venv is missing";
  auto error = [](const std::string& kidnap) {
    const std::string yaml =
        "building: bim/office.ifc\ntrajectory: {rooms: [Corridor]}\nkidnap: " + kidnap + "\n";
    const Result<ScenarioConfig> c = ParseScenarioYaml(yaml, "t.yaml", kRoot);
    if (!c.ok()) return c.error();
    const auto s = PrepareSimulation(c.value(), std::string(IS_GRAPHS_TEST_TMP_DIR) + "/bim_cache");
    return s.ok() ? std::string() : s.error();
  };
  EXPECT_EQ(error("{time: 3, rooms: [Meeting, Corridor]}"), "");
  EXPECT_NE(error("{time: 3, rooms: [Meeting, Lobby]}").find("kidnap.rooms[1]"), std::string::npos);
  EXPECT_NE(error("{time: 3, rooms: [Meeting], start: {room: Attic}}").find("kidnap.start.room"),
            std::string::npos);
}

}  // namespace
}  // namespace sim
}  // namespace is_graphs
