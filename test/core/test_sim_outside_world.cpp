// The world outside the building (scene.outside): footprints, the check that an object stands
// clear of every room (with the room named), the objects added to the scene, the YAML.
#include <gtest/gtest.h>

#include "is_graphs/sim/outside_world.h"
#include "is_graphs/sim/scenario_yaml.h"

namespace is_graphs {
namespace sim {
namespace {

agraph::AGraph TwoRooms() {
  agraph::AGraph g;
  g.storeys.push_back({0, -1, "", "Ground", 0.0, 3.0});
  g.storeys.push_back({1, -1, "", "First", 3.0, 3.0});
  agraph::Room a;
  a.id = 0;
  a.name = "101";
  a.long_name = "Hall";
  a.storey = 0;
  a.polygon = {{0, 0}, {10, 0}, {10, 8}, {0, 8}};
  agraph::Room b = a;
  b.id = 1;
  b.name = "201";
  b.long_name = "";
  b.storey = 1;
  b.polygon = {{0, 0}, {16, 0}, {16, 8}, {0, 8}};  // the upper storey reaches further east
  g.rooms = {a, b};
  return g;
}

OutsideObjectConfig Object(const std::string& type, double x, double y) {
  OutsideObjectConfig o;
  o.type = type;
  o.position = {x, y};
  return o;
}

TEST(SimOutsideWorld, FootprintsOfTheKinds) {
  const auto car = OutsideFootprint(Object("car", 0.0, 0.0));
  ASSERT_EQ(car.size(), 4u);
  EXPECT_NEAR(car[2].x(), 2.25, 1e-9);
  EXPECT_NEAR(car[2].y(), 0.9, 1e-9);
  OutsideObjectConfig turned = Object("wall", 0.0, 0.0);
  turned.yaw_deg = 90.0;
  EXPECT_NEAR(OutsideFootprint(turned)[2].y(), 5.0, 1e-9);  // 10 m long, now along y
  const auto tree = OutsideFootprint(Object("tree", 1.0, 1.0));
  ASSERT_EQ(tree.size(), 12u);
  EXPECT_NEAR((tree[0] - Eigen::Vector2d(1.0, 1.0)).norm(), 1.5, 1e-9);
}

TEST(SimOutsideWorld, ObjectsMustStandClearOfEveryRoom) {
  const agraph::AGraph g = TwoRooms();
  EXPECT_EQ(CheckOutside(Object("car", 5.0, -4.0), g, "scene.outside[0]"), "");
  const std::string inside = CheckOutside(Object("car", 5.0, 4.0), g, "scene.outside[1]");
  EXPECT_NE(inside.find("scene.outside[1]: the car at (5, 4) stands inside the building"),
            std::string::npos)
      << inside;
  EXPECT_NE(inside.find("'101 (Hall)' of storey 'Ground'"), std::string::npos) << inside;
  // Clear of the ground floor, inside the first floor's room.
  const std::string upper = CheckOutside(Object("tree", 14.0, 4.0), g, "scene.outside[2]");
  EXPECT_NE(upper.find("'201' of storey 'First'"), std::string::npos) << upper;
  // 0.3 m from the wall: against it.
  const std::string close = CheckOutside(Object("car", 5.0, -1.2), g, "scene.outside[3]");
  EXPECT_NE(close.find("against the building"), std::string::npos) << close;
  // A building around the whole house: its footprint holds the rooms' corners.
  OutsideObjectConfig around = Object("building", 5.0, 4.0);
  around.size = {50.0, 50.0, 5.0};
  EXPECT_NE(CheckOutside(around, g, "scene.outside[4]").find("inside the building"),
            std::string::npos);
}

TEST(SimOutsideWorld, AddedOnTheGroundWithALogLine) {
  const agraph::AGraph g = TwoRooms();
  SceneMesh scene;
  OutsideObjectConfig high = Object("building", 40.0, 4.0);
  high.base_z = 2.0;
  const auto log = AddOutsideWorld(&scene, g, {Object("tree", -5.0, 4.0), high});
  ASSERT_TRUE(log.ok()) << log.error();
  ASSERT_EQ(log.value().size(), 2u);
  EXPECT_EQ(log.value()[0], "scene.outside[0]: a tree at (-5, 4)");
  EXPECT_GT(scene.size(), 12u);
  float z_min = 1e9f, z_max = -1e9f;
  for (const auto& v : scene.vertices)
    z_min = std::min(z_min, v.z()), z_max = std::max(z_max, v.z());
  EXPECT_NEAR(z_min, 0.0f, 1e-5);         // the tree on the ground (the lowest storey's)
  EXPECT_NEAR(z_max, 2.0f + 9.0f, 1e-4);  // the building from its base_z, 9 m high
  SceneMesh untouched;
  const auto bad = AddOutsideWorld(&untouched, g, {Object("car", 5.0, 4.0)});
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(untouched.size(), 0u);
}

const char* kBase = R"(building: bim/office.ifc
trajectory: {rooms: [Corridor]}
scene:
  outside:
)";

TEST(SimOutsideWorld, YamlKeysAndBadValuesNameTheLine) {
  auto r = ParseScenarioYaml(std::string(kBase) +
                                 "    - {type: tree, position: [-5, 2], radius: 2.5}\n"
                                 "    - {type: car, position: [1, -6], yaw_deg: 30, base_z: 0.1}\n",
                             "s.yaml", "/repo");
  ASSERT_TRUE(r.ok()) << r.error();
  ASSERT_EQ(r.value().scene.outside.size(), 2u);
  EXPECT_EQ(r.value().scene.outside[0].radius, 2.5);
  EXPECT_EQ(*r.value().scene.outside[1].base_z, 0.1);
  for (const auto& [bad, expected] : std::vector<std::pair<std::string, std::string>>{
           {"    - {type: ufo, position: [1, 2]}\n", "s.yaml:5: scene.outside[0].type: must be"},
           {"    - {type: car}\n", "s.yaml:5: scene.outside[0].position: missing"},
           {"    - {type: car, position: [1, 2]}\n    - {type: tree, position: [1, 2], radius: "
            "-1}\n",
            "s.yaml:6: scene.outside[1].radius"},
           {"    - {type: car, position: [1, 2], reflectivity: 2}\n",
            "s.yaml:5: scene.outside[0].reflectivity"},
           {"    - {type: car, position: [1, 2], wheels: 4}\n",
            "s.yaml:5: scene.outside[0].wheels: unknown key"}}) {
    r = ParseScenarioYaml(std::string(kBase) + bad, "s.yaml", "/repo");
    ASSERT_FALSE(r.ok()) << bad;
    EXPECT_NE(r.error().find(expected), std::string::npos) << r.error();
  }
}

}  // namespace
}  // namespace sim
}  // namespace is_graphs
