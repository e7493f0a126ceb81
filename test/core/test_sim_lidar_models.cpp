// The simulator's LiDAR models beyond the VLP-16 (issue 23): the OS1-64's and the XT32's beams,
// rings and per-point times as their drivers give them, the Ouster's point frame (os_lidar,
// turned half a turn on its mount), the model defaults and their YAML.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "is_graphs/sim/embree_scene.h"
#include "is_graphs/sim/scan_simulator.h"
#include "is_graphs/sim/scenario_yaml.h"
#include "sim_test_helpers.h"

namespace is_graphs {
namespace sim {
namespace {

constexpr double kSx = 10.0, kSy = 8.0, kSz = 3.0;

// A noise-free model of `kind` on a robot standing at (2, 4) in a box room, yawed 0.3 rad.
struct StandingLidar {
  explicit StandingLidar(LidarModelKind kind)
      : mesh(testing::BoxRoom(kSx, kSy, kSz)), model(NoiseFree(kind)) {
    embree = std::move(EmbreeScene::Create(mesh)).value();
    TrajectoryConfig tc;
    tc.pause = 0.0;
    tc.waypoints = {{}};  // validation only
    Trajectory trajectory = std::move(Trajectory::Build({2.0, 4.0, 0.3}, {}, tc, 1.0)).value();
    motion = std::make_unique<RobotMotion>(std::move(trajectory), GaitConfig{}, 0.0);
    base_T_mount.translation() = ScenarioConfig().velodyne_offset;
    base_T_sensor = base_T_mount * model.spec().mount_T_points;
    const ScenarioConfig defaults;
    simulator =
        std::make_unique<ScanSimulator>(*embree, mesh, model, *motion, base_T_sensor,
                                        BodyBox{defaults.body_center, defaults.body_size}, 7);
    scan = simulator->Simulate(0, 0.5);
  }
  static LidarConfig NoiseFree(LidarModelKind kind) {
    LidarConfig c = LidarConfig::For(kind);
    c.range_noise_stddev = 0.0;
    c.range_resolution = 0.0;
    return c;
  }
  // Largest distance of the scan's points to the room's surfaces, through base <- `frame`.
  double WorstDistance(const Eigen::Isometry3d& base_T_frame) const {
    double worst = 0.0;
    for (const LidarPoint& p : scan.points) {
      const Eigen::Vector3d q =
          motion->BasePose(scan.stamp + p.time) * base_T_frame * Eigen::Vector3d(p.x, p.y, p.z);
      worst = std::max(worst, testing::DistanceToBoxRoom(q, kSx, kSy, kSz));
    }
    return worst;
  }
  SceneMesh mesh;
  LidarModel model;
  std::unique_ptr<EmbreeScene> embree;
  std::unique_ptr<RobotMotion> motion;
  Eigen::Isometry3d base_T_mount{Eigen::Isometry3d::Identity()};
  Eigen::Isometry3d base_T_sensor{Eigen::Isometry3d::Identity()};
  std::unique_ptr<ScanSimulator> simulator;
  LidarScan scan;
};

double ElevationDeg(const LidarPoint& p) {
  return std::atan2(p.z, std::hypot(p.x, p.y)) * 180.0 / M_PI;
}

TEST(SimLidarModels, Os1_64HasSixtyFourRowsOfTenTwentyFourColumnsFiredAtOnce) {
  StandingLidar lidar(LidarModelKind::kOs1_64);
  EXPECT_EQ(lidar.model.Lasers(), 64);
  EXPECT_EQ(lidar.model.FiringsPerScan(), 1024);
  ASSERT_GT(lidar.scan.points.size(), 50000u);  // 65536 beams, the body hides some
  std::set<int> rings;
  for (const LidarPoint& p : lidar.scan.points) {
    ASSERT_LT(p.ring, 64);
    ASSERT_LT(p.column, 1024u);
    rings.insert(p.ring);
    // ouster-ros: row (ring) 0 is the highest beam, +22.5 deg, down to -22.5 deg.
    EXPECT_NEAR(ElevationDeg(p), 22.5 - 45.0 * p.ring / 63.0, 0.01);
    // Every beam of a column at once, the column's time after the scan start.
    EXPECT_NEAR(p.time, p.column * 0.1 / 1024.0, 1e-7);
  }
  EXPECT_EQ(rings.size(), 64u);
}

TEST(SimLidarModels, Os1_64PointsAreInTheOsLidarFrame) {
  // ouster-ros' points are in os_lidar: half a turn about z and 36.18 mm above os_sensor.
  StandingLidar lidar(LidarModelKind::kOs1_64);
  const Eigen::Isometry3d& mount_T_points = lidar.model.spec().mount_T_points;
  EXPECT_NEAR(mount_T_points.translation().z(), 0.03618, 1e-9);
  EXPECT_TRUE(mount_T_points.linear().isApprox(
      Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitZ()).toRotationMatrix(), 1e-12));
  EXPECT_LT(lidar.WorstDistance(lidar.base_T_sensor), 2e-3);
  EXPECT_GT(lidar.WorstDistance(lidar.base_T_mount), 0.5);  // read as os_sensor: off the walls
}

TEST(SimLidarModels, HesaiXt32ChannelsFireOneAfterTheOther) {
  StandingLidar lidar(LidarModelKind::kHesaiXt32);
  EXPECT_EQ(lidar.model.Lasers(), 32);
  EXPECT_EQ(lidar.model.FiringsPerScan(), 2000);  // 0.18 deg at 10 Hz
  ASSERT_GT(lidar.scan.points.size(), 50000u);
  std::set<int> rings;
  for (const LidarPoint& p : lidar.scan.points) {
    ASSERT_LT(p.ring, 32);
    rings.insert(p.ring);
    EXPECT_NEAR(ElevationDeg(p), 15.0 - p.ring, 0.01);  // channel 0 at +15, 31 at -16 deg
    EXPECT_NEAR(p.time, p.column * 0.1 / 2000.0 + p.ring * 1.512e-6, 1e-7);
  }
  EXPECT_EQ(rings.size(), 32u);
  EXPECT_LT(lidar.WorstDistance(lidar.base_T_sensor), 2e-3);
  EXPECT_TRUE(lidar.base_T_sensor.isApprox(lidar.base_T_mount));
}

TEST(SimLidarModels, Vlp16DefaultsAreTheConfigDefaults) {
  // The VLP-16 stays the default: LidarConfig::For(vlp16) is the default config (the existing
  // scenarios' bags do not change).
  const LidarConfig a = LidarConfig::For(LidarModelKind::kVlp16), b;
  EXPECT_EQ(a.model, b.model);
  EXPECT_EQ(a.azimuth_resolution_deg, b.azimuth_resolution_deg);
  EXPECT_EQ(a.min_range, b.min_range);
  EXPECT_EQ(a.max_range, b.max_range);
  EXPECT_EQ(a.range_noise_stddev, b.range_noise_stddev);
  EXPECT_EQ(a.range_resolution, b.range_resolution);
  EXPECT_EQ(a.intensity_noise_stddev, b.intensity_noise_stddev);
  EXPECT_EQ(LidarModel(b).Lasers(), 16);
  EXPECT_TRUE(LidarModel(b).spec().mount_T_points.isApprox(Eigen::Isometry3d::Identity()));
}

const char* kBase = R"(
building: bim/office.ifc
trajectory: {rooms: [Corridor]}
)";

TEST(SimLidarModels, YamlModelGivesItsDefaultsThenTheKeys) {
  auto r =
      ParseScenarioYaml(std::string(kBase) + "sensor: {model: os1_64, range_noise_stddev: 0.02}\n",
                        "s.yaml", "/repo");
  ASSERT_TRUE(r.ok()) << r.error();
  EXPECT_EQ(r.value().sensor.model, LidarModelKind::kOs1_64);
  EXPECT_EQ(r.value().sensor.range_noise_stddev, 0.02);  // the key
  EXPECT_EQ(r.value().sensor.range_resolution, 0.001);   // the model's
  EXPECT_EQ(r.value().sensor.min_range, 0.5);
  r = ParseScenarioYaml(std::string(kBase) + "sensor: {model: hesai_xt32}\n", "s.yaml", "/repo");
  ASSERT_TRUE(r.ok()) << r.error();
  EXPECT_EQ(r.value().sensor.azimuth_resolution_deg, 0.18);
  EXPECT_EQ(r.value().sensor.range_resolution, 0.004);
  r = ParseScenarioYaml(kBase, "s.yaml", "/repo");
  ASSERT_TRUE(r.ok()) << r.error();
  EXPECT_EQ(r.value().sensor.model, LidarModelKind::kVlp16);
}

TEST(SimLidarModels, YamlErrorsNameTheField) {
  auto r = ParseScenarioYaml(std::string(kBase) + "sensor: {model: vlp32}\n", "s.yaml", "/repo");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("sensor.model: unknown model 'vlp32'"), std::string::npos) << r.error();
  r = ParseScenarioYaml(
      std::string(kBase) + "sensor: {model: os1_64, azimuth_resolution_deg: 0.2}\n", "s.yaml",
      "/repo");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("sensor.azimuth_resolution_deg: an OS1 runs 512, 1024 or 2048"),
            std::string::npos)
      << r.error();
}

}  // namespace
}  // namespace sim
}  // namespace is_graphs
