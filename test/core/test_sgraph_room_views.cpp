// Room detection from views that see more than one space: a doorway, a corridor's mouth, a
// corridor and the room seen through its door, a partition that leaves a wide passage.
#include <gtest/gtest.h>

#include <vector>

#include "is_graphs/sgraph/room_detection.h"

namespace is_graphs {
namespace sgraph {
namespace {

using Eigen::Vector2d;

// A wall face from `a` to `b` whose normal (into the space it bounds) is `normal`.
Wall2D Face(int id, const Vector2d& a, const Vector2d& b, const Vector2d& normal) {
  Wall2D w;
  w.id = id;
  w.normal = normal.normalized();
  w.d = w.normal.dot(a);
  w.start = a;
  w.end = b;
  return w;
}

std::optional<RoomCandidate> DetectAt(const std::vector<Wall2D>& walls, const Vector2d& at) {
  const FrontendConfig config;
  return DetectRoom(walls, at, CastRays(walls, at, config), config);
}

// D4's meeting room: a corridor (y 0..2, x 0..18) and south of it, through a 1.2 m door at
// x 12..13.2, a room (x 10.9..18, y -5..-0.15). The S-Graph maps each face of the corridor wall
// as one plane across the door; the room's side of it as two pieces.
std::vector<Wall2D> CorridorAndRoom(bool corridor_side_face, bool room_side_face) {
  std::vector<Wall2D> walls = {
      Face(0, {0, 2}, {18, 2}, {0, -1}),           // corridor, north face
      Face(1, {10.9, -5}, {18, -5}, {0, 1}),       // room, south
      Face(2, {10.9, -5}, {10.9, -0.15}, {1, 0}),  // room, west
      Face(3, {18, -5}, {18, -0.15}, {-1, 0}),     // room, east
  };
  if (corridor_side_face) walls.push_back(Face(4, {0, 0}, {18, 0}, {0, 1}));
  if (room_side_face) {
    walls.push_back(Face(5, {10.9, -0.15}, {12, -0.15}, {0, -1}));
    walls.push_back(Face(6, {13.2, -0.15}, {18, -0.15}, {0, -1}));
  }
  return walls;
}

TEST(RoomViews, CorridorAndTheRoomSeenThroughItsDoorAreNoFourWallRoom) {
  // Unless the corridor wall is mapped, the rectangle of the corridor's far face and the room's
  // three walls takes most rays (what the rule rests on).
  const auto unmapped = DetectAt(CorridorAndRoom(false, false), Vector2d(12.6, -1.0));
  ASSERT_TRUE(unmapped);
  ASSERT_TRUE(unmapped->rectangular);
  EXPECT_NEAR(unmapped->center.y(), -1.5, 1e-9);  // between y = -5 and y = 2
  // With the corridor's wall mapped across that rectangle, it is two spaces: no four-wall room.
  const auto divided = DetectAt(CorridorAndRoom(true, false), Vector2d(12.6, -1.0));
  EXPECT_TRUE(!divided || !divided->rectangular);
  // With the room's own side of that wall mapped too, the room itself.
  const auto room = DetectAt(CorridorAndRoom(true, true), Vector2d(12.6, -1.0));
  ASSERT_TRUE(room);
  ASSERT_TRUE(room->rectangular);
  EXPECT_LT((room->center - Vector2d(14.45, -2.575)).norm(), 1e-6);
}

// A room (x 0..7, y 0..5) with a partition from its south wall at x = 2.6, `length` long.
std::vector<Wall2D> RoomWithPartition(double length) {
  return {Face(0, {0, 0}, {7, 0}, {0, 1}), Face(1, {7, 0}, {7, 5}, {-1, 0}),
          Face(2, {7, 5}, {0, 5}, {0, -1}), Face(3, {0, 5}, {0, 0}, {1, 0}),
          Face(4, {2.6, 0}, {2.6, length}, {1, 0})};  // its east face
}

TEST(RoomViews, PartitionLeavingAWidePassageDoesNotDivideARoom) {
  // 2.45 m long: a 2.55 m passage, wider than room_max_opening (2 m). One room.
  const auto wide = DetectAt(RoomWithPartition(2.45), Vector2d(4.5, 2.5));
  ASSERT_TRUE(wide);
  ASSERT_TRUE(wide->rectangular);
  EXPECT_LT((wide->center - Vector2d(3.5, 2.5)).norm(), 1e-6);
  // 3.9 m long: a 1.1 m doorway. Not the 7 x 5 m room.
  const auto narrow = DetectAt(RoomWithPartition(3.9), Vector2d(4.5, 2.5));
  EXPECT_FALSE(narrow && narrow->rectangular && (narrow->center - Vector2d(3.5, 2.5)).norm() < 0.5);
}

TEST(RoomViews, StandingInADoorwayOrACorridorsMouthIsInAnOpening) {
  const FrontendConfig config;
  // A 0.15 m wall between a hall (y < 2.5) and a room (y > 2.65), one plane per face across a
  // door at x 9.5..10.5.
  const std::vector<Wall2D> wall = {Face(0, {0, 2.5}, {12, 2.5}, {0, -1}),
                                    Face(1, {0, 2.65}, {12, 2.65}, {0, 1})};
  EXPECT_TRUE(InOpening(wall, Vector2d(10.0, 2.58), config));   // in the door
  EXPECT_TRUE(InOpening(wall, Vector2d(10.0, 2.9), config));    // just through it
  EXPECT_FALSE(InOpening(wall, Vector2d(10.0, 1.25), config));  // the hall's middle
  EXPECT_FALSE(InOpening(wall, Vector2d(10.0, 4.0), config));   // the room's
  // Beyond the wall's end (plus room_gap_margin) the line runs through nothing.
  EXPECT_FALSE(InOpening(wall, Vector2d(14.0, 2.58), config));
  // A corridor's mouth: a 2 m gap between two pieces of the crossing corridor's wall.
  const std::vector<Wall2D> mouth = {Face(0, {-5, 0}, {-1, 0}, {0, 1}),
                                     Face(1, {1, 0}, {5, 0}, {0, 1})};
  EXPECT_TRUE(InOpening(mouth, Vector2d(0.0, -0.29), config));
  EXPECT_FALSE(InOpening(mouth, Vector2d(0.0, -1.0), config));
}

TEST(RoomViews, WallsLeftOutLieBehindTheKeptOnes) {
  // A room (y 1.32..5.1) first closed from its doorway with the hall's far wall (y = -1.2,
  // seen through the door), then from inside by its own four walls.
  const std::vector<Wall2D> walls = {
      Face(1, {-6, -1.2}, {6, -1.2}, {0, 1}),    // the hall's far wall
      Face(20, {-8, 1.32}, {6, 1.32}, {0, 1}),   // the room's wall on the hall's side
      Face(8, {-8, 5.1}, {6, 5.1}, {0, -1}),     // the room's far wall
      Face(63, {-7, 1.32}, {-7, 5.1}, {1, 0}),   // its west wall
      Face(69, {-2, 1.32}, {-2, 5.1}, {-1, 0}),  // its east wall
  };
  EXPECT_TRUE(LeftOutLieBehind(walls, {1, 20, 8, 63, 69}, {20, 8, 63, 69}));
  // A left-out wall inside the kept ones' space is not behind them (an end wall gone from view).
  EXPECT_FALSE(LeftOutLieBehind(walls, {1, 20, 8, 63, 69}, {1, 20, 8, 63}));
  EXPECT_FALSE(LeftOutLieBehind(walls, {1, 20, 8, 63, 69, 99}, {20, 8, 63, 69}));  // unknown
  EXPECT_TRUE(LeftOutLieBehind(walls, {20, 8}, {20, 8}));  // nothing left out
}

TEST(RoomViews, AFaceMappedTwiceIsOnOneLine) {
  const Wall2D a = Face(0, {0, 0}, {4, 0}, {0, 1});
  const Wall2D b = Face(1, {5, 0.05}, {9, 0.05 + 4 * std::tan(M_PI / 180.0)}, {0, 1});
  Wall2D tilted = b;
  tilted.normal = Eigen::Rotation2Dd(M_PI / 180.0) * Vector2d(0, 1);
  tilted.d = tilted.normal.dot(tilted.start);
  EXPECT_TRUE(SameLine(a, tilted));
  EXPECT_FALSE(SameLine(a, Face(2, {0, 0.15}, {4, 0.15}, {0, -1})));  // its back face
  EXPECT_FALSE(SameLine(a, Face(3, {0, 0.2}, {4, 0.2}, {0, 1})));     // 0.2 m apart
}

// An L-shaped room (x 0..6, y 0..2, and x 0..2, y 2..6) seen from its corner arm: a point in
// the other arm is in view, one behind the inner corner is not, one past a wall is not. A
// polygonal view's walls enclose no convex area, so "inside" is what the rays saw.
TEST(RoomViews, InsideAViewIsWhatItsRaysSaw) {
  const std::vector<Wall2D> walls = {
      Face(0, {0, 0}, {6, 0}, {0, 1}),  Face(1, {6, 0}, {6, 2}, {-1, 0}),
      Face(2, {2, 2}, {6, 2}, {0, -1}), Face(3, {2, 2}, {2, 6}, {-1, 0}),
      Face(4, {0, 6}, {2, 6}, {0, -1}), Face(5, {0, 0}, {0, 6}, {1, 0}),
  };
  const FrontendConfig config;
  const Vector2d at(1.0, 1.0);
  const RayFan fan = CastRays(walls, at, config);
  EXPECT_TRUE(InFan(fan, at, Vector2d(5.0, 1.0), 0.3));   // along the x arm
  EXPECT_TRUE(InFan(fan, at, Vector2d(1.0, 5.0), 0.3));   // along the y arm
  EXPECT_FALSE(InFan(fan, at, Vector2d(4.0, 4.0), 0.3));  // behind the inner corner
  EXPECT_FALSE(InFan(fan, at, Vector2d(7.0, 1.0), 0.3));  // past the end wall
  EXPECT_FALSE(InFan(fan, at, Vector2d(5.9, 1.0), 0.3));  // within the margin of it
  // The polygon's walls alone would put neither arm's far end inside: the "in front of every
  // wall" test fails for a point in the y arm (behind face 2's line).
  EXPECT_LT(walls[2].normal.dot(Vector2d(1.0, 5.0)) - walls[2].d, 0.0);
}

}  // namespace
}  // namespace sgraph
}  // namespace is_graphs
