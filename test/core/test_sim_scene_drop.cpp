// The scene leaves out the mesh objects of its drop_classes (open doorways: IfcDoor), and with
// them IFC4's "...StandardCase" subtypes: KIT-EDC_with_SB.ifc writes IfcDoorStandardCase, whose
// leaves stood in every doorway of the D8 scenario (the walk was blocked).
#include <gtest/gtest.h>

#include <string>

#include "is_graphs/sim/scene.h"
#include "sim_test_helpers.h"

namespace is_graphs {
namespace sim {
namespace {

TEST(SceneDrop, DoorsAndTheirStandardCaseSubtypesAreLeftOut) {
  SceneConfig config;  // drop_classes: IfcDoor
  const std::string obj =
      "o IfcWall#1\nv 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 2 3\n"
      "o IfcDoor#2\nv 0 1 0\nv 1 1 0\nv 0 1 1\nf 4 5 6\n"
      "o IfcDoorStandardCase#3\nv 0 2 0\nv 1 2 0\nv 0 2 1\nf 7 8 9\n"
      "o IfcWallStandardCase#4\nv 0 3 0\nv 1 3 0\nv 0 3 1\nf 10 11 12\n"
      "o IfcDoorway#5\nv 0 4 0\nv 1 4 0\nv 0 4 1\nf 13 14 15\n";
  const auto scene = testing::SceneOfObj(obj, config);
  ASSERT_TRUE(scene.ok()) << scene.error();
  // The two walls and the made-up "IfcDoorway" (not a StandardCase of IfcDoor) stay.
  EXPECT_EQ(scene.value().size(), 3u);
  config.drop_classes.clear();
  EXPECT_EQ(testing::SceneOfObj(obj, config).value().size(), 5u);
}

}  // namespace
}  // namespace sim
}  // namespace is_graphs
