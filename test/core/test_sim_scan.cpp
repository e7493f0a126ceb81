// The VLP-16 scan simulator on a synthetic box room: field layout (ring, time), points on the
// surfaces within the configured noise, self-filter, motion distortion, determinism.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numeric>

#include "is_graphs/sim/embree_scene.h"
#include "is_graphs/sim/scan_simulator.h"
#include "sim_test_helpers.h"

namespace is_graphs {
namespace sim {
namespace {

constexpr double kSx = 10.0, kSy = 8.0, kSz = 3.0;

struct World {
  explicit World(const std::vector<PlanarWaypoint>& waypoints, double speed = 0.8,
                 LidarConfig sensor = {}, GaitConfig gait = {})
      : mesh(testing::BoxRoom(kSx, kSy, kSz)), model(sensor) {
    embree = std::move(EmbreeScene::Create(mesh)).value();
    TrajectoryConfig tc;
    tc.speed = speed;
    tc.pause = 0.0;
    tc.waypoints = {{}};  // validation only
    Trajectory trajectory =
        std::move(Trajectory::Build({2.0, 4.0, 0.0}, waypoints, tc, 5.0)).value();
    motion = std::make_unique<RobotMotion>(std::move(trajectory), gait, 0.0);
    base_T_velodyne.translation() = ScenarioConfig().velodyne_offset;
    const ScenarioConfig defaults;
    simulator =
        std::make_unique<ScanSimulator>(*embree, mesh, model, *motion, base_T_velodyne,
                                        BodyBox{defaults.body_center, defaults.body_size}, 42);
  }
  // A point of scan `scan` in bim, through the sensor pose at the point's own time.
  Eigen::Vector3d InBim(const LidarScan& scan, const LidarPoint& p) const {
    return motion->BasePose(scan.stamp + p.time) * base_T_velodyne * Eigen::Vector3d(p.x, p.y, p.z);
  }
  SceneMesh mesh;
  LidarModel model;
  std::unique_ptr<EmbreeScene> embree;
  std::unique_ptr<RobotMotion> motion;
  Eigen::Isometry3d base_T_velodyne{Eigen::Isometry3d::Identity()};
  std::unique_ptr<ScanSimulator> simulator;
};

TEST(SimScan, RingsAndTimesFollowTheVlp16Layout) {
  World world({});  // standing still
  const LidarScan scan = world.simulator->Simulate(0, 1.0);
  ASSERT_GT(scan.points.size(), 15000u);
  std::vector<int> per_ring(16, 0);
  float last_time = -1.0f;
  for (const LidarPoint& p : scan.points) {
    ASSERT_LT(p.ring, 16);
    ++per_ring[p.ring];
    // Elevation of the point = the ring's beam angle (-15 + 2 ring degrees).
    const double elevation = std::atan2(p.z, std::hypot(p.x, p.y)) * 180.0 / M_PI;
    EXPECT_NEAR(elevation, -15.0 + 2.0 * p.ring, 0.01);
    // Time: within the scan, in firing order, and matching the (clockwise) azimuth.
    EXPECT_GE(p.time, 0.0f);
    EXPECT_LT(p.time, 0.1f);
    EXPECT_GE(p.time, last_time);
    last_time = p.time;
    double azimuth = -std::atan2(p.y, p.x);
    if (azimuth < 0.0) azimuth += 2.0 * M_PI;
    const double expected = azimuth / (2.0 * M_PI) * 0.1;
    const double diff = std::abs(p.time - expected);
    EXPECT_LT(std::min(diff, 0.1 - diff), 1e-4) << "azimuth " << azimuth;
  }
  // The upper rings see the room all around; the lowest ones lose the directions the body
  // hides.
  for (int ring = 8; ring < 16; ++ring) EXPECT_EQ(per_ring[ring], 1800) << "ring " << ring;
  EXPECT_GT(per_ring[0], 0);
  EXPECT_LT(per_ring[0], 1800);
}

TEST(SimScan, PointsLieOnTheSurfacesWithinTheNoise) {
  // Walking at up to 1 m/s with the gait sway: for each point, the sensor pose at the point's
  // own time gives the true range along its beam to the room's surfaces; the measured ranges
  // differ from it by the configured Gaussian noise (mean 0, standard deviation sigma).
  LidarConfig sensor;
  sensor.range_noise_stddev = 0.015;
  World world({{{8.0, 4.0}, std::nullopt, false}}, 1.0, sensor);
  const Eigen::Array3d lo(0.0, 0.0, 0.0), hi(kSx, kSy, kSz);
  double sum = 0.0, sum2 = 0.0, sum2_start_pose = 0.0;
  std::size_t n = 0, far = 0;
  for (int k = 5; k < 15; ++k) {
    const LidarScan scan = world.simulator->Simulate(k, 0.1 * k);
    const Eigen::Isometry3d start = world.motion->BasePose(scan.stamp) * world.base_T_velodyne;
    for (const LidarPoint& p : scan.points) {
      const Eigen::Vector3d v(p.x, p.y, p.z);
      const Eigen::Isometry3d pose =
          world.motion->BasePose(scan.stamp + p.time) * world.base_T_velodyne;
      const Eigen::Array3d o = pose.translation().array();
      const Eigen::Array3d d = (pose.linear() * v.normalized()).array();
      double true_range = std::numeric_limits<double>::infinity();
      for (int a = 0; a < 3; ++a) {
        if (std::abs(d[a]) > 1e-12) {
          true_range = std::min(true_range, ((d[a] > 0 ? hi[a] : lo[a]) - o[a]) / d[a]);
        }
      }
      const double residual = v.norm() - true_range;
      if (std::abs(residual) > 6 * sensor.range_noise_stddev) ++far;
      sum += residual;
      sum2 += residual * residual;
      ++n;
      const double e = testing::DistanceToBoxRoom(start * v, kSx, kSy, kSz);
      sum2_start_pose += e * e;
    }
  }
  ASSERT_GT(n, 100000u);
  const double mean = sum / n;
  const double stddev = std::sqrt(sum2 / n - mean * mean);
  EXPECT_EQ(far, 0u);
  EXPECT_NEAR(mean, 0.0, 5e-4);                                  // std error ~0.04 mm
  EXPECT_NEAR(stddev, sensor.range_noise_stddev, 0.03 * 0.015);  // 2 mm quantization included
  // Motion distortion is in the data: one pose per scan explains the points worse.
  EXPECT_GT(std::sqrt(sum2_start_pose / n), 1.3 * stddev);
}

TEST(SimScan, NoiseFreeRangesAreExact) {
  LidarConfig sensor;
  sensor.range_noise_stddev = 0.0;
  sensor.range_resolution = 0.0;
  GaitConfig still;
  still.bob_amplitude = still.roll_amplitude_deg = still.pitch_amplitude_deg = 0.0;
  World world({{{8.0, 4.0}, std::nullopt, false}}, 1.0, sensor, still);
  const LidarScan scan = world.simulator->Simulate(7, 0.7);
  double worst = 0.0;
  for (const LidarPoint& p : scan.points) {
    worst = std::max(worst, testing::DistanceToBoxRoom(world.InBim(scan, p), kSx, kSy, kSz));
  }
  EXPECT_LT(worst, 2e-3);  // float32 points, float rays
}

TEST(SimScan, NoReturnsFromTheBodyGrazingOrBeyondRange) {
  LidarConfig sensor;
  sensor.max_range = 5.0;
  sensor.max_incidence_deg = 70.0;
  sensor.range_noise_stddev = 0.0;
  World world({}, 0.8, sensor);
  const LidarScan scan = world.simulator->Simulate(3, 0.3);
  const ScenarioConfig defaults;
  const Eigen::Vector3d lo = defaults.body_center - 0.5 * defaults.body_size;
  const Eigen::Vector3d hi = defaults.body_center + 0.5 * defaults.body_size;
  for (const LidarPoint& p : scan.points) {
    const Eigen::Vector3d v(p.x, p.y, p.z);
    EXPECT_LE(v.norm(), 5.0 + 1e-3);
    const Eigen::Vector3d in_base = world.base_T_velodyne * v;
    EXPECT_FALSE((in_base.array() > lo.array()).all() && (in_base.array() < hi.array()).all());
  }
  // Grazing: the floor seen at more than 70 deg from its normal gives nothing, i.e. no floor
  // point farther than (sensor height) * tan(70 deg).
  const double height = 0.525 + 0.1877;
  for (const LidarPoint& p : scan.points) {
    const Eigen::Vector3d q = world.InBim(scan, p);
    const bool on_floor =
        q.z() < 0.05 && q.x() > 0.2 && q.x() < kSx - 0.2 && q.y() > 0.2 && q.y() < kSy - 0.2;
    if (on_floor) {
      EXPECT_LT(std::hypot(q.x() - 2.1, q.y() - 4.0), height * std::tan(70.0 * M_PI / 180.0) + 0.1);
    }
  }
  EXPECT_GT(world.simulator->MaskedFraction(), 0.05);
  EXPECT_LT(world.simulator->MaskedFraction(), 0.2);
}

TEST(SimScan, SameSeedSameScanOtherIndexOtherNoise) {
  World a({{{8.0, 4.0}, std::nullopt, false}});
  World b({{{8.0, 4.0}, std::nullopt, false}});
  const LidarScan sa = a.simulator->Simulate(4, 0.4);
  const LidarScan sb = b.simulator->Simulate(4, 0.4);
  ASSERT_EQ(sa.points.size(), sb.points.size());
  for (std::size_t i = 0; i < sa.points.size(); ++i) {
    ASSERT_TRUE(testing::SamePoint(sa.points[i], sb.points[i])) << i;
  }
  const LidarScan other = a.simulator->Simulate(5, 0.4);  // same pose, other noise stream
  std::size_t same = 0;
  for (std::size_t i = 0; i < std::min(sa.points.size(), other.points.size()); ++i) {
    same += sa.points[i].x == other.points[i].x ? 1 : 0;
  }
  EXPECT_LT(same, sa.points.size() / 2);
}

}  // namespace
}  // namespace sim
}  // namespace is_graphs
