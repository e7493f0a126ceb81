// OdometryGuard on a walk at 50 Hz (0.8 m/s, turning, with reading noise; seed printed): every
// message of the clean walk is accepted and passed on unchanged; a NaN, a stamp not after the
// last, one +50 m glitch and a spin are skipped; a lasting +50 m step is skipped for
// step_confirm_time and then bridged: the corrected odometry goes on from where it was, within
// the noise of the truth; time going back starts the guard over.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

#include "is_graphs/common/odometry_guard.h"
#include "is_graphs/geometry/se3.h"

namespace is_graphs {
namespace common {
namespace {

constexpr double kRate = 50.0;  // Hz

struct Sample {
  double stamp;
  Eigen::Isometry3d pose;
};

// A walk of `seconds` at 0.8 m/s with a slow weave, readings with 1 mm / 0.05 deg noise.
std::vector<Sample> Walk(double seconds, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::vector<Sample> out;
  double x = 0.0, y = 0.0, yaw = 0.0;
  for (int i = 0; i < seconds * kRate; ++i) {
    const double t = 100.0 + i / kRate;
    const double yaw_rate = 0.6 * std::sin(0.4 * t);
    x += 0.8 / kRate * std::cos(yaw);
    y += 0.8 / kRate * std::sin(yaw);
    yaw += yaw_rate / kRate;
    out.push_back({t, geometry::IsometryFromXYYaw(x + 1e-3 * noise(rng), y + 1e-3 * noise(rng),
                                                  yaw + 1e-3 * noise(rng))});
  }
  return out;
}

unsigned Seed() {
  const unsigned seed = 20261128;
  std::printf("seed %u\n", seed);
  return seed;
}

TEST(OdometryGuard, AcceptsEveryMessageOfACleanWalkUnchanged) {
  const auto walk = Walk(20.0, Seed());
  OdometryGuard guard;
  for (const auto& s : walk) {
    const auto r = guard.Check(s.stamp, s.pose);
    ASSERT_EQ(r.verdict, OdometryGuard::Verdict::kAccepted) << s.stamp << ": " << r.message;
    EXPECT_TRUE(r.odom_T_base.isApprox(s.pose, 1e-12));
  }
  EXPECT_EQ(guard.rejected(), 0);
  EXPECT_EQ(guard.bridged(), 0);
}

TEST(OdometryGuard, SkipsNonFiniteAndOutOfOrderMessages) {
  const auto walk = Walk(2.0, Seed());
  OdometryGuard guard;
  for (int i = 0; i < 50; ++i) ASSERT_TRUE(guard.Check(walk[i].stamp, walk[i].pose).usable());
  Eigen::Isometry3d nan_x = walk[50].pose;
  nan_x.translation().x() = std::numeric_limits<double>::quiet_NaN();
  auto r = guard.Check(walk[50].stamp, nan_x);
  EXPECT_EQ(r.verdict, OdometryGuard::Verdict::kNonFinite);
  EXPECT_NE(r.message.find("position"), std::string::npos) << r.message;
  Eigen::Isometry3d nan_rotation = walk[50].pose;
  nan_rotation.linear()(0, 0) = std::numeric_limits<double>::infinity();
  r = guard.Check(walk[50].stamp, nan_rotation);
  EXPECT_EQ(r.verdict, OdometryGuard::Verdict::kNonFinite);
  EXPECT_NE(r.message.find("orientation"), std::string::npos) << r.message;
  EXPECT_EQ(guard.Check(std::numeric_limits<double>::quiet_NaN(), walk[50].pose).verdict,
            OdometryGuard::Verdict::kNonFinite);
  EXPECT_EQ(guard.Check(walk[49].stamp, walk[49].pose).verdict,
            OdometryGuard::Verdict::kOutOfOrder);
  // After the skipped ones, the walk goes on (a 20 ms hole is plausible).
  EXPECT_EQ(guard.Check(walk[51].stamp, walk[51].pose).verdict, OdometryGuard::Verdict::kAccepted);
  EXPECT_EQ(guard.rejected(), 4);
}

TEST(OdometryGuard, SkipsOneGlitchAndGoesOnWithTheNextMessage) {
  const auto walk = Walk(4.0, Seed());
  OdometryGuard guard;
  for (size_t i = 0; i < walk.size(); ++i) {
    Eigen::Isometry3d reading = walk[i].pose;
    if (i == 100) reading.translation().x() += 50.0;
    const auto r = guard.Check(walk[i].stamp, reading);
    if (i == 100) {
      EXPECT_EQ(r.verdict, OdometryGuard::Verdict::kGlitch);
      EXPECT_NE(r.message.find("moved 50"), std::string::npos) << r.message;
    } else {
      ASSERT_EQ(r.verdict, OdometryGuard::Verdict::kAccepted) << i << ": " << r.message;
      EXPECT_TRUE(r.odom_T_base.isApprox(walk[i].pose, 1e-12));
    }
  }
  EXPECT_EQ(guard.rejected(), 1);
}

TEST(OdometryGuard, SkipsASpinFasterThanTheRobotTurns) {
  const auto walk = Walk(2.0, Seed());
  OdometryGuard guard;
  for (int i = 0; i < 50; ++i) ASSERT_TRUE(guard.Check(walk[i].stamp, walk[i].pose).usable());
  Eigen::Isometry3d spun = walk[50].pose;
  spun.linear() = spun.linear() * Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ());
  const auto r = guard.Check(walk[50].stamp, spun);
  EXPECT_EQ(r.verdict, OdometryGuard::Verdict::kGlitch);
  EXPECT_NE(r.message.find("turned 90"), std::string::npos) << r.message;
}

TEST(OdometryGuard, BridgesALastingStepAfterStepConfirmTime) {
  const auto walk = Walk(6.0, Seed());
  OdometryGuardConfig config;
  config.step_confirm_time = 0.5;
  OdometryGuard guard(config);
  const Eigen::Vector3d step(50.0, -3.0, 0.0);
  const size_t first = 100;  // t = 102 s
  int skipped = 0;
  size_t bridged_at = 0;
  for (size_t i = 0; i < walk.size(); ++i) {
    Eigen::Isometry3d reading = walk[i].pose;
    if (i >= first) reading.pretranslate(step);
    const auto r = guard.Check(walk[i].stamp, reading);
    if (r.verdict == OdometryGuard::Verdict::kGlitch) {
      ++skipped;
      continue;
    }
    if (r.verdict == OdometryGuard::Verdict::kBridged) {
      bridged_at = i;
      EXPECT_NE(r.message.find("stepped by 50"), std::string::npos) << r.message;
    } else {
      ASSERT_EQ(r.verdict, OdometryGuard::Verdict::kAccepted) << i << ": " << r.message;
    }
    // Continuous: the corrected odometry is the walk's (across the step, the motion of the
    // step before it), within the readings' noise over 3 m.
    EXPECT_LT((r.odom_T_base.translation() - walk[i].pose.translation()).norm(), 0.02) << i;
  }
  // 0.5 s at 50 Hz after the first stepped message (26: the stamps' rounding).
  EXPECT_GE(bridged_at, first + 25);
  EXPECT_LE(bridged_at, first + 26);
  EXPECT_EQ(skipped, static_cast<int>(bridged_at - first));
  EXPECT_EQ(guard.bridged(), 1);
  EXPECT_EQ(guard.rejected(), skipped);
}

TEST(OdometryGuard, WithoutStepConfirmTimeALastingStepIsSkippedThroughout) {
  const auto walk = Walk(3.0, Seed());
  OdometryGuardConfig config;
  config.step_confirm_time = 0.0;
  OdometryGuard guard(config);
  int usable = 0;
  for (size_t i = 0; i < walk.size(); ++i) {
    Eigen::Isometry3d reading = walk[i].pose;
    if (i >= 50) reading.translation().x() += 50.0;
    usable += guard.Check(walk[i].stamp, reading).usable();
  }
  EXPECT_EQ(usable, 50);
}

TEST(OdometryGuard, TimeGoingBackStartsOver) {
  const auto walk = Walk(4.0, Seed());
  OdometryGuard guard;
  for (int i = 100; i < 150; ++i) ASSERT_TRUE(guard.Check(walk[i].stamp, walk[i].pose).usable());
  // The bag restarted: two seconds earlier, somewhere else.
  const auto r = guard.Check(walk[0].stamp, walk[0].pose);
  EXPECT_EQ(r.verdict, OdometryGuard::Verdict::kTimeBack);
  EXPECT_TRUE(r.odom_T_base.isApprox(walk[0].pose, 1e-12));
  EXPECT_EQ(guard.Check(walk[1].stamp, walk[1].pose).verdict, OdometryGuard::Verdict::kAccepted);
}

TEST(OdometryGuard, AcceptsTheFirstMessageAfterAGapWhereverThePlausibleWalkGotTo) {
  const auto walk = Walk(25.0, Seed());
  OdometryGuard guard;
  for (int i = 0; i < 50; ++i) ASSERT_TRUE(guard.Check(walk[i].stamp, walk[i].pose).usable());
  // 20 s without odometry (a pause), then the walk 16 m further on.
  EXPECT_EQ(guard.Check(walk[1050].stamp, walk[1050].pose).verdict,
            OdometryGuard::Verdict::kAccepted);
  EXPECT_EQ(guard.Check(walk[1051].stamp, walk[1051].pose).verdict,
            OdometryGuard::Verdict::kAccepted);
}

TEST(OdometryGuardConfig, ValidateNamesTheField) {
  OdometryGuardConfig c;
  EXPECT_EQ(c.Validate(), "");
  c.max_linear_speed = 0.0;
  EXPECT_EQ(c.Validate().rfind("max_linear_speed", 0), 0u);
  c = {};
  c.step_confirm_time = -1.0;
  EXPECT_EQ(c.Validate().rfind("step_confirm_time", 0), 0u);
}

}  // namespace
}  // namespace common
}  // namespace is_graphs
