// The odometry guard on the simulator's leg odometry of the scenarios whose drift, gait and
// routes are the harshest (the double drift, the kidnap carry, the harsh office, stairs, the
// other LiDARs' robots, dropped scans): it accepts every message, so the guard changes nothing
// on a bag without faults (the correction stays the identity, the readings pass bit for bit).
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

#include "is_graphs/common/odometry_guard.h"
#include "is_graphs/sim/scenario_yaml.h"
#include "is_graphs/sim/simulation.h"
#include "sim_office_helpers.h"

namespace is_graphs {
namespace sim {
namespace {

class GuardOnScenario : public ::testing::TestWithParam<const char*> {};

TEST_P(GuardOnScenario, AcceptsEveryOdometryMessage) {
  if (!testing::HaveConverter()) GTEST_SKIP() << "the converter's venv is missing";
  const std::string yaml = testing::kSourceRoot + "/bags/" + GetParam() + ".yaml";
  const Result<ScenarioConfig> config = LoadScenarioYaml(yaml, testing::kSourceRoot);
  ASSERT_TRUE(config.ok()) << config.error();
  std::ifstream building(testing::kSourceRoot + "/" + config.value().building);
  if (!building.good()) GTEST_SKIP() << config.value().building << " is not here";
  const auto sim =
      PrepareSimulation(config.value(), std::string(IS_GRAPHS_TEST_TMP_DIR) + "/bim_cache");
  ASSERT_TRUE(sim.ok()) << sim.error();
  const Simulation& s = *sim.value();
  OdometryDrift odometry = s.MakeOdometry();
  common::OdometryGuard guard;
  const double dt = 1.0 / s.config.odometry.rate_hz;
  int leg = 0, samples = 0;
  for (; samples * dt <= s.duration; ++samples) {
    const double t = samples * dt;
    const Eigen::Isometry3d truth = s.motion->BasePose(t);
    const int now = s.motion->LegAt(t);
    if (now != leg) odometry.Carried();  // as the runner: the carry is not seen
    leg = now;
    const OdometrySample o = odometry.Step(t, truth);
    const auto r = guard.Check(s.config.start_time + t, o.odom_T_base);
    ASSERT_EQ(r.verdict, common::OdometryGuard::Verdict::kAccepted)
        << GetParam() << " at " << t << " s: " << r.message;
    ASSERT_TRUE(r.odom_T_base.isApprox(o.odom_T_base, 0.0));
  }
  std::printf("%s: %d odometry messages over %.0f s, all accepted\n", GetParam(), samples,
              s.duration);
}

INSTANTIATE_TEST_SUITE_P(Scenarios, GuardOnScenario,
                         ::testing::Values("R1_double_drift", "R3_kidnapped", "H1_office_harsh",
                                           "H4_fzk_haus_harsh", "M3_ac11_stairs_up",
                                           "M7_tower_down", "S1_office_os1_64", "R2_dropped_scans",
                                           "D6_large"));

}  // namespace
}  // namespace sim
}  // namespace is_graphs
