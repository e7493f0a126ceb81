// Glass in the scan simulator (scene.glass): a pane across a box room, a robot standing before
// it. Off: the pane is a wall. On: beams pass it to the wall behind, except near-normal ones that
// return off the pane with the configured probability; the same seed gives the same scan; the
// YAML keys and their bad values.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "is_graphs/geometry/triangle_mesh.h"
#include "is_graphs/sim/embree_scene.h"
#include "is_graphs/sim/scan_simulator.h"
#include "is_graphs/sim/scenario_yaml.h"
#include "sim_test_helpers.h"

namespace is_graphs {
namespace sim {
namespace {

constexpr double kSx = 10.0, kSy = 8.0, kSz = 3.0, kPaneX = 5.0;

struct GlassWorld {
  explicit GlassWorld(const GlassConfig& glass) : mesh(testing::BoxRoom(kSx, kSy, kSz)) {
    mesh.glass.assign(mesh.size(), 0);
    // A pane 2 cm thick across the room at x = 5, touching no wall (a beam passing it next to
    // a solid would go on inside that solid).
    mesh.AddBox({kPaneX, 0.5 * kSy}, 0.3, {0.02, kSy - 1.0, kSz - 0.6}, 0.0, 0.1f);
    mesh.glass.resize(mesh.size(), 1);
    embree = std::move(EmbreeScene::Create(mesh)).value();
    TrajectoryConfig tc;
    tc.pause = 0.0;
    tc.waypoints = {{}};  // validation only
    Trajectory trajectory = std::move(Trajectory::Build({2.0, 4.0, 0.0}, {}, tc, 2.0)).value();
    motion = std::make_unique<RobotMotion>(std::move(trajectory), GaitConfig{}, 0.0);
    base_T_velodyne.translation() = ScenarioConfig().velodyne_offset;
    const ScenarioConfig defaults;
    simulator =
        std::make_unique<ScanSimulator>(*embree, mesh, model, *motion, base_T_velodyne,
                                        BodyBox{defaults.body_center, defaults.body_size}, 7);
    simulator->SetGlass(glass);
  }
  // (points on the pane, points on the far wall seen through the pane's area, those of them
  // within 14 deg of the pane's normal: the sensor's gait sway is under a degree)
  std::array<int, 3> Count(const LidarScan& scan) const {
    std::array<int, 3> n{0, 0, 0};
    for (const LidarPoint& p : scan.points) {
      const Eigen::Vector3d q =
          motion->BasePose(scan.stamp + p.time) * base_T_velodyne * Eigen::Vector3d(p.x, p.y, p.z);
      if (std::abs(q.x() - kPaneX) < 0.06 && q.y() > 0.6 && q.y() < kSy - 0.6 && q.z() > 0.4 &&
          q.z() < kSz - 0.4)
        ++n[0];
      if (q.x() > kSx - 0.1 && q.y() > 1.0 && q.y() < kSy - 1.0) {  // its ray crossed the pane
        ++n[1];
        const Eigen::Vector3d d = Eigen::Vector3d(p.x, p.y, p.z).normalized();
        if (std::abs(d.x()) > std::cos(14.0 * M_PI / 180.0)) ++n[2];
      }
    }
    return n;
  }
  SceneMesh mesh;
  LidarModel model{LidarConfig{}};
  std::unique_ptr<EmbreeScene> embree;
  std::unique_ptr<RobotMotion> motion;
  Eigen::Isometry3d base_T_velodyne{Eigen::Isometry3d::Identity()};
  std::unique_ptr<ScanSimulator> simulator;
};

GlassConfig On(double return_probability) {
  GlassConfig g;
  g.enabled = true;
  g.return_probability = return_probability;
  return g;
}

TEST(SimGlass, OffThePaneIsAWall) {
  GlassWorld world{GlassConfig{}};
  const auto n = world.Count(world.simulator->Simulate(0, 0.5));
  EXPECT_GT(n[0], 1000);
  EXPECT_EQ(n[1], 0) << "points on the far wall behind an opaque pane";
}

TEST(SimGlass, BeamsPassThePaneToTheWallBehind) {
  GlassWorld world{On(0.0)};
  const LidarScan scan = world.simulator->Simulate(0, 0.5);
  const auto n = world.Count(scan);
  EXPECT_EQ(n[0], 0) << "returns off a pane that returns nothing";
  EXPECT_GT(n[1], 500);
  // The wall behind the pane where it is: the distance counts from the sensor, across the pane.
  for (const LidarPoint& p : scan.points) {
    const Eigen::Vector3d q = world.motion->BasePose(scan.stamp + p.time) * world.base_T_velodyne *
                              Eigen::Vector3d(p.x, p.y, p.z);
    if (q.x() > kPaneX + 0.06) {
      EXPECT_LT(testing::DistanceToBoxRoom(q, kSx, kSy, kSz), 0.1) << q.transpose();
    }
  }
}

TEST(SimGlass, NearNormalBeamsReturnOffThePane) {
  GlassWorld always{On(1.0)};
  const auto n = always.Count(always.simulator->Simulate(0, 0.5));
  EXPECT_GT(n[0], 50) << "near-normal returns off the pane";
  EXPECT_EQ(n[2], 0) << "a near-normal beam passed a pane that returns every one";
  EXPECT_GT(n[1], 500) << "oblique beams pass";
  GlassWorld some{On(0.3)};
  const auto m = some.Count(some.simulator->Simulate(0, 0.5));
  EXPECT_GT(m[0], 0);
  EXPECT_LT(m[0], n[0]);
  EXPECT_GT(m[2], 0);
}

TEST(SimGlass, SameSeedSameScan) {
  GlassWorld a{On(0.3)}, b{On(0.3)};
  const LidarScan sa = a.simulator->Simulate(3, 0.5), sb = b.simulator->Simulate(3, 0.5);
  ASSERT_EQ(sa.points.size(), sb.points.size());
  for (std::size_t i = 0; i < sa.points.size(); ++i) {
    ASSERT_EQ(sa.points[i].x, sb.points[i].x) << i;
    ASSERT_EQ(sa.points[i].y, sb.points[i].y) << i;
  }
}

TEST(SimGlass, TheSceneMarksTheGlassClassesTriangles) {
  const std::string obj =
      "o IfcWall#1\nv 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 2 3\n"
      "o IfcWindow#2\nv 0 1 0\nv 1 1 0\nv 0 1 1\nf 4 5 6\n"
      "o IfcWindowStandardCase#3\nv 0 2 0\nv 1 2 0\nv 0 2 1\nf 7 8 9\n";
  SceneConfig config;
  auto scene = testing::SceneOfObj(obj, config);
  ASSERT_TRUE(scene.ok()) << scene.error();
  EXPECT_TRUE(scene.value().glass.empty()) << "glass off: no flags";
  config.glass.enabled = true;
  config.clutter.push_back({});
  config.clutter.back().position = Eigen::Vector2d(3.0, 3.0);
  scene = testing::SceneOfObj(obj, config);
  ASSERT_TRUE(scene.ok()) << scene.error();
  const auto& glass = scene.value().glass;
  ASSERT_EQ(glass.size(), scene.value().size());
  EXPECT_EQ(glass[0], 0);
  EXPECT_EQ(glass[1], 1);
  EXPECT_EQ(glass[2], 1);
  for (std::size_t t = 3; t < glass.size(); ++t) EXPECT_EQ(glass[t], 0) << "clutter";
  config.glass.classes = {"IfcCurtainWall"};
  scene = testing::SceneOfObj(obj, config);
  ASSERT_FALSE(scene.ok());
  EXPECT_NE(scene.error().find("scene.glass.classes: no object of IfcCurtainWall"),
            std::string::npos)
      << scene.error();
}

const char* kBase = R"(
building: bim/office.ifc
trajectory: {rooms: [Corridor]}
)";

TEST(SimGlass, YamlKeysAndBadValues) {
  auto r = ParseScenarioYaml(kBase, "s.yaml", "/repo");
  ASSERT_TRUE(r.ok()) << r.error();
  EXPECT_FALSE(r.value().scene.glass.enabled);
  r = ParseScenarioYaml(std::string(kBase) + "scene: {glass: {}}\n", "s.yaml", "/repo");
  ASSERT_TRUE(r.ok()) << r.error();
  EXPECT_TRUE(r.value().scene.glass.enabled);
  EXPECT_TRUE(r.value().scene.glass.IsGlass("IfcWindowStandardCase"));
  EXPECT_FALSE(r.value().scene.glass.IsGlass("IfcWall"));
  r = ParseScenarioYaml(
      std::string(kBase) + "scene: {glass: {classes: [IfcPlate], return_probability: 0.1}}\n",
      "s.yaml", "/repo");
  ASSERT_TRUE(r.ok()) << r.error();
  EXPECT_EQ(r.value().scene.glass.classes, std::vector<std::string>{"IfcPlate"});
  EXPECT_EQ(r.value().scene.glass.return_probability, 0.1);
  for (const auto& [bad, field] : std::vector<std::pair<std::string, std::string>>{
           {"{return_probability: 1.5}", "scene.glass.return_probability"},
           {"{return_max_angle_deg: -1}", "scene.glass.return_max_angle_deg"},
           {"{max_layers: 0}", "scene.glass.max_layers"},
           {"{classes: []}", "scene.glass.classes"},
           {"{transmission: 0.5}", "transmission"},
           {"true", "scene.glass"}}) {
    r = ParseScenarioYaml(std::string(kBase) + "scene: {glass: " + bad + "}\n", "s.yaml", "/repo");
    ASSERT_FALSE(r.ok()) << bad;
    EXPECT_NE(r.error().find(field), std::string::npos) << bad << ": " << r.error();
  }
}

}  // namespace
}  // namespace sim
}  // namespace is_graphs
