// LiDAR sensor effects in the scan simulator (sensor.effects): range noise growing with range,
// mixed pixels at depth edges, dark surfaces losing far returns, multi-path ghosts below a polished
// floor. Each effect with neutral parameters gives the scan without it; each changes the scan as
// described and only where it should; the same seed gives the same scan; the YAML's bad values
// name their line and field.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "is_graphs/geometry/triangle_mesh.h"
#include "is_graphs/sim/embree_scene.h"
#include "is_graphs/sim/scan_simulator.h"
#include "is_graphs/sim/scenario_yaml.h"
#include "is_graphs/sim/sensor_effects.h"
#include "sim_test_helpers.h"

namespace is_graphs {
namespace sim {
namespace {

// A robot standing at (x0, y0) facing +x in `mesh`, its VLP-16 with `effects`.
struct World {
  World(SceneMesh m, const SensorEffectsConfig& effects, double x0 = 2.0, double y0 = 4.0)
      : mesh(std::move(m)) {
    LidarConfig lidar;
    lidar.effects = effects;
    model = std::make_unique<LidarModel>(lidar);
    embree = std::move(EmbreeScene::Create(mesh)).value();
    TrajectoryConfig tc;
    tc.pause = 0.0;
    tc.waypoints = {{}};
    Trajectory trajectory = std::move(Trajectory::Build({x0, y0, 0.0}, {}, tc, 2.0)).value();
    motion = std::make_unique<RobotMotion>(std::move(trajectory), GaitConfig{}, 0.0);
    base_T_velodyne.translation() = ScenarioConfig().velodyne_offset;
    const ScenarioConfig defaults;
    simulator =
        std::make_unique<ScanSimulator>(*embree, mesh, *model, *motion, base_T_velodyne,
                                        BodyBox{defaults.body_center, defaults.body_size}, 7);
  }
  std::vector<Eigen::Vector3d> Points(const LidarScan& scan) const {
    std::vector<Eigen::Vector3d> q;
    for (const LidarPoint& p : scan.points)
      q.push_back(motion->BasePose(scan.stamp + p.time) * base_T_velodyne *
                  Eigen::Vector3d(p.x, p.y, p.z));
    return q;
  }
  std::vector<Eigen::Vector3d> Scan(std::uint64_t index = 0) const {
    return Points(simulator->Simulate(index, 0.5));
  }
  SceneMesh mesh;
  std::unique_ptr<LidarModel> model;
  std::unique_ptr<EmbreeScene> embree;
  std::unique_ptr<RobotMotion> motion;
  Eigen::Isometry3d base_T_velodyne{Eigen::Isometry3d::Identity()};
  std::unique_ptr<ScanSimulator> simulator;
};

SceneMesh PolishedRoom(double sx, double sy, double sz) {
  SceneMesh m = testing::BoxRoom(sx, sy, sz);
  m.polished.assign(m.size(), 0);
  for (int t = 0; t < 12; ++t) m.polished[t] = 1;  // the floor box (BoxRoom's first)
  return m;
}

SensorEffectsConfig AllOn() {
  SensorEffectsConfig e;
  e.range_noise.enabled = e.mixed_pixels.enabled = e.dark_surfaces.enabled = e.ghosts.enabled =
      true;
  return e;
}

TEST(SimSensorEffects, NeutralEffectsLeaveTheScanAsWithout) {
  const SceneMesh room = PolishedRoom(10.0, 8.0, 3.0);
  const LidarScan off = World(room, {}).simulator->Simulate(2, 0.5);
  SensorEffectsConfig e;
  e.range_noise.enabled = true;  // the sensor's own sigma, flat
  e.range_noise.stddev_at_zero = LidarConfig().range_noise_stddev;
  e.range_noise.per_metre = 0.0;
  EXPECT_TRUE(testing::SameScan(off, World(room, e).simulator->Simulate(2, 0.5)));
  e = {};
  e.mixed_pixels.enabled = true;
  e.mixed_pixels.probability = 0.0;
  EXPECT_TRUE(testing::SameScan(off, World(room, e).simulator->Simulate(2, 0.5)));
  e = {};
  e.ghosts.enabled = true;
  e.ghosts.probability = 0.0;
  EXPECT_TRUE(testing::SameScan(off, World(room, e).simulator->Simulate(2, 0.5)));
  e = {};
  e.dark_surfaces.enabled = true;
  e.dark_surfaces.reference_reflectivity = 1e-9;  // everything detected
  EXPECT_TRUE(testing::SameScan(off, World(room, e).simulator->Simulate(2, 0.5)));
  EXPECT_FALSE(testing::SameScan(off, World(room, AllOn()).simulator->Simulate(2, 0.5)));
}

// Standard deviation of the x of points on the near (x = 0) and far (x = sx) walls, in a band
// straight ahead of / behind the robot.
std::pair<double, double> WallSpread(const std::vector<Eigen::Vector3d>& points, double sx) {
  double s[2] = {0, 0}, s2[2] = {0, 0};
  int n[2] = {0, 0};
  for (const Eigen::Vector3d& q : points) {
    if (std::abs(q.y() - 4.0) > 1.0 || q.z() < 0.3 || q.z() > 2.7) continue;
    const int k = q.x() < 1.0 ? 0 : q.x() > sx - 5.0 ? 1 : -1;
    if (k < 0) continue;
    const double r = k == 0 ? q.x() : q.x() - sx;
    s[k] += r;
    s2[k] += r * r;
    ++n[k];
  }
  EXPECT_GT(n[0], 50);
  EXPECT_GT(n[1], 5);
  auto sd = [&](int k) { return std::sqrt(s2[k] / n[k] - (s[k] / n[k]) * (s[k] / n[k])); };
  return {sd(0), sd(1)};
}

TEST(SimSensorEffects, RangeNoiseGrowsWithRange) {
  const double sx = 45.0;
  const SceneMesh hall = testing::BoxRoom(sx, 8.0, 3.0);
  SensorEffectsConfig e;
  e.range_noise.enabled = true;
  e.range_noise.per_metre = 0.002;
  std::vector<Eigen::Vector3d> on, off;
  for (std::uint64_t i = 0; i < 3; ++i) {
    const auto a = World(hall, e).Scan(i), b = World(hall, {}).Scan(i);
    on.insert(on.end(), a.begin(), a.end());
    off.insert(off.end(), b.begin(), b.end());
  }
  const auto [near_on, far_on] = WallSpread(on, sx);
  const auto [near_off, far_off] = WallSpread(off, sx);
  // Expected sigma: near (~2 m) 0.016 m, far (~43 m) 0.098 m; off both 0.015 m.
  EXPECT_NEAR(near_on, 0.016, 0.006);
  EXPECT_NEAR(far_on, 0.098, 0.035);
  EXPECT_GT(far_on, 3.0 * near_on);
  EXPECT_LT(far_off, 2.0 * near_off + 0.01) << "the flat noise grows with range";
  EXPECT_NEAR(RangeNoiseStddev(e.range_noise, 43.0, 1.0), 0.012 + 0.086, 1e-9);
  e.range_noise.incidence = 0.01;
  EXPECT_NEAR(RangeNoiseStddev(e.range_noise, 0.0, 0.5), 0.022, 1e-9);
}

// Points in the free space between a box's back face and the far wall, in the box's shadow.
int BetweenBoxAndWall(const std::vector<Eigen::Vector3d>& points) {
  int n = 0;
  for (const Eigen::Vector3d& q : points)
    if (q.x() > 6.7 && q.x() < 19.7 && std::abs(q.y() - 4.0) < 1.0 && q.z() > 0.1 && q.z() < 1.4)
      ++n;
  return n;
}

TEST(SimSensorEffects, MixedPixelsAtADepthEdgeNotOnAFlatWall) {
  SceneMesh hall = testing::BoxRoom(20.0, 8.0, 3.0);
  SceneMesh with_box = hall;
  with_box.AddBox({6.0, 4.0}, 0.0, {1.0, 1.0, 1.5}, 0.0, 0.5f);
  SensorEffectsConfig e;
  e.mixed_pixels.enabled = true;
  e.mixed_pixels.probability = 1.0;
  int on = 0, off = 0;
  for (std::uint64_t i = 0; i < 4; ++i) {
    on += BetweenBoxAndWall(World(with_box, e).Scan(i));
    off += BetweenBoxAndWall(World(with_box, {}).Scan(i));
  }
  EXPECT_EQ(off, 0);
  EXPECT_GT(on, 4) << "no mixed pixel at the box's edges";
  // A flat wall (and the room's continuous corners): every point on a surface.
  int stray = 0;
  for (const Eigen::Vector3d& q : World(hall, e).Scan())
    if (testing::DistanceToBoxRoom(q, 20.0, 8.0, 3.0) > 0.1) ++stray;
  EXPECT_EQ(stray, 0);
}

TEST(SimSensorEffects, DarkSurfacesLoseFarReturnsKeepNearOnes) {
  const double sx = 60.0;
  SceneMesh dark = testing::BoxRoom(sx, 8.0, 3.0);
  for (float& r : dark.reflectivity) r = 0.02f;  // reach 44.7 m head-on (10 % at 100 m)
  SensorEffectsConfig e;
  e.dark_surfaces.enabled = true;
  auto count = [&](const std::vector<Eigen::Vector3d>& points, bool far) {
    int n = 0;
    for (const Eigen::Vector3d& q : points)
      if (std::abs(q.y() - 4.0) < 3.5 && q.z() > 0.2 && q.z() < 2.8 &&
          (far ? q.x() > sx - 0.2 : q.x() < 0.2))
        ++n;
    return n;
  };
  const auto on = World(dark, e).Scan(), off = World(dark, {}).Scan();
  EXPECT_GT(count(off, true), 10);
  EXPECT_LT(count(on, true), 0.3 * count(off, true)) << "a dark wall at 58 m";
  EXPECT_EQ(count(on, false), count(off, false)) << "a dark wall at 2 m";
  EXPECT_NEAR(DetectionProbability(e.dark_surfaces, 0.1, 1.0, 100.0), 0.5, 1e-9);
  EXPECT_GT(DetectionProbability(e.dark_surfaces, 0.1, 1.0, 80.0), 0.9);
  EXPECT_LT(DetectionProbability(e.dark_surfaces, 0.1, 1.0, 125.0), 0.1);
}

TEST(SimSensorEffects, GhostsBelowAPolishedFloorOnlyWhenOn) {
  const SceneMesh room = PolishedRoom(10.0, 8.0, 3.0);
  SensorEffectsConfig e;
  e.ghosts.enabled = true;
  e.ghosts.probability = 1.0;
  auto below = [](const std::vector<Eigen::Vector3d>& points, bool mirrored) {
    int n = 0;
    for (const Eigen::Vector3d& q : points) {
      if (q.z() > -0.1) continue;
      ++n;  // a ghost is the mirror image of the room below its floor
      if (mirrored) {
        EXPECT_LT(testing::DistanceToBoxRoom({q.x(), q.y(), -q.z()}, 10.0, 8.0, 3.0), 0.1) << q;
      }
    }
    return n;
  };
  EXPECT_EQ(below(World(room, {}).Scan(), false), 0);
  EXPECT_GT(below(World(room, e).Scan(), true), 500);
  SceneMesh matt = room;
  matt.polished.clear();
  EXPECT_EQ(below(World(matt, e).Scan(), false), 0) << "ghosts off a floor that is not polished";
}

TEST(SimSensorEffects, PolishedFloorMarksSlabsNotTheSiteNorClutter) {
  const std::string obj =
      "o IfcSlab#1\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"
      "o IfcSite#2\nv 0 0 -1\nv 1 0 -1\nv 0 1 -1\nf 4 5 6\n"
      "o IfcWall#3\nv 0 0 0\nv 1 0 0\nv 0 0 1\nf 7 8 9\n";
  SceneConfig config;
  auto scene = testing::SceneOfObj(obj, config);
  ASSERT_TRUE(scene.ok()) << scene.error();
  EXPECT_TRUE(scene.value().polished.empty()) << "off: no flags";
  config.polished_floor = true;
  config.clutter.push_back({});
  config.clutter.back().position = Eigen::Vector2d(3.0, 3.0);
  scene = testing::SceneOfObj(obj, config);
  ASSERT_TRUE(scene.ok()) << scene.error();
  const auto& polished = scene.value().polished;
  ASSERT_EQ(polished.size(), scene.value().size());
  EXPECT_EQ(polished[0], 1);
  EXPECT_EQ(polished[1], 0) << "the site";
  EXPECT_EQ(polished[2], 0) << "a wall";
  for (std::size_t t = 3; t < polished.size(); ++t) EXPECT_EQ(polished[t], 0) << "clutter";
}

TEST(SimSensorEffects, SameSeedSameScan) {
  SceneMesh room = PolishedRoom(10.0, 8.0, 3.0);
  room.AddBox({6.0, 4.0}, 0.0, {1.0, 1.0, 1.5}, 0.0, 0.05f);
  const World a(room, AllOn()), b(room, AllOn());
  EXPECT_TRUE(testing::SameScan(a.simulator->Simulate(3, 0.5), b.simulator->Simulate(3, 0.5)));
  EXPECT_FALSE(testing::SameScan(a.simulator->Simulate(3, 0.5), b.simulator->Simulate(4, 0.5)));
}

const char* kBase = R"(building: bim/office.ifc
trajectory: {rooms: [Corridor]}
scene: {polished_floor: true}
sensor:
  effects:
)";

TEST(SimSensorEffects, YamlKeysAndBadValuesNameTheirLine) {
  auto r = ParseScenarioYaml(std::string(kBase) + "    mixed_pixels: {}\n    ghosts: {}\n",
                             "s.yaml", "/repo");
  ASSERT_TRUE(r.ok()) << r.error();
  const SensorEffectsConfig& e = r.value().sensor.effects;
  EXPECT_TRUE(e.mixed_pixels.enabled && e.ghosts.enabled);
  EXPECT_FALSE(e.range_noise.enabled || e.dark_surfaces.enabled);
  EXPECT_TRUE(r.value().scene.polished_floor);
  for (const auto& [bad, field] : std::vector<std::pair<std::string, std::string>>{
           {"mixed_pixels: {probability: 1.5}",
            "s.yaml:6: sensor.effects.mixed_pixels.probability"},
           {"mixed_pixels: {threshold: 0}", "s.yaml:6: sensor.effects.mixed_pixels.threshold"},
           {"range_noise: {per_metre: -0.001}", "s.yaml:6: sensor.effects.range_noise.per_metre"},
           {"dark_surfaces: {softness: 0}", "s.yaml:6: sensor.effects.dark_surfaces.softness"},
           {"ghosts: {probability: -0.1}", "s.yaml:6: sensor.effects.ghosts.probability"},
           {"ghosts: {min_incidence_deg: 95}", "s.yaml:6: sensor.effects.ghosts.min_incidence"},
           {"ghosts: true", "s.yaml:6: sensor.effects.ghosts: must be a map"},
           {"echoes: {}", "s.yaml:6: sensor.effects.echoes: unknown key"}}) {
    r = ParseScenarioYaml(std::string(kBase) + "    " + bad + "\n", "s.yaml", "/repo");
    ASSERT_FALSE(r.ok()) << bad;
    EXPECT_NE(r.error().find(field), std::string::npos) << bad << ": " << r.error();
  }
  r = ParseScenarioYaml(
      "building: bim/office.ifc\ntrajectory: {rooms: [Corridor]}\nsensor: {effects: {ghosts: "
      "{}}}\n",
      "s.yaml", "/repo");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("s.yaml:3: sensor.effects.ghosts: needs `scene.polished_floor"),
            std::string::npos)
      << r.error();
}

}  // namespace
}  // namespace sim
}  // namespace is_graphs
