// Scenario YAML parsing and validation: defaults, every error names its field.
#include <gtest/gtest.h>

#include "is_graphs/sim/scenario_yaml.h"

namespace is_graphs {
namespace sim {
namespace {

Result<ScenarioConfig> Parse(const std::string& text) {
  return ParseScenarioYaml(text, "s.yaml", "/repo");
}

void ExpectError(const std::string& text, const std::string& expected) {
  const Result<ScenarioConfig> r = Parse(text);
  ASSERT_FALSE(r.ok()) << text;
  EXPECT_NE(r.error().find(expected), std::string::npos) << r.error();
  EXPECT_EQ(r.error().rfind("s.yaml", 0), 0u) << r.error();
}

TEST(SimScenarioYaml, LocalizerStoreyEmptyMeansTheWholeBuilding) {
  const Result<ScenarioConfig> r = Parse(R"(
building: bim/office.ifc
storey: "1.OG"
localizer_storey: ""
trajectory: {rooms: [Corridor]}
)");
  ASSERT_TRUE(r.ok()) << r.error();
  ASSERT_TRUE(r.value().localizer_storey.has_value());
  EXPECT_EQ(*r.value().localizer_storey, "");
  EXPECT_EQ(r.value().storey, "1.OG");
}

TEST(SimScenarioYaml, ReadsAFullScenario) {
  const Result<ScenarioConfig> r = Parse(R"(
name: demo
building: bim/office.ifc
storey: Ground floor
seed: 7
duration: 120
trajectory:
  rooms: [Corridor, "101"]
  start: {room: Corridor}
  speed: 1.0
  loop: true
sensor: {range_noise_stddev: 0.02, max_range: 80}
gait: {bob_amplitude: 0.02}
odometry: {scale_error: 0.01, yaw_bias_per_m: 0.001, translation_random_walk: 0.01}
scene:
  drop_classes: [IfcDoor, IfcWindow]
  deviations:
    - {type: move_wall, wall: p_n1, offset: 0.1}
    - {type: remove_wall, wall: 3}
    - {type: add_wall, start: [1, 1], end: [3, 1], thickness: 0.12}
    - {type: rotate_wall, wall: p_s1, angle_deg: -12.5}
    - {type: close_doorway, doorway: D_101, height: 2.0}
  clutter:
    - {type: pallet, room: "101", offset: [0.5, 0]}
    - {type: person, position: [2, 6]}
  random_clutter: {count: 5, types: [box]}
)");
  ASSERT_TRUE(r.ok()) << r.error();
  const ScenarioConfig& c = r.value();
  EXPECT_EQ(c.name, "demo");
  EXPECT_EQ(c.base_dir, "/repo");
  EXPECT_EQ(c.storey, "Ground floor");
  EXPECT_FALSE(c.localizer_storey.has_value());  // the localizer is told `storey`
  EXPECT_EQ(c.seed, 7u);
  EXPECT_EQ(c.trajectory.rooms.size(), 2u);
  EXPECT_EQ(c.trajectory.start.room, "Corridor");
  EXPECT_TRUE(c.trajectory.loop);
  EXPECT_DOUBLE_EQ(c.sensor.range_noise_stddev, 0.02);
  EXPECT_DOUBLE_EQ(c.sensor.azimuth_resolution_deg, 0.2);  // default kept
  EXPECT_DOUBLE_EQ(c.odometry.rate_hz, 50.0);
  ASSERT_EQ(c.scene.deviations.size(), 5u);
  EXPECT_EQ(c.scene.deviations[4].type, DeviationConfig::Type::kCloseDoorway);
  EXPECT_EQ(c.scene.deviations[4].doorway.name, "D_101");
  EXPECT_DOUBLE_EQ(c.scene.deviations[4].height, 2.0);
  EXPECT_EQ(c.scene.deviations[0].wall.name, "p_n1");
  EXPECT_EQ(c.scene.deviations[3].type, DeviationConfig::Type::kRotateWall);
  EXPECT_DOUBLE_EQ(c.scene.deviations[3].angle_deg, -12.5);
  EXPECT_EQ(c.scene.deviations[1].wall.id, 3);
  EXPECT_EQ(c.scene.deviations[2].type, DeviationConfig::Type::kAddWall);
  ASSERT_EQ(c.scene.clutter.size(), 2u);
  EXPECT_TRUE(c.scene.clutter[1].position.has_value());
  EXPECT_EQ(c.scene.random_clutter.count, 5);
}

TEST(SimScenarioYaml, WaypointsWithAndWithoutYaw) {
  const Result<ScenarioConfig> r =
      Parse("building: b.ifc\ntrajectory: {waypoints: [[0, 0], [1, 2, 1.57]]}\n");
  ASSERT_TRUE(r.ok()) << r.error();
  ASSERT_EQ(r.value().trajectory.waypoints.size(), 2u);
  EXPECT_FALSE(r.value().trajectory.waypoints[0].yaw);
  EXPECT_DOUBLE_EQ(*r.value().trajectory.waypoints[1].yaw, 1.57);
}

TEST(SimScenarioYaml, ErrorsNameTheField) {
  const std::string rooms = "trajectory: {rooms: [A, B]";
  ExpectError("building: b.ifc\ntrajectory: {rooms: [A, B], speed: -0.5}\n",
              "trajectory.speed: must be in [0.3, 1.2]");
  ExpectError("trajectory: {rooms: [A]}\n", "building: missing");
  ExpectError("building: b.ifc\n", "trajectory: missing");
  ExpectError("building: b.ifc\ntrajectory: {}\n", "trajectory: needs `rooms`");
  ExpectError("building: b.ifc\n" + rooms + ", sped: 1}\n", "trajectory.sped: unknown key");
  ExpectError("building: b.ifc\n" + rooms + "}\nsensor: {max_range: x}\n",
              "sensor.max_range: must be a number");
  ExpectError("building: b.ifc\n" + rooms + "}\nodometry: {scale_error: 0.9}\n",
              "odometry.scale_error");
  ExpectError("building: b.ifc\n" + rooms + ", waypoints: [[1, 2]]}\n", "not both");
  ExpectError("building: b.ifc\ntrajectory: {waypoints: [[1]]}\n",
              "trajectory.waypoints[0]: must be a list of 2 to 3 numbers");
  ExpectError("building: b.ifc\n" + rooms + "}\nscene: {deviations: [{type: shift_wall}]}\n",
              "scene.deviations[0].type");
  ExpectError(
      "building: b.ifc\n" + rooms + "}\nscene: {deviations: [{type: move_wall, wall: w}]}\n",
      "scene.deviations[0].offset: missing");
  ExpectError(
      "building: b.ifc\n" + rooms + "}\nscene: {clutter: [{type: sofa, position: [0, 0]}]}\n",
      "scene.clutter[0].type");
  ExpectError("building: b.ifc\n" + rooms + "}\nscene: {clutter: [{type: box}]}\n",
              "scene.clutter[0]: needs `position` or `room`");
  ExpectError("building: b.ifc\n" + rooms + "}\nduration: -3\n", "duration");
  ExpectError(
      "building: b.ifc\n" + rooms + "}\nscene: {deviations: [{type: rotate_wall, wall: w}]}\n",
      "scene.deviations[0].angle_deg: missing");
  ExpectError("building: b.ifc\n" + rooms +
                  "}\nscene: {deviations: [{type: rotate_wall, wall: w, angle_deg: 60}]}\n",
              "scene.deviations[0].angle_deg");
}

TEST(SimScenarioYaml, ReadsDropoutsAndKidnap) {
  const Result<ScenarioConfig> r = Parse(R"(
building: b.ifc
duration: 100
trajectory: {rooms: [A, B]}
sensor: {dropouts: [[10, 14.5], [20, 23]]}
kidnap: {time: 55, waypoints: [[1, 2], [3, 4, 0.5]], start: {pose: [0, 2, 0]}, loop: true}
)");
  ASSERT_TRUE(r.ok()) << r.error();
  const ScenarioConfig& c = r.value();
  ASSERT_EQ(c.sensor.dropouts.size(), 2u);
  EXPECT_DOUBLE_EQ(c.sensor.dropouts[0].start, 10.0);
  EXPECT_DOUBLE_EQ(c.sensor.dropouts[0].end, 14.5);
  ASSERT_TRUE(c.kidnap.has_value());
  EXPECT_DOUBLE_EQ(c.kidnap->time, 55.0);
  ASSERT_EQ(c.kidnap->waypoints.size(), 2u);
  EXPECT_DOUBLE_EQ(*c.kidnap->waypoints[1].yaw, 0.5);
  EXPECT_TRUE(c.kidnap->start.pose.has_value());
  EXPECT_TRUE(c.kidnap->loop);
  // The second route walks with the trajectory's speeds.
  const TrajectoryConfig t = c.kidnap->AsTrajectory(c.trajectory);
  EXPECT_TRUE(t.rooms.empty());
  EXPECT_EQ(t.waypoints.size(), 2u);
  EXPECT_DOUBLE_EQ(t.speed, c.trajectory.speed);
  EXPECT_FALSE(Parse("building: b.ifc\ntrajectory: {rooms: [A]}\n").value().kidnap);
}

TEST(SimScenarioYaml, DropoutAndKidnapErrorsNameTheField) {
  const std::string base = "building: b.ifc\nduration: 60\ntrajectory: {rooms: [A, B]}\n";
  ExpectError(base + "sensor: {dropouts: [1, 2]}\n",
              "sensor.dropouts[0]: must be a list of 2 numbers");
  ExpectError(base + "sensor: {dropouts: 5}\n", "sensor.dropouts: must be a list");
  ExpectError(base + "sensor: {dropouts: [[3, 2]]}\n",
              "sensor.dropouts[0]: must be [t_start, t_end] in s with 0 <= t_start < t_end");
  ExpectError(base + "sensor: {dropouts: [[-1, 2]]}\n", "sensor.dropouts[0]: must be");
  ExpectError(base + "sensor: {dropouts: [[1, 5], [4, 6]]}\n",
              "sensor.dropouts[1]: must start after sensor.dropouts[0] ends (5 s), got 4");
  ExpectError(base + "sensor: {dropouts: [[1, 2], [70, 75]]}\n",
              "sensor.dropouts[1]: must start before the end of the bag (duration 60 s), got 70");
  ExpectError(base + "sensor: {dropouts: [[1, x]]}\n", "sensor.dropouts[0][1]: must be a number");
  ExpectError(base + "kidnap: {rooms: [A]}\n", "kidnap.time: missing");
  ExpectError(base + "kidnap: {time: 0, rooms: [A]}\n", "kidnap.time: must be > 0");
  ExpectError(base + "kidnap: {time: 60, rooms: [A]}\n",
              "kidnap.time: must be before the end of the bag (duration 60 s), got 60");
  ExpectError(base + "kidnap: {time: 5}\n", "kidnap: needs `rooms`");
  ExpectError(base + "kidnap: {time: 5, rooms: [A], waypoints: [[1, 2]]}\n", "kidnap: give either");
  ExpectError(base + "kidnap: {time: 5, rooms: [A], start: {room: A, pose: [0, 0, 0]}}\n",
              "kidnap.start: give either");
  ExpectError(base + "kidnap: {time: 5, rooms: [A], speed: 1}\n", "kidnap.speed: unknown key");
  ExpectError(base + "kidnap: {time: 5, waypoints: [[1]]}\n",
              "kidnap.waypoints[0]: must be a list of 2 to 3 numbers");
  ExpectError(base + "kidnap: [5]\n", "kidnap: must be a mapping");
}

TEST(SimScenarioYaml, InvalidYamlGivesTheLine) {
  const Result<ScenarioConfig> r = Parse("building: b.ifc\ntrajectory: {rooms: [A, B]\n");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("invalid YAML"), std::string::npos) << r.error();
  EXPECT_NE(r.error().find("s.yaml:"), std::string::npos) << r.error();
}

}  // namespace
}  // namespace sim
}  // namespace is_graphs
