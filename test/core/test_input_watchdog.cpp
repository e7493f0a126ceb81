// InputWatchdog: fresh while odometry, tf map -> odom and S-Graph revisions keep coming; late
// (DEGRADED) past degraded_after / max_distance_without_sgraph, stopped (LOST) past lost_after /
// lost_distance_without_sgraph, naming the input; armed, everything counts as just seen.
#include <gtest/gtest.h>

#include <cmath>

#include "is_graphs/merging/input_watchdog.h"

namespace is_graphs {
namespace merging {
namespace {

using Health = InputWatchdog::Health;

// 1 s / 10 s, 3 m / 15 m.
WatchdogConfig Config() {
  WatchdogConfig c;
  c.degraded_after = 1.0;
  c.lost_after = 10.0;
  c.max_distance_without_sgraph = 3.0;
  c.lost_distance_without_sgraph = 15.0;
  return c;
}

// A robot walking at 0.8 m/s, all inputs at 50 Hz up to `until`; S-Graph revisions every 0.8 m
// up to `sgraph_until`.
void Feed(InputWatchdog& w, double from, double until, double sgraph_until, double tf_until) {
  for (int i = std::lround(from * 50); i <= std::lround(until * 50); ++i) {
    const double t = i / 50.0, distance = 0.8 * t;
    w.OnOdometry(t, distance);
    if (t <= tf_until) w.OnMapToOdom(t);
    if (t <= sgraph_until && i % 50 == 0) w.OnSGraph(distance);
  }
}

TEST(InputWatchdog, FreshWhileEveryInputComes) {
  InputWatchdog w(Config());
  w.Arm(0.0, 0.0);
  Feed(w, 0.0, 30.0, 30.0, 30.0);
  const auto r = w.Check(30.05);
  EXPECT_EQ(r.health, Health::kFresh) << r.message;
  EXPECT_EQ(r.message, "");
  EXPECT_LT(r.distance_since_sgraph, 0.85);
}

TEST(InputWatchdog, OdometryStoppingIsLateThenStopped) {
  InputWatchdog w(Config());
  w.Arm(0.0, 0.0);
  Feed(w, 0.0, 10.0, 10.0, 10.0);
  EXPECT_EQ(w.Check(10.9).health, Health::kFresh);
  const auto late = w.Check(11.2);
  EXPECT_EQ(late.health, Health::kLate);
  EXPECT_NE(late.message.find("no odometry for 1.2 s (DEGRADED"), std::string::npos)
      << late.message;
  const auto lost = w.Check(20.5);
  EXPECT_EQ(lost.health, Health::kStopped);
  EXPECT_NE(lost.message.find("no odometry for 10.5 s (LOST past 10 s)"), std::string::npos)
      << lost.message;
}

TEST(InputWatchdog, TheSGraphNodeHangingStopsMapToOdom) {
  InputWatchdog w(Config());
  w.Arm(0.0, 0.0);
  Feed(w, 0.0, 20.0, 10.0, 10.0);  // odometry goes on, tf and revisions stop at 10 s
  const auto r = w.Check(11.1);
  EXPECT_EQ(r.health, Health::kLate);
  EXPECT_NE(r.message.find("no tf map -> odom"), std::string::npos) << r.message;
  EXPECT_EQ(w.Check(20.1).health, Health::kStopped);
}

TEST(InputWatchdog, WalkingWithoutRevisionsIsLateByDistance) {
  InputWatchdog w(Config());
  w.Arm(0.0, 0.0);
  Feed(w, 0.0, 10.0, 5.0, 10.0);  // the S-Graph stops at 4 m (clouds without points)
  // 8 m walked, 4 since the last revision: late (3 m), not lost (15 m).
  auto r = w.Check(10.0);
  EXPECT_EQ(r.health, Health::kLate);
  EXPECT_NEAR(r.distance_since_sgraph, 4.0, 0.1);
  EXPECT_NE(r.message.find("no S-Graph revision over"), std::string::npos) << r.message;
  Feed(w, 10.0, 30.0, 5.0, 30.0);
  r = w.Check(30.0);
  EXPECT_EQ(r.health, Health::kStopped) << r.message;
}

TEST(InputWatchdog, StandingStillWithoutRevisionsIsFresh) {
  InputWatchdog w(Config());
  w.Arm(0.0, 0.0);
  for (double t = 0.0; t <= 60.0; t += 0.02) w.OnOdometry(t, 0.0), w.OnMapToOdom(t);
  EXPECT_EQ(w.Check(60.0).health, Health::kFresh);
}

TEST(InputWatchdog, ArmingCountsEveryInputAsJustSeen) {
  InputWatchdog w(Config());
  w.Arm(100.0, 50.0);
  EXPECT_EQ(w.Check(100.5).health, Health::kFresh);
  EXPECT_EQ(w.Check(101.5).health, Health::kLate);
}

TEST(WatchdogConfig, ValidateNamesTheField) {
  WatchdogConfig c;
  EXPECT_EQ(c.Validate(), "");
  c.lost_after = 0.5;
  EXPECT_EQ(c.Validate().rfind("lost_after", 0), 0u);
  c = {};
  c.degraded_sigma_per_m = -1.0;
  EXPECT_EQ(c.Validate().rfind("degraded_sigma_per_m", 0), 0u);
}

}  // namespace
}  // namespace merging
}  // namespace is_graphs
