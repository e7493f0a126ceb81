// The whole simulation on the project's office building (bim/office.ifc through the converter):
// scene with clutter and deviations, route, determinism of scans and odometry.
#include <gtest/gtest.h>

#include <fstream>

#include "is_graphs/sim/scenario_yaml.h"
#include "is_graphs/sim/simulation.h"
#include "sim_office_helpers.h"
#include "sim_test_helpers.h"

namespace is_graphs {
namespace sim {
namespace {

const std::string& kRoot = testing::kSourceRoot;

using testing::HaveConverter;
using testing::Prepare;

const char* kScenario = R"(
building: bim/office.ifc
seed: 11
duration: 8
trajectory: {rooms: [Corridor, "102"], speed: 1.0, pause: 0.2}
odometry: {scale_error: 0.02, translation_random_walk: 0.01, yaw_random_walk: 0.002}
scene:
  deviations: [{type: move_wall, wall: p_s2, offset: 0.2}, {type: remove_wall, wall: p_n3}]
  clutter: [{type: pallet, room: "111"}, {type: person, position: [12.0, 2.0]}]
  random_clutter: {count: 6}
)";

TEST(SimPipeline, SameScenarioSameOutput) {
  if (!HaveConverter()) GTEST_SKIP() << "bim/office.ifc or the converter's venv is missing";
  const auto a = Prepare(kScenario);
  const auto b = Prepare(kScenario);
  ASSERT_TRUE(a && b);
  EXPECT_EQ(a->scene.triangles.size(), b->scene.triangles.size());
  EXPECT_EQ(a->NumScans(), 80);
  for (int k : {0, 37, 79}) {
    const LidarScan sa = a->scans->Simulate(k, 0.1 * k);
    const LidarScan sb = b->scans->Simulate(k, 0.1 * k);
    ASSERT_EQ(sa.points.size(), sb.points.size());
    ASSERT_GT(sa.points.size(), 10000u);
    EXPECT_TRUE(testing::SameScan(sa, sb)) << "scan " << k;
  }
  OdometryDrift oa = a->MakeOdometry(), ob = b->MakeOdometry();
  for (int i = 0; i <= 400; ++i) {
    const double t = i / 50.0;
    const OdometrySample x = oa.Step(t, a->motion->BasePose(t));
    const OdometrySample y = ob.Step(t, b->motion->BasePose(t));
    ASSERT_TRUE(x.odom_T_base.isApprox(y.odom_T_base, 0.0)) << t;
  }
}

TEST(SimPipeline, DeviationsChangeTheSceneNotTheAGraph) {
  if (!HaveConverter()) GTEST_SKIP() << "bim/office.ifc or the converter's venv is missing";
  const auto planned = Prepare("building: bim/office.ifc\ntrajectory: {rooms: [Corridor]}\n");
  const auto built = Prepare(kScenario);
  ASSERT_TRUE(planned && built);
  EXPECT_EQ(planned->graph.walls.size(), built->graph.walls.size());
  EXPECT_NE(planned->scene.triangles.size(), built->scene.triangles.size());
  EXPECT_NEAR(built->floor_z, 0.0, 0.05);
  // Doors are dropped: a horizontal ray through the middle of a doorway passes.
  const agraph::Doorway& door = planned->graph.doorways[0];
  const agraph::Wall& wall = planned->graph.walls[door.wall];
  const Eigen::Vector3d n = planned->graph.surfaces[wall.surface_a].plane.normal;
  const Eigen::Vector3d from = door.position + Eigen::Vector3d(0, 0, 1.0) - 0.5 * n;
  const RayHit hit = planned->embree->Intersect(Ray{from.cast<float>(), n.cast<float>(), 1.0f});
  EXPECT_LT(hit.triangle, 0);
}

// close_doorway: the opening filled across its width, the wall's thickness, to the ceiling; the
// A-Graph keeps the doorway. A doorway that is not there is an error naming the field.
TEST(SimPipeline, AClosedDoorwayIsFilled) {
  if (!HaveConverter()) GTEST_SKIP() << "bim/office.ifc or the converter's venv is missing";
  const auto built = Prepare(
      "building: bim/office.ifc\ntrajectory: {rooms: [Corridor]}\n"
      "scene: {deviations: [{type: close_doorway, doorway: 0}]}\n");
  ASSERT_TRUE(built);
  const agraph::Doorway& door = built->graph.doorways[0];
  const agraph::Wall& wall = built->graph.walls[door.wall];
  const Eigen::Vector3d n = built->graph.surfaces[wall.surface_a].plane.normal;
  for (double z : {0.3, 1.0, 2.2}) {
    const Eigen::Vector3d from = door.position + Eigen::Vector3d(0, 0, z) - 0.5 * n;
    const RayHit hit = built->embree->Intersect(Ray{from.cast<float>(), n.cast<float>(), 1.0f});
    EXPECT_GE(hit.triangle, 0) << z;
    EXPECT_NEAR(hit.distance, 0.5 - 0.5 * std::max(wall.thickness, 0.05), 0.03) << z;
  }
  const Result<ScenarioConfig> c = ParseScenarioYaml(
      "building: bim/office.ifc\ntrajectory: {rooms: [Corridor]}\n"
      "scene: {deviations: [{type: close_doorway, doorway: nope}]}\n",
      "t.yaml", kRoot);
  ASSERT_TRUE(c.ok()) << c.error();
  const auto s = PrepareSimulation(c.value(), std::string(IS_GRAPHS_TEST_TMP_DIR) + "/bim_cache");
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().find("scene.deviations[0].doorway"), std::string::npos) << s.error();
}

// A wall built turned (rotate_wall): rays along its normal, 1 m either side of its centre, hit
// it nearer on one side and farther on the other by tan(angle) each; the plan's wall, level.
TEST(SimPipeline, ARotatedWallIsBuiltTurnedAboutItsCentre) {
  if (!HaveConverter()) GTEST_SKIP() << "bim/office.ifc or the converter's venv is missing";
  const auto planned = Prepare("building: bim/office.ifc\ntrajectory: {rooms: [Corridor]}\n");
  const auto built = Prepare(
      "building: bim/office.ifc\ntrajectory: {rooms: [Corridor]}\n"
      "scene: {deviations: [{type: rotate_wall, wall: p_s2, angle_deg: 10}]}\n");
  ASSERT_TRUE(planned && built);
  const agraph::AGraph& g = planned->graph;
  const auto wall = std::find_if(g.walls.begin(), g.walls.end(),
                                 [](const agraph::Wall& w) { return w.name == "p_s2"; });
  ASSERT_NE(wall, g.walls.end());
  const agraph::WallSurface& face = g.surfaces[wall->surface_a];
  const Eigen::Vector3d n = face.plane.normal, t = face.Tangent();
  const Eigen::Vector3d on_face = wall->center - (n.dot(wall->center) - face.plane.d) * n;
  auto distance = [&](const Simulation& p, double along) {
    const Eigen::Vector3d from = on_face + along * t + 0.6 * n + Eigen::Vector3d(0, 0, 1.0);
    return p.embree->Intersect(Ray{from.cast<float>(), (-n).cast<float>(), 5.0f}).distance;
  };
  EXPECT_NEAR(distance(*planned, 1.0), 0.6, 0.01);
  EXPECT_NEAR(distance(*planned, -1.0), 0.6, 0.01);
  EXPECT_NEAR(std::abs(distance(*built, 1.0) - distance(*built, -1.0)),
              2.0 * std::tan(10.0 * M_PI / 180.0), 0.03);
  EXPECT_NEAR(distance(*built, 1.0) + distance(*built, -1.0), 1.2, 0.03) << "about its centre";
}

TEST(SimPipeline, BadInputsNameTheField) {
  if (!HaveConverter()) GTEST_SKIP() << "bim/office.ifc or the converter's venv is missing";
  auto error = [](const std::string& yaml) {
    const Result<ScenarioConfig> c = ParseScenarioYaml(yaml, "t.yaml", kRoot);
    if (!c.ok()) return c.error();
    const auto s = PrepareSimulation(c.value(), std::string(IS_GRAPHS_TEST_TMP_DIR) + "/bim_cache");
    return s.ok() ? std::string() : s.error();
  };
  EXPECT_NE(error("building: bim/nope.ifc\ntrajectory: {rooms: [A]}\n").find("building:"),
            std::string::npos);
  EXPECT_NE(
      error("building: bim/office.ifc\nstorey: Roof\ntrajectory: {rooms: [A]}\n").find("storey:"),
      std::string::npos);
  EXPECT_NE(error("building: bim/office.ifc\ntrajectory: {rooms: [Corridor, Lobby]}\n")
                .find("trajectory.rooms[1]"),
            std::string::npos);
  EXPECT_NE(error("building: bim/office.ifc\ntrajectory: {rooms: [Corridor]}\n"
                  "scene: {deviations: [{type: remove_wall, wall: nope}]}\n")
                .find("scene.deviations[0].wall"),
            std::string::npos);
  // A partition across the corridor blocks the route.
  EXPECT_NE(error("building: bim/office.ifc\ntrajectory: {rooms: [Corridor, \"101\"]}\n"
                  "scene: {deviations: [{type: add_wall, start: [0.15, 6.0], end: [18, 6.0]}]}\n")
                .find("trajectory: the walk"),
            std::string::npos);
}

}  // namespace
}  // namespace sim
}  // namespace is_graphs
