// ScanOdometrySync: a cloud waits for the odometry of its own sweep (and why: a turning robot's
// scan deskewed without it has tilted walls).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

#include "is_graphs/sgraph/scan_odometry_sync.h"
#include "is_graphs/sgraph/sgraph_builder.h"
#include "sgraph_test_helpers.h"

namespace is_graphs {
namespace sgraph {
namespace {

Scan ScanAt(double stamp, double sweep) {
  Scan s;
  s.stamp = stamp;
  for (int i = 0; i < 10; ++i) {
    ScanPoint p;
    p.x = 1.0f;
    p.time = static_cast<float>(sweep * i / 9.0);
    s.points.push_back(p);
  }
  return s;
}

TEST(ScanOdometrySync, LastFiringIsTheStampPlusTheLatestPointTime) {
  Scan s = ScanAt(10.0, 0.1);
  EXPECT_NEAR(LastFiring(s), 10.1, 1e-6);
  s.points[3].time = std::numeric_limits<float>::quiet_NaN();
  EXPECT_NEAR(LastFiring(s), 10.1, 1e-6);
  s.has_time = false;  // no per-point time: the stamp
  EXPECT_DOUBLE_EQ(LastFiring(s), 10.0);
}

TEST(ScanOdometrySync, ACloudWaitsUntilOdometryCoversItsSweep) {
  ScanOdometrySync sync(0.3);
  sync.Push(ScanAt(10.0, 0.1), Eigen::Isometry3d::Identity(), /*now=*/0.0);
  EXPECT_TRUE(sync.Release(/*odom_stamp=*/10.0, 0.01).empty());  // only the first firing
  EXPECT_TRUE(sync.Release(10.08, 0.02).empty());
  const auto out = sync.Release(10.1, 0.03);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_FALSE(out[0].waited_out);
  EXPECT_DOUBLE_EQ(out[0].scan.stamp, 10.0);
  EXPECT_EQ(sync.size(), 0u);
}

TEST(ScanOdometrySync, OdometryThatNeverComesReleasesTheCloudAfterMaxWait) {
  ScanOdometrySync sync(0.3);
  sync.Push(ScanAt(10.0, 0.1), Eigen::Isometry3d::Identity(), 5.0);
  EXPECT_TRUE(sync.Release(10.05, 5.29).empty());
  const auto out = sync.Release(10.05, 5.31);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_TRUE(out[0].waited_out);
}

TEST(ScanOdometrySync, OrderIsKept) {
  ScanOdometrySync sync(0.3);
  // The second cloud is covered first (its stamp is earlier: out of order) but may not overtake.
  sync.Push(ScanAt(10.1, 0.1), Eigen::Isometry3d::Identity(), 0.0);
  sync.Push(ScanAt(10.0, 0.1), Eigen::Isometry3d::Identity(), 0.0);
  EXPECT_TRUE(sync.Release(10.15, 0.1).empty());
  const auto out = sync.Release(10.2, 0.1);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_DOUBLE_EQ(out[0].scan.stamp, 10.1);
  EXPECT_DOUBLE_EQ(out[1].scan.stamp, 10.0);
}

TEST(ScanOdometrySync, AFullQueueReleasesItsOldestAndZeroWaitReleasesAtOnce) {
  ScanOdometrySync sync(10.0, /*max_pending=*/2);
  for (int i = 0; i < 3; ++i)
    sync.Push(ScanAt(10.0 + 0.1 * i, 0.1), Eigen::Isometry3d::Identity(), 0.0);
  const auto out = sync.Release(0.0, 0.0);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_TRUE(out[0].waited_out);
  EXPECT_EQ(sync.size(), 2u);
  sync.Clear();
  EXPECT_EQ(sync.size(), 0u);

  ScanOdometrySync no_wait(0.0);
  no_wait.Push(ScanAt(10.0, 0.1), Eigen::Isometry3d::Identity(), 0.0);
  EXPECT_EQ(no_wait.Release(0.0, 0.0).size(), 1u);
}

// A robot turning on the spot at 40 deg/s in an 8 x 5 m room, scanned over a 0.1 s sweep (each
// point fired at the time the beam passed its azimuth). Returns the worst angle between a mapped
// wall plane and the true wall it lies on, after one keyframe, when odometry reached `odom_until`
// (seconds after the scan's first firing) before the scan was added.
double WorstWallAngleDeg(double odom_until, bool through_sync) {
  std::mt19937 rng(11);
  const PointList world = testing::PolygonRoom({{0, 0}, {8, 0}, {8, 5}, {0, 5}}, 0.05, 0.005, rng);
  constexpr double kRate = 40.0 * M_PI / 180.0, kStamp = 100.0, kSweep = 0.1;
  const auto pose = [&](double t) {
    Eigen::Isometry3d p = Eigen::Isometry3d::Identity();
    p.translation() = Eigen::Vector3d(3.0, 2.5, 0.5);
    p.linear() =
        Eigen::AngleAxisd(kRate * (t - kStamp), Eigen::Vector3d::UnitZ()).toRotationMatrix();
    return p;
  };
  Scan scan;
  scan.stamp = kStamp;
  scan.frame_id = "velodyne";
  for (const auto& w : world) {
    const Eigen::Vector3d at_start = pose(kStamp).inverse() * w.cast<double>();
    double azimuth = std::atan2(at_start.y(), at_start.x());
    if (azimuth < 0) azimuth += 2 * M_PI;
    const double tau = kSweep * azimuth / (2 * M_PI);
    const Eigen::Vector3d q = pose(kStamp + tau).inverse() * w.cast<double>();
    if (std::abs(q.z()) > 0.4 * q.head<2>().norm()) continue;
    ScanPoint p;
    p.x = static_cast<float>(q.x()), p.y = static_cast<float>(q.y()),
    p.z = static_cast<float>(q.z());
    p.time = static_cast<float>(tau);
    scan.points.push_back(p);
  }
  SGraphBuilder builder{FrontendConfig{}, BackendConfig{}};
  ScanOdometrySync sync(0.5);
  // Odometry at 50 Hz from 0.5 s before the scan; the cloud arrives with the one at kStamp.
  const auto odom_at = [&](int i) { return kStamp - 0.5 + 0.02 * i; };
  const int first = 25, last = 25 + static_cast<int>(std::lround(odom_until / 0.02));
  for (int i = 0; i <= last; ++i) {
    builder.AddOdometry(odom_at(i), pose(odom_at(i)));
    if (i == first && through_sync) sync.Push(scan, Eigen::Isometry3d::Identity(), 0.0);
    for (auto& ready : sync.Release(odom_at(i), 0.0))
      builder.AddScan(ready.scan, ready.base_T_sensor);
  }
  if (through_sync && sync.size() > 0) return -1.0;  // never released
  if (!through_sync) builder.AddScan(scan, Eigen::Isometry3d::Identity());
  const SGraph graph = builder.Snapshot();
  double worst = 0.0;
  int walls = 0;
  for (const auto& p : graph.planes) {
    const Eigen::Vector3d& n = p.plane.normal;
    if (std::abs(n.z()) > 0.5) continue;
    ++walls;
    // The true walls are axis-aligned: the angle to the nearest axis.
    const double off = std::abs(std::remainder(std::atan2(n.y(), n.x()), M_PI / 2));
    worst = std::max(worst, off * 180.0 / M_PI);
  }
  return walls >= 3 ? worst : -1.0;
}

TEST(ScanOdometrySync, ATurningScanNeedsTheOdometryOfItsWholeSweep) {
  // Odometry only up to the first firing: the rest of the sweep is deskewed with the pose held
  // (FrontendConfig::max_odom_extrapolation) and the walls come out rotated.
  const double held = WorstWallAngleDeg(0.0, false);
  // The cloud held until odometry passed its last firing: deskewed properly.
  const double synced = WorstWallAngleDeg(0.12, true);
  const double in_order = WorstWallAngleDeg(0.12, false);
  std::printf("worst wall angle: odometry held %.2f deg, synced %.2f deg, in order %.2f deg\n",
              held, synced, in_order);
  ASSERT_GE(held, 0.0);
  ASSERT_GE(synced, 0.0);
  EXPECT_GT(held, 1.0);
  EXPECT_LT(synced, 0.3);
  EXPECT_NEAR(synced, in_order, 1e-9);
}

}  // namespace
}  // namespace sgraph
}  // namespace is_graphs
