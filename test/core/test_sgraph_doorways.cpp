// Doorways of the S-Graph from the walked path (DetectDoorways) and the gap in a wall's points
// (GapWidth), on hand-made graphs: two rooms split by a wall at x = 4 with a door at y = 2.5.
#include <gtest/gtest.h>

#include "is_graphs/sgraph/doorway_detection.h"
#include "is_graphs/sgraph/frontend_config.h"

namespace is_graphs {
namespace sgraph {
namespace {

Plane Wall(int id, double x, double normal_x, double y0, double y1, double height = 2.6) {
  Plane p;
  p.id = id;
  p.plane = geometry::Plane(Eigen::Vector3d(normal_x, 0.0, 0.0), normal_x * x);
  p.start = {x, y0};
  p.end = {x, y1};
  p.z_min = 0.0;
  p.z_max = height;
  return p;
}

void Walk(SGraph& g, const std::vector<Eigen::Vector2d>& points) {
  for (const auto& p : points) {
    Keyframe k;
    k.id = static_cast<int>(g.keyframes.size());
    k.previous = k.id - 1;
    k.pose.translation() = Eigen::Vector3d(p.x(), p.y(), 0.5);
    g.keyframes.push_back(k);
  }
}

// Room 0 (x < 4) owns the wall's west face (plane 0), room 1 the east face (plane 1); each face
// spans the door (one plane per face, as association merges the pieces).
SGraph TwoRooms() {
  SGraph g;
  g.planes.push_back(Wall(0, 3.95, -1.0, 0.0, 5.0));
  g.planes.push_back(Wall(1, 4.05, 1.0, 0.0, 5.0));
  Room a, b;
  a.id = 0, a.planes = {0}, a.center = {2.0, 2.5, 0.0};
  b.id = 1, b.planes = {1}, b.center = {6.0, 2.5, 0.0};
  g.rooms = {a, b};
  return g;
}

TEST(DoorwayDetection, AStepThroughAWallIsADoorwayBetweenItsRooms) {
  SGraph g = TwoRooms();
  Walk(g, {{2.0, 2.0}, {2.8, 2.2}, {3.6, 2.5}, {4.4, 2.5}, {5.2, 2.7}});
  const auto doors = DetectDoorways(g, DoorwayConfig{});
  ASSERT_EQ(doors.size(), 1u);
  EXPECT_NEAR(doors[0].position.x(), 4.0, 1e-9);  // the mean of the two faces' crossings
  EXPECT_NEAR(doors[0].position.y(), 2.5, 1e-9);
  EXPECT_EQ(doors[0].rooms, (std::vector<int>{0, 1}));
  EXPECT_EQ(doors[0].planes, (std::vector<int>{0, 1}));
  EXPECT_EQ(doors[0].keyframes, (std::vector<int>{2}));
  EXPECT_EQ(doors[0].id, 16 * 2);
  EXPECT_EQ(doors[0].width, 0.0);  // one plane per face: the graph alone does not close the gap
}

// A face along several rooms is one plane of each: the doorway joins the nearest on each side.
TEST(DoorwayDetection, OfTheRoomsAlongAFaceTheNearestOnEachSide) {
  SGraph g = TwoRooms();
  Room far = g.rooms[1];
  far.id = 5, far.center = {6.0, 8.0, 0.0};
  g.rooms.push_back(far);
  Room west = g.rooms[0];
  west.id = 6, west.center = {2.0, -3.0, 0.0};
  g.rooms.insert(g.rooms.begin(), west);
  Walk(g, {{3.6, 2.5}, {4.4, 2.5}});
  const auto doors = DetectDoorways(g, DoorwayConfig{});
  ASSERT_EQ(doors.size(), 1u);
  EXPECT_EQ(doors[0].rooms, (std::vector<int>{0, 1}));
}

TEST(DoorwayDetection, TheSameDoorWalkedTwiceIsOneDoorway) {
  SGraph g = TwoRooms();
  Walk(g, {{3.5, 2.4}, {4.5, 2.4}, {5.5, 2.0}, {4.5, 2.7}, {3.5, 2.7}});
  const auto doors = DetectDoorways(g, DoorwayConfig{});
  ASSERT_EQ(doors.size(), 1u);
  EXPECT_NEAR(doors[0].position.y(), 2.55, 1e-9);
  EXPECT_EQ(doors[0].keyframes, (std::vector<int>{0, 3}));
}

TEST(DoorwayDetection, NoDoorwayWithoutACrossing) {
  SGraph g = TwoRooms();
  // Along the wall; up to it and back; a scan gap (a 2 m step) over it; around its end.
  Walk(g, {{3.6, 0.5}, {3.6, 1.3}, {3.6, 2.1}, {3.9, 2.1}, {3.6, 2.1}});
  g.keyframes.push_back(g.keyframes.back());
  g.keyframes.back().id = 5, g.keyframes.back().previous = 4;
  g.keyframes.back().pose.translation().x() = 5.6;
  Walk(g, {{3.0, 5.8}, {3.8, 5.9}, {4.6, 5.8}});
  g.keyframes[6].previous = -1;
  EXPECT_TRUE(DetectDoorways(g, DoorwayConfig{}).empty());
  DoorwayConfig off;
  off.detect = false;
  SGraph through = TwoRooms();
  Walk(through, {{3.6, 2.5}, {4.4, 2.5}});
  EXPECT_EQ(DetectDoorways(through, DoorwayConfig{}).size(), 1u);
  EXPECT_TRUE(DetectDoorways(through, off).empty());
}

TEST(DoorwayDetection, PlanesOfNoRoomAndLowPlanesGiveNone) {
  SGraph g = TwoRooms();
  g.rooms.clear();  // the same crossing, before any room was found
  Walk(g, {{3.6, 2.5}, {4.4, 2.5}});
  EXPECT_TRUE(DetectDoorways(g, DoorwayConfig{}).empty());
  SGraph low;
  low.planes.push_back(Wall(0, 3.95, -1.0, 0.0, 5.0, 1.0));  // 1 m tall: furniture
  Room r;
  r.id = 0, r.planes = {0};
  low.rooms = {r};
  Walk(low, {{3.6, 2.5}, {4.4, 2.5}});
  EXPECT_TRUE(DetectDoorways(low, DoorwayConfig{}).empty());
}

TEST(DoorwayDetection, TheGapBetweenTwoPiecesOfAWallIsTheWidth) {
  // The west face mapped as two pieces, y 0..2 and 2.9..5: the door is the 0.9 m between them.
  SGraph g;
  g.planes.push_back(Wall(0, 3.95, -1.0, 0.0, 2.0));
  g.planes.push_back(Wall(1, 3.95, -1.0, 2.9, 5.0));
  Room r;
  r.id = 7, r.planes = {0, 1};
  g.rooms = {r};
  Walk(g, {{3.6, 2.45}, {4.4, 2.45}});
  const auto doors = DetectDoorways(g, DoorwayConfig{});
  ASSERT_EQ(doors.size(), 1u);
  EXPECT_NEAR(doors[0].width, 0.9, 1e-9);
  EXPECT_NEAR(doors[0].position.x(), 3.95, 1e-9);
  EXPECT_EQ(doors[0].rooms, (std::vector<int>{7}));
  // A gap wider than max_width is open space: no doorway.
  g.planes[1] = Wall(1, 3.95, -1.0, 5.0, 7.0);
  g.keyframes.clear();
  Walk(g, {{3.6, 3.5}, {4.4, 3.5}});
  EXPECT_TRUE(DetectDoorways(g, DoorwayConfig{}).empty());
}

TEST(DoorwayDetection, GapWidthIsBetweenTheNearestPointsEitherSide) {
  EXPECT_NEAR(GapWidth({-2.0, -0.45, -0.5, 0.4, 1.0}, 2.5), 0.85, 1e-12);
  EXPECT_EQ(GapWidth({-0.4, -1.0}, 2.5), 0.0);  // not closed on one side
  EXPECT_EQ(GapWidth({-1.5, 1.5}, 2.5), 0.0);   // wider than a doorway
  EXPECT_EQ(GapWidth({}, 2.5), 0.0);
  EXPECT_NEAR(GapWidth({-0.4, std::nan(""), 0.5}, 2.5), 0.9, 1e-12);
}

TEST(DoorwayDetection, ConfigNamesTheBadParameter) {
  FrontendConfig f;
  EXPECT_EQ(f.Validate(), "");
  f.doorways.max_width = -1.0;
  EXPECT_EQ(f.Validate().rfind("doorway_max_width must be > 0", 0), 0u) << f.Validate();
  f.doorways.max_width = 2.5;
  f.doorways.band_low = 2.0;
  EXPECT_NE(f.Validate().find("doorway_band_low"), std::string::npos) << f.Validate();
}

}  // namespace
}  // namespace sgraph
}  // namespace is_graphs
